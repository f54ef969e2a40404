"""The double pendulum's Lagrange equations (worked example ``double-pendulum-lagrange``, section 7.5) against an
independent computation: Newton's law for each bob written from scratch in Cartesian components, with the two rod
tensions as unknowns (four equations in θ̈₁, θ̈₂, S₁, S₂, solved by numpy), and the energies summed bob by bob from
their Cartesian velocities.

Tolerance 1e-10 relative to the acceleration scale g/l + θ̇²: both sides solve small well-conditioned systems of
O(1) numbers (det M ≥ m₁ m₂ l₁² l₂² > 0), so they agree to round-off amplified by the condition number (< 1e3 here);
the energies are sums of products, 1e-12 of m g l + T.

No input in range is physically impossible (any masses, lengths and starting state), so nothing is refused.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch07.double_pendulum_lagrange_example import EXAMPLE

CASES = [
    {},
    {"theta2_0_deg": -40.0, "theta1_rate_0_deg_s": 200.0, "theta2_rate_0_deg_s": -100.0, "m2_kg": 3.0},
    {"m1_kg": 0.2, "m2_kg": 5.0, "l1_m": 0.4, "l2_m": 1.7, "theta1_0_deg": 170.0, "theta2_0_deg": 95.0},
    {"g_m_s2": 0.0, "theta1_rate_0_deg_s": 360.0, "theta2_rate_0_deg_s": 30.0, "theta2_0_deg": 120.0},
]


def _newton(values):
    """θ̈₁, θ̈₂ from the bobs' Newton's laws with the tensions S₁ (rod 1) and S₂ (rod 2) unknown (x horizontal, z up)."""
    m1, m2, l1, l2, g = (values[n] for n in ("m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"))
    t1, t2 = math.radians(values["theta1_0_deg"]), math.radians(values["theta2_0_deg"])
    w1, w2 = math.radians(values["theta1_rate_0_deg_s"]), math.radians(values["theta2_rate_0_deg_s"])
    u1 = np.array([math.sin(t1), -math.cos(t1)])  # along rod 1, pivot → A
    u2 = np.array([math.sin(t2), -math.cos(t2)])  # along rod 2, A → B
    n1 = np.array([math.cos(t1), math.sin(t1)])  # d u1/dθ1
    n2 = np.array([math.cos(t2), math.sin(t2)])
    # a_A = l1 (n1 θ̈1 − u1 θ̇1²), a_B = a_A + l2 (n2 θ̈2 − u2 θ̇2²)
    # A: m1 a_A = −S1 u1 + S2 u2 + m1 g;   B: m2 a_B = −S2 u2 + m2 g
    A = np.zeros((4, 4))
    b = np.zeros(4)
    weight = np.array([0.0, -g])
    A[0:2, 0] = m1 * l1 * n1
    A[0:2, 2] = u1
    A[0:2, 3] = -u2
    b[0:2] = m1 * l1 * u1 * w1 * w1 + m1 * weight
    A[2:4, 0] = m2 * l1 * n1
    A[2:4, 1] = m2 * l2 * n2
    A[2:4, 3] = u2
    b[2:4] = m2 * (l1 * u1 * w1 * w1 + l2 * u2 * w2 * w2) + m2 * weight
    solution = np.linalg.solve(A, b)
    v_a = l1 * n1 * w1
    v_b = v_a + l2 * n2 * w2
    kinetic = 0.5 * m1 * v_a @ v_a + 0.5 * m2 * v_b @ v_b
    potential = m1 * g * (-l1 * math.cos(t1)) + m2 * g * (-l1 * math.cos(t1) - l2 * math.cos(t2))
    return solution[0], solution[1], kinetic, potential


@pytest.mark.parametrize("changes", CASES)
def test_accelerations_and_energies_match_newtons_laws_for_each_bob(changes):
    values = EXAMPLE.inputs.validate(changes)
    acc1, acc2, kinetic, potential = _newton(values)
    out = EXAMPLE.solve(values).outputs
    rates = (math.radians(values["theta1_rate_0_deg_s"]), math.radians(values["theta2_rate_0_deg_s"]))
    scale = values["g_m_s2"] / min(values["l1_m"], values["l2_m"]) + max(r * r for r in rates) + 1e-300
    assert out["theta1_acceleration_rad_s2"] == pytest.approx(acc1, abs=1e-10 * scale)
    assert out["theta2_acceleration_rad_s2"] == pytest.approx(acc2, abs=1e-10 * scale)
    m, l = values["m1_kg"] + values["m2_kg"], values["l1_m"] + values["l2_m"]
    energy = m * values["g_m_s2"] * l + kinetic
    assert out["kinetic_energy_J"] == pytest.approx(kinetic, abs=1e-12 * energy)
    assert out["potential_energy_J"] == pytest.approx(potential, abs=1e-12 * energy)


@pytest.mark.parametrize("changes", CASES)
def test_the_check_step_agrees_with_the_engine_and_holds_the_energy(changes):
    check = EXAMPLE.solve(EXAMPLE.inputs.validate(changes)).steps[-1]
    assert check.title.startswith("Check")
    assert np.allclose(
        check.values["thetaddot_Lagrange"], check.values["thetaddot_Newton_Euler"], rtol=1e-12, atol=1e-12
    )
    assert check.values["dE/dt"] == 0.0  # within round-off of its scale, so shown as 0
