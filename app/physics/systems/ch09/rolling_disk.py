"""A thin disk rolling without slipping on a horizontal floor: the nonholonomic member of the catalogue.

Frame N: z up, the floor z = 0. Coordinates: the contact point (x, y) (m), the
heading ψ, the lean θ (from the vertical) and the spin φ (rad), with
R_NB = Rz(ψ) Rx(θ) Ry(φ): the disk's axis is body y. The centre is at
(x, y, 0) + r·(sin ψ sin θ, −cos ψ sin θ, cos θ). Rolling without slip makes
the material contact point's velocity zero, which fixes ẋ and ẏ in terms of
the angle rates: the generalized speeds are the three angle rates, and the
constraint, being on velocities only, is built into q̇ = q̇(q, u).
"""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import (
    Coordinate,
    Reaction,
    RigidBody,
    Singularity,
    Speed,
    SystemDescription,
    parameter,
    vector,
)

m, r, g = sympy.symbols("m r g", positive=True)
x = Coordinate("x", "x", unit="m")
y = Coordinate("y", "y", unit="m")
psi = Coordinate("psi", "\\psi")
theta = Coordinate("theta", "\\theta")
phi = Coordinate("phi", "\\phi")
heading_rate = Speed("heading_rate", "u_\\psi")
lean_rate = Speed("lean_rate", "u_\\theta")
spin_rate = Speed("spin_rate", "u_\\phi")
ps, th = psi.symbol, theta.symbol
u_psi, u_theta, u_phi = heading_rate.symbol, lean_rate.symbol, spin_rate.symbol
contact = vector(x.symbol, y.symbol, 0)
centre = contact + r * vector(sympy.sin(ps) * sympy.sin(th), -sympy.cos(ps) * sympy.sin(th), sympy.cos(th))
# No slip: the centre moves as the disk turns about its contact point, ω × (centre − contact). With
# ω = u_ψ ẑ + u_θ x̂' + u_φ ŷ'' this gives ẋ = r u_φ cos ψ, ẏ = r u_φ sin ψ (the contact point moves along the heading).
rates = (r * u_phi * sympy.cos(ps), r * u_phi * sympy.sin(ps), u_psi, u_theta, u_phi)

SYSTEM = SystemDescription(
    id="rolling-disk",
    title="Disk rolling without slipping",
    chapter=9,
    coordinates=(x, y, psi, theta, phi),
    parameters=ParameterSet(
        (
            parameter("mass_kg", "kg", 1.0, low=0.01, high=100.0, label="m", description="Mass of the disk"),
            parameter("radius_m", "m", 0.1, low=0.005, high=5.0, label="r", description="Radius of the disk"),
            parameter("g_m_s2", "m/s²", 9.81, low=0.0, high=100.0, label="g", description="Gravitational acceleration"),
        )
    ),
    symbols={"mass_kg": m, "radius_m": r, "g_m_s2": g},
    bodies=(
        RigidBody(
            "disk",
            m,
            centre,
            (("z", ps), ("x", th), ("y", phi.symbol)),
            sympy.diag(m * r**2 / 4, m * r**2 / 2, m * r**2 / 4),
        ),
    ),
    gravity=vector(0, 0, -g),
    speeds=(heading_rate, lean_rate, spin_rate),
    coordinate_rates=rates,
    speeds_from_rates=(psi.rate, theta.rate, phi.rate),
    reactions=(
        Reaction("floor", on="disk", point=contact, forces=(vector(1, 0, 0), vector(0, 1, 0), vector(0, 0, 1))),
    ),
    singularities=(
        Singularity(
            sympy.cos(th),
            "cos θ",
            "the angles are singular where cos θ = 0 (the disk flat, lean ±90°): heading and spin turn about one "
            "axis there; choose a lean strictly between −90° and 90°",
        ),
    ),
    state_ranges={"theta": (-1.0, 1.0)},
    assumptions=(
        "A uniform thin disk (a knife edge) rolling without slipping or pivoting friction on a rigid "
        "floor; it never loses contact."
    ),
)
