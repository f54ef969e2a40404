"""Issue 27, point 1: a worked example in every section (but 1.3, the biographical one), each in one structure — the
situation, what is wanted, why this approach, the steps with their numbers computed from inputs the student may
change, a check, and "what if" — on a lesson page of its section.

Each example's own numbers are checked against an independent computation in the tests of its system
(tests/physics/systems/chNN/); here: the structure, its place in the course, and that the steps include the check."""

from __future__ import annotations

import pytest

from app.course import load_catalogue
from app.physics.systems import worked_examples

COURSE = load_catalogue()
EXAMPLES = worked_examples()
#: Sections without a worked example on purpose: 1.3 is the biographical section (no problem to work).
WITHOUT_EXAMPLE = {"1.3"}
SECTIONS = [s.number for chapter in COURSE.chapters for s in chapter.sections if s.number not in WITHOUT_EXAMPLE]
STORIED = {example_id: e for example_id, e in EXAMPLES.items() if e.story is not None}
#: Fewest words each part of a story has: enough for a reason, not a heading.
MIN_WORDS = 15


def _listed_in(section: str) -> set[str]:
    """The ids of the examples that lesson pages of ``section`` show."""
    return {e for lesson in COURSE.lessons.values() if lesson.section == section for e in lesson.examples}


@pytest.mark.parametrize("section", SECTIONS)
def test_every_section_has_a_worked_example_with_its_story(section):
    shown = [STORIED[e] for e in _listed_in(section) if e in STORIED and STORIED[e].section == section]
    assert shown, f"section {section}: no lesson of it shows a worked example with its story and section"


@pytest.mark.parametrize("example_id", sorted(STORIED))
def test_a_story_is_whole_placed_in_its_section_and_its_steps_end_in_a_check(example_id):
    example = STORIED[example_id]
    assert example.story is not None
    for part, text in example.story.as_dict().items():
        assert len(text.split()) >= MIN_WORDS, f"{example_id}: its {part} has {len(text.split())} words"
    assert example.id in _listed_in(example.section), f"{example_id}: no lesson of section {example.section} shows it"
    chapter = int(example.section.split(".")[0])
    assert example.chapter == chapter, (example.chapter, example.section)
    solution = example.solve(example.inputs.defaults())
    checks = [step for step in solution.steps if step.title.startswith("Check")]
    assert checks, f"{example_id}: no step titled 'Check…' (the conservation law, limit or second method it states)"
    assert len(solution.steps) >= 3, f"{example_id}: a worked example has its steps, not one formula"
