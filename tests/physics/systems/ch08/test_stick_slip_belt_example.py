"""The stick–slip worked example against the scene's integrated model, which locates every mode change as an event.

Independent computation: :func:`~app.physics.systems.ch08.stick_slip_belt.transitions` integrates the block's
equations of motion (Dormand–Prince at rtol 1e-12, events located by root finding) from a start on the belt at
the example's sticking point, and records each break-loose and each re-stick with the state there and the energy
dissipated so far. The example chains closed forms. Their difference is the integrator's: at rtol 1e-12 event
times and positions come out within 3e-13 of the period and of x_break (measured over three cycles in these
cases), so 1e-10 of those scales is the tolerance (300 times the measured error, for other platforms' round-off),
and 1e-10 of the energy scale ½(μ_s N)²/k + ½ m v_b² for the heat and the belt's work.
"""

from __future__ import annotations

import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch08 import stick_slip_belt as belt
from app.physics.systems.ch08.stick_slip_belt_example import EXAMPLE

TOL = 1e-10

CASES = [
    {},
    {"belt_speed_m_s": -1.2, "mu_kinetic": 0.1},
    {"mu_static": 1.5, "mu_kinetic": 0.2, "stiffness_N_m": 400.0},
    {
        "mass_kg": 12.0,
        "stiffness_N_m": 5.0,
        "belt_speed_m_s": 0.05,
        "mu_static": 0.3,
        "mu_kinetic": 0.29,
        "g_m_s2": 1.62,
    },
]


@pytest.mark.parametrize("changes", CASES)
def test_the_cycle_matches_the_integrated_model(changes):
    p = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(p).outputs
    params = {**belt.PARAMETERS.defaults(), **p, "x0_m": out["stick_position_m"], "v0_m_s": p["belt_speed_m_s"]}
    assert belt.initial_state(params)[belt.MODE] == belt.STICK
    period, x_scale = out["period_s"], abs(out["break_position_m"])
    events = belt.transitions(params, t_end_s=3.2 * period, rtol=1e-12)
    kinds = [e.index for e in events][:6]  # three whole cycles (a fourth may have begun)
    assert kinds == [belt.STICK_BREAKS, belt.SLIP_STOPS] * 3, kinds
    times = [0.0] + [e.t_s for e in events]
    for cycle in range(3):
        stick = times[2 * cycle + 1] - times[2 * cycle]
        slip = times[2 * cycle + 2] - times[2 * cycle + 1]
        assert stick == pytest.approx(out["stick_time_s"], abs=TOL * period)
        assert slip == pytest.approx(out["slip_time_s"], abs=TOL * period)
        broke, stuck = events[2 * cycle].state, events[2 * cycle + 1].state
        assert broke[belt.X] == pytest.approx(out["break_position_m"], abs=TOL * x_scale)
        assert stuck[belt.X] == pytest.approx(out["stick_position_m"], abs=TOL * x_scale)
    normal = p["mass_kg"] * p["g_m_s2"]
    energy_scale = (
        0.5 * (p["mu_static"] * normal) ** 2 / p["stiffness_N_m"] + 0.5 * p["mass_kg"] * p["belt_speed_m_s"] ** 2
    )
    heat = events[3].state[belt.DISSIPATED] - events[1].state[belt.DISSIPATED]  # one whole cycle, re-stick to re-stick
    assert out["dissipated_per_cycle_J"] == pytest.approx(heat, abs=TOL * energy_scale)
    belt_work = events[3].state[belt.BELT_WORK] - events[1].state[belt.BELT_WORK]
    assert belt_work == pytest.approx(heat, abs=TOL * energy_scale)  # the check step's balance, integrated


def test_the_check_step_balances():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["W_belt"] == pytest.approx(check.values["E_diss"], rel=1e-12)


def test_inputs_without_a_cycle_are_refused():
    with pytest.raises(ParameterError, match="at rest"):
        EXAMPLE.inputs.validate({"belt_speed_m_s": 0.0})
    with pytest.raises(ParameterError, match="μ_k"):
        EXAMPLE.inputs.validate({"mu_static": 0.4, "mu_kinetic": 0.4})
    with pytest.raises(ParameterError):
        EXAMPLE.inputs.validate({"mu_static": 0.3, "mu_kinetic": 0.5})
    with pytest.raises(ParameterError, match="at rest"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "belt_speed_m_s": 0.0})
