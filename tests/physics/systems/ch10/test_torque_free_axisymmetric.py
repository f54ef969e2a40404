"""The torque-free axisymmetric body's closed form against an independent integration and the conservation laws.

The reference integrates Euler's equations and the quaternion kinematics with
scipy's DOP853 at rtol = atol = 1e-12, from an initial state built here from
the definitions alone (L along +Z, body axis tilted θ about X, L_body = I ω),
with its own quaternion algebra and its own elementary rotation matrices, so it
shares no formula with the model.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch10 import torque_free_axisymmetric as physics

# (I_transverse, I_axial, spin_rad_s, nutation_deg): prolate, slender prolate, oblate coin,
# slightly oblate near-sphere, and the flat-disc limit I_a = 2 I_t.
CASES = {
    "football": (1.0, 0.4, 3.0, 25.0),
    "tumbling-rod": (2.0, 0.1, 4.0, 65.0),
    "coin": (0.5, 0.99, 1.0, 15.0),
    "near-sphere": (0.95, 1.0, 2.0, 20.0),
    "flat-disc-limit": (0.5, 1.0, 1.5, 40.0),
}


def params_of(case: tuple[float, float, float, float]) -> dict[str, float]:
    I_t, I_a, spin, nutation = case
    return {"I_transverse": I_t, "I_axial": I_a, "spin_rad_s": spin, "nutation_deg": nutation}


def _rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _matrix_of_quaternion(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _free_body_rhs(_t: float, y: np.ndarray, inertia: np.ndarray) -> np.ndarray:
    """q̇ = ½ q ⊗ (0, ω) and Euler's equations I ω̇ = (I ω) × ω, body axes."""
    w, x, yq, z = y[:4]
    ox, oy, oz = omega = y[4:]
    q_dot = 0.5 * np.array([-x * ox - yq * oy - z * oz, w * ox + yq * oz - z * oy, w * oy - x * oz + z * ox, w * oz + x * oy - yq * ox])
    omega_dot = np.cross(inertia * omega, omega) / inertia
    return np.concatenate([q_dot, omega_dot])


def reference_run(case, t_s: np.ndarray):
    """Attitude matrices (N, 3, 3) and body ω (N, 3) from the tight DOP853 integration."""
    I_t, I_a, spin, nutation = case
    theta = math.radians(nutation)
    inertia = np.array([I_t, I_t, I_a])
    L = I_a * spin / math.cos(theta)  # defines |L| from ω3 = L·k / I_a
    L_body = L * (_rx(theta).T @ np.array([0.0, 0.0, 1.0]))  # L = +Z in the world, body tilted by Rx(θ)
    y0 = np.concatenate([[math.cos(theta / 2), math.sin(theta / 2), 0.0, 0.0], L_body / inertia])
    sol = solve_ivp(_free_body_rhs, (0.0, t_s[-1]), y0, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t_s, args=(inertia,))
    assert sol.success
    return np.array([_matrix_of_quaternion(q) for q in sol.y[:4].T]), sol.y[4:].T


@pytest.mark.parametrize("name", CASES)
def test_closed_form_matches_tight_integration_over_twenty_precession_periods(name):
    case = CASES[name]
    motion = physics.motion_from_params(params_of(case))
    t_s = np.linspace(0.0, 20.0 * motion.precession_period_s, 2001)
    R_ref, omega_ref = reference_run(case, t_s)

    series = physics.TorqueFreeAxisymmetric().evaluate(params_of(case), t_s).series
    phi, theta, psi = series["phi"], series["theta"], series["psi"]
    R_closed = np.array([_rz(a) @ _rx(b) @ _rz(c) for a, b, c in zip(phi, theta, psi)])

    # The reference's global error grows with the phase it accumulates (up to ~1000 rad here);
    # measured: 1.3e-13 (coin) to 2.5e-12 (tumbling rod) per radian of phase. Allow 1e-11 per
    # radian. A wrong sign or rate in φ̇ or ψ̇ gives errors of order 1.
    phase_rad = max(abs(phi[-1]), abs(psi[-1]), 100.0)
    tolerance = 1e-11 * phase_rad
    assert np.max(np.abs(R_closed - R_ref)) < tolerance

    # The same comparison as 3-1-3 angles read off the reference matrices (θ ≥ 15° here, so well defined).
    theta_ref = np.arctan2(np.hypot(R_ref[:, 2, 0], R_ref[:, 2, 1]), R_ref[:, 2, 2])
    phi_ref = np.arctan2(R_ref[:, 0, 2], -R_ref[:, 1, 2])
    psi_ref = np.arctan2(R_ref[:, 2, 0], R_ref[:, 2, 1])
    wrapped = lambda a: np.abs(np.arctan2(np.sin(a), np.cos(a)))  # noqa: E731
    assert np.max(np.abs(theta - theta_ref)) < tolerance
    assert np.max(wrapped(phi - phi_ref)) < tolerance / math.sin(theta[0])  # φ, ψ are read through sin θ
    assert np.max(wrapped(psi - psi_ref)) < tolerance / math.sin(theta[0])

    # Body-axis ω from the closed form, against the reference's (rad/s, relative to |ω|).
    assert np.max(np.abs(motion.angular_velocity_body_rad_s(t_s) - omega_ref)) < tolerance * motion.angular_speed_rad_s


@pytest.mark.parametrize("name", CASES)
def test_angular_momentum_stays_on_Z_and_energy_stays_constant(name):
    case = CASES[name]
    motion = physics.motion_from_params(params_of(case))
    t_s = np.linspace(0.0, 500.0, 5001)
    phi, theta, psi = motion.euler_angles_313(t_s)
    omega_body = motion.angular_velocity_body_rad_s(t_s)
    inertia = np.array([case[0], case[0], case[1]])
    L_world = np.array([_rz(a) @ _rx(b) @ _rz(c) @ (inertia * w) for a, b, c, w in zip(phi, theta, psi, omega_body)])
    L = motion.angular_momentum_kg_m2_s
    # Round-off only (the matrices and ω use the same angles, so large φ costs nothing):
    # measured ≤ 2.4e-16 |L| and ≤ 3.3e-16 relative for T and |L|; allow 1e-14 (about 50 ulp).
    assert np.max(np.abs(L_world - [0.0, 0.0, L])) < 1e-14 * L
    solution = physics.TorqueFreeAxisymmetric().evaluate(params_of(case), t_s)
    energy, momentum = solution.invariants["energy"], solution.invariants["angular_momentum"]
    assert np.max(np.abs(energy - motion.energy_J)) < 1e-14 * motion.energy_J
    assert np.max(np.abs(momentum - L)) < 1e-14 * L
    # T = ½ ω·L, with ω = φ̇ K + ψ̇ k and L = L K, is ½ L (φ̇ + ψ̇ cos θ): an independent form.
    assert motion.energy_J == pytest.approx(0.5 * L * (motion.precession_rate_rad_s + motion.spin_rate_rad_s * math.cos(theta[0])), rel=1e-14)


def test_rates_of_the_default_prolate_body_by_hand():
    # I_t = 1, I_a = 0.4 kg·m², ω3 = 3 rad/s, θ = 25°.
    motion = physics.motion_from_params(physics.PARAMETERS.defaults())
    c = math.cos(math.radians(25.0))
    assert motion.angular_momentum_kg_m2_s == pytest.approx(1.2 / c, rel=1e-15)
    assert motion.precession_rate_rad_s == pytest.approx(1.2 / c, rel=1e-15)
    assert motion.spin_rate_rad_s == pytest.approx(1.8, rel=1e-15)
    assert motion.body_frame_precession_rate_rad_s == pytest.approx(-1.8, rel=1e-15)
    assert motion.sense == "direct"


@pytest.mark.parametrize("name", CASES)
def test_cone_geometry(name):
    motion = physics.motion_from_params(params_of(CASES[name]))
    theta, beta, gamma = motion.nutation_rad, motion.body_cone_half_angle_rad, motion.space_cone_half_angle_rad
    assert math.tan(beta) == pytest.approx(motion.inertia_ratio * math.tan(theta), rel=1e-13)
    # ω lies between L and k for a prolate body (cones touch outside), beyond L for an oblate one.
    if motion.sense == "direct":
        assert beta < theta and gamma + beta == pytest.approx(theta, rel=1e-13)
        assert motion.precession_rate_rad_s > 0 and motion.spin_rate_rad_s > 0
    else:
        assert beta > theta and beta - gamma == pytest.approx(theta, rel=1e-13)
        assert motion.precession_rate_rad_s > 0 and motion.spin_rate_rad_s < 0
    # ω = φ̇ K + ψ̇ k on the nodal frame makes angle γ with K and β with k, and has the stated magnitude.
    omega = motion.angular_velocity_nodal_rad_s()
    k = motion.symmetry_axis_nodal()
    assert np.linalg.norm(omega) == pytest.approx(motion.angular_speed_rad_s, rel=1e-14)
    assert math.atan2(np.linalg.norm(omega[:2]), omega[2]) == pytest.approx(gamma, rel=1e-12)
    assert math.atan2(np.linalg.norm(np.cross(omega, k)), omega @ k) == pytest.approx(beta, rel=1e-12)
    # ω·k = ω3 (the spin input).
    assert omega @ k == pytest.approx(motion.spin_rad_s, rel=1e-14)


def test_ratio_cases_sphere_flat_disc_and_no_nutation():
    sphere = physics.motion_from_params({"I_transverse": 1.0, "I_axial": 1.0, "spin_rad_s": 2.0, "nutation_deg": 30.0})
    assert sphere.sense == "none" and sphere.spin_rate_rad_s == 0.0 and sphere.space_cone_half_angle_rad == 0.0
    assert sphere.body_cone_half_angle_rad == pytest.approx(math.radians(30.0), rel=1e-14)  # ω along L
    assert sphere.precession_rate_rad_s == pytest.approx(sphere.angular_speed_rad_s, rel=1e-14)

    disc = physics.motion_from_params({"I_transverse": 0.5, "I_axial": 1.0, "spin_rad_s": 1.5, "nutation_deg": 40.0})
    assert disc.spin_rate_rad_s == pytest.approx(-1.5, rel=1e-15)  # ψ̇ = −ω3 for a flat disc
    assert disc.precession_rate_rad_s == pytest.approx(3.0 / math.cos(math.radians(40.0)), rel=1e-15)
    assert disc.sense == "retrograde"

    upright = physics.motion_from_params({"I_transverse": 1.0, "I_axial": 0.4, "spin_rad_s": 3.0, "nutation_deg": 0.0})
    assert upright.body_cone_half_angle_rad == 0.0 and upright.space_cone_half_angle_rad == 0.0
    # With θ = 0 only φ + ψ is seen: the body turns about L at ω3.
    assert upright.precession_rate_rad_s + upright.spin_rate_rad_s == pytest.approx(3.0, rel=1e-15)

    # Nearly spherical: γ tiny but to full relative precision (no θ − β cancellation).
    nearly = physics.motion_from_params({"I_transverse": 1.0, "I_axial": 1.0 + 1e-9, "spin_rad_s": 1.0, "nutation_deg": 30.0})
    omega = nearly.angular_velocity_nodal_rad_s()
    assert nearly.space_cone_half_angle_rad == pytest.approx(math.atan2(abs(omega[1]), omega[2]), rel=1e-9)
    assert nearly.space_cone_half_angle_rad == pytest.approx(1e-9 * math.sin(math.radians(30.0)) * math.cos(math.radians(30.0)), rel=1e-6)


@pytest.mark.parametrize("ratio, aspect", [(0.4, 2.0), (1.0, 1.0), (2.0, 0.0), (0.1, math.sqrt(19.0))])
def test_spheroid_aspect_ratio_matches_the_spheroids_inertia_by_quadrature(ratio, aspect):
    assert physics.spheroid_aspect_ratio(ratio) == pytest.approx(aspect, rel=1e-14, abs=1e-15)
    if aspect == 0.0:
        return
    # Uniform spheroid, b = 1, a = aspect, sliced into discs of radius r(z) = √(1 − z²/a²):
    # dI_axial = ½ r⁴ dz·π, dI_transverse = (¼ r⁴ + z² r²) dz·π (density π-free: only the ratio matters).
    a = aspect
    r2 = lambda z: 1.0 - (z / a) ** 2  # noqa: E731
    axial = quad(lambda z: 0.5 * r2(z) ** 2, -a, a, epsabs=0, epsrel=1e-13)[0]
    transverse = quad(lambda z: 0.25 * r2(z) ** 2 + z * z * r2(z), -a, a, epsabs=0, epsrel=1e-13)[0]
    assert axial / transverse == pytest.approx(ratio, rel=1e-12)


@pytest.mark.parametrize(
    "values, field, words",
    [
        ({"I_transverse": 1.0, "I_axial": 2.5}, "I_axial", "triangle inequality"),
        ({"spin_rad_s": 0.0}, "spin_rad_s", "must not be zero"),
        ({"spin_rad_s": -2.0}, "spin_rad_s", "must be positive"),
        ({"nutation_deg": 90.0}, "nutation_deg", "between"),
        ({"I_transverse": float("nan")}, "I_transverse", "finite"),
        ({"I_axial": 0.0}, "I_axial", "between"),
    ],
)
def test_impossible_inputs_are_refused_with_a_reason(values, field, words):
    with pytest.raises(ParameterError) as info:
        physics.PARAMETERS.validate(values)
    assert info.value.field == field and words in str(info.value)


def test_the_limits_themselves_are_accepted():
    physics.PARAMETERS.validate({"I_transverse": 1.0, "I_axial": 2.0})  # flat disc
    physics.PARAMETERS.validate({"nutation_deg": physics.MAX_NUTATION_DEG})
    with pytest.raises(ParameterError):
        physics.AxisymmetricFreeMotion(I_transverse_kg_m2=1.0, I_axial_kg_m2=0.4, spin_rad_s=1.0, nutation_rad=math.radians(90.0))


@pytest.mark.parametrize("name", CASES)
def test_nodal_and_body_quaternions_compose_to_the_3_1_3_attitude(name):
    # The scene's two per-frame orientations: Rz(φ) and Rx(θ)Rz(ψ). Their product must be the
    # attitude built by the general rotation-sequence code, at small and very large times
    # (the half-angles are reduced modulo 4π, which must not change the rotation).
    from app.physics.math.rotations import quaternion_from_euler_313, quaternion_multiply

    motion = physics.motion_from_params(params_of(CASES[name]))
    for t_s in (0.0, 0.37, 12.5, 1234.5, 9.87e5):
        q_nodal, q_body = motion.nodal_and_body_quaternions(t_s)
        drawn = quaternion_multiply(np.array(q_nodal), np.array(q_body))
        phi, theta, psi = (float(a) for a in motion.euler_angles_313(t_s))
        expected = quaternion_from_euler_313(phi, theta, psi)
        # Same rotation up to the quaternion's sign; angles up to ~4e6 rad carry ~1e-9 rad of rounding.
        assert min(np.abs(drawn - expected).max(), np.abs(drawn + expected).max()) < 1e-15 * max(1.0, abs(phi), abs(psi)) * 4
        assert _matrix_of_quaternion(drawn) @ np.array([0.0, 0.0, 1.0]) == pytest.approx(
            _rz(phi) @ _rx(theta) @ np.array([0.0, 0.0, 1.0]), abs=1e-14 * max(1.0, abs(phi)) * 4
        )
