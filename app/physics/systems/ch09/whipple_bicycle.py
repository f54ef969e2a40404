"""The Whipple bicycle: four rigid bodies, two knife-edge wheels rolling without slip, no rider control.

The benchmark of Meijaard, Papadopoulos, Ruina and Schwab (2007, Proc. R. Soc. A 463, 1955–1982) gives its
parameters (their Table 1, the defaults here) in their frame: x forward, y to the right, z down, the origin at the
rear contact. Parameters are entered in that frame, as published; the model turns them into ours (x forward, y to the
left, z up: y and z change sign, and so do the products of inertia I_xz).

Bodies: the rear wheel R, the rear frame B (with the rider, rigid), the front frame H (fork and handlebar) and the
front wheel F. Coordinates: the rear contact's x, y (m), yaw ψ, lean (roll) φ, the rear wheel's spin θ_R, the rear
frame's pitch θ_B, the steer δ and the front wheel's spin θ_F (rad). The front wheel touching the ground fixes the
pitch (a configuration constraint); no slip at both contacts fixes five rates (x, y, ψ, θ_B, θ_F), leaving three
degrees of freedom in speed: lean rate, steer rate and the rear wheel's rate (the forward speed).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import Coordinate, parameter
from app.physics.mechanics.multibody.compiled import CompiledSystem
from app.physics.mechanics.multibody.linearise import eigenvalues, stability_crossings, state_matrix
from app.physics.mechanics.multibody.parts import (
    Body,
    MultibodySystem,
    ReferenceMotion,
    Revolute,
    RollingContact,
    RollingWheel,
    column,
    inertia,
)

#: (name, unit, benchmark value, low, high, label, description), in the benchmark's frame (z down).
_TABLE: tuple[tuple[str, str, float, float, float, str, str], ...] = (
    ("wheelbase_m", "m", 1.02, 0.5, 2.0, "w", "distance between the wheels' contact points"),
    ("trail_m", "m", 0.08, -0.2, 0.3, "c", "distance the front contact trails behind the steer axis's ground point"),
    ("steer_axis_tilt_rad", "rad", math.pi / 10, -0.5, 0.8, "λ", "steer axis tilt back from the vertical"),
    ("gravity_m_s2", "m/s²", 9.81, 0.0, 30.0, "g", "gravitational acceleration"),
    ("rear_wheel_radius_m", "m", 0.3, 0.1, 1.0, "r_R", "rear wheel radius"),
    ("rear_wheel_mass_kg", "kg", 2.0, 0.1, 20.0, "m_R", "rear wheel mass"),
    ("rear_wheel_Ixx_kg_m2", "kg·m²", 0.0603, 0.001, 2.0, "I_Rxx", "rear wheel moment about a diameter"),
    ("rear_wheel_Iyy_kg_m2", "kg·m²", 0.12, 0.001, 4.0, "I_Ryy", "rear wheel moment about its axle"),
    ("rear_frame_x_m", "m", 0.3, -1.0, 2.0, "x_B", "rear frame's mass centre, forward of the rear contact"),
    ("rear_frame_z_m", "m", -0.9, -3.0, 0.0, "z_B", "rear frame's mass centre, below the ground (negative: above)"),
    ("rear_frame_mass_kg", "kg", 85.0, 1.0, 300.0, "m_B", "rear frame mass, rider included"),
    ("rear_frame_Ixx_kg_m2", "kg·m²", 9.2, 0.01, 100.0, "I_Bxx", "rear frame central moment about x"),
    ("rear_frame_Iyy_kg_m2", "kg·m²", 11.0, 0.01, 100.0, "I_Byy", "rear frame central moment about y"),
    ("rear_frame_Izz_kg_m2", "kg·m²", 2.8, 0.01, 100.0, "I_Bzz", "rear frame central moment about z"),
    ("rear_frame_Ixz_kg_m2", "kg·m²", 2.4, -50.0, 50.0, "I_Bxz", "rear frame central product of inertia xz"),
    ("front_frame_x_m", "m", 0.9, -1.0, 3.0, "x_H", "front frame's mass centre, forward of the rear contact"),
    ("front_frame_z_m", "m", -0.7, -3.0, 0.0, "z_H", "front frame's mass centre, below the ground (negative: above)"),
    ("front_frame_mass_kg", "kg", 4.0, 0.1, 50.0, "m_H", "front frame (fork and handlebar) mass"),
    ("front_frame_Ixx_kg_m2", "kg·m²", 0.05892, 0.0001, 10.0, "I_Hxx", "front frame central moment about x"),
    ("front_frame_Iyy_kg_m2", "kg·m²", 0.06, 0.0001, 10.0, "I_Hyy", "front frame central moment about y"),
    ("front_frame_Izz_kg_m2", "kg·m²", 0.00708, 0.0001, 10.0, "I_Hzz", "front frame central moment about z"),
    ("front_frame_Ixz_kg_m2", "kg·m²", -0.00756, -5.0, 5.0, "I_Hxz", "front frame central product of inertia xz"),
    ("front_wheel_radius_m", "m", 0.35, 0.1, 1.0, "r_F", "front wheel radius"),
    ("front_wheel_mass_kg", "kg", 3.0, 0.1, 20.0, "m_F", "front wheel mass"),
    ("front_wheel_Ixx_kg_m2", "kg·m²", 0.1405, 0.001, 2.0, "I_Fxx", "front wheel moment about a diameter"),
    ("front_wheel_Iyy_kg_m2", "kg·m²", 0.28, 0.001, 4.0, "I_Fyy", "front wheel moment about its axle"),
)

#: The forward speed of the reference motion (upright, straight ahead), m/s: not in the equations, only in the motion.
SPEED = parameter(
    "speed_m_s", "m/s", 4.6, low=-20.0, high=20.0, label="v",
    description="forward speed of the upright, straight-ahead motion the bicycle is linearised about",
)  # fmt: skip

PARAMETERS = ParameterSet(
    [parameter(n, unit, v, low=lo, high=hi, label=label, description=d) for n, unit, v, lo, hi, label, d in _TABLE]
    + [SPEED]
)
SYMBOLS = {name: sympy.Symbol(name, real=True) for name, *_ in _TABLE} | {"speed_m_s": sympy.Symbol("v", real=True)}
_s = SYMBOLS
w, c, tilt, g = _s["wheelbase_m"], _s["trail_m"], _s["steer_axis_tilt_rad"], _s["gravity_m_s2"]
rR, rF = _s["rear_wheel_radius_m"], _s["front_wheel_radius_m"]

x, y = Coordinate("x", "x", "m"), Coordinate("y", "y", "m")
yaw, lean = Coordinate("yaw", "\\psi"), Coordinate("lean", "\\phi")
rear_spin, pitch = Coordinate("rear_spin", "\\theta_R"), Coordinate("pitch", "\\theta_B")
steer, front_spin = Coordinate("steer", "\\delta"), Coordinate("front_spin", "\\theta_F")


def _flipped_inertia(body: str, *, axisymmetric: bool) -> sympy.Matrix:
    """The published central inertia turned from the benchmark's frame (y right, z down) into ours (y left, z up)."""
    ixx, iyy = _s[f"{body}_Ixx_kg_m2"], _s[f"{body}_Iyy_kg_m2"]
    if axisymmetric:
        return inertia(ixx, iyy, ixx)
    return inertia(ixx, iyy, _s[f"{body}_Izz_kg_m2"], ixz=-_s[f"{body}_Ixz_kg_m2"])


#: Where the steer axis meets the ground, from the rear wheel's centre, in the rear frame's components (m).
STEER_AXIS_FOOT = column(w + c, 0, -rR)


def _upright(params: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """Upright and straight ahead, the rear wheel turning at speed_m_s / r_R (the pitch and the other rates are
    solved from the constraints)."""
    n = len(SYSTEM.coordinates)
    q, u = np.zeros(n), np.zeros(n)
    u[SYSTEM.index("rear_spin")] = params["speed_m_s"] / params["rear_wheel_radius_m"]
    return q, u


#: The linear model of the benchmark: lean φ and steer δ and their rates, about upright straight-ahead rolling.
REFERENCE = ReferenceMotion(
    about="upright, straight-ahead rolling at speed_m_s (m/s)",
    coordinates=("lean", "steer"),
    speeds=("lean", "steer"),
    state=_upright,
    sweep=("speed_m_s", 0.0, 10.0),
    crossing_names=(("stable", True, "weave speed"), ("unstable", False, "capsize speed")),
)


SYSTEM = MultibodySystem(
    id="whipple-bicycle",
    title="The Whipple bicycle (the 2007 benchmark)",
    parameters=PARAMETERS,
    symbols=SYMBOLS,
    bodies=(
        Body("rear_wheel", _s["rear_wheel_mass_kg"], _flipped_inertia("rear_wheel", axisymmetric=True)),
        Body(
            "rear_frame",
            _s["rear_frame_mass_kg"],
            _flipped_inertia("rear_frame", axisymmetric=False),
            column(_s["rear_frame_x_m"], 0, -_s["rear_frame_z_m"] - rR),
        ),
        Body(
            "front_frame",
            _s["front_frame_mass_kg"],
            _flipped_inertia("front_frame", axisymmetric=False),
            column(_s["front_frame_x_m"] - w - c, 0, -_s["front_frame_z_m"]),
        ),
        Body("front_wheel", _s["front_wheel_mass_kg"], _flipped_inertia("front_wheel", axisymmetric=True)),
    ),
    joints=(
        RollingWheel("rear_wheel", rR, x=x, y=y, yaw=yaw, lean=lean, spin=rear_spin),
        Revolute("rear_wheel.axle", "rear_frame", pitch, axis=column(0, 1, 0)),
        Revolute(
            "rear_frame", "front_frame", steer, axis=column(-sympy.sin(tilt), 0, sympy.cos(tilt)), at=STEER_AXIS_FOOT
        ),
        Revolute("front_frame", "front_wheel", front_spin, axis=column(0, 1, 0), at=column(-c, 0, rF)),
    ),
    contacts=(RollingContact("front_wheel", rF),),
    gravity=g,
    dependent_coordinates=("pitch",),
    dependent_speeds=("x", "y", "yaw", "pitch", "front_spin"),
    chapter=9,
    assumptions=(
        "Four rigid bodies; knife-edge wheels rolling without slip on a flat floor and never leaving it; no friction "
        "in the hinges; a rigid rider who neither steers nor leans."
    ),
    reference=REFERENCE,
)


def weave_and_capsize(model: CompiledSystem, params: Mapping[str, float], *, low: float = 0.0, high: float = 10.0):
    """The self-stable band's ends (m/s): the weave speed, where the oscillating pair turns stable, and the capsize
    speed, where the real lean mode turns unstable; None for an end not found on [low, high]."""
    base = dict(params)

    def spectrum(speed: float) -> np.ndarray:
        return eigenvalues(state_matrix(model, {**base, "speed_m_s": speed}, REFERENCE))

    crossings = stability_crossings(spectrum, low, high)
    weave = next((c.value for c in crossings if c.becomes == "stable" and c.oscillating), None)
    capsize = next((c.value for c in crossings if c.becomes == "unstable" and not c.oscillating), None)
    return weave, capsize
