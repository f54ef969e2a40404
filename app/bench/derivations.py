"""Benchmark of the derivation engine: ``dynlab derivations`` writes docs/bench/derivations.json and .svg.

For every catalogue system and every formulation that applies, measured from
an empty cache (a temporary directory, so sympy and numba start cold):

* ``derive_s`` — sympy's derivation; ``code_s`` — generating and importing the
  right-hand side; ``numba_s`` — compiling it for live scenes;
* ``second_request_ms`` — POST /api/systems/{id}/derive again (median of 10,
  through the HTTP stack): what a student waits for after the first time;
* ``agreement`` — the largest relative difference of (q̇, q̈) from the
  reference formulation at 200 random states;
* ``symbolic`` — "proven" if sympy shows the equations identical within
  :data:`PROOF_TIMEOUT_S` (in a bounded child process), "not proven in 10 s"
  otherwise (and "differ" if sympy finds they are not the same);
* ``frame_us`` — physics of one 30 Hz frame with the compiled RK4 at the
  automatic step count for the system's default state.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from app.physics.core.bounded import BoundedRunner, WorkRefused
from app.physics.mechanics import engine
from app.physics.mechanics.agreement import (
    formulation_agreement,
    proves_same_equations,
    random_states,
    reference_formulation,
)
from app.physics.mechanics.engine import available_formulations
from app.physics.solvers import RK4, LiveRun, automatic_steps_per_frame
from app.physics.solvers.system import OdeSystem
from app.physics.systems import analytical_systems

OUT_DIR = Path(__file__).resolve().parents[2] / "docs" / "bench"
PROOF_TIMEOUT_S = 10.0
FRAME_DT_S = 1.0 / 30.0


def _prove(system_id: str, formulation: str) -> bool:
    """In a child process: whether sympy proves ``formulation`` equal to the reference for ``system_id``."""
    return proves_same_equations(analytical_systems()[system_id], formulation)


def _frame_us(result: engine.Derived, p: np.ndarray, state: np.ndarray) -> tuple[float, int]:
    """Mean physics cost (µs) of a 30 Hz frame with RK4, and the steps per frame used."""
    rate = max(1.0, float(np.max(np.abs(result.state_derivative(0.0, state, p)))))
    steps = automatic_steps_per_frame("rk4", rate, FRAME_DT_S)
    run = LiveRun(
        OdeSystem(rhs=result.kernel(), parameters=p, state_names=tuple(f"y{i}" for i in range(len(state)))),
        RK4(steps_per_frame=steps),
        state.copy(),
    )
    run.advance(FRAME_DT_S)
    start = time.perf_counter()
    for _ in range(300):
        run.advance(FRAME_DT_S)
    return 1e6 * (time.perf_counter() - start) / 300, steps


def measure(*, prove: bool = True) -> dict[str, Any]:
    from fastapi.testclient import TestClient

    from app.main import create_app

    runner = BoundedRunner(
        max_jobs=1,
        timeout_s=PROOF_TIMEOUT_S,
        memory_mb=2048,
        preload=("app.physics.core.bounded", "numpy", "sympy", __name__),
    )
    rows = []
    with tempfile.TemporaryDirectory() as cache, TestClient(create_app()) as client:
        os.environ["DYNLAB_DERIVATION_CACHE"] = cache
        engine._memory.clear()
        for system_id, system in analytical_systems().items():
            params = system.parameters.defaults()
            p = np.array(system.parameter_array(params))
            states = random_states(system, np.random.default_rng(1), 200)
            for formulation, reason in available_formulations(system).items():
                if reason:
                    continue
                # Its own empty cache: the derivations shipped with the app are read only without a directory.
                result = engine.derived(system, formulation, directory=Path(cache))
                start = time.perf_counter()
                result.kernel()
                numba_s = time.perf_counter() - start
                timings = []
                for _ in range(10):
                    start = time.perf_counter()
                    answer = client.post(f"/api/systems/{system_id}/derive", json={"formulation": formulation})
                    timings.append(1e3 * (time.perf_counter() - start))
                    answer.raise_for_status()
                frame_us, steps = _frame_us(result, p, states[0])
                symbolic = "reference" if formulation == reference_formulation(system) else "not attempted"
                if prove and symbolic == "not attempted":
                    try:
                        symbolic = (
                            "proven" if runner.run(_prove, (system_id, formulation), what="the proof") else "differ"
                        )
                    except WorkRefused:
                        symbolic = f"not proven in {PROOF_TIMEOUT_S:g} s"
                row = {
                    "system": system_id,
                    "formulation": formulation,
                    "derive_s": result.derive_s,
                    "code_s": result.compile_s,
                    "numba_s": numba_s,
                    "second_request_ms": statistics.median(timings),
                    "second_request_max_ms": max(timings),
                    "frame_us": frame_us,
                    "steps_per_frame": steps,
                    "symbolic": symbolic,
                }
                rows.append(row)
                print(
                    f"{system_id:22s} {formulation:13s} derive {result.derive_s:6.2f} s  code "
                    f"{result.compile_s:5.2f} s  numba {numba_s:5.2f} s  "
                    f"again {row['second_request_ms']:5.1f} ms  frame {frame_us:6.1f} µs  {symbolic}",
                    flush=True,
                )
            agreement = formulation_agreement(system, params, states)
            for row in rows:
                if row["system"] == system_id:
                    row["agreement"] = agreement[row["formulation"]]
    return {
        "generated_by": "dynlab derivations",
        "machine": f"{os.cpu_count()} cores",
        "proof_timeout_s": PROOF_TIMEOUT_S,
        "rows": rows,
    }


def write_svg(report: dict[str, Any], path: Path) -> None:
    """Horizontal bars: derivation time (log scale) per system and formulation, the second request beside it."""
    rows = report["rows"]
    height = 24 + 16 * len(rows)
    left, width = 250, 420
    lo, hi = -3, 2  # 1 ms … 100 s

    def x(seconds: float) -> float:
        return left + width * (min(max(np.log10(max(seconds, 1e-3)), lo), hi) - lo) / (hi - lo)

    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{left + width + 240}" height="{height + 30}" '
        'font-family="sans-serif" font-size="11">',
        f'<text x="{left}" y="14">derivation time (blue) and a second request (orange), log scale, 1 ms … 100 s</text>',
    ]
    for k in range(lo, hi + 1):
        parts.append(f'<line x1="{x(10.0**k):.1f}" y1="20" x2="{x(10.0**k):.1f}" y2="{height}" stroke="#ddd"/>')
        parts.append(f'<text x="{x(10.0**k):.1f}" y="{height + 14}" text-anchor="middle">{10.0**k:g} s</text>')
    for i, row in enumerate(rows):
        y = 24 + 16 * i
        parts.append(
            f'<text x="{left - 6}" y="{y + 10}" text-anchor="end">{row["system"]} · {row["formulation"]}</text>'
        )
        parts.append(
            f'<rect x="{left}" y="{y + 1}" width="{x(row["derive_s"]) - left:.1f}" height="6" fill="#3b6fb6"/>'
        )
        parts.append(
            f'<rect x="{left}" y="{y + 8}" width="{x(row["second_request_ms"] / 1e3) - left:.1f}" height="6" '
            'fill="#e08a2c"/>'
        )
        parts.append(
            f'<text x="{left + width + 6}" y="{y + 10}">{row["derive_s"]:.2f} s / {row["second_request_ms"]:.1f} '
            f"ms · {row['symbolic']}</text>"
        )
    parts.append("</svg>")
    path.write_text("\n".join(parts), encoding="utf-8")


def main(argv: Sequence[str] | None = None) -> int:
    arguments = list(sys.argv[1:] if argv is None else argv)
    if "--scaling" in arguments:  # the scaling study of the N-link pendulum and the bicycle (app.bench.scaling)
        from app.bench.scaling import main as scaling_main

        return scaling_main([a for a in arguments if a != "--scaling"])
    parser = argparse.ArgumentParser(prog="dynlab derivations", description=__doc__.splitlines()[0])
    parser.add_argument("--scaling", action="store_true", help="instead: the N-link pendulum's scaling (scaling.json)")
    parser.add_argument("--no-proofs", action="store_true", help="skip the symbolic proofs (10 s each at most)")
    parser.add_argument("--out", type=Path, default=OUT_DIR, help="output folder (default docs/bench)")
    args = parser.parse_args(argv)
    report = measure(prove=not args.no_proofs)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "derivations.json").write_text(json.dumps(report, indent=1), encoding="utf-8")
    write_svg(report, args.out / "derivations.svg")
    print(f"wrote {args.out / 'derivations.json'} and derivations.svg")
    return 0
