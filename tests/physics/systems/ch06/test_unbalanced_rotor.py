"""The unbalanced rotor against hand-derived reactions, a particle model of the disk, and the two-plane balance.

Hand derivations (written here, independently of the model code). Rotor at constant ω about the shaft X,
bearings A (x = 0) and B (x = L), disk of mass m and radius r at x = a, gravity g along −Z.

* Pure static imbalance (skew 0, eccentricity e): the disk's centre G runs on a circle of radius e, so the
  shaft must supply m a_G = −m e ω² û(φ) (û: from the axis to G) plus m g Ẑ to hold up the weight. The skew-0
  disk's principal axis is parallel to the shaft, so there is no couple about G: the total is shared like a
  beam load at x = a, (L − a)/L at A and a/L at B. With û = (0, cos φ, sin φ) (G level with the shaft on +Y
  at φ = 0, the model's stated frame):
  |R_A| = (L − a)/L · √((m e ω²)² + (m g)² − 2 m e ω² m g sin φ), and likewise a/L at B.
  Gravity's moment about the shaft is −m g e cos φ, so the drive supplies T = m g e cos φ (zero on average).
* Pure dynamic imbalance (e = 0, skew β): with I_a = m r²/2 (axial) and I_d = m r²/4 (diametral), the
  inertia about G in the rotor frame is I_d 1 + (I_a − I_d) n nᵀ with n = (cos β, 0, sin β); H_G = I_G ω x̂
  turns with the rotor, so dH_G/dt = ω x̂ × H_G, of size C = (I_a − I_d) ω² sin β cos β = m r² ω² sin β cos β / 4,
  perpendicular to the plane of the shaft and the disk's axis. G does not accelerate, so the bearings supply a
  pure couple: R_A = −R_B, |R_B| = |C| / L; with gravity the weight shares add, so over a turn |R_A| swings
  between | |C|/L − m g (L − a)/L | and |C|/L + m g (L − a)/L. No torque is needed (G is on the shaft).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06 import unbalanced_rotor as rotor

BASE = {
    **rotor.PARAMETERS.defaults(),
    "shaft_speed_rad_s": 120.0, "disk_mass_kg": 8.0, "disk_radius_m": 0.25, "bearing_span_m": 0.8, "disk_position_m": 0.3,
}  # fmt: skip
TURN = np.linspace(0.0, 2.0 * math.pi, 721)  # spin angles over one turn (rad)


def loads(**changes):
    params = rotor.PARAMETERS.validate({k: v for k, v in {**BASE, **changes}.items()})
    model = rotor.UnbalancedRotor.from_params(params)
    speed = params["shaft_speed_rad_s"]
    t = TURN / speed if speed else np.zeros_like(TURN)
    return params, model, model.at(t)


def test_pure_static_imbalance_matches_the_beam_shares_of_m_e_omega2_plus_weight():
    params, model, got = loads(eccentricity_m=0.003, skew_deg=0.0, g_m_s2=9.81)
    m, e, w, g = params["disk_mass_kg"], params["eccentricity_m"], params["shaft_speed_rad_s"], params["g_m_s2"]
    L, a = params["bearing_span_m"], params["disk_position_m"]
    phi = got.spin_angle
    total = np.sqrt((m * e * w**2) ** 2 + (m * g) ** 2 - 2.0 * m * e * w**2 * m * g * np.sin(phi))
    # Each force is a sum of terms of size ≤ m e ω² + m g ≈ 424 N: rounding leaves ~1e-13 N.
    assert got.bearing_A_force_N == pytest.approx((L - a) / L * total, rel=1e-12, abs=1e-11)
    assert got.bearing_B_force_N == pytest.approx(a / L * total, rel=1e-12, abs=1e-11)
    assert got.driving_torque_Nm == pytest.approx(m * g * e * np.cos(phi), abs=1e-13)
    assert model.imbalance == "static"


def test_pure_static_imbalance_without_gravity_is_constant_and_needs_no_torque():
    params, _, got = loads(eccentricity_m=0.003, skew_deg=0.0, g_m_s2=0.0)
    m, e, w = params["disk_mass_kg"], params["eccentricity_m"], params["shaft_speed_rad_s"]
    L, a = params["bearing_span_m"], params["disk_position_m"]
    assert got.bearing_A_force_N == pytest.approx(np.full(TURN.size, (L - a) / L * m * e * w**2), rel=1e-13)
    assert got.bearing_B_force_N == pytest.approx(np.full(TURN.size, a / L * m * e * w**2), rel=1e-13)
    assert np.all(got.driving_torque_Nm == 0.0)


@pytest.mark.parametrize("skew_deg", [-20.0, 1.0, 5.0, 30.0])
def test_pure_dynamic_imbalance_is_a_couple_of_size_quarter_m_r2_omega2_sin_cos(skew_deg):
    params, model, got = loads(eccentricity_m=0.0, skew_deg=skew_deg, g_m_s2=0.0)
    m, r, w, L = params["disk_mass_kg"], params["disk_radius_m"], params["shaft_speed_rad_s"], params["bearing_span_m"]
    beta = math.radians(skew_deg)
    couple = (0.5 * m * r**2 - 0.25 * m * r**2) * w**2 * math.sin(beta) * math.cos(beta)
    # Products of sines and cosines of size ≤ 1 times |C|/L: rounding ~1e-15 relative; 1e-12 leaves margin.
    assert got.bearing_B_force_N == pytest.approx(np.full(TURN.size, abs(couple) / L), rel=1e-12)
    assert got.bearing_A_N == pytest.approx(-got.bearing_B_N, rel=1e-12, abs=1e-12 * abs(couple) / L)
    assert np.all(got.driving_torque_Nm == 0.0)
    assert model.imbalance == "dynamic"


def test_pure_dynamic_imbalance_with_gravity_swings_between_difference_and_sum():
    params, _, got = loads(eccentricity_m=0.0, skew_deg=3.0, g_m_s2=9.81)
    m, r, w, L, a, g = (params[k] for k in ("disk_mass_kg", "disk_radius_m", "shaft_speed_rad_s", "bearing_span_m", "disk_position_m", "g_m_s2"))
    beta = math.radians(3.0)
    couple_share = 0.25 * m * r**2 * w**2 * math.sin(beta) * math.cos(beta) / L
    weight_A, weight_B = m * g * (L - a) / L, m * g * a / L
    # 721 samples over a turn include φ = 0, 90°, 180°, 270°, where the couple's reaction is vertical (±Z).
    assert got.bearing_A_force_N.max() == pytest.approx(couple_share + weight_A, rel=1e-12)
    assert got.bearing_A_force_N.min() == pytest.approx(abs(couple_share - weight_A), rel=1e-12)
    assert got.bearing_B_force_N.max() == pytest.approx(couple_share + weight_B, rel=1e-12)
    assert got.bearing_B_force_N.min() == pytest.approx(abs(couple_share - weight_B), rel=1e-12)


def test_a_rotor_at_rest_carries_only_its_weight():
    params, model, got = loads(shaft_speed_rad_s=0.0, eccentricity_m=0.004, skew_deg=10.0, g_m_s2=9.81)
    m, g, e, L, a = (params[k] for k in ("disk_mass_kg", "g_m_s2", "eccentricity_m", "bearing_span_m", "disk_position_m"))
    assert np.all(np.isfinite(got.bearing_A_N)) and np.all(np.isfinite(got.driving_torque_Nm))
    assert got.bearing_A_force_N == pytest.approx(np.full(TURN.size, m * g * (L - a) / L), rel=1e-14)
    assert got.bearing_B_force_N == pytest.approx(np.full(TURN.size, m * g * a / L), rel=1e-14)
    assert np.all(got.bearing_A_rotating_N == 0.0) and np.all(got.bearing_B_rotating_N == 0.0)
    # The rotor stands at φ = 0 with G level with the shaft: the drive holds it against m g e.
    assert got.driving_torque_Nm == pytest.approx(np.full(TURN.size, m * g * e), rel=1e-14)
    assert model.imbalance == "both"


# -- an independent check: the disk as particles, Newton's law for each -------------------------------------------
def disk_particles(m, r, e, beta, a):
    """Thin disk as point masses (kg, rotor-frame positions m): Gauss–Legendre in radius (exact for ∫ρ³dρ with 4
    points), 64 equal angles (exact for the degree-2 trigonometric terms of every first and second moment)."""
    nodes, weights = np.polynomial.legendre.leggauss(4)
    rho, w_rho = 0.5 * r * (nodes + 1.0), 0.5 * r * weights
    angles = np.linspace(0.0, 2.0 * math.pi, 64, endpoint=False)
    sigma = m / (math.pi * r**2)
    u = np.array([math.sin(beta), 0.0, -math.cos(beta)])  # two in-plane directions of the tilted disk
    v = np.array([0.0, 1.0, 0.0])
    R, A = np.meshgrid(rho, angles, indexing="ij")
    masses = (sigma * np.outer(w_rho * rho, np.full(angles.size, 2.0 * math.pi / angles.size))).ravel()
    points = np.array([a, e, 0.0]) + (R * np.cos(A)).ravel()[:, None] * u + (R * np.sin(A)).ravel()[:, None] * v
    return masses, points


def particle_reactions(masses, points, w, L):
    """Rotating bearing reactions (rotor frame, N) from Σ m_i a_i and Σ r_i × m_i a_i, a_i = −ω² (0, y_i, z_i)."""
    forces = -(w**2) * masses[:, None] * points * np.array([0.0, 1.0, 1.0])
    F, M = forces.sum(axis=0), np.cross(points, forces).sum(axis=0)
    # Moments about A: (L x̂) × (0, B_y, B_z) = L (0, −B_z, B_y) = (M_y, M_z) components → R_B = (0, M_z, −M_y) / L.
    R_B = np.array([0.0, M[2], -M[1]]) / L
    return F - R_B, R_B


@pytest.mark.parametrize("e, skew_deg", [(0.002, 0.0), (0.0, 4.0), (0.003, -7.0), (0.01, 25.0)])
def test_reactions_agree_with_a_particle_model_of_the_disk(e, skew_deg):
    params, model, got = loads(eccentricity_m=e, skew_deg=skew_deg, g_m_s2=0.0)
    m, r, w, L, a = (params[k] for k in ("disk_mass_kg", "disk_radius_m", "shaft_speed_rad_s", "bearing_span_m", "disk_position_m"))
    masses, points = disk_particles(m, r, e, math.radians(skew_deg), a)
    A_rotor, B_rotor = particle_reactions(masses, points, w, L)
    steady = model.steady_loads()
    # The quadrature is exact for these moments; what is left is rounding over 256 particles (~1e-13 relative).
    scale = m * r * w**2
    assert steady.bearing_A_rotating_rotor_N == pytest.approx(A_rotor, abs=1e-11 * scale)
    assert steady.bearing_B_rotating_rotor_N == pytest.approx(B_rotor, abs=1e-11 * scale)


# -- balancing in two planes ---------------------------------------------------------------------------------------
def test_static_imbalance_midway_between_planes_needs_half_the_moment_opposite_in_each():
    params, model, _ = loads(eccentricity_m=0.004, skew_deg=0.0, disk_position_m=0.4, correction_plane_1_m=0.1,
                             correction_plane_2_m=0.7, correction_radius_m=0.2)  # fmt: skip
    m, e, rho = params["disk_mass_kg"], params["eccentricity_m"], params["correction_radius_m"]
    assert model.correction.masses_kg == pytest.approx([m * e / (2 * rho)] * 2, rel=1e-13)
    assert model.correction.angles_rad == pytest.approx([math.pi] * 2, abs=1e-13)


def test_couple_imbalance_needs_equal_masses_half_a_turn_apart():
    # Tilt towards +z: points at q (sin β, 0, −cos β) give I_xz = ∫ x z dm = −(m r²/4) sin β cos β. With U₁ = −U₂,
    # (x₂ − x₁) U₂ = −(0, I_xz): mass 2 at +z (90°), mass 1 at −z (270°), each (m r²/4) sin β cos β / (ρ (x₂ − x₁)).
    params, model, _ = loads(eccentricity_m=0.0, skew_deg=6.0, disk_position_m=0.4, correction_plane_1_m=0.1,
                             correction_plane_2_m=0.7, correction_radius_m=0.2)  # fmt: skip
    m, r, rho, beta = params["disk_mass_kg"], params["disk_radius_m"], params["correction_radius_m"], math.radians(6.0)
    expected = 0.25 * m * r**2 * math.sin(beta) * math.cos(beta) / (rho * 0.6)
    assert model.correction.masses_kg == pytest.approx([expected] * 2, rel=1e-12)
    assert np.degrees(model.correction.angles_rad) == pytest.approx([270.0, 90.0], abs=1e-10)


@pytest.mark.parametrize("e, skew_deg, planes", [(0.002, 2.0, (0.05, 0.75)), (0.01, -15.0, (0.3, 0.35)), (0.0005, 30.0, (0.6, 0.0))])
def test_the_corrected_rotor_has_no_rotating_reactions(e, skew_deg, planes):
    changes = dict(eccentricity_m=e, skew_deg=skew_deg, correction_plane_1_m=planes[0], correction_plane_2_m=planes[1], g_m_s2=0.0)
    params, model, _ = loads(**changes, balanced="on")
    _, unbalanced, before = loads(**changes)
    assert model.imbalance == "balanced" and unbalanced.imbalance == "both"
    # Independently: the particle disk plus the two correction masses as particles must need no rotating force.
    m, r, w, L, a = (params[k] for k in ("disk_mass_kg", "disk_radius_m", "shaft_speed_rad_s", "bearing_span_m", "disk_position_m"))
    masses, points = disk_particles(m, r, e, math.radians(skew_deg), a)
    extra = model.correction.parts()
    masses = np.concatenate([masses, [p.mass_kg for p in extra]])
    points = np.vstack([points, [p.centre_m for p in extra]])
    scale = max(before.bearing_A_force_N.max(), before.bearing_B_force_N.max())
    for reaction in particle_reactions(masses, points, w, L):
        assert np.linalg.norm(reaction) < 1e-11 * scale  # rounding only: the balance is exact
    after = model.at(TURN / params["shaft_speed_rad_s"])
    assert after.bearing_A_force_N.max() < 1e-12 * scale and after.bearing_B_force_N.max() < 1e-12 * scale


def test_a_balanced_rotor_under_gravity_carries_its_new_weight_and_needs_no_torque():
    params, model, got = loads(eccentricity_m=0.002, skew_deg=3.0, g_m_s2=9.81, balanced="on")
    total = params["disk_mass_kg"] + float(np.sum(model.correction.masses_kg))
    both = got.bearing_A_force_N + got.bearing_B_force_N
    assert both == pytest.approx(np.full(TURN.size, total * 9.81), rel=1e-12)  # both vertical, summing to the weight
    assert np.max(np.abs(got.driving_torque_Nm)) < 1e-12 * total * 9.81 * params["disk_radius_m"]


# -- inputs ----------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "changes, field",
    [
        ({"disk_mass_kg": -1.0}, "disk_mass_kg"),
        ({"disk_position_m": 0.9}, "disk_position_m"),
        ({"eccentricity_m": 0.3}, "eccentricity_m"),
        ({"skew_deg": float("nan")}, "skew_deg"),
        ({"shaft_speed_rad_s": float("inf")}, "shaft_speed_rad_s"),
        ({"correction_plane_1_m": 1.2}, "correction_plane_1_m"),
        ({"correction_plane_2_m": 0.055}, "correction_plane_2_m"),
        ({"balanced": "yes"}, "balanced"),
    ],
)
def test_bad_input_is_refused_naming_the_field(changes, field):
    with pytest.raises(ParameterError) as info:
        rotor.PARAMETERS.validate({**BASE, "bearing_span_m": 0.8, **changes})
    assert info.value.field == field


def test_simulate_series_are_the_loads():
    params = rotor.PARAMETERS.validate(BASE)
    t = np.linspace(0.0, 0.2, 41)
    solution = rotor.UnbalancedRotorModel().evaluate(params, t)
    got = rotor.UnbalancedRotor.from_params(params).at(t)
    assert set(solution.series) == {"spin_angle", "bearing_A_force_N", "bearing_B_force_N", "driving_torque_Nm"}
    assert solution.series["spin_angle"] == pytest.approx(params["shaft_speed_rad_s"] * t, rel=1e-15)
    assert solution.series["bearing_A_force_N"] == pytest.approx(got.bearing_A_force_N, rel=1e-15)
