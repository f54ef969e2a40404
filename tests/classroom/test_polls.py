"""Polls: validation naming the field, one answer per student, histograms, the revealed answer, CSV, privacy."""

from __future__ import annotations

import csv
import io
import json
import math
from datetime import datetime

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.classroom.polls import MAX_ANSWER_MAGNITUDE, Poll, PollClosedError, PollError, nice_width, spreadsheet_text
from app.physics.core.readout import Quantity, Readout

CHOICE = {"question": "What does the tip of the axis trace?", "kind": "choice", "choices": ["a circle", "waves", "loops", "cusps"]}
NUMBER = {"question": "Below what spin does the top stop sleeping?", "kind": "number", "unit": "rad/s"}


def poll(base: dict, **extra) -> Poll:
    return Poll.create({**base, **extra}, poll_id="p1")


def numbers(*values: float, **extra) -> Poll:
    p = poll(NUMBER, **extra)
    for k, value in enumerate(values):
        p.submit(f"token-{k}", {"value": value})
    return p


def top_readout(*, critical: float | None = 15.658, locus: str = "loops") -> dict:
    """The JSON a heavy-top scene's readout gives (built by the real Readout, not by hand)."""
    return Readout(
        [
            Quantity("t_s", "time t", 1.0, "s"),
            Quantity.or_text("critical_spin_rad_s", "sleeping threshold |ω₃|", critical, "rad/s", "none: no gravity"),
            Quantity.word("locus", "axis locus", locus),
        ]
    ).as_dict()


# ---- creating a poll --------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("raw", "field"),
    [
        ({**NUMBER, "colour": "red"}, "colour"),
        ({"kind": "number", "unit": "m"}, "question"),
        ({**NUMBER, "question": "   "}, "question"),
        ({**NUMBER, "question": "x" * 301}, "question"),
        ({**NUMBER, "question": 42}, "question"),
        ({**NUMBER, "kind": "essay"}, "kind"),
        ({**CHOICE, "choices": ["only one"]}, "choices"),
        ({**CHOICE, "choices": [str(k) for k in range(9)]}, "choices"),
        ({**CHOICE, "choices": ["same", "same"]}, "choices"),
        ({**CHOICE, "choices": "a, b"}, "choices"),
        ({**CHOICE, "choices": ["fine", "y" * 81]}, "choices[1]"),
        ({**CHOICE, "choices": ["fine", ""]}, "choices[1]"),
        ({**CHOICE, "unit": "m"}, "unit"),
        ({**NUMBER, "choices": ["a", "b"]}, "choices"),
        ({**NUMBER, "unit": "u" * 21}, "unit"),
        ({**NUMBER, "answer_value": math.inf}, "answer_value"),
        ({**NUMBER, "answer_value": math.nan}, "answer_value"),
        ({**NUMBER, "answer_value": True}, "answer_value"),
        ({**NUMBER, "answer_value": "3"}, "answer_value"),
        ({**NUMBER, "answer_value": 2e12}, "answer_value"),
        ({**NUMBER, "answer_choice": 1}, "answer_choice"),
        ({**CHOICE, "answer_choice": 4}, "answer_choice"),
        ({**CHOICE, "answer_choice": True}, "answer_choice"),
        ({**CHOICE, "answer_value": 1.0}, "answer_value"),
        ({**CHOICE, "answer_quantity": "locus"}, "answer_choices"),
        ({**CHOICE, "answer_choices": {"loops": 2}}, "answer_choices"),
        ({**CHOICE, "answer_quantity": "locus", "answer_choices": {"loops": 7}}, "answer_choices.loops"),
        ({**CHOICE, "answer_quantity": "locus", "answer_choices": ["loops"]}, "answer_choices"),
        ({**CHOICE, "answer_quantity": "locus", "answer_choices": {"loops": 2}, "answer_choice": 2}, "answer_choice"),
        ({**NUMBER, "answer_quantity": "critical_spin_rad_s", "answer_value": 15.0}, "answer_value"),
        ({**NUMBER, "answer_quantity": "__import__('os')"}, "answer_quantity"),
        ({**NUMBER, "answer_quantity": ""}, "answer_quantity"),
        ({**NUMBER, "show_names": "yes"}, "show_names"),
    ],
)
def test_a_bad_poll_is_refused_naming_its_field(raw, field):
    with pytest.raises(PollError) as caught:
        Poll.create(raw, poll_id="p1")
    assert caught.value.field == field
    assert field.split("[")[0].split(".")[0] in str(caught.value)


def test_a_poll_that_is_not_an_object_is_refused():
    with pytest.raises(PollError) as caught:
        Poll.create(["question"], poll_id="p1")  # type: ignore[arg-type]
    assert caught.value.field == "body"


def test_a_good_poll_is_open_anonymous_and_trimmed():
    p = poll(CHOICE, question="  Which?  ")
    shown = (p.poll_id, p.question, p.kind, p.choices, p.unit, p.open, p.show_names)
    assert shown == ("p1", "Which?", "choice", tuple(CHOICE["choices"]), "", True, False)
    assert poll(NUMBER).unit == "rad/s"
    assert poll({"question": "How many?", "kind": "number"}).unit == ""  # a pure number


# ---- answers --------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("base", "answer", "field"),
    [
        (CHOICE, {"choice": 4}, "choice"),
        (CHOICE, {"choice": -1}, "choice"),
        (CHOICE, {"choice": True}, "choice"),
        (CHOICE, {"choice": 1.0}, "choice"),
        (CHOICE, {"value": 1.0}, "choice"),
        (CHOICE, {"choice": 1, "value": 2.0}, "choice"),
        (NUMBER, {"value": math.nan}, "value"),
        (NUMBER, {"value": -math.inf}, "value"),
        (NUMBER, {"value": 10 * MAX_ANSWER_MAGNITUDE}, "value"),
        (NUMBER, {"value": "15"}, "value"),
        (NUMBER, {"value": False}, "value"),
        (NUMBER, {}, "value"),
    ],
)
def test_a_bad_answer_is_refused_naming_its_field_and_not_counted(base, answer, field):
    p = poll(base)
    with pytest.raises(PollError) as caught:
        p.submit("token-a", answer)
    assert caught.value.field == field
    assert p.answer_count == 0


def test_one_answer_per_student_the_latest_counts():
    p = poll(CHOICE)
    p.submit("token-a", {"choice": 0})
    p.submit("token-b", {"choice": 2})
    p.submit("token-a", {"choice": 3})  # changed their mind
    assert p.answer_count == 2
    assert [b["count"] for b in p.results()["histogram"]] == [0, 0, 1, 1]


def test_a_closed_poll_refuses_answers_and_keeps_the_old_ones():
    p = poll(NUMBER)
    p.submit("token-a", {"value": 12.0})
    p.close()
    with pytest.raises(PollClosedError) as caught:
        p.submit("token-a", {"value": 20.0})
    assert isinstance(caught.value, PollError)  # the route answers 409 for it, 422 for other PollErrors
    with pytest.raises(PollClosedError):
        p.submit("token-new", {"value": 20.0})
    assert p.answer_count == 1
    assert p.results()["histogram"][0]["lo"] == 12.0
    p.reopen()
    p.submit("token-a", {"value": 20.0})
    assert p.answer_count == 1
    assert p.results()["histogram"][0]["lo"] == 20.0


# ---- histograms ----------------------------------------------------------------------------------
def test_choice_histogram_has_one_bin_per_choice_in_order():
    p = poll(CHOICE)
    for k, choice in enumerate([1, 1, 3, 1, 0]):
        p.submit(f"token-{k}", {"choice": choice})
    histogram = p.results()["histogram"]
    assert [(b["label"], b["lo"], b["hi"], b["count"]) for b in histogram] == [
        ("a circle", None, None, 1), ("waves", None, None, 3), ("loops", None, None, 0), ("cusps", None, None, 1),
    ]  # fmt: skip


def test_number_histogram_uses_nice_bins():
    histogram = numbers(0.31, 0.35, 0.42, 0.9, 1.05).results()["histogram"]
    assert [b["label"] for b in histogram] == [f"{k / 10:.1f} to {(k + 1) / 10:.1f}" for k in range(3, 11)]
    assert [b["count"] for b in histogram] == [2, 1, 0, 0, 0, 0, 1, 1]
    assert histogram[0]["lo"] == 0.3 and histogram[-1]["hi"] == 1.1


def test_nice_width_is_one_two_or_five_times_a_power_of_ten():
    assert [nice_width(span) for span in (8.0, 8.1, 15.0, 16.1, 39.0, 40.1, 0.0008)] == [1.0, 2.0, 2.0, 5.0, 5.0, 10.0, 0.0001]


def test_equal_answers_make_one_bin():
    histogram = numbers(15.0, 15.0, 15.0).results()["histogram"]
    assert histogram == [{"label": "15", "lo": 15.0, "hi": 15.0, "count": 3}]
    assert len(numbers(0.0, 5e-324).results()["histogram"]) == 1  # closer than any bin width a float can hold
    assert numbers().results()["histogram"] == []


def test_the_revealed_value_lies_inside_the_histogram_range():
    p = numbers(10.0, 11.0, 12.0, answer_value=31.0)
    p.reveal(None)
    histogram = p.results()["histogram"]
    assert histogram[0]["lo"] <= 10.0 and histogram[-1]["hi"] > 31.0
    assert sum(b["count"] for b in histogram) == 3  # the revealed value widens the range but is not an answer


@settings(max_examples=150, deadline=None)
@given(st.lists(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False), min_size=1, max_size=40))
def test_number_bins_are_contiguous_nice_about_eight_and_hold_every_answer(values):
    histogram = numbers(*values).results()["histogram"]
    assert sum(b["count"] for b in histogram) == len(values)
    low, high = min(values), max(values)
    if high - low <= max(1e-9 * max(abs(low), abs(high)), 1e-300):  # all equal, to 1e-9 or below a float's reach
        assert [(b["lo"], b["hi"]) for b in histogram] == [(low, high)]  # one bin, from the least to the greatest
        return
    assert 1 <= len(histogram) <= 10
    width = histogram[0]["hi"] - histogram[0]["lo"]
    mantissa = width / 10.0 ** math.floor(math.log10(width))
    assert min(abs(mantissa - nice) for nice in (1.0, 2.0, 5.0, 10.0)) < 1e-6
    for left, right in zip(histogram, histogram[1:]):
        assert math.isclose(left["hi"], right["lo"], rel_tol=1e-12, abs_tol=1e-12 * width)
    for value in values:  # each answer is counted in the bin that holds it (the edges are rounded to the width)
        assert histogram[0]["lo"] - 1e-9 * width <= value <= histogram[-1]["hi"] + 1e-9 * width


# ---- revealing the answer ---------------------------------------------------------------------------
def test_reveal_a_number_computed_by_the_scene():
    p = poll(NUMBER, answer_quantity="critical_spin_rad_s")
    p.submit("token-a", {"value": 10.0})
    revealed = p.reveal(top_readout(critical=3.0717))
    assert revealed == {
        "text": "3.07 rad/s", "value": 3.0717, "choice": None, "unit": "rad/s",
        "source": "computed by the scene: sleeping threshold |ω₃|",
    }  # fmt: skip
    assert not p.open
    assert p.public()["revealed"] == revealed == p.results()["revealed"]
    with pytest.raises(PollClosedError):
        p.submit("token-a", {"value": 3.0})


def test_reveal_a_word_computed_by_the_scene_as_a_choice():
    p = poll(CHOICE, answer_quantity="locus", answer_choices={"circle": 0, "waves": 1, "loops": 2, "cusps": 3})
    revealed = p.reveal(top_readout(locus="loops"))
    assert revealed == {"text": "loops", "value": None, "choice": 2, "unit": "", "source": "computed by the scene: axis locus"}


def test_reveal_the_instructors_own_answer():
    assert poll(NUMBER, answer_value=15.66).reveal(None) == {
        "text": "15.7 rad/s", "value": 15.66, "choice": None, "unit": "rad/s", "source": "given by the instructor",
    }  # fmt: skip
    assert poll(CHOICE, answer_choice=3).reveal(top_readout()) == {
        "text": "cusps", "value": None, "choice": 3, "unit": "", "source": "given by the instructor",
    }  # fmt: skip


@pytest.mark.parametrize(
    ("extra", "readout", "field", "words"),
    [
        ({"answer_quantity": "critical_spin_rad_s"}, None, "answer_quantity", "no readout"),
        ({"answer_quantity": "nutation_period_s"}, top_readout(), "answer_quantity", "has no 'nutation_period_s'"),
        ({"answer_quantity": "critical_spin_rad_s"}, top_readout(critical=None), "answer_quantity", "none: no gravity"),
        ({"answer_quantity": "locus"}, top_readout(), "answer_quantity", "no value now"),
        ({"answer_quantity": "t_s"}, top_readout(), "answer_quantity", "but the poll asks for rad/s"),
        ({}, top_readout(), "reveal", "no answer to show"),
    ],
)
def test_a_number_the_scene_cannot_give_is_an_error_and_changes_nothing(extra, readout, field, words):
    p = poll(NUMBER, **extra)
    p.submit("token-a", {"value": 10.0})
    with pytest.raises(PollError) as caught:
        p.reveal(readout)
    assert caught.value.field == field
    assert words in str(caught.value)
    assert p.open and p.revealed is None and p.answer_count == 1


def test_a_word_no_choice_maps_is_an_error_and_changes_nothing():
    p = poll(CHOICE, answer_quantity="locus", answer_choices={"waves": 1, "loops": 2})
    with pytest.raises(PollError) as caught:
        p.reveal(top_readout(locus="vertical"))
    assert caught.value.field == "answer_choices" and "'vertical'" in str(caught.value)
    with pytest.raises(PollError) as caught:
        poll(CHOICE, answer_quantity="t_s", answer_choices={"waves": 1}).reveal(top_readout())
    assert "is a number" in str(caught.value)
    assert p.open and p.revealed is None


def test_reopening_withdraws_the_revealed_answer():
    p = poll(NUMBER, answer_value=1.0)
    p.reveal(None)
    p.reopen()
    assert p.open and p.public()["revealed"] is None


# ---- CSV and privacy ----------------------------------------------------------------------------------
def answered_by_named_students(**extra) -> Poll:
    p = poll(NUMBER, question='At what spin, in "rad/s", does it stop sleeping, roughly?', **extra)
    p.submit("token-b", {"value": 12.5}, name="Ada Lovelace")
    p.submit("token-a", {"value": 20.0})  # no name given
    p.submit("token-b", {"value": 15.25}, name="Ada Lovelace")  # replaces, keeps "student 1"
    return p


def rows(p: Poll) -> list[list[str]]:
    return list(csv.reader(io.StringIO(p.to_csv())))


def test_csv_round_trips_through_the_csv_module_anonymous_by_default():
    p = answered_by_named_students()
    header, *body = rows(p)
    assert header == ["poll_id", "question", "student", "answer", "unit", "answered_at_utc"]
    assert [row[:5] for row in body] == [
        ["p1", p.question, "student 1", "15.25", "rad/s"],
        ["p1", p.question, "student 2", "20.0", "rad/s"],
    ]
    assert '"At what spin, in ""rad/s"", does it stop sleeping, roughly?"' in p.to_csv()  # commas and quotes quoted
    for row in body:
        assert row[5].endswith("Z") and datetime.fromisoformat(row[5].replace("Z", "+00:00")).utcoffset().total_seconds() == 0
    assert "Ada" not in p.to_csv()


def test_csv_and_results_show_names_only_when_turned_on():
    p = answered_by_named_students()
    assert "names" not in p.results()
    p.show_names = True
    assert [row[2] for row in rows(p)[1:]] == ["Ada Lovelace", "student 2"]
    assert p.results()["names"] == [{"name": "Ada Lovelace", "answer": "15.25 rad/s"}, {"name": "student 2", "answer": "20 rad/s"}]
    choice = poll(CHOICE, show_names=True)
    choice.submit("token-a", {"choice": 2}, name="Grace")
    assert rows(choice)[1][2:4] == ["Grace", "loops"]


def test_public_never_shows_names_or_answers():
    p = answered_by_named_students(show_names=True)
    p.submit("token-c", {"value": 123.456}, name="Grace Hopper")
    public = p.public()
    assert set(public) == {"poll_id", "question", "kind", "choices", "unit", "open", "answers", "revealed"}
    assert public["answers"] == 3
    text = json.dumps(public)
    for secret in ("Ada", "Grace", "123.456", "15.25", "token-"):
        assert secret not in text


@pytest.mark.parametrize(
    ("typed", "cell"),
    [
        ('=HYPERLINK("http://e.vil","x")', '\'=HYPERLINK("http://e.vil","x")'),
        ("=cmd|' /C calc'!A0", "'=cmd|' /C calc'!A0"),
        ("+SUM(1,2)", "'+SUM(1,2)"),
        ("-2+3", "'-2+3"),
        ("-3.2", "'-3.2"),  # typed text that looks like a number is still text a person typed
        ("@SUM(A1)", "'@SUM(A1)"),
        ("\t=1", "'\t=1"),
        ("\r=1", "'\r=1"),
        ("Ada", "Ada"),
        ("a=b", "a=b"),  # only the first character can start a formula
        ("", ""),
    ],
)
def test_a_text_cell_that_could_start_a_formula_gets_a_leading_quote(typed, cell):
    assert spreadsheet_text(typed) == cell


def test_a_withdrawn_answer_leaves_the_results_and_its_number_is_not_reused():
    p = numbers(1.0, 2.0, 3.0, show_names=True)
    p.withdraw("token-1")
    p.withdraw("no-such-student")  # nothing to withdraw: nothing changes
    assert p.answer_count == 2 and sum(b["count"] for b in p.results()["histogram"]) == 2
    p.submit("token-9", {"value": 4.0})
    assert [row[2] for row in rows(p)[1:]] == ["student 1", "student 3", "student 4"]
