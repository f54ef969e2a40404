"""Worked example ``collar-on-arm-path-variables`` (2.4) against an independent computation.

Independent: the collar's Cartesian position x = r cos θ, y = r sin θ (θ = Ω t + α t²/2, r = r₀ + b sin ω_c t) is
written here, differentiated by sympy and evaluated with 30 significant digits; the polar components are the
projections of those Cartesian vectors on the arm's e_r, e_θ, and a_t, a_n, κ come from v·a and |v × a|. The example
uses the polar formulas on the arm (the four named terms) instead. The scene model's own path variables
(:meth:`~app.physics.systems.ch02.rotating_arm.ArmState.path_variables`) are compared too.

Tolerance: 1e-12 of the scale (|v| for velocities, |a| for accelerations, |a|/v² for the curvature). The example's
numbers are a few products of O(1) numbers, exact to a few ulps (≈ 1e-15) of those scales.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02.rotating_arm import RotatingArm
from app.physics.systems.ch02.rotating_arm_example import EXAMPLE

RTOL = 1e-12
t = sympy.Symbol("t", real=True)


def reference(inputs) -> dict[str, object]:
    with mpmath.workdps(30):
        f = {k: sympy.Float(inputs[k], 30) for k in inputs if k != "t_s"}
        theta = f["arm_rate_rad_s"] * t + f["arm_acceleration_rad_s2"] * t**2 / 2
        r = f["collar_mean_m"] + f["collar_amplitude_m"] * sympy.sin(f["collar_frequency_rad_s"] * t)
        x, y = r * sympy.cos(theta), r * sympy.sin(theta)
        at = sympy.Float(inputs["t_s"], 30)
        value = lambda e: mpmath.mpf(sympy.N(e.subs(t, at), 30))  # noqa: E731
        vx, vy, ax, ay = (value(sympy.diff(e, t, k)) for e, k in ((x, 1), (y, 1), (x, 2), (y, 2)))
        th = value(theta)
        c, s = mpmath.cos(th), mpmath.sin(th)
        speed = mpmath.sqrt(vx**2 + vy**2)
        a_size = mpmath.sqrt(ax**2 + ay**2)
        a_n = abs(vx * ay - vy * ax) / speed
        return {
            "velocity_m_s": np.array([float(vx), float(vy), 0.0]),
            "acceleration_m_s2": np.array([float(ax), float(ay), 0.0]),
            "velocity_polar_m_s": np.array([float(vx * c + vy * s), float(-vx * s + vy * c), 0.0]),
            "acceleration_polar_m_s2": np.array([float(ax * c + ay * s), float(-ax * s + ay * c), 0.0]),
            "speed_m_s": float(speed),
            "a_tangential_m_s2": float((vx * ax + vy * ay) / speed),
            "a_normal_m_s2": float(a_n),
            "curvature_1_m": float(a_n / speed**2),
            "|a|": float(a_size),
        }


CASES = [
    {},
    {
        "arm_rate_rad_s": -2.0,
        "arm_acceleration_rad_s2": 0.3,
        "collar_mean_m": -0.4,
        "collar_amplitude_m": 1.1,
        "collar_frequency_rad_s": 4.2,
        "t_s": 3.3,
    },
    {
        "arm_rate_rad_s": 0.6,
        "collar_mean_m": 0.0,
        "collar_amplitude_m": 1.2,
        "collar_frequency_rad_s": 1.0,
        "t_s": 0.0,
    },  # through the pivot: r = 0, all Coriolis
    {
        "arm_rate_rad_s": 3.0,
        "arm_acceleration_rad_s2": -0.3,
        "collar_mean_m": 1.5,
        "collar_amplitude_m": 0.5,
        "collar_frequency_rad_s": 0.0,
        "t_s": 12.0,
    },  # clamped collar, arm slowing down
    {"arm_rate_rad_s": 0.0, "t_s": 0.5},  # arm held still: a straight path, κ = 0
]


@pytest.mark.parametrize("changes", CASES)
def test_polar_terms_and_path_variables_match_sympy(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    ref = reference(inputs)
    v_scale, a_scale = ref["speed_m_s"], ref["|a|"]
    for name, scale in (
        ("velocity_m_s", v_scale),
        ("velocity_polar_m_s", v_scale),
        ("acceleration_m_s2", a_scale),
        ("acceleration_polar_m_s2", a_scale),
        ("speed_m_s", v_scale),
        ("a_tangential_m_s2", a_scale),
        ("a_normal_m_s2", a_scale),
        ("curvature_1_m", a_scale / v_scale**2),
    ):
        difference = np.abs(np.asarray(out[name], float) - np.asarray(ref[name], float))
        assert np.all(difference <= RTOL * scale), (name, out[name], ref[name])


@pytest.mark.parametrize("changes", CASES)
def test_the_scene_model_and_the_check_step_agree(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    solution = EXAMPLE.solve(inputs)
    speed, a_t, a_n = RotatingArm.from_params(inputs).at(inputs["t_s"]).path_variables()
    a_scale = float(np.linalg.norm(solution.outputs["acceleration_m_s2"]))
    assert solution.outputs["speed_m_s"] == pytest.approx(float(speed[0]), rel=RTOL)
    assert solution.outputs["a_tangential_m_s2"] == pytest.approx(float(a_t[0]), abs=RTOL * a_scale)
    assert solution.outputs["a_normal_m_s2"] == pytest.approx(float(a_n[0]), abs=RTOL * a_scale)
    check = solution.steps[-1].values
    assert solution.steps[-1].title.startswith("Check")
    assert np.allclose(check["v (polar terms)"], check["v (chain rule)"], rtol=0.0, atol=RTOL * float(speed[0]))
    assert np.allclose(check["a (polar terms)"], check["a (chain rule)"], rtol=0.0, atol=RTOL * a_scale)
    assert check["sqrt(a_t² + a_n²)"] == pytest.approx(check["|a|"], abs=RTOL * a_scale)


def test_the_lesson_s_instant_t0_has_a_coriolis_term_twice_the_centripetal():
    solution = EXAMPLE.solve(EXAMPLE.inputs.validate({"t_s": 0.0}))
    terms = solution.steps[2].values
    assert terms["2 r_dot theta_dot"] == pytest.approx(1.8, rel=RTOL)  # lesson 2.4: 2 × 0.9 × 1
    assert terms["-r theta_dot²"] == pytest.approx(-0.8, rel=RTOL)


@pytest.mark.parametrize(
    ("changes", "field", "words"),
    [
        ({"arm_rate_rad_s": 0.0, "collar_amplitude_m": 0.0}, "t_s", "at rest"),
        ({"arm_rate_rad_s": 0.0, "collar_frequency_rad_s": np.pi, "t_s": 0.5}, "t_s", "at rest"),
        ({"collar_mean_m": 1.5, "collar_amplitude_m": 1.0}, "collar_amplitude_m", "slide off the arm"),
    ],
)
def test_impossible_combinations_are_refused(changes, field, words):
    with pytest.raises(ParameterError, match=words) as caught:
        EXAMPLE.inputs.validate(changes)
    assert caught.value.field == field
    with pytest.raises(ValueError, match=words):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **changes})
