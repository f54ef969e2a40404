"""A fair share of a scene worker: no viewer, client or request takes the frames of the others.

A worker draws every viewer's scene once a frame (30 frames/s) in one thread. A
scene whose controls ask for a lot of computing (RK4 at 4096 steps per frame on
the double pendulum costs about 10 ms a frame) would, left alone, slow the frame
for everyone in its worker; so would a request that computes minutes of motion at
once (a share link's ``go_to_s`` of 600 s, 300 frames of ``step``). The rules:

* **Per viewer:** each viewer's scene has :data:`VIEWER_FRAME_SHARE_S` of computing
  a frame. Its cost is measured (:class:`FrameCost`, a running mean of the wall time
  of its advance and drawing); a scene that costs more advances only on that fraction
  of frames, so it runs slower than real time and its readout says by how much
  (:func:`slowdown_note`). At the scenes' defaults every scene costs far less (the
  dearest, measured, is under a tenth of the share).
* **Per client:** the viewers one client address has open on one worker share
  :data:`CLIENT_FRAME_SHARE_S` a frame, so many tabs cost their owner, not the class.
* **Per request:** stepping, going to a time and recording are paced
  (:class:`Pace`): after each :data:`SLICE_S` of computing they give the frame loop
  the processor for as long again, and a request that would need more than
  :data:`REQUEST_COMPUTE_S` of computing is refused before it starts, naming the
  limit (its cost is estimated from the scene's measured frame cost).
"""

from __future__ import annotations

import time
from collections.abc import Callable

#: Computing one viewer's scene may take per displayed frame (s); beyond it the scene runs slower than real time.
VIEWER_FRAME_SHARE_S = 3e-3
#: Computing all the viewers of one client address in one worker may take per displayed frame (s).
CLIENT_FRAME_SHARE_S = 6e-3
#: Most computing one request (step, go to a time, a recording) may take (s).
REQUEST_COMPUTE_S = 2.0
#: A paced request computes this long (s), then leaves the processor to the frame loop for as long.
SLICE_S = 4e-3
#: Weight of the newest frame in a scene's running mean cost (about the last 10 frames count).
COST_WEIGHT = 0.1


class FrameCost:
    """The running mean wall time (s) one viewer's scene takes to advance and draw one frame."""

    __slots__ = ("mean_s", "frames")

    def __init__(self) -> None:
        self.mean_s = 0.0
        self.frames = 0

    def add(self, seconds: float) -> None:
        self.frames += 1
        weight = max(COST_WEIGHT, 1.0 / self.frames)  # the first frames set the mean, later ones move it
        self.mean_s += weight * (seconds - self.mean_s)

    def rate(self, share_s: float = VIEWER_FRAME_SHARE_S) -> float:
        """The fraction of frames this scene may advance on (1: every frame) to keep within ``share_s`` a frame."""
        return 1.0 if self.mean_s <= share_s else share_s / self.mean_s


def slowdown_note(rate: float, cost_s: float, *, client: bool) -> str:
    """Why a scene runs at ``rate`` × its chosen speed, for its readout."""
    whose = "this device's scenes together" if client else "one viewer"
    return (
        f"Running at {rate:.2g}× the chosen speed: a frame of this scene costs {1e3 * cost_s:.1f} ms of computing, "
        f"more than {whose} may take ({1e3 * (CLIENT_FRAME_SHARE_S if client else VIEWER_FRAME_SHARE_S):g} ms a frame) "
        f"while a class shares the server. Fewer steps per frame, or the automatic method, run in real time."
    )


class RequestTooCostly(ValueError):
    """A request would compute longer than :data:`REQUEST_COMPUTE_S`; the message names the field and the limit."""


def check_request_cost(field: str, *, frames: int, frame_cost_s: float, what: str) -> None:
    """Refuse (``RequestTooCostly``, naming ``field``) ``frames`` frames of ``frame_cost_s`` each (s) over the limit."""
    estimate_s = frames * frame_cost_s
    if estimate_s > REQUEST_COMPUTE_S:
        raise RequestTooCostly(
            f"{field}: {what} needs {frames} frames at about {1e3 * frame_cost_s:.1f} ms each, about {estimate_s:.0f} s "
            f"of computing; one request may take at most {REQUEST_COMPUTE_S:g} s while a class shares the server. "
            f"Ask for less, or use fewer steps per frame."
        )


class Pace:
    """Called once a frame by a long computation: every :data:`SLICE_S` it sleeps as long (letting the frame loop
    run), and it stops the computation (returns False) once ``limit_s`` of computing is spent."""

    def __init__(self, *, limit_s: float = REQUEST_COMPUTE_S, clock: Callable[[], float] = time.perf_counter) -> None:
        self.limit_s = limit_s
        self.spent_s = 0.0
        self._clock = clock
        self._slice_start = clock()

    def __call__(self) -> bool:
        now = self._clock()
        ran = now - self._slice_start
        if ran >= SLICE_S:
            self.spent_s += ran
            time.sleep(ran)
            self._slice_start = self._clock()
        return self.spent_s + (self._clock() - self._slice_start) < self.limit_s

    @property
    def exhausted(self) -> bool:
        return self.spent_s + (self._clock() - self._slice_start) >= self.limit_s
