"""What one displayed frame costs each scene, measured without a browser.

A scene is built on a :class:`NullClient` — an object that accepts every viser
call a scene makes and sends nothing — and advanced frame by frame at 30 Hz.
The time of ``advance`` is the scene's whole frame: its physics and the
Python side of updating its drawing. The physics share of it is measured with
the profiler: the time spent in ``app.physics`` code entered from the scene,
as a fraction of the profiled frame, applied to the unprofiled frame time. For
an integrated scene the compiled live run is also timed on its own.
"""

from __future__ import annotations

import contextlib
import cProfile
import pstats
import time
from pathlib import Path
from typing import Any

import app.physics

PHYSICS_DIR = str(Path(app.physics.__file__).resolve().parent)

#: Frames timed per scene after the warm-up frames (30 Hz: 20 s of motion).
TIMED_FRAMES = 600
WARM_UP_FRAMES = 30
FRAME_DT_S = 1.0 / 30.0


#: What a viser scene node's pose is when it was made without one (a scene may read it back).
_SCENE_NODE_DEFAULTS: dict[str, tuple[float, ...]] = {"position": (0.0, 0.0, 0.0), "wxyz": (1.0, 0.0, 0.0, 0.0)}


class NullHandle:
    """Stands for any viser handle or API: remembers attributes set on it; any call returns a new handle.

    An attribute never set is a handle of its own, made on first use and kept
    (so ``client.scene`` is one object), which makes every ``add_*`` result distinct.
    """

    def __init__(self) -> None:
        object.__setattr__(self, "_values", {})

    def __setattr__(self, name: str, value: Any) -> None:
        self._values[name] = value

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return self._values.setdefault(name, _SCENE_NODE_DEFAULTS.get(name) or NullHandle())

    def __call__(self, *args: Any, **kwargs: Any) -> NullHandle:
        """A new handle holding the keyword arguments it was made with, as viser's handles do (``add_frame(...,
        position=…)`` has that ``position``: a scene may read it back)."""
        handle = NullHandle()
        handle._values.update(kwargs)
        return handle

    def __enter__(self) -> NullHandle:
        return self

    def __exit__(self, *exc: object) -> None:
        return None


class NullClient(NullHandle):
    """A viser client that draws nothing: what a scene spends per frame, without the websocket."""

    def atomic(self) -> contextlib.AbstractContextManager[None]:
        return contextlib.nullcontext()


def _time_frames(advance, frames: int) -> float:
    for _ in range(WARM_UP_FRAMES):
        advance(FRAME_DT_S)
    start = time.perf_counter()
    for _ in range(frames):
        advance(FRAME_DT_S)
    return (time.perf_counter() - start) / frames


def _physics_fraction(profile: cProfile.Profile) -> float:
    """Share of the profiled time spent in ``app.physics`` functions called from outside it."""
    stats = pstats.Stats(profile).stats  # type: ignore[attr-defined]
    total = sum(tt for _, _, tt, _, _ in stats.values())
    in_physics = 0.0
    for (filename, _, _), (_, _, _, _, callers) in stats.items():
        if not filename.startswith(PHYSICS_DIR):
            continue
        for (caller_file, _, _), (_, _, _, cumulative) in callers.items():
            if not caller_file.startswith(PHYSICS_DIR):
                in_physics += cumulative
    return min(in_physics / total, 1.0) if total > 0 else 0.0


def scene_frame_cost_us(cls) -> tuple[float, float]:
    """µs per ``advance`` of a scene at its defaults on a :class:`NullClient`: the whole frame, and its physics
    share."""
    scene = cls(NullClient(), cls.parameters.defaults())
    try:
        frame_us = 1e6 * _time_frames(scene.advance, TIMED_FRAMES)
        profile = cProfile.Profile()
        profile.enable()
        for _ in range(WARM_UP_FRAMES * 4):
            scene.advance(FRAME_DT_S)
        profile.disable()
        return frame_us, frame_us * _physics_fraction(profile)
    finally:
        scene.close()


def live_run_cost_us(cls) -> tuple[float, Any]:
    """µs one frame of an integrated scene's compiled live run takes (physics only), and the integrator used."""
    from app.physics.solvers import LiveRun
    from app.physics.solvers.step_policy import choose_integrator

    model = cls.model()
    params = model.parameters.defaults()
    integrator, _ = choose_integrator(model, params, {}, FRAME_DT_S)
    run = LiveRun(model.system(params), integrator, model.initial_state(params))
    return 1e6 * _time_frames(run.advance, 3000), integrator
