"""Worked example ``tower-drop-deflection``: a stone dropped or thrown on the rotating Earth, first order and exact.

The system is :mod:`app.physics.systems.ch03.eastward_deflection` (the lesson's scene), in the local frame of
:mod:`app.physics.systems.earth`: x east, y north, z up, origin at the foot of the plumb line through the release
point at height h. Seen from the ground, ``r̈ = −g Z − 2 Ω × ṙ``.

First order in Ω: the Coriolis term acting along the path without rotation, ``u − g t Z``, displaces the body by
``δr(t) = −(Ω × u) t² + ⅓ g t³ (Ω × Z)``; its vertical part moves the landing instant by ``δt = δr_z / |v_z(t₀)|``,
which carries the horizontal launch velocity on by ``u_h δt``. So the first-order landing point lies
``δr_h(t₀) + u_h δt`` from the one without rotation (for a drop from rest: ``⅓ Ω g t₀³ cos λ`` east). The exact
landing point is from :class:`~app.physics.systems.ch03.eastward_deflection.Flight` (the closed-form solution).

Every in-range input is possible (a body released above the ground always lands), so nothing is refused beyond the
ranges.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample, zero_round_off
from app.physics.systems.ch03.eastward_deflection import PARAMETERS, Flight

INPUTS = PARAMETERS
_UP = np.array([0.0, 0.0, 1.0])


def first_order_deflection(flight: Flight) -> tuple[np.ndarray, float, float, np.ndarray]:
    """``(δr(t₀), v_z(t₀), δt, deflection)`` to first order in Ω: the displacement at the landing instant
    without rotation (m, (3,)), the vertical velocity then (m/s), the shift of the landing instant (s) and the
    horizontal deflection of the landing point (m, (3,), up component 0)."""
    u, omega, g = flight.v0_m_s, flight.omega_local, flight.g_m_s2
    t0 = flight.fall_time_without_rotation_s()
    shift = -np.cross(omega, u) * t0**2 + (g / 3.0) * np.cross(omega, _UP) * t0**3
    vz = float(u[2]) - g * t0
    dt = float(shift[2]) / -vz
    deflection = shift + u * dt
    deflection[2] = 0.0
    return shift, vz, dt, deflection


def solve(inputs: Mapping[str, Any]) -> Solution:
    flight = Flight.from_params(inputs)
    u, omega, g, h = flight.v0_m_s, flight.omega_local, flight.g_m_s2, float(inputs["height_m"])
    t0 = flight.fall_time_without_rotation_s()
    plain_landing = np.array([u[0] * t0, u[1] * t0, 0.0])  # h + u_z t0 − ½ g t0² = 0 by the choice of t0
    shift, vz, dt, first = first_order_deflection(flight)

    t_land = flight.landing_time_s()
    position, velocity = flight.state(np.array([t_land]))
    exact = position[0] - plain_landing
    exact[2] = 0.0
    # What a zero is measured against: the size a deflection of this flight has where Ω is square to it (at the
    # poles a drop's deflection is cos 90° ≈ 6e-17 of that: round-off, shown as 0).
    scale = float(np.linalg.norm(omega)) * (g * t0**3 / 3.0 + float(np.linalg.norm(u)) * t0**2)
    shift, first, exact = (zero_round_off(v, scale) for v in (shift, first, exact))
    # The small parameter of the expansion: the Earth's turn during the flight, and the Coriolis push on the launch
    # speed against gravity (which sets how far a change of height moves the landing instant).
    epsilon = float(np.linalg.norm(omega)) * (t0 + float(np.linalg.norm(u)) / g)
    difference = exact - first
    first_size = float(np.linalg.norm(first))
    relative = float(np.linalg.norm(difference)) / first_size if first_size > 0.0 else 0.0
    energy_release = 0.5 * float(u @ u) + g * h
    energy_landing = 0.5 * float(velocity[0] @ velocity[0]) + g * float(position[0, 2])
    steps = (
        Step(
            "The Earth's angular velocity in the local frame (east, north, up)",
            r"\bar\Omega = \Omega\cos\lambda\,\bar j + \Omega\sin\lambda\,\bar k,\quad \Omega = 7.292115\times10^{-5}"
            r"\ \text{rad/s}",
            {"lambda": inputs["latitude_deg"], "Omega": omega},
            {"lambda": "deg", "Omega": "rad/s"},
        ),
        Step(
            "The flight if the Earth did not turn",
            r"h + u_z t_0 - \tfrac12 g t_0^2 = 0\ \Rightarrow\ t_0 = \frac{u_z + \sqrt{u_z^2 + 2gh}}{g},\quad "
            r"\bar r_0(t_0) = h\,\bar k + \bar u\,t_0 - \tfrac12 g t_0^2\,\bar k",
            {"t_0": t0, "r_land_0": plain_landing},
            {"t_0": "s", "r_land_0": "m"},
        ),
        Step(
            "First order in Ω: the Coriolis push along that flight",
            r"\delta\ddot{\bar r} = -2\,\bar\Omega\times(\bar u - g t\,\bar k)\ \Rightarrow\ "
            r"\delta\bar r(t_0) = -(\bar\Omega\times\bar u)\,t_0^2 + \tfrac13 g t_0^3\,(\bar\Omega\times\bar k)",
            {"delta_r": shift},
            {"delta_r": "m"},
            {"delta_r": scale},
        ),
        Step(
            "First-order landing point: a higher or lower flight lands later or sooner",
            r"\delta t = \frac{\delta r_z}{|v_z(t_0)|},\ v_z(t_0) = u_z - g t_0,\quad "
            r"\Delta\bar r_1 = \delta\bar r_h(t_0) + \bar u_h\,\delta t\quad "
            r"\big(\text{from rest: } \tfrac13\,\Omega g t_0^3\cos\lambda \text{ east}\big)",
            {"v_z": vz, "delta_t": dt, "deflection_1": first},
            {"v_z": "m/s", "delta_t": "s", "deflection_1": "m"},
            {"deflection_1": scale},
        ),
        Step(
            "The exact landing point, from the closed-form solution of the rotating-frame equations",
            r"\bar v(t) = [R(t)]\,\bar u + [S_1(t)]\,\bar g,\quad \bar r(t) = h\bar k + [S_1(t)]\,\bar u + "
            r"[S_2(t)]\,\bar g,\quad r_z(t_{\rm land}) = 0,\quad \Delta\bar r = \bar r(t_{\rm land}) - \bar r_0(t_0)",
            {"t_land": t_land, "deflection": exact, "east_mm": 1000.0 * exact[0], "north_mm": 1000.0 * exact[1]},
            {"t_land": "s", "deflection": "m", "east_mm": "mm", "north_mm": "mm"},
            {"deflection": scale},
        ),
        Step(
            "Check: the Coriolis force does no work, and first order misses only a relative error of order ε",
            r"\tfrac12|\bar v_{\rm land}|^2 = \tfrac12|\bar u|^2 + g h,\quad "
            r"\frac{|\Delta\bar r - \Delta\bar r_1|}{|\Delta\bar r_1|} \sim \varepsilon = "
            r"\Omega\left(t_0 + \frac{|\bar u|}{g}\right)",
            {
                "half_v2_plus_gz_release": energy_release,
                "half_v2_plus_gz_landing": energy_landing,
                "exact_minus_first_order": difference,
                "relative_difference": relative,
                "epsilon": epsilon,
            },
            {
                "half_v2_plus_gz_release": "J/kg",
                "half_v2_plus_gz_landing": "J/kg",
                "exact_minus_first_order": "m",
                "relative_difference": "",
                "epsilon": "",
            },
            {"exact_minus_first_order": scale},
        ),
    )
    outputs = {
        "fall_time_s": t0,
        "landing_time_s": t_land,
        "first_order_deflection_m": first,
        "deflection_m": exact,
        "landing_speed_m_s": float(np.linalg.norm(velocity[0])),
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={"first_order_deflection_m": scale, "deflection_m": scale},
    )


EXAMPLE = WorkedExample(
    id="tower-drop-deflection",
    title="A stone dropped on the turning Earth: where it lands, to first order and exactly",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "fall_time_s": "s",
        "landing_time_s": "s",
        "first_order_deflection_m": "m",
        "deflection_m": "m",
        "landing_speed_m_s": "m/s",
    },
    section="3.6",
    story=ExampleStory(
        situation=(
            "A stone is let go from rest at the top of a 100 m tower at latitude 45° N, with "
            "$g = 9.80665$ m/s² along the plumb line. The ground, and the frame we measure in, turns with the "
            "Earth at $\\Omega = 7.292115\\times10^{-5}$ rad/s about the polar axis. The stone may also be "
            "thrown, with any launch velocity relative to the ground; air drag is left out."
        ),
        wanted=(
            "How far from the point it would hit on a non-turning Earth the stone lands, east and north, in "
            "millimetres: first as the classic first-order estimate in $\\Omega$, then exactly, together with "
            "the fall time and the landing speed. We also want to know how much the "
            "first-order estimate misses, so that we can tell when it is good enough for a real measurement."
        ),
        approach=(
            "We stay in the ground's frame, because that is where the tower, the release point and the landing "
            "mark are. With the centrifugal part already inside $g$, the only price of the turning frame is the "
            "Coriolis term $-2\\bar\\Omega\\times\\dot{\\bar r}$. It is tiny, so to first order it may act "
            "along the flight without rotation; two integrations give the displacement in closed form. Working "
            "in a non-turning frame instead would mean following the stone and the tower's foot round the "
            "Earth's axis, about 330 m per second each at this latitude, to find a difference of millimetres. "
            "The exact answer solves the same linear equation in closed form."
        ),
        check=(
            "The Coriolis force is always perpendicular to the velocity, so it does no work: the stone's "
            "$\\tfrac12 v^2 + g z$ per unit mass must be the same at landing as at release, whatever the "
            "latitude or launch. The last step prints both. It also prints the exact minus the first-order "
            "deflection: relative to the first-order result it must be of the order of the expansion's small "
            "number $\\varepsilon = \\Omega(t_0 + |\\bar u|/g)$, about $3\\times10^{-4}$ here, so a few "
            "micrometres, almost all of it the second-order drift towards the equator."
        ),
        what_if=(
            "Move the **latitude**. The eastward deflection follows $\\cos\\lambda$: largest at the equator, "
            "zero at the poles where $\\bar\\Omega$ is parallel to the fall. Then give the stone an upward "
            "**launch velocity** of 40 m/s from 1 m: it climbs while being pushed west and falls while "
            "being pushed east, and it lands west of the launch point; the scene draws that path magnified."
        ),
    ),
)
