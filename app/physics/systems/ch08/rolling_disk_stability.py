"""Steady upright rolling of the disk and its stability, by linearising the multiplier equations numerically.

Upright rolling straight along +x at spin Ω (rad/s) — θ = 0, ψ̇ = θ̇ = 0,
φ̇ = Ω, ẋ = r Ω — is a motion of the equations of
:mod:`.rolling_disk_constrained` for every Ω. Small departures in the lean
θ, lean rate θ̇ and heading rate ψ̇ obey ż = J(Ω) z with z = (θ, θ̇, ψ̇) and
J (3, 3) (1/s) found here by central differences of the accelerations the
index-reduced equations give, [M Aᵀ; A 0] [q̈; λ] = [f; c], at the upright
state. One eigenvalue of J is 0 (a steady turn is as good as a straight run);
the other two are ±√(−k) with the lean stiffness k = −½ Σ λ² (1/s²):
k > 0, the lean oscillates about upright (stable, to first order); k < 0,
it grows. The critical spin Ω_c is the root of k(Ω) = 0.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from app.physics.constrained.system import ConstrainedSystem
from app.physics.systems.ch08.rolling_disk_constrained import HEADING, LEAN, SPIN

#: Central-difference step (rad, rad/s): truncation ~h² and rounding ~ε/h both stay below 1e-10 of J's entries.
JACOBIAN_STEP = 1e-5
#: Indices into the state (q, v) of z = (θ, θ̇, ψ̇).
LINEARISED = (LEAN, 5 + LEAN, 5 + HEADING)


def constrained_accelerations(system: ConstrainedSystem, state: np.ndarray) -> np.ndarray:
    """q̈ (5,) at ``state`` = (q, v) (10,) from [M Aᵀ; A 0] [q̈; λ] = [f; c] (the rolling rows imposed on
    accelerations)."""
    n, m = system.n_coordinates, system.n_constraints
    q, v = state[:n], state[n:]
    mass, forces = system.mass_and_forces(0.0, q, v)
    _, rows, convective = system.constraint_terms(q, v)
    saddle = np.block([[mass, rows.T], [rows, np.zeros((m, m))]])
    return np.linalg.solve(saddle, np.concatenate([forces, convective]))[:n]


def upright_state(system: ConstrainedSystem, spin_rate_rad_s: float) -> np.ndarray:
    """(q, v) (10,) of upright rolling along +x at spin Ω (rad/s); the radius is ``system.parameters[1]`` (m)."""
    state = np.zeros(10)
    state[5 + SPIN] = spin_rate_rad_s
    state[5] = float(system.parameters[1]) * spin_rate_rad_s
    return state


def upright_jacobian(system: ConstrainedSystem, spin_rate_rad_s: float) -> np.ndarray:
    """J (3, 3) = ∂(θ̇, θ̈, ψ̈)/∂(θ, θ̇, ψ̇) at upright rolling with spin Ω (rad/s)."""
    state = upright_state(system, spin_rate_rad_s)
    jacobian = np.empty((3, 3))
    for column, index in enumerate(LINEARISED):
        up, down = state.copy(), state.copy()
        up[index] += JACOBIAN_STEP
        down[index] -= JACOBIAN_STEP
        rate_up = np.concatenate([up[5:], constrained_accelerations(system, up)])
        rate_down = np.concatenate([down[5:], constrained_accelerations(system, down)])
        jacobian[:, column] = (rate_up - rate_down)[list(LINEARISED)] / (2.0 * JACOBIAN_STEP)
    return jacobian


def upright_eigenvalues(system: ConstrainedSystem, spin_rate_rad_s: float) -> np.ndarray:
    """The three eigenvalues (1/s, complex) of the linearised lean-and-heading motion at spin Ω (rad/s)."""
    return np.linalg.eigvals(upright_jacobian(system, spin_rate_rad_s))


def lean_stiffness_1_s2(system: ConstrainedSystem, spin_rate_rad_s: float) -> float:
    """k = −½ Σ λ² (1/s²): positive where upright rolling at Ω is stable to first order, negative where the lean
    grows."""
    return float(-0.5 * np.sum(upright_eigenvalues(system, spin_rate_rad_s) ** 2).real)


def critical_spin_rad_s(system: ConstrainedSystem) -> float:
    """Ω_c (rad/s): upright rolling is stable for |φ̇| > Ω_c (0 if it is stable at rest, as without gravity)."""
    if lean_stiffness_1_s2(system, 0.0) >= 0.0:
        return 0.0
    mass_kg, radius_m, g_m_s2 = (float(value) for value in system.parameters)
    # Bracket: spin energy ~ m r² Ω² against the fall's m g r, with a factor 100 of room.
    high = 10.0 * np.sqrt(g_m_s2 / radius_m)
    if lean_stiffness_1_s2(system, high) <= 0.0:
        raise ValueError(
            f"no spin below {high:.3g} rad/s steadies the upright disk (mass_kg = {mass_kg}, radius_m = "
            f"{radius_m}, g_m_s2 = {g_m_s2})"
        )
    return float(brentq(lambda spin: lean_stiffness_1_s2(system, spin), 0.0, high, xtol=1e-13, rtol=1e-14))


def stability_sentence(spin_rate_rad_s: float, critical_rad_s: float) -> str:
    """'upright rolling at 12.0 rad/s is stable (critical 5.7 rad/s)' — for a readout or a report."""
    verdict = "stable" if abs(spin_rate_rad_s) > critical_rad_s else "unstable"
    return f"upright rolling at {abs(spin_rate_rad_s):.1f} rad/s is {verdict} (critical {critical_rad_s:.1f} rad/s)"
