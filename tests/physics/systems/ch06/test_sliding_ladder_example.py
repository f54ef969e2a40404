"""The sliding-ladder worked example against the scene's own model and the smooth-contact closed form.

The example solves its three Newton–Euler equations as a 3×3 linear system (or, held, the statics with an equal
share of each friction limit); the scene's integrated model computes the same quantities by eliminating the forces
by hand (:func:`~app.physics.systems.ch06.sliding_ladder.contact_dynamics`, a separate code path used by the
integrator). Both are a few dozen floating-point operations on O(1) numbers, so they agree to round-off: 1e-12 of
the scales g/L (rad/s²) and m g (N) leaves some 10³ ulps. Without friction the closed forms
θ̈ = −(3g/2L) cos θ₀, N_A = (3/4) m g sin θ₀ cos θ₀ and N_B = m g (1 − (3/4) cos² θ₀) must hold to the same tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06 import sliding_ladder as model
from app.physics.systems.ch06.sliding_ladder_example import EXAMPLE, HELD, SLIDES

RTOL = 1e-12

CASES = [
    {},
    {"angle0_deg": 45.0, "mu_floor": 0.3},
    {"angle0_deg": 45.0, "mu_floor": 0.2, "mu_wall": 0.5, "length_m": 2.5, "mass_kg": 60.0},
    {"angle0_deg": 60.0, "mu_floor": 0.3, "mu_wall": 0.2},  # the scene's "held" preset
    {"angle0_deg": 89.9, "g_m_s2": 1.62},
    {"angle0_deg": 12.0, "mu_floor": 1.0, "mu_wall": 1.0},  # held: 1/(2 tan 12° + 1) = 0.70
    {"angle0_deg": 20.0, "mu_floor": 0.5, "mu_wall": 0.1},  # slides: 1/(2 tan 20° + 0.1) = 1.19
]


@pytest.mark.parametrize("changes", CASES)
def test_the_example_matches_the_scene_model(changes):
    p = EXAMPLE.inputs.validate(changes)
    outputs = EXAMPLE.solve(p).outputs
    y = model.initial_state(p)
    out = np.empty(model.N_CONTACT)
    model.contact_dynamics(y, model.kernel_parameters(p), out)
    m, g, length = p["mass_kg"], p["g_m_s2"], p["length_m"]
    assert (outputs["held"] == HELD) == model.friction_holds(p)
    assert outputs["angular_acceleration_rad_s2"] == pytest.approx(out[model.C_ANGULAR_ACC], abs=RTOL * g / length)
    for name, index in (
        ("wall_force_N", model.C_WALL_N),
        ("floor_force_N", model.C_FLOOR_N),
        ("wall_friction_N", model.C_WALL_FRICTION),
        ("floor_friction_N", model.C_FLOOR_FRICTION),
    ):
        assert outputs[name] == pytest.approx(out[index], abs=RTOL * m * g), name
    check = EXAMPLE.solve(p).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["theta_ddot_about_I"] == pytest.approx(
        check.values["theta_ddot_Newton_Euler"], abs=RTOL * g / length
    )


@pytest.mark.parametrize("angle", [5.0, 30.0, 60.0, 85.0])
def test_smooth_contacts_match_the_closed_form(angle):
    p = EXAMPLE.inputs.validate({"angle0_deg": angle, "mass_kg": 7.0, "length_m": 3.0})
    outputs = EXAMPLE.solve(p).outputs
    theta, m, g, length = math.radians(angle), 7.0, p["g_m_s2"], 3.0
    assert outputs["angular_acceleration_rad_s2"] == pytest.approx(-1.5 * g * math.cos(theta) / length, rel=RTOL)
    assert outputs["wall_force_N"] == pytest.approx(0.75 * m * g * math.sin(theta) * math.cos(theta), rel=RTOL)
    assert outputs["floor_force_N"] == pytest.approx(m * g * (1.0 - 0.75 * math.cos(theta) ** 2), rel=RTOL)


def test_the_holding_limit_is_where_sliding_starts():
    # Just below μ_f,hold the ladder slides with θ̈ → 0⁻; at it, it is held.
    p = EXAMPLE.inputs.validate({"angle0_deg": 60.0, "mu_wall": 0.2})
    hold = EXAMPLE.solve(p).outputs["mu_floor_to_hold"]
    below = EXAMPLE.solve({**p, "mu_floor": hold * (1 - 1e-6)}).outputs
    assert below["held"] == SLIDES and -1e-4 < below["angular_acceleration_rad_s2"] < 0.0
    assert EXAMPLE.solve({**p, "mu_floor": min(hold * (1 + 1e-9), 1.0)}).outputs["held"] == HELD


def test_impossible_inputs_are_refused():
    # Within the ranges every combination is possible (held or sliding); μ_f above 1 is refused: beyond 4/3 the
    # sliding equations can have no consistent solution (Painlevé), which this example does not treat.
    with pytest.raises(ParameterError):
        EXAMPLE.inputs.validate({"mu_floor": 1.5})
    with pytest.raises(ParameterError):
        EXAMPLE.inputs.validate({"angle0_deg": 90.0})
