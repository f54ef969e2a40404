"""``dynlab constrained``: work against precision for the chapter-8 DAE algorithms, one run, one machine.

Three cases, each a :class:`~app.physics.constrained.system.ConstrainedSystem` from its
consistent start, each with a reference for the positions at the final time:

* ``cartesian-pendulum`` — the unit problem (m = 1 kg, L = 1 m, g = 1 m/s², released
  at rest from the horizontal), 1 s; reference: the exact simple-pendulum motion,
  sin(θ/2) = k sn(K − t√(g/L) | k²) with k = sin(θ₀/2), from ``scipy.special.ellipj``;
* ``massive-four-bar`` — engineer E's four-bar with link masses at its defaults
  (9 coordinates, 8 constraints), 2 s; reference: its one-degree-of-freedom
  equation in the crank angle (DOP853, rtol 1e-13), mapped to the nine
  coordinates by chapter 4's loop closure;
* ``andrews`` — Andrews' squeezing mechanism (7 coordinates, 6 constraints),
  0.03 s; reference: the test set's published solution at t = 0.03 s.

Every algorithm (uncorrected index reduction, Baumgarte, projection, coordinate
partitioning) runs with each integrator through its setting sweep (RK4: steps
per frame; Dormand–Prince: rtol); scipy's ``solve_ivp`` Radau and BDF run on the
index-1 equations ``[M −Cᵀ; C 0] [v̇; λ] = [f; c]`` with a numpy right-hand side
and no projection. For each run: process CPU time (best of a few), the error
(largest absolute difference of the final positions from the reference, over
all coordinates, in their own units: m or rad) and the final constraint residuals
(largest |g| and |C v|). Writes ``docs/bench/constrained_precision.json`` and one
SVG per case, ``docs/bench/constrained-precision-<case>.svg`` (hyphens: the
names the Solver lab serves under ``/bench/``).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from app.bench.plot import work_precision_svg
from app.bench.work_precision import OUT_DIR, Progress, _machine, _timed, cost_at_error
from app.physics.constrained.algorithms import ALGORITHMS, algorithm_system, repartition_count
from app.physics.constrained.residuals import constraint_residuals
from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers import make_integrator, simulate

REPORT_FILE = "constrained_precision.json"
SVG_PREFIX = "constrained-precision-"


@dataclass(frozen=True)
class ConstrainedCase:
    """One benchmarked motion: a constrained system from a consistent start to ``t_end_s``, with reference positions."""

    id: str
    title: str
    system: ConstrainedSystem
    positions0: np.ndarray
    rates0: np.ndarray
    t_end_s: float
    frame_rate_hz: float
    #: Reference positions (n,) at ``t_end_s``, in the coordinates' own units.
    reference_positions: np.ndarray
    reference_name: str
    error_unit: str
    #: The smallest error the reference resolves (same unit): below it a run's "error" is the reference's own.
    reference_floor: float
    #: RK4 steps per frame swept for this case (its time scales differ: 1 s pendulum, 0.03 s mechanism).
    rk4_steps_per_frame: tuple[int, ...] = (1, 2, 4, 8, 16, 32, 64)
    #: Baumgarte's α = β (1/s): critical damping of the residuals at a rate well above the motion's, below 1/h.
    baumgarte_1_s: float = 10.0
    #: Indices of angle coordinates: their error is taken modulo 2π.
    angle_coordinates: tuple[int, ...] = ()

    def position_error(self, positions: np.ndarray) -> float:
        """Largest |q − q_ref| at the final time over all coordinates (angles compared modulo 2π)."""
        difference = np.asarray(positions, dtype=float) - self.reference_positions
        for i in self.angle_coordinates:
            difference[i] = math.remainder(difference[i], 2.0 * math.pi)
        return float(np.max(np.abs(difference)))


def cartesian_pendulum_case() -> ConstrainedCase:
    from app.physics.systems.ch08.cartesian_pendulum import exact_states, pendulum_system

    q0, v0 = np.array([1.0, 0.0]), np.zeros(2)
    t_end = 1.0
    exact = exact_states(1.0, 1.0, np.concatenate([q0, v0]), np.array([t_end]))[0]
    return ConstrainedCase(
        id="cartesian-pendulum",
        title="Cartesian pendulum, unit problem, 1 s",
        system=pendulum_system(1.0, 1.0, 1.0),
        positions0=q0,
        rates0=v0,
        t_end_s=t_end,
        frame_rate_hz=60.0,
        reference_positions=exact[:2],
        reference_name=(
            "the exact motion released at rest from the horizontal, m = 1 kg, L = 1 m, g = 1 m/s² "
            "(Jacobi elliptic functions, scipy.special.ellipj)"
        ),
        error_unit="m",
        reference_floor=1e-14,
        rk4_steps_per_frame=(1, 2, 4, 8, 16, 32, 64),
        baumgarte_1_s=5.0,
    )


def massive_four_bar_case() -> ConstrainedCase:
    from app.physics.systems.ch08.massive_four_bar import (
        PARAMETERS,
        crank_acceleration_rad_s2,
        four_bar_absolute_motion,
        massive_four_bar_initial_state,
        massive_four_bar_system,
    )

    params = PARAMETERS.defaults()
    q0, v0 = massive_four_bar_initial_state(params)
    t_end = 2.0
    crank = solve_ivp(
        lambda _t, y: np.array([y[1], float(crank_acceleration_rad_s2(params, np.array([y[0]]), np.array([y[1]]))[0])]),
        (0.0, t_end),
        np.array([q0[2], v0[2]]),
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
    )
    theta, omega = crank.y[:, -1]
    q_ref, _, _ = four_bar_absolute_motion(params, np.array([theta]), np.array([omega]), np.zeros(1))
    return ConstrainedCase(
        id="massive-four-bar",
        title=f"Massive four-bar, {t_end:g} s (9 coordinates, 8 constraints)",
        system=massive_four_bar_system(params),
        positions0=q0,
        rates0=v0,
        t_end_s=t_end,
        frame_rate_hz=60.0,
        reference_positions=q_ref[0],
        reference_name=(
            "the one-degree-of-freedom equation in the crank angle (DOP853, rtol 1e-13) through "
            "chapter 4's loop closure"
        ),
        error_unit="m or rad",
        reference_floor=1e-10,
        rk4_steps_per_frame=(1, 2, 4, 8, 16, 32, 64),
        baumgarte_1_s=10.0,
        angle_coordinates=(2, 5, 8),
    )


def andrews_case() -> ConstrainedCase:
    from app.physics.systems.ch08.andrews_squeezer import (
        REFERENCE_POSITIONS_RAD,
        REFERENCE_TIME_S,
        andrews_initial_state,
        andrews_system,
    )

    q0, v0 = andrews_initial_state()
    return ConstrainedCase(
        id="andrews",
        title="Andrews' squeezing mechanism, 0.03 s (7 coordinates, 6 constraints)",
        system=andrews_system(),
        positions0=q0,
        rates0=v0,
        t_end_s=REFERENCE_TIME_S,
        frame_rate_hz=1000.0,
        reference_positions=REFERENCE_POSITIONS_RAD,
        reference_name="the published solution of the IVP test set (PSIDE, rtol = atol = 1e-14)",
        error_unit="rad",
        reference_floor=2e-9,
        rk4_steps_per_frame=(4, 8, 16, 32, 64, 128, 256),
        baumgarte_1_s=500.0,
    )


CASES: dict[str, Callable[[], ConstrainedCase]] = {
    "cartesian-pendulum": cartesian_pendulum_case,
    "massive-four-bar": massive_four_bar_case,
    "andrews": andrews_case,
}


def index1_rhs(system: ConstrainedSystem) -> Callable[[float, np.ndarray], np.ndarray]:
    """``y = (q, v)`` (2n,) ↦ ``(v, v̇)`` from ``[M −Cᵀ; C 0] [v̇; λ] = [f; c]`` with numpy, as a scipy user would write
    it."""
    n, m = system.n_coordinates, system.n_constraints

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:n], y[n:]
        mass, forces = system.mass_and_forces(t, q, v)
        _, jacobian, convective = system.constraint_terms(q, v)
        kkt = np.zeros((n + m, n + m))
        kkt[:n, :n], kkt[:n, n:], kkt[n:, :n] = mass, -jacobian.T, jacobian
        solution = np.linalg.solve(kkt, np.concatenate([forces, convective]))
        return np.concatenate([v, solution[:n]])

    return rhs


#: Dormand–Prince tolerances swept for every case.
DOPRI5_RTOLS = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
INTEGRATORS = {"rk4": ("RK4", "steps_per_frame"), "dopri5": ("Dormand–Prince 5(4)", "rtol")}


def our_sweeps(case: ConstrainedCase) -> list[tuple[str, str, str, str, tuple[float, ...]]]:
    """(algorithm, integrator, label, setting name, settings) for every DAE algorithm with each compiled integrator."""
    settings = {"rk4": case.rk4_steps_per_frame, "dopri5": DOPRI5_RTOLS}
    return [
        (
            algorithm,
            integrator,
            f"{algorithm} + {INTEGRATORS[integrator][0]}",
            INTEGRATORS[integrator][1],
            settings[integrator],
        )
        for algorithm in ALGORITHMS
        for integrator in INTEGRATORS
    ]


@dataclass(frozen=True)
class Run:
    """One measured run: final positions (n,) and rates (n,), best CPU time (s), right-hand-side evaluations, status."""

    positions: np.ndarray
    rates: np.ndarray
    cpu_s: float
    rhs_evals: int
    status: str
    #: Times coordinate partitioning re-chose its dependent coordinates (0 for every other method).
    repartitions: int = 0


def run_ours(case: ConstrainedCase, algorithm: str, integrator_name: str, setting: float, *, repeats: int = 3) -> Run:
    """One of our DAE algorithms with a compiled integrator; best process CPU time of the integration over
    ``repeats``."""
    if integrator_name == "rk4":
        integrator = make_integrator("rk4", steps_per_frame=int(setting))
    else:
        integrator = make_integrator(integrator_name, rtol=float(setting))
    gain = case.baumgarte_1_s if algorithm == "baumgarte" else 0.0
    y0 = np.concatenate([case.positions0, case.rates0])
    n = case.system.n_coordinates

    def once():
        ode = algorithm_system(case.system, algorithm, alpha_1_s=gain, beta_1_s=gain, q=case.positions0)
        return ode, simulate(ode, integrator, y0, t_end_s=case.t_end_s, frame_rate_hz=case.frame_rate_hz)

    once()  # compile and warm
    best = math.inf
    for _ in range(repeats):
        ode, result = once()
        best = min(best, result.cpu_s)
        if result.cpu_s > 0.5:
            break
    final = result.states[-1]
    status = (
        result.status
        if result.status == "ok" and len(result.states) == round(case.t_end_s * case.frame_rate_hz) + 1
        else "failed"
    )
    return Run(final[:n], final[n:], best, int(result.rhs_evals), status, repartition_count(ode.parameters, n))


def run_scipy(case: ConstrainedCase, method: str, rtol: float) -> Run:
    """scipy ``solve_ivp`` (``method`` = "Radau" or "BDF") on the index-1 equations, atol = rtol·1e-3, no projection."""
    rhs = index1_rhs(case.system)
    y0 = np.concatenate([case.positions0, case.rates0])
    n = case.system.n_coordinates

    def run():
        return solve_ivp(rhs, (0.0, case.t_end_s), y0, method=method, rtol=rtol, atol=rtol * 1e-3)

    solution, cpu = _timed(run, repeats=2)
    final = solution.y[:, -1]
    status = "ok" if solution.success and np.all(np.isfinite(final)) else "failed"
    return Run(final[:n], final[n:], cpu, int(solution.nfev), status)


#: scipy sweeps: (method id, label, rtol values).
SCIPY_SWEEPS = (
    ("scipy-Radau", "scipy Radau, index 1 (numpy RHS)", (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)),
    ("scipy-BDF", "scipy BDF, index 1 (numpy RHS)", (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)),
)


_PROJECTION = {
    "uncorrected": "none",
    "baumgarte": "none (the residuals are fed back into the accelerations)",
    "projection": "positions onto g = 0 and velocities onto C v = 0 after every step",
    "partitioning": "none (dependent coordinates solved from the independent ones by Newton at every stage)",
}


def _point(case: ConstrainedCase, setting: float, run: Run) -> dict[str, Any]:
    """One point of a sweep: the setting, cost, error and the final residuals (m or rad; m/s or rad/s)."""
    finite = run.status == "ok" and bool(np.all(np.isfinite(run.positions)) and np.all(np.isfinite(run.rates)))
    point: dict[str, Any] = {
        "setting": setting,
        "cpu_s": run.cpu_s,
        "rhs_evals": run.rhs_evals,
        "repartitions": run.repartitions,
    }
    if not finite:
        point.update(
            error=None,
            position_residual=None,
            velocity_residual=None,
            status=run.status if run.status != "ok" else "non_finite",
        )
        return point
    position_residual, velocity_residual = constraint_residuals(case.system, np.concatenate([run.positions, run.rates]))
    point.update(
        error=case.position_error(run.positions),
        position_residual=float(position_residual[0]),
        velocity_residual=float(velocity_residual[0]),
        status="ok",
    )
    return point


def run_benchmark(case_ids: Sequence[str] | None = None, *, quick: bool = False) -> dict[str, Any]:
    """Measure every sweep of every case; return the report dictionary."""
    cases = [CASES[c]() for c in (case_ids or CASES)]
    every = 2 if quick else 1
    sweeps = {
        case.id: [(a, i, label, s, values[::every]) for a, i, label, s, values in our_sweeps(case)] for case in cases
    }
    scipy_sweeps = [(m, label, values[::every]) for m, label, values in SCIPY_SWEEPS]
    runs = sum(len(s[4]) for case_sweeps in sweeps.values() for s in case_sweeps) + len(cases) * sum(
        len(s[2]) for s in scipy_sweeps
    )
    progress = Progress(runs)
    report: dict[str, Any] = {
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "machine": _machine(),
        "error_measure": (
            "largest |q − q_ref| over all coordinates at the final time, in each coordinate's unit (m or rad)"
        ),
        "residuals": (
            "position_residual: largest |g(q)| (m, or rad for angle constraints); "
            "velocity_residual: largest |C v| (m/s or rad/s), both at the final time"
        ),
        "cases": [],
    }
    for case in cases:
        methods = []
        for method, integrator, label, setting_name, settings in sweeps[case.id]:
            points = []
            for setting in settings:
                progress.step(f"{case.id}: {label} {setting_name}={setting:g}")
                points.append(_point(case, setting, run_ours(case, method, integrator, setting)))
            methods.append(
                {
                    "method": f"{method}-{integrator}",
                    "algorithm": method,
                    "integrator": integrator,
                    "family": "dynlab",
                    "label": label,
                    "setting_name": setting_name,
                    "baumgarte_1_s": case.baumgarte_1_s if method == "baumgarte" else None,
                    "projection": _PROJECTION[method],
                    "points": points,
                }
            )
        for method, label, settings in scipy_sweeps:
            points = []
            for rtol in settings:
                progress.step(f"{case.id}: {label} rtol={rtol:g}")
                points.append(_point(case, rtol, run_scipy(case, method.split("-", 1)[1], rtol)))
            methods.append(
                {
                    "method": method,
                    "algorithm": "index-1",
                    "integrator": method.split("-", 1)[1],
                    "family": "scipy",
                    "label": label,
                    "setting_name": "rtol",
                    "projection": "none",
                    "points": points,
                }
            )
        report["cases"].append(_case_entry(case, methods))
    return report


def _case_entry(case: ConstrainedCase, methods: list[dict[str, Any]]) -> dict[str, Any]:
    """A case's part of the report, with the keys the work-precision plot reads (title, error_unit, methods, …)."""
    cost = {}
    for target in (1e-4, 1e-6, 1e-8):
        cost[f"{target:.0e}"] = {m["method"]: cost_at_error(m["points"], target) for m in methods}
    return {
        "case_id": case.id,
        "scene_id": f"{SVG_PREFIX}{case.id}",
        "title": case.title,
        "t_end_s": case.t_end_s,
        "frame_rate_hz": case.frame_rate_hz,
        "coordinates": list(case.system.coordinate_names),
        "constraints": case.system.n_constraints,
        "error_measure": "largest final position error over all coordinates",
        "error_unit": case.error_unit,
        "reference": case.reference_name,
        "reference_positions": [float(x) for x in case.reference_positions],
        "reference_floor": case.reference_floor,
        "cpu_s_at_error": cost,
        "methods": methods,
        "plot": f"{SVG_PREFIX}{case.id}.svg",
    }


def write_report(report: dict[str, Any], out_dir: Path = OUT_DIR) -> list[Path]:
    """Write the JSON and one SVG per case into ``out_dir``; returns the paths."""
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / REPORT_FILE
    path.write_text(json.dumps(report, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    written = [path]
    for case in report["cases"]:
        svg = out_dir / case["plot"]
        svg.write_text(work_precision_svg(case), encoding="utf-8")
        written.append(svg)
    return written


def main(argv: Sequence[str] | None = None) -> int:
    import argparse

    parser = argparse.ArgumentParser(prog="dynlab constrained", description=__doc__.splitlines()[0])
    parser.add_argument("--case", action="append", choices=sorted(CASES), help="only this case (repeatable)")
    parser.add_argument("--quick", action="store_true", help="every other setting only (a smoke run)")
    parser.add_argument("--out", type=Path, default=OUT_DIR, help="output folder (default docs/bench)")
    args = parser.parse_args(argv)
    report = run_benchmark(args.case, quick=args.quick)
    for path in write_report(report, args.out):
        print(f"wrote {path}")
    for case in report["cases"]:
        print(case["title"])
        for method in case["methods"]:
            best = min((p for p in method["points"] if p["error"] is not None), key=lambda p: p["error"], default=None)
            if best is not None:
                print(
                    f"  {method['label']:<44} best error {best['error']:.1e} {case['error_unit']} in "
                    f"{best['cpu_s'] * 1e3:.3g} ms"
                )
    return 0
