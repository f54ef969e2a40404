"""Projectile with drag (app/physics/projectile.py) against closed forms and a second integrator."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import lambertw

from app.physics.systems import worked_examples
from app.physics.systems.ch01 import projectile

EXAMPLES = worked_examples()

DEFAULTS = projectile.INPUTS.defaults()
NO_DRAG = {**DEFAULTS, "linear_drag_kg_s": 0.0, "quadratic_drag_kg_m": 0.0}
LINEAR = {**DEFAULTS, "mass_kg": 0.5, "linear_drag_kg_s": 0.05, "quadratic_drag_kg_m": 0.0}


@pytest.mark.parametrize("height0_m", [0.0, 30.0])
def test_linear_drag_matches_the_closed_form_at_every_sample(height0_m):
    inputs = {**LINEAR, "height0_m": height0_m}
    traj = projectile.simulate(inputs)
    x_exact, v_exact = projectile.linear_drag_closed_form(inputs, traj.t_s)
    # DOP853 at rtol 1e-11 / atol 1e-12 over ~5 s: global error observed <= 7e-13 of the largest
    # coordinate (~100 m) and 3e-13 of the launch speed. 1e-10 of those scales allows ~100x
    # growth; a wrong drag term or a mis-sampled dense output would be off by >= 1e-4.
    np.testing.assert_allclose(traj.position_m, x_exact, rtol=0, atol=1e-10 * np.abs(x_exact).max())
    np.testing.assert_allclose(traj.velocity_m_s, v_exact, rtol=0, atol=1e-10 * inputs["speed0_m_s"])


def test_linear_drag_flight_time_matches_lambert_w():
    # From h0 = 0 the landing time solves a(1 - e^-u) = u with u = k t, k = b/m, a = 1 + k v0z/g.
    # Its nonzero root is u = a + W0(-a e^-a) (Lambert W, principal branch) -- a closed form
    # independent of both the module's closed form and its integrator.
    inputs = {**LINEAR, "height0_m": 0.0}
    m, b, g = inputs["mass_kg"], inputs["linear_drag_kg_s"], inputs["g_m_s2"]
    k = b / m
    v0 = projectile.initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])
    a = 1.0 + k * v0[2] / g
    t_land = (a + lambertw(-a * math.exp(-a), 0).real) / k
    traj = projectile.simulate(inputs)
    # The event root is located to ~1e-12 s and W0 is accurate to ~1e-15: 1e-9 relative.
    assert traj.t_s[-1] == pytest.approx(t_land, rel=1e-9)
    assert traj.position_m[-1, 0] == pytest.approx(v0[0] / k * (1 - math.exp(-k * t_land)), rel=1e-9)


@pytest.mark.parametrize("height0_m", [0.0, 12.5])
def test_no_drag_is_the_parabola(height0_m):
    inputs = {**NO_DRAG, "height0_m": height0_m}
    out = projectile.solve(inputs).outputs
    g, v, h = inputs["g_m_s2"], inputs["speed0_m_s"], height0_m
    vx, vz = v * math.cos(math.radians(inputs["elevation_deg"])), v * math.sin(math.radians(inputs["elevation_deg"]))
    t_flight = (vz + math.sqrt(vz**2 + 2 * g * h)) / g
    apex = h + vz**2 / (2 * g)
    # The motion is a quadratic in t, which DOP853 (order 8) integrates exactly up to rounding,
    # so 1e-10 relative is generous.
    assert out["flight_time_s"] == pytest.approx(t_flight, rel=1e-10)
    assert out["range_m"] == pytest.approx(vx * t_flight, rel=1e-10)
    # Energy conservation gives the landing speed: v_land^2 = v0^2 + 2 g h0.
    assert out["landing_speed_m_s"] == pytest.approx(math.sqrt(v**2 + 2 * g * h), rel=1e-10)
    # max_height_m is the highest of the 241 uniform samples, so it can undershoot the apex by at
    # most g (dt/2)^2 / 2 with dt the sample spacing. From h0 = 0 the apex is at t_flight/2,
    # which is the middle sample exactly, so there it must agree to 1e-10 relative.
    dt = t_flight / 240
    if h == 0.0:
        assert out["max_height_m"] == pytest.approx(apex, rel=1e-10)
    else:
        assert 0.0 <= apex - out["max_height_m"] <= g * (dt / 2) ** 2 / 2 + 1e-9 * apex


@pytest.mark.parametrize(
    "inputs",
    [DEFAULTS, LINEAR, {**DEFAULTS, "height0_m": 50.0, "elevation_deg": 70.0, "quadratic_drag_kg_m": 0.01, "linear_drag_kg_s": 0.02}],
    ids=["quadratic", "linear", "both-high"],
)
def test_work_energy_and_impulse_momentum_balances_close(inputs):
    # These are consistency checks between separately integrated quantities: the kinetic energy
    # comes from the integrated velocity, the drag work and impulse are integrated as extra
    # states, gravity's work and impulse from position and time. At rtol 1e-11 the residuals are
    # observed <= 5e-12 of T0 and ~5e-16 of |p0|; 1e-9 leaves >= 100x margin while a missing
    # or mis-signed term would be O(1e-2) or more.
    traj = projectile.simulate(inputs)
    T0 = traj.kinetic_energy_J[0]
    p0 = inputs["mass_kg"] * inputs["speed0_m_s"]
    assert np.abs(traj.energy_residual_J).max() <= 1e-9 * T0
    assert np.linalg.norm(traj.momentum_residual_N_s, axis=1).max() <= 1e-9 * p0
    # And both terms matter: drag removed a visible share of the energy.
    assert -traj.work_drag_J[-1] > 1e-3 * T0


@pytest.mark.parametrize("inputs", [DEFAULTS, LINEAR], ids=["quadratic", "linear"])
def test_drag_work_is_never_positive_and_never_increases(inputs):
    # Power of drag is F_d . v = -(b + c|v|)|v|^2 <= 0, so W_drag(t) is non-increasing from 0.
    traj = projectile.simulate(inputs)
    W = traj.work_drag_J
    assert W[0] == 0.0
    assert np.all(W <= 0.0)
    # Allowed increase between samples: integration noise, 1e-12 of |W_end| (none observed).
    assert np.all(np.diff(W) <= 1e-12 * abs(W[-1]))
    # The drag force reported at each sample opposes the velocity there.
    assert np.all(np.einsum("ij,ij->i", traj.drag_force_N, traj.velocity_m_s) <= 0.0)


@pytest.mark.parametrize("inputs", [DEFAULTS, LINEAR], ids=["quadratic", "linear"])
def test_landing_slower_than_launch_with_drag_from_ground_level(inputs):
    out = projectile.solve({**inputs, "height0_m": 0.0}).outputs
    # Same height, so gravity did no net work; drag took energy away.
    assert out["landing_speed_m_s"] < inputs["speed0_m_s"]
    # ... and exactly the drag work: T_land = T0 + W_drag. 1e-8 relative: the work-energy
    # residual is <= 5e-12 of T0 (see above) and T_land is a sizeable fraction of T0.
    assert 0.5 * inputs["mass_kg"] * out["landing_speed_m_s"] ** 2 == pytest.approx(
        0.5 * inputs["mass_kg"] * inputs["speed0_m_s"] ** 2 + out["work_drag_J"], rel=1e-8
    )


def _best_angle(inputs, angles):
    ranges = [projectile.simulate({**inputs, "elevation_deg": float(a)}, samples=3).position_m[-1, 0] for a in angles]
    return angles[int(np.argmax(ranges))]


def test_best_range_angle_is_45_without_drag_and_lower_with_drag():
    angles = np.arange(30.0, 51.0, 1.0)
    assert _best_angle(NO_DRAG, angles) == 45.0
    # Default baseball-like drag (c = 7.6e-4 kg/m, 40 m/s): optimum well below 45 degrees.
    assert _best_angle(DEFAULTS, angles) < 45.0
    assert _best_angle(LINEAR, angles) < 45.0


def _reference_quadratic_flight(inputs):
    """Independent integration: planar state (x, z, vx, vz), implicit Radau, own right-hand side."""
    m, g, b, c = inputs["mass_kg"], inputs["g_m_s2"], inputs["linear_drag_kg_s"], inputs["quadratic_drag_kg_m"]
    a = math.radians(inputs["elevation_deg"])
    y0 = [0.0, inputs["height0_m"], inputs["speed0_m_s"] * math.cos(a), inputs["speed0_m_s"] * math.sin(a)]

    def rhs(_t, y):
        _, _, vx, vz = y
        k = (b + c * math.hypot(vx, vz)) / m
        return [vx, vz, -k * vx, -g - k * vz]

    def ground(_t, y):
        return y[1]

    ground.terminal, ground.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 1000.0), y0, method="Radau", rtol=1e-12, atol=1e-12, events=ground)
    assert sol.status == 1
    return float(sol.t_events[0][0]), float(sol.y_events[0][0][0])


@pytest.mark.parametrize(
    "inputs",
    [DEFAULTS, {**DEFAULTS, "quadratic_drag_kg_m": 0.02, "linear_drag_kg_s": 0.01, "height0_m": 20.0, "elevation_deg": 60.0}],
    ids=["defaults", "heavy-drag-raised"],
)
def test_quadratic_drag_matches_an_independent_radau_integration(inputs):
    t_ref, x_ref = _reference_quadratic_flight(inputs)
    out = projectile.solve(inputs).outputs
    # Radau (implicit, order 5) at rtol 1e-12 and DOP853 (explicit, order 8) at rtol 1e-11: the
    # two agree to <= 5e-13 relative (observed); 1e-10 relative leaves 200x margin for platform
    # differences, while drag itself changes the range by tens of percent.
    assert out["flight_time_s"] == pytest.approx(t_ref, rel=1e-10)
    assert out["range_m"] == pytest.approx(x_ref, rel=1e-10)


def test_starting_on_the_ground_moving_down_is_refused():
    # elevation is >= 1 degree by its range, so only simulate() called directly can get here.
    with pytest.raises(ValueError, match="height0_m"):
        projectile.simulate({**DEFAULTS, "elevation_deg": -5.0, "height0_m": 0.0})


def test_closed_form_refuses_zero_linear_drag():
    with pytest.raises(ValueError, match="linear_drag_kg_s"):
        projectile.linear_drag_closed_form(NO_DRAG, np.array([0.0, 1.0]))


# -- the examples registry -------------------------------------------------------------


def test_registry_holds_the_chapter_1_examples():
    assert {"1.1", "1.2", "particle-work-energy"} <= set(EXAMPLES)
    assert EXAMPLES["particle-work-energy"].chapter == 1
    for key, example in EXAMPLES.items():
        assert example.id == key
        assert set(example.output_units)  # every example declares output units


@pytest.mark.parametrize("example_id", sorted(EXAMPLES))
def test_every_example_solves_its_defaults_into_strict_json(example_id):
    example = EXAMPLES[example_id]
    solution = example.solve(example.inputs.validate({}))
    data = solution.as_dict()
    text = json.dumps(data, allow_nan=False)  # raises on NaN/inf and on numpy types
    assert json.loads(text) == data
    assert set(data["outputs"]) == set(example.output_units)
    for name, raw in solution.outputs.items():
        value = data["outputs"][name]
        if isinstance(raw, str):  # a verdict in words (e.g. whether principal moments repeat)
            assert value and isinstance(value, str), name
        elif np.shape(raw) == (3, 3):  # a tensor or a set of axes: three rows of three floats
            assert isinstance(value, list) and all(isinstance(row, list) and len(row) == 3 for row in value), name
            assert all(isinstance(v, float) for row in value for v in row), name
        elif np.ndim(raw) == 1 and np.shape(raw) == (3,):
            assert isinstance(value, list) and len(value) == 3 and all(isinstance(v, float) for v in value), name
        elif np.ndim(raw) == 0:
            assert isinstance(value, (int, float)) and not isinstance(value, bool), name
        else:  # sweeps for plots: flat lists of numbers
            assert isinstance(value, list) and all(isinstance(v, float) for v in value), name
    assert data["steps"], "a worked example shows its steps"
    number = lambda x: isinstance(x, float | int) and not isinstance(x, bool)  # noqa: E731
    for step in data["steps"]:
        assert step["title"] and step["latex"] and isinstance(step["values"], dict)
        for v in step["values"].values():
            # A number; a vector (3 components in space, 2 in a plane, or a row of a constraint matrix); or a matrix
            # given as rows of equal length (the page writes each as [a, b, …]).
            if isinstance(v, list) and v and isinstance(v[0], list):
                assert all(isinstance(row, list) and len(row) == len(v[0]) and all(map(number, row)) for row in v), v
            else:
                assert number(v) or (isinstance(v, list) and v and all(map(number, v))), (step["title"], v)


# -- the apex, the vacuum comparison and the two legs of the flight ---------------------------


@pytest.mark.parametrize("height0_m", [0.0, 12.5])
def test_vacuum_flight_is_what_the_integrator_flies_without_drag(height0_m):
    # The closed form against the integration with b = c = 0 (a quadratic in t, integrated exactly up to
    # rounding; the landing and apex events are located to ~1e-13 s): 1e-10 relative.
    inputs = {**NO_DRAG, "height0_m": height0_m}
    vacuum = projectile.vacuum_flight(inputs)
    traj = projectile.simulate(inputs)
    v0 = projectile.initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])
    assert vacuum.flight_time_s == pytest.approx(traj.t_s[-1], rel=1e-10)
    assert vacuum.range_m == pytest.approx(traj.position_m[-1, 0], rel=1e-10)
    assert vacuum.apex_time_s == pytest.approx(traj.apex_time_s, rel=1e-10)
    assert vacuum.apex_height_m == pytest.approx(traj.apex_position_m[2], rel=1e-10)
    # And the apex event sits where the parabola peaks: t = v0z/g, x = v0x t, z = h0 + v0z²/(2g).
    g = inputs["g_m_s2"]
    np.testing.assert_allclose(
        traj.apex_position_m, [v0[0] * v0[2] / g, 0.0, height0_m + v0[2] ** 2 / (2 * g)], rtol=1e-10, atol=1e-12
    )


def test_apex_with_linear_drag_matches_the_closed_form():
    # v_z(t) = (v0z + g/k) e^{−kt} − g/k vanishes at t* = ln(1 + k v0z/g)/k; the position there from the
    # module's closed form (checked above against the integrator). The apex event is located to ~1e-12 s
    # and v_z's slope there is −g, so 1e-9 relative holds with margin.
    inputs = {**LINEAR, "height0_m": 5.0}
    m, b, g = inputs["mass_kg"], inputs["linear_drag_kg_s"], inputs["g_m_s2"]
    k = b / m
    v0z = projectile.initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])[2]
    t_apex = math.log(1.0 + k * v0z / g) / k
    traj = projectile.simulate(inputs)
    assert traj.apex_time_s == pytest.approx(t_apex, rel=1e-9)
    position, _ = projectile.linear_drag_closed_form(inputs, np.array([t_apex]))
    np.testing.assert_allclose(traj.apex_position_m, position[0], rtol=1e-9)
    # The sampled maximum of solve() can only undershoot the located apex.
    assert traj.position_m[:, 2].max() <= traj.apex_position_m[2] + 1e-9


@pytest.mark.parametrize(
    ("inputs", "expected"),
    [
        (NO_DRAG, "neither: equal"),  # symmetric parabola: climb = fall = v0z/g
        ({**NO_DRAG, "height0_m": 12.5}, "the fall"),  # it falls further than it climbed
        (DEFAULTS, "the fall"),  # drag: the climb decelerates faster than g, the fall accelerates slower
        (LINEAR, "the fall"),
        ({**DEFAULTS, "quadratic_drag_kg_m": 1e-5}, "the fall"),  # the smallest drag a control sets is still seen
    ],
    ids=["vacuum", "vacuum-raised", "quadratic", "linear", "faint-drag"],
)
def test_the_fall_takes_longer_than_the_climb_once_anything_breaks_the_symmetry(inputs, expected):
    traj = projectile.simulate(inputs)
    assert projectile.longer_leg(traj) == expected
    assert traj.climb_time_s + traj.fall_time_s == pytest.approx(traj.t_s[-1], rel=1e-14)  # one rounding
    if expected == "the fall":
        # Clear of the "equal" band by 1e4 or more (faint drag: ~1e-3 of the flight).
        assert traj.fall_time_s - traj.climb_time_s > 1e4 * projectile.EQUAL_LEGS_RTOL * traj.t_s[-1]


def test_vacuum_flight_refuses_a_start_on_the_ground_moving_down():
    with pytest.raises(ValueError, match="height0_m"):
        projectile.vacuum_flight({**NO_DRAG, "elevation_deg": -5.0, "height0_m": 0.0})
