"""The checked course catalogue (app/course/catalogue.py): every bad reference stops the load, naming the file."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from app.course import CatalogueError, load_catalogue
from app.main import create_app
from app.physics.systems import worked_examples
from app.scenes import SCENES
from app.settings import Settings

OUTLINE = """
[[chapter]]
number = 1
title = "Basic Considerations"
summary = "One."
sections = [{ number = "1.1", title = "Vector operations" }, { number = "1.2", title = "Newtonian mechanics" }]

[[chapter]]
number = 10
title = "Gyroscopic Effects"
summary = "Ten."
sections = [{ number = "10.2", title = "Spinning top" }]
"""


def lesson_text(*, id: str = "1-1-good", chapter: int = 1, section: str = "1.1", order: int = 1, refs: str = "") -> str:
    return (
        f'+++\nid = "{id}"\nchapter = {chapter}\nsection = "{section}"\norder = {order}\n'
        f'title = "A lesson"\nsummary = "What it is about."\n{refs}\n+++\nSome text with $a_b$.\n'
    )


def write_course(root: Path, lessons: dict[str, str]) -> Path:
    """A lessons directory under ``root``: the two-chapter outline and ``lessons`` (relative path -> text)."""
    (root / "course.toml").write_text(OUTLINE, encoding="utf-8")
    for relative, text in lessons.items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root


def test_a_consistent_course_loads_with_several_scenes_and_examples(tmp_path):
    refs = 'scenes = ["robot-arm-cable", "radar-tracking"]\nexamples = ["1.1", "1.2"]'
    catalogue = load_catalogue(write_course(tmp_path, {"ch01/good.md": lesson_text(refs=refs)}))
    lesson = catalogue.lessons["1-1-good"]
    assert lesson.scenes == ("robot-arm-cable", "radar-tracking")
    assert lesson.scene == "robot-arm-cable"  # the page and /api/chapters show the first
    assert lesson.examples == ("1.1", "1.2")
    assert [ch.number for ch in catalogue.chapters] == [1, 10]
    assert catalogue.chapters[0].lessons == (lesson,)


def test_the_one_scene_shorthand_is_accepted_and_mixing_both_forms_is_refused(tmp_path):
    catalogue = load_catalogue(write_course(tmp_path, {"ch01/short.md": lesson_text(refs='scene = "projectile-drag"')}))
    assert catalogue.lessons["1-1-good"].scenes == ("projectile-drag",)
    both = 'scene = "projectile-drag"\nscenes = ["projectile-drag"]'
    write_course(tmp_path, {"ch01/short.md": lesson_text(refs=both)})
    with pytest.raises(ValueError, match=r"short\.md: front matter has both 'scene' and 'scenes'"):
        load_catalogue(tmp_path)


@pytest.mark.parametrize(
    ("front_matter", "bad_reference"),
    [
        ({"refs": 'scenes = ["robot-arm-cable", "no-such-scene"]'}, "unknown scene 'no-such-scene'"),
        ({"refs": 'examples = ["1.1", "9.99"]'}, "unknown worked example '9.99'"),
        ({"refs": 'derivations = ["lagrange-pendulum"]'}, "unknown derivation 'lagrange-pendulum'"),
        ({"refs": 'scenes = ["four-bar", "four-bar"]'}, "scene listed more than once: four-bar"),
        ({"chapter": 5, "section": "5.1"}, "chapter 5 is not in course.toml"),
        ({"section": "1.7"}, "section '1.7' is not a section of chapter 1"),
        ({"refs": 'scenes = "heavy-top"'}, "'scenes' must be a list of ids"),
    ],
    ids=["scene", "example", "derivation", "repeated", "chapter", "section", "not-a-list"],
)
def test_a_bad_reference_raises_naming_the_file_and_the_reference(tmp_path, front_matter, bad_reference):
    root = write_course(tmp_path, {"ch01/good.md": lesson_text(order=1), "ch01/broken.md": lesson_text(id="1-1-broken", order=2, **front_matter)})
    with pytest.raises(ValueError) as info:
        load_catalogue(root)
    message = str(info.value)
    assert str(root / "ch01" / "broken.md") in message
    assert bad_reference in message
    assert "good.md" not in message  # only the broken file is blamed


def test_a_duplicated_lesson_id_names_both_files(tmp_path):
    root = write_course(tmp_path, {"ch01/first.md": lesson_text(), "ch01/second.md": lesson_text(order=2)})
    with pytest.raises(CatalogueError, match=r"second\.md: lesson id '1-1-good' is already used by .*first\.md"):
        load_catalogue(root)


def test_every_problem_is_reported_at_once(tmp_path):
    refs = 'scenes = ["nope-a"]\nexamples = ["nope-b"]'
    root = write_course(tmp_path, {"ch01/broken.md": lesson_text(section="1.9", refs=refs)})
    with pytest.raises(CatalogueError) as info:
        load_catalogue(root)
    assert all(part in str(info.value) for part in ("'1.9'", "'nope-a'", "'nope-b'"))


def test_derivation_references_are_checked_against_the_registry_given(tmp_path):
    root = write_course(tmp_path, {"ch01/good.md": lesson_text(refs='derivations = ["lagrange-pendulum"]')})
    catalogue = load_catalogue(root, derivations={"lagrange-pendulum": object()})
    assert catalogue.lessons["1-1-good"].derivations == ("lagrange-pendulum",)


def test_the_server_does_not_start_with_a_bad_reference(tmp_path):
    root = write_course(tmp_path, {"ch10/top.md": lesson_text(id="10-2-top", chapter=10, section="10.2", refs='scenes = ["heavy-tops"]')})
    with pytest.raises(CatalogueError, match=r"top\.md: unknown scene 'heavy-tops'"):
        create_app(Settings(lessons_dir=root))


def test_the_lesson_page_shows_every_referenced_example(tmp_path):
    refs = 'scenes = ["radar-tracking"]\nexamples = ["1.1", "1.2", "particle-work-energy"]'
    root = write_course(tmp_path, {"ch01/good.md": lesson_text(refs=refs)})
    client = TestClient(create_app(Settings(lessons_dir=root)))  # no lifespan: the lesson page needs no scene host
    page = client.get("/lessons/1-1-good")
    assert page.status_code == 200
    config = json.loads(re.search(r'<script type="application/json" id="dynlab-config">(.*?)</script>', page.text, re.S).group(1))
    assert [example["id"] for example in config["examples"]] == ["1.1", "1.2", "particle-work-energy"]
    assert config["scene"]["id"] == "radar-tracking"


def test_the_real_course_references_every_scene_and_example():
    catalogue = load_catalogue()
    referenced_scenes = {scene_id for lesson in catalogue.lessons.values() for scene_id in lesson.scenes}
    referenced_examples = {example_id for lesson in catalogue.lessons.values() for example_id in lesson.examples}
    assert set(SCENES) - referenced_scenes == set(), "a scene no lesson shows"
    assert set(worked_examples()) - referenced_examples == set(), "a worked example no lesson shows"
