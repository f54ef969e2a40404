"""The ready questions in lessons/polls.toml: they load, and every answer is really computed by its scene.

Each question's scene is built headless on a real loopback viser client (the
scene tests' viewer), set up as the question says (defaults, preset, params),
run for one second of demo, and its readout revealed through the question's own
poll. Questions that state their numbers in words are also held to an
independent closed form, so a preset that drifts from its question fails here.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import pytest

from app.classroom.polls import Poll
from app.classroom.ready_questions import DEFAULT_READY_QUESTIONS, ReadyQuestion, load_ready_questions
from app.scenes import SCENES, Scene
from app.scenes.kit import FRAME_DT_S
from tests.scenes.conftest import HeadlessClient, headless_viewer

QUESTIONS = load_ready_questions(DEFAULT_READY_QUESTIONS, SCENES)
BY_ID = {q.id: q for q in QUESTIONS}
#: One second of demo before the reveal, as in class (the instructor runs it, then reveals).
DEMO_FRAMES = 30
G = 9.81
#: Closed forms for questions whose text states the set-up. Tolerance 1e-6 relative: each scene computes these
#: from closed forms or event-located integration at rtol 1e-8 (the ladder's separation angle agrees to 1e-10),
#: while a wrong preset or quantity is off by percent or more.
CLOSED_FORMS = {
    "helix-curvature": 1.0 / (1.0 + 0.2**2),  # κ = R / (R² + c²), R = 1 m, c = 0.2 m
    "helix-tangential-acceleration": 0.0,  # steady speed
    "helix-torsion": 0.2 / (1.0 + 0.2**2),  # τ = c / (R² + c²)
    "cardan-largest-speed-ratio": 1.0 / math.cos(math.radians(30.0)),
    "slider-crank-stroke": 2 * 0.3,  # twice the crank, whatever the rod
    "sphere-moment-of-inertia": 0.4 * 10.0 * 0.2**2,  # (2/5) m r²
    "principal-shaft-bearing-moment": 0.0,
    "ladder-leaves-wall": math.degrees(math.asin(2.0 / 3.0 * math.sin(math.radians(60.0)))),
    "head-on-elastic-speed": (2 * 2.0 * 3.0 + (1.0 - 2.0) * -1.0) / (2.0 + 1.0),  # (2 m₁ v₁ + (m₂ − m₁) v₂)/(m₁ + m₂)
    "hoop-critical-spin": math.sqrt(G / 0.5),
    "spherical-pendulum-cone-rate": math.sqrt(G / (1.0 * math.cos(math.radians(60.0)))),
    "cantilever-first-frequency": 1.875104068711961**2 * math.sqrt(50.0 / (1.0 * 1.0**4)),  # β₁² √(EI/(m L⁴))
    "four-bar-constraint-count": 8.0,  # 4 pins × 2 equations
    "foucault-paris-turn": 360.0 / (math.degrees(7.292115e-5) * 3600.0 * math.sin(math.radians(48.85))),
}


@pytest.fixture(scope="module")
def viewer() -> Iterator:
    with headless_viewer() as connected:
        yield connected


def test_the_shipped_questions_cover_every_chapter_whose_scenes_have_readouts():
    assert 20 <= len(QUESTIONS) <= 30
    per_chapter = Counter(q.chapter for q in QUESTIONS)
    answerable = {cls.chapter for cls in SCENES.values() if cls.readout is not Scene.readout}
    assert set(per_chapter) == answerable
    assert all(2 <= n <= 3 for n in per_chapter.values()), per_chapter
    assert set(CLOSED_FORMS) <= set(BY_ID)


@pytest.mark.parametrize("question_id", sorted(BY_ID))
def test_every_answer_is_computed_by_its_scene(viewer, question_id):
    question = BY_ID[question_id]
    cls = SCENES[question.scene_id]
    client = HeadlessClient(viewer[1])
    scene = cls(client, question.scene_params(cls))
    try:
        for _ in range(DEMO_FRAMES):
            with client.atomic():
                scene.advance(FRAME_DT_S)
        assert scene.status == "", scene.status
        readout = scene.readout()
        assert readout is not None
        revealed = Poll.create(question.poll_body(), poll_id="p1").reveal(readout.as_dict())
    finally:
        scene.close()
    assert revealed["source"].startswith("computed by the scene: ")
    if question.kind == "number":
        assert math.isfinite(revealed["value"])
        assert revealed["unit"] == question.unit
        if question_id in CLOSED_FORMS:
            assert math.isclose(revealed["value"], CLOSED_FORMS[question_id], rel_tol=1e-6, abs_tol=1e-12), revealed
    else:
        assert 0 <= revealed["choice"] < len(question.choices)
        assert revealed["text"] == question.choices[revealed["choice"]]


def test_ready_question_schema_and_poll_body():
    question = BY_ID["heavy-top-locus"]
    assert question.schema() == {
        "id": "heavy-top-locus", "chapter": 10, "scene_id": "heavy-top", "question": question.question, "kind": "choice",
        "choices": ["a circle", "waves", "loops", "cusps"], "unit": "", "preset": None,
        "params": {"theta0_deg": 30.0, "precession_rate0_rad_s": 0.0, "nutation_rate0_rad_s": 0.0},
        "answer_quantity": "locus",
    }  # fmt: skip
    assert question.poll_body() == {
        "question": question.question, "kind": "choice", "choices": ["a circle", "waves", "loops", "cusps"],
        "answer_quantity": "locus", "answer_choices": {"circle": 0, "waves": 1, "loops": 2, "cusps": 3},
    }  # fmt: skip
    number = BY_ID["heavy-top-sleeping-threshold"]
    assert number.poll_body() == {"question": number.question, "kind": "number", "unit": "rad/s", "answer_quantity": "critical_spin_rad_s"}
    assert isinstance(number, ReadyQuestion) and number.preset is None and number.params == {}


# ---- the loader's errors ---------------------------------------------------------------------------
GOOD = """
[[question]]
id = "sleeping"
chapter = 10
scene = "heavy-top"
question = "Below what spin does it stop sleeping?"
kind = "number"
unit = "rad/s"
answer_quantity = "critical_spin_rad_s"
"""


def load(tmp_path: Path, text: str) -> tuple[ReadyQuestion, ...]:
    path = tmp_path / "polls.toml"
    path.write_text(text, encoding="utf-8")
    return load_ready_questions(path, SCENES)


def test_a_good_file_loads(tmp_path):
    (question,) = load(tmp_path, GOOD)
    assert (question.id, question.scene_id, question.unit) == ("sleeping", "heavy-top", "rad/s")


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (('scene = "heavy-top"', 'scene = "no-such-scene"'), "unknown scene 'no-such-scene'"),
        (("chapter = 10", "chapter = 9"), "chapter 9 is not the chapter of scene 'heavy-top' (10)"),
        (('kind = "number"', 'kind = "number"\npreset = "no-such-preset"'), "has no preset 'no-such-preset'"),
        (('kind = "number"', 'kind = "number"\nparams = { spin_rad_s = "fast" }'), "refuses its params: spin_rad_s"),
        (('kind = "number"', 'kind = "number"\nparams = { spin_typo = 3.0 }'), "refuses its params: spin_typo"),
        (('kind = "number"', 'kind = "number"\ncolour = "red"'), "unknown key 'colour'"),
        (('unit = "rad/s"\n', ""), "states its unit"),
        (('answer_quantity = "critical_spin_rad_s"', ""), "missing answer_quantity"),
        (('kind = "number"', 'kind = "number"\nchoices = ["a", "b"]'), "a number poll has no choices"),
    ],
)
def test_a_bad_question_stops_the_load_naming_its_id(tmp_path, change, words):
    old, new = change
    with pytest.raises(ValueError) as caught:
        load(tmp_path, GOOD.replace(old, new))
    assert "question 'sleeping'" in str(caught.value)
    assert words in str(caught.value)


def test_a_scene_without_a_readout_cannot_answer(tmp_path):
    # Every shipped scene has a readout, so the heavy top stands in with its readout taken away.
    class SilentTop(SCENES["heavy-top"]):
        readout = Scene.readout

    path = tmp_path / "polls.toml"
    path.write_text(GOOD, encoding="utf-8")
    with pytest.raises(ValueError, match="'heavy-top' has no readout"):
        load_ready_questions(path, {**SCENES, "heavy-top": SilentTop})


def test_a_choice_mapped_out_of_range_stops_the_load(tmp_path):
    text = GOOD.replace(
        'kind = "number"\nunit = "rad/s"\nanswer_quantity = "critical_spin_rad_s"',
        'kind = "choice"\nchoices = ["waves", "loops"]\nanswer_quantity = "locus"\nanswer_choices = { "loops" = 2 }',
    )
    with pytest.raises(ValueError, match=r"question 'sleeping': answer_choices\.loops"):
        load(tmp_path, text)


def test_a_repeated_id_stops_the_load(tmp_path):
    with pytest.raises(ValueError, match="question 'sleeping': the id is used twice"):
        load(tmp_path, GOOD + GOOD)


def test_a_malformed_file_names_itself(tmp_path):
    with pytest.raises(ValueError, match="polls.toml: cannot read"):
        load(tmp_path, "[[question]\n")
    with pytest.raises(ValueError, match="id must be lower-case words"):
        load(tmp_path, GOOD.replace('id = "sleeping"', 'id = "Sleeping Top"'))
