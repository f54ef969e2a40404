"""The body spun on a non-principal shaft: H three ways, the bearing moment, the energy split, edge cases, cost."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.bodies import inertia
from app.physics.core.parameters import ParameterError
from app.physics.systems.ch05 import angular_momentum as am

CASES = [
    {"body": "plate", "tilt_deg": 30.0},
    {"body": "plate", "tilt_deg": -65.0, "spin_rate_rad_s": -7.5},
    {"body": "box", "tilt_deg": 20.0, "length_m": 0.3, "width_m": 0.5, "height_m": 0.2},
    {"body": "disk", "tilt_deg": 45.0, "radius_m": 0.4},
    {"body": "disk", "tilt_deg": 5.0, "spin_rate_rad_s": 25.0, "mass_kg": 120.0},
]
TIMES = np.linspace(0.0, 3.0, 37)


def spin(values: dict, **extra) -> am.ShaftSpin:
    return am.ShaftSpin.from_params(am.PARAMETERS.validate({**values, **extra}))


def momentum_scale(motion: am.ShaftSpin) -> float:
    """|H_G| (kg·m²/s), never zero: the scale every relative tolerance below is taken against."""
    return max(float(np.linalg.norm(motion.at(np.zeros(1)).angular_momentum_G)), 1e-300)


@pytest.mark.parametrize("case", CASES, ids=[f"{c['body']}-{c['tilt_deg']:g}" for c in CASES])
def test_angular_momentum_three_ways(case):
    motion = spin(case, view="particles")
    state = motion.at(TIMES)
    scale = momentum_scale(motion)
    # 1. The tensor product H_G = R I_body Rᵀ ω with the attitude matrix at each instant (the model instead turns H_G(0)).
    R = motion.attitude(TIMES)
    by_tensor = np.einsum("nij,jk,nlk,l->ni", R, motion.body.inertia_body_kg_m2, R, motion.omega_rad_s)
    # Both are a few rounded products of numbers of size |H|: 1e-12 relative leaves 1000 ulps.
    assert np.max(np.abs(by_tensor - state.angular_momentum_G)) <= 1e-12 * scale
    # 2. The particle sum Σ (rᵢ − r_G) × mᵢ vᵢ over the equivalent point masses (a moving centre included).
    particles = motion.particles_at(state)
    by_particles = particles.angular_momentum(state.centre_m)
    assert np.max(np.abs(by_particles - state.angular_momentum_G)) <= 1e-12 * scale
    # 3. dH/dt by a central difference of H(t) against ω × H. Truncation h²/6 |d³H/dt³| = h² Ω² |dH/dt| / 6 and
    # round-off ε|H|/h: with h = 1e-4 / |Ω| s both are below 1e-8 |H| |Ω|, so 1e-7 |Ω| |H| is a safe bound.
    omega = abs(motion.spin_rate_rad_s)
    h = 1e-4 / omega
    central = (motion.at(TIMES + h).angular_momentum_G - motion.at(TIMES - h).angular_momentum_G) / (2.0 * h)
    assert np.max(np.abs(central - state.bearing_moment)) <= 1e-7 * omega * scale
    assert np.allclose(state.bearing_moment, np.cross(motion.omega_rad_s, state.angular_momentum_G), rtol=0.0, atol=1e-12 * omega * scale)


@pytest.mark.parametrize("shape", am.BODIES)
def test_equivalent_particles_have_the_mass_centre_and_tensor_of_the_body(shape):
    body = spin({"body": shape, "length_m": 0.7, "width_m": 0.2, "height_m": 0.45}).body
    positions, masses = am.equivalent_particles(np.diag(body.inertia_body_kg_m2), body.mass_kg)
    assert len(masses) == (8 if shape == "box" else 4)  # a flat body needs only the corners of a rectangle
    assert masses.sum() == pytest.approx(body.mass_kg, rel=1e-15)
    assert np.max(np.abs(masses @ positions)) <= 1e-15 * body.radius_m * body.mass_kg
    tensor = sum(inertia.parallel_axis(np.zeros((3, 3)), m, r) for m, r in zip(masses, positions))
    assert np.max(np.abs(tensor - body.inertia_body_kg_m2)) <= 1e-12 * np.trace(body.inertia_body_kg_m2)


def test_particle_sums_equal_the_rigid_body_formulas_with_a_moving_centre():
    motion = spin({"body": "box", "tilt_deg": 35.0, "spin_rate_rad_s": 6.0}, view="particles",
                  centre_velocity_m_s=[0.7, -0.4, 1.1], centre_position_m=[0.2, -0.5, 0.3])  # fmt: skip
    state = motion.at(TIMES)
    particles = motion.particles_at(state)
    m, v_g = motion.body.mass_kg, motion.centre_velocity_m_s
    assert np.max(np.abs(particles.linear_momentum() - m * v_g)) <= 1e-13 * m * np.linalg.norm(v_g)
    assert np.allclose(state.linear_momentum, m * v_g, rtol=1e-15, atol=0.0)
    # H_O = H_G + r_G × m v_G about the world origin.
    h_o = particles.angular_momentum(np.zeros(3))
    expected = state.angular_momentum_G + np.cross(state.centre_m, m * v_g)
    scale = float(np.max(np.linalg.norm(expected, axis=-1)))
    assert np.max(np.abs(h_o - state.angular_momentum_O)) <= 1e-12 * scale
    assert np.max(np.abs(expected - state.angular_momentum_O)) <= 1e-12 * scale
    # T = ½ m v_G² + Σ ½ mᵢ |vᵢ − v_G|² = Σ ½ mᵢ |vᵢ|², and the part about G is ½ ω·H_G.
    total = particles.kinetic_energy()
    assert np.max(np.abs(state.kinetic_energy_J - total)) <= 1e-12 * float(total.max())
    assert np.allclose(particles.kinetic_energy(relative_to_m_s=v_g), state.kinetic_energy_about_centre_J, rtol=1e-12, atol=0.0)
    assert np.allclose(state.kinetic_energy_centre_J, 0.5 * m * float(v_g @ v_g), rtol=1e-15, atol=0.0)


@pytest.mark.parametrize("radius, tilt_deg, rate", [(0.25, 30.0, 4.0), (0.4, 60.0, -9.0), (1.2, 10.0, 2.5)])
def test_skewed_disk_matches_its_textbook_closed_form(radius, tilt_deg, rate):
    """Thin disk, axis tilted θ from the shaft: |M| = Ω² (I_a − I_t) sin θ cos θ, T = ½ Ω² (I_t sin²θ + I_a cos²θ),
    and tan(angle of H from ω) = (I_a − I_t) sin θ cos θ / (I_t sin²θ + I_a cos²θ), with I_a = ½ m r², I_t = ¼ m r²."""
    m = 3.0
    motion = spin({"body": "disk", "radius_m": radius, "tilt_deg": tilt_deg, "spin_rate_rad_s": rate, "mass_kg": m})
    state = motion.at(TIMES)
    th = math.radians(tilt_deg)
    i_a, i_t = 0.5 * m * radius**2, 0.25 * m * radius**2
    along = i_t * math.sin(th) ** 2 + i_a * math.cos(th) ** 2
    across = (i_a - i_t) * math.sin(th) * math.cos(th)
    # A dozen rounded operations on each side: 1e-13 relative.
    assert state.bearing_moment_N_m == pytest.approx(np.full(TIMES.shape, rate**2 * across), rel=1e-13)
    assert state.kinetic_energy_J == pytest.approx(np.full(TIMES.shape, 0.5 * rate**2 * along), rel=1e-13)
    assert state.angle_between_omega_and_H == pytest.approx(np.full(TIMES.shape, math.atan2(across, along)), rel=1e-13)
    # The bearing forces: equal and opposite, across the shaft, a couple equal to dH/dt about G, |F| = |M| / span.
    span = motion.bearing_span_m
    couple = np.cross([0.0, 0.0, -span / 2], state.bearing_force_A) + np.cross([0.0, 0.0, span / 2], state.bearing_force_B)
    assert np.allclose(couple, state.bearing_moment, rtol=0.0, atol=1e-14 * rate**2 * i_a)
    assert np.array_equal(state.bearing_force_A, -state.bearing_force_B)
    assert np.all(state.bearing_force_B[:, 2] == 0.0)
    assert np.linalg.norm(state.bearing_force_B, axis=-1) == pytest.approx(rate**2 * abs(across) / span, rel=1e-13)


def test_h_sweeps_a_cone_turning_with_the_body():
    motion = spin({"body": "plate", "tilt_deg": 30.0, "spin_rate_rad_s": 4.0})
    state = motion.at(TIMES)
    h = state.angular_momentum_G
    # Constant length and constant shaft component; the part across the shaft turns through Ω t.
    assert np.ptp(np.linalg.norm(h, axis=-1)) <= 1e-15 * np.linalg.norm(h[0]) * 4
    assert np.ptp(h[:, 2]) == 0.0
    turned = np.unwrap(np.arctan2(h[:, 1], h[:, 0]))
    assert turned - turned[0] == pytest.approx(4.0 * TIMES, abs=1e-12)


@pytest.mark.parametrize("case", [{"body": "plate", "tilt_deg": 0.0}, {"body": "disk", "tilt_deg": 0.0},
                                  {"body": "box", "tilt_deg": 0.0}, {"body": "plate", "tilt_deg": 90.0},
                                  {"body": "disk", "tilt_deg": -90.0}])  # fmt: skip
def test_a_principal_shaft_gives_h_parallel_to_omega_and_no_bearing_moment(case):
    motion = spin(case, spin_rate_rad_s=12.0)
    state = motion.at(TIMES)
    assert motion.body.shaft_is_principal
    scale = momentum_scale(motion)
    # At 90° cos(π/2) ≈ 6e-17 leaves products of inertia of that relative size, hence 1e-15.
    assert np.max(state.bearing_moment_N_m) <= 1e-15 * 12.0 * scale
    assert np.max(state.angle_between_omega_and_H) <= 1e-15
    assert not spin({**case, "tilt_deg": 30.0}).body.shaft_is_principal


def test_zero_spin_gives_zero_everything_and_no_angle():
    """Issue 24, Found 12: at Ω = 0 the angle between ω and H_G was reported as 0.0. ω = 0 and H_G = 0 have no direction,
    so the angle is NaN (null in the answer, whose event says why); everything else is a finite zero."""
    motion = spin({"body": "plate", "tilt_deg": 40.0, "spin_rate_rad_s": 0.0})
    state = motion.at(TIMES)
    for name in ("angular_momentum_G", "angular_momentum_O", "bearing_moment", "bearing_force_A", "bearing_force_B",
                 "kinetic_energy_J", "bearing_moment_N_m", "spin_angle"):  # fmt: skip
        values = getattr(state, name)
        assert np.all(np.isfinite(values)) and np.all(values == 0.0), name
    assert np.all(np.isnan(state.angle_between_omega_and_H))
    report = am.ShaftSpinModel().simulate(am.PARAMETERS.validate({"spin_rate_rad_s": 0.0}), {}, t_end_s=2.0, frame_rate_hz=30.0).as_dict()
    assert all(value is None for value in report["series"]["angle_between_omega_and_H"])
    assert report["stats"]["status"] == "undefined" and report["stats"]["max_invariant_drift"] == 0.0
    assert report["events"] == [{"t_s": 0.0, "kind": "undefined", "message": f"angle between ω and H_G: {am.NO_SPIN_ANGLE}"}]


def test_a_principal_shaft_has_omega_and_h_parallel():
    """tilt 0: the shaft is a principal axis, H_G ∥ ω, and the angle between them is a defined 0."""
    report = am.ShaftSpinModel().simulate(am.PARAMETERS.validate({"tilt_deg": 0.0}), {}, t_end_s=2.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] == "ok" and max(report["series"]["angle_between_omega_and_H"]) == 0.0


def test_simulate_report_has_the_contract_series_and_constant_invariants():
    params = am.PARAMETERS.validate({})
    report = am.ShaftSpinModel().simulate(params, {}, t_end_s=5.0, frame_rate_hz=30.0).as_dict()
    assert set(report["series"]) == set(am.ShaftSpinModel.series_units) == {
        "spin_angle", "angular_momentum_x_kg_m2_s", "angular_momentum_y_kg_m2_s", "angular_momentum_z_kg_m2_s",
        "bearing_moment_N_m", "angle_between_omega_and_H", "kinetic_energy_J",
    }  # fmt: skip
    assert report["stats"]["status"] == "ok"
    # |H| and T are constant: only rounding in the rotation of H_G(0) moves them (16 ulps).
    assert report["stats"]["max_invariant_drift"] < 4e-15


@pytest.mark.parametrize(
    "raw, field",
    [({"tilt_deg": 95.0}, "tilt_deg"), ({"body": "sphere"}, "body"), ({"spin_rate_rad_s": float("nan")}, "spin_rate_rad_s"),
     ({"mass_kg": 0.0}, "mass_kg"), ({"centre_velocity_m_s": [1.0, 2.0]}, "centre_velocity_m_s"),
     ({"view": "ghost"}, "view"), ({"bearing_span_m": -1.0}, "bearing_span_m")],
)  # fmt: skip
def test_bad_input_is_refused_naming_the_field(raw, field):
    with pytest.raises(ParameterError) as info:
        am.PARAMETERS.validate(raw)
    assert info.value.field == field


def test_motions_are_cached_per_parameter_set_and_cannot_be_changed():
    motion = spin({})
    assert spin({}) is motion and spin({"tilt_deg": 31.0}) is not motion
    assert spin({"view": "particles", "centre_velocity_m_s": [0.1, 0.0, 0.0]}) is not spin({"view": "particles"})
    with pytest.raises(ValueError):  # shared by every caller: its arrays are read-only
        motion.body.inertia_body_kg_m2[0, 0] = 1.0


@pytest.mark.parametrize("tilt_deg, rate", [(0.0, 3.0), (17.0, -2.5), (90.0, 7.0), (-40.0, 0.0)])
def test_the_drawn_attitude_quaternion_is_the_attitude_matrix(tilt_deg, rate):
    """The per-frame quaternion (composed in closed form) against the matrix R_z(Ωt) R_x(tilt) converted: 1e-14, up to sign."""
    from app.physics.math.rotations import quaternion_from_matrix

    motion = spin({"tilt_deg": tilt_deg, "spin_rate_rad_s": rate})
    for t in (0.0, 0.37, 5.1, 123.4):
        q = np.array(motion.attitude_wxyz(t))
        q_ref = quaternion_from_matrix(motion.attitude(np.array([t]))[0])
        assert min(np.abs(q - q_ref).max(), np.abs(q + q_ref).max()) < 1e-14  # a few roundings of unit-size numbers
