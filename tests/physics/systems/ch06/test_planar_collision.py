"""Two disks collide: conservation laws, the closed form for disks, the hard cases, bad input.

Tolerances: each conservation law is a sum of a few products of O(1) numbers, so it holds
to round-off; 1e-12 relative to the scale of the quantity (momentum m|v|, angular momentum
m|v|r + I|ω|, energy T) leaves a margin of ~10⁴ ulps.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, assume, given, settings
from hypothesis import strategies as st

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06.impact import SLIP_STATES
from app.physics.systems.ch06.planar_collision import EXAMPLE, collide, relative_contact_velocity

DEFAULTS = EXAMPLE.inputs.defaults()


def inputs(**changes):
    return EXAMPLE.inputs.validate(changes)


def scales(c):
    momentum = sum(d.mass_kg * np.linalg.norm(d.velocity_m_s) for d in c.before) + np.linalg.norm(c.impulse_N_s)
    angular = sum(d.mass_kg * np.linalg.norm(d.velocity_m_s) * (np.linalg.norm(d.centre_m) + d.radius_m) + d.inertia_kg_m2 * abs(d.spin_rad_s) for d in c.before)
    angular += np.linalg.norm(c.impulse_N_s) * (c.before[0].radius_m + c.before[1].radius_m)
    return momentum, max(angular, 1e-300), max(c.energy_before_J, 1e-300)


def check_conservation(c):
    momentum_scale, angular_scale, energy_scale = scales(c)
    p_before = sum(d.momentum_N_s for d in c.before)
    p_after = sum(d.momentum_N_s for d in c.after)
    assert np.linalg.norm(p_after - p_before) <= 1e-12 * momentum_scale
    for before, after in zip(c.before, c.after):  # each disk about the contact point: the impulse there has no moment
        assert abs(after.angular_momentum_about(c.contact_point_m) - before.angular_momentum_about(c.contact_point_m)) <= 1e-12 * angular_scale
    for point in (np.zeros(3), np.array([3.7, -2.1, 0.0]), c.before[1].centre_m):  # the pair about fixed points
        h_before = sum(d.angular_momentum_about(point) for d in c.before)
        h_after = sum(d.angular_momentum_about(point) for d in c.after)
        assert abs(h_after - h_before) <= 1e-12 * (angular_scale + np.linalg.norm(point) * momentum_scale)
    energy_after = sum(d.kinetic_energy_J for d in c.after)
    assert c.impact.energy_loss_J >= 0.0
    assert c.energy_before_J - energy_after == pytest.approx(c.impact.energy_loss_J, abs=1e-12 * energy_scale)


def test_defaults_conserve_momentum_and_angular_momentum_and_lose_energy():
    c = collide(DEFAULTS)
    check_conservation(c)
    assert c.impact.slip_state == "slid throughout"
    assert c.impact.energy_loss_J > 0.1


def test_disks_match_their_closed_form():
    # W is diagonal for disks, so P_n = (1 + e)(−v_n)/W_nn and P_t = −sign(v_t) min(μ P_n, |v_t|/W_tt) exactly.
    for changes in ({}, {"friction_coefficient": 1.0}, {"omega2_rad_s": -30.0, "restitution": 0.3}):
        c = collide(inputs(**changes))
        W, (vn, vt) = c.inverse_effective_mass, c.contact_velocity_m_s
        e, mu = c_inputs(changes, "restitution"), c_inputs(changes, "friction_coefficient")
        p_n = (1 + e) * -vn / W[0, 0]
        p_t = -math.copysign(min(mu * p_n, abs(vt) / W[1, 1]), vt)
        np.testing.assert_allclose(c.impact.impulse_N_s, [p_n, p_t], rtol=1e-12)


def c_inputs(changes, name):
    return changes.get(name, DEFAULTS[name])


def test_elastic_frictionless_keeps_energy():
    c = collide(inputs(restitution=1.0, friction_coefficient=0.0, omega1_rad_s=4.0))
    assert abs(c.impact.energy_loss_J) <= 1e-12 * c.energy_before_J
    assert abs(sum(d.kinetic_energy_J for d in c.after) - c.energy_before_J) <= 1e-12 * c.energy_before_J
    assert c.after[0].spin_rad_s == 4.0  # no friction: spins untouched
    check_conservation(c)


def test_plastic_impact_leaves_no_normal_separation():
    c = collide(inputs(restitution=0.0))
    d1, d2 = c.after
    vn_after = relative_contact_velocity(d1, d2, c.normal, c.tangent, c.contact_point_m)[0]
    assert abs(vn_after) <= 1e-12 * abs(c.contact_velocity_m_s[0])
    check_conservation(c)


def test_high_friction_oblique_impact_sticks():
    c = collide(inputs(friction_coefficient=1.5, line_of_centres_deg=60.0))
    assert c.impact.slip_state == "stuck"
    d1, d2 = c.after
    vt_after = relative_contact_velocity(d1, d2, c.normal, c.tangent, c.contact_point_m)[1]
    assert abs(vt_after) <= 1e-12 * np.linalg.norm(c.contact_velocity_m_s)
    check_conservation(c)


@pytest.mark.parametrize("angle_deg", [89.9, 89.999999])
def test_grazing_impact(angle_deg):
    # v2 − v1 = (−4, 0): the normal approach speed is 4 cos β, down to 7e-8 m/s.
    c = collide(inputs(line_of_centres_deg=angle_deg, friction_coefficient=0.5))
    assert c.contact_velocity_m_s[0] == pytest.approx(-4.0 * math.cos(math.radians(angle_deg)), rel=1e-9)
    assert np.linalg.norm(c.impulse_N_s) <= 4.0 * abs(c.contact_velocity_m_s[0])  # the impulse vanishes with the approach
    check_conservation(c)


plane = st.floats(-20.0, 20.0)


@settings(max_examples=300, deadline=None)
@given(
    m1=st.floats(0.01, 1000.0), m2=st.floats(0.01, 1000.0), r1=st.floats(0.01, 10.0), r2=st.floats(0.01, 10.0),
    v1=st.tuples(plane, plane), v2=st.tuples(plane, plane), w1=st.floats(-50.0, 50.0), w2=st.floats(-50.0, 50.0),
    beta=st.floats(-180.0, 180.0), e=st.floats(0.0, 1.0), mu=st.floats(0.0, 10.0),
)  # fmt: skip
@example(m1=5.0, m2=20.0, r1=4.0, r2=1.0, v1=(0.0, 1.0), v2=(0.0, 1.0), w1=6.983523722197165e-162, w2=0.0, beta=92.0, e=1.0,
         mu=0.0)  # an approach of 1e-163 m/s: its works underflowed before the law was scaled  # fmt: skip
@example(m1=6.0, m2=12.0, r1=3.0, r2=1.0, v1=(0.0, -1.0), v2=(0.0, 0.0), w1=1.0, w2=0.0, beta=-11.0,
         e=1.1907349770501229e-161, mu=0.0)  # e² underflowed in the restitution phase's root: a division by zero  # fmt: skip
@example(m1=6.0, m2=12.0, r1=3.0, r2=1.0, v1=(0.0, -1.0), v2=(0.0, 0.0), w1=1.0, w2=0.0, beta=-11.0,
         e=1.1907349770501229e-161, mu=1.7207033471796733e-154)  # the same, then an absurd slip-stop impulse  # fmt: skip
def test_every_impact_conserves_momenta_and_never_creates_energy(m1, m2, r1, r2, v1, v2, w1, w2, beta, e, mu):
    values = dict(m1_kg=m1, m2_kg=m2, r1_m=r1, r2_m=r2, v1_m_s=[*v1, 0.0], v2_m_s=[*v2, 0.0], omega1_rad_s=w1,
                  omega2_rad_s=w2, line_of_centres_deg=beta, restitution=e, friction_coefficient=mu)  # fmt: skip
    try:
        validated = EXAMPLE.inputs.validate(values)
    except ParameterError as exc:
        assert exc.field == "v2_m_s" and "not approaching" in exc.message
        assume(False)
    c = collide(validated)
    assert c.impact.slip_state in ("slid throughout", "stuck")  # a diagonal W never reverses the slip
    check_conservation(c)
    outputs = EXAMPLE.solve(validated).outputs
    assert outputs["slip_state"] in SLIP_STATES
    assert outputs["v1_after_m_s"][2] == 0.0 and outputs["impulse_N_s"][2] == 0.0


@pytest.mark.parametrize(
    "changes, field",
    [
        ({"m1_kg": -1.0}, "m1_kg"),
        ({"r2_m": 0.0}, "r2_m"),
        ({"v1_m_s": [1.0, math.inf, 0.0]}, "v1_m_s"),
        ({"v2_m_s": [-1.0, 0.0, 0.5]}, "v2_m_s"),
        ({"restitution": 1.2}, "restitution"),
        ({"friction_coefficient": -0.1}, "friction_coefficient"),
        ({"v1_m_s": [-3.0, 0.0, 0.0]}, "v2_m_s"),  # separating at contact: no impact
        ({"line_of_centres_deg": 90.0}, "v2_m_s"),  # sliding past each other: no normal approach
    ],
)
def test_bad_input_names_the_field(changes, field):
    with pytest.raises(ParameterError) as info:
        EXAMPLE.inputs.validate(changes)
    assert info.value.field == field


def test_solution_outputs_and_units():
    solution = EXAMPLE.solve(DEFAULTS)
    assert set(solution.outputs) == set(EXAMPLE.output_units)
    assert set(solution.outputs) >= {"v1_after_m_s", "v2_after_m_s", "omega1_after_rad_s", "omega2_after_rad_s", "impulse_N_s", "energy_loss_J", "slip_state"}
    for step in solution.as_dict()["steps"]:
        assert set(step["values"]) == set(step["units"])
