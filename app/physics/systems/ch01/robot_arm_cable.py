"""Worked Example 1.1: a robotic arm ABC pulled by a cable from C to a fixed point D.

Frame: fixed xyz with A at the origin and z vertical (unit vectors i, j, k).
Link AB lies in the horizontal plane at angle theta from x; link BC is raised by
gamma about a horizontal pin at B perpendicular to AB, so AB and BC share a
vertical plane. D lies on the x axis. Lengths in m, forces in N, moments in N·m.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.math.vectors import moment_about_point, unit_vector


def _check_cable_has_length(values: Mapping[str, Any]) -> None:
    arm_geometry(values["theta_deg"], values["gamma_deg"], values["AB_m"], values["BC_m"], values["D_x_m"])


INPUTS = ParameterSet(
    (
        Parameter(
            "theta_deg",
            "deg",
            25.0,
            -180.0,
            180.0,
            "Angle of link AB from the x axis, in the horizontal plane",
            "θ",
            step=1,
        ),
        Parameter("gamma_deg", "deg", 40.0, -90.0, 90.0, "Elevation of link BC above the horizontal", "γ", step=1),
        Parameter("tension_N", "N", 5000.0, 0.0, 100_000.0, "Tension in cable CD", "T", step=100),
        Parameter("AB_m", "m", 2.0, 0.05, 10.0, "Length of link AB", "AB", step=0.05),
        Parameter("BC_m", "m", 1.5, 0.05, 10.0, "Length of link BC", "BC", step=0.05),
        Parameter("D_x_m", "m", 3.5, -10.0, 10.0, "x coordinate of the cable anchor D on the x axis", "x_D", step=0.05),
    ),
    check=_check_cable_has_length,
)


@dataclass(frozen=True)
class ArmGeometry:
    """Points of the arm (m, fixed frame xyz)."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    e_AB: np.ndarray  # unit vector along AB
    e_BC: np.ndarray  # unit vector along BC
    e_CD: np.ndarray  # unit vector from C toward D (cable direction on the arm)


@dataclass(frozen=True)
class CableLoads:
    """The cable force on the arm and its moments (N, N·m, fixed frame xyz)."""

    geometry: ArmGeometry
    F_N: np.ndarray
    F_BC_N: float
    M_A_Nm: np.ndarray
    M_z_Nm: float
    M_AB_Nm: float


#: Words of :func:`turning_about_z`: how the cable turns the arm about the vertical axis through A, seen from above.
TURNING_WORDS = ("counter-clockwise", "clockwise", "none")
#: |M_z| at or below this fraction of |F|·|r_C| counts as no turning: the moment is exact to a few
#: ulps of that scale (≈ 1e-16; θ = 180° leaves sin θ ≈ 1e-16), while θ = 1e-6° already gives ≈ 1e-8 of it.
NO_TURNING_RTOL = 1e-12


def arm_geometry(theta_deg: float, gamma_deg: float, AB_m: float, BC_m: float, D_x_m: float) -> ArmGeometry:
    theta, gamma = np.radians(theta_deg), np.radians(gamma_deg)
    A = np.zeros(3)
    e_AB = np.array([np.cos(theta), np.sin(theta), 0.0])
    e_BC = np.array([np.cos(gamma) * np.cos(theta), np.cos(gamma) * np.sin(theta), np.sin(gamma)])
    B = A + AB_m * e_AB
    C = B + BC_m * e_BC
    D = np.array([D_x_m, 0.0, 0.0])
    try:
        e_CD = unit_vector(D - C)
    except ValueError:
        raise ParameterError(
            "D_x_m", "the cable end C coincides with the anchor D, so the cable has no direction"
        ) from None
    return ArmGeometry(A, B, C, D, e_AB, e_BC, e_CD)


def cable_loads(inputs: Mapping[str, Any]) -> CableLoads:
    g = arm_geometry(inputs["theta_deg"], inputs["gamma_deg"], inputs["AB_m"], inputs["BC_m"], inputs["D_x_m"])
    F = inputs["tension_N"] * g.e_CD
    M_A = moment_about_point(g.C, F, g.A)
    return CableLoads(
        geometry=g,
        F_N=F,
        F_BC_N=float(F @ g.e_BC),
        M_A_Nm=M_A,
        M_z_Nm=float(M_A[2]),
        M_AB_Nm=float(M_A @ g.e_AB),
    )


def round_off_scales(loads: CableLoads) -> dict[str, float]:
    """The magnitude each load is computed against (N for forces, N·m for moments), by output name: |F| for the force
    and its component along BC, |r_C|·|F| for the moments. A load within round-off of its scale is zero (θ = 180° leaves
    M_z = −1e-12 N·m of a 17 500 N·m scale; θ = 25°, γ = 45° an x component of M_A of 4.5e-13 N·m)."""
    force = float(np.linalg.norm(loads.F_N))
    moment = float(np.linalg.norm(loads.geometry.C)) * force
    return {"F_N": force, "F_BC_N": force, "M_A_Nm": moment, "M_z_Nm": moment, "M_AB_Nm": moment}


def turning_about_z(loads: CableLoads) -> str:
    """How the cable turns the arm about the vertical z axis through A, seen from above (one of :data:`TURNING_WORDS`).

    M_z > 0 turns it counter-clockwise (right-hand rule about +z), M_z < 0 clockwise.
    """
    counter_clockwise, clockwise, none = TURNING_WORDS
    scale = float(np.linalg.norm(loads.F_N)) * float(np.linalg.norm(loads.geometry.C))
    if abs(loads.M_z_Nm) <= NO_TURNING_RTOL * scale:
        return none
    return counter_clockwise if loads.M_z_Nm > 0.0 else clockwise


def solve(inputs: Mapping[str, Any]) -> Solution:
    loads = cable_loads(inputs)
    g = loads.geometry
    scale = round_off_scales(loads)
    steps = (
        Step(
            "Positions of B, C and D",
            r"\bar r_{B} = AB(\cos\theta\,\bar i + \sin\theta\,\bar j),\quad "
            r"\bar r_{C} = \bar r_{B} + BC(\cos\gamma\cos\theta\,\bar i + \cos\gamma\sin\theta\,\bar j + "
            r"\sin\gamma\,\bar k),\quad "
            r"\bar r_{D} = x_D\,\bar i",
            {"r_B": g.B, "r_C": g.C, "r_D": g.D},
            {"r_B": "m", "r_C": "m", "r_D": "m"},
        ),
        Step(
            "Cable direction and force on the arm",
            r"\bar e_{CD} = \frac{\bar r_D - \bar r_C}{|\bar r_D - \bar r_C|},\quad \bar F = T\,\bar e_{CD}",
            {"e_CD": g.e_CD, "F": loads.F_N},
            {"e_CD": "", "F": "N"},
        ),
        Step(
            "(a) Component of F along BC",
            r"F_{BC} = \bar F\cdot\bar e_{BC}",
            {"e_BC": g.e_BC, "F_BC": loads.F_BC_N},
            {"e_BC": "", "F_BC": "N"},
            scales={"F_BC": scale["F_BC_N"]},
        ),
        Step(
            "(b) Moment of F about A",
            r"\bar M_A = \bar r_{C/A}\times\bar F",
            {"M_A": loads.M_A_Nm},
            {"M_A": "N·m"},
            scales={"M_A": scale["M_A_Nm"]},
        ),
        Step(
            "(c) Moment about the vertical z axis",
            r"M_z = \bar M_A\cdot\bar k",
            {"M_z": loads.M_z_Nm},
            {"M_z": "N·m"},
            scales={"M_z": scale["M_z_Nm"]},
        ),
        Step(
            "(d) Moment about the line of arm AB",
            r"M_{AB} = \bar M_A\cdot\bar e_{AB},\quad \bar e_{AB} = \cos\theta\,\bar i + \sin\theta\,\bar j",
            {"e_AB": g.e_AB, "M_AB": loads.M_AB_Nm},
            {"e_AB": "", "M_AB": "N·m"},
            scales={"M_AB": scale["M_AB_Nm"]},
        ),
        Step(
            "Check: other points of the line of action and of the axis give the same moments",
            r"\bar M_A = \bar r_{D/A}\times\bar F = \bar r_{C/A}\times\bar F,\qquad "
            r"M_{AB} = (\bar r_{C/B}\times\bar F)\cdot\bar e_{AB} = (\bar r_{C/A}\times\bar F)\cdot\bar e_{AB}",
            {
                "M_A (via C)": loads.M_A_Nm,
                "M_A (via D)": moment_about_point(g.D, loads.F_N, g.A),
                "M_AB (about A)": loads.M_AB_Nm,
                "M_AB (about B)": float(moment_about_point(g.C, loads.F_N, g.B) @ g.e_AB),
            },
            {"M_A (via C)": "N·m", "M_A (via D)": "N·m", "M_AB (about A)": "N·m", "M_AB (about B)": "N·m"},
            scales={
                "M_A (via C)": scale["M_A_Nm"],
                "M_A (via D)": scale["M_A_Nm"],
                "M_AB (about A)": scale["M_AB_Nm"],
                "M_AB (about B)": scale["M_AB_Nm"],
            },
        ),
    )
    outputs = {
        "F_N": loads.F_N,
        "F_BC_N": loads.F_BC_N,
        "M_A_Nm": loads.M_A_Nm,
        "M_z_Nm": loads.M_z_Nm,
        "M_AB_Nm": loads.M_AB_Nm,
    }
    return Solution(outputs=outputs, steps=steps, output_scales=scale)


EXAMPLE = WorkedExample(
    id="1.1",
    title="Robotic arm and cable: force components and moments",
    chapter=1,
    inputs=INPUTS,
    solve=solve,
    output_units={"F_N": "N", "F_BC_N": "N", "M_A_Nm": "N·m", "M_z_Nm": "N·m", "M_AB_Nm": "N·m"},
    section="1.1",
    story=ExampleStory(
        situation=(
            "A robotic arm has a base link $AB$, 2 m long, lying in the horizontal plane at $\\theta = 25°$ "
            "from the $x$ axis, and a second link $BC$, 1.5 m long, raised $\\gamma = 40°$ about a horizontal "
            "pin at $B$, so both links stand in one vertical plane. A cable from the tip $C$ to the anchor "
            "$D$ on the $x$ axis, 3.5 m from the base $A$, pulls with a tension of 5000 N."
        ),
        wanted=(
            "(a) The part of the cable force that acts along link $BC$; (b) the moment of the cable force about "
            "the base $A$; (c) its moment about the vertical axis through $A$, which the base's turning motor "
            "must resist; (d) its moment about the line of link $AB$, which twists that link."
        ),
        approach=(
            "Everything is done with Cartesian components on one fixed frame $xyz$ at $A$, $z$ up: write the "
            "position of every point, turn the cable's direction into a unit vector, and let dot and cross "
            "products do the geometry. A component along a line is a dot product with that line's unit "
            "vector; a moment about a point is a cross product; a moment about an axis is the moment about "
            "any point of it, dotted with the axis. Finding perpendicular distances and angles in 3D with "
            "trigonometry instead would need a sketch for each part and is where sign mistakes creep in."
        ),
        check=(
            "A force's moment about a point does not depend on which point of its line of action we use, so "
            "$\\bar r_D\\times\\bar F$ must equal $\\bar r_C\\times\\bar F$: $D$ is on the cable too. A "
            "moment about an axis does not depend on which point of the axis we take moments about, so using "
            "$B$ instead of $A$ for $M_{AB}$ must give the same number. The last step computes both pairs, and "
            "they agree to round-off."
        ),
        what_if=(
            "Move **θ** down to 0°. The arm then lies in the vertical $xz$ plane with the cable, so the "
            "force crosses the $z$ axis and is coplanar with line $AB$: $M_z$ and $M_{AB}$ both fall to zero "
            "and $\\bar M_A$ points purely along $\\bar j$ (16 445 N·m). In the scene, watch the green $M_z$ "
            "and blue $M_{AB}$ arrows shrink away while the purple $\\bar M_A$ swings round to horizontal."
        ),
    ),
)
