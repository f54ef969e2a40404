"""Physics checks of the integrator library (app/physics/integrators/).

Every check compares against something the library does not compute itself: a
closed form (forced harmonic oscillator, ball with linear drag via Lambert W),
or scipy's DOP853 at rtol = atol = 1e-12 driven by the model's pure-Python
right-hand side. Each tolerance is stated with the observed value it guards.

The kernels below live at module level so numba's on-disk cache (``cache=True``)
can key them to this file.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import RK45, solve_ivp
from scipy.special import lambertw

from app.physics.solvers import (
    METHODS,
    RK4,
    DormandPrince,
    LiveRun,
    OdeSystem,
    RigidBodySplitting,
    automatic_steps_per_frame,
    Events,
    dormand_prince,
    make_integrator,
    simulate,
)
from app.physics.solvers.controls import integrator_from_controls
from app.physics.solvers.kernels import EVENTS_SIGNATURE, RHS_SIGNATURE, kernel, no_projection
from app.physics.solvers.solve import MAX_STEPS_PER_FRAME, STEP_RATIO, STEPS_PER_BATCH
from app.physics.solvers.step_policy import choose_integrator
from app.physics.systems.ch10 import heavy_top

# --------------------------------------------------------------------------- kernels


@kernel(RHS_SIGNATURE)
def forced_oscillator_rhs(t, y, p, dydt):
    """x'' + ω² x = F cos(Ω t); y = [x, v], p = [ω, F, Ω]. Time-dependent, so stage times matter."""
    omega = p[0]
    dydt[0] = y[1]
    dydt[1] = -omega * omega * y[0] + p[1] * math.cos(p[2] * t)


@kernel(RHS_SIGNATURE)
def ball_rhs(t, y, p, dydt):
    """Vertical flight with linear drag: y = [z (m), v (m/s)], p = [g (m/s²), k (1/s)]."""
    dydt[0] = y[1]
    dydt[1] = -p[0] - p[1] * y[1]


@kernel(EVENTS_SIGNATURE)
def height_event(t, y, p, g_out):
    """Height above the ground (m): the event is z = 0."""
    g_out[0] = y[0]


@kernel(RHS_SIGNATURE)
def stiff_decay_rhs(t, y, p, dydt):
    """y' = λ y componentwise, p = [λ] (1/s)."""
    for i in range(y.shape[0]):
        dydt[i] = p[0] * y[i]


# --------------------------------------------------------------------------- problems

OMEGA, FORCE, DRIVE = 2.0, 1.0, 3.0  # rad/s, m/s², rad/s (off resonance)
OSC_Y0 = np.array([1.0, 0.0])  # m, m/s
OSCILLATOR = OdeSystem(
    rhs=forced_oscillator_rhs, parameters=np.array([OMEGA, FORCE, DRIVE]), state_names=("x", "v")
)


def oscillator_exact(t: np.ndarray) -> np.ndarray:
    """Closed form of the forced oscillator from OSC_Y0: homogeneous part + K cos Ωt."""
    t = np.asarray(t, dtype=float)
    K = FORCE / (OMEGA**2 - DRIVE**2)
    x0, v0 = OSC_Y0
    x = (x0 - K) * np.cos(OMEGA * t) + v0 / OMEGA * np.sin(OMEGA * t) + K * np.cos(DRIVE * t)
    v = -(x0 - K) * OMEGA * np.sin(OMEGA * t) + v0 * np.cos(OMEGA * t) - K * DRIVE * np.sin(DRIVE * t)
    return np.stack([x, v], axis=-1)


G, DRAG = 9.81, 0.3  # m/s², 1/s
BALL = OdeSystem(
    rhs=ball_rhs, parameters=np.array([G, DRAG]), state_names=("z", "v"),
    events=Events(height_event, directions=(-1,), terminal=(True,)),
)


def with_direction(system: OdeSystem, direction: int) -> OdeSystem:
    """``system`` with its one event watched in ``direction`` instead."""
    return dataclasses.replace(system, events=dataclasses.replace(system.events, directions=(direction,)))


def ball_height(z0: float, v0: float, t: float) -> float:
    vt = G / DRAG
    return z0 + (v0 + vt) / DRAG * (1.0 - math.exp(-DRAG * t)) - vt * t


def ball_velocity(v0: float, t: float) -> float:
    vt = G / DRAG
    return (v0 + vt) * math.exp(-DRAG * t) - vt


def ball_crossing_time(z0: float, v0: float, branch: int) -> float:
    """Roots of z(t) = 0 in closed form: with u = k t, u = c − d e^{−u}, so u = c + W(−d e^{−c}).

    Branch 0 is the later root (the falling crossing), branch −1 the earlier one
    (the rising crossing when the ball starts below ground).
    """
    vt = G / DRAG
    d = (v0 + vt) / vt
    c = DRAG * z0 / vt + d
    return float((c + lambertw(-d * math.exp(-c), branch).real) / DRAG)


TOP_PARAMS = heavy_top.PARAMETERS.defaults()
TOP = heavy_top.HeavyTop().system(TOP_PARAMS)
TOP_Y0 = heavy_top.initial_state(TOP_PARAMS)
FRAME_RATE = 60.0  # Hz


@pytest.fixture(scope="module")
def top_reference():
    """Heavy top (default parameters, spin 60 rad/s) over 1 s at every 1/60 s frame, by DOP853 at 1e-12."""

    def rhs(t, y):
        out = np.empty(7)
        TOP.rhs.python(t, y, TOP.parameters, out)
        return out

    t_eval = np.arange(61) / FRAME_RATE
    sol = solve_ivp(rhs, (0.0, 1.0), TOP_Y0, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t_eval)
    assert sol.success
    return sol.y.T


#: Step cap for the adaptive runs here (each needs < 1000): a broken error estimate then fails in
#: milliseconds instead of grinding through the default 2 million steps in the Python twin.
MAX_TEST_STEPS = 20_000


def max_error(states: np.ndarray, exact: np.ndarray) -> float:
    return float(np.max(np.abs(states - exact)))


# --------------------------------------------------------------------------- 1. orders

#: What each registered method claims (Integrator.order); the measurements below must agree (splitting6 and
#: splitting8 on the heavy top against its quadrature: tests/physics/solvers/test_splitting_orders.py).
DECLARED_ORDER = {"rk4": 4, "splitting2": 2, "splitting4": 4, "dopri5": 5, "splitting6": 6, "splitting8": 8}


def test_every_registered_method_has_a_convergence_test():
    # A new method in the registry must get an entry (and so a measured order) here.
    assert set(METHODS) == set(DECLARED_ORDER)
    for method, order in DECLARED_ORDER.items():
        assert make_integrator(method, steps_per_frame=1).order == order


@pytest.mark.parametrize(
    ("method", "problem"),
    [("rk4", "oscillator"), ("rk4", "heavy_top"), ("splitting2", "heavy_top"), ("splitting4", "heavy_top")],
)
def test_fixed_step_methods_converge_at_their_declared_order(method, problem, request):
    if problem == "oscillator":
        # Forced oscillator over 2 s sampled at 10 Hz: h·ω = 0.1, 0.05, 0.025.
        system, y0, t_end, rate = OSCILLATOR, OSC_Y0, 2.0, 10.0
        exact = oscillator_exact(np.arange(21) / rate)
    else:
        # Heavy top over 1 s at 60 Hz: h·ω3 = 0.5, 0.25, 0.125 against DOP853 at 1e-12.
        system, y0, t_end, rate = TOP, TOP_Y0, 1.0, FRAME_RATE
        exact = request.getfixturevalue("top_reference")
    errors = []
    for steps_per_frame in (2, 4, 8):
        integrator = make_integrator(method, steps_per_frame=steps_per_frame)
        result = simulate(system, integrator, y0, t_end_s=t_end, frame_rate_hz=rate)
        assert result.status == "ok"
        errors.append(max_error(result.states, exact))
    # Smallest error observed: 3.3e-8 (splitting4 on the top), 2.5e-8 (rk4, closed-form oscillator),
    # ~1e4 times the DOP853 reference's own error (3e-12 against DOP853 at 1e-14), so the
    # ratios measure the method alone.
    observed = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # Observed at the time of writing: rk4 4.02/4.01 (oscillator), 3.97/3.99 (top);
    # splitting2 2.00/2.00; splitting4 4.00/4.00. ±0.3 leaves room for pre-asymptotic
    # terms; a wrong coefficient drops the order by at least one.
    declared = integrator.order
    assert declared == DECLARED_ORDER[method]
    assert np.all(np.abs(observed - declared) <= 0.3), f"{method} on {problem}: errors {errors}, orders {observed}"


def test_dopri5_error_tracks_rtol():
    t = np.arange(101) / 10.0  # 10 s at 10 Hz, ~3 periods of the free part
    rtols = [1e-4, 1e-6, 1e-8, 1e-10]
    errors = []
    for rtol in rtols:
        result = simulate(OSCILLATOR, make_integrator("dopri5", rtol=rtol), OSC_Y0, t_end_s=10.0, frame_rate_hz=10.0)
        assert result.status == "ok"
        errors.append(max_error(result.states, oscillator_exact(t)))
    errors = np.array(errors)
    # Tighter tolerance, smaller error -- strictly, at every step of 100x.
    assert np.all(np.diff(errors) < 0.0), errors
    # The state is O(1) (|x| ≤ 1.2 m, |v| ≤ 2.4 m/s); observed error / rtol = 7.8, 5.2, 4.9, 4.7.
    # Global error accumulates local errors held to rtol, so a few × rtol is expected; 100×
    # is the usual bound for a well-behaved non-stiff problem over a few periods.
    assert np.all(errors <= 100.0 * np.array(rtols)), errors / rtols
    # Tolerance proportionality: local error held to rtol with local extrapolation gives global
    # error ∝ rtol. Observed log-log slope 1.04; [0.7, 1.3] still flags a wrong controller exponent.
    slope = np.polyfit(np.log10(rtols), np.log10(errors), 1)[0]
    assert 0.7 <= slope <= 1.3, slope


def test_dopri5_tableau_is_scipys_rk45():
    # The docstring promises the Dormand–Prince pair and Shampine's dense output as in scipy's
    # RK45; the numbers are rationals in double precision, so they must agree exactly.
    for name in ("A", "B", "C", "E", "P"):
        np.testing.assert_array_equal(getattr(dormand_prince, name), getattr(RK45, name), err_msg=name)


# --------------------------------------------------------------------------- 2. twins

@pytest.mark.parametrize("method", ["rk4", "splitting2", "splitting4", "dopri5", "splitting6", "splitting8"])
def test_python_twin_matches_numba(method):
    integrator = make_integrator(method, steps_per_frame=4)
    if method == "dopri5":
        # 380 steps needed here; the cap makes a broken controller fail fast in the Python twin.
        integrator = DormandPrince(rtol=1e-9, max_steps=MAX_TEST_STEPS)
    runs = {
        backend: simulate(TOP, integrator, TOP_Y0, t_end_s=0.25, frame_rate_hz=FRAME_RATE, backend=backend)
        for backend in ("numba", "python")
    }
    compiled, python = runs["numba"], runs["python"]
    assert compiled.status == python.status == "ok"
    assert compiled.steps == python.steps and compiled.rhs_evals == python.rhs_evals
    # Same source, same IEEE operations in the same order: at the time of writing the two runs
    # are bit-identical for all four methods. 1e-13 of each component's scale (q ~ 1, ω3 = 60 rad/s)
    # allows for a libm/LLVM difference in the last bit of a sin/cos, amplified over 15 frames.
    scale = np.max(np.abs(python.states), axis=0)
    assert np.all(np.abs(compiled.states - python.states) <= 1e-13 * scale)


# --------------------------------------------------------------------------- 3. dense output

@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_dopri5_dense_output_matches_closed_form_inside_steps(rtol):
    rng = np.random.default_rng(20240611)
    t_out = np.sort(rng.uniform(0.0, 10.0, 1000))
    y = OSC_Y0.copy()
    y_out = np.full((t_out.size, 2), np.nan)
    outcome = DormandPrince(rtol=rtol, max_steps=MAX_TEST_STEPS).solve(OSCILLATOR, 0.0, y, t_out, y_out)
    assert outcome.status == "ok" and outcome.frames_done == t_out.size
    # Far more outputs than steps (observed 121 and 425 steps for 1000 random times), so
    # most outputs come from the interpolant, not from step ends.
    assert outcome.steps < t_out.size / 2
    # Shampine's quartic interpolant is accurate to the step's own error; observed
    # max error / rtol = 5.2 (1e-6) and 4.8 (1e-9), like the step ends. Bound: 100 × rtol.
    error = max_error(y_out, oscillator_exact(t_out))
    assert error <= 100.0 * rtol, error / rtol
    # y ends at the last output time.
    np.testing.assert_allclose(y, oscillator_exact(t_out[-1]), rtol=0.0, atol=100.0 * rtol)


# --------------------------------------------------------------------------- 4. events

@pytest.mark.parametrize(("z0", "v0"), [(10.0, 0.0), (0.0, 20.0), (-5.0, 20.0)])
@pytest.mark.parametrize("backend", ["numba", "python"])
def test_terminal_event_finds_the_landing(z0, v0, backend):
    # (10, 0): dropped; (0, 20): thrown up from the ground (the event function is 0 at t = 0, which must not count);
    # (-5, 20): thrown up from a pit, so z rises through 0 first -- ignored, direction is −1.
    t_land = ball_crossing_time(z0, v0, branch=0)
    assert abs(ball_height(z0, v0, t_land)) < 1e-12 and ball_velocity(v0, t_land) < 0.0
    t_out = np.linspace(0.1, 10.0, 100)
    y = np.array([z0, v0])
    y_out = np.full((t_out.size, 2), np.nan)
    outcome = DormandPrince(rtol=1e-10, max_steps=MAX_TEST_STEPS).solve(
        BALL, 0.0, y, t_out, y_out, backend=backend
    )
    assert outcome.status == "event"
    # Observed relative error 2e-12..3e-12: the Illinois iteration converges to 1e-13 of the
    # step on an interpolant good to ~rtol = 1e-10; the required 1e-9 is 300× the observed.
    assert abs(outcome.t_event_s - t_land) <= 1e-9 * t_land
    # At the event the state is on the ground (observed |z| ≤ 2.2e-16 m) ...
    assert abs(y[0]) < 1e-9
    # ... moving down at the closed-form speed (observed ≤ 7e-12 relative; 1e-8 = 100 × rtol).
    assert abs(y[1] - ball_velocity(v0, t_land)) <= 1e-8 * abs(y[1])
    # Outputs up to the event are written (and right); none after it.
    before = t_out < outcome.t_event_s
    assert outcome.frames_done == int(np.count_nonzero(before))
    assert np.all(np.isnan(y_out[~before]))
    exact = np.array([[ball_height(z0, v0, t), ball_velocity(v0, t)] for t in t_out[before]])
    np.testing.assert_allclose(y_out[before], exact, rtol=0.0, atol=1e-8)  # O(10 m) state, 100 × rtol


def test_event_direction_is_respected():
    z0, v0 = -5.0, 20.0  # starts in a pit: crosses z = 0 rising at t ≈ 0.28 s, falling at t ≈ 3.10 s
    t_rise = ball_crossing_time(z0, v0, branch=-1)
    t_fall = ball_crossing_time(z0, v0, branch=0)
    assert 0.0 < t_rise < t_fall and ball_velocity(v0, t_rise) > 0.0
    t_out = np.linspace(0.1, 2.0, 20)  # ends before the fall
    cases = {-1: (BALL, None), +1: (with_direction(BALL, +1), t_rise), 0: (with_direction(BALL, 0), t_rise)}
    for direction, (system, t_expected) in cases.items():
        y = np.array([z0, v0])
        y_out = np.full((t_out.size, 2), np.nan)
        outcome = DormandPrince(rtol=1e-10, max_steps=MAX_TEST_STEPS).solve(system, 0.0, y, t_out, y_out)
        if t_expected is None:
            # Falling-only: the rising crossing is ignored and the run reaches the last output.
            assert outcome.status == "ok" and outcome.t_event_s is None
            assert outcome.frames_done == t_out.size and np.all(np.isfinite(y_out))
            assert y[0] > 0.0
        else:
            assert outcome.status == "event", direction
            assert abs(outcome.t_event_s - t_expected) <= 1e-9 * t_expected, direction
            assert abs(y[0]) < 1e-9 and y[1] > 0.0


def test_events_are_ignored_when_switched_off():
    # With events=False the same run passes the landing and writes every output.
    t_out = np.linspace(0.1, 5.0, 50)
    y = np.array([10.0, 0.0])
    y_out = np.full((t_out.size, 2), np.nan)
    outcome = DormandPrince(rtol=1e-10, max_steps=MAX_TEST_STEPS).solve(BALL, 0.0, y, t_out, y_out, events=False)
    assert outcome.status == "ok" and outcome.frames_done == t_out.size
    assert y_out[-1, 0] < 0.0  # below ground: the event did not stop it
    assert abs(y_out[-1, 0] - ball_height(10.0, 0.0, 5.0)) <= 1e-8  # 100 × rtol on an O(10 m) state


# --------------------------------------------------------------------------- 5. projection hook

def test_rk4_projection_keeps_the_quaternion_unit():
    # 1000 steps of h = 1/240 s (h·ω3 = 0.25): RK4 alone does not preserve |q|.
    integrator = RK4(steps_per_frame=4)
    n_frames = 250
    projected = simulate(TOP, integrator, TOP_Y0, t_end_s=n_frames / FRAME_RATE, frame_rate_hz=FRAME_RATE)
    free = simulate(
        dataclasses.replace(TOP, project=no_projection), integrator, TOP_Y0,
        t_end_s=n_frames / FRAME_RATE, frame_rate_hz=FRAME_RATE,
    )
    assert projected.steps == free.steps == 1000
    norm_error = lambda r: np.max(np.abs(np.linalg.norm(r.states[:, :4], axis=1) - 1.0))  # noqa: E731
    # Dividing by the norm leaves |q| within a few ulp of 1 (observed 1.1e-16); 1e-14 is ~45 ulp.
    assert norm_error(projected) <= 1e-14
    # Same steps with the identity hook: observed drift 2.6e-5. Demanding > 1e-8 (a million
    # times the bound above) shows it is the hook, not RK4, that holds |q| = 1.
    assert norm_error(free) > 1e-8


# --------------------------------------------------------------------------- 6. blow-up

STIFF = OdeSystem(rhs=stiff_decay_rhs, parameters=np.array([-1e4]), state_names=("a", "b"))
STIFF_Y0 = np.array([1.0, 2.0])


def test_simulate_reports_a_blow_up_in_words():
    # h λ = −1e4/60 ≈ −167, far outside RK4's stability region: |R(hλ)| ≈ 3e7 per step, so the
    # state overflows after ~40 frames of the 60 asked for.
    result = simulate(STIFF, RK4(steps_per_frame=1), STIFF_Y0, t_end_s=1.0, frame_rate_hz=60.0)
    assert result.status == "non_finite" and not result.ok
    assert 1 < len(result.states) < 61
    assert np.all(np.isfinite(result.states)) and np.all(np.isfinite(result.t_s))
    assert len(result.t_s) == len(result.states)
    assert "steps per frame" in result.message and f"{result.t_s[-1]:.3f}" in result.message


def test_live_run_keeps_the_last_finite_state_and_pauses():
    run = LiveRun(STIFF, RK4(steps_per_frame=1), STIFF_Y0)
    frames = 0
    while run.advance(1 / 60) and frames < 1000:
        frames += 1
    assert 0 < frames < 1000
    assert not run.running and run.status == "non_finite"
    assert "steps per frame" in run.message
    assert np.all(np.isfinite(run.y))
    # The kept state is the one simulate() reaches in as many frames (same arithmetic).
    reference = simulate(STIFF, RK4(steps_per_frame=1), STIFF_Y0, t_end_s=1.0, frame_rate_hz=60.0)
    assert len(reference.states) == frames + 1
    np.testing.assert_array_equal(run.y, reference.states[-1])
    assert run.t_s == pytest.approx(frames / 60, rel=1e-12)
    # Paused: further calls do nothing.
    kept, t_kept = run.y.copy(), run.t_s
    assert run.advance(1 / 60) is False
    np.testing.assert_array_equal(run.y, kept)
    assert run.t_s == t_kept


def test_live_run_starts_afresh_when_the_frame_length_changes():
    # At 1/60 s frames the batch of 60 blows up at frame 41, far ahead of playback. At 1 µs frames
    # (h λ = −0.01, well inside RK4's stability region) nothing can blow up, so after the switch
    # the run must carry on from the current finite state instead of reporting the old failure.
    run = LiveRun(STIFF, RK4(steps_per_frame=1), STIFF_Y0, batch_frames=60)
    for _ in range(3):
        assert run.advance(1 / 60)
    assert run.advance(1e-6), run.message
    assert run.running and np.all(np.isfinite(run.y))


def _batches(run: LiveRun) -> list[int]:
    """Record the frames each of ``run``'s kernel calls computes (the batch sizes)."""
    sizes: list[int] = []
    run_frames = run.integrator.run_frames

    def recording(system, t0_s, y, frame_dt_s, n_frames, y_frames, **kwargs):
        sizes.append(n_frames)
        return run_frames(system, t0_s, y, frame_dt_s, n_frames, y_frames, **kwargs)

    run.integrator.run_frames = recording  # an instance attribute shadows the method
    return sizes


@pytest.mark.parametrize("steps_per_frame", [1, 12, 136, 137, 2048, 4096])
def test_a_live_batch_takes_at_most_its_step_budget_and_the_motion_does_not_depend_on_it(steps_per_frame):
    """One kernel call holds a scene worker's frame loop: a costly run computes fewer frames per call (one, past
    the budget), a cheap one the full batch; either way each frame is the state simulate() reaches (same arithmetic)."""
    frames = 40
    run = LiveRun(OSCILLATOR, RK4(steps_per_frame=steps_per_frame), OSC_Y0)
    sizes = _batches(run)
    states = [run.y.copy()]
    for _ in range(frames):
        assert run.advance(1 / FRAME_RATE)
        states.append(run.y.copy())
    expected_batch = max(1, min(run.batch_frames, STEPS_PER_BATCH // steps_per_frame))
    assert set(sizes) == {expected_batch} and sum(sizes) >= frames
    assert expected_batch * steps_per_frame <= max(STEPS_PER_BATCH, steps_per_frame)
    reference = simulate(OSCILLATOR, RK4(steps_per_frame=steps_per_frame), OSC_Y0, t_end_s=frames / FRAME_RATE, frame_rate_hz=FRAME_RATE)
    np.testing.assert_array_equal(np.array(states), reference.states[: frames + 1])


def test_an_adaptive_live_run_sizes_its_batches_from_the_steps_it_took():
    """Dormand–Prince: one frame first (its cost is unknown), then as many as the last batch's steps per frame
    allow; the batch sizes follow from step counts alone, so two runs from the same start are identical."""
    motions = []
    for _ in range(2):
        run = LiveRun(OSCILLATOR, DormandPrince(rtol=1e-12), OSC_Y0)
        sizes = _batches(run)
        states = []
        for _ in range(60):
            assert run.advance(1 / FRAME_RATE)
            states.append(run.y.copy())
        motions.append(np.array(states))
        assert sizes[0] == 1 and max(sizes) <= run.batch_frames and len(sizes) > 1
    np.testing.assert_array_equal(motions[0], motions[1])
    times = np.arange(1, 61) / FRAME_RATE
    np.testing.assert_allclose(motions[0], oscillator_exact(times), rtol=0, atol=1e-9)  # the closed form; rtol 1e-12 gives ~1e-11


# --------------------------------------------------------------------------- 7. automatic steps

@pytest.mark.parametrize("method", sorted(STEP_RATIO))
@pytest.mark.parametrize("rate", [0.0, 0.5, 6.0, 60.0, 377.0, 2000.0])
def test_automatic_steps_per_frame_follows_the_rule(method, rate):
    frame_dt = 1 / 60
    ratio = STEP_RATIO[method]
    n = automatic_steps_per_frame(method, rate, frame_dt)
    assert isinstance(n, int) and 1 <= n <= MAX_STEPS_PER_FRAME
    # h·ω ≤ ratio (the ceil subtracts 1e-9 to absorb round-off in ω·dt/ratio, so allow that).
    assert (frame_dt / n) * rate <= ratio * (1.0 + 1e-9)
    # ... and no more steps than that needs.
    if n > 1:
        assert (frame_dt / (n - 1)) * rate > ratio
    assert make_integrator(method, fastest_rate_rad_s=rate, frame_dt_s=frame_dt).steps_per_frame == n


def test_automatic_steps_per_frame_is_capped():
    for method in STEP_RATIO:
        assert automatic_steps_per_frame(method, 1e9, 1 / 60) == MAX_STEPS_PER_FRAME
        assert automatic_steps_per_frame(method, 0.0, 1 / 60) == 1


def test_automatic_steps_for_the_default_top():
    # ω_max from the energy bound: √(2 (E + m g l) / I_min) with E ≈ ½ I_a ω3² + m g l cos θ0,
    # i.e. the 60 rad/s spin plus what all the potential energy could add (61.5 rad/s).
    rate = heavy_top.HeavyTop().fastest_rate_rad_s(TOP_PARAMS, TOP_Y0)
    mgl = TOP_PARAMS["mass_kg"] * TOP_PARAMS["g_m_s2"] * TOP_PARAMS["cg_distance_m"]
    energy = 0.5 * TOP_PARAMS["I_axial"] * 60.0**2 + mgl * math.cos(math.radians(30.0))
    assert rate == pytest.approx(math.sqrt(2.0 * (energy + mgl) / TOP_PARAMS["I_axial"]), rel=1e-12)
    # RK4 then needs ceil(61.5 / 60 / 0.1) = 11 steps per frame.
    assert automatic_steps_per_frame("rk4", rate, 1 / 60) == 11


# --------------------------------------------------------------------------- 8. construction

@pytest.mark.parametrize("bad_rtol", [0.0, -1e-8, 1e-20, 0.5, math.nan, math.inf])
def test_bad_rtol_is_rejected_naming_the_field(bad_rtol):
    with pytest.raises(ValueError, match="rtol"):
        make_integrator("dopri5", rtol=bad_rtol)
    with pytest.raises(ValueError, match="rtol"):
        integrator_from_controls(
            {"method": "dopri5", "rtol": bad_rtol}, default_method="splitting4", fastest_rate_rad_s=60.0, frame_dt_s=1 / 60
        )


@pytest.mark.parametrize("bad_method", ["euler", "RK4", "", "dopri"])
def test_unknown_method_is_rejected_naming_the_field(bad_method):
    with pytest.raises(ValueError, match="method"):
        make_integrator(bad_method)
    with pytest.raises(ValueError, match="method"):
        integrator_from_controls({"method": bad_method}, default_method="rk4", fastest_rate_rad_s=1.0, frame_dt_s=1 / 60)


@pytest.mark.parametrize("bad_steps", [0, -3, 2.5])
def test_bad_steps_per_frame_is_rejected_naming_the_field(bad_steps):
    with pytest.raises(ValueError, match="steps_per_frame"):
        make_integrator("rk4", steps_per_frame=bad_steps)


def test_auto_means_the_models_default():
    model = heavy_top.HeavyTop()
    assert model.default_method == "splitting4"
    for controls in ({"method": "auto"}, {}):
        integrator = integrator_from_controls(
            controls, default_method=model.default_method, fastest_rate_rad_s=60.0, frame_dt_s=1 / 60
        )
        assert isinstance(integrator, RigidBodySplitting) and integrator.name == "splitting4"
        assert integrator.steps_per_frame == automatic_steps_per_frame("splitting4", 60.0, 1 / 60)
    # A model with an accuracy target: auto is the cheapest of its methods meeting the target (measured, see
    # tests/physics/solvers/test_step_choice.py), no longer always default_method — a splitting method here.
    integrator, choice = choose_integrator(model, TOP_PARAMS, {"method": "auto", "steps_per_frame": 0}, 1 / 60)
    assert isinstance(integrator, RigidBodySplitting) and integrator.name in model.methods
    assert choice.method == integrator.name and choice.estimated_error <= model.accuracy_target.error
    # An explicit choice wins over the default; steps_per_frame = 0 means automatic.
    chosen = integrator_from_controls({"method": "rk4", "steps_per_frame": 0}, default_method="splitting4",
                                      fastest_rate_rad_s=60.0, frame_dt_s=1 / 60)
    assert isinstance(chosen, RK4) and chosen.steps_per_frame == 10
    assert isinstance(integrator_from_controls({"method": "dopri5", "rtol": 1e-6}, default_method="splitting4",
                                               fastest_rate_rad_s=60.0, frame_dt_s=1 / 60), DormandPrince)
