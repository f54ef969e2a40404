"""Events with reset maps (app/physics/solvers/system.py ``Events``, Dormand–Prince), on a bouncing ball.

A ball dropped from rest at height h₀ under gravity g bounces with restitution
e: event y = 0 falling, reset v ← −e v. Closed form: first impact at
t₀ = √(2h₀/g) with speed v₀ = √(2 g h₀); after bounce k the speed is eᵏ v₀, the
flight lasts 2 eᵏ v₀ / g and the apex is h₀ e²ᵏ. Between impacts the motion is a
parabola, which Dormand–Prince integrates exactly (up to round-off), so the
tolerances below measure the event location and the restart alone.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from app.physics.solvers import DormandPrince, Events, OdeSystem, make_integrator, simulate
from app.physics.solvers.kernels import EVENTS_SIGNATURE, RESET_SIGNATURE, RHS_SIGNATURE, kernel

G_M_S2, RESTITUTION, H0_M = 9.81, 0.8, 1.0
FLOOR, APEX = 0, 1  # event indices


@kernel(RHS_SIGNATURE)
def falling_rhs(t, y, p, dydt):
    """y = [height (m), vertical velocity (m/s)], p = [g (m/s²), e]."""
    dydt[0] = y[1]
    dydt[1] = -p[0]


@kernel(EVENTS_SIGNATURE)
def floor_and_apex(t, y, p, g_out):
    """Event 0: height (floor contact); event 1: vertical velocity (apex where it falls through 0)."""
    g_out[0] = y[0]
    g_out[1] = y[1]


@kernel(RESET_SIGNATURE)
def bounce(t, y, p, index):
    """At the floor the normal velocity reverses, scaled by the restitution e = p[1]."""
    if index == 0:
        y[1] = -p[1] * y[1]


BALL = OdeSystem(
    rhs=falling_rhs, parameters=np.array([G_M_S2, RESTITUTION]), state_names=("height_m", "velocity_m_s"),
    events=Events(
        floor_and_apex, directions=(-1, -1), terminal=(False, False), reset=bounce, resets=(True, False),
        # The parabola has no local error, so unbounded steps would grow past whole flights
        # (the sixth lasts 0.24 s) and skip impacts; 0.05 s puts ≥ 4 checks in every flight.
        max_step_s=0.05,
    ),
)
Y0 = np.array([H0_M, 0.0])
T_END_S = 3.0  # six impacts; they accumulate at t ≈ 4.06 s


def closed_form_impacts(n: int) -> np.ndarray:
    v0 = math.sqrt(2.0 * G_M_S2 * H0_M)
    flights = [2.0 * RESTITUTION**k * v0 / G_M_S2 for k in range(1, n)]
    return math.sqrt(2.0 * H0_M / G_M_S2) + np.concatenate([[0.0], np.cumsum(flights)])


def run(system: OdeSystem, *, backend: str = "numba"):
    integrator = DormandPrince(rtol=1e-10, max_steps=20_000)
    return simulate(system, integrator, Y0, t_end_s=T_END_S, frame_rate_hz=60.0, backend=backend)


@pytest.mark.parametrize("backend", ["numba", "python"])
def test_bounce_times_and_apex_heights_match_the_closed_form(backend):
    result = run(BALL, backend=backend)
    assert result.status == "ok"
    impacts = np.array([e.t_s for e in result.events if e.index == FLOOR])
    apexes = [e for e in result.events if e.index == APEX]
    expected = closed_form_impacts(6)
    assert len(impacts) == 6 and expected[-1] < T_END_S < expected[-1] + 2 * RESTITUTION**6 * math.sqrt(2 * G_M_S2 * H0_M) / G_M_S2
    # Observed error ≤ 4e-15 s: the parabola is integrated exactly and the Illinois iteration stops
    # at 1e-13 of a step (~0.1 s). 1e-11 s allows that location error to add up over six bounces.
    np.testing.assert_allclose(impacts, expected, rtol=0.0, atol=1e-11)
    # Every impact lands at the closed-form speed e^k v0 (before the reset reverses it).
    v0 = math.sqrt(2.0 * G_M_S2 * H0_M)
    speeds = [-e.state[1] for e in result.events if e.index == FLOOR]
    np.testing.assert_allclose(speeds, v0 * RESTITUTION ** np.arange(6), rtol=1e-11)
    # Apex k, e^k v0 / g after impact k, at height h0 e^(2k): six of them before 3 s (the last at 2.998 s).
    apex_times = expected + v0 * RESTITUTION ** np.arange(1, 7) / G_M_S2
    assert len(apexes) == 6 and apex_times[-1] < T_END_S
    np.testing.assert_allclose([e.t_s for e in apexes], apex_times, rtol=0.0, atol=1e-11)
    heights = np.array([e.state[0] for e in apexes])
    np.testing.assert_allclose(heights, H0_M * RESTITUTION ** (2 * np.arange(1, 7)), rtol=0.0, atol=1e-11)
    # No frame is below the floor (observed lowest frame 1.5e-3 m: frames fall between impacts).
    assert result.states[:, 0].min() >= 0.0


def test_without_the_reset_map_the_ball_falls_through_the_floor():
    # Same events, none of them resetting: the floor contact is only recorded. The ball crosses
    # y = 0 at the closed-form time and keeps falling, so it is deep below the floor at the end:
    # the reset map, not the event, is what makes the floor a floor.
    no_reset = dataclasses.replace(BALL, events=dataclasses.replace(BALL.events, reset=None, resets=None))
    result = run(no_reset)
    assert result.status == "ok"
    crossings = [e.t_s for e in result.events if e.index == FLOOR]
    assert crossings == pytest.approx([closed_form_impacts(1)[0]], abs=1e-11)
    assert result.states[-1, 0] < -30.0  # free fall for 3 s from 1 m: 1 − ½ g t² = −43.1 m


def test_a_terminal_event_stops_at_the_first_impact():
    terminal = dataclasses.replace(
        BALL, events=Events(floor_and_apex, directions=(-1, -1), terminal=(True, False))
    )
    result = run(terminal)
    assert result.status == "event" and result.ok
    assert result.t_event_s == pytest.approx(closed_form_impacts(1)[0], abs=1e-11)


def test_methods_without_event_support_refuse_the_system():
    with pytest.raises(ValueError, match="rk4 does not handle events"):
        simulate(BALL, make_integrator("rk4", steps_per_frame=4), Y0, t_end_s=1.0, frame_rate_hz=60.0)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (dict(directions=(2,), terminal=(False,)), "direction"),
        (dict(directions=(-1,), terminal=(False, True)), "terminal has 2 entries"),
        (dict(directions=(-1,), terminal=(False,), resets=(True,)), "reset is None"),
        (dict(directions=(-1,), terminal=(True,), reset=bounce, resets=(True,)), "not both"),
    ],
)
def test_bad_event_declarations_are_rejected(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Events(floor_and_apex, **kwargs)
