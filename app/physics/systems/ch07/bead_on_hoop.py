"""A bead sliding without friction on a circular hoop that spins about its vertical diameter at a prescribed rate.

Frame N: z up, the hoop's centre at the origin; the hoop's plane turns about z
at Ω (a prescribed motion: the system is rheonomic). θ is the bead's angle
from the bottom of the hoop. The hoop pushes on the bead along its inward
normal in the hoop's plane and perpendicular to that plane (the push that
drives the bead round).
"""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import TIME, Coordinate, Particle, Reaction, SystemDescription, parameter, vector

m, R, Omega, g = sympy.symbols("m R Omega g", positive=True)
theta = Coordinate("theta", "\\theta")
th = theta.symbol
angle = Omega * TIME
bead = R * vector(sympy.sin(th) * sympy.cos(angle), sympy.sin(th) * sympy.sin(angle), -sympy.cos(th))

SYSTEM = SystemDescription(
    id="bead-on-rotating-hoop",
    title="Bead on a spinning hoop",
    chapter=7,
    coordinates=(theta,),
    parameters=ParameterSet(
        (
            parameter("hoop_radius_m", "m", 0.5, low=0.01, high=10.0, label="R", description="Radius of the hoop"),
            parameter(
                "hoop_speed_rad_s",
                "rad/s",
                6.0,
                low=0.0,
                high=100.0,
                label="Ω",
                description="Prescribed spin of the hoop about its vertical diameter",
            ),
            parameter("g_m_s2", "m/s²", 9.81, low=0.0, high=100.0, label="g", description="Gravitational acceleration"),
            parameter(
                "bead_mass_kg",
                "kg",
                0.1,
                low=0.001,
                high=100.0,
                label="m",
                description="Mass of the bead (it scales the energies, not the motion)",
            ),
        )
    ),
    symbols={"hoop_radius_m": R, "hoop_speed_rad_s": Omega, "g_m_s2": g, "bead_mass_kg": m},
    particles=(Particle("bead", m, bead),),
    gravity=vector(0, 0, -g),
    reactions=(
        Reaction("hoop", on="bead", point=bead, forces=(-bead / R, vector(-sympy.sin(angle), sympy.cos(angle), 0))),
    ),
    assumptions="A frictionless bead (a particle) on a rigid hoop whose spin is held at Ω whatever the bead does.",
)
