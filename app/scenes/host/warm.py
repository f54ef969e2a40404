"""Warming: what a scene worker compiles and derives before its first student asks, and ``dynlab warm``.

Two disk caches make a server start quick: numba's compiled kernels (``__pycache__`` beside each module) and the
derivations of chapters 7 and 9 (:func:`app.physics.mechanics.engine.cache_directory`). A fresh install has neither:
the first process to import the scenes compiles every kernel (about 25 s of one core on the 2-core test machine),
and every scene worker that starts before the derivations are kept derives them again. ``dynlab warm`` fills both
once, in one process, before anything else starts: the test suite's first step (tests/run.sh) and a container
image's last (Dockerfile).
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass

log = logging.getLogger(__name__)


def warm_compiled_models(scenes: dict) -> None:
    """Compile, at their defaults, the equations that scenes build at run time rather than import time.

    Runs in the background after a worker starts, so that the first student to open a scene does not wait:
    chapters 7 and 9 derive (or load from the disk cache) and compile their equations (sympy up to a few seconds
    per system, numba about half a second); chapter 8 compiles each constrained system's right-hand-side and
    after-step callbacks, which are built per system at run time (0.1–0.25 s each with a warm disk cache).
    """
    from app.physics.core.bounded import WorkBusy, WorkInterrupted

    for scene in scenes.values():
        model = getattr(scene, "model", None)
        try:
            if model is not None:
                model().prepare(scene.parameters.defaults())  # (nothing for a model that builds nothing at run time)
        except (WorkBusy, WorkInterrupted) as exc:  # a busy or stopping machine: the first viewer derives it instead
            log.warning("warming %s put off: %s", scene.id, exc)
        except Exception:  # a failure here only means the first viewer compiles it, and sees the error then
            log.exception("warming %s failed", scene.id)


@dataclass(frozen=True)
class Warmed:
    """What :func:`warm_caches` did: how many scenes, and how long each step took (s, wall clock)."""

    scenes: int
    import_s: float
    models_s: float


def warm_caches(*, started: float) -> Warmed:
    """Prepare every scene's model at its defaults (:func:`warm_compiled_models`), here and now. Importing this module
    has imported every scene, which compiled (or loaded from the disk cache) every numba kernel they use: ``started``
    is :func:`time.perf_counter` from before that import."""
    from app.scenes import SCENES

    imported = time.perf_counter()
    warm_compiled_models(SCENES)
    return Warmed(scenes=len(SCENES), import_s=imported - started, models_s=time.perf_counter() - imported)
