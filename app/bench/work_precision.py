"""``dynlab bench``: speed against error for every integrated model, one run, one machine.

For each case the error of every method is measured against a reference —
the closed form or quadrature solution where one exists, else Dormand–Prince
at rtol 1e-13 — at every frame of the run, and plotted against process CPU time
while each method's step (steps per frame) or tolerance is swept. Methods:
ours (numba kernels), scipy ``solve_ivp`` (RK45, DOP853, LSODA, Radau) with a
numpy right-hand side, and MuJoCo (RK4 and its default Euler) where the system
can be written in it. Ratios are quoted at equal error, interpolated on the
log–log curves. Writes ``docs/bench/work_precision.json`` and one SVG per case.
"""

from __future__ import annotations

import json
import math
import platform
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from app.physics.bodies.rigid_body import RigidBody
from app.physics.math.rotations import rotate_vector
from app.physics.solvers import METHODS, make_integrator, simulate
from app.physics.solvers.integrated_model import simulate_model
from app.physics.systems.ch10 import heavy_top

OUT_DIR = Path(__file__).resolve().parents[2] / "docs" / "bench"
E3 = np.array([0.0, 0.0, 1.0])


def angle_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle (rad) between unit vectors row by row, accurate for tiny angles (atan2 form)."""
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def attitude_error_rad(q: np.ndarray, q_ref: np.ndarray) -> np.ndarray:
    """Rotation angle (rad) between two attitude series (N, 4), sign-insensitive."""
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    q_ref = q_ref / np.linalg.norm(q_ref, axis=-1, keepdims=True)
    dot = np.abs(np.sum(q * q_ref, axis=-1))
    # 2·atan2(|q × q_ref-like vector part|, dot) is accurate near zero.
    w1, v1 = q[:, :1], q[:, 1:]
    w2, v2 = q_ref[:, :1], q_ref[:, 1:]
    vector_part = w2 * v1 - w1 * v2 - np.cross(v1, v2)
    return 2.0 * np.arctan2(np.linalg.norm(vector_part, axis=-1), dot)


@dataclass
class Case:
    """One benchmarked motion: a rigid body about a fixed point over ``t_end_s``."""

    id: str
    title: str
    body: RigidBody
    y0: np.ndarray
    t_end_s: float
    frame_rate_hz: float
    error_measure: str
    reference_name: str
    #: (F+1, 4) reference attitude at the frame times.
    reference_quaternion: Callable[[np.ndarray], np.ndarray]
    #: Error of a run (frames of quaternions (F+1, 4)) against the reference.
    error_kind: str = "axis"  # "axis": symmetry-axis angle; "attitude": full rotation angle
    default_method: str = "splitting4"
    target_error: float = 1e-6
    scene_id: str | None = None
    notes: list[str] = field(default_factory=list)

    def error(self, quaternions: np.ndarray, reference: np.ndarray) -> float:
        if self.error_kind == "axis":
            axis = rotate_vector(quaternions, E3)
            axis_ref = rotate_vector(reference, E3)
            return float(angle_between(axis, axis_ref).max())
        return float(attitude_error_rad(quaternions, reference).max())


def heavy_top_case() -> Case:
    params = heavy_top.PARAMETERS.defaults()
    body = heavy_top.rigid_body(params)
    y0 = heavy_top.initial_state(params)

    def reference(t: np.ndarray) -> np.ndarray:
        return heavy_top.quadrature(params).quaternion(t)

    return Case(
        id="heavy-top", scene_id="heavy-top", title="Heavy symmetric top, 10 s (scene defaults)", body=body, y0=y0,
        t_end_s=10.0, frame_rate_hz=60.0, error_measure="largest symmetry-axis angle error over all frames",
        reference_name="quadrature solution (Jacobi elliptic functions for θ, elliptic integrals of the third kind for φ and ψ)",
        reference_quaternion=reference, error_kind="axis",
    )


def free_body_case() -> Case:
    inertia = (1e-3, 2e-3, 3e-3)
    omega0 = np.array([0.01, 10.0, 0.01])
    body = RigidBody(inertia)
    y0 = np.concatenate([[1.0, 0.0, 0.0, 0.0], omega0])

    def reference(t: np.ndarray) -> np.ndarray:
        from app.physics.systems.ch10.free_body_elliptic import free_body_elliptic

        return free_body_elliptic(inertia=inertia, omega0_body=omega0).quaternion(t)

    return Case(
        id="free-body-dzhanibekov", title="Torque-free body, intermediate-axis flips, 10 s (I = (1, 2, 3)·10⁻³ kg·m²)",
        body=body, y0=y0, t_end_s=10.0, frame_rate_hz=60.0, error_measure="largest attitude error (rotation angle) over all frames",
        reference_name="Jacobi elliptic closed form (ω) with quadrature for the angle about L",
        reference_quaternion=reference, error_kind="attitude",
    )


CASES: dict[str, Callable[[], Case]] = {"heavy-top": heavy_top_case, "free-body-dzhanibekov": free_body_case}

#: Settings swept for each of our methods: steps per frame (fixed step) or rtol (adaptive).
OUR_SETTINGS: dict[str, list[float]] = {
    "splitting4": [1, 2, 3, 4, 6, 8, 12, 16],
    "splitting2": [2, 4, 8, 16, 32, 64, 128],
    "rk4": [2, 4, 8, 12, 16, 24, 32, 64],
    "dopri5": [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11],
}


def our_sweeps() -> list[tuple[str, str, str, str, list[float]]]:
    """One sweep per registered method: (method id, family, label, setting name, settings)."""
    missing = set(METHODS) - set(OUR_SETTINGS)
    if missing:
        raise ValueError(f"no benchmark settings for the registered methods {sorted(missing)}")
    return [
        (name, "dynlab", f"{spec.short_label} (numba)", "rtol" if spec.adaptive else "steps_per_frame", OUR_SETTINGS[name])
        for name, spec in METHODS.items()
    ]


# Sweeps: (method id, family, label, setting name, settings).
OUR_SWEEPS = our_sweeps()
SCIPY_SWEEPS = [
    ("scipy-RK45", "scipy", "scipy RK45 (numpy RHS)", "rtol", [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]),
    ("scipy-DOP853", "scipy", "scipy DOP853 (numpy RHS)", "rtol", [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]),
    ("scipy-LSODA", "scipy", "scipy LSODA (numpy RHS)", "rtol", [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]),
    ("scipy-Radau", "scipy", "scipy Radau (numpy RHS)", "rtol", [1e-4, 1e-5, 1e-6, 1e-7]),
]
MUJOCO_SWEEPS = [
    ("mujoco-RK4", "mujoco", "MuJoCo RK4 (ball joint)", "steps_per_frame", [1, 2, 4, 8, 16, 32]),
    ("mujoco-Euler", "mujoco", "MuJoCo Euler, its default (ball joint)", "steps_per_frame", [4, 16, 64]),
]


def _timed(fn: Callable[[], Any], *, repeats: int) -> tuple[Any, float]:
    """Run ``fn`` up to ``repeats`` times (stopping early past 0.5 s) and keep the best CPU time."""
    best = math.inf
    result = None
    for _ in range(repeats):
        start = time.process_time()
        result = fn()
        elapsed = time.process_time() - start
        best = min(best, elapsed)
        if elapsed > 0.5:
            break
    return result, best


def numpy_rhs(body: RigidBody) -> Callable[[float, np.ndarray], np.ndarray]:
    """The rigid body's right-hand side written with numpy, as a scipy user would."""
    inertia = np.asarray(body.inertia_pivot_kg_m2)
    mgl = body.gravity_moment_N_m

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q, omega = y[:4], y[4:]
        w, x, yq, z = q
        q_dot = 0.5 * np.array(
            [-x * omega[0] - yq * omega[1] - z * omega[2], w * omega[0] + yq * omega[2] - z * omega[1],
             w * omega[1] - x * omega[2] + z * omega[0], w * omega[2] + x * omega[1] - yq * omega[0]]
        )
        z_body = np.array([2.0 * (x * z - w * yq), 2.0 * (yq * z + w * x), 1.0 - 2.0 * (x * x + yq * yq)]) / (q @ q)
        torque = mgl * np.array([z_body[1], -z_body[0], 0.0])
        omega_dot = (np.cross(inertia * omega, omega) + torque) / inertia
        return np.concatenate([q_dot, omega_dot])

    return rhs


def run_ours(case: Case, method: str, setting: float, frames_t: np.ndarray) -> tuple[np.ndarray, float, int, str]:
    if METHODS[method].adaptive:
        integrator = make_integrator(method, rtol=float(setting))
    else:
        integrator = make_integrator(method, steps_per_frame=int(setting))
    system = case.body.system()
    run = lambda: simulate(system, integrator, case.y0, t_end_s=case.t_end_s, frame_rate_hz=case.frame_rate_hz)  # noqa: E731
    simulate(system, integrator, case.y0, t_end_s=min(case.t_end_s, 0.1), frame_rate_hz=case.frame_rate_hz)  # warm
    result, cpu = _timed(run, repeats=5)
    return result.states[:, :4], cpu, result.rhs_evals, result.status


def run_scipy(case: Case, method: str, rtol: float, frames_t: np.ndarray) -> tuple[np.ndarray, float, int, str]:
    rhs = numpy_rhs(case.body)
    name = method.split("-", 1)[1]
    run = lambda: solve_ivp(rhs, (0.0, case.t_end_s), case.y0, method=name, rtol=rtol, atol=rtol * 1e-3, t_eval=frames_t)  # noqa: E731
    solution, cpu = _timed(run, repeats=2)
    status = "ok" if solution.success else "failed"
    return solution.y[:4].T, cpu, int(solution.nfev), status


def run_mujoco(case: Case, method: str, steps_per_frame: int, frames_t: np.ndarray) -> tuple[np.ndarray, float, int, str]:
    from app.bench.mujoco_models import simulate_rigid_body_mujoco

    body = case.body
    kwargs = dict(
        inertia_pivot=body.inertia_pivot_kg_m2, mass_kg=body.mass_kg if body.mass_kg > 0 else 1.0,
        cg_distance_m=body.cg_distance_m, g_m_s2=body.g_m_s2, q0=case.y0[:4], omega0_body=case.y0[4:],
        t_end_s=case.t_end_s, frame_rate_hz=case.frame_rate_hz, steps_per_frame=int(steps_per_frame),
        integrator=method.split("-", 1)[1],
    )
    best = math.inf
    run = None
    for _ in range(3):
        run = simulate_rigid_body_mujoco(**kwargs)
        best = min(best, run.cpu_s)
        if run.cpu_s > 0.5:
            break
    status = "ok" if np.all(np.isfinite(run.quaternion)) else "non_finite"
    return run.quaternion, best, int(run.steps), status


def cost_at_error(points: Sequence[dict], target: float) -> float | None:
    """CPU time (s) at ``target`` error by log–log interpolation along a sweep (None if never reached)."""
    usable = sorted(
        ((p["error"], p["cpu_s"]) for p in points if p["status"] == "ok" and p["error"] > 0 and p["cpu_s"] > 0),
        key=lambda e: -e[0],
    )
    for (e1, c1), (e2, c2) in zip(usable, usable[1:]):
        if e2 <= target <= e1:
            if e1 == e2:
                return min(c1, c2)
            w = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(c1) + w * (math.log(c2) - math.log(c1)))
    reached = [c for e, c in usable if e <= target]
    return min(reached) if reached else None


def live_frame_costs() -> list[dict[str, Any]]:
    """Cost of one displayed frame (30 Hz) of every scene, at its defaults (see :mod:`app.bench.frame_costs`).

    ``physics_us_per_frame``: for an integrated scene, one frame of its compiled
    live run; for an animated closed-form scene, the physics share of its
    ``advance`` (profiled); 0 for a scene that computes nothing per frame.
    ``scene_us_per_frame``: the scene's whole ``advance`` (physics and the
    Python side of the drawing updates, nothing sent).
    Integrated and closed-form scenes also give the largest relative drift of
    their invariants over 60 s; scenes drawing a worked example give the cost
    of solving it again when a control changes.
    """
    from app.bench.frame_costs import FRAME_DT_S, live_run_cost_us, scene_frame_cost_us
    from app.physics.core.closed_form import ClosedFormModel, evaluate_model
    from app.physics.solvers.integrated_model import IntegratedModel
    from app.scenes import SCENES

    out = []
    for scene_id, cls in SCENES.items():
        entry: dict[str, Any] = {"scene_id": scene_id}
        model_cls = cls.model
        scene_us, scene_physics_us = scene_frame_cost_us(cls) if cls.animated else (0.0, 0.0)
        drift = None
        if isinstance(model_cls, type) and issubclass(model_cls, IntegratedModel):
            physics_us, integrator = live_run_cost_us(cls)
            model = model_cls()
            params = model.parameters.defaults()
            drift = simulate_model(model, params, {}, t_end_s=60.0, frame_rate_hz=30.0).max_invariant_drift
            entry.update(method=integrator.name, description=integrator.describe(FRAME_DT_S), physics_us_per_frame=physics_us)
        elif isinstance(model_cls, type) and issubclass(model_cls, ClosedFormModel):
            model = model_cls()
            params = model.parameters.defaults()
            drift = evaluate_model(model, params, t_end_s=60.0, frame_rate_hz=30.0)["stats"]["max_invariant_drift"]
            entry.update(
                method="closed-form", physics_us_per_frame=scene_physics_us,
                description=f"{model.description}, evaluated at each frame's time",
            )
        elif cls.example is not None:
            example = cls.example
            inputs = example.inputs.defaults()
            example.solve(inputs)
            start = time.perf_counter()
            for _ in range(100):
                example.solve(inputs)
            entry.update(
                method="static", physics_us_per_frame=0.0, solve_us_on_change=1e4 * (time.perf_counter() - start),
                description=f"{example.id} is solved again only when a control changes"
                + ("; frames only move what was drawn" if cls.animated else "; nothing is computed per frame"),
            )
        else:
            continue
        entry["scene_us_per_frame"] = scene_us
        if drift is not None:
            entry["max_invariant_drift_60s"] = drift
        out.append(entry)
    return out


def _machine() -> dict[str, Any]:
    import numba
    import scipy

    info: dict[str, Any] = {
        "cpu": platform.processor() or platform.machine(), "cores": __import__("os").cpu_count(),
        "python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__, "numba": numba.__version__,
    }
    try:
        import mujoco

        info["mujoco"] = mujoco.__version__
    except ImportError:
        info["mujoco"] = None
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return info


class Progress:
    """A one-line progress bar on stderr."""

    def __init__(self, total: int) -> None:
        self.total = total
        self.done = 0
        self.start = time.perf_counter()

    def step(self, text: str) -> None:
        self.done += 1
        width = 30
        filled = int(width * self.done / self.total)
        elapsed = time.perf_counter() - self.start
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {elapsed:5.0f} s  {text[:60]:<60}")
        sys.stderr.flush()
        if self.done == self.total:
            sys.stderr.write("\n")


def run_benchmark(case_ids: Sequence[str] | None = None, *, include_mujoco: bool = True, quick: bool = False) -> dict[str, Any]:
    """Measure every sweep of every case; return the report dictionary."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        include_mujoco = False
    cases = [CASES[c]() for c in (case_ids or CASES)]
    sweeps = OUR_SWEEPS + SCIPY_SWEEPS + (MUJOCO_SWEEPS if include_mujoco else [])
    if quick:
        sweeps = [(m, f, l, s, values[::3]) for m, f, l, s, values in sweeps]
    progress = Progress(sum(len(s[4]) for s in sweeps) * len(cases) + 1)
    report: dict[str, Any] = {"created": datetime.now(timezone.utc).isoformat(timespec="seconds"), "machine": _machine(), "scenes": []}
    for case in cases:
        frames_t = np.arange(int(round(case.t_end_s * case.frame_rate_hz)) + 1) / case.frame_rate_hz
        reference = case.reference_quaternion(frames_t)
        methods = []
        for method, family, label, setting_name, settings in sweeps:
            runner = {"dynlab": run_ours, "scipy": run_scipy, "mujoco": run_mujoco}[family]
            points = []
            for setting in settings:
                progress.step(f"{case.id}: {label} {setting_name}={setting:g}")
                quaternions, cpu, evals, status = runner(case, method, setting, frames_t)
                error = case.error(quaternions, reference) if status == "ok" and len(quaternions) == len(frames_t) else math.inf
                points.append({"setting": setting, "cpu_s": cpu, "error": error if math.isfinite(error) else None,
                               "rhs_evals": evals, "status": status if math.isfinite(error) else "failed"})
            methods.append({"method": method, "family": family, "label": label, "setting_name": setting_name, "points": points})
        # The default operating point: what a scene uses at 60 frames/s with "auto".
        default_integrator = make_integrator(
            case.default_method, fastest_rate_rad_s=case.body.fastest_rate_rad_s(case.y0), frame_dt_s=1.0 / case.frame_rate_hz
        )
        q_default, cpu_default, _, _ = run_ours(case, case.default_method, default_integrator.steps_per_frame, frames_t)
        default = {
            "method": case.default_method, "setting": default_integrator.steps_per_frame, "setting_name": "steps_per_frame",
            "description": default_integrator.describe(1.0 / case.frame_rate_hz),
            "cpu_s": cpu_default, "error": case.error(q_default, reference),
        }
        ratios = []
        for method in methods:
            for p in method["points"]:
                if p["error"] is None:
                    p["status"] = "failed"
        default_points = next(m["points"] for m in methods if m["method"] == case.default_method)
        ours = cost_at_error(default_points, case.target_error)
        for baseline in ("scipy-DOP853", "scipy-RK45", "scipy-LSODA", "scipy-Radau", "mujoco-RK4", "mujoco-Euler"):
            base = next((m for m in methods if m["method"] == baseline), None)
            if base is None or ours is None:
                continue
            theirs = cost_at_error(base["points"], case.target_error)
            if theirs is None:
                ratios.append({"baseline": baseline, "at_error": case.target_error, "ratio": None,
                               "text": f"{base['label']} never reached {case.target_error:.0e} in the sweep"})
                continue
            ratio = theirs / ours
            ratios.append({"baseline": baseline, "at_error": case.target_error, "ratio": ratio, "ours_cpu_s": ours, "theirs_cpu_s": theirs,
                           "text": f"At {case.target_error:.0e} {'rad'} error, {case.default_method} needs {ours * 1e3:.3g} ms of CPU; "
                                   f"{base['label']} needs {theirs * 1e3:.3g} ms: {ratio:.0f}× more."})
        report["scenes"].append(
            {
                "scene_id": case.id, "live_scene": case.scene_id, "title": case.title, "t_end_s": case.t_end_s,
                "frame_rate_hz": case.frame_rate_hz, "error_measure": case.error_measure, "error_unit": "rad",
                "reference": case.reference_name, "target_error": case.target_error, "default": default,
                "methods": methods, "ratios": ratios, "plot": f"{case.id}.svg",
            }
        )
    progress.step("live scenes: physics cost per frame and 60 s invariant drift")
    report["live_scenes"] = live_frame_costs()
    return report


def write_report(report: dict[str, Any], out_dir: Path = OUT_DIR) -> list[Path]:
    from app.bench.plot import write_svgs

    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / "work_precision.json"
    path.write_text(json.dumps(report, indent=1, allow_nan=False) + "\n")
    return [path, *write_svgs(report, out_dir)]


def main(argv: Sequence[str] | None = None) -> int:
    import argparse

    parser = argparse.ArgumentParser(prog="dynlab bench", description=__doc__.splitlines()[0])
    parser.add_argument("--case", action="append", choices=sorted(CASES), help="only this case (repeatable)")
    parser.add_argument("--no-mujoco", action="store_true", help="skip MuJoCo even if installed")
    parser.add_argument("--quick", action="store_true", help="every third setting only (a smoke run)")
    parser.add_argument("--out", type=Path, default=OUT_DIR, help="output folder (default docs/bench)")
    args = parser.parse_args(argv)
    report = run_benchmark(args.case, include_mujoco=not args.no_mujoco, quick=args.quick)
    for path in write_report(report, args.out):
        print(f"wrote {path}")
    for scene in report["scenes"]:
        print(f"{scene['title']}: default {scene['default']['description']}: "
              f"{scene['default']['cpu_s'] * 1e3:.3g} ms, error {scene['default']['error']:.2e} rad")
        for ratio in scene["ratios"]:
            print("  " + ratio["text"])
    for live in report["live_scenes"]:
        drift = f", 60 s drift {live['max_invariant_drift_60s']:.1e}" if "max_invariant_drift_60s" in live else ""
        print(f"live {live['scene_id']}: {live['physics_us_per_frame']:.2f} µs/frame ({live['description']}){drift}")
    return 0
