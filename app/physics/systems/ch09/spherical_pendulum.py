"""The spherical pendulum: a point mass on a massless rod free to swing in every direction from a fixed pivot.

Frame N: z up, the pivot at the origin. θ (rad) is the rod's angle from the
downward vertical, φ (rad) its azimuth about z. φ is ignorable: the Lagrangian
does not contain it, so its momentum m l² sin²θ φ̇ (the angular momentum about
the vertical) is conserved and Routh's method removes it.
"""

from __future__ import annotations

import sympy

from app.physics.mechanics.description import Coordinate, Particle, Reaction, Singularity, SystemDescription, vector
from app.physics.systems.ch07.simple_pendulum import PENDULUM_PARAMETERS

m, l, g = sympy.symbols("m l g", positive=True)
theta = Coordinate("theta", "\\theta")
phi = Coordinate("phi", "\\phi")
th, ph = theta.symbol, phi.symbol
bob = l * vector(sympy.sin(th) * sympy.cos(ph), sympy.sin(th) * sympy.sin(ph), -sympy.cos(th))

SYSTEM = SystemDescription(
    id="spherical-pendulum",
    title="Spherical pendulum",
    chapter=9,
    coordinates=(theta, phi),
    parameters=PENDULUM_PARAMETERS,
    symbols={"mass_kg": m, "length_m": l, "g_m_s2": g},
    particles=(Particle("bob", m, bob),),
    gravity=vector(0, 0, -g),
    reactions=(Reaction("rod", on="bob", point=bob, forces=(-bob / l,)),),
    ignorable=("phi",),
    singularities=(
        Singularity(
            sympy.sin(th),
            "sin θ",
            "the angles are singular where sin θ = 0 (the rod vertical): the azimuth φ is undefined there; "
            "choose θ strictly between 0 and 180°",
        ),
    ),
    state_ranges={"theta": (0.2, 2.9)},
    assumptions=(
        "A point mass on a rigid massless rod, frictionless pivot. The angles are singular at θ = 0 "
        "(straight down), where φ is undefined."
    ),
)
