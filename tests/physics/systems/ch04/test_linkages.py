"""Linkages and rolling (chapter 4), each checked against an independent computation.

- Four-bar positions against scipy's fsolve on the raw loop equations (from a
  guess 0.05 rad off), the branch against its geometric definition and against
  the textbook Freudenstein formula; rates and accelerations against finite
  differences of the positions; the crank's travel against brute-force
  sampling; behaviour through toggle and change points.
- Slider-crank against fsolve and finite differences; stroke and quick-return
  ratio against dense sampling.
- Cardan joint against a root-find of the cross's constraint u · v = 0 built
  here with scipy rotations; its speed ratio against finite differences, its
  span and its integral over a turn.
- Rolling: the contact point's velocity is zero to round-off, and the pose's
  finite differences reproduce ω, v_G and a stationary contact point.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, fsolve
from scipy.spatial.transform import Rotation

from app.physics.systems.ch04 import cardan_joint, four_bar, slider_crank
from app.physics.systems.ch04.crank_drive import CrankDrive
from app.physics.systems.ch04.four_bar import FourBar, FourBarLinkage, FourBarMotion
from app.physics.systems.ch04.rolling import SteadyRolling, SteadyRollingMotion

RNG_SEED = 20240604


def random_linkages(count: int, seed: int = RNG_SEED) -> list[FourBar]:
    """Random link lengths in [0.2, 2] m that can close somewhere."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        d, a, b, c = rng.uniform(0.2, 2.0, 4)
        try:
            out.append(FourBar(d, a, b, c))
        except ValueError:
            continue
    return out


def loop_equations(lengths, theta2):
    a, b, c, d = lengths

    def f(x):
        t3, t4 = x
        return [a * math.cos(theta2) + b * math.cos(t3) - d - c * math.cos(t4),
                a * math.sin(theta2) + b * math.sin(t3) - c * math.sin(t4)]

    return f


def angle_difference(x, y):
    return np.abs((np.asarray(x) - np.asarray(y) + np.pi) % (2 * np.pi) - np.pi)


def assembled_samples(linkage: FourBar, rng, count: int, *, min_sin_mu: float = 0.0):
    """(crank angle, positions per branch) at random crank angles where the loop closes with |sin μ| > min_sin_mu."""
    theta = rng.uniform(-np.pi, np.pi, count)
    mu = linkage.transmission_angle(theta)
    positions = {branch: linkage.positions(theta, branch) for branch in four_bar.BRANCHES}
    ok = np.isfinite(positions["open"].rocker_angle) & (np.abs(np.sin(mu)) > min_sin_mu)
    return theta[ok], ok, positions


# ---- four-bar positions ------------------------------------------------------------------


def test_four_bar_positions_match_an_independent_numerical_loop_closure_on_both_branches():
    """fsolve from a guess 0.05 rad away converges to the closed form to 1e-9 rad (its xtol is 1e-13)."""
    rng = np.random.default_rng(1)
    checked = 0
    for linkage in random_linkages(60):
        lengths = (linkage.crank_m, linkage.coupler_m, linkage.rocker_m, linkage.ground_m)
        theta, ok, positions = assembled_samples(linkage, rng, 8, min_sin_mu=0.05)
        for branch in four_bar.BRANCHES:
            pos = positions[branch]
            for theta2, t3, t4 in zip(theta, pos.coupler_angle[ok], pos.rocker_angle[ok]):
                guess = np.array([t3, t4]) + rng.choice([-0.05, 0.05], 2)
                solution, info, status, _ = fsolve(loop_equations(lengths, theta2), guess, full_output=True, xtol=1e-13)
                assert status == 1
                assert np.all(angle_difference(solution, [t3, t4]) < 1e-9), (linkage, branch, theta2)
                checked += 1
    assert checked > 300


def test_open_and_crossed_are_the_geometric_sides_and_the_textbook_freudenstein_roots():
    """Open: B left of the line A→O₄ (cross product > 0); its rocker angle is Freudenstein's
    θ₄ = 2 atan2(−B − √(B² − 4AC), 2A) (the 'minus' root), crossed the 'plus' root; to 1e-9 rad."""
    rng = np.random.default_rng(2)
    for linkage in random_linkages(40, seed=3):
        a, b, c, d = linkage.crank_m, linkage.coupler_m, linkage.rocker_m, linkage.ground_m
        theta, ok, positions = assembled_samples(linkage, rng, 10, min_sin_mu=0.05)
        k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
        A = np.cos(theta) - k1 - k2 * np.cos(theta) + k3
        B = -2.0 * np.sin(theta)
        C = k1 - (k2 + 1.0) * np.cos(theta) + k3
        root = np.sqrt(B * B - 4 * A * C)
        for branch, sign in (("open", -1.0), ("crossed", 1.0)):
            pos = positions[branch]
            to_o4 = np.array([d, 0.0]) - pos.crank_pin[ok]
            to_b = pos.rocker_pin[ok] - pos.crank_pin[ok]
            side = to_o4[:, 0] * to_b[:, 1] - to_o4[:, 1] * to_b[:, 0]
            assert np.all(side > 0) if branch == "open" else np.all(side < 0)
            freudenstein = 2.0 * np.arctan2(-B + sign * root, 2.0 * A)
            assert np.all(angle_difference(pos.rocker_angle[ok], freudenstein) < 1e-9)


def test_the_loop_closes_and_the_link_lengths_hold():
    linkage = FourBar(1.0, 0.3, 1.0, 0.9)
    theta = np.linspace(-np.pi, np.pi, 1001)
    for branch in four_bar.BRANCHES:
        pos = linkage.positions(theta, branch)
        assert np.max(linkage.loop_residual(pos)) < 1e-14
        assert np.allclose(np.linalg.norm(pos.rocker_pin - pos.crank_pin, axis=1), 1.0, atol=1e-14, rtol=0)
        assert np.allclose(np.linalg.norm(pos.rocker_pin - [1.0, 0.0], axis=1), 0.9, atol=1e-14, rtol=0)


# ---- four-bar rates -----------------------------------------------------------------------


def test_four_bar_rates_and_accelerations_match_finite_differences_of_the_positions():
    """Five-point central differences of the closed-form positions in the crank angle (ω₂ = 1.3 rad/s,
    α₂ = 0) at 240 random configurations with |sin μ| > 0.2, both assemblies. Rates with h = 1e-4 rad:
    truncation ~h⁴|θ⁽⁵⁾|/30 (measured ≤ 6e-10 relative), round-off ~ε/h ≈ 1e-12; tolerance 1e-8·(1 + |ω|).
    Accelerations with h = 3e-4 rad: truncation ~h⁴|θ⁽⁶⁾|/90 (measured ≤ 1.5e-7 relative), round-off
    ~5ε/h² ≈ 1e-8; tolerance 1e-6·(1 + |α|). (The errors fall as h⁴ when h shrinks, as they must if the
    linear solves are exact.)"""
    rng = np.random.default_rng(4)
    omega2 = 1.3
    checked = 0
    for linkage in random_linkages(40, seed=5):
        theta, ok, _ = assembled_samples(linkage, rng, 6, min_sin_mu=0.2)
        for branch in four_bar.BRANCHES:
            pos = linkage.positions(theta, branch)
            w3, w4, singular = linkage.rates(theta, pos.coupler_angle, pos.rocker_angle, omega2)
            assert not singular.any()
            a3, a4 = linkage.accelerations(theta, pos.coupler_angle, pos.rocker_angle, omega2, w3, w4, 0.0)
            for name, rate, accel in (("coupler_angle", w3, a3), ("rocker_angle", w4, a4)):
                def offsets(h, name=name):
                    base = getattr(pos, name)
                    return {k: angle_difference_signed(getattr(linkage.positions(theta + k * h, branch), name), base) for k in (-2, -1, 1, 2)}

                h = 1e-4
                f = offsets(h)
                first = (-f[2] + 8 * f[1] - 8 * f[-1] + f[-2]) / (12 * h) * omega2
                assert np.all(np.abs(first - rate) < 1e-8 * (1 + np.abs(rate)))
                h = 3e-4
                f = offsets(h)
                second = (-f[2] + 16 * f[1] + 16 * f[-1] - f[-2]) / (12 * h * h) * omega2**2  # f(0) = 0
                assert np.all(np.abs(second - accel) < 1e-6 * (1 + np.abs(accel)))
            checked += len(theta)
    assert checked > 200


def angle_difference_signed(x, y):
    return (np.asarray(x) - np.asarray(y) + np.pi) % (2 * np.pi) - np.pi


def test_motion_angles_are_continuous_in_time_and_their_rates_are_their_time_derivatives():
    """Double crank over 5 turns at 60 Hz: no frame-to-frame jump of 2π, winding of one turn per
    crank turn for crank, coupler and rocker, and the reported rates equal central differences
    in time (h = 1e-6 s: error ≲ 1e-9 rad/s) to 1e-6 rad/s."""
    params = dict(four_bar.PARAMETERS.defaults(), ground_m=0.3, crank_m=0.7, coupler_m=0.9, rocker_m=0.8, crank_speed_rad_s=2.0)
    motion = FourBarMotion.from_params(params)
    period = 2 * np.pi / 2.0
    t = np.arange(0, 5 * period, 1 / 60)
    state = motion.at(t)
    for name in ("crank_angle", "coupler_angle", "rocker_angle"):
        series = getattr(state, name)
        assert np.max(np.abs(np.diff(series))) < 0.5
    turns = motion.at(np.array([0.0, 5 * period]))
    for name in ("crank_angle", "coupler_angle", "rocker_angle"):
        assert getattr(turns, name)[1] - getattr(turns, name)[0] == pytest.approx(5 * 2 * np.pi, abs=1e-9)
    h = 1e-6
    plus, minus = motion.at(t + h), motion.at(t - h)
    for angle, rate in (("coupler_angle", "coupler_rate"), ("rocker_angle", "rocker_rate")):
        fd = (getattr(plus, angle) - getattr(minus, angle)) / (2 * h)
        assert np.max(np.abs(fd - getattr(state, rate))) < 1e-6


# ---- four-bar classification and travel --------------------------------------------------------


def test_grashof_class_agrees_with_brute_force_sampling_of_the_crank_travel():
    """Whether the loop closes at every one of 7200 crank angles (independent of the cos-bound
    formula) agrees with both the Grashof rule and the computed crank range; the computed arcs'
    ends are where sampling stops closing (to the sampling step)."""
    names = set()
    for linkage in random_linkages(300, seed=6):
        theta = np.linspace(-np.pi, np.pi, 7200, endpoint=False)
        closes = np.isfinite(linkage.positions(theta, "open").rocker_angle)
        grashof = linkage.grashof()
        crank_range = linkage.crank_range()
        names.add(grashof.name)
        assert closes.all() == crank_range.turns_fully == grashof.crank_turns_fully, linkage
        for lower, upper in crank_range.arcs_rad:
            inside = angle_difference(theta, 0.5 * (lower + upper)) <= 0.5 * (upper - lower) - 1e-3
            outside = angle_difference(theta, 0.5 * (lower + upper)) >= 0.5 * (upper - lower) + 1e-3
            assert closes[inside].all()
            if len(crank_range.arcs_rad) == 1:
                assert not closes[outside].any()
    assert names >= {"crank-rocker", "double-crank", "rocker-crank", "double-rocker", "non-Grashof"}


@pytest.mark.parametrize(
    "lengths, name",
    [
        ((1.0, 0.3, 1.0, 0.9), "crank-rocker"),
        ((0.3, 0.7, 0.9, 0.8), "double-crank"),
        ((1.0, 0.9, 0.8, 0.3), "rocker-crank"),
        ((1.0, 0.8, 0.35, 0.9), "double-rocker"),
        ((1.0, 0.4, 1.0, 0.4), "change point"),
        ((1.2, 0.9, 0.7, 0.6), "non-Grashof"),
    ],
)
def test_grashof_classes_of_textbook_examples(lengths, name):
    assert FourBar(*lengths).grashof().name == name


def test_a_linkage_that_cannot_close_is_refused_with_the_reason():
    with pytest.raises(ValueError, match=r"cannot be assembled.*ground, 10 m.*3 m"):
        FourBar(10.0, 1.0, 1.0, 1.0)
    params = dict(four_bar.PARAMETERS.defaults(), ground_m=1.2, crank_m=0.9, coupler_m=0.7, rocker_m=0.6, crank_angle0_deg=180.0)
    with pytest.raises(ValueError, match=r"cannot close with the crank at 180.0°.*-75.0° to 75.0°"):
        four_bar.PARAMETERS.validate(params)
    with pytest.raises(ValueError, match="branch"):
        FourBar(1.0, 0.3, 1.0, 0.9).positions(np.array([0.0]), "sideways")


# ---- toggle and change points --------------------------------------------------------------------


def non_grashof_motion() -> FourBarMotion:
    params = dict(four_bar.PARAMETERS.defaults(), ground_m=1.2, crank_m=0.9, coupler_m=0.7, rocker_m=0.6, crank_angle0_deg=0.0, crank_speed_rad_s=1.5)
    return FourBarMotion.from_params(params)


def test_through_a_toggle_the_crank_reverses_the_branch_is_kept_and_the_singular_rate_is_flagged():
    motion = non_grashof_motion()
    lower, upper = motion.drive.limits_rad
    events = motion.events(10.0)
    toggles = [e for e in events if e.kind == "toggle"]
    assert len(toggles) >= 5 and all("rocker rate is unbounded here" in e.message for e in toggles)
    t_toggle = np.array([e.t_s for e in toggles])
    at_toggle = motion.at(t_toggle)
    # At a toggle the crank is at the end of its travel and coupler and rocker are in line.
    assert np.all(np.minimum(np.abs(at_toggle.crank_angle - lower), np.abs(at_toggle.crank_angle - upper)) < 1e-12)
    assert np.all(np.abs(np.sin(at_toggle.coupler_angle - at_toggle.rocker_angle)) < four_bar.SINGULAR_SIN)
    assert at_toggle.singular.all() and np.isnan(at_toggle.rocker_rate).all() and np.isnan(at_toggle.coupler_rate).all()
    # Just beside it the rate is finite but huge (it grows like 1/√(distance from the toggle)).
    near = motion.at(t_toggle[:3] - 1e-6)
    assert np.all(np.isfinite(near.rocker_rate)) and np.all(np.abs(near.rocker_rate) > 100 * abs(motion.drive.speed_rad_s))
    # The crank sweeps back and forth inside its travel, and B stays left of A→O₄ (open) throughout.
    t = np.linspace(0.0, 10.0, 6001)
    state = motion.at(t)
    assert np.all((state.crank_angle >= lower - 1e-12) & (state.crank_angle <= upper + 1e-12))
    assert np.ptp(state.crank_angle) == pytest.approx(upper - lower, rel=1e-3)
    pos = state.positions
    to_o4 = np.array([1.2, 0.0]) - pos.crank_pin
    to_b = pos.rocker_pin - pos.crank_pin
    side = to_o4[:, 0] * to_b[:, 1] - to_o4[:, 1] * to_b[:, 0]
    assert np.all(side >= -1e-9)
    assert not state.singular.any()  # frames that miss the toggle instant by any margin have finite rates


def test_the_simulate_report_shows_undefined_rates_as_null_with_the_events():
    motion = non_grashof_motion()
    first = motion.events(5.0)[0].t_s
    # A frame rate that lands a frame exactly on the first toggle instant.
    report = FourBarLinkage().simulate(dict(four_bar.PARAMETERS.defaults(), ground_m=1.2, crank_m=0.9, coupler_m=0.7, rocker_m=0.6,
                                                   crank_angle0_deg=0.0, crank_speed_rad_s=1.5), {}, t_end_s=2.0, frame_rate_hz=1.0 / first).as_dict()
    assert report["series"]["rocker_rate"][1] is None and report["series"]["rocker_angle"][1] is not None
    assert report["stats"]["status"] == "undefined" and report["events"][0]["kind"] == "toggle"
    assert report["invariants"]["loop_closure_residual"][1] < 1e-12


def test_a_change_point_is_flagged_and_the_assembly_label_is_kept():
    """Parallelogram (d = b, a = c): all links fall in line at θ₂ = 0 and π; the motion keeps the
    open assembly (B left of A→O₄) on both sides and reports the rates there as undefined."""
    params = dict(four_bar.PARAMETERS.defaults(), ground_m=1.0, crank_m=0.4, coupler_m=1.0, rocker_m=0.4, crank_angle0_deg=60.0, crank_speed_rad_s=1.0)
    motion = FourBarMotion.from_params(params)
    events = motion.events(2 * np.pi)
    assert [e.kind for e in events] == ["change-point", "change-point"]
    assert [round(e.t_s, 9) for e in events] == [round(2 * np.pi / 3, 9), round(5 * np.pi / 3, 9)]
    at_events = motion.at(np.array([e.t_s for e in events]))
    assert at_events.singular.all()
    t = np.linspace(0.0, 2 * np.pi, 2001)
    pos = motion.at(t).positions
    to_o4 = np.array([1.0, 0.0]) - pos.crank_pin
    to_b = pos.rocker_pin - pos.crank_pin
    assert np.all(to_o4[:, 0] * to_b[:, 1] - to_o4[:, 1] * to_b[:, 0] >= -1e-12)


def test_crank_drive_reversal_and_crossing_times():
    """A crank rocking on [-0.4, 0.6] rad at 0.5 rad/s, starting at 0.2 rad moving down."""
    drive = CrankDrive(0.2, -0.5, (-0.4, 0.6))
    reversals = drive.reversal_times(6.0)
    assert [round(t, 12) for t, _ in reversals] == [1.2, 3.2, 5.2]
    assert [angle for _, angle in reversals] == [-0.4, 0.6, -0.4]
    assert drive.angle(np.array([0.0, 1.2, 2.2, 3.2, 5.2])) == pytest.approx([0.2, -0.4, 0.1, 0.6, -0.4], abs=1e-12)
    # The rate at a reversal instant is the one the crank leaves with.
    assert drive.rate(np.array([0.0, 1.2, 2.2, 3.2, 5.2])) == pytest.approx([-0.5, 0.5, 0.5, -0.5, 0.5])
    # Passing 0 rad: down at t = 0.4 s, up at 2.0 s, down at 4.4 s, up at 6.0 s.
    assert drive.times_at_angle(0.0, 6.0) == pytest.approx([0.4, 2.0, 4.4, 6.0], abs=1e-12)
    assert drive.period_s == pytest.approx(4.0)


# ---- slider-crank ---------------------------------------------------------------------------


def random_slider_cranks(count: int, seed: int):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        r, l, e = rng.uniform(0.05, 1.0), rng.uniform(0.1, 3.0), rng.uniform(-0.5, 0.5)
        try:
            out.append(slider_crank.SliderCrank(r, l, e))
        except ValueError:
            continue
    return out


def test_slider_crank_matches_an_independent_numerical_loop_closure():
    """fsolve (xtol 1e-12, Newton-like so the last step is far smaller) on r e^{iθ} + l e^{iφ} = x + i e from a guess
    5% and 0.05 rad off: slider position to 1e-11 m, rod angle to 1e-11 rad."""
    rng = np.random.default_rng(7)
    for mech in random_slider_cranks(50, seed=8):
        theta = rng.uniform(-np.pi, np.pi, 6)
        x, phi = mech.positions(theta)
        for th, xi, ph in zip(theta, x, phi):
            def f(u, th=th):
                return [mech.crank_m * math.cos(th) + mech.rod_m * math.cos(u[1]) - u[0],
                        mech.crank_m * math.sin(th) + mech.rod_m * math.sin(u[1]) - mech.offset_m]

            solution, _, status, _ = fsolve(f, [xi * 1.05, ph + 0.05], full_output=True, xtol=1e-12)
            assert status == 1
            assert abs(solution[0] - xi) < 1e-11 and abs(solution[1] - ph) < 1e-11


def test_slider_crank_velocity_and_acceleration_match_finite_differences():
    """Five-point central differences in time of the closed-form positions (ω = 2.5 rad/s), 30 random
    mechanisms. Velocity with h = 3e-4 s (truncation ~h⁴|x⁽⁵⁾|/30, measured ≤ 3e-11 relative; round-off
    ~ε|x|/h ≈ 2e-12) to 1e-9·(1 + |ẋ|); acceleration with h = 1e-3 s (truncation measured ≤ 1e-8
    relative, round-off ~5ε|x|/h² ≈ 3e-9) to 1e-7·(1 + |ẍ|); the rod rate like the velocity."""
    for mech in random_slider_cranks(30, seed=9):
        motion = slider_crank.SliderCrankMotion(mech, CrankDrive(0.3, 2.5))
        t = np.linspace(0.0, 3.0, 50)
        state = motion.at(t)

        def offsets(h, name):
            base = getattr(state, name)
            return {k: getattr(motion.at(t + k * h), name) - base for k in (-2, -1, 1, 2)}

        h = 3e-4
        for position, rate in (("slider_position_m", "slider_velocity_m_s"), ("rod_angle", "rod_rate")):
            f = offsets(h, position)
            first = (-f[2] + 8 * f[1] - 8 * f[-1] + f[-2]) / (12 * h)
            exact = getattr(state, rate)
            assert np.all(np.abs(first - exact) < 1e-9 * (1 + np.abs(exact)))
        h = 1e-3
        f = offsets(h, "slider_position_m")
        second = (-f[2] + 16 * f[1] + 16 * f[-1] - f[-2]) / (12 * h * h)
        exact = state.slider_acceleration_m_s2
        assert np.all(np.abs(second - exact) < 1e-7 * (1 + np.abs(exact)))


def test_slider_crank_stroke_and_quick_return_ratio_match_dense_sampling():
    """Stroke ends against the extremes of 200 001 samples per turn (error ≲ (2π/2e5)²·x'' ≈ 1e-9 m);
    the outward/return time ratio against the sampled times of those extremes (step 3e-5 rad) to 1e-4."""
    mech = slider_crank.SliderCrank(0.3, 0.8, 0.25)
    theta = np.linspace(0.0, 2 * np.pi, 200_001)
    x, _ = mech.positions(theta)
    x_min, x_max = mech.stroke_limits_m
    assert x.min() == pytest.approx(x_min, abs=1e-9) and x.max() == pytest.approx(x_max, abs=1e-9)
    outer, inner = theta[np.argmax(x)], theta[np.argmin(x)]
    outward = (outer - inner) % (2 * np.pi)
    assert mech.stroke_time_ratio() == pytest.approx(outward / (2 * np.pi - outward), abs=1e-4)
    assert mech.stroke_time_ratio() < 0.9  # the offset really makes a quick return
    assert mech.stroke_time_ratio(counterclockwise=False) == pytest.approx(1.0 / mech.stroke_time_ratio(), rel=1e-14)
    assert slider_crank.SliderCrank(0.3, 0.8, 0.0).stroke_time_ratio() == pytest.approx(1.0, abs=1e-15)


def test_a_rod_too_short_for_a_full_turn_is_refused():
    with pytest.raises(ValueError, match=r"connecting rod \(0.4 m\) must be longer than crank \+ \|offset\| \(0.5 m\)"):
        slider_crank.SliderCrank(0.3, 0.4, -0.2)


# ---- cardan joint ----------------------------------------------------------------------------


def cross_constraint(beta: float, phi1: float, phi2: float) -> float:
    """u · v for the pins built here with scipy rotations: u = R_x(φ₁) ŷ, v = R_e₂(φ₂) ẑ."""
    e2 = np.array([math.cos(beta), math.sin(beta), 0.0])
    u = Rotation.from_rotvec([phi1, 0.0, 0.0]).apply([0.0, 1.0, 0.0])
    v = Rotation.from_rotvec(phi2 * e2).apply([0.0, 0.0, 1.0])
    return float(u @ v)


@pytest.mark.parametrize("beta_deg", [0.0, 10.0, 30.0, 60.0, 85.0])
def test_cardan_output_angle_solves_the_cross_constraint(beta_deg):
    """brentq on u · v = 0 in (φ₁ − π/2, φ₁ + π/2) (the output stays within a quarter turn of the
    input): agreement to 1e-12 rad over three turns, including the quadrants where tan is ±∞."""
    beta = math.radians(beta_deg)
    joint = cardan_joint.CardanJoint(beta)
    phi1 = np.concatenate([np.linspace(-3 * np.pi, 3 * np.pi, 97), [np.pi / 2, 3 * np.pi / 2, -np.pi / 2]])
    phi2 = joint.output_angle(phi1)
    for p1, p2 in zip(phi1, phi2):
        root = brentq(lambda x: cross_constraint(beta, p1, x), p1 - np.pi / 2 + 1e-9, p1 + np.pi / 2 - 1e-9, xtol=1e-15)
        assert abs(root - p2) < 1e-12
    ordered = np.unique(phi1)
    assert np.all(np.diff(joint.output_angle(ordered)) > 0)  # the output never turns back


@pytest.mark.parametrize("beta_deg", [5.0, 30.0, 60.0, 80.0])
def test_cardan_speed_ratio_is_the_derivative_spans_cos_beta_to_sec_beta_and_makes_one_turn_per_turn(beta_deg):
    beta = math.radians(beta_deg)
    joint = cardan_joint.CardanJoint(beta)
    phi1 = np.linspace(0.0, 2 * np.pi, 7201)
    ratio = joint.speed_ratio(phi1)
    # The derivative of the output angle, by central differences (h = 1e-6: error ≲ 1e-9 even at 80°).
    h = 1e-6
    fd = (joint.output_angle(phi1 + h) - joint.output_angle(phi1 - h)) / (2 * h)
    assert np.max(np.abs(fd - ratio)) < 1e-7 * joint.speed_ratio_span[1] ** 3
    # Extremes over a turn (the grid holds 0°, 90°, 180°, 270° exactly).
    assert ratio.min() == pytest.approx(math.cos(beta), rel=1e-12)
    assert ratio.max() == pytest.approx(1.0 / math.cos(beta), rel=1e-12)
    assert joint.speed_ratio_span == pytest.approx((math.cos(beta), 1.0 / math.cos(beta)), rel=1e-15)
    # Integrated over one input turn the output also turns once (quad to 1e-11 rad).
    turn, _ = quad(lambda p: float(joint.speed_ratio(p)), 0.0, 2 * np.pi, epsabs=1e-13, limit=200)
    assert turn == pytest.approx(2 * np.pi, abs=1e-10)
    assert joint.output_angle(7.3 + 2 * np.pi) - joint.output_angle(7.3) == pytest.approx(2 * np.pi, abs=1e-13)
    # Output acceleration α₂ = ω₁² d(ratio)/dφ₁ against a difference of the ratio.
    slope_fd = (joint.speed_ratio(phi1 + h) - joint.speed_ratio(phi1 - h)) / (2 * h)
    assert np.max(np.abs(slope_fd - joint.speed_ratio_slope(phi1))) < 1e-6 * joint.speed_ratio_span[1] ** 5


def test_cardan_at_90_degrees_is_refused():
    with pytest.raises(ValueError, match="90"):
        cardan_joint.PARAMETERS.validate({"shaft_angle_deg": 90.0})
    cardan_joint.PARAMETERS.validate({"shaft_angle_deg": 89.0})


def test_cardan_model_series_keep_the_cross_pins_perpendicular():
    solution = cardan_joint.CardanJointDrive().evaluate({"shaft_angle_deg": 40.0, "input_speed_rad_s": 3.0}, np.linspace(0.0, 20.0, 2001))
    # u · v = sin φ₁ cos φ₂ − cos φ₁ sin φ₂ cos β carries the round-off of the angles, ~ε|φ₁| (φ₁ reaches 60 rad).
    phi1 = solution.series["input_angle"]
    assert np.all(np.abs(solution.invariants["cross_pin_dot_product"]) < 4 * np.finfo(float).eps * (1 + np.abs(phi1)))
    assert np.all(np.diff(solution.series["output_angle"]) > 0)
    assert solution.series["output_rate"] == pytest.approx(3.0 * solution.series["speed_ratio"], rel=1e-15)


# ---- rolling ---------------------------------------------------------------------------------


def random_rolling(count: int, seed: int) -> list[SteadyRolling]:
    rng = np.random.default_rng(seed)
    out = []
    for k in range(count):
        body = "cone" if k % 2 else "disk"
        params = {"body": body, "rim_radius_m": rng.uniform(0.05, 2.0), "tilt_deg": rng.uniform(5.0, 60.0) if body == "cone" else rng.uniform(0.0, 60.0),
                  "path_radius_m": rng.uniform(0.2, 20.0), "speed_m_s": rng.uniform(-5.0, 5.0)}
        out.append(SteadyRolling.from_params(params))
    return out


def test_contact_point_velocity_is_zero_to_round_off():
    """v_C = v_G + ω × r_GC: at most 1e-14 of the rolling speed scale max(|v|, |ω| R) for disks and cones."""
    t = np.linspace(0.0, 10.0, 201)
    for rolling in random_rolling(40, seed=10):
        state = rolling.at(t)
        scale = max(abs(rolling.speed_m_s), float(np.max(np.linalg.norm(state.angular_velocity, axis=1))) * rolling.rim_radius_m)
        assert np.max(np.linalg.norm(state.contact_point_velocity, axis=1)) < 1e-14 * scale


def test_rolling_pose_differences_reproduce_omega_centre_velocity_and_a_stationary_contact_point():
    """From the pose alone (attitude quaternion and centre at t ± h, h = 1e-6 s): the body point
    touching the ground at t does not move (|ΔX|/2h below 1e-7 m/s; truncation ~h²|X'''| ≈ 1e-11,
    round-off ~ε·|X|/h ≈ 1e-9), Ṙ Rᵀ gives ω to 1e-7 rad/s, and the centre's difference gives v_G to 1e-8 m/s."""
    h = 1e-6
    for rolling in random_rolling(20, seed=11):
        for t0 in (0.0, 0.7, 3.1):
            t = np.array([t0 - h, t0, t0 + h])
            state = rolling.at(t)
            rot = Rotation.from_quat(state.wxyz, scalar_first=True)
            body_point = rot[1].inv().apply(state.contact_point[1] - state.center[1])
            world = state.center + rot.apply(np.repeat(body_point[None], 3, axis=0))
            assert np.linalg.norm(world[2] - world[0]) / (2 * h) < 1e-7
            matrices = rot.as_matrix()
            skew = (matrices[2] - matrices[0]) / (2 * h) @ matrices[1].T
            omega_fd = np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
            assert np.max(np.abs(omega_fd - state.angular_velocity[1])) < 1e-7
            assert np.max(np.abs((state.center[2] - state.center[0]) / (2 * h) - state.center_velocity[1])) < 1e-8


def test_rim_points_are_body_fixed_points_on_the_rim():
    """The drawing's rim points equal the body frame's rim circle carried by the attitude quaternion (to 1e-14 m),
    the first one touches the ground at t = 0, and all have the speed v_G + ω × r."""
    for rolling in random_rolling(6, seed=14):
        state = rolling.at(np.array([0.0, 1.3]))
        angles = np.linspace(0.0, 2 * np.pi, 8, endpoint=False) + np.pi
        body = rolling.rim_radius_m * np.stack([np.cos(angles), np.sin(angles), np.zeros(8)], axis=-1)
        for i in (0, 1):
            expected = state.center[i] + Rotation.from_quat(state.wxyz[i], scalar_first=True).apply(body)
            assert np.max(np.abs(rolling.rim_points(state, i, 8) - expected)) < 1e-14 * max(1.0, rolling.path_radius_m)
        assert np.max(np.abs(rolling.rim_points(state, 0, 8)[0] - state.contact_point[0])) < 1e-14 * max(1.0, rolling.path_radius_m)


def test_the_rolling_cone_turns_about_its_line_of_contact_and_its_apex_stays_put():
    """For the cone, ω is parallel to the contact line O→C (angle below 1e-14 rad) and has no vertical
    part; the apex O′ is the origin and the rim's centre stays on the axis through it."""
    for rolling in [r for r in random_rolling(20, seed=12) if r.body == "cone"]:
        state = rolling.at(np.linspace(0.0, 5.0, 51))
        assert np.max(rolling.axis_misalignment(state)) < 1e-14
        assert np.max(np.abs(state.angular_velocity[:, 2])) < 1e-14 * np.max(np.abs(state.angular_velocity))
        assert np.allclose(rolling.axis_point, 0.0, atol=1e-15)
        along_axis = np.einsum("ij,ij->i", state.center, state.axis)
        assert np.allclose(np.linalg.norm(state.center, axis=1), along_axis, rtol=1e-14)


def test_the_disk_instantaneous_axis_passes_through_o_prime():
    for rolling in [r for r in random_rolling(20, seed=13) if r.body == "disk"]:
        state = rolling.at(np.linspace(0.0, 5.0, 51))
        assert np.max(rolling.axis_misalignment(state)) < 1e-12


def test_rolling_model_report_and_refusals():
    report = SteadyRollingMotion().simulate({"body": "cone", "rim_radius_m": 0.4, "tilt_deg": 20.0, "path_radius_m": 1.5, "speed_m_s": 0.8}, {},
                            t_end_s=5.0, frame_rate_hz=30.0).as_dict()
    assert max(report["series"]["contact_point_speed"]) < 1e-15
    assert report["stats"]["status"] == "ok"
    with pytest.raises(ValueError, match="half-angle"):
        SteadyRollingMotion.parameters.validate({"body": "cone", "tilt_deg": 2.0})
