"""Virtual work: a toggle press held in equilibrium, and the slider-crank's drive torque by dynamic virtual work.

**Toggle press** (statics). Frame (planar, m): the fixed pin A at the origin,
x along the line AC, y up. Bar AB (length a) makes the angle θ with AC; bar BC
(length b) ends at the pin C of a slider that runs along AC on a frictionless
guide. Loads: P down at the knee B, the bars' weights W₁ and W₂ down at their
midpoints G₁ and G₂. The press's output is the force Q with which the
workpiece pushes back on C along −x; to find it, release that constraint: the
frame becomes a mechanism with one degree of freedom θ, and every load point
moves by ``δr = r′(θ) δθ`` (differentiated positions). ``δW = 0`` for every δθ
gives Q without any pin or guide force (they do no virtual work). At θ = 0 the
bars lie in line (the toggle position): ``δx_C = 0`` for every δθ, Q does no
virtual work, and no finite Q holds a load that does: :class:`TogglePositionError`.
The independent check is the member-by-member equilibrium of the two bars,
six equations solved as one linear system: :func:`toggle_equilibrium`.

**Slider-crank** (dynamics), as in :mod:`app.physics.systems.ch06.mechanism_kinetics`
(same frame, links and parameters): with ``δr_i = r_i′(θ) δθ`` and ``δφ_i = φ_i′ δθ``,
``τ δθ + Σ (F_i − m_i a_i)·δr_i − Σ I_i α_i δφ_i = 0`` for every δθ, so
``τ = Σ (m_i a_i − F_i)·r_i′ + Σ I_i α_i φ_i′`` (bodies: crank about G₁, rod about
G₂, slider at B; F_i their weights). Pin forces act in equal and opposite pairs on
points that move together, and the guide force is normal to the slider's only
motion, so their virtual work is zero (:func:`constraint_virtual_work`, computed
from Newton–Euler's pin forces, shows it term by term).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from app.physics.bodies.inertia import slender_rod
from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.systems.ch04.crank_drive import CrankDrive
from app.physics.systems.ch06 import mechanism_kinetics as kinetics

#: |δx_C/δθ| below this fraction of a + b is the toggle position (θ = 0 gives exactly 0).
TOGGLE_TOLERANCE = 1e-12
#: Bar BC may lean no closer to the vertical than this (cos of its angle to AC): beyond it C barely moves.
LEAST_BC_COSINE = 0.05


class TogglePositionError(ValueError):
    """The released constraint's force does no virtual work here: no finite force holds the loads."""


def _check_toggle(values: Mapping[str, Any]) -> None:
    TogglePress.from_params(values)


TOGGLE_PARAMETERS = ParameterSet(
    (
        Parameter("bar_AB_m", "m", 1.0, 0.1, 5.0, "Length a of bar AB (A: fixed pin)", "a", step=0.01),
        Parameter(
            "bar_BC_m", "m", 1.0, 0.1, 5.0, "Length b of bar BC (C: pin of the slider on line AC)", "b", step=0.01
        ),
        Parameter(
            "angle_deg",
            "deg",
            20.0,
            0.0,
            85.0,
            "Angle θ of bar AB above the line AC (0: the bars in line, the toggle position)",
            "θ",
            step=0.5,
        ),
        Parameter("load_B_N", "N", 500.0, -10_000.0, 10_000.0, "Load P at the knee B, downward positive", "P", step=10),
        Parameter("weight_AB_N", "N", 50.0, 0.0, 10_000.0, "Weight W₁ of bar AB, at its midpoint G₁", "W₁", step=5),
        Parameter("weight_BC_N", "N", 50.0, 0.0, 10_000.0, "Weight W₂ of bar BC, at its midpoint G₂", "W₂", step=5),
    ),
    check=_check_toggle,
)


@dataclass(frozen=True)
class TogglePress:
    """Bars a = AB and b = BC (m), angle θ of AB above AC (rad), loads P, W₁, W₂ (N, downward positive)."""

    bar_AB_m: float
    bar_BC_m: float
    angle_rad: float
    load_B_N: float
    weight_AB_N: float
    weight_BC_N: float

    def __post_init__(self) -> None:
        a, b, theta = self.bar_AB_m, self.bar_BC_m, self.angle_rad
        if not (a > 0.0 and b > 0.0):
            raise ParameterError("bar_AB_m", "both bars need positive lengths")
        if not 0.0 <= theta < 0.5 * math.pi:
            raise ParameterError("angle_deg", "θ must lie in [0°, 90°)")
        if self._bc_reach_m < LEAST_BC_COSINE * b:
            raise ParameterError(
                "bar_BC_m",
                f"bar BC (b = {b:g} m) must reach line AC well clear of the vertical: b cos(BC's angle) ≥ "
                f"{LEAST_BC_COSINE:g} b "
                f"needs b ≥ {a * math.sin(theta) / math.sqrt(1.0 - LEAST_BC_COSINE**2):.4g} m at a = {a:g} m and "
                f"θ = {math.degrees(theta):g}°",
            )

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> TogglePress:
        return cls(
            params["bar_AB_m"],
            params["bar_BC_m"],
            math.radians(params["angle_deg"]),
            params["load_B_N"],
            params["weight_AB_N"],
            params["weight_BC_N"],
        )

    @property
    def _bc_reach_m(self) -> float:
        """√(b² − a² sin²θ) (m): the horizontal span of BC (or −1 when BC cannot reach AC)."""
        squared = self.bar_BC_m**2 - (self.bar_AB_m * math.sin(self.angle_rad)) ** 2
        return math.sqrt(squared) if squared > 0.0 else -1.0

    def points(self) -> dict[str, np.ndarray]:
        """A, B, C, G₁, G₂ as (2,) positions (m)."""
        a, theta = self.bar_AB_m, self.angle_rad
        knee = a * np.array([math.cos(theta), math.sin(theta)])
        slider = np.array([a * math.cos(theta) + self._bc_reach_m, 0.0])
        return {"A": np.zeros(2), "B": knee, "C": slider, "G1": 0.5 * knee, "G2": 0.5 * (knee + slider)}

    def virtual_displacements(self) -> dict[str, np.ndarray]:
        """δr/δθ (m per rad, (2,)) of B, C, G₁, G₂ for the mechanism left when C's hold along AC is released.

        ``B′ = a(−sin θ, cos θ)``; ``x_C′ = −a sin θ − a² sin θ cos θ / √(b² − a² sin²θ)``; midpoints average their
        ends.
        """
        a, theta = self.bar_AB_m, self.angle_rad
        knee = a * np.array([-math.sin(theta), math.cos(theta)])
        slider = np.array([-a * math.sin(theta) * (1.0 + a * math.cos(theta) / self._bc_reach_m), 0.0])
        return {"B": knee, "C": slider, "G1": 0.5 * knee, "G2": 0.5 * (knee + slider)}

    def loads(self) -> dict[str, np.ndarray]:
        """The applied loads (N, (2,)) by the point they act at: P at B, W₁ at G₁, W₂ at G₂."""
        return {
            "B": np.array([0.0, -self.load_B_N]),
            "G1": np.array([0.0, -self.weight_AB_N]),
            "G2": np.array([0.0, -self.weight_BC_N]),
        }

    def load_virtual_work_N_m(self) -> float:
        """Σ F·δr/δθ of the applied loads (N·m per rad of δθ)."""
        displacements = self.virtual_displacements()
        return float(sum(force @ displacements[point] for point, force in self.loads().items()))


def holding_force_by_virtual_work(press: TogglePress) -> float:
    """Q (N, on C along −x) from ``δW = (Σ F·r′ − Q x_C′) δθ = 0``; :class:`TogglePositionError` where ``x_C′ = 0``."""
    slider_coefficient = float(press.virtual_displacements()["C"][0])
    loads = press.load_virtual_work_N_m()
    scale = press.bar_AB_m + press.bar_BC_m
    if abs(slider_coefficient) <= TOGGLE_TOLERANCE * scale:
        if abs(loads) <= TOGGLE_TOLERANCE * scale * (abs(press.load_B_N) + press.weight_AB_N + press.weight_BC_N):
            raise TogglePositionError(
                "θ (deg): at the toggle position (θ = 0°, bars in line) neither the loads nor Q do virtual work: "
                "the virtual-work equation holds for every Q, so it does not fix Q"
            )
        raise TogglePositionError(
            f"θ (deg): at θ = {math.degrees(press.angle_rad):g}° the bars lie in line (the toggle position): "
            "δx_C = 0 for "
            f"every δθ, so Q does no virtual work while the loads do {loads:.4g} N·m per rad; no finite Q holds them "
            "(the force needed grows like 1/θ as θ → 0)"
        )
    return loads / slider_coefficient


@dataclass(frozen=True)
class ToggleForces:
    """Member-by-member equilibrium (N): A ground on AB, B bar AB on bar BC, C_y the guide on BC (up), Q on C (along
    −x)."""

    pin_A_N: np.ndarray
    pin_B_N: np.ndarray
    guide_C_N: float
    holding_force_N: float


def toggle_equilibrium(press: TogglePress) -> ToggleForces:
    """Both bars' force and moment balances, ``K u = f`` for ``u = [A_x, A_y, B_x, B_y, C_y, Q]``, one linear solve.

    Bar AB (P applied at its end B, moments about A): ``A − B − P ŷ − W₁ ŷ = 0``,
    ``r_B × (−B − P ŷ) − r_G₁ × W₁ ŷ = 0``. Bar BC (moments about B):
    ``B + C_y ŷ − Q x̂ − W₂ ŷ = 0``, ``(r_C − r_B) × (−Q, C_y) − (r_G₂ − r_B) × W₂ ŷ = 0``.
    Refused (:class:`TogglePositionError`) at the toggle position, where the system is singular.
    """
    holding_force_by_virtual_work(press)  # the same refusal, with its reason, at the toggle position
    p = press.points()
    knee, to_c, to_g2 = p["B"], p["C"] - p["B"], p["G2"] - p["B"]
    K = np.array(
        [
            [1.0, 0.0, -1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, -1.0, 0.0, 0.0],
            [0.0, 0.0, knee[1], -knee[0], 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0, 0.0, -1.0],
            [0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, to_c[0], to_c[1]],
        ]
    )
    f = np.array(
        [
            0.0,
            press.load_B_N + press.weight_AB_N,
            press.load_B_N * knee[0] + press.weight_AB_N * p["G1"][0],
            0.0,
            press.weight_BC_N,
            press.weight_BC_N * to_g2[0],
        ]
    )
    u = np.linalg.solve(K, f)
    return ToggleForces(u[0:2], u[2:4], float(u[4]), float(u[5]))


# --- The slider-crank by dynamic virtual work --------------------------------------------------------------------


@dataclass(frozen=True)
class DynamicVirtualWork:
    """The slider-crank's virtual work per unit δθ at N instants; vectors (N, 2) in the mechanism frame.

    ``virtual_displacement_*``: r′(θ) (m/rad) of G₁, G₂ and B; ``rod_virtual_rotation``: φ′ (N,);
    ``inertia_force_*``: −m a (N); ``gravity_work_N_m`` = Σ m g·r′, ``inertia_work_N_m`` = Σ −m a·r′ − Σ I α φ′
    (N·m per rad, (N,)); ``driving_torque_N_m`` = −(both), the τ that makes δW vanish.
    """

    motion: kinetics.LinkMotion
    virtual_displacement_G1: np.ndarray
    virtual_displacement_G2: np.ndarray
    virtual_displacement_B: np.ndarray
    rod_virtual_rotation: np.ndarray
    inertia_force_G1_N: np.ndarray
    inertia_force_G2_N: np.ndarray
    inertia_force_B_N: np.ndarray
    gravity_work_N_m: np.ndarray
    inertia_work_N_m: np.ndarray

    @property
    def driving_torque_N_m(self) -> np.ndarray:
        return -(self.gravity_work_N_m + self.inertia_work_N_m)


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.sum(u * v, axis=-1)


def crank_inertia_about_centre_kg_m2(links: kinetics.SliderCrankLinks) -> float:
    """I_G₁ of the crank about its own centre, normal to the plane (kg·m²)."""
    return float(slender_rod(links.crank_mass_kg, links.mechanism.crank_m)[0, 0])


def dynamic_virtual_work(
    links: kinetics.SliderCrankLinks, theta: np.ndarray, omega: np.ndarray | float, alpha: np.ndarray | float
) -> DynamicVirtualWork:
    """Every term of ``τ δθ + Σ(F − m a)·δr − Σ I α δφ = 0`` per unit δθ at crank angles θ (rad), speeds ω (rad/s)
    and accelerations α (rad/s²), each (N,) or scalars broadcast to θ's shape.

    The kinematic coefficients r′ and φ′ are the chapter-4 rates at unit crank speed
    (:func:`~app.physics.systems.ch06.mechanism_kinetics.link_motion` with ω = 1, α = 0).
    """
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    motion = kinetics.link_motion(
        links, theta, np.broadcast_to(omega, theta.shape), np.broadcast_to(alpha, theta.shape)
    )
    unit = kinetics.link_motion(links, theta, np.ones_like(theta), np.zeros_like(theta))
    weight = np.array([0.0, -links.g_m_s2])
    m_c, m_r, m_s = links.crank_mass_kg, links.rod_mass_kg, links.slider_mass_kg
    d_g1, d_g2, d_b = unit.crank_centre_velocity, unit.rod_centre_velocity, unit.slider_velocity
    gravity = _dot(m_c * weight, d_g1) + _dot(m_r * weight, d_g2) + _dot(m_s * weight, d_b)
    inertia_g1 = -m_c * motion.crank_centre_acceleration
    inertia_g2 = -m_r * motion.rod_centre_acceleration
    inertia_b = -m_s * motion.slider_acceleration
    couples = (
        crank_inertia_about_centre_kg_m2(links) * motion.crank_acceleration_rad_s2
        + links.rod_inertia_about_centre_kg_m2 * motion.rod_acceleration * unit.rod_rate
    )
    inertia = _dot(inertia_g1, d_g1) + _dot(inertia_g2, d_g2) + _dot(inertia_b, d_b) - couples
    return DynamicVirtualWork(
        motion, d_g1, d_g2, d_b, unit.rod_rate, inertia_g1, inertia_g2, inertia_b, gravity, inertia
    )


def driving_torque_by_virtual_work(
    links: kinetics.SliderCrankLinks,
    theta: np.ndarray,
    omega: np.ndarray,
    *,
    crank_acceleration_rad_s2: np.ndarray | float = 0.0,
) -> np.ndarray:
    """τ (N·m, (N,)) that moves the crank at θ (rad), ω (rad/s) with acceleration α (rad/s², default 0: held speed)."""
    return dynamic_virtual_work(links, theta, omega, crank_acceleration_rad_s2).driving_torque_N_m


def crank_acceleration_by_virtual_work(
    links: kinetics.SliderCrankLinks, theta: np.ndarray, omega: np.ndarray, *, drive_torque_N_m: np.ndarray | float
) -> np.ndarray:
    """α (rad/s², (N,)) that a torque τ (N·m) gives the crank at θ (rad), ω (rad/s).

    Every acceleration is linear in α, so the virtual-work torque is ``τ(α) = τ(0) + M α``;
    the coefficient ``M = τ(1) − τ(0)`` (kg·m²) is the generalized inertia M(θ).
    """
    at_rest = driving_torque_by_virtual_work(links, theta, omega, crank_acceleration_rad_s2=0.0)
    inertia = driving_torque_by_virtual_work(links, theta, omega, crank_acceleration_rad_s2=1.0) - at_rest
    return (np.asarray(drive_torque_N_m, dtype=float) - at_rest) / inertia


@dataclass(frozen=True)
class ConstraintVirtualWork:
    """Virtual work per unit δθ (N·m per rad, (N,)) of each constraint force on the body it acts on, from
    Newton–Euler's forces: at O (δr_O = 0), the pair ∓A at the crank pin, the pair ∓B at the wrist pin, and
    the guide's N (normal to δr_B). Each pair cancels; ``total`` is their sum."""

    pivot_O: np.ndarray
    crank_pin_on_crank: np.ndarray
    crank_pin_on_rod: np.ndarray
    wrist_pin_on_rod: np.ndarray
    wrist_pin_on_slider: np.ndarray
    guide: np.ndarray

    @property
    def total(self) -> np.ndarray:
        return (
            self.pivot_O
            + self.crank_pin_on_crank
            + self.crank_pin_on_rod
            + self.wrist_pin_on_rod
            + self.wrist_pin_on_slider
            + self.guide
        )


def constraint_virtual_work(
    links: kinetics.SliderCrankLinks, theta: np.ndarray, forces: kinetics.PinForces
) -> ConstraintVirtualWork:
    """The virtual work of Newton–Euler's pin and guide ``forces`` at crank angles θ (rad, (N,)), per unit δθ."""
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    unit = kinetics.link_motion(links, theta, np.ones_like(theta), np.zeros_like(theta))
    d_a, d_b = 2.0 * unit.crank_centre_velocity, unit.slider_velocity
    guide = np.stack([np.zeros_like(forces.guide_force_N), forces.guide_force_N], axis=-1)
    return ConstraintVirtualWork(
        pivot_O=np.zeros_like(theta),  # O does not move
        crank_pin_on_crank=_dot(-forces.crank_pin_A_N, d_a),
        crank_pin_on_rod=_dot(forces.crank_pin_A_N, d_a),
        wrist_pin_on_rod=_dot(-forces.wrist_pin_B_N, d_b),
        wrist_pin_on_slider=_dot(forces.wrist_pin_B_N, d_b),
        guide=_dot(guide, d_b),
    )


def _crank_speed_held() -> Parameter:
    return replace(
        kinetics.PARAMETERS.by_name["crank_speed_rad_s"],
        description="Crank speed ω, held constant by the motor (counterclockwise positive)",
    )


PARAMETERS = ParameterSet(
    tuple(
        _crank_speed_held() if p.name == "crank_speed_rad_s" else p
        for p in kinetics.PARAMETERS.parameters
        if p.name not in ("drive", "drive_torque_N_m")
    ),
    check=kinetics.PARAMETERS.check,
)


def crank_drive(params: Mapping[str, Any]) -> CrankDrive:
    """The motor: θ = θ(0) + ω t (rad)."""
    return CrankDrive(math.radians(params["crank_angle0_deg"]), params["crank_speed_rad_s"])


class SliderCrankVirtualWork(ClosedFormModel):
    """The slider-crank at constant crank speed: its drive torque by dynamic virtual work and by Newton–Euler."""

    parameters = PARAMETERS
    series_units = {
        "crank_angle": "rad",
        "driving_torque_virtual_work_N_m": "N·m",
        "driving_torque_newton_euler_N_m": "N·m",
        "constraint_virtual_work_N_m": "N·m",
    }
    invariant_units = {"torque_difference": "N·m"}
    description = (
        "dynamic virtual work τ = Σ(m a − F)·r′ + Σ I α φ′ with the chapter-4 kinematic coefficients, "
        "against the 8×8 Newton–Euler solve"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        links = kinetics.SliderCrankLinks.from_params(params)
        drive = crank_drive(params)
        theta = drive.angle(np.asarray(t_s, dtype=float))
        omega = params["crank_speed_rad_s"]
        by_virtual_work = driving_torque_by_virtual_work(links, theta, omega)
        forces = kinetics.newton_euler(links, theta, omega, crank_acceleration_rad_s2=0.0)
        series = {
            "crank_angle": theta,
            "driving_torque_virtual_work_N_m": by_virtual_work,
            "driving_torque_newton_euler_N_m": forces.driving_torque_N_m,
            "constraint_virtual_work_N_m": constraint_virtual_work(links, theta, forces).total,
        }
        return ClosedFormSolution(series, {"torque_difference": by_virtual_work - forces.driving_torque_N_m})

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        """The largest |τ| over a turn (N·m), at least 1e-12."""
        links = kinetics.SliderCrankLinks.from_params(params)
        turn = np.linspace(0.0, 2.0 * math.pi, 73)
        return {
            "torque_difference": max(
                float(np.max(np.abs(driving_torque_by_virtual_work(links, turn, params["crank_speed_rad_s"])))), 1e-12
            )
        }
