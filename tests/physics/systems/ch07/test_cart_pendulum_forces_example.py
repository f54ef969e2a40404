"""The pendulum on the sprung, driven cart (worked example ``cart-pendulum-generalized-forces``, section 7.4) against
an independent computation: Newton's laws for the cart and the bob written from scratch, with the rod's tension S
and the rail's vertical push N as unknowns (four equations in ẍ, θ̈, S, N), solved by numpy; and each generalized
force as a central difference of the virtual work ``Σ F·δr`` of its force through a small change of one coordinate.

Tolerances: the accelerations and the tension come from a 4×4 and a 2×2 solve of well-conditioned O(1) systems,
1e-10 relative to the largest acceleration term (g, ẋ-terms, F/M); the central differences (step 1e-6) are exact
for forces whose virtual work is linear in the step (the spring, the drive) and have truncation error about
1e-12 m·g·l for gravity, so 1e-8 of the force scale.

No input in range is physically impossible here (any masses, spring, drive and starting state), so nothing is refused.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch07.cart_pendulum_forces_example import EXAMPLE

CASES = [
    {},
    {"force_amplitude_N": 10.0, "x0_m": 0.3, "theta_rate_0_deg_s": 90.0, "x_rate_0_m_s": 1.0},
    {
        "cart_mass_kg": 0.5,
        "bob_mass_kg": 4.0,
        "length_m": 2.5,
        "stiffness_N_m": 300.0,
        "x0_m": -1.2,
        "theta_0_deg": 120.0,
    },
    {"theta_0_deg": -75.0, "theta_rate_0_deg_s": -400.0, "g_m_s2": 1.62, "force_amplitude_N": 250.0},
]
H = 1e-6


def _newton(values):
    """(ẍ, θ̈, S, N) from the cart's and the bob's Newton's laws (x along the rail, z up)."""
    M, m, l = values["cart_mass_kg"], values["bob_mass_kg"], values["length_m"]
    k, F, g = values["stiffness_N_m"], values["force_amplitude_N"], values["g_m_s2"]
    x, th, w = values["x0_m"], math.radians(values["theta_0_deg"]), math.radians(values["theta_rate_0_deg_s"])
    e = np.array([-math.sin(th), math.cos(th)])  # bob → cart, along the rod
    # bob: m (ẍ + l cos θ θ̈ − l sin θ θ̇², l sin θ θ̈ + l cos θ θ̇²) = S e + (0, −m g)
    # cart: M (ẍ, 0) = (F − k x, 0) − S e + (0, N − M g)
    A = np.array(
        [
            [m, m * l * math.cos(th), -e[0], 0.0],
            [0.0, m * l * math.sin(th), -e[1], 0.0],
            [M, 0.0, e[0], 0.0],
            [0.0, 0.0, e[1], -1.0],
        ]
    )
    b = np.array([m * l * math.sin(th) * w * w, -m * g - m * l * math.cos(th) * w * w, F - k * x, -M * g])
    return np.linalg.solve(A, b)


def _generalized_forces(values):
    """(Q_x, Q_θ) of the drive, the spring and gravity, each ΣF·δr/δq by central differences of the positions."""
    m, l = values["bob_mass_kg"], values["length_m"]
    k, F, g = values["stiffness_N_m"], values["force_amplitude_N"], values["g_m_s2"]
    x, th = values["x0_m"], math.radians(values["theta_0_deg"])

    def points(x_, th_):
        return np.array([x_, 0.0]), np.array([x_ + l * math.sin(th_), -l * math.cos(th_)])

    forces_cart = np.array([F - k * x, 0.0])
    force_bob = np.array([0.0, -m * g])
    found = []
    for dq in ((H, 0.0), (0.0, H)):
        cart_p, bob_p = points(x + dq[0], th + dq[1])
        cart_m, bob_m = points(x - dq[0], th - dq[1])
        found.append(float(forces_cart @ (cart_p - cart_m) + force_bob @ (bob_p - bob_m)) / (2 * H))
    return found


@pytest.mark.parametrize("changes", CASES)
def test_accelerations_and_tension_match_newtons_laws_with_the_constraint_forces_as_unknowns(changes):
    values = EXAMPLE.inputs.validate(changes)
    x_acc, th_acc, tension, _ = _newton(values)
    out = EXAMPLE.solve(values).outputs
    l, g = values["length_m"], values["g_m_s2"]
    w = math.radians(values["theta_rate_0_deg_s"])
    scale = (
        g
        + l * w * w
        + (values["force_amplitude_N"] + values["stiffness_N_m"] * abs(values["x0_m"])) / values["cart_mass_kg"]
    )
    assert out["x_acceleration_m_s2"] == pytest.approx(x_acc, abs=1e-10 * scale)
    assert out["theta_acceleration_rad_s2"] == pytest.approx(th_acc, abs=1e-10 * scale / l)
    assert out["rod_tension_N"] == pytest.approx(tension, abs=1e-10 * scale * values["bob_mass_kg"])


@pytest.mark.parametrize("changes", CASES)
def test_generalized_forces_match_the_virtual_work_of_the_forces(changes):
    values = EXAMPLE.inputs.validate(changes)
    q_x, q_theta = _generalized_forces(values)
    out = EXAMPLE.solve(values).outputs
    scale = (
        values["force_amplitude_N"]
        + values["stiffness_N_m"] * abs(values["x0_m"])
        + values["bob_mass_kg"] * values["g_m_s2"]
    )
    assert out["Q_x_N"] == pytest.approx(q_x, abs=1e-8 * scale)
    assert out["Q_theta_N_m"] == pytest.approx(q_theta, abs=1e-8 * scale * values["length_m"])


def test_the_constraint_forces_contribute_nothing_and_the_check_agrees():
    steps = EXAMPLE.solve(EXAMPLE.inputs.validate(CASES[2])).steps
    constraint = next(s for s in steps if s.title.startswith("Constraint forces"))
    assert np.all(constraint.values["Q^S/S"] == 0.0) and np.all(constraint.values["Q^rail/N_rail"] == 0.0)
    check = steps[-1]
    assert check.title.startswith("Check")
    assert check.values["xddot_Lagrange"] == pytest.approx(check.values["xddot_Newton_Euler"], rel=1e-12)
    assert check.values["thetaddot_Lagrange"] == pytest.approx(check.values["thetaddot_Newton_Euler"], rel=1e-12)
