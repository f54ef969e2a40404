"""A base for chapter-3 scenes whose motion is a closed form in time, replayed from t = 0.

The scene's clock ``t_s`` (s of simulated time) advances by ``playback_speed × dt`` each frame and
wraps at ``replay_s``; a playback speed of 0 holds the instant ``time_s``. The time controls are the
moving-frame scene's (one definition). Subclasses draw the instant ``self.t_s`` in ``_draw`` (the kit's
:meth:`~app.scenes.kit.Scene.redraw`).
"""

from __future__ import annotations

from abc import abstractmethod

from app.scenes.ch03.moving_frame import DISPLAY_PARAMETERS
from app.scenes.kit import Scene

__all__ = ["DISPLAY_PARAMETERS", "ReplayedScene"]


class ReplayedScene(Scene):
    """Keeps ``t_s`` for a closed-form motion; the motion a room hands on is just that time."""

    animated = True

    def start_clock(self) -> None:
        """Put the clock at the instant ``time_s`` (within the replay)."""
        self.t_s = float(self.params["time_s"]) % float(self.params["replay_s"])

    @abstractmethod
    def _draw(self) -> None:
        """Draw the motion at ``self.t_s``."""

    def step_motion(self, dt_s: float) -> bool:
        """``playback_speed × dt_s`` of motion, wrapping at ``replay_s``; a speed of 0 holds the instant (False)."""
        speed = float(self.params["playback_speed"])
        if speed == 0.0:
            return False
        self.t_s = (self.t_s + speed * dt_s) % float(self.params["replay_s"])
        return True

    def step_without_drawing(self, t_s: float) -> None:
        """A closed form: the instant ``t_s`` of the replay (s; the replay repeats every ``replay_s``)."""
        self.t_s = t_s % float(self.params["replay_s"])
