"""A base for the chapter-4 scenes whose motion is a closed form replayed in a fixed cycle (sections 4.1 and 4.2).

The clock ``t_s`` (simulated s) runs round ``cycle_s`` and starts again; each frame redraws the instant with its
arrows moved at 30 Hz and their labels at 15 Hz (half the label messages per student). Subclasses implement
``_draw(move_labels=...)``; the kit's ``redraw`` and time controls (resume, go to) use it with every label moved.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar

from app.scenes.kit import Scene

#: Frames between moves of the arrow labels (2: at 15 Hz).
LABEL_MOVE_EVERY_FRAMES = 2


class CyclingScene(Scene):
    """A closed-form motion replayed from t = 0 every :attr:`cycle_s` seconds."""

    animated = True
    #: Length of one replay of the motion (s).
    cycle_s: ClassVar[float]

    @abstractmethod
    def _draw(self, *, move_labels: bool = True) -> None:
        """Draw the motion at ``self.t_s``; ``move_labels=False`` leaves the arrow labels where they are this frame."""

    def step_motion(self, dt_s: float) -> bool:
        """The clock runs round one cycle of the motion and starts again."""
        self.t_s = (self.t_s + dt_s) % self.cycle_s
        return True

    def advance(self, dt_s: float) -> None:
        """One frame: the arrows move every frame, their labels every other one."""
        if self.step_motion(dt_s):
            self._frame = getattr(self, "_frame", 0) + 1
            self._draw(move_labels=self._frame % LABEL_MOVE_EVERY_FRAMES == 0)
