"""The impulse law: energetic restitution with Coulomb friction never creates energy.

Tolerances: the law is closed-form phase by phase, so identities that hold exactly
(energy from the quadratic form, the separation speed at e = 1 or e = 0, Coulomb's
ratio while sliding) are checked to 1e-12 relative — a few hundred ulps of the
velocities involved. The comparison with a brute-force march along the normal
impulse uses 1e-3 relative: that march takes 200 000 first-order steps, so its own
error is of order 1/200 000 per phase, well below 1e-3. The compiled core and its
Python twin run the same source in the same order: they agree to 1e-14 of the scale of
each quantity (a few tens of ulps; measured ≤ 2e-16 over 100 000 random contacts).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from app.physics.bodies.inertia import slender_rod
from app.physics.systems.ch06.impact import IMPACT_OUT_SIZE, SLIP_STATES, impact_kernel, resolve_impact


def bar_end_on_floor(*, mass_kg: float, length_m: float, angle_rad: float) -> np.ndarray:
    """W (1/kg) at the lower end of a slender bar at ``angle_rad`` above a floor, frame [normal = up, tangent = +x]."""
    inertia = float(slender_rod(mass_kg, length_m)[0, 0])
    rx, ry = -0.5 * length_m * math.cos(angle_rad), -0.5 * length_m * math.sin(angle_rad)
    return np.array([[1 / mass_kg + rx * rx / inertia, -rx * ry / inertia], [-rx * ry / inertia, 1 / mass_kg + ry * ry / inertia]])


def newton_textbook_impulse(W: np.ndarray, v: np.ndarray, e: float, mu: float) -> np.ndarray:
    """Newton's kinematic law (vn' = −e vn) with Coulomb friction, solved the textbook way.

    Try sticking (vt' = 0); if that needs |Pt| > μ Pn, slide against the initial slip (Pt = −μ sign(vt) Pn).
    This is the law whose energy gain is the paradox; it is here only to show the gain.
    """
    stick = np.linalg.solve(W, np.array([-e * v[0], 0.0]) - v)
    if abs(stick[1]) <= mu * stick[0]:
        return stick
    slope = -mu * math.copysign(1.0, v[1])
    p_n = -(1.0 + e) * v[0] / (W[0, 0] + W[0, 1] * slope)
    return np.array([p_n, slope * p_n])


def quadratic_energy_loss(W: np.ndarray, v: np.ndarray, impulse: np.ndarray) -> float:
    return -0.5 * float(impulse @ (2.0 * v + W @ impulse))


def resolve(W, v, e, mu):
    return resolve_impact(inverse_effective_mass=np.asarray(W, float), contact_velocity_m_s=np.asarray(v, float), restitution=e, friction_coefficient=mu)


BAR_45 = bar_end_on_floor(mass_kg=1.0, length_m=1.0, angle_rad=math.radians(45.0))  # [[2.5, −1.5], [−1.5, 2.5]] 1/kg


def test_paradox_case_newton_creates_energy_energetic_law_does_not():
    # A 1 kg, 1 m bar at 45° strikes the floor with its lower end: vn = −2 m/s, sliding at +0.5 m/s; e = 0.9, μ = 0.5.
    # |W_tn| / W_tt = 0.6 > μ, so the slip stops during the impact and then reverses.
    v, e, mu = np.array([-2.0, 0.5]), 0.9, 0.5
    newton = newton_textbook_impulse(BAR_45, v, e, mu)
    assert quadratic_energy_loss(BAR_45, v, newton) < -0.5  # Newton's law gains 0.53 J out of 1.0 J (a gain, not round-off)
    result = resolve(BAR_45, v, e, mu)
    assert result.slip_state == "reversed"
    assert result.energy_loss_J > 0.3
    assert result.energy_loss_J == pytest.approx(quadratic_energy_loss(BAR_45, v, result.impulse_N_s), rel=1e-12)
    assert result.contact_velocity_after_m_s[1] < 0.0  # sliding the other way at the end
    assert result.impulse_N_s[1] > 0.0


def test_elastic_frictionless_keeps_energy_and_reverses_the_normal_speed():
    v = np.array([-3.0, 1.2])
    result = resolve(BAR_45, v, 1.0, 0.0)
    energy_scale = 0.5 * float(v @ np.linalg.solve(BAR_45, v))
    assert abs(result.energy_loss_J) <= 1e-12 * energy_scale
    assert abs(quadratic_energy_loss(BAR_45, v, result.impulse_N_s)) <= 1e-12 * energy_scale
    assert result.impulse_N_s[1] == 0.0
    assert result.contact_velocity_after_m_s[0] == pytest.approx(3.0, rel=1e-12)


def test_plastic_impact_ends_with_zero_normal_speed():
    result = resolve([[1.5, 0.0], [0.0, 4.5]], [-2.0, 3.0], 0.0, 0.2)
    assert abs(result.contact_velocity_after_m_s[0]) <= 1e-12 * 2.0
    assert result.impulse_N_s[0] == pytest.approx(2.0 / 1.5, rel=1e-12)


def test_sliding_throughout_follows_coulomb_ratio():
    result = resolve(BAR_45, [-2.0, 3.0], 0.5, 0.1)
    assert result.slip_state == "slid throughout"
    assert result.impulse_N_s[1] == pytest.approx(-0.1 * result.impulse_N_s[0], rel=1e-12)
    assert result.contact_velocity_after_m_s[1] > 0.0


def test_high_friction_oblique_impact_sticks():
    result = resolve(BAR_45, [-2.0, 1.0], 0.7, 2.0)  # |W_tn|/W_tt = 0.6 ≤ μ: once slip stops it stays stopped
    assert result.slip_state == "stuck"
    assert abs(result.contact_velocity_after_m_s[1]) <= 1e-12 * 2.0
    assert abs(result.impulse_N_s[1]) <= 2.0 * result.impulse_N_s[0]


def test_grazing_impact_gives_a_vanishing_finite_impulse():
    for vn in (-1e-9, -1e-300):
        result = resolve(BAR_45, [vn, 2.0], 0.8, 0.5)
        assert np.all(np.isfinite(result.impulse_N_s))
        assert 0.0 <= result.energy_loss_J
        assert 0.0 < result.impulse_N_s[0] <= 10.0 * abs(vn)
        assert result.contact_velocity_after_m_s[1] == pytest.approx(2.0, rel=1e-6)


def _march(W, v, e, mu, steps=200_000):
    """Brute-force the same law: step the normal impulse, friction against the slip, until the energetic target."""
    v = np.array(v, float)
    P = np.zeros(2)
    compression = restitution = 0.0
    p_end = 4.0 * abs(v[0]) / (W[0, 0] - mu * abs(W[0, 1])) if W[0, 0] > mu * abs(W[0, 1]) else 50.0
    dp = p_end / steps
    can_stick = abs(W[1, 0]) <= mu * W[1, 1]
    while True:
        u = v + W @ P
        if abs(u[1]) <= abs(W[1, 1] * mu * dp) and can_stick:
            slope = -W[1, 0] / W[1, 1]
        else:
            slope = -mu * np.sign(u[1]) if u[1] != 0.0 else -mu * np.sign(W[1, 0])
        if u[0] < 0.0:
            compression += u[0] * dp
        else:
            restitution += u[0] * dp
            if restitution >= -e * e * compression:
                return P
        P = P + dp * np.array([1.0, slope])


@pytest.mark.parametrize(
    "v, e, mu",
    [([-2.0, 0.5], 0.9, 0.5), ([-2.0, 1.0], 0.7, 2.0), ([-2.0, 3.0], 0.5, 0.1), ([-1.0, -0.2], 0.6, 0.3)],
    ids=["reverses", "sticks", "slides", "slides-negative"],
)
def test_closed_form_phases_agree_with_a_brute_force_march(v, e, mu):
    result = resolve(BAR_45, v, e, mu)
    marched = _march(BAR_45, v, e, mu)
    np.testing.assert_allclose(result.impulse_N_s, marched, rtol=1e-3, atol=1e-3 * abs(v[0]))


@st.composite
def contacts(draw):
    a = np.array([[draw(st.floats(-3, 3)), draw(st.floats(-3, 3))], [draw(st.floats(-3, 3)), draw(st.floats(-3, 3))]])
    W = a @ a.T + draw(st.floats(1e-3, 2.0)) * np.eye(2)
    v = np.array([-draw(st.floats(1e-6, 50.0)), draw(st.floats(-50.0, 50.0))])
    return W, v, draw(st.floats(0.0, 1.0)), draw(st.floats(0.0, 5.0, allow_subnormal=False))


@settings(max_examples=400, deadline=None)
@given(contacts())
@example(contact=(2.0 * np.eye(2), np.array([-1e-6, 1.0]), 1.0, np.finfo(float).tiny))  # found by CI: mu P_n underflows
def test_energy_is_never_created_and_matches_the_quadratic_form(contact):
    W, v, e, mu = contact
    result = resolve(W, v, e, mu)
    assert result.slip_state in SLIP_STATES
    assert result.energy_loss_J >= 0.0
    energy_scale = 0.5 * float(v @ np.linalg.solve(W, v))
    # Both are sums of O(energy_scale) terms: 1e-9 of the scale allows for W's condition number (≤ ~1e4 here).
    assert result.energy_loss_J == pytest.approx(quadratic_energy_loss(W, v, result.impulse_N_s), abs=1e-9 * energy_scale)
    # The bodies do not interpenetrate after; v' = v + W P cancels terms of size |v| + |W P|, so allow round-off of those.
    assert result.contact_velocity_after_m_s[0] >= -1e-12 * (np.linalg.norm(v) + np.linalg.norm(W @ result.impulse_N_s))
    assert result.impulse_N_s[0] >= 0.0
    # Inside the friction cone; below the normal range (mu P_n < 2.2e-308) a product keeps only absolute precision.
    assert abs(result.impulse_N_s[1]) <= mu * result.impulse_N_s[0] * (1 + 1e-12) + np.finfo(float).tiny


@settings(max_examples=400, deadline=None)
@given(contacts(), st.booleans())
def test_the_compiled_core_and_its_python_twin_agree(contact, no_initial_slip):
    W, v, e, mu = contact
    if no_initial_slip:
        v[1] = 0.0  # the stick branch from the start
    W, v = np.ascontiguousarray(W), np.ascontiguousarray(v)
    compiled, python = np.empty(IMPACT_OUT_SIZE), np.empty(IMPACT_OUT_SIZE)
    impact_kernel.compiled(W, v, e, mu, compiled)
    impact_kernel.python(W, v, e, mu, python)
    assert compiled[5] == python[5] and python[5] in (0.0, 1.0, 2.0)  # the same slip state
    impulse_scale = np.max(np.abs(python[:2]))
    velocity_scale = np.max(np.abs(v)) + np.max(np.abs(W @ python[:2]))  # v' = v + W P cancels terms this big
    energy_scale = 0.5 * float(v @ np.linalg.solve(W, v))
    # Same source, same order of operations: round-off only, 1e-14 of each scale (see the module text).
    np.testing.assert_allclose(compiled[:2], python[:2], rtol=0.0, atol=1e-14 * impulse_scale)
    np.testing.assert_allclose(compiled[2:4], python[2:4], rtol=0.0, atol=1e-14 * velocity_scale)
    assert abs(compiled[4] - python[4]) <= 1e-14 * energy_scale
    # And resolve_impact reports the compiled core's numbers under their names.
    result = resolve(W, v, e, mu)
    np.testing.assert_array_equal(np.r_[result.impulse_N_s, result.contact_velocity_after_m_s, result.energy_loss_J], compiled[:5])
    assert result.slip_state == SLIP_STATES[int(compiled[5])]


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"contact_velocity_m_s": [0.0, 1.0]}, "not approaching"),
        ({"contact_velocity_m_s": [0.5, 1.0]}, "not approaching"),
        ({"contact_velocity_m_s": [-1.0, math.nan]}, "contact_velocity_m_s"),
        ({"restitution": 1.5}, "restitution"),
        ({"friction_coefficient": -0.1}, "friction_coefficient"),
        ({"inverse_effective_mass": [[1.0, 0.5], [0.4, 1.0]]}, "inverse_effective_mass"),
        ({"inverse_effective_mass": [[1.0, 2.0], [2.0, 1.0]]}, "inverse_effective_mass"),
    ],
)
def test_bad_input_is_refused_naming_it(kwargs, field):
    arguments = {"inverse_effective_mass": BAR_45, "contact_velocity_m_s": [-1.0, 0.0], "restitution": 0.5, "friction_coefficient": 0.3}
    arguments.update(kwargs)
    with pytest.raises(ValueError, match=field):
        resolve_impact(**{k: np.asarray(v, float) if k != "restitution" and k != "friction_coefficient" else v for k, v in arguments.items()})


def test_no_initial_slip_that_friction_can_hold_is_stuck():
    assert resolve([[1.5, 0.0], [0.0, 4.5]], [-4.0, 0.0], 1.0, 0.0).slip_state == "stuck"
    starts_to_slide = resolve(BAR_45, [-2.0, 0.0], 0.5, 0.1)  # |W_tn|/W_tt = 0.6 > μ: it slides from the start
    assert starts_to_slide.slip_state == "slid throughout"
    assert starts_to_slide.impulse_N_s[1] == pytest.approx(0.1 * starts_to_slide.impulse_N_s[0], rel=1e-12)


@pytest.mark.parametrize("e,mu", [(1.0, 0.0), (0.5, 0.3), (0.0, 2.0)])
@pytest.mark.parametrize("scale", [1e-163, 1e-300, 1e150])
def test_the_law_is_homogeneous_in_the_approach_speed_even_where_its_works_would_underflow(e, mu, scale):
    # Impulses and velocities scale with the approach, the energy loss with its square (exactly: the law is followed
    # for the approach scaled to unit size). Before that scaling an approach of 1e-163 m/s underflowed its works
    # (1e-326 J) and the phase sequence never ended (found by the planar-collision property test).
    W = np.array([[0.25, 0.0], [0.0, 0.75]])
    unit = resolve(W, [-0.0349, -1.0], e, mu)
    tiny = resolve(W, [-0.0349 * scale, -1.0 * scale], e, mu)
    np.testing.assert_allclose(tiny.impulse_N_s, unit.impulse_N_s * scale, rtol=1e-12, atol=0.0)
    np.testing.assert_allclose(tiny.contact_velocity_after_m_s, unit.contact_velocity_after_m_s * scale, rtol=1e-12, atol=0.0)
    assert tiny.slip_state == unit.slip_state
    if scale ** 2 > 1e-290:  # a square that a double can hold
        assert tiny.energy_loss_J == pytest.approx(unit.energy_loss_J * scale**2, rel=1e-12)
