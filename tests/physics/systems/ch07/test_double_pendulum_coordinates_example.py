"""The double pendulum's inverse kinematics (worked example ``double-pendulum-coordinates``, section 7.2) against an
independent computation: scipy's ``fsolve`` on the two position equations ``x_B(θ₁, θ₂) = x``, ``z_B(θ₁, θ₂) = z``
from a grid of starting guesses, its roots reduced to (−π, π] and collected.

Tolerance 1e-9 rad: fsolve stops at a relative step of 1e-13 and the position equations are well conditioned away
from the rods in line (|det J| = l₁ l₂ |sin(θ₂ − θ₁)| ≥ 0.1 m² in these cases), so its roots are good to about
1e-12 rad; the law-of-cosines answer is good to a few ulps. The Jacobian determinant is a product of O(1) numbers:
1e-12 relative.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch07.double_pendulum_coordinates_example import EXAMPLE

CASES = [
    {},
    {"l1_m": 1.3, "l2_m": 0.6, "bob_x_m": -0.4, "bob_z_m": -1.5},
    {"l1_m": 0.5, "l2_m": 2.0, "bob_x_m": 1.0, "bob_z_m": 1.2},  # above the pivot, the upper rod shorter
    {"l1_m": 2.0, "l2_m": 1.0, "bob_x_m": 0.0, "bob_z_m": -2.5},
]


def _wrap(angle):
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _roots(l1, l2, x, z):
    def residual(q):
        return [l1 * math.sin(q[0]) + l2 * math.sin(q[1]) - x, -l1 * math.cos(q[0]) - l2 * math.cos(q[1]) - z]

    found = []
    for guess1 in np.linspace(-3.0, 3.0, 7):
        for guess2 in np.linspace(-3.0, 3.0, 7):
            root, info, ok, _ = fsolve(residual, [guess1, guess2], xtol=1e-13, full_output=True)
            if ok != 1 or max(abs(r) for r in info["fvec"]) > 1e-12:
                continue
            root = (_wrap(root[0]), _wrap(root[1]))
            if not any(abs(_wrap(root[0] - f[0])) < 1e-6 and abs(_wrap(root[1] - f[1])) < 1e-6 for f in found):
                found.append(root)
    return sorted(found)


@pytest.mark.parametrize("changes", CASES)
def test_both_configurations_match_a_numerical_root_finder(changes):
    values = EXAMPLE.inputs.validate(changes)
    l1, l2, x, z = values["l1_m"], values["l2_m"], values["bob_x_m"], values["bob_z_m"]
    outputs = EXAMPLE.solve(values).outputs
    mine = sorted(zip(outputs["theta1_rad"], outputs["theta2_rad"]))
    roots = _roots(l1, l2, x, z)
    assert len(roots) == 2
    for (t1, t2), (r1, r2) in zip(mine, roots):
        assert abs(_wrap(t1 - r1)) < 1e-9 and abs(_wrap(t2 - r2)) < 1e-9
    for (t1, t2), det in zip(zip(outputs["theta1_rad"], outputs["theta2_rad"]), outputs["jacobian_det_m2"]):
        jacobian = np.array([[l1 * math.cos(t1), l2 * math.cos(t2)], [l1 * math.sin(t1), l2 * math.sin(t2)]])
        assert det == pytest.approx(np.linalg.det(jacobian), rel=1e-12, abs=1e-12 * l1 * l2)
    assert outputs["reach_m"] == pytest.approx(math.hypot(x, z), rel=1e-15)


def test_the_check_step_lands_on_the_point_with_every_constraint_met():
    values = EXAMPLE.inputs.defaults()
    check = EXAMPLE.solve(values).steps[-1]
    assert check.title.startswith("Check")
    target = [values["bob_x_m"], 0.0, values["bob_z_m"]]
    for name in ("r_B_first", "r_B_second"):
        assert np.allclose(check.values[name], target, rtol=0, atol=1e-14)
    for name in ("g_first", "g_second"):
        assert np.all(np.abs(check.values[name]) <= 1e-14)
    assert check.values["rank"] == 4


@pytest.mark.parametrize(
    ("changes", "words"),
    [
        ({"bob_x_m": 3.0, "bob_z_m": -1.0}, "no configuration"),  # beyond l₁ + l₂ = 2 m
        ({"l1_m": 2.0, "l2_m": 0.5, "bob_x_m": 0.5, "bob_z_m": -0.5}, "no configuration"),  # inside |l₁ − l₂|
        ({"bob_x_m": 0.0, "bob_z_m": 0.0}, "every θ₁"),  # the pivot with equal rods
    ],
)
def test_points_that_no_configuration_or_every_configuration_fits_are_refused(changes, words):
    with pytest.raises(ParameterError, match=words) as refused:
        EXAMPLE.inputs.validate(changes)
    assert refused.value.field == "bob_x_m"
    with pytest.raises(ValueError, match=words):  # solve refuses too, called without the check
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **changes})
