"""The double pendulum: two point masses on massless rods, swinging in a vertical plane.

Frame N: x horizontal in the plane of motion, z up; the pivot O at the origin.
θ1 and θ2 (rad) are the rods' angles from the downward vertical. Newton–Euler
needs each rod's tension (along the rod) and the plane's reaction on each
mass (along y) as unknowns.
"""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import Coordinate, Particle, Reaction, SystemDescription, parameter, vector

m1, m2, l1, l2, g = sympy.symbols("m_1 m_2 l_1 l_2 g", positive=True)
theta1 = Coordinate("theta1", "\\theta_1")
theta2 = Coordinate("theta2", "\\theta_2")
t1, t2 = theta1.symbol, theta2.symbol
first = vector(l1 * sympy.sin(t1), 0, -l1 * sympy.cos(t1))
second = first + vector(l2 * sympy.sin(t2), 0, -l2 * sympy.cos(t2))
plane_normal = vector(0, 1, 0)

SYSTEM = SystemDescription(
    id="double-pendulum",
    title="Double pendulum",
    chapter=7,
    coordinates=(theta1, theta2),
    parameters=ParameterSet(
        (
            parameter("m1_kg", "kg", 1.0, low=0.01, high=100.0, label="m₁", description="Mass of the upper bob"),
            parameter("m2_kg", "kg", 1.0, low=0.01, high=100.0, label="m₂", description="Mass of the lower bob"),
            parameter("l1_m", "m", 1.0, low=0.05, high=10.0, label="l₁", description="Length of the upper rod"),
            parameter("l2_m", "m", 1.0, low=0.05, high=10.0, label="l₂", description="Length of the lower rod"),
            parameter("g_m_s2", "m/s²", 9.81, low=0.0, high=100.0, label="g", description="Gravitational acceleration"),
        )
    ),
    symbols={"m1_kg": m1, "m2_kg": m2, "l1_m": l1, "l2_m": l2, "g_m_s2": g},
    particles=(Particle("A", m1, first), Particle("B", m2, second)),
    gravity=vector(0, 0, -g),
    reactions=(
        Reaction("rod1", on="A", point=first, forces=(-first / l1,)),
        Reaction("rod2", on="B", point=second, forces=((first - second) / l2,), against="A"),
        Reaction("planeA", on="A", point=first, forces=(plane_normal,)),
        Reaction("planeB", on="B", point=second, forces=(plane_normal,)),
    ),
    assumptions="Point masses on rigid massless rods, frictionless pins, motion in one vertical plane.",
)
