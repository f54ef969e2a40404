"""The heavy symmetric top as a catalogue system: the same physics as chapter 10's, derived five ways.

Frames and angles as in :mod:`app.physics.systems.ch10.heavy_top`: N with +Z
up, 3-1-3 Euler angles R_NB = Rz(φ) Rx(θ) Rz(ψ) (φ precession, θ nutation, ψ
spin, rad), the centre of mass on body axis 3 at l from the fixed pivot. The
parameters keep chapter 10's names: I_transverse_pivot and I_axial are the
principal moments about the pivot (kg·m²). φ and ψ are ignorable. The angles
are singular at θ = 0 and π (gimbal lock), where φ and ψ merge.
"""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import (
    Coordinate,
    Reaction,
    RigidBody,
    Singularity,
    SystemDescription,
    parameter,
    vector,
)
from app.physics.mechanics.kinematics import simple_rotation

m, l, I_t, I_a, g = sympy.symbols("m l I_t I_a g", positive=True)
phi = Coordinate("phi", "\\phi")
theta = Coordinate("theta", "\\theta")
psi = Coordinate("psi", "\\psi")
rotations = (("z", phi.symbol), ("x", theta.symbol), ("z", psi.symbol))
axis = simple_rotation("z", phi.symbol) * simple_rotation("x", theta.symbol) * vector(0, 0, 1)
centre = l * axis
pivot = vector(0, 0, 0)
transverse_about_centre = I_t - m * l**2

SYSTEM = SystemDescription(
    id="heavy-top",
    title="Heavy symmetric top",
    chapter=9,
    coordinates=(phi, theta, psi),
    parameters=ParameterSet(
        (
            parameter("mass_kg", "kg", 1.0, low=0.01, high=100.0, label="m", description="Mass of the top"),
            parameter(
                "cg_distance_m",
                "m",
                0.05,
                low=0.001,
                high=2.0,
                label="l",
                description="Pivot to centre of mass, along the symmetry axis",
            ),
            parameter(
                "I_transverse_pivot",
                "kg·m²",
                0.0125,
                low=1e-5,
                high=100.0,
                label="I_t",
                description="Moment of inertia about a transverse axis through the pivot",
            ),
            parameter(
                "I_axial",
                "kg·m²",
                0.01,
                low=1e-5,
                high=100.0,
                label="I_a",
                description="Moment of inertia about the symmetry axis",
            ),
            parameter(
                "g_m_s2", "m/s²", 9.807, low=0.0, high=100.0, label="g", description="Gravitational acceleration"
            ),
        )
    ),
    symbols={"mass_kg": m, "cg_distance_m": l, "I_transverse_pivot": I_t, "I_axial": I_a, "g_m_s2": g},
    bodies=(RigidBody("top", m, centre, rotations, sympy.diag(transverse_about_centre, transverse_about_centre, I_a)),),
    gravity=vector(0, 0, -g),
    reactions=(Reaction("pivot", on="top", point=pivot, forces=(vector(1, 0, 0), vector(0, 1, 0), vector(0, 0, 1))),),
    ignorable=("phi", "psi"),
    singularities=(
        Singularity(
            sympy.sin(theta.symbol),
            "sin θ",
            "the Euler angles are singular where sin θ = 0 (θ = 0 or 180°): φ and ψ turn about one axis there "
            "and cannot be told apart; choose θ strictly between 0 and 180°",
        ),
    ),
    state_ranges={"theta": (0.2, 2.9)},
    assumptions=(
        "A rigid axisymmetric body on a frictionless fixed pivot. The Euler angles are singular at θ = 0 and 180°."
    ),
)
