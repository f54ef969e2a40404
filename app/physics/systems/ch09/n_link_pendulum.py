"""An N-link pendulum (N = 2 … 20), planar or spatial: the derivation engine's scaling study.

Frame N: z up, the first link hinged at the origin. Each link is a uniform thin rod of mass m (kg) and length l (m),
hinged to the end of the one before. Planar: every hinge turns about the y axis, coordinate θ_k (rad) the link's
angle from hanging straight down, relative to the link before. Spatial: every joint is a universal joint, a turn α_k
about the previous link's x axis then β_k about the new y axis (a thin rod has no moment about its own axis, so a
third turn would leave the mass matrix singular). Its reference motion is hanging straight down at rest; the linear
model's eigenvalues are ±iω for the small-oscillation frequencies ω.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.mechanics.description import Coordinate, parameter
from app.physics.mechanics.multibody.parts import (
    GROUND,
    Body,
    MultibodyFamily,
    MultibodySystem,
    ReferenceMotion,
    Revolute,
    column,
    inertia,
)

MIN_LINKS, MAX_LINKS = 2, 20
#: A spatial chain has twice the coordinates: at 10 links (20 coordinates) it derives in about 4.5 s cold; at 20 it
#: took minutes, too long for a request to wait on.
MAX_SPATIAL_LINKS = 10
PHYSICAL = (
    parameter("link_mass_kg", "kg", 1.0, low=0.01, high=100.0, label="m", description="mass of each link"),
    parameter("link_length_m", "m", 0.5, low=0.01, high=10.0, label="l", description="length of each link"),
    parameter("gravity_m_s2", "m/s²", 9.81, low=0.0, high=30.0, label="g", description="gravitational acceleration"),
)
PARAMETERS = ParameterSet(
    (
        Parameter("links", "", 3, MIN_LINKS, MAX_LINKS, "How many links (2 to 20; spatial: 2 to 10)", "N", kind="int"),
        Parameter("planar", "", "planar", kind="choice", choices=("planar", "spatial"), label="motion",
                  description="planar: hinges about one axis; spatial: universal joints, the links swing anywhere"),
        *PHYSICAL,
    )
)  # fmt: skip
m, l, g = (sympy.Symbol(name, positive=True) for name in ("m", "l", "g"))
SYMBOLS = {"link_mass_kg": m, "link_length_m": l, "gravity_m_s2": g}


@functools.cache
def chain(links: int, planar: bool) -> MultibodySystem:
    """The N-link pendulum's parts: N rods, N hinges (planar) or N universal joints (spatial)."""
    if not MIN_LINKS <= links <= MAX_LINKS:
        raise ValueError(f"links: {MIN_LINKS} to {MAX_LINKS}, got {links}")
    bodies, joints = [], []
    parent, at = GROUND, column(0, 0, 0)
    axial = m * l**2 / 12 if planar else 0  # a thin rod's moment about its own axis (planar: never used)
    for k in range(1, links + 1):
        if planar:
            joints.append(
                Revolute(parent, f"link{k}", Coordinate(f"theta{k}", f"\\theta_{{{k}}}"), column(0, 1, 0), at)
            )
        else:
            gimbal = f"gimbal{k}"
            joints.append(Revolute(parent, gimbal, Coordinate(f"alpha{k}", f"\\alpha_{{{k}}}"), column(1, 0, 0), at))
            joints.append(Revolute(gimbal, f"link{k}", Coordinate(f"beta{k}", f"\\beta_{{{k}}}"), column(0, 1, 0)))
        bodies.append(Body(f"link{k}", m, inertia(m * l**2 / 12, m * l**2 / 12, axial), column(0, 0, -l / 2)))
        parent, at = f"link{k}", column(0, 0, -l)
    coordinates = tuple(j.coordinate.name for j in joints)
    n = len(coordinates)
    reference = ReferenceMotion(
        about="hanging straight down at rest",
        coordinates=coordinates,
        speeds=coordinates,
        state=lambda params: (np.zeros(n), np.zeros(n)),
    )
    return MultibodySystem(
        id="n-link-pendulum",
        title=f"{links}-link pendulum ({'planar' if planar else 'spatial'})",
        parameters=ParameterSet(PHYSICAL),
        symbols=SYMBOLS,
        bodies=tuple(bodies),
        joints=tuple(joints),
        gravity=g,
        chapter=9,
        assumptions=ASSUMPTIONS,
        reference=reference,
    )


ASSUMPTIONS = "Uniform thin rods; frictionless hinges (or universal joints, spatial); uniform gravity."


def _member(params) -> MultibodySystem:
    links, planar = int(params["links"]), params["planar"] == "planar"
    if not planar and links > MAX_SPATIAL_LINKS:
        raise ParameterError(
            "links", f"a spatial chain has at most {MAX_SPATIAL_LINKS} links (twice the coordinates of a planar one)"
        )
    return chain(links, planar)


FAMILY = MultibodyFamily(
    id="n-link-pendulum",
    title="N-link pendulum",
    chapter=9,
    assumptions=ASSUMPTIONS,
    parameters=PARAMETERS,
    build=lambda params: _member(params),
)
SYSTEM = FAMILY
