"""The method registry (app/physics/solvers/registry.py): every declared fact is measured.

The problem with a known solution is a torque-free asymmetric rigid body
(principal moments (2, 3, 4)·10⁻³ kg·m²): its body angular velocity is a Jacobi
elliptic closed form (app/physics/systems/ch10/free_body_elliptic.py), and it
is a rigid body about a fixed point, so every registered method — the
splittings included — can integrate it.
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.bodies.rigid_body import PivotedBody, rigid_body_rhs
from app.physics.solvers import METHODS, OdeSystem, make_integrator, simulate
from app.physics.solvers.kernels import Kernel
from app.physics.solvers.registry import STEP_RATIO, method_spec
from app.physics.systems.ch10.free_body_elliptic import free_body_elliptic

INERTIA = (2e-3, 3e-3, 4e-3)  # kg·m²
OMEGA0 = np.array([1.0, 4.0, 2.0])  # rad/s, body frame: |ω| ≈ 4.6 rad/s, well away from the separatrix
Y0 = np.concatenate([[1.0, 0.0, 0.0, 0.0], OMEGA0])
BODY = PivotedBody(INERTIA)
SYSTEM = BODY.system()
T_END, RATE = 2.0, 30.0  # s, Hz
FRAMES_T = np.arange(int(T_END * RATE) + 1) / RATE
EXACT_OMEGA = free_body_elliptic(inertia=INERTIA, omega0_body=OMEGA0).omega_body(FRAMES_T)


def omega_error(result, exact: np.ndarray = EXACT_OMEGA) -> float:
    """Largest body-rate error (rad/s) over all frames against the elliptic closed form ``exact`` (F+1, 3)."""
    assert result.status == "ok"
    return float(np.max(np.abs(result.states[:, 4:7] - exact)))


#: Steps per frame swept for each fixed-step method: coarse enough that the error stays far
#: above round-off (smallest observed 1e-10), fine enough to be in the asymptotic range.
FIXED_STEPS = {"rk4": (2, 4, 8), "splitting4": (1, 2, 4), "splitting2": (2, 4, 8), "splitting6": (1, 2, 4), "splitting8": (1, 2, 4)}
#: Frame rate (Hz) of a fixed-step method's sweep where it is not RATE: at 30 Hz the order-6 and order-8
#: splittings are already at round-off with one step per frame (8e-10 and 2e-14 rad/s), so they are
#: swept at 5 Hz (h·|ω| = 0.92, 0.46, 0.23), where their errors (3.5e-5 … 8.9e-9, 3.5e-8 … 5.1e-13 rad/s)
#: are well above it.
FRAME_RATE_FOR_ORDER = {"splitting6": 5.0, "splitting8": 5.0}
#: Tolerances swept for the adaptive method.
ADAPTIVE_RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)


def test_keys_and_step_ratios_are_the_api_contract():
    assert list(METHODS) == ["splitting4", "splitting2", "rk4", "dopri5", "splitting6", "splitting8"]
    assert STEP_RATIO == {"splitting4": 0.25, "splitting2": 0.02, "rk4": 0.1, "splitting6": 1.0, "splitting8": 1.0}
    for name, spec in METHODS.items():
        assert spec.name == name and make_integrator(name, steps_per_frame=1).spec is spec


@pytest.mark.parametrize("method", list(METHODS))
def test_measured_order_matches_the_declared_order(method):
    spec = METHODS[method]
    if spec.adaptive:
        # An adaptive method of order p spends work N ∝ error^(−1/p): the slope of log error
        # against log(rhs evaluations) over five tolerances is −p.
        errors, evals = [], []
        for rtol in ADAPTIVE_RTOLS:
            result = simulate(SYSTEM, make_integrator(method, rtol=rtol), Y0, t_end_s=T_END, frame_rate_hz=RATE)
            errors.append(omega_error(result))
            evals.append(result.rhs_evals)
        observed = -np.polyfit(np.log(evals), np.log(errors), 1)[0]
        # Observed 5.45 for dopri5 (work includes the start-up and frame-bound steps). ±0.6: a wrong
        # tableau or controller exponent moves the slope by ≥ 1.
        assert abs(observed - spec.order) <= 0.6, (errors, evals, observed)
        return
    errors = []
    rate = FRAME_RATE_FOR_ORDER.get(method, RATE)
    exact = free_body_elliptic(inertia=INERTIA, omega0_body=OMEGA0).omega_body(np.arange(int(T_END * rate) + 1) / rate)
    for steps in FIXED_STEPS[method]:
        result = simulate(SYSTEM, make_integrator(method, steps_per_frame=steps), Y0, t_end_s=T_END, frame_rate_hz=rate)
        errors.append(omega_error(result, exact))
    observed = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # Halving h divides the error by 2^p. Observed: rk4 4.0/4.0, splitting4 4.0/4.0, splitting2 2.0/2.0,
    # splitting6 5.96/5.99, splitting8 8.09/7.99.
    # ±0.3 leaves room for pre-asymptotic terms; a wrong coefficient drops the order by at least one.
    assert np.all(np.abs(observed - spec.order) <= 0.3), (method, errors, observed)


def test_every_registered_method_has_a_sweep():
    assert set(FIXED_STEPS) | {m for m, s in METHODS.items() if s.adaptive} == set(METHODS)


def counting(kernel: Kernel, calls: list[int]) -> Kernel:
    """The same kernel whose Python twin counts its calls."""

    def counted(*args):
        calls[0] += 1
        return kernel.python(*args)

    return Kernel(compiled=kernel.compiled, python=counted)


@pytest.mark.parametrize("method", [m for m, s in METHODS.items() if not s.adaptive])
def test_declared_cost_per_step_is_what_the_kernel_calls(method):
    # Run the Python twin with a counting rhs / torque: the calls per step are the spec's evals_per_step.
    calls = [0]
    system = OdeSystem(
        rhs=counting(SYSTEM.rhs, calls), parameters=SYSTEM.parameters, state_names=SYSTEM.state_names,
        project=SYSTEM.project, torque=counting(SYSTEM.torque, calls),
    )
    integrator = make_integrator(method, steps_per_frame=3)
    result = simulate(system, integrator, Y0, t_end_s=5 / RATE, frame_rate_hz=RATE, backend="python")
    assert result.steps == 15
    # A splitting's last kick of a step leaves the torque its next step starts with, so its run (one
    # run_frames call here) evaluates the torque once more, at the start.
    per_run = 1 if METHODS[method].needs_torque else 0
    assert calls[0] == result.rhs_evals == 15 * METHODS[method].evals_per_step + per_run


def test_needs_torque_is_checked_with_a_clear_error():
    plain = OdeSystem(rhs=rigid_body_rhs, parameters=SYSTEM.parameters, state_names=SYSTEM.state_names)
    for name, spec in METHODS.items():
        if spec.needs_torque:
            with pytest.raises(ValueError, match=f"{name} needs a rigid body.*torque"):
                simulate(plain, make_integrator(name, steps_per_frame=1), Y0, t_end_s=0.1, frame_rate_hz=RATE)
        else:
            assert simulate(plain, make_integrator(name, steps_per_frame=1), Y0, t_end_s=0.1, frame_rate_hz=RATE).ok


def test_unknown_method_names_the_field():
    with pytest.raises(ValueError, match="unknown method 'euler'"):
        method_spec("euler")
