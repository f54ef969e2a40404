"""The scene abstraction every chapter reuses.

A :class:`Scene` is one browser's view of one model: it builds its viser nodes on
that client's own ``client.scene`` (so one student's controls never move
another's scene), redraws when its parameters change, advances its animation a
frame at a time, and removes what it built when the client leaves. Scenes draw;
the numbers they draw come from ``app.physics``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import viser
from viser._viser import InitialCameraConfig

from app.physics.core.parameters import ParameterSet
from app.physics.solvers.integrated_model import IntegratedModel


@dataclass(frozen=True)
class Preset:
    """A named set of parameter values the lesson page offers as one button.

    ``values`` must validate against the scene's parameters (a test checks every
    preset); controls not named keep their current values.
    """

    name: str
    label: str
    values: Mapping[str, Any]
    description: str = ""

    def schema(self) -> dict[str, Any]:
        return {"name": self.name, "label": self.label, "values": dict(self.values), "description": self.description}


class Scene(ABC):
    """One client's instance of a scene.

    Subclasses set the class attributes and implement :meth:`build` and
    :meth:`update`; animated scenes also implement :meth:`advance`.
    """

    id: ClassVar[str]
    title: ClassVar[str]
    chapter: ClassVar[int]
    parameters: ClassVar[ParameterSet]
    animated: ClassVar[bool] = False
    #: Buttons on the lesson page that set several controls at once.
    presets: ClassVar[tuple[Preset, ...]] = ()
    #: Initial camera (m, world frame, +Z up).
    camera_position: ClassVar[tuple[float, float, float]] = (4.0, -6.0, 4.0)
    camera_look_at: ClassVar[tuple[float, float, float]] = (0.0, 0.0, 0.0)

    def __init__(self, client: viser.ClientHandle, params: Mapping[str, Any]) -> None:
        self.client = client
        self.params = dict(params)
        #: A message the page may show (e.g. why the last parameters were refused).
        self.status = ""
        client.gui.main_panel.minimize()  # the lesson page carries the controls
        # viser 1.1.1 (pinned) sets an initial camera only server-wide; the same
        # message addressed to one client makes it this viewer's start pose and
        # its "Reset View" target without fighting the student's own camera.
        self._initial_camera = InitialCameraConfig(client._websock_connection.queue_message)
        self.build()
        self.update()
        self._set_initial_camera()

    @classmethod
    def schema(cls) -> dict[str, Any]:
        return {
            "id": cls.id,
            "title": cls.title,
            "chapter": cls.chapter,
            "animated": cls.animated,
            # Integrated scenes publish live invariants at /api/scenes/{id}/sessions/{sid}/live.
            "integrated": issubclass(getattr(cls, "model", type(None)), IntegratedModel),
            # Scenes with live numbers (readouts, marks on controls) for the lesson page.
            "readout": cls.readout is not Scene.readout,
            "parameters": cls.parameters.schema(),
            "presets": [preset.schema() for preset in cls.presets],
        }

    @abstractmethod
    def build(self) -> None:
        """Create this scene's nodes on ``self.client.scene``."""

    @abstractmethod
    def update(self) -> None:
        """Redraw for ``self.params`` (called after build and on every change)."""

    def set_params(self, params: Mapping[str, Any]) -> None:
        """Take already-validated parameters and redraw."""
        self.params = dict(params)
        with self.client.atomic():
            self.update()
            self._set_initial_camera()

    def camera_view(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """Initial camera (position, look-at point) in m on the world frame (+Z up)."""
        return self.camera_position, self.camera_look_at

    def _set_initial_camera(self) -> None:
        position, look_at = self.camera_view()
        self._initial_camera.look_at = look_at
        self._initial_camera.position = position

    def advance(self, dt_s: float) -> None:
        """Advance the animation by ``dt_s`` seconds of wall-clock time."""

    def readout(self) -> dict[str, Any] | None:
        """Numbers a student reads beside the scene, polled by the lesson page.

        ``{"quantities": [{"name", "label", "value", "unit"}, ...],
        "marks": {parameter_name: [{"value", "label"}, ...]}, "message": str}``:
        ``name`` is a stable id (tests and pages find values by it), ``value`` a
        finite number or a short string, ``marks`` put a labelled tick on a
        control's slider (e.g. the sleeping-top threshold on the spin control).
        """
        return None

    def close(self) -> None:
        """Remove everything this scene added (the client may still be connected)."""
        self.client.scene.reset()
