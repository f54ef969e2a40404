"""A fair share of a scene worker: no client, viewer or request takes the frames of the others.

A worker draws every viewer's scene once a frame (30 frames/s) in one thread. A
scene whose controls ask for a lot of computing (RK4 at 4096 steps per frame on
the double pendulum costs about 10 ms a frame) would, left alone, slow the frame
for everyone in its worker; so would many tabs from one device, or a request that
computes minutes of motion at once (a share link's ``go_to_s`` of 600 s, 300
frames of ``step``). The rules:

* **Frames, shared by device.** Each viewer's cost a frame is measured
  (:class:`FrameCost`: the least of its last few drawn frames, since waiting for
  the interpreter's lock only ever adds, plus the mean of the physics an
  integrated scene computes in batches of frames). A device's demand is the sum of
  its viewers' costs. A few devices share :data:`FRAME_LOOP_SHARE` of the frame
  max-min fairly (:func:`allowances`): while all fits nobody is slowed, and a
  device alone is never slowed. A worker serving a class (:data:`CLASS_DEVICES`
  devices or more) streams to all of them whatever the frame loop's share says,
  so there a device may use at most the larger of :data:`CLASS_FLOOR_S` and
  :data:`CLASS_MULTIPLE` times the median device's cost: a class whose scenes
  cost alike is never slowed however large, while a device several times dearer
  than its class is (RK4 at 4096 steps a frame; also, measured, a default
  rigid-body-points scene at 2.2 ms a frame among heavy tops at 0.25 ms). A
  device over its allowance has its viewers advance on only that fraction of
  frames: its scenes run slower than real time, each step still the one its
  controls chose, and its time controls say by how much and why
  (:func:`slowdown_note`). Measured with ``dynlab load --attack``: one device
  attacking a class of 100 took them from 29.6 to 0.5 frames/s before these
  rules, 28.3 after (docs/bench/attack.json).
* **Requests** (step, going to a time, a recording) compute at most
  :data:`REQUEST_COMPUTE_S`: a request estimated to need more is refused before it
  starts, naming the limit, and one that runs over is stopped and undone. They are
  paced (:class:`Pace`): after each :data:`SLICE_S` of computing they leave the
  processor to the frame loop for :data:`PACE_RATIO` times as long.
"""

from __future__ import annotations

import math
import time
from collections import deque
from collections.abc import Callable, Mapping

#: The part of each frame period the frame loop's scenes may share (the rest is viser's streaming and the calls).
FRAME_LOOP_SHARE = 0.5
#: Most computing one request (step, go to a time, a recording) may take (s): a share link to 600 s of the heavy
#: top needs about half of it, a 60 s recording most of it.
REQUEST_COMPUTE_S = 1.0
#: A paced request computes this long (s) ...
SLICE_S = 2e-3
#: A step of more than this many frames, or any jump to a time, is a *long* request: paced, one at a time in a worker,
#: and counted against the device's share of long requests (:class:`app.api.access.SessionDirectory`). The step
#: button steps one frame.
LONG_STEP_FRAMES = 30
#: ... then leaves the processor to the frame loop for this many times as long (a tenth of a worker's time at most:
#: every slice holds the interpreter's lock, so the frame loop waits a slice at most, then runs).
PACE_RATIO = 9.0
#: A worker serving this many devices serves a class: each device may then use at most the larger of
#: :data:`CLASS_FLOOR_S` and :data:`CLASS_MULTIPLE` times the median device's cost a frame, however idle the frame.
CLASS_DEVICES = 8
CLASS_FLOOR_S = 1.0e-3
CLASS_MULTIPLE = 2.0
#: Frames a paced computation runs before its whole cost is projected from them.
PROJECT_AFTER = 10
#: Frames a viewer's cost is taken over (the least of them), and frames measured before it may be slowed.
COST_WINDOW = 8
COST_WARM_UP = 3


class FrameCost:
    """What one viewer's scene costs to advance and draw one frame (s): the least of its last :data:`COST_WINDOW`
    frames (a frame interrupted by another thread only ever looks dearer). Unknown (0) for the first
    :data:`COST_WARM_UP` frames, which include compiling and first drawings."""

    __slots__ = ("_recent", "frames")

    def __init__(self) -> None:
        self._recent: deque[float] = deque(maxlen=COST_WINDOW)
        self.frames = 0

    def add(self, seconds: float) -> None:
        self.frames += 1
        if self.frames > 1:  # the first frame after a viewer connects pays for compiling and first drawings
            self._recent.append(seconds)

    @property
    def seconds(self) -> float:
        return min(self._recent) if self.frames >= COST_WARM_UP and self._recent else 0.0


def allowances(demands: Mapping[str, float], *, capacity_s: float) -> dict[str, float]:
    """Each client's allowance (s of computing a frame) given what each demands (s a frame), ``inf`` for no limit.

    A few clients share ``capacity_s`` max-min fairly (unlimited while everything fits). In a class
    (:data:`CLASS_DEVICES` or more) a client asking no more than the larger of :data:`CLASS_FLOOR_S` and
    :data:`CLASS_MULTIPLE` times the median is never limited, so a class whose scenes cost alike is never slowed
    however large it is; a dearer one gets at most that much (or its fair share, if less)."""
    fair = _max_min_shares(demands, capacity_s=capacity_s)
    if len(demands) < CLASS_DEVICES:
        return fair
    ordered = sorted(demands.values())
    middle = len(ordered) // 2
    median = ordered[middle] if len(ordered) % 2 else 0.5 * (ordered[middle - 1] + ordered[middle])
    typical = max(CLASS_FLOOR_S, CLASS_MULTIPLE * median)
    return {client: math.inf if demand <= typical else min(fair[client], typical) for client, demand in demands.items()}


def _max_min_shares(demands: Mapping[str, float], *, capacity_s: float) -> dict[str, float]:
    total = sum(demands.values())
    if total <= capacity_s or len(demands) < 2:
        return {client: math.inf for client in demands}
    out: dict[str, float] = {}
    left, remaining = capacity_s, sorted(demands.items(), key=lambda item: item[1])
    while remaining:
        level = left / len(remaining)
        client, demand = remaining[0]
        if demand > level:  # everyone left asks more than an equal share: they get it
            out.update({c: level for c, _ in remaining})
            break
        out[client] = math.inf
        left -= demand
        remaining.pop(0)
    return out


def slowdown_note(rate: float, demand_s: float, allowance_s: float, *, viewers: int) -> str:
    """Why a client's scenes run at ``rate`` × their chosen speed, for the readout."""
    whose = "this scene costs" if viewers == 1 else f"this device's {viewers} scenes cost"
    return (
        f"Running at {rate:.2g}× the chosen speed: {whose} {1e3 * demand_s:.1f} ms of computing a frame, and while a "
        f"class shares this server each device may use {1e3 * allowance_s:.1f} ms. Fewer steps per frame, the "
        f"automatic method or fewer open tabs run in real time."
    )


class RequestTooCostly(ValueError):
    """A request would compute longer than :data:`REQUEST_COMPUTE_S`; the message names the field and the limit."""

    @classmethod
    def over_limit(cls, field: str, what: str, advice: str) -> RequestTooCostly:
        """ "``field``: ``what`` takes more than the limit …; ``advice``" (the words every such refusal uses)."""
        return cls(
            f"{field}: {what} takes more than the {REQUEST_COMPUTE_S:g} s of "
            f"computing one request may use while a class shares the server; {advice}"
        )


def check_request_cost(field: str, *, frames: int, frame_cost_s: float, what: str) -> None:
    """Refuse (``RequestTooCostly``, naming ``field``) ``frames`` frames of ``frame_cost_s`` each (s) over the limit."""
    estimate_s = frames * frame_cost_s
    if estimate_s > REQUEST_COMPUTE_S:
        raise RequestTooCostly(
            f"{field}: {what} needs {frames} frames at about {1e3 * frame_cost_s:.2g} ms each, about {estimate_s:.0f} "
            f"s of computing; one request may take at most {REQUEST_COMPUTE_S:g} s while a class shares the server. "
            f"Ask for less, or use fewer steps per frame."
        )


class Pace:
    """Called once a frame by a long computation of ``frames`` frames: every :data:`SLICE_S` it sleeps
    :data:`PACE_RATIO` times as long (the frame loop runs meanwhile), and it stops the computation (returns False) once
    ``limit_s`` is spent, or as soon as the frames done so far show that the whole would take longer (after
    :data:`PROJECT_AFTER` of them), so a request whose cost was not known yet is refused for the price of a few
    frames."""

    def __init__(
        self, *, frames: int, limit_s: float = REQUEST_COMPUTE_S, clock: Callable[[], float] = time.perf_counter
    ) -> None:
        self.frames = frames
        self.limit_s = limit_s
        self.spent_s = 0.0
        self.done = 0
        self.over = False
        self._clock = clock
        self._slice_start = clock()

    def __call__(self) -> bool:
        self.done += 1
        ran = self._clock() - self._slice_start
        if ran >= SLICE_S:
            self.spent_s += ran
            time.sleep(PACE_RATIO * ran)
            self._slice_start = self._clock()
            ran = 0.0
        spent = self.spent_s + ran
        projected = spent / self.done * self.frames if self.done >= PROJECT_AFTER else spent
        self.over = spent >= self.limit_s or projected > self.limit_s
        return not self.over

    @property
    def exhausted(self) -> bool:
        """The computation was stopped for its limit (spent, or projected from the frames done)."""
        return self.over


def is_long_request(*, step: int, go_to_s: float | None) -> bool:
    """Whether a playback request computes long enough to be paced and counted (:data:`LONG_STEP_FRAMES`)."""
    return go_to_s is not None or step > LONG_STEP_FRAMES
