"""How the derivation engine scales: ``dynlab derivations --scaling`` writes docs/bench/scaling.json and .svg.

For the N-link pendulum (:mod:`app.physics.systems.ch09.n_link_pendulum`), N = 2 … 20 planar and 2 … 10 spatial,
each measured cold in a fresh process (sympy's caches empty, the derivation and numba caches in a new temporary
folder):

* ours: ``derive_s`` (the kinematics and Kane's M, f), ``generate_s`` (shared subexpressions, Python source),
  ``load_s`` (importing it), ``numba_s`` (compiling the DAE kernels for live scenes), ``rhs_us`` (one evaluation
  of the accelerations in plain Python, median of 50), the operation counts written out and in the code, and
  ``frame_us``: one live frame as the ``n-link-pendulum`` scene computes it (first mode at 5°, 30 frames/s, the
  step the model's 1e-6 accuracy target chooses, compiled kernels; CPU time of 10 s of motion over its frames),
  with ``frame_integration`` saying which step that was;
* what a user writes with sympy (planar only): ``sympy.physics.mechanics.KanesMethod`` for the same rods and
  hinges, in each link's angle from the vertical as sympy's own examples write it, then ``lambdify`` of the full
  mass matrix and forcing (``derive_s``, ``lambdify_s``, and ``rhs_us`` for evaluating both and solving with
  numpy). A run over :data:`RUN_LIMIT_S` is stopped and reported as over it.

The issue's targets: the 20-link chain derived and compiled cold in under 5 s, and the bicycle in under 15 s cold and
under 50 ms cached; the report states what was measured against them.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

OUT_DIR = Path(__file__).resolve().parents[2] / "docs" / "bench"
PLANAR_LINKS = (2, 4, 6, 8, 10, 12, 14, 16, 18, 20)
SPATIAL_LINKS = (2, 4, 6, 8, 10)
SYMPY_LINKS = PLANAR_LINKS
PARAMS = {"link_mass_kg": 1.0, "link_length_m": 0.5, "gravity_m_s2": 9.81}


def _median_us(call, repeats: int = 50) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return 1e6 * statistics.median(times)


def measure_ours(links: int, planar: bool) -> dict[str, Any]:
    """One cold measurement of the engine (call in a fresh process): everything derived into a new folder."""
    saved = os.environ.get("DYNLAB_DERIVATION_CACHE")
    with tempfile.TemporaryDirectory() as folder:
        os.environ["DYNLAB_DERIVATION_CACHE"] = folder  # the scene's model prepares its chain here, cold too
        try:
            row = _measure_ours_in(Path(folder), links, planar)
        finally:
            if saved is None:
                os.environ.pop("DYNLAB_DERIVATION_CACHE", None)
            else:
                os.environ["DYNLAB_DERIVATION_CACHE"] = saved
    return row


def _measure_ours_in(folder: Path, links: int, planar: bool) -> dict[str, Any]:
    from app.physics.mechanics.multibody.compiled import compiled
    from app.physics.systems.ch09.n_link_pendulum import chain

    start = time.perf_counter()
    model = compiled(chain(links, planar), directory=folder)
    total_s = time.perf_counter() - start
    start = time.perf_counter()
    model.kernels()
    numba_s = time.perf_counter() - start
    p = model.parameter_array(PARAMS)
    rng = np.random.default_rng(1)
    q, u = rng.uniform(-0.5, 0.5, model.n), rng.uniform(-1.0, 1.0, model.n)
    rhs_us = _median_us(lambda: model.accelerations(q, u, p))
    frame_us, frame_integration = _live_frame_us(links, planar)
    return {
        "engine": "ours",
        "links": links,
        "planar": planar,
        "coordinates": model.n,
        "derive_s": model.derive_s,
        "generate_s": model.generate_s,
        "load_s": model.load_s,
        "derive_generate_load_s": total_s,
        "numba_s": numba_s,
        "rhs_us": rhs_us,
        "frame_us": frame_us,
        "frame_integration": frame_integration,
        "operations_written_out": model.operations["before_cse"],
        "operations_in_code": model.operations["after_cse"],
    }


def _live_frame_us(links: int, planar: bool) -> tuple[float, str]:
    """CPU time (µs) of one frame of the scene's motion: the first mode at 5°, 10 s at 30 frames/s, the automatic
    step for the model's 1e-6 target; and that step, in words."""
    from app.physics.systems.ch09.n_link_pendulum_model import PARAMETERS as CHAIN
    from app.physics.systems.ch09.n_link_pendulum_model import NLinkPendulumMotion

    motion = NLinkPendulumMotion()
    params = CHAIN.validate(
        {"links": links, "planar": "planar" if planar else "spatial", "start": "mode", "mode": 1, "amplitude_deg": 5.0}
    )
    report = motion.simulate(
        params, {c.name: c.default for c in motion.controls()}, t_end_s=10.0, frame_rate_hz=FRAME_RATE_HZ
    )
    return 1e6 * report.cpu_s / (len(report.t_s) - 1), report.description


#: The scenes' frame rate (Hz).
FRAME_RATE_HZ = 30.0


def measure_sympy(links: int) -> dict[str, Any]:
    """One cold measurement of sympy.physics.mechanics' KanesMethod with lambdify for the planar chain."""
    import sympy
    from sympy.physics import mechanics as me

    start = time.perf_counter()
    q, u = me.dynamicsymbols(f"q1:{links + 1}"), me.dynamicsymbols(f"u1:{links + 1}")
    m, l, g = sympy.symbols("m l g", positive=True)
    ground = me.ReferenceFrame("N")
    pivot = me.Point("O")
    pivot.set_vel(ground, 0)
    joint, bodies, loads = pivot, [], []
    for k in range(links):
        # Each link's angle from the vertical (absolute angles, as sympy's and PyDy's n-pendulum examples write it:
        # relative ones nest every rotation, and KanesMethod then took 143 s at 12 links and over 700 s at 14).
        link = ground.orientnew(f"L{k}", "Axis", (q[k], ground.y))
        link.set_ang_vel(ground, u[k] * ground.y)
        centre = joint.locatenew(f"G{k}", -l / 2 * link.z)
        centre.v2pt_theory(joint, ground, link)
        rod = me.inertia(link, m * l**2 / 12, m * l**2 / 12, m * l**2 / 12)
        bodies.append(me.RigidBody(f"rod{k}", centre, link, m, (rod, centre)))
        loads.append((centre, -m * g * ground.z))
        end = joint.locatenew(f"E{k}", -l * link.z)
        end.v2pt_theory(joint, ground, link)
        joint = end
    kane = me.KanesMethod(ground, q_ind=q, u_ind=u, kd_eqs=[qk.diff() - uk for qk, uk in zip(q, u)])
    kane.kanes_equations(bodies, loads)
    mass, forcing = kane.mass_matrix_full, kane.forcing_full
    derive_s = time.perf_counter() - start
    start = time.perf_counter()
    arguments = [*q, *u, m, l, g]
    mass_f, forcing_f = sympy.lambdify(arguments, mass), sympy.lambdify(arguments, forcing)
    lambdify_s = time.perf_counter() - start
    rng = np.random.default_rng(1)
    values = [*rng.uniform(-0.5, 0.5, links), *rng.uniform(-1.0, 1.0, links), 1.0, 0.5, 9.81]
    rhs_us = _median_us(
        lambda: np.linalg.solve(np.asarray(mass_f(*values), float), np.asarray(forcing_f(*values), float).ravel())
    )
    return {
        "engine": "sympy",
        "links": links,
        "planar": True,
        "coordinates": links,
        "derive_s": derive_s,
        "lambdify_s": lambdify_s,
        "derive_lambdify_s": derive_s + lambdify_s,
        "rhs_us": rhs_us,
    }


#: A measurement still running after this long (s) is stopped and reported as over it.
RUN_LIMIT_S = 300.0


def _in_fresh_process(kind: str, links: int, planar: bool) -> dict[str, Any]:
    command = [sys.executable, "-m", "app.bench.scaling", "--one", kind, str(links), "planar" if planar else "spatial"]
    try:
        done = subprocess.run(
            command, capture_output=True, text=True, check=True, env=os.environ.copy(), timeout=RUN_LIMIT_S
        )
    except subprocess.TimeoutExpired:
        return {"engine": kind, "links": links, "planar": planar, "over_limit_s": RUN_LIMIT_S}
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure_bicycle() -> dict[str, Any]:
    """The Whipple bicycle cold (fresh process, new cache folder), then cached (the same folder, another process)."""
    with tempfile.TemporaryDirectory() as folder:
        env = {**os.environ, "DYNLAB_DERIVATION_CACHE": folder}
        timed = []
        for _ in range(2):
            command = [sys.executable, "-m", "app.bench.scaling", "--bicycle-once"]
            done = subprocess.run(command, capture_output=True, text=True, check=True, env=env)
            timed.append(json.loads(done.stdout.strip().splitlines()[-1]))
    cold, cached = timed
    return {"cold": cold, "cached": cached}


def _bicycle_once() -> dict[str, Any]:
    from app.physics.mechanics.multibody.compiled import compiled
    from app.physics.systems.ch09.whipple_bicycle import SYSTEM

    start = time.perf_counter()
    model = compiled(SYSTEM)
    equations_s = time.perf_counter() - start
    start = time.perf_counter()
    model.kernels()
    numba_s = time.perf_counter() - start
    return {
        "from_cache": model.from_cache,
        "equations_s": equations_s,
        "numba_s": numba_s,
        "total_s": equations_s + numba_s,
        "operations_written_out": model.operations["before_cse"],
        "operations_in_code": model.operations["after_cse"],
    }


def measure() -> dict[str, Any]:
    rows = []
    for links in PLANAR_LINKS:
        rows.append(_in_fresh_process("ours", links, True))
        print(f"ours planar {links}: {rows[-1]['derive_generate_load_s']:.2f} s + numba {rows[-1]['numba_s']:.2f} s")
    for links in SPATIAL_LINKS:
        rows.append(_in_fresh_process("ours", links, False))
        print(f"ours spatial {links}: {rows[-1]['derive_generate_load_s']:.2f} s + numba {rows[-1]['numba_s']:.2f} s")
    for links in SYMPY_LINKS:
        rows.append(_in_fresh_process("sympy", links, True))
        if "over_limit_s" in rows[-1]:
            print(f"sympy planar {links}: over {RUN_LIMIT_S:g} s, stopped (and no larger chain tried)")
            break
        print(f"sympy planar {links}: {rows[-1]['derive_lambdify_s']:.2f} s")
    bicycle = measure_bicycle()
    twenty = next(r for r in rows if r["engine"] == "ours" and r["planar"] and r["links"] == 20)
    return {
        "generated_by": "dynlab derivations --scaling",
        "machine": f"{os.cpu_count()} cores",
        "rows": rows,
        "bicycle": bicycle,
        "targets": {
            "chain_20_derive_and_compile_cold_s": {
                "target": 5.0,
                "derive_generate_load_s": twenty["derive_generate_load_s"],
                "with_numba_s": twenty["derive_generate_load_s"] + twenty["numba_s"],
            },
            "chain_20_live_frame_us": {"target": 50.0, "measured": twenty["frame_us"]},
            "bicycle_cold_s": {"target": 15.0, "measured": bicycle["cold"]["total_s"]},
            "bicycle_cached_s": {"target": 0.05, "measured": bicycle["cached"]["equations_s"]},
        },
    }


def scaling_svg(report: dict[str, Any]) -> str:
    """Cold time (s, log) against the number of coordinates, for each engine and stage."""
    rows = report["rows"]

    def measured(key: str, engine: str, planar: bool) -> list[tuple[int, float]]:
        return [
            (r["coordinates"], r[key]) for r in rows if r["engine"] == engine and r["planar"] == planar and key in r
        ]

    series = [
        ("ours, planar: derive + generate + load", "#1f5eea", measured("derive_generate_load_s", "ours", True)),
        ("ours, planar: numba compile of the kernels", "#7aa2f7", measured("numba_s", "ours", True)),
        ("ours, spatial: derive + generate + load", "#2e8b57", measured("derive_generate_load_s", "ours", False)),
        ("sympy KanesMethod + lambdify, planar", "#d1495b", measured("derive_lambdify_s", "sympy", True)),
    ]
    width, height, left, right, top, bottom = 760, 440, 70, 470, 50, 390
    xs = [x for _, _, points in series for x, _ in points]
    ys = [y for _, _, points in series for _, y in points if y > 0]
    x_lo, x_hi = min(xs), max(xs)
    y_lo, y_hi = np.floor(np.log10(min(ys))), np.ceil(np.log10(max(ys)))

    def px(x: float) -> float:
        return left + (x - x_lo) / (x_hi - x_lo) * (right - left)

    def py(y: float) -> float:
        return bottom - (np.log10(max(y, 1e-9)) - y_lo) / (y_hi - y_lo) * (bottom - top)

    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" '
        'font-family="sans-serif" font-size="12" role="img" aria-label="Derivation time against the number of '
        'coordinates, the N-link pendulum">',
        f'<text x="{left}" y="22" font-size="14" font-weight="bold">The N-link pendulum, cold: time against '
        "coordinates (log scale)</text>",
    ]
    for k in range(int(y_lo), int(y_hi) + 1):
        out.append(f'<line x1="{left}" x2="{right}" y1="{py(10.0**k):.1f}" y2="{py(10.0**k):.1f}" stroke="#e3e6ec"/>')
        out.append(f'<text x="{left - 6}" y="{py(10.0**k) + 4:.1f}" text-anchor="end">{10.0**k:g} s</text>')
    for x in sorted(set(xs)):
        out.append(f'<text x="{px(x):.1f}" y="{bottom + 16}" text-anchor="middle">{x}</text>')
    out.append(f'<text x="{(left + right) / 2}" y="{bottom + 36}" text-anchor="middle">coordinates (planar: links; '
               "spatial: twice the links)</text>")  # fmt: skip
    out.append(
        f'<rect x="{left}" y="{top}" width="{right - left}" height="{bottom - top}" fill="none" stroke="#9aa3b2"/>'
    )
    for i, (name, color, points) in enumerate(series):
        path = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in points)
        out.append(f'<polyline points="{path}" fill="none" stroke="{color}" stroke-width="2"/>')
        out += [f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="3" fill="{color}"/>' for x, y in points]
        out.append(f'<rect x="{right + 14}" y="{top + 22 * i}" width="14" height="4" fill="{color}"/>')
        out.append(f'<text x="{right + 34}" y="{top + 22 * i + 6}">{name}</text>')
    bicycle = report["bicycle"]
    out.append(
        f'<text x="{right + 14}" y="{top + 120}">bicycle: {bicycle["cold"]["total_s"]:.1f} s cold, '
        f"{1e3 * bicycle['cached']['equations_s']:.0f} ms cached</text>"
    )
    out.append("</svg>")
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="dynlab derivations --scaling", description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=OUT_DIR, help="output folder (default docs/bench)")
    parser.add_argument("--one", nargs=3, metavar=("ENGINE", "LINKS", "PLANAR"), help=argparse.SUPPRESS)
    parser.add_argument("--bicycle-once", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        engine, links, planar = args.one
        row = measure_sympy(int(links)) if engine == "sympy" else measure_ours(int(links), planar == "planar")
        print(json.dumps(row))
        return 0
    if args.bicycle_once:
        print(json.dumps(_bicycle_once()))
        return 0
    report = measure()
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "scaling.json").write_text(json.dumps(report, indent=1), encoding="utf-8")
    (args.out / "scaling.svg").write_text(scaling_svg(report), encoding="utf-8")
    print(f"wrote {args.out / 'scaling.json'} and scaling.svg")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
