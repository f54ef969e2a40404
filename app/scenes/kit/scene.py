"""The scene abstraction every chapter reuses.

A :class:`Scene` is one browser's view of one model: it builds its viser nodes on
that client's own ``client.scene`` (so one student's controls never move
another's scene), redraws when its parameters change, advances its animation a
frame at a time, and removes what it built when the client leaves. Scenes draw;
the numbers they draw come from ``app.physics``.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any, ClassVar, Literal

import viser

from app.physics.core.model import Model
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.readout import Readout
from app.physics.core.solution import WorkedExample
from app.scenes.kit.trail import Trail
from app.scenes.viser_boundary import set_initial_camera

#: Simulated seconds per displayed frame (the host draws at 30 Hz).
FRAME_DT_S = 1.0 / 30.0
#: Latest simulated time :meth:`Scene.go_to` computes (s): a share link's bound.
GO_TO_MAX_S = 600.0
#: Where a label's text sits against its point (viser's ``add_label`` anchors: the text's corner or edge there).
LabelAnchor = Literal[
    "top-left",
    "top-center",
    "top-right",
    "center-left",
    "center-center",
    "center-right",
    "bottom-left",
    "bottom-center",
    "bottom-right",
]


def checked_go_to_time(t_s: Any) -> float:
    """``t_s`` as a float in [0, :data:`GO_TO_MAX_S`] s; ValueError naming ``t_s`` otherwise."""
    if (
        isinstance(t_s, bool)
        or not isinstance(t_s, int | float)
        or not math.isfinite(t_s)
        or not 0.0 <= t_s <= GO_TO_MAX_S
    ):
        raise ValueError(f"t_s: a simulated time from 0 to {GO_TO_MAX_S:g} s, got {t_s!r}")
    return float(t_s)


def motion_numbers(motion: Any, keys: tuple[str, ...]) -> dict[str, float]:
    """The finite numbers ``motion[key]`` for each key (``t_s`` ≥ 0 s); ValueError starting "motion:" otherwise."""
    if not isinstance(motion, Mapping):
        raise ValueError(f"motion: must be a mapping with {', '.join(keys)}, got {type(motion).__name__}")
    out: dict[str, float] = {}
    for key in keys:
        value = motion.get(key)
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
            raise ValueError(f"motion: {key} must be a finite number, got {value!r}")
        out[key] = float(value)
    if out.get("t_s", 0.0) < 0.0:
        raise ValueError(f"motion: t_s must be a time ≥ 0 s, got {out['t_s']!r}")
    return out


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


def compose_parameters(
    *,
    model: type[Model] | None,
    example: WorkedExample | None,
    controls: tuple[Parameter, ...],
    slider_ranges: Mapping[str, tuple[float, float, float]],
    check_controls: Callable[[Mapping[str, Any]], object] | None,
) -> ParameterSet:
    """A scene's parameters: the model's (or the worked example's inputs), the scene's own controls,
    then the model's controls (an integrated model's integration controls; none for a closed form).

    ``slider_ranges`` narrows named parameters to ``(min, max, step)`` on a linear
    slider. The whole-set check is the model's (or example's), followed by
    ``check_controls`` when the scene has one.
    """
    if model is not None and example is not None:
        raise TypeError("a scene shows either a model or a worked example, not both")
    physical = model.parameters if model is not None else example.inputs if example is not None else ParameterSet(())
    integration = tuple(model.controls()) if model is not None else ()
    parameters = (*physical.parameters, *controls, *integration)
    unknown = set(slider_ranges) - {p.name for p in parameters}
    if unknown:
        raise ValueError(f"slider_ranges names no parameter: {', '.join(sorted(unknown))}")
    parameters = tuple(
        replace(
            p, min=slider_ranges[p.name][0], max=slider_ranges[p.name][1], step=slider_ranges[p.name][2], scale="linear"
        )
        if p.name in slider_ranges
        else p
        for p in parameters
    )
    model_check = physical.check
    if check_controls is None:
        check = model_check
    else:

        def check(values: Mapping[str, Any]) -> None:
            if model_check is not None:
                model_check(values)
            check_controls(values)

    return ParameterSet(parameters, check=check)


class Scene(ABC):
    """One client's instance of a scene.

    Subclasses set the class attributes and implement :meth:`build` and
    :meth:`update`; an animated scene draws its current motion in ``_draw`` (or
    :meth:`redraw`), moves it in :meth:`step_motion` where its clock is not a
    plain ``t_s += dt`` and names what makes the motion in :attr:`motion_attributes`
    (or overrides :meth:`motion_state`/:meth:`resume_from`). A scene
    declares what it shows — its ``model`` (a closed-form or integrated model
    class) or the worked ``example`` whose inputs it draws — and its own
    ``controls`` (display options, time scale, …); :attr:`parameters` is
    composed from them once, when the class is defined.
    """

    id: ClassVar[str]
    title: ClassVar[str]
    chapter: ClassVar[int]
    #: The model drawn (a :class:`~app.physics.core.model.Model` class: closed-form or integrated), or None.
    model: ClassVar[type[Model] | None] = None
    #: The worked example whose inputs the scene draws (instead of a model), or None.
    example: ClassVar[WorkedExample | None] = None
    #: Scene-only parameters (display options, time scale, …), after the model's.
    controls: ClassVar[tuple[Parameter, ...]] = ()
    #: Narrower slider ranges for the lesson page: name -> (min, max, step).
    slider_ranges: ClassVar[Mapping[str, tuple[float, float, float]]] = {}
    #: Composed by ``__init_subclass__``: model/example parameters, controls, integration controls.
    parameters: ClassVar[ParameterSet] = ParameterSet(())
    #: Raises ValueError for control values impossible with the rest (run after the model's check).
    check_controls: ClassVar[Callable[[Mapping[str, Any]], object] | None] = None
    animated: ClassVar[bool] = False
    #: Buttons on the lesson page that set several controls at once.
    presets: ClassVar[tuple[Preset, ...]] = ()
    #: Most viser messages one animated frame may send, on average (a test holds every scene to it).
    #: Each message costs the server 10–20 µs per viewer: a class of 100 at 30 frames/s multiplies it by 3000.
    frame_message_budget: ClassVar[float] = 8.0
    #: Initial camera (m, world frame, +Z up).
    camera_position: ClassVar[tuple[float, float, float]] = (4.0, -6.0, 4.0)
    camera_look_at: ClassVar[tuple[float, float, float]] = (0.0, 0.0, 0.0)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.parameters = compose_parameters(
            model=cls.model,
            example=cls.example,
            controls=tuple(cls.controls),
            slider_ranges=cls.slider_ranges,
            check_controls=cls.check_controls,
        )

    def __init__(self, client: viser.ClientHandle, params: Mapping[str, Any]) -> None:
        self.client = client
        self.params = dict(params)
        #: A message the page may show (e.g. why the last parameters were refused).
        self.status = ""
        client.gui.main_panel.minimize()  # the lesson page carries the controls
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
            "integrated": cls.model is not None and cls.model.integrated,
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
        set_initial_camera(self.client, position=position, look_at=look_at)

    # -- motion: where an animated scene is, going back there, redrawing it --------------------------------------
    #: An animated scene's motion as ``{key in motion_state(): instance attribute}``, every value a float, ``t_s``
    #: (simulated s) first. The default fits the common closed-form scene: a clock ``self.t_s`` and ``_draw()``.
    motion_attributes: ClassVar[Mapping[str, str]] = {"t_s": "t_s"}
    #: The clock of a scene that keeps one (simulated s): set by the scene, moved by :meth:`step_motion`.
    t_s: float

    def advance(self, dt_s: float) -> None:
        """Advance the animation by ``dt_s`` seconds of wall-clock time: :meth:`step_motion`, then :meth:`redraw`."""
        if self.animated and self.step_motion(dt_s):
            self.redraw()

    def step_motion(self, dt_s: float) -> bool:
        """Advance the motion ``dt_s`` s without drawing; False when it stopped (``status`` says why).

        The default moves the clock ``t_s``; a scene that loops or keeps more (a spin angle) overrides it, so
        that :meth:`advance` and :meth:`go_to` share one rule.
        """
        self.t_s += dt_s
        return True

    def redraw(self) -> None:
        """Draw the current motion without advancing it."""
        self._draw()

    def _draw(self) -> None:
        """Move the drawing to the current motion (an animated scene implements it or overrides :meth:`redraw`)."""
        raise NotImplementedError(f"{type(self).__name__} draws no motion")

    def restart_motion(self) -> None:
        """Back to the current parameters' start, drawn: every motion attribute at 0, then :meth:`update` (which
        may set another start, such as a chosen starting time)."""
        for attribute in self.motion_attributes.values():
            setattr(self, attribute, 0.0)
        self.update()

    def motion_state(self) -> dict[str, Any] | None:
        """The motion now, as JSON data (floats) another instance with the same parameters can :meth:`resume_from`
        and :meth:`redraw` exactly (a room's students exploring from the instructor's demo, the scrubber's history);
        always with ``t_s`` (simulated s). None for a scene that is not animated."""
        if not self.animated:
            return None
        return {key: float(getattr(self, attribute)) for key, attribute in self.motion_attributes.items()}

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        """Put this instance at ``motion`` (from :meth:`motion_state`, same parameters), without drawing; its trails
        start again, empty.

        Raises ``ValueError`` ("motion: …") for a motion this scene cannot take (a missing key, not finite, t_s < 0).
        """
        if not self.animated:
            raise ValueError(f"motion: {self.id} is not animated, so it has no motion to resume")
        values = motion_numbers(motion, tuple(self.motion_attributes))
        for key, attribute in self.motion_attributes.items():
            setattr(self, attribute, values[key])
        self.clear_trails()

    def drawn_trails(self) -> list[Trail]:
        """Every :class:`Trail` this scene keeps (as an attribute, or in a list, tuple or dict attribute)."""
        found: list[Trail] = []
        for value in vars(self).values():
            items = (
                value.values() if isinstance(value, dict) else value if isinstance(value, list | tuple) else (value,)
            )
            found.extend(item for item in items if isinstance(item, Trail))
        return found

    def clear_trails(self) -> None:
        """Empty every trail: a trail is history, not the instant, so after :meth:`resume_from` it starts again."""
        for trail in self.drawn_trails():
            trail.clear()

    def go_to(self, t_s: float) -> None:
        """The motion at simulated time ``t_s`` (0–:data:`GO_TO_MAX_S` s, else ValueError) from the current
        parameters' start, drawn: restart, step the motion frame by frame without drawing, redraw. Deterministic:
        two instances with the same parameters draw the same instant."""
        t_s = checked_go_to_time(t_s)
        if not self.animated:
            raise ValueError(f"t_s: {self.id} is not animated, so it has no time to go to")
        with self.client.atomic():
            self.restart_motion()
            self.step_without_drawing(t_s)
            self.redraw()

    def step_without_drawing(self, t_s: float) -> None:
        """Step :meth:`step_motion` from the start to ``t_s``: whole frames of :data:`FRAME_DT_S` (as the host
        plays them, so loops and replays happen as on screen), then the part of a frame left."""
        frames = math.floor(t_s / FRAME_DT_S + 1e-9)
        for _ in range(frames):
            if not self.step_motion(FRAME_DT_S) or not self.pace():
                return
        rest = t_s - frames * FRAME_DT_S
        if rest > 1e-12:
            self.step_motion(rest)

    def motion_cost_s(self) -> float | None:
        """What stepping this scene's motion one frame without drawing costs (s), as measured; None where it is not
        measured (a closed form in time costs next to nothing)."""
        return None

    @staticmethod
    def pace() -> bool:
        """Called after each frame of a long computation (:meth:`step_without_drawing`); False stops it there. The
        host replaces it on an instance while it computes a request, to keep the request within its share
        (:class:`app.scenes.host.fair_share.Pace`)."""
        return True

    def readout(self) -> Readout | None:
        """Numbers a student reads beside the scene, polled by the lesson page (None: no readout).

        Quantities are found by ``name`` (time is always ``t_s``); marks put a
        labelled tick on a control's slider (e.g. the sleeping-top threshold on
        the spin control).
        """
        return None

    def close(self) -> None:
        """Remove everything this scene added (the client may still be connected)."""
        self.client.scene.reset()
