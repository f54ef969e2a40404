"""``dynlab bench``: speed against error for every integrated model, one run, one machine.

For each case the error of every method is measured against a reference —
the closed form or quadrature solution where one exists, else Dormand–Prince
at rtol 1e-13 — at every frame of the run, and plotted against process CPU time
while each method's step (steps per frame) or tolerance is swept. Methods:
ours (numba kernels), scipy ``solve_ivp`` (RK45, DOP853, LSODA, Radau) with a
numpy right-hand side, and MuJoCo (RK4 and its default Euler) where the system
can be written in it. Ratios are quoted at equal error, interpolated on the
log–log curves: the default method's at the case's target error, and the cheapest
of ours against DOP853 and MuJoCo RK4 at 1e-3, 1e-6 and 1e-9 rad
(:func:`best_ratios`, summed up in ``ratio_summary``). The heavy top is measured on
four parameter sets (scene default, fast, slow, sleeping), and the sleeping top
over 600 s gives each method's energy drift beside its attitude error
(``phase_drift``). Writes ``docs/bench/work_precision.json``, one SVG per case and
``heavy-top-phase-drift.svg``.
"""

from __future__ import annotations

import json
import math
import platform
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from app.physics.bodies.rigid_body import PivotedBody
from app.physics.math.rotations import rotate_vector
from app.physics.solvers import METHODS, make_integrator, simulate
from app.physics.solvers.step_choice import AccuracyTarget, StepChoice, choose
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
    body: PivotedBody
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
    #: Method ids of the other libraries' sweeps to run (None: all of them).
    baselines: tuple[str, ...] | None = None

    def frame_errors(self, quaternions: np.ndarray, reference: np.ndarray) -> np.ndarray:
        """(N,) error (rad) of each frame's attitude (N, 4) against ``reference`` (N, 4)."""
        if self.error_kind == "axis":
            return angle_between(rotate_vector(quaternions, E3), rotate_vector(reference, E3))
        return attitude_error_rad(quaternions, reference)

    def error(self, quaternions: np.ndarray, reference: np.ndarray) -> float:
        return float(self.frame_errors(quaternions, reference).max())

    def automatic_choice(self) -> StepChoice | None:
        """What a live scene's ``auto`` runs for this motion: the cheapest method meeting :attr:`target_error`
        over the case's span, from the same pilots (:func:`~app.physics.solvers.step_choice.choose`)."""
        target = AccuracyTarget(self.target_error, "rad", self.error_measure, horizon_s=self.t_end_s)
        return choose(
            self.body.system(),
            self.y0,
            tuple(METHODS),
            target=target,
            frame_dt_s=1.0 / self.frame_rate_hz,
            horizon_s=self.t_end_s,
            fastest_rate_rad_s=self.body.fastest_rate_rad_s(self.y0),
            error=lambda states, reference: self.frame_errors(states[:, :4], reference[:, :4]),
        )


def heavy_top_params(overrides: dict[str, float]) -> dict[str, Any]:
    """The heavy-top scene's defaults with ``overrides`` (validated like a request)."""
    return heavy_top.PARAMETERS.validate(overrides)


def _heavy_top_case(
    case_id: str,
    title: str,
    overrides: dict[str, float],
    *,
    error_kind: str,
    scene_id: str | None = None,
    baselines: tuple[str, ...] | None = None,
) -> Case:
    """A heavy symmetric top over 10 s at 60 frames/s against its quadrature solution."""
    params = heavy_top_params(overrides)
    measure = {
        "axis": "largest symmetry-axis angle error over all frames",
        "attitude": "largest attitude error (rotation angle, spin phase included) over all frames",
    }[error_kind]
    return Case(
        id=case_id,
        scene_id=scene_id,
        title=title,
        body=heavy_top.rigid_body(params),
        y0=heavy_top.initial_state(params),
        t_end_s=10.0,
        frame_rate_hz=60.0,
        error_measure=measure,
        reference_name=(
            "quadrature solution (Jacobi elliptic functions for θ, elliptic integrals of the third kind for φ and ψ)"
        ),
        reference_quaternion=heavy_top.quadrature(params).quaternion,
        error_kind=error_kind,
        baselines=baselines,
    )


def heavy_top_case() -> Case:
    return _heavy_top_case(
        "heavy-top", "Heavy symmetric top, 10 s (scene defaults)", {}, error_kind="axis", scene_id="heavy-top"
    )


#: The other libraries' sweeps run on the added heavy-top cases: the two the ratios are quoted against.
RATIO_BASELINES = ("scipy-DOP853", "mujoco-RK4")


def fast_top_case() -> Case:
    return _heavy_top_case(
        "heavy-top-fast",
        "Fast heavy top: spin 150 rad/s, 10 s",
        {"spin_rad_s": 150.0},
        error_kind="axis",
        baselines=RATIO_BASELINES,
    )


def slow_top_case() -> Case:
    return _heavy_top_case(
        "heavy-top-slow",
        "Slow heavy top: spin 15 rad/s from 45°, nutation to 80°, 10 s",
        {"spin_rad_s": 15.0, "theta0_deg": 45.0},
        error_kind="axis",
        baselines=RATIO_BASELINES,
    )


#: Released 1° from upright at 60 rad/s (four times the sleeping threshold of 15.7 rad/s): the axis stays
#: within 1.04° of the vertical, so the error that matters is the phase of the spin (attitude error).
SLEEPING_TOP = {"spin_rad_s": 60.0, "theta0_deg": 1.0}


def sleeping_top_case() -> Case:
    return _heavy_top_case(
        "heavy-top-sleeping",
        "Sleeping top: 60 rad/s released 1° from upright, 10 s",
        SLEEPING_TOP,
        error_kind="attitude",
        baselines=RATIO_BASELINES,
    )


def free_body_case() -> Case:
    inertia = (1e-3, 2e-3, 3e-3)
    omega0 = np.array([0.01, 10.0, 0.01])
    body = PivotedBody(inertia)
    y0 = np.concatenate([[1.0, 0.0, 0.0, 0.0], omega0])

    def reference(t: np.ndarray) -> np.ndarray:
        from app.physics.systems.ch10.free_body_elliptic import free_body_elliptic

        return free_body_elliptic(inertia=inertia, omega0_body=omega0).quaternion(t)

    return Case(
        id="free-body-dzhanibekov",
        title="Torque-free body, intermediate-axis flips, 10 s (I = (1, 2, 3)·10⁻³ kg·m²)",
        body=body,
        y0=y0,
        t_end_s=10.0,
        frame_rate_hz=60.0,
        error_measure="largest attitude error (rotation angle) over all frames",
        reference_name="Jacobi elliptic closed form (ω) with quadrature for the angle about L",
        reference_quaternion=reference,
        error_kind="attitude",
    )


CASES: dict[str, Callable[[], Case]] = {
    "heavy-top": heavy_top_case,
    "free-body-dzhanibekov": free_body_case,
    "heavy-top-fast": fast_top_case,
    "heavy-top-slow": slow_top_case,
    "heavy-top-sleeping": sleeping_top_case,
}

#: Settings swept for each of our methods: steps per frame (fixed step) or rtol (adaptive).
OUR_SETTINGS: dict[str, list[float]] = {
    "splitting4": [1, 2, 3, 4, 6, 8, 12, 16],
    # 3 steps per frame: a point on each side of 1e-3 rad on the heavy tops, where a ratio is quoted.
    "splitting2": [2, 3, 4, 8, 16, 32, 64, 128],
    "rk4": [2, 4, 8, 12, 16, 24, 32, 64],
    "dopri5": [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11],
    "splitting6": [1, 2, 3, 4, 6, 8],
    "splitting8": [1, 2, 3, 4, 6],
}


def our_sweeps() -> list[tuple[str, str, str, str, list[float]]]:
    """One sweep per registered method: (method id, family, label, setting name, settings)."""
    missing = set(METHODS) - set(OUR_SETTINGS)
    if missing:
        raise ValueError(f"no benchmark settings for the registered methods {sorted(missing)}")
    return [
        (
            name,
            "dynlab",
            f"{spec.short_label} (numba)",
            "rtol" if spec.adaptive else "steps_per_frame",
            OUR_SETTINGS[name],
        )
        for name, spec in METHODS.items()
    ]


# Sweeps: (method id, family, label, setting name, settings).
OUR_SWEEPS = our_sweeps()
SCIPY_SWEEPS: list[tuple[str, str, str, str, list[float]]] = [
    ("scipy-RK45", "scipy", "scipy RK45 (numpy RHS)", "rtol", [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]),
    # From 1e-3: the ratios at 1e-3 rad need a DOP853 point on each side of that error.
    (
        "scipy-DOP853",
        "scipy",
        "scipy DOP853 (numpy RHS)",
        "rtol",
        [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12],
    ),
    ("scipy-LSODA", "scipy", "scipy LSODA (numpy RHS)", "rtol", [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]),
    ("scipy-Radau", "scipy", "scipy Radau (numpy RHS)", "rtol", [1e-4, 1e-5, 1e-6, 1e-7]),
]
MUJOCO_SWEEPS: list[tuple[str, str, str, str, list[float]]] = [
    # To 256 steps per frame: the ratios at 1e-9 rad need a point below that error.
    ("mujoco-RK4", "mujoco", "MuJoCo RK4 (ball joint)", "steps_per_frame", [1, 2, 4, 8, 16, 32, 64, 128, 256]),
    ("mujoco-Euler", "mujoco", "MuJoCo Euler, its default (ball joint)", "steps_per_frame", [4, 16, 64]),
]


#: One timing rule for every family (ours, scipy, MuJoCo): each run is warm, and the least CPU time of up to
#: TIMING_REPEATS runs is kept, stopping once the runs have used TIMING_BUDGET_S of CPU (after at least
#: TIMING_MIN_REPEATS). Every setting gets the same CPU budget: a sub-millisecond run needs hundreds of
#: repeats on a loaded machine before its least time is its own cost (the first tens are up to 60 % dearer,
#: measured), a long one is measured a few times only.
TIMING_REPEATS = 1000
TIMING_MIN_REPEATS = 2
TIMING_BUDGET_S = 0.3


def _best_cpu(run: Callable[[], tuple[Any, float]], *, repeats: int = TIMING_REPEATS) -> tuple[Any, float]:
    """Repeat ``run`` (returning its result and its CPU time in s) by the timing rule above, at most ``repeats`` times.

    Returns the last result and the least CPU time (s).
    """
    best = math.inf
    spent = 0.0
    result = None
    for repeat in range(1, repeats + 1):
        result, cpu = run()
        best = min(best, cpu)
        spent += cpu
        if repeat >= TIMING_MIN_REPEATS and spent >= TIMING_BUDGET_S:
            break
    return result, best


def _timed(fn: Callable[[], Any], *, repeats: int = TIMING_REPEATS) -> tuple[Any, float]:
    """:func:`_best_cpu` of ``fn`` timed by the process CPU clock around the call."""

    def run() -> tuple[Any, float]:
        start = time.process_time()
        result = fn()
        return result, time.process_time() - start

    return _best_cpu(run, repeats=repeats)


def numpy_rhs(body: PivotedBody) -> Callable[[float, np.ndarray], np.ndarray]:
    """The rigid body's right-hand side written with numpy, as a scipy user would."""
    inertia = np.asarray(body.inertia_pivot_kg_m2)
    mgl = body.gravity_moment_N_m

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q, omega = y[:4], y[4:]
        w, x, yq, z = q
        q_dot = 0.5 * np.array(
            [
                -x * omega[0] - yq * omega[1] - z * omega[2],
                w * omega[0] + yq * omega[2] - z * omega[1],
                w * omega[1] - x * omega[2] + z * omega[0],
                w * omega[2] + x * omega[1] - yq * omega[0],
            ]
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
    result, cpu = _timed(run)
    return result.states[:, :4], cpu, result.rhs_evals, result.status


def run_scipy(case: Case, method: str, rtol: float, frames_t: np.ndarray) -> tuple[np.ndarray, float, int, str]:
    rhs = numpy_rhs(case.body)
    name = method.split("-", 1)[1]

    def run():
        return solve_ivp(rhs, (0.0, case.t_end_s), case.y0, method=name, rtol=rtol, atol=rtol * 1e-3, t_eval=frames_t)

    solution, cpu = _timed(run)
    status = "ok" if solution.success else "failed"
    return solution.y[:4].T, cpu, int(solution.nfev), status


def run_mujoco(
    case: Case, method: str, steps_per_frame: int, frames_t: np.ndarray
) -> tuple[np.ndarray, float, int, str]:
    from app.bench.mujoco_models import simulate_rigid_body_mujoco

    body = case.body
    kwargs: dict[str, Any] = dict(
        inertia_pivot=body.inertia_pivot_kg_m2,
        mass_kg=body.mass_kg if body.mass_kg > 0 else 1.0,
        cg_distance_m=body.cg_distance_m,
        g_m_s2=body.g_m_s2,
        q0=case.y0[:4],
        omega0_body=case.y0[4:],
        t_end_s=case.t_end_s,
        frame_rate_hz=case.frame_rate_hz,
        steps_per_frame=int(steps_per_frame),
        integrator=method.split("-", 1)[1],
    )
    simulate_rigid_body_mujoco(**{**kwargs, "t_end_s": 1.0 / case.frame_rate_hz})  # warm

    def timed_run():
        # MuJoCo's own clock: the stepping loop only, model compilation excluded.
        mujoco_run = simulate_rigid_body_mujoco(**kwargs)
        return mujoco_run, mujoco_run.cpu_s

    run, best = _best_cpu(timed_run)
    status = "ok" if np.all(np.isfinite(run.quaternion)) else "non_finite"
    return run.quaternion, best, int(run.steps), status


def mujoco_batch_check(case: Case) -> dict[str, Any]:
    """Is the per-frame Python loop fair to MuJoCo? Its RK4 at one step per frame, timed both ways.

    The benchmark drives MuJoCo as a user would, one ``mj_step(model, data, nstep)`` call per frame;
    ``mujoco.rollout`` runs the same steps in one C++ call with no Python between them. The two are
    timed alternately, the least CPU time of TIMING_REPEATS runs each, and give the same states
    (checked); the relative difference is what a batch interface would take off MuJoCo's cost.
    """
    import mujoco
    from mujoco import rollout

    from app.bench.mujoco_models import build_rigid_body_model, simulate_rigid_body_mujoco

    body = case.body
    frames = int(round(case.t_end_s * case.frame_rate_hz))
    body_kwargs: dict[str, Any] = dict(
        inertia_pivot=body.inertia_pivot_kg_m2,
        mass_kg=body.mass_kg,
        cg_distance_m=body.cg_distance_m,
        g_m_s2=body.g_m_s2,
    )
    model, data = build_rigid_body_model(**body_kwargs, timestep_s=1.0 / case.frame_rate_hz, integrator="RK4")
    model.opt.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_ENERGY)
    data.qpos[:] = case.y0[:4] / np.linalg.norm(case.y0[:4])
    data.qvel[:] = case.y0[4:]
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    initial = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, initial, spec)
    loop_kwargs: dict[str, Any] = dict(
        **body_kwargs,
        q0=case.y0[:4],
        omega0_body=case.y0[4:],
        t_end_s=case.t_end_s,
        frame_rate_hz=case.frame_rate_hz,
        steps_per_frame=1,
        integrator="RK4",
    )
    loop_cpu = batch_cpu = math.inf
    # Alternated, so a change in the machine's load between them falls on both.
    for _ in range(TIMING_REPEATS):
        loop = simulate_rigid_body_mujoco(**loop_kwargs)
        loop_cpu = min(loop_cpu, loop.cpu_s)
        start = time.process_time()
        states = rollout.rollout(model, data, initial[None, :], nstep=frames)[0]
        batch_cpu = min(batch_cpu, time.process_time() - start)
    # FULLPHYSICS state: time, then qpos (the quaternion), then qvel.
    same = bool(np.allclose(states[0, :, 1:5], loop.quaternion[1:], rtol=0.0, atol=1e-12))
    saving = 1.0 - batch_cpu / loop_cpu
    return {
        "case": case.id,
        "method": "mujoco-RK4",
        "steps_per_frame": 1,
        "loop_cpu_s": loop_cpu,
        "rollout_cpu_s": batch_cpu,
        "same_states": same,
        "rollout_saving": saving,
        "text": f"MuJoCo RK4, 1 step/frame, {case.id}: {loop_cpu * 1e3:.3g} ms with one mj_step call per frame, "
        f"{batch_cpu * 1e3:.3g} ms in one mujoco.rollout call ({100 * abs(saving):.0f}% "
        f"{'less' if saving >= 0 else 'more'})"
        f"{'' if same else ' (states differ!)'}.",
    }


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
    from app.scenes import SCENES

    out = []
    for scene_id, cls in SCENES.items():
        entry: dict[str, Any] = {"scene_id": scene_id}
        model_cls = cls.model
        scene_us, scene_physics_us = scene_frame_cost_us(cls) if cls.animated else (0.0, 0.0)
        drift = None
        if model_cls is not None:
            # Stepped live: its compiled run's cost per frame, with the integrator a scene uses (measured first, as a
            # scene would choose it); a formula evaluated at each frame's time: its share of the scene's own frame.
            live = live_run_cost_us(cls) if model_cls.integrated else None
            model = model_cls()
            report = model.simulate(model.parameters.defaults(), {}, t_end_s=60.0, frame_rate_hz=30.0)
            drift = report.max_invariant_drift
            if live is not None:
                physics_us, integrator = live
                entry.update(
                    method=integrator.name, description=integrator.describe(FRAME_DT_S), physics_us_per_frame=physics_us
                )
            else:
                entry.update(
                    method=report.method,
                    physics_us_per_frame=scene_physics_us,
                    description=f"{report.description}, evaluated at each frame's time",
                )
        elif cls.example is not None:
            example = cls.example
            inputs = example.inputs.defaults()
            example.solve(inputs)
            start = time.perf_counter()
            for _ in range(100):
                example.solve(inputs)
            entry.update(
                method="static",
                physics_us_per_frame=0.0,
                solve_us_on_change=1e4 * (time.perf_counter() - start),
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
        "cpu": platform.processor() or platform.machine(),
        "cores": __import__("os").cpu_count(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
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
        sys.stderr.write(
            f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {elapsed:5.0f} s  {text[:60]:<60}"
        )
        sys.stderr.flush()
        if self.done == self.total:
            sys.stderr.write("\n")


def run_benchmark(
    case_ids: Sequence[str] | None = None, *, include_mujoco: bool = True, quick: bool = False
) -> dict[str, Any]:
    """Measure every sweep of every case; return the report dictionary."""
    try:
        import mujoco  # noqa: F401
    except ImportError:
        include_mujoco = False
    cases = [CASES[c]() for c in (case_ids or CASES)]
    sweeps = OUR_SWEEPS + SCIPY_SWEEPS + (MUJOCO_SWEEPS if include_mujoco else [])
    if quick:
        sweeps = [(m, f, l, s, values[::3]) for m, f, l, s, values in sweeps]

    def case_sweeps(case: Case) -> list:
        return [s for s in sweeps if s[1] == "dynlab" or case.baselines is None or s[0] in case.baselines]

    study_runs = list(PHASE_DRIFT_RUNS[:2] if quick else PHASE_DRIFT_RUNS)
    progress = Progress(sum(len(s[4]) for case in cases for s in case_sweeps(case)) + len(study_runs) + 1)
    report: dict[str, Any] = {
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "machine": _machine(),
        "scenes": [],
    }
    for case in cases:
        frames_t = np.arange(int(round(case.t_end_s * case.frame_rate_hz)) + 1) / case.frame_rate_hz
        reference = case.reference_quaternion(frames_t)
        methods = []
        for method, family, label, setting_name, settings in case_sweeps(case):
            runner = {"dynlab": run_ours, "scipy": run_scipy, "mujoco": run_mujoco}[family]
            points = []
            for setting in settings:
                progress.step(f"{case.id}: {label} {setting_name}={setting:g}")
                quaternions, cpu, evals, status = runner(case, method, setting, frames_t)
                error = (
                    case.error(quaternions, reference)
                    if status == "ok" and len(quaternions) == len(frames_t)
                    else math.inf
                )
                points.append(
                    {
                        "setting": setting,
                        "cpu_s": cpu,
                        "error": error if math.isfinite(error) else None,
                        "rhs_evals": evals,
                        "status": status if math.isfinite(error) else "failed",
                    }
                )
            methods.append(
                {"method": method, "family": family, "label": label, "setting_name": setting_name, "points": points}
            )
        # The default operating point: what a scene runs at this frame rate with "auto" (the error-target choice).
        choice = case.automatic_choice()
        if choice is None:
            raise RuntimeError(f"{case.id}: no pilot run of any method finished; the automatic choice is undefined")
        adaptive = choice.steps_per_frame is None
        setting = choice.rtol if adaptive else choice.steps_per_frame
        assert setting is not None  # a choice sets rtol or steps_per_frame
        default_integrator = (
            make_integrator(choice.method, rtol=choice.rtol)
            if adaptive
            else make_integrator(choice.method, steps_per_frame=choice.steps_per_frame)
        )
        q_default, cpu_default, _, _ = run_ours(case, choice.method, setting, frames_t)
        default = {
            "method": choice.method,
            "setting": setting,
            "setting_name": "rtol" if adaptive else "steps_per_frame",
            "description": default_integrator.describe(1.0 / case.frame_rate_hz),
            "cpu_s": cpu_default,
            "error": case.error(q_default, reference),
            "target_error": case.target_error,
            "estimated_error": choice.estimated_error,
            "accuracy": choice.text(),
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
                ratios.append(
                    {
                        "baseline": baseline,
                        "at_error": case.target_error,
                        "ratio": None,
                        "text": f"{base['label']} never reached {case.target_error:.0e} in the sweep",
                    }
                )
                continue
            ratio = theirs / ours
            ratios.append(
                {
                    "baseline": baseline,
                    "at_error": case.target_error,
                    "ratio": ratio,
                    "ours_cpu_s": ours,
                    "theirs_cpu_s": theirs,
                    "ours": case.default_method,
                    "text": f"At {case.target_error:.0e} {'rad'} error, {case.default_method} needs "
                    f"{ours * 1e3:.3g} ms of CPU; {base['label']} needs {theirs * 1e3:.3g} ms: {ratio:.0f}× more.",
                }
            )
        ratios.extend(best_ratios(methods))
        report["scenes"].append(
            {
                "scene_id": case.id,
                "live_scene": case.scene_id,
                "title": case.title,
                "t_end_s": case.t_end_s,
                "frame_rate_hz": case.frame_rate_hz,
                "error_measure": case.error_measure,
                "error_unit": "rad",
                "reference": case.reference_name,
                "target_error": case.target_error,
                "default": default,
                "methods": methods,
                "ratios": ratios,
                "plot": f"{case.id}.svg",
            }
        )
    report["ratio_summary"] = ratio_summary(report["scenes"])
    report["timing"] = {
        "rule": (
            f"every run warm; least process CPU time of up to {TIMING_REPEATS} runs, stopping once the runs have used "
            f"{TIMING_BUDGET_S:g} s (at least {TIMING_MIN_REPEATS} runs); the same rule for ours, scipy and MuJoCo"
        ),
        "mujoco": (
            "compiled model, contacts, constraints and the energy computation off; "
            "one mj_step(model, data, nstep) call per frame, model compilation not timed"
        ),
    }
    if include_mujoco and "heavy-top-slow" in (case_ids or CASES):
        report["timing"]["mujoco_batch_check"] = mujoco_batch_check(CASES["heavy-top-slow"]())
    report["phase_drift"] = phase_drift_study(study_runs, progress=progress)
    progress.step("live scenes: physics cost per frame and 60 s invariant drift")
    report["live_scenes"] = live_frame_costs()
    return report


#: Errors (rad) at which the best of our methods is compared with each baseline.
RATIO_ERRORS = (1e-3, 1e-6, 1e-9)
#: What the issue asks of the best of ours at every one of those errors: at least this many times cheaper.
REQUIRED_RATIO = {"scipy-DOP853": 100.0, "mujoco-RK4": 20.0}


def _error_span(points: Sequence[dict]) -> tuple[float, float] | None:
    errors = [p["error"] for p in points if p["status"] == "ok" and p["error"] is not None and p["error"] > 0]
    return (min(errors), max(errors)) if errors else None


def best_ratios(methods: Sequence[dict], errors: Sequence[float] = RATIO_ERRORS) -> list[dict[str, Any]]:
    """At each error, the cheapest of our methods against each baseline of :data:`REQUIRED_RATIO` (ratio = theirs /
    ours).

    Costs are interpolated along each curve (:func:`cost_at_error`). A baseline whose sweep does not
    reach down to the error gives no ratio; one whose largest error is already below it is costed at its
    cheapest point, an over-estimate, so that ratio is marked ``"bracketed": false``.
    """
    ours = [m for m in methods if m["family"] == "dynlab"]
    out = []
    for error in errors:
        costs = [(cost_at_error(m["points"], error), m["method"]) for m in ours]
        reached = [(c, name) for c, name in costs if c is not None]
        if not reached:
            continue
        our_cpu, our_method = min(reached)
        for baseline, required in REQUIRED_RATIO.items():
            base = next((m for m in methods if m["method"] == baseline), None)
            if base is None:
                continue
            theirs = cost_at_error(base["points"], error)
            span = _error_span(base["points"])
            entry: dict[str, Any] = {
                "baseline": baseline,
                "at_error": error,
                "ours": our_method,
                "ours_cpu_s": our_cpu,
                "required_ratio": required,
            }
            if theirs is None:
                entry.update(ratio=None, text=f"{base['label']} never reached {error:.0e} rad in the sweep")
            else:
                ratio = theirs / our_cpu
                entry.update(
                    ratio=ratio,
                    theirs_cpu_s=theirs,
                    bracketed=bool(span and span[1] >= error),
                    meets_requirement=ratio >= required,
                    text=f"At {error:.0e} rad, the cheapest of ours ({our_method}) needs {our_cpu * 1e3:.3g} ms "
                    "of CPU; "
                    f"{base['label']} needs {theirs * 1e3:.3g} ms: {ratio:.0f}× more (asked: ≥ {required:.0f}×).",
                )
            out.append(entry)
    return out


def ratio_summary(scenes: Sequence[dict]) -> dict[str, Any]:
    """Per heavy-top case, the best-of-ours ratios at :data:`RATIO_ERRORS` against each baseline, and whether all meet
    the ask."""
    cases: dict[str, Any] = {}
    for scene in scenes:
        if not str(scene["scene_id"]).startswith("heavy-top"):
            continue
        table: dict[str, list] = {}
        for r in scene["ratios"]:
            if "required_ratio" in r:
                table.setdefault(r["baseline"], []).append(
                    {"at_error": r["at_error"], "ratio": r["ratio"], "ours": r["ours"]}
                )
        cases[scene["scene_id"]] = table
    met = [
        r.get("meets_requirement", False)
        for s in scenes
        if str(s["scene_id"]).startswith("heavy-top")
        for r in s["ratios"]
        if "required_ratio" in r
    ]
    return {"errors": list(RATIO_ERRORS), "required": REQUIRED_RATIO, "cases": cases, "all_met": bool(met) and all(met)}


#: Runs of the phase-against-drift study: (method, steps per frame), None for the step (or rtol 1e-8) a live
#: scene picks automatically; one step per frame is the cheapest setting a student can choose.
PHASE_DRIFT_RUNS: tuple[tuple[str, int | None], ...] = (
    ("splitting2", 1),
    ("splitting2", None),
    ("splitting4", 1),
    ("splitting4", None),
    ("splitting6", 1),
    ("splitting8", 1),
    ("rk4", 4),
    ("rk4", None),
    ("dopri5", None),
)
PHASE_DRIFT_SECONDS = 600.0


def _setting_text(integrator, steps_per_frame: int | None) -> str:
    """``1 step/frame``, ``auto: 5 steps/frame`` or ``auto: rtol 1e-8``."""
    if integrator.adaptive:
        return f"auto: rtol {integrator.rtol:.0e}"
    n = integrator.steps_per_frame
    return f"{'' if steps_per_frame else 'auto: '}{n} step{'' if n == 1 else 's'}/frame"


def phase_drift_study(
    runs: Sequence[tuple[str, int | None]] = PHASE_DRIFT_RUNS, *, progress: Progress | None = None
) -> dict[str, Any]:
    """The sleeping top over 600 s at 60 frames/s: each run's largest relative energy drift beside its attitude error
    (rad).

    The attitude error (rotation angle, spin phase included) is against the quadrature solution. A
    symplectic method keeps the energy error bounded and small while its phase error grows with time.
    """
    params = heavy_top_params(SLEEPING_TOP)
    body = heavy_top.rigid_body(params)
    y0 = heavy_top.initial_state(params)
    system = body.system()
    rows = []
    reference = None
    for method, steps_per_frame in runs:
        if progress is not None:
            progress.step(f"phase against drift: {method}, {PHASE_DRIFT_SECONDS:g} s")
        integrator = make_integrator(
            method, steps_per_frame=steps_per_frame, fastest_rate_rad_s=body.fastest_rate_rad_s(y0), frame_dt_s=1 / 60
        )
        result = simulate(system, integrator, y0, t_end_s=PHASE_DRIFT_SECONDS, frame_rate_hz=60.0)
        if reference is None:
            reference = heavy_top.quadrature(params).quaternion(result.t_s)
        energy = body.energy_J(result.states)
        error = attitude_error_rad(result.states[:, :4], reference)
        rows.append(
            {
                "method": method,
                "label": METHODS[method].short_label,
                "description": integrator.describe(1 / 60),
                "setting": "auto" if steps_per_frame is None else steps_per_frame,
                "setting_text": _setting_text(integrator, steps_per_frame),
                "status": result.status,
                "cpu_s": result.cpu_s,
                "energy_drift": float(np.max(np.abs(energy - energy[0])) / abs(energy[0])),
                "attitude_error_rad": float(error.max()),
                "attitude_error_10s_rad": float(error[: 10 * 60 + 1].max()),
            }
        )
    return {
        "title": f"Sleeping top over {PHASE_DRIFT_SECONDS:g} s: energy drift beside attitude error",
        "case": "heavy-top-sleeping",
        "parameters": {k: float(v) for k, v in params.items()},
        "t_end_s": PHASE_DRIFT_SECONDS,
        "frame_rate_hz": 60.0,
        "reference": "quadrature solution",
        "methods": rows,
        "plot": "heavy-top-phase-drift.svg",
    }


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
        print(
            f"{scene['title']}: default {scene['default']['description']}: "
            f"{scene['default']['cpu_s'] * 1e3:.3g} ms, error {scene['default']['error']:.2e} rad"
        )
        for ratio in scene["ratios"]:
            print("  " + ratio["text"])
    if "mujoco_batch_check" in report["timing"]:
        print(report["timing"]["mujoco_batch_check"]["text"])
    summary = report["ratio_summary"]
    print(
        f"best of ours against {', '.join(summary['required'])} at "
        f"{', '.join(f'{e:.0e}' for e in summary['errors'])} rad"
        f" (all asked ratios met: {summary['all_met']}):"
    )
    for case_id, table in summary["cases"].items():
        for baseline, rows in table.items():
            cells = ", ".join(
                f"{r['at_error']:.0e}: {r['ratio']:.0f}× ({r['ours']})" if r["ratio"] else f"{r['at_error']:.0e}: —"
                for r in rows
            )
            print(f"  {case_id} vs {baseline}: {cells}")
    for row in report["phase_drift"]["methods"]:
        print(
            f"sleeping top {PHASE_DRIFT_SECONDS:g} s, {row['description']}: energy drift {row['energy_drift']:.1e}, "
            f"attitude error {row['attitude_error_rad']:.1e} rad"
        )
    for live in report["live_scenes"]:
        drift = f", 60 s drift {live['max_invariant_drift_60s']:.1e}" if "max_invariant_drift_60s" in live else ""
        print(f"live {live['scene_id']}: {live['physics_us_per_frame']:.2f} µs/frame ({live['description']}){drift}")
    return 0
