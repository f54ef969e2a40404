"""The simple pendulum: a point mass on a massless rod in a vertical plane (x horizontal, z up; θ from the downward
vertical)."""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import Coordinate, Particle, Reaction, SystemDescription, parameter, vector

m, l, g = sympy.symbols("m l g", positive=True)
theta = Coordinate("theta", "\\theta")
bob = vector(l * sympy.sin(theta.symbol), 0, -l * sympy.cos(theta.symbol))
#: A bob on a rod: its mass, the rod's length and gravity (the spherical pendulum has the same three).
PENDULUM_PARAMETERS = ParameterSet(
    (
        parameter("mass_kg", "kg", 1.0, low=0.01, high=100.0, label="m", description="Mass of the bob"),
        parameter("length_m", "m", 1.0, low=0.05, high=10.0, label="l", description="Length of the rod"),
        parameter("g_m_s2", "m/s²", 9.81, low=0.0, high=100.0, label="g", description="Gravitational acceleration"),
    )
)

SYSTEM = SystemDescription(
    id="simple-pendulum",
    title="Simple pendulum",
    chapter=7,
    coordinates=(theta,),
    parameters=PENDULUM_PARAMETERS,
    symbols={"mass_kg": m, "length_m": l, "g_m_s2": g},
    particles=(Particle("bob", m, bob),),
    gravity=vector(0, 0, -g),
    reactions=(
        Reaction("rod", on="bob", point=bob, forces=(-bob / l,)),
        Reaction("plane", on="bob", point=bob, forces=(vector(0, 1, 0),)),
    ),
    assumptions="A point mass on a rigid massless rod, frictionless pivot, motion in one vertical plane.",
)
