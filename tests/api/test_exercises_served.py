"""The exercise API against ``dynlab serve`` (tests/served.py), as a student and an instructor use it: a learner's own
numbers, answers checked part by part (units converted, a wrong dimension named, a named mistake told, an unreadable
answer refused and not counted), the solution closed until every part is solved or given up, progress kept and carried
to another device by its resume code, and what a hostile student tries (another's token, a guessed exercise, absurd
answers, a flood of learners)."""

from __future__ import annotations

import httpx
import pytest

from app.practice.variants import learner_variant, variant
from tests.practice.shipped import EXERCISES

PLATE = "5-2-plate-about-corner"
DISK = "5-3-tilted-disk-bearings"


@pytest.fixture(scope="module")
def api(served) -> httpx.Client:
    with served.new_client() as client:
        yield client


def _learner(api: httpx.Client) -> tuple[str, dict[str, str], dict]:
    made = api.post("/api/learners")
    assert made.status_code == 200, made.text
    body = made.json()
    return body["learner_id"], {"X-Learner-Token": body["token"]}, body


def _attempt(api, exercise_id: str, number: int, part: str, answer: dict, headers=None) -> httpx.Response:
    return api.post(
        f"/api/exercises/{exercise_id}/attempts",
        json={"variant": number, "part": part, "answer": answer},
        headers=headers or {},
    )


def test_the_exercises_are_listed_by_section_and_an_unknown_one_is_a_404(api):
    listed = api.get("/api/exercises", params={"section": "5.2"}).json()
    assert [e["id"] for e in listed] == [e.id for e in EXERCISES.values() if e.section == "5.2"]
    assert next(e for e in listed if e["id"] == PLATE) == {
        "id": PLATE, "title": EXERCISES[PLATE].title, "chapter": 5, "section": "5.2", "parts": 3
    }  # fmt: skip
    assert api.get("/api/exercises", params={"section": "5.2; drop"}).status_code == 422
    assert api.get("/api/exercises/no-such-exercise").status_code == 404
    assert api.get(f"/api/exercises/{PLATE}", params={"variant": -1}).status_code == 422
    assert api.get(f"/api/exercises/{PLATE}", params={"variant": 2**31}).status_code == 422


def test_a_learner_works_an_exercise_part_by_part_and_keeps_it(api, served):
    learner_id, me, made = _learner(api)
    shown = api.get(f"/api/exercises/{DISK}", headers=me).json()
    number = shown["variant"]
    assert number == learner_variant(DISK, learner_id)  # their own numbers, the same each time
    assert api.get(f"/api/exercises/{DISK}", headers=me).json()["given"] == shown["given"]
    drawn = variant(EXERCISES[DISK], number)
    assert {name: g["value"] for name, g in shown["given"].items()} == drawn.given
    assert shown["scene"]["params"]["mass_kg"] == drawn.given["mass_kg"] and shown["scene"]["url"].startswith("/lessons/")
    assert "{{" not in shown["statement"] and shown["parts"][0]["answer_kind"] == "number"
    h = drawn.answers["h"]

    wrong = _attempt(api, DISK, number, "h", {"value": h.mistakes["h-along-axis"], "unit": "kg*m^2/s"}, me).json()
    assert wrong["correct"] is False and wrong["mistake"]["id"] == "h-along-axis"
    unreadable = _attempt(api, DISK, number, "h", {"value": 1.0, "unit": "kg*m^2/s; rm"}, me)
    assert unreadable.status_code == 422 and unreadable.json()["detail"][0]["loc"] == ["body", "answer"]
    in_grams = _attempt(api, DISK, number, "h", {"value": h.value * 1e7, "unit": "g*cm^2/s"}, me).json()
    assert in_grams["correct"] is True
    foreign = _attempt(api, DISK, number, "force", {"value": 3.0, "unit": "N*m"}, me).json()
    assert foreign["correct"] is False and "a moment or an energy" in foreign["feedback"]

    kept = api.get("/api/progress", headers=me).json()
    assert kept["learner_id"] == learner_id
    h_kept = next(p for p in kept["parts"] if p["part"] == "h")
    assert h_kept == {
        "exercise_id": DISK, "part": "h", "variant": number, "attempts": 2, "solved": True, "gave_up": False,
        "mistakes": ["h-along-axis"],
    }  # the unreadable answer was not counted
    in_section = sum(e.section == "5.3" for e in EXERCISES.values())
    assert kept["sections"]["5.3"] == {"exercises": in_section, "started": 1, "solved": 0}
    assert api.get(f"/api/exercises/{DISK}/solution", headers=me).status_code == 403  # two parts still open
    for part in ("angle", "force"):
        assert _attempt(api, DISK, number, part, {"value": drawn.answers[part].value, "unit": ""}, me).json()["correct"]
    solution = api.get(f"/api/exercises/{DISK}/solution", headers=me).json()
    assert [p["answer"]["value"] for p in solution["parts"]] == pytest.approx([drawn.answers[p].value for p in ("h", "angle", "force")])
    assert api.get("/api/progress", headers=me).json()["sections"]["5.3"]["solved"] == 1

    # Another device: the resume code carries the same learner and progress; the first token still works.
    with served.new_client() as phone:
        resumed = phone.post("/api/learners/resume", json={"code": made["resume_code"].lower().replace("-", " ")})
        assert resumed.status_code == 200, resumed.text
        there = phone.get("/api/progress", headers={"X-Learner-Token": resumed.json()["token"]}).json()
        assert there["learner_id"] == learner_id and there["sections"]["5.3"]["solved"] == 1
    assert api.get("/api/progress", headers=me).status_code == 200


def test_giving_up_opens_the_solution_and_is_kept(api):
    learner_id, me, _ = _learner(api)
    number = learner_variant(PLATE, learner_id)
    drawn = variant(EXERCISES[PLATE], number)
    assert _attempt(api, PLATE, number, "ixx", {"value": drawn.answers["ixx"].value, "unit": "kg*m^2"}, me).json()["correct"]
    solution = api.post(f"/api/exercises/{PLATE}/give-up", json={"variant": number}, headers=me).json()
    assert solution["variant"] == number and [p["id"] for p in solution["parts"]] == ["ixx", "ixy", "izz"]
    parts = {p["part"]: p for p in api.get("/api/progress", headers=me).json()["parts"]}
    assert parts["ixx"]["solved"] and not parts["ixx"]["gave_up"] and parts["ixy"]["gave_up"] and parts["izz"]["gave_up"]
    assert api.get(f"/api/exercises/{PLATE}/solution", params={"variant": number}, headers=me).status_code == 200


def test_an_instructor_sees_any_solution_and_a_student_without_a_token_sees_none(api, served):
    assert api.get(f"/api/exercises/{PLATE}/solution", params={"variant": 3}, headers=served.instructor_headers).status_code == 200
    refused = api.get(f"/api/exercises/{PLATE}/solution", params={"variant": 3})
    assert refused.status_code == 401 and "X-Learner-Token" in refused.json()["detail"]
    forged = api.get(f"/api/exercises/{PLATE}/solution", params={"variant": 3}, headers={"X-Learner-Token": "x" * 32})
    assert forged.status_code == 401
    # Someone else's progress is out of reach: a token is the only key, and one learner's shows only their own parts.
    first_id, first, _ = _learner(api)
    _, second, _ = _learner(api)
    _attempt(api, PLATE, learner_variant(PLATE, first_id), "ixx", {"value": 1.0, "unit": "kg*m^2"}, first)
    assert api.get("/api/progress", headers=second).json()["parts"] == []


def test_a_learner_works_on_their_own_numbers_only(api):
    """Found by an outside attack: a second learner gave up on a classmate's variant to read its answers; solving
    variant 0 counted as solving; an attempt on another variant wiped a solved part. A learner's attempts, give-ups
    and solutions are for their own variant (409 otherwise, nothing kept); without a token any variant is checked
    and nothing is kept."""
    first_id, first, _ = _learner(api)
    _, second, _ = _learner(api)
    mine = learner_variant(PLATE, first_id)
    other = (mine + 1) % 2**31
    assert api.post(f"/api/exercises/{PLATE}/give-up", json={"variant": mine}, headers=second).status_code == 409
    assert api.get(f"/api/exercises/{PLATE}/solution", params={"variant": mine}, headers=second).status_code == 409
    zero = variant(EXERCISES[PLATE], 0).answers["ixx"].value
    refused = _attempt(api, PLATE, 0 if mine else 1, "ixx", {"value": zero, "unit": "kg*m^2"}, first)
    assert refused.status_code == 409 and f"variant {mine}" in refused.json()["detail"]
    assert api.get("/api/progress", headers=first).json()["parts"] == []
    right = variant(EXERCISES[PLATE], mine).answers["ixx"].value
    assert _attempt(api, PLATE, mine, "ixx", {"value": right, "unit": "kg*m^2"}, first).json()["correct"]
    assert _attempt(api, PLATE, other, "ixx", {"value": 1.0, "unit": "kg*m^2"}, first).status_code == 409
    (kept,) = api.get("/api/progress", headers=first).json()["parts"]
    assert kept["solved"] and kept["variant"] == mine
    anonymous = _attempt(api, PLATE, other, "ixx", {"value": 1.0, "unit": "kg*m^2"})
    assert anonymous.status_code == 200 and anonymous.json()["correct"] is False


@pytest.mark.parametrize(
    "answer",
    [
        {"value": "1e400"}, {"value": 1e300, "unit": "kg*m^2"}, {"value": 1.0, "unit": "x" * 41}, {"expression": "x" * 401},
        {"vector": [1, 2]}, {"choice": "a" * 33}, {"value": 1.0, "unit": "kg", "extra": 1}, {},
        {"expression": "__import__('os').system('id')"}, {"value": 1.0, "unit": "m^9^9^9"},
    ],
)
def test_absurd_answers_are_refused_with_a_4xx_and_change_nothing(api, answer):
    learner_id, me, _ = _learner(api)
    bead = "7-5-bead-on-hoop-lagrange"
    part = "kinetic" if "expression" in answer else "steady"
    response = _attempt(api, bead, learner_variant(bead, learner_id), part, answer, me)
    assert response.status_code == 422, response.text
    assert api.get("/api/progress", headers=me).json()["parts"] == []


def test_a_flood_of_new_learners_from_one_address_gets_a_429_with_retry_after(served):
    with served.new_client() as flood:
        statuses = [flood.post("/api/learners").status_code for _ in range(140)]
    assert statuses.count(200) >= 100 and statuses[-1] == 429
    refused = next(code for code in statuses if code != 200)
    assert refused == 429


def test_a_server_that_keeps_nothing_still_checks_answers_and_says_it_keeps_no_learners():
    """In-process (no data directory: nothing kept), beside the served tests: a page's stale token does not stop its
    answer from being checked; asking for a learner is a 503 with Retry-After that says why."""
    from fastapi.testclient import TestClient

    from app.main import create_app

    with TestClient(create_app()) as client:
        made = client.post("/api/learners")
        assert made.status_code == 503 and "keeps no progress" in made.json()["detail"] and made.headers["Retry-After"]
        drawn = variant(EXERCISES[PLATE], 0)
        checked = client.post(
            f"/api/exercises/{PLATE}/attempts",
            json={"variant": 0, "part": "ixx", "answer": {"value": drawn.answers["ixx"].value, "unit": "kg*m^2"}},
            headers={"X-Learner-Token": "a-token-from-another-server"},
        )
        assert checked.status_code == 200 and checked.json()["correct"] is True
        assert client.get("/api/progress", headers={"X-Learner-Token": "x"}).status_code == 503
