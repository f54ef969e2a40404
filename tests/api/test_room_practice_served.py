"""Exercises in a class room (issue 27, point 7) against ``dynlab serve``: the instructor assigns a section with one set
of numbers for the class, students work it from their room with their learner tokens, and the instructor's results
count per part who tried, solved and gave up, and which named mistakes are common — anonymous until names are turned
on; the CSV neutralises a name typed as a formula. And what a hostile student tries: assigning, reading the results,
another room's token, an exercise not assigned, a variant not theirs."""

from __future__ import annotations

import csv
import io

import httpx
import pytest

from app.practice.variants import class_variant, learner_variant, room_student_variant, variant
from tests.practice.shipped import EXERCISES

SECTION = "6.1"
PLATE = "5-2-plate-about-corner"
DISK = "5-3-tilted-disk-bearings"
CHOSEN = [PLATE, DISK]


@pytest.fixture(scope="module")
def room(served) -> dict:
    with served.new_client() as instructor:
        made = instructor.post("/api/rooms", json={"lesson_id": None}, headers=served.instructor_headers)
        assert made.status_code == 200, made.text
        yield made.json()
        instructor.delete(f"/api/rooms/{made.json()['room_id']}", headers=served.instructor_headers)


class Student:
    """A student's browser: its own cookies, the room's token and a learner's."""

    def __init__(self, served, code: str, name: str) -> None:
        self.client = served.new_client()
        joined = self.client.post("/api/rooms/join", json={"code": code, "name": name})
        assert joined.status_code == 200, joined.text
        self.student_token, self.student_id = joined.json()["student_token"], joined.json()["student_id"]
        made = self.client.post("/api/learners").json()
        self.learner_id, self.learner_token = made["learner_id"], made["token"]
        self.headers = {"X-Student-Token": self.student_token, "X-Learner-Token": self.learner_token}

    def attempt(self, room_id: str, exercise_id: str, number: int, part: str, answer: dict) -> httpx.Response:
        body = {"variant": number, "part": part, "answer": answer, "room_id": room_id}
        return self.client.post(f"/api/exercises/{exercise_id}/attempts", json=body, headers=self.headers)


def _number_answer(exercise_id: str, number: int, part_id: str, *, mistake: str | None = None) -> dict:
    drawn = variant(EXERCISES[exercise_id], number)
    answer = drawn.answers[part_id]
    value = answer.mistakes[mistake] if mistake else answer.value
    part = EXERCISES[exercise_id].part(part_id)
    assert part is not None and part.kind == "number"
    return {"value": float(value), "unit": part.unit}


def test_an_assigned_section_is_worked_from_the_room_and_counted_for_the_instructor(served, room):
    room_id, code = room["room_id"], room["code"]
    instructor = served.instructor_headers
    with served.new_client() as api:
        assigned = api.put(
            f"/api/rooms/{room_id}/assignment", json={"section": SECTION, "class_variant": True}, headers=instructor
        )
        assert assigned.status_code == 200, assigned.text
        ids = [e.id for e in EXERCISES.values() if e.section == SECTION]  # a section's set, in course order
        assert assigned.json()["exercise_ids"] == ids and assigned.json()["class_variant"] is True
        seed = assigned.json()["seed"]
        chosen = api.put(
            f"/api/rooms/{room_id}/assignment", json={"exercise_ids": CHOSEN, "class_variant": True}, headers=instructor
        )
        assert chosen.json()["exercise_ids"] == CHOSEN and chosen.json()["seed"] == seed  # the class keeps its numbers
        state = api.get(f"/api/rooms/{room_id}/state").json()
        assert state["assignment"]["exercise_ids"] == CHOSEN and "seed" not in state["assignment"]

        ada, bob = Student(served, code, "Ada"), Student(served, code, "=HYPERLINK(1)")
        try:
            number = class_variant(PLATE, seed)
            for student in (ada, bob):  # the class's numbers, whoever asks, and not their own
                shown = student.client.get(
                    f"/api/exercises/{PLATE}", params={"room": room_id}, headers=student.headers
                ).json()
                assert shown["variant"] == number != learner_variant(PLATE, student.learner_id)
                assert shown["room"] == {"room_id": room_id, "code": code, "lesson_id": None, "class_variant": True}
            part = EXERCISES[PLATE].parts[0]
            mistake = EXERCISES[PLATE].mistakes_of(part.id)[0]
            # Ada: a named mistake, then right; Bob: the same mistake, then gives up.
            wrong = ada.attempt(room_id, PLATE, number, part.id, _number_answer(PLATE, number, part.id, mistake=mistake.id))
            assert wrong.status_code == 200 and wrong.json()["mistake"]["id"] == mistake.id, wrong.text
            right = ada.attempt(room_id, PLATE, number, part.id, _number_answer(PLATE, number, part.id))
            assert right.json()["correct"] is True
            assert bob.attempt(
                room_id, PLATE, number, part.id, _number_answer(PLATE, number, part.id, mistake=mistake.id)
            ).json()["mistake"]["id"] == mistake.id
            gave_up = bob.client.post(
                f"/api/exercises/{PLATE}/give-up", json={"variant": number, "room_id": room_id}, headers=bob.headers
            )
            assert gave_up.status_code == 200, gave_up.text
            # Their own numbers are refused in the room (the class works on one set).
            own = learner_variant(PLATE, ada.learner_id)
            refused = ada.attempt(room_id, PLATE, own, part.id, _number_answer(PLATE, own, part.id))
            assert refused.status_code == 409 and str(number) in refused.json()["detail"]

            results = api.get(f"/api/rooms/{room_id}/assignment/results", headers=instructor)
            assert results.status_code == 200, results.text
            body = results.json()
            assert body["students"] == 2 and body["show_names"] is False
            plate = next(e for e in body["exercises"] if e["exercise_id"] == PLATE)
            assert plate["variant"] == number
            first = plate["parts"][0]
            assert (first["tried"], first["solved"], first["gave_up"]) == (2, 1, 1)
            assert first["mistakes"][0] == {"mistake": mistake.id, "text": mistake.text, "students": 2}
            assert "names" not in first  # anonymous
            second = plate["parts"][1]
            assert (second["tried"], second["solved"], second["gave_up"]) == (1, 0, 1)  # Bob gave up on every part
            untouched = next(e for e in body["exercises"] if e["exercise_id"] != PLATE)
            assert all(p["tried"] == 0 for p in untouched["parts"])

            anonymous = list(csv.reader(io.StringIO(api.get(
                f"/api/rooms/{room_id}/assignment/results.csv", headers=instructor).text)))  # fmt: skip
            assert anonymous[0][:2] == ["student_id", "student"]
            assert {r[1] for r in anonymous[1:]} == {"student 1", "student 2"}

            # Names on: the instructor sees who, and the CSV keeps a typed formula as text.
            named = api.put(
                f"/api/rooms/{room_id}/assignment",
                json={"exercise_ids": CHOSEN, "class_variant": True, "show_names": True},
                headers=instructor,
            )
            assert named.json()["seed"] == seed  # the class keeps its numbers while the assignment changes
            first = next(e for e in api.get(f"/api/rooms/{room_id}/assignment/results", headers=instructor).json()[
                "exercises"] if e["exercise_id"] == PLATE)["parts"][0]  # fmt: skip
            assert [(n["student"], n["solved"], n["gave_up"]) for n in first["names"]] == [
                ("Ada", True, False),
                ("=HYPERLINK(1)", False, True),
            ]
            rows = list(csv.reader(io.StringIO(api.get(
                f"/api/rooms/{room_id}/assignment/results.csv", headers=instructor).text)))  # fmt: skip
            names = {r[1] for r in rows[1:]}
            assert names == {"Ada", "'=HYPERLINK(1)"}
            ada_first = next(r for r in rows if r[1] == "Ada" and r[2] == PLATE and r[3] == part.id)
            assert ada_first[0] == ada.student_id and ada_first[4:9] == [str(number), "2", "yes", "no", mistake.id]

            # Bob removed: his work leaves the results.
            students = api.get(f"/api/rooms/{room_id}/students", headers=instructor).json()["students"]
            bob_id = next(s["student_id"] for s in students if s["name"] == "=HYPERLINK(1)")
            assert api.delete(f"/api/rooms/{room_id}/students/{bob_id}", headers=instructor).status_code == 200
            first = next(e for e in api.get(f"/api/rooms/{room_id}/assignment/results", headers=instructor).json()[
                "exercises"] if e["exercise_id"] == PLATE)["parts"][0]  # fmt: skip
            assert (first["tried"], first["solved"], first["gave_up"]) == (1, 1, 0)
        finally:
            ada.client.close()
            bob.client.close()


def test_a_hostile_student_cannot_assign_read_results_or_count_work_that_is_not_theirs(served, room):
    room_id, code = room["room_id"], room["code"]
    instructor = served.instructor_headers
    with served.new_client() as api:
        assert api.put(
            f"/api/rooms/{room_id}/assignment", json={"exercise_ids": [PLATE]}, headers=instructor
        ).status_code == 200
        eve = Student(served, code, "Eve")
        try:
            # Instructor doors are closed to a student (and change nothing).
            for method, path, body in (
                ("PUT", f"/api/rooms/{room_id}/assignment", {"exercise_ids": [DISK]}),
                ("DELETE", f"/api/rooms/{room_id}/assignment", None),
                ("GET", f"/api/rooms/{room_id}/assignment/results", None),
                ("GET", f"/api/rooms/{room_id}/assignment/results.csv", None),
            ):
                answer = eve.client.request(method, path, json=body, headers=eve.headers)
                assert answer.status_code == 403, (method, path, answer.text)
            assert api.get(f"/api/rooms/{room_id}/state").json()["assignment"]["exercise_ids"] == [PLATE]
            # Own numbers now (no class variant): the student's own in this room, whatever device or learner asks.
            number = room_student_variant(room_id, eve.student_id, PLATE)
            shown = eve.client.get(f"/api/exercises/{PLATE}", params={"room": room_id}, headers=eve.headers).json()
            assert shown["variant"] == number
            part = EXERCISES[PLATE].parts[0]
            answer = _number_answer(PLATE, number, part.id)
            assert eve.attempt(room_id, PLATE, number, part.id, answer).json()["correct"] is True
            # Not assigned, another room's id, a forged student token, no learner token: refused, nothing counted.
            disk = learner_variant(DISK, eve.learner_id)
            disk_answer = _number_answer(DISK, disk, EXERCISES[DISK].parts[0].id) if EXERCISES[
                DISK].parts[0].kind == "number" else {"choice": "a"}  # fmt: skip
            assert eve.attempt(room_id, DISK, disk, EXERCISES[DISK].parts[0].id, disk_answer).status_code == 409
            assert eve.attempt("0" * 16, PLATE, number, part.id, answer).status_code == 404
            forged = {**eve.headers, "X-Student-Token": "x" * 24}
            body = {"variant": number, "part": part.id, "answer": answer, "room_id": room_id}
            assert eve.client.post(f"/api/exercises/{PLATE}/attempts", json=body, headers=forged).status_code == 403
            no_learner = {"X-Student-Token": eve.student_token}
            assert eve.client.post(f"/api/exercises/{PLATE}/attempts", json=body, headers=no_learner).status_code == 401
            for bad in ({"room_id": "not-a-room"}, {"room_id": "A" * 16}, {"room_id": 7}):
                refused = eve.client.post(f"/api/exercises/{PLATE}/attempts", json={**body, **bad}, headers=eve.headers)
                assert refused.status_code == 422, refused.text
            for bad in ({"section": "5.2", "exercise_ids": [PLATE]}, {}, {"exercise_ids": ["no-such"]},
                        {"section": "1.3"}, {"exercise_ids": []}, {"exercise_ids": [PLATE] * 25},
                        {"section": "5.2", "seed": -1}):  # fmt: skip
                refused = api.put(f"/api/rooms/{room_id}/assignment", json=bad, headers=instructor)
                assert refused.status_code == 422, (bad, refused.text)
            assert api.get(f"/api/rooms/{room_id}/state").json()["assignment"]["exercise_ids"] == [PLATE]
            results = api.get(f"/api/rooms/{room_id}/assignment/results", headers=instructor).json()
            first = results["exercises"][0]["parts"][0]
            assert (first["tried"], first["solved"]) == (1, 1)  # only Eve's one real attempt
            # Taken back: pages stop showing it, and work in the room is refused.
            assert api.delete(f"/api/rooms/{room_id}/assignment", headers=instructor).status_code == 200
            assert api.get(f"/api/rooms/{room_id}/state").json()["assignment"] is None
            assert eve.attempt(room_id, PLATE, number, part.id, answer).status_code == 409
        finally:
            eve.client.close()


@pytest.fixture
def fresh_room(served) -> dict:
    with served.new_client() as instructor:
        made = instructor.post("/api/rooms", json={"lesson_id": None}, headers=served.instructor_headers)
        assert made.status_code == 200, made.text
        yield made.json()
        instructor.delete(f"/api/rooms/{made.json()['room_id']}", headers=served.instructor_headers)


def test_a_students_record_in_the_room_is_the_rooms_whatever_they_do_with_their_own_progress(served, fresh_room):
    """The hostile student's session (helper-41's findings), each now a test: giving up and then typing the worked
    answers in stays "gave up"; forgetting one's own progress (DELETE /api/progress) leaves the room's record; a
    learner token two students share (a lab PC) keeps each student's work apart; the class's numbers survive turning
    one set off and on and taking the assignment back; names that turn the text's direction are refused; every CSV
    text cell is quoted; loose types are refused; the instructor's solution in the room is the class's."""
    room_id, code = fresh_room["room_id"], fresh_room["code"]
    instructor = served.instructor_headers
    with served.new_client() as api:
        put = lambda body: api.put(f"/api/rooms/{room_id}/assignment", json=body, headers=instructor)  # noqa: E731
        seed = put({"exercise_ids": [PLATE], "class_variant": True}).json()["seed"]
        assert put({"exercise_ids": [PLATE], "class_variant": False}).json()["seed"] is None
        assert put({"exercise_ids": [PLATE], "class_variant": True}).json()["seed"] == seed  # off and on: the same
        assert api.delete(f"/api/rooms/{room_id}/assignment", headers=instructor).status_code == 200
        assert put({"exercise_ids": [PLATE, DISK], "class_variant": True}).json()["seed"] == seed  # taken back too
        for loose in ({"seed": "12"}, {"class_variant": "yes"}, {"class_variant": 1}, {"show_names": "false"}):
            assert put({"exercise_ids": [PLATE], **loose}).status_code == 422, loose
        number = class_variant(PLATE, seed)
        solution = api.get(f"/api/exercises/{PLATE}/solution", params={"room": room_id}, headers=instructor).json()
        assert solution["variant"] == number

        bidi = served.new_client()
        refused = bidi.post("/api/rooms/join", json={"code": code, "name": "\u202eecilA"})
        assert refused.status_code == 422, refused.text
        bidi.close()

        cheat, careful = Student(served, code, "x;=1+1"), Student(served, code, "Careful")
        try:
            part = EXERCISES[PLATE].parts[0]
            solved = cheat.client.post(
                f"/api/exercises/{PLATE}/give-up", json={"variant": number, "room_id": room_id}, headers=cheat.headers
            ).json()
            copied = next(p["answer"] for p in solved["parts"] if p["id"] == part.id)
            assert cheat.attempt(room_id, PLATE, number, part.id, copied).json()["correct"] is True  # still checked
            # The careful student works on the cheat's computer: the cheat's learner token, the careful one's room
            # token. The room keeps each student's work as theirs.
            shared_pc = {**careful.headers, "X-Learner-Token": cheat.learner_token}
            body = {"variant": number, "part": part.id, "answer": _number_answer(PLATE, number, part.id),
                    "room_id": room_id}  # fmt: skip
            assert careful.client.post(f"/api/exercises/{PLATE}/attempts", json=body, headers=shared_pc).json()[
                "correct"] is True  # fmt: skip
            # The cheat forgets their own progress: the room's record stays.
            assert cheat.client.delete("/api/progress", headers={"X-Learner-Token": cheat.learner_token}).status_code == 200
            put({"exercise_ids": [PLATE, DISK], "class_variant": True, "show_names": True})
            results = api.get(f"/api/rooms/{room_id}/assignment/results", headers=instructor).json()
            first = next(e for e in results["exercises"] if e["exercise_id"] == PLATE)["parts"][0]
            work = {n["student_id"]: n for n in first["names"]}
            assert work[cheat.student_id]["gave_up"] is True and work[cheat.student_id]["solved"] is False
            assert work[cheat.student_id]["attempts"] == 1
            assert work[careful.student_id]["solved"] is True and work[careful.student_id]["attempts"] == 1
            assert (first["tried"], first["solved"], first["gave_up"]) == (2, 1, 1)
            text = api.get(f"/api/rooms/{room_id}/assignment/results.csv", headers=instructor).text
            assert '"x;=1+1"' in text and f'"{cheat.student_id}"' in text  # text cells quoted: one cell, no formula
        finally:
            cheat.client.close()
            careful.client.close()
