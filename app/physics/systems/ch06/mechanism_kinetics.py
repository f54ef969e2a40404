"""Planar kinetics of the offset slider-crank: Newton–Euler per link, and the torque-driven motion.

Frame (planar, m), as in :mod:`app.physics.systems.ch04.slider_crank`: crank
pivot O at the origin, x along the slider's line y = e, y up; gravity ``g``
acts along −y. Crank OA (length r, angle θ), connecting rod AB (length l,
angle φ) and slider B. The links are uniform slender rods (centres of mass at
their midpoints G₁, G₂; inertias from :func:`app.physics.bodies.inertia.slender_rod`),
the slider a particle at B. The guide is frictionless and two-sided: its
force ``N`` on the slider is along y and may pull as well as push (guide
friction is out of scope).

Unknown forces (N), each acting on the link named second:

* ``O`` — ground on crank at the pivot O;
* ``A`` — crank on rod at the crank pin A (the rod pushes back with −A);
* ``B`` — rod on slider at the wrist pin B (the slider pushes back with −B);
* ``N`` — guide on slider, along y; and the driving torque ``τ`` (N·m, ccw) on the crank.

Eight unknowns, eight equations (crank: two forces and the moment about O;
rod: two forces and the moment about G₂; slider: two forces — it does not
turn), all linear in the unknowns once the motion is known: :func:`newton_euler`.
With the crank speed given (drive ``"speed"``) the crank acceleration is zero
and τ is an unknown; with τ given (drive ``"torque"``) the crank acceleration
takes τ's place among the unknowns, since every acceleration is linear in it.

The one-degree-of-freedom equation of motion (the generalized form): with
kinetic energy ``T = ½ M(θ) θ̇²`` and potential ``V(θ)``,
``M(θ) θ̈ + ½ M'(θ) θ̇² + V'(θ) = τ``. The compiled right-hand side
:func:`mechanism_rhs` integrates it, together with the torque's work
``W = ∫ τ θ̇ dt``, so that ``T + V − W`` stays at its initial value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from app.physics.bodies.inertia import parallel_axis, slender_rod
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import RHS_SIGNATURE, kernel
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch04 import slider_crank as kinematics
from app.physics.systems.earth import STANDARD_GRAVITY_M_S2

DRIVES = ("speed", "torque")
STATE_NAMES = ("crank_angle", "crank_speed", "torque_work")
#: The automatic step is chosen for the speed the drive torque can build up over this many turns.
TURNS_FOR_STEP_CHOICE = 10.0

_GEOMETRY = kinematics.PARAMETERS.by_name


def _check(values: Mapping[str, Any]) -> None:
    kinematics.SliderCrank(values["crank_m"], values["rod_m"], values["offset_m"])


PARAMETERS = ParameterSet(
    (
        Parameter(
            "drive",
            "",
            DRIVES[0],
            kind="choice",
            choices=DRIVES,
            label="drive",
            description="'speed': a motor holds the crank speed constant (the torque it needs is computed); "
            "'torque': a constant torque is applied and the motion follows from it",
        ),
        _GEOMETRY["crank_m"],
        _GEOMETRY["rod_m"],
        _GEOMETRY["offset_m"],
        replace(
            _GEOMETRY["crank_speed_rad_s"],
            default=10.0,
            description="Crank speed ω (counterclockwise positive): held constant by the 'speed' drive; "
            "the initial speed under the 'torque' drive",
        ),
        Parameter(
            "drive_torque_N_m",
            "N·m",
            2.0,
            -100.0,
            100.0,
            "Constant torque τ on the crank under the 'torque' drive (counterclockwise positive)",
            "τ",
            step=0.1,
        ),
        _GEOMETRY["crank_angle0_deg"],
        Parameter(
            "crank_mass_kg",
            "kg",
            1.0,
            0.01,
            100.0,
            "Mass of the crank (a uniform slender rod)",
            "crank mass",
            scale="log",
        ),
        Parameter(
            "rod_mass_kg",
            "kg",
            2.0,
            0.01,
            100.0,
            "Mass of the connecting rod (a uniform slender rod)",
            "rod mass",
            scale="log",
        ),
        Parameter(
            "slider_mass_kg",
            "kg",
            3.0,
            0.01,
            100.0,
            "Mass of the slider (a particle at the wrist pin B)",
            "slider mass",
            scale="log",
        ),
        Parameter(
            "g_m_s2",
            "m/s²",
            STANDARD_GRAVITY_M_S2,
            0.0,
            30.0,
            "Gravitational acceleration along −y (0: the mechanism lies in a horizontal plane)",
            "g",
            step=0.01,
        ),
    ),
    check=_check,
)


@dataclass(frozen=True)
class SliderCrankLinks:
    """The slider-crank's geometry with its link masses (kg) and gravity (m/s², along −y)."""

    mechanism: kinematics.SliderCrank
    crank_mass_kg: float
    rod_mass_kg: float
    slider_mass_kg: float
    g_m_s2: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> SliderCrankLinks:
        mechanism = kinematics.SliderCrank(params["crank_m"], params["rod_m"], params["offset_m"])
        return cls(
            mechanism, params["crank_mass_kg"], params["rod_mass_kg"], params["slider_mass_kg"], params["g_m_s2"]
        )

    @property
    def crank_inertia_about_pivot_kg_m2(self) -> float:
        """I_O of the crank about the pivot axis (normal to the plane), kg·m²: a rod's m r²/12 moved r/2."""
        r = self.mechanism.crank_m
        about_pivot = parallel_axis(
            slender_rod(self.crank_mass_kg, r), self.crank_mass_kg, np.array([0.0, 0.0, 0.5 * r])
        )
        return float(about_pivot[0, 0])

    @property
    def rod_inertia_about_centre_kg_m2(self) -> float:
        """I_G₂ of the connecting rod about its centre, normal to the plane (kg·m²)."""
        return float(slender_rod(self.rod_mass_kg, self.mechanism.rod_m)[0, 0])

    def kernel_parameters(self, *, drive: str, drive_torque_N_m: float) -> np.ndarray:
        """``p = [torque drive (0/1), r, l, e, m_crank, m_rod, m_slider, g, τ, I_O, I_G₂]`` for
        :func:`mechanism_rhs`."""
        mech = self.mechanism
        return np.array(
            [
                float(drive == "torque"),
                mech.crank_m,
                mech.rod_m,
                mech.offset_m,
                self.crank_mass_kg,
                self.rod_mass_kg,
                self.slider_mass_kg,
                self.g_m_s2,
                drive_torque_N_m,
                self.crank_inertia_about_pivot_kg_m2,
                self.rod_inertia_about_centre_kg_m2,
            ]
        )


@dataclass(frozen=True)
class LinkMotion:
    """Positions (m), velocities (m/s) and accelerations (m/s²) at N instants, arrays (N, 2) in the mechanism frame
    unless noted: pins A and B, link centres G₁ (crank) and G₂ (rod); rod angle, rate and acceleration (N,)."""

    crank_angle: np.ndarray
    crank_speed_rad_s: np.ndarray
    crank_acceleration_rad_s2: np.ndarray
    rod_angle: np.ndarray
    rod_rate: np.ndarray
    rod_acceleration: np.ndarray
    crank_pin: np.ndarray
    slider_pin: np.ndarray
    crank_centre: np.ndarray
    rod_centre: np.ndarray
    crank_centre_velocity: np.ndarray
    rod_centre_velocity: np.ndarray
    slider_velocity: np.ndarray
    crank_centre_acceleration: np.ndarray
    rod_centre_acceleration: np.ndarray
    slider_acceleration: np.ndarray


def _unit(angle: np.ndarray) -> np.ndarray:
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def _normal(angle: np.ndarray) -> np.ndarray:
    return np.stack([-np.sin(angle), np.cos(angle)], axis=-1)


def link_motion(
    links: SliderCrankLinks, theta: np.ndarray | float, omega: np.ndarray | float, alpha: np.ndarray | float
) -> LinkMotion:
    """Every link's motion from the crank's angle θ (rad), speed ω (rad/s) and acceleration α (rad/s²), each (N,),
    by the chapter-4 loop closure (:class:`~app.physics.systems.ch04.slider_crank.SliderCrank`)."""
    mech = links.mechanism
    r, l = mech.crank_m, mech.rod_m
    theta, omega, alpha = np.broadcast_arrays(
        *(np.atleast_1d(np.asarray(v, dtype=float)) for v in (theta, omega, alpha))
    )
    x, phi = mech.positions(theta)
    xdot, phidot = mech.rates(theta, phi, omega)
    xddot, phiddot = mech.accelerations(theta, phi, omega, phidot, alpha)
    along_crank, across_crank = _unit(theta), _normal(theta)
    along_rod, across_rod = _unit(phi), _normal(phi)
    crank_pin = r * along_crank
    pin_velocity = r * omega[:, None] * across_crank
    pin_acceleration = r * (alpha[:, None] * across_crank - (omega**2)[:, None] * along_crank)
    rod_centre_acceleration = pin_acceleration + 0.5 * l * (
        phiddot[:, None] * across_rod - (phidot**2)[:, None] * along_rod
    )
    zeros = np.zeros_like(x)
    return LinkMotion(
        crank_angle=theta,
        crank_speed_rad_s=omega,
        crank_acceleration_rad_s2=alpha,
        rod_angle=phi,
        rod_rate=phidot,
        rod_acceleration=phiddot,
        crank_pin=crank_pin,
        slider_pin=np.stack([x, np.full_like(x, mech.offset_m)], axis=-1),
        crank_centre=0.5 * crank_pin,
        rod_centre=crank_pin + 0.5 * l * along_rod,
        crank_centre_velocity=0.5 * pin_velocity,
        rod_centre_velocity=pin_velocity + 0.5 * l * phidot[:, None] * across_rod,
        slider_velocity=np.stack([xdot, zeros], axis=-1),
        crank_centre_acceleration=0.5 * pin_acceleration,
        rod_centre_acceleration=rod_centre_acceleration,
        slider_acceleration=np.stack([xddot, zeros], axis=-1),
    )


def kinetic_energy_J(links: SliderCrankLinks, motion: LinkMotion) -> np.ndarray:
    """T (J), shape (N,): crank about its fixed pivot, rod's translation of G₂ plus rotation, slider's translation."""
    return 0.5 * (
        links.crank_inertia_about_pivot_kg_m2 * motion.crank_speed_rad_s**2
        + links.rod_mass_kg * np.sum(motion.rod_centre_velocity**2, axis=-1)
        + links.rod_inertia_about_centre_kg_m2 * motion.rod_rate**2
        + links.slider_mass_kg * np.sum(motion.slider_velocity**2, axis=-1)
    )


def rotational_kinetic_J(links: SliderCrankLinks, motion: LinkMotion) -> np.ndarray:
    """½ I_G ω² summed over the crank and the rod (J), shape (N,): the slider does not turn. The rest of
    :func:`kinetic_energy_J` is the links' translation, ½ m v_G²."""
    crank_about_centre = float(slender_rod(links.crank_mass_kg, links.mechanism.crank_m)[0, 0])
    return 0.5 * (
        crank_about_centre * motion.crank_speed_rad_s**2 + links.rod_inertia_about_centre_kg_m2 * motion.rod_rate**2
    )


def potential_energy_J(links: SliderCrankLinks, motion: LinkMotion) -> np.ndarray:
    """V (J), shape (N,): gravity, zero at y = 0 (the crank pivot's height)."""
    heights = (
        links.crank_mass_kg * motion.crank_centre[:, 1]
        + links.rod_mass_kg * motion.rod_centre[:, 1]
        + links.slider_mass_kg * motion.slider_pin[:, 1]
    )
    return links.g_m_s2 * heights


def generalized_inertia_kg_m2(links: SliderCrankLinks, theta: np.ndarray | float) -> np.ndarray:
    """M(θ) = 2T/θ̇² (kg·m²), shape (N,): the inertia the crank feels, from the kinetic energy at unit crank speed."""
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    motion = link_motion(links, theta, np.ones_like(theta), np.zeros_like(theta))
    return 2.0 * kinetic_energy_J(links, motion)


@dataclass(frozen=True)
class PinForces:
    """Newton–Euler's answer at N instants: pin forces (N, 2) in N (see the module docstring for who acts on
    whom), the guide's normal force (N,) in N along +y, the driving torque (N,) in N·m and the crank
    acceleration (N,) in rad/s² (given or found)."""

    pivot_O_N: np.ndarray
    crank_pin_A_N: np.ndarray
    wrist_pin_B_N: np.ndarray
    guide_force_N: np.ndarray
    driving_torque_N_m: np.ndarray
    crank_acceleration_rad_s2: np.ndarray


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z component of a × b for arrays (..., 2)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _balance(links: SliderCrankLinks, motion: LinkMotion) -> tuple[np.ndarray, np.ndarray]:
    """The eight Newton–Euler equations ``K u = f`` for ``u = [O_x, O_y, A_x, A_y, B_x, B_y, N, τ]``:
    K (N, 8, 8), f (N, 8). Rows: crank x, y, moment about O; rod x, y, moment about G₂; slider x, y."""
    n = motion.crank_angle.shape[0]
    m_c, m_r, m_s, g = links.crank_mass_kg, links.rod_mass_kg, links.slider_mass_kg, links.g_m_s2
    weight = np.array([0.0, -g])
    K = np.zeros((n, 8, 8))
    f = np.zeros((n, 8))
    a_pin, g2 = motion.crank_pin, motion.rod_centre
    # Crank: O − A + m_c g = m_c a_G1;  τ + r_A × (−A) + r_G1 × m_c g = I_O α.
    K[:, 0, 0], K[:, 0, 2] = 1.0, -1.0
    K[:, 1, 1], K[:, 1, 3] = 1.0, -1.0
    f[:, 0:2] = m_c * (motion.crank_centre_acceleration - weight)
    K[:, 2, 2], K[:, 2, 3], K[:, 2, 7] = a_pin[:, 1], -a_pin[:, 0], 1.0
    f[:, 2] = links.crank_inertia_about_pivot_kg_m2 * motion.crank_acceleration_rad_s2 - _cross(
        motion.crank_centre, m_c * weight
    )
    # Rod: A − B + m_r g = m_r a_G2;  (r_A − r_G2) × A + (r_B − r_G2) × (−B) = I_G2 φ̈.
    K[:, 3, 2], K[:, 3, 4] = 1.0, -1.0
    K[:, 4, 3], K[:, 4, 5] = 1.0, -1.0
    f[:, 3:5] = m_r * (motion.rod_centre_acceleration - weight)
    to_a, to_b = a_pin - g2, motion.slider_pin - g2
    K[:, 5, 2], K[:, 5, 3] = -to_a[:, 1], to_a[:, 0]
    K[:, 5, 4], K[:, 5, 5] = to_b[:, 1], -to_b[:, 0]
    f[:, 5] = links.rod_inertia_about_centre_kg_m2 * motion.rod_acceleration
    # Slider: B + N ŷ + m_s g = m_s a_B.
    K[:, 6, 4] = 1.0
    K[:, 7, 5], K[:, 7, 6] = 1.0, 1.0
    f[:, 6:8] = m_s * (motion.slider_acceleration - weight)
    return K, f


def newton_euler(
    links: SliderCrankLinks,
    theta: np.ndarray,
    omega: np.ndarray,
    *,
    crank_acceleration_rad_s2: np.ndarray | float | None = None,
    drive_torque_N_m: np.ndarray | None = None,
) -> PinForces:
    """Pin forces, guide force and the torque or the crank acceleration, by one 8×8 linear solve per instant.

    θ (rad) and ω (rad/s) are arrays (N,). Give exactly one of the crank
    acceleration α (rad/s²; then τ is found: inverse dynamics) or the torque τ
    (N·m; then α is found: forward dynamics). Every acceleration is linear in
    α, so in the forward case the τ column of the system is replaced by the
    column of α: the equations evaluated at α = 1 minus those at α = 0.
    """
    if (crank_acceleration_rad_s2 is None) == (drive_torque_N_m is None):
        raise ValueError("newton_euler: give exactly one of crank_acceleration_rad_s2 and drive_torque_N_m")
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    omega = np.broadcast_to(np.asarray(omega, dtype=float), theta.shape)
    if crank_acceleration_rad_s2 is not None:
        alpha = np.broadcast_to(np.asarray(crank_acceleration_rad_s2, dtype=float), theta.shape)
        K, f = _balance(links, link_motion(links, theta, omega, alpha))
        u = np.linalg.solve(K, f[..., None])[..., 0]
        torque = u[:, 7]
    else:
        torque = np.broadcast_to(np.asarray(drive_torque_N_m, dtype=float), theta.shape)
        K, f0 = _balance(links, link_motion(links, theta, omega, np.zeros_like(theta)))
        _, f1 = _balance(links, link_motion(links, theta, omega, np.ones_like(theta)))
        K[:, :, 7] = -(f1 - f0)  # α's coefficients, moved to the left-hand side
        f0[:, 2] -= torque
        u = np.linalg.solve(K, f0[..., None])[..., 0]
        alpha = u[:, 7]
    return PinForces(
        u[:, 0:2], u[:, 2:4], u[:, 4:6], u[:, 6], np.array(torque, dtype=float), np.array(alpha, dtype=float)
    )


@kernel(RHS_SIGNATURE)
def mechanism_rhs(t, y, p, dydt):
    """``[θ̇, θ̈, Ẇ]`` for ``y = [θ (rad), θ̇ (rad/s), W (J)]`` and ``p`` of :meth:`SliderCrankLinks.kernel_parameters`.

    Kinematic coefficients (derivatives with respect to θ, written ′) from the
    loop ``l sin φ = e − r sin θ``: ``φ′ = −r cos θ / (l cos φ)``,
    ``φ″ = (r sin θ + l sin φ φ′²) / (l cos φ)``, ``x′ = −r sin θ − l sin φ φ′``,
    ``x″ = −r cos θ − l cos φ φ′² − l sin φ φ″``; G₂ = A + ½ l (cos φ, sin φ).
    Then ``M = I_O + m_r|G₂′|² + I_G φ′² + m_s x′²``,
    ``½M′ = m_r G₂′·G₂″ + I_G φ′φ″ + m_s x′x″`` and ``V′ = g(m_c ½ r cos θ + m_r G₂y′)``.
    Torque drive: ``θ̈ = (τ − ½M′θ̇² − V′)/M``. Speed drive: ``θ̈ = 0`` and the
    motor's torque is ``τ = ½M′θ̇² + V′``. Either way ``Ẇ = τ θ̇``.
    """
    torque_drive, r, l, e = p[0], p[1], p[2], p[3]
    m_c, m_r, m_s, g, applied, inertia_o, inertia_g = p[4], p[5], p[6], p[7], p[8], p[9], p[10]
    theta, omega = y[0], y[1]
    sin_t, cos_t = math.sin(theta), math.cos(theta)
    sin_p = (e - r * sin_t) / l
    cos_p = math.sqrt(1.0 - sin_p * sin_p)
    phi1 = -r * cos_t / (l * cos_p)
    phi2 = (r * sin_t + l * sin_p * phi1 * phi1) / (l * cos_p)
    x1 = -r * sin_t - l * sin_p * phi1
    x2 = -r * cos_t - l * cos_p * phi1 * phi1 - l * sin_p * phi2
    gx1 = -r * sin_t - 0.5 * l * sin_p * phi1
    gy1 = r * cos_t + 0.5 * l * cos_p * phi1
    gx2 = -r * cos_t - 0.5 * l * (cos_p * phi1 * phi1 + sin_p * phi2)
    gy2 = -r * sin_t + 0.5 * l * (cos_p * phi2 - sin_p * phi1 * phi1)
    inertia = inertia_o + m_r * (gx1 * gx1 + gy1 * gy1) + inertia_g * phi1 * phi1 + m_s * x1 * x1
    half_slope = m_r * (gx1 * gx2 + gy1 * gy2) + inertia_g * phi1 * phi2 + m_s * x1 * x2
    potential_slope = g * (0.5 * m_c * r * cos_t + m_r * gy1)
    dydt[0] = omega
    if torque_drive > 0.5:
        dydt[1] = (applied - half_slope * omega * omega - potential_slope) / inertia
        dydt[2] = applied * omega
    else:
        dydt[1] = 0.0
        dydt[2] = (half_slope * omega * omega + potential_slope) * omega


def speed_limit_rad_s(params: Mapping[str, Any]) -> float:
    """Highest crank speed the automatic step is chosen for (rad/s).

    Speed drive: twice the held speed (never reached). Torque drive: with no
    friction a constant torque speeds the crank up without limit, so the limit
    is the speed reached, where M(θ) is least, once the torque has worked for
    :data:`TURNS_FOR_STEP_CHOICE` turns on top of the energy in play; a live
    scene pauses there, and a longer run's accuracy shows in its drift.
    """
    speed = abs(params["crank_speed_rad_s"])
    if params["drive"] != "torque":
        return 2.0 * speed + 1.0
    links = SliderCrankLinks.from_params(params)
    least_inertia = float(np.min(generalized_inertia_kg_m2(links, np.linspace(0.0, 2.0 * math.pi, 73))))
    energy = energy_scale_J(params) + 2.0 * math.pi * TURNS_FOR_STEP_CHOICE * abs(params["drive_torque_N_m"])
    return max(math.sqrt(2.0 * energy / least_inertia), 2.0 * speed + 1.0)


def energy_scale_J(params: Mapping[str, Any]) -> float:
    """Energy in play (J): the initial kinetic energy, the potential's range over a turn and one turn of the torque's
    work."""
    links = SliderCrankLinks.from_params(params)
    theta = np.linspace(0.0, 2.0 * math.pi, 73)
    potential = potential_energy_J(links, link_motion(links, theta, np.zeros_like(theta), np.zeros_like(theta)))
    theta0 = math.radians(params["crank_angle0_deg"])
    kinetic0 = 0.5 * float(generalized_inertia_kg_m2(links, theta0)[0]) * params["crank_speed_rad_s"] ** 2
    turn_of_work = 2.0 * math.pi * abs(params["drive_torque_N_m"]) if params["drive"] == "torque" else 0.0
    return max(kinetic0 + float(np.ptp(potential)) + turn_of_work, 1e-12)


class MechanismKinetics(IntegratedModel):
    """The slider-crank with link masses, driven at constant crank speed or by a constant torque."""

    parameters = PARAMETERS
    methods = ("rk4", "dopri5")
    default_method = "rk4"
    series_units = {
        "crank_angle": "rad",
        "crank_speed_rad_s": "rad/s",
        "driving_torque_N_m": "N·m",
        "pin_force_O_N": "N",
        "pin_force_A_N": "N",
        "pin_force_B_N": "N",
        "guide_force_N": "N",
        "kinetic_energy_J": "J",
        "work_energy_residual_J": "J",
    }
    invariant_units = {"work_energy_residual": "J"}
    #: 1e-8, not 1e-6: the lesson checks the work–energy balance (motor work = ΔT + ΔV) to 1e-8 of the energy scale.
    accuracy_target = AccuracyTarget(
        1e-8, "", "crank angle per turn, crank speed per the speed scale, motor work per the energy scale: the largest"
    )
    auto_methods = ("rk4",)  # the simulate contract answers with RK4; the target sets its step

    def solution_error(self, params: Mapping[str, Any], states: np.ndarray, reference: np.ndarray) -> np.ndarray:
        """(N,) largest of |Δθ|/2π, |Δω|/ω_scale and |ΔW|/E_scale between ``states`` and ``reference`` (N, 3),
        dimensionless."""
        difference = np.abs(np.asarray(states, dtype=float) - np.asarray(reference, dtype=float))
        scales = np.array([2.0 * math.pi, max(speed_limit_rad_s(params), 1e-12), energy_scale_J(params)])
        return np.max(difference / scales, axis=1)

    def system(self, params: Mapping[str, Any]) -> OdeSystem:
        links = SliderCrankLinks.from_params(params)
        p = links.kernel_parameters(drive=params["drive"], drive_torque_N_m=params["drive_torque_N_m"])
        return OdeSystem(rhs=mechanism_rhs, parameters=p, state_names=STATE_NAMES)

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.array([math.radians(params["crank_angle0_deg"]), params["crank_speed_rad_s"], 0.0])

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The highest crank speed of the run times how sharply M(θ) changes, √(M_max/M_min), at least 2 (rad/s).

        The kinematic coefficients carry a second harmonic of θ; a heavy slider
        also makes M(θ) dip steeply at the dead centres, over a crank arc of
        about √(M_min/M_max) rad, which the crank crosses that much faster.
        """
        links = SliderCrankLinks.from_params(params)
        inertia = generalized_inertia_kg_m2(links, np.linspace(0.0, 2.0 * math.pi, 145))
        sharpness = max(2.0, math.sqrt(float(np.max(inertia) / np.min(inertia))))
        return sharpness * max(speed_limit_rad_s(params), abs(float(state[1])))

    def forces(self, params: Mapping[str, Any], states: np.ndarray) -> PinForces:
        """Newton–Euler at states (N, 3): inverse dynamics (α = 0) for the speed drive, forward for the torque drive."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        links = SliderCrankLinks.from_params(params)
        if params["drive"] == "torque":
            return newton_euler(links, states[:, 0], states[:, 1], drive_torque_N_m=params["drive_torque_N_m"])
        return newton_euler(links, states[:, 0], states[:, 1], crank_acceleration_rad_s2=0.0)

    def energies(self, params: Mapping[str, Any], states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Kinetic and potential energy (J) at states (N, 3), shapes (N,)."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        links = SliderCrankLinks.from_params(params)
        motion = link_motion(links, states[:, 0], states[:, 1], np.zeros(states.shape[0]))
        return kinetic_energy_J(links, motion), potential_energy_J(links, motion)

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        forces = self.forces(params, states)
        kinetic, _ = self.energies(params, states)
        return {
            "crank_angle": states[:, 0].copy(),
            "crank_speed_rad_s": states[:, 1].copy(),
            "driving_torque_N_m": forces.driving_torque_N_m,
            "pin_force_O_N": np.linalg.norm(forces.pivot_O_N, axis=-1),
            "pin_force_A_N": np.linalg.norm(forces.crank_pin_A_N, axis=-1),
            "pin_force_B_N": np.linalg.norm(forces.wrist_pin_B_N, axis=-1),
            "guide_force_N": forces.guide_force_N,
            "kinetic_energy_J": kinetic,
            "work_energy_residual_J": self.invariants(params, states)["work_energy_residual"],
        }

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """The work–energy residual ``(T + V) − (T₀ + V₀) − W`` (J), shape (N,): zero when the torque's work
        accounts for the change of energy (W starts at 0)."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        kinetic, potential = self.energies(params, states)
        kinetic0, potential0 = self.energies(params, self.initial_state(params))
        return {"work_energy_residual": kinetic + potential - states[:, 2] - (kinetic0[0] + potential0[0])}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        return {"work_energy_residual": energy_scale_J(params)}

    series_labels = {
        "crank_angle": "θ",
        "crank_speed_rad_s": "ω (crank)",
        "driving_torque_N_m": "τ",
        "pin_force_O_N": "|O|",
        "pin_force_A_N": "|A|",
        "pin_force_B_N": "|B|",
        "guide_force_N": "N (guide)",
        "kinetic_energy_J": "T",
        "work_energy_residual_J": "T + V − T₀ − V₀ − W",
        "work_energy_residual": "T + V − T₀ − V₀ − W",
    }

    def energy_parts(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> EnergyParts:
        """Translation of G₁, G₂ and the slider, rotation of crank and rod, gravity; the motor's work W is the
        drive's (tracked in the state for either drive)."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        links = SliderCrankLinks.from_params(params)
        motion = link_motion(links, states[:, 0], states[:, 1], np.zeros(states.shape[0]))
        kinetic, rotational = kinetic_energy_J(links, motion), rotational_kinetic_J(links, motion)
        return EnergyParts(
            potential_energy_J(links, motion),
            translational_kinetic_J=kinetic - rotational,
            rotational_kinetic_J=rotational,
            drive_work_J=states[:, 2].copy(),
        )
