"""The sliding bar's scene at its stops: a landing is held and explained in the model's words, never reported as a
numerical failure, whatever the host's frame length; while held, the phase says why the motion stopped."""

from __future__ import annotations

import pytest

from app.physics.systems.ch08 import sliding_bar as physics
from app.scenes import SCENES
from app.scenes.kit.background_pilots import PILOTS

SCENE = SCENES["sliding-bar-friction"]
PRESETS = {preset.name: preset.values for preset in SCENE.presets}


def built(client, values):
    scene = SCENE(client, SCENE.parameters.validate(values))
    assert PILOTS.wait_idle(60.0), "the step-choice pilot did not finish"
    return scene


def play(scene, *, frames: int, dt_s: float) -> list[str]:
    """Advance ``frames`` host frames of ``dt_s`` s as the host does (it stops advancing a scene with a status);
    returns every status seen."""
    seen = []
    for _ in range(frames):
        if scene.status:
            seen.append(scene.status)
            break
        scene.advance(dt_s)
    return seen


@pytest.mark.parametrize("host_frame_s", [1 / 30, 1 / 60, 1 / 120])
@pytest.mark.parametrize("preset", ["slide-and-fall", "stick-then-slip", "painleve-reversed"])
def test_a_landing_is_held_in_the_models_words_at_any_host_frame(client, preset, host_frame_s):
    # Before: with a host frame shorter than the scene's physics frame (1/30 s) the live run reached the landing
    # first and the scene stopped with "a terminal event was reached … Loosen the tolerance" (stick-then-slip).
    scene = built(client, PRESETS[preset])
    landing = scene.stop
    assert landing is not None and landing.index == physics.LANDS
    assert play(scene, frames=round(1.5 / host_frame_s), dt_s=host_frame_s) == []
    assert scene._held_s > 0.0
    readout = scene.readout()
    assert readout.message.startswith("The bar lands flat at t = ")
    values = {quantity.name: quantity for quantity in readout.quantities}
    assert values["t_s"].value == pytest.approx(landing.t_s, abs=1e-9)
    assert values["phase"].text == "landed flat: the run stopped"


def test_a_live_run_that_reaches_its_event_first_is_held_there(client):
    # The look-ahead's stop forgotten: the live run's own located landing holds the bar, with the model's message.
    scene = built(client, PRESETS["stick-then-slip"])
    expected = scene.stop
    scene.stop = None
    assert play(scene, frames=90, dt_s=1 / 30) == []
    assert scene.stop is not None and scene.stop.index == physics.LANDS
    assert scene.stop.t_s == pytest.approx(expected.t_s, abs=1e-9)
    assert "lands flat" in scene.readout().message
    assert scene._held_s > 0.0


def test_the_phase_says_sliding_while_it_slides(client):
    scene = built(client, PRESETS["slide-and-fall"])
    play(scene, frames=3, dt_s=1 / 30)
    phase = next(q for q in scene.readout().quantities if q.name == "phase")
    assert phase.text == "sliding"
