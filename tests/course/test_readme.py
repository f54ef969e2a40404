"""README.md's "What is here" table is generated from the catalogue and kept in step with it."""

from __future__ import annotations

from app.course import load_catalogue
from app.course.readme import README, REGENERATE, committed_table, readme_table, with_table
from app.physics.systems import worked_examples
from app.scenes import SCENES

TABLE = readme_table(load_catalogue())


def test_readme_table_matches_the_catalogue():
    committed = committed_table(README.read_text(encoding="utf-8"))
    assert committed == TABLE, f"README.md's 'What is here' table is out of date with the lessons and registries; run `{REGENERATE}`"


def test_table_has_a_row_per_chapter_and_names_every_scene_and_example():
    catalogue = load_catalogue()
    rows = TABLE.splitlines()[2:]
    assert [row.split(" | ")[0].removeprefix("| ") for row in rows] == [f"{ch.number} {ch.title}" for ch in catalogue.chapters]
    for scene_id in SCENES:
        assert f"`{scene_id}`" in TABLE, scene_id
    for example_id in worked_examples():
        assert f"`{example_id}`" in TABLE, example_id
    for lesson in catalogue.lessons.values():
        assert f"{lesson.section} {lesson.title}" in TABLE, lesson.id


def test_regenerating_replaces_only_the_table():
    text = README.read_text(encoding="utf-8")
    stale = with_table(text, "| stale |")
    assert committed_table(stale) == "| stale |"
    assert with_table(stale, TABLE) == with_table(text, TABLE)
    assert stale.split("| stale |")[0] == text.split(TABLE)[0]
