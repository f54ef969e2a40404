"""The recent motion of one viewer's scene, frame by frame, for the lesson page's scrubber.

Each displayed frame the host records the scene's ``motion_state()`` (simulated
time and whatever the scene needs to redraw that instant). Scrubbing back puts
the scene at a recorded motion and redraws it: replayed from stored states, not
recomputed. Playing on from a scrubbed instant forgets the frames after it (the
motion from there is new).
"""

from __future__ import annotations

import bisect
from collections import deque
from collections.abc import Mapping
from typing import Any

#: Frames kept per viewer: 60 s of motion at 30 frames/s (about 0.5 MB for the largest state).
HISTORY_FRAMES = 1800


class MotionHistory:
    """A bounded, time-ordered record of ``(t_s, motion)``; the oldest frame goes first when it is full."""

    def __init__(self, *, max_frames: int = HISTORY_FRAMES) -> None:
        self._frames: deque[tuple[float, Mapping[str, Any]]] = deque(maxlen=max_frames)

    def __len__(self) -> int:
        return len(self._frames)

    def record(self, motion: Mapping[str, Any] | None) -> None:
        """Add the motion just drawn (ignored for None: a scene without a motion to keep)."""
        if motion is None:
            return
        t_s = float(motion["t_s"])
        if self._frames and t_s < self._frames[-1][0]:
            self._frames.clear()  # time went back (a replay restarted): the old frames belong to another run
        self._frames.append((t_s, motion))

    def span_s(self) -> tuple[float, float] | None:
        """Earliest and latest simulated time kept (s), or None if empty."""
        return (self._frames[0][0], self._frames[-1][0]) if self._frames else None

    def since(self, t_s: float) -> list[tuple[float, Mapping[str, Any]]]:
        """The kept ``(t_s, motion)`` frames later than ``t_s`` (s), oldest first (a copy: the frame loop goes on)."""
        return [frame for frame in self._frames if frame[0] > t_s]

    def at(self, t_s: float) -> Mapping[str, Any]:
        """The last recorded motion at or before ``t_s``; ValueError outside the kept span."""
        span = self.span_s()
        if span is None or not span[0] - 1e-9 <= t_s <= span[1] + 1e-9:
            kept = "nothing yet" if span is None else f"{span[0]:.2f} s to {span[1]:.2f} s"
            raise ValueError(f"seek_s: {t_s:g} s is outside the motion kept for scrubbing ({kept})")
        times = [t for t, _ in self._frames]
        return self._frames[max(0, bisect.bisect_right(times, t_s + 1e-9) - 1)][1]

    def latest(self, count: int) -> list[tuple[float, Mapping[str, Any]]]:
        """The last ``count`` kept frames ``(t_s, motion)``, oldest first (fewer if fewer are kept)."""
        return list(self._frames)[-count:] if count > 0 else []

    def forget_after(self, t_s: float) -> None:
        """Drop the frames later than ``t_s`` (play resumes from a scrubbed instant: what followed is not this run)."""
        while self._frames and self._frames[-1][0] > t_s + 1e-9:
            self._frames.pop()

    def clear(self) -> None:
        self._frames.clear()
