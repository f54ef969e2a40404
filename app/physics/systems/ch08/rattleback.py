"""The rattleback: a rigid body with a curved underside, rolling without slip on a floor, whose spin reverses.

The model and its parameter set are Kane and Levinson's (1982, Int. J. Non-Linear Mech. 17, 175–186): the body is an
ellipsoid with semi-axes a (long), b and c (m), its mass centre G a distance h (m) below the ellipsoid's centre, and
its central inertia has a product xy (kg·m²) in the ellipsoid's axes: the principal axes of inertia are turned by a
small angle δ about the vertical from the axes of the surface's curvature. That misalignment couples rocking about
the long axis with pitching about the short one, and through the rolling contact both with the spin: spun one way
the body pitches harder and harder until the spin stops and reverses; spun the other way it spins far longer.

Frame N: z up, the floor z = 0. The body frame's origin is G; its axes are the ellipsoid's, z up when upright (Kane
and Levinson's axis 3 points down: their D = −2e−5 kg·m² is this model's inertia_xy = +2e−5 kg·m², their roll α and
pitch β are this model's roll and −pitch).
Coordinates: G's x, y, z (m), then the heading ψ (yaw, about N's z), the roll φ about the heading's x axis and the
pitch θ about the rolled y axis (rad). The underside touching the floor fixes z (a configuration constraint); no
slip fixes the rates of x, y (and z), leaving three degrees of freedom in speed: the spin, the roll and the pitch
rates. No friction but the grip that stops slip: the energy is conserved.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import Coordinate, parameter
from app.physics.mechanics.multibody.parts import (
    GROUND,
    Body,
    EllipsoidContact,
    MultibodySystem,
    Prismatic,
    ReferenceMotion,
    Revolute,
    column,
    inertia,
)

PARAMETERS = ParameterSet(
    (
        parameter("mass_kg", "kg", 1.0, low=0.001, high=100.0, label="m", description="mass"),
        parameter("semi_axis_a_m", "m", 0.20, low=0.001, high=2.0, label="a", description="long semi-axis (along x)"),
        parameter("semi_axis_b_m", "m", 0.03, low=0.001, high=2.0, label="b", description="middle semi-axis (along y)"),
        parameter("semi_axis_c_m", "m", 0.02, low=0.001, high=2.0, label="c",
                  description="short semi-axis (vertical when upright)"),
        parameter("mass_centre_drop_m", "m", 0.01, low=0.0, high=2.0, label="h",
                  description="the mass centre's distance below the ellipsoid's centre"),
        parameter("inertia_xx_kg_m2", "kg·m²", 2e-4, low=1e-8, high=10.0, label="A",
                  description="central moment of inertia about the long (x) axis"),
        parameter("inertia_yy_kg_m2", "kg·m²", 1.6e-3, low=1e-8, high=10.0, label="B",
                  description="central moment of inertia about the middle (y) axis"),
        parameter("inertia_zz_kg_m2", "kg·m²", 1.7e-3, low=1e-8, high=10.0, label="C",
                  description="central moment of inertia about the vertical (z) axis"),
        parameter("inertia_xy_kg_m2", "kg·m²", 2e-5, low=-1.0, high=1.0, label="D",
                  description="the central inertia tensor's xy entry: the misalignment of the principal axes"),
        parameter("gravity_m_s2", "m/s²", 9.81, low=0.0, high=30.0, label="g",
                  description="gravitational acceleration"),
        parameter("spin_rad_s", "rad/s", 5.0, low=-50.0, high=50.0, label="ω",
                  description="spin about the vertical of the steady motion the eigenvalues are about (positive: "
                  "anticlockwise seen from above)"),
    )
)  # fmt: skip

_LETTERS = ("m", "a", "b", "c", "h", "A", "B", "C", "D", "g", "omega")
SYMBOLS = {p.name: sympy.Symbol(letter, real=True) for p, letter in zip(PARAMETERS.parameters, _LETTERS, strict=True)}
m, a, b, c, h, A, B, C, D, g = (SYMBOLS[p.name] for p in PARAMETERS.parameters[:10])

x, y, z = (Coordinate(name, name, unit="m") for name in ("x", "y", "z"))
yaw, roll, pitch = Coordinate("yaw", "\\psi"), Coordinate("roll", "\\phi"), Coordinate("pitch", "\\theta")


def _upright_spinning(params: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """Upright (G straight above the lowest point, at height c − h), spinning at spin_rad_s about the vertical."""
    q, u = np.zeros(6), np.zeros(6)
    q[2] = params["semi_axis_c_m"] - params["mass_centre_drop_m"]
    u[3] = params["spin_rad_s"]
    return q, u


#: Rocking (roll, pitch) and the spin about upright steady spinning at spin_rad_s; yaw itself never matters.
REFERENCE = ReferenceMotion(
    about="upright, spinning steadily about the vertical at spin_rad_s (rad/s)",
    coordinates=("roll", "pitch"),
    speeds=("yaw", "roll", "pitch"),
    state=_upright_spinning,
    sweep=("spin_rad_s", -10.0, 10.0),
)

SYSTEM = MultibodySystem(
    id="rattleback",
    title="The rattleback (Kane and Levinson's model)",
    parameters=PARAMETERS,
    symbols=SYMBOLS,
    bodies=(Body("rattleback", m, inertia(A, B, C, ixy=D)),),
    joints=(
        Prismatic(GROUND, "slide_x", x, column(1, 0, 0)),
        Prismatic("slide_x", "slide_y", y, column(0, 1, 0)),
        Prismatic("slide_y", "slide_z", z, column(0, 0, 1)),
        Revolute("slide_z", "heading", yaw, column(0, 0, 1)),
        Revolute("heading", "rolled", roll, column(1, 0, 0)),
        Revolute("rolled", "rattleback", pitch, column(0, 1, 0)),
    ),
    contacts=(EllipsoidContact("rattleback", column(a, b, c), centre=column(0, 0, h)),),
    gravity=g,
    dependent_coordinates=("z",),
    dependent_speeds=("z", "x", "y"),
    chapter=8,
    assumptions=(
        "A rigid ellipsoid rolling without slip on a flat floor, never leaving it; no rolling or spin friction (energy "
        "is conserved)."
    ),
    reference=REFERENCE,
)
