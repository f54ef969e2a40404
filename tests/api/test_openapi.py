"""The OpenAPI document describes every answer: a 200 schema per route, the 403/404/413/422/429s it can give, the session-id pattern."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.scenes.host.host import SESSION_ID_PATTERN

SPEC = TestClient(create_app()).get("/openapi.json").json()  # no lifespan needed: the spec is static
OPERATIONS = [(path, method, op) for path, item in SPEC["paths"].items() for method, op in item.items()]
#: Routes whose path names something that may not exist (404), and routes that read a body or a checked path (422).
CAN_BE_NOT_FOUND = {
    ("/api/examples/{example_id}/solve", "post"),
    ("/api/scenes/{scene_id}/sessions/{session_id}", "put"),
    ("/api/scenes/{scene_id}/sessions/{session_id}", "get"),
    ("/api/scenes/{scene_id}/simulate", "post"),
    ("/api/scenes/{scene_id}/sessions/{session_id}/live", "get"),
    ("/api/bench/work-precision", "get"),
    ("/api/systems/{system_id}/derive", "post"),
    ("/api/systems/{system_id}/rhs", "post"),
    ("/api/systems/{system_id}/eigenvalues", "post"),
}
#: The classroom: a room, poll or code that may not exist; every one of these reads a body or a checked id.
ROOM_ROUTES = {
    ("/api/rooms/{room_id}", "delete"),
    ("/api/rooms/join", "post"),
    ("/api/rooms/{room_id}/state", "get"),
    ("/api/rooms/{room_id}/state", "post"),
    ("/api/rooms/{room_id}/polls/ready", "get"),
    ("/api/rooms/{room_id}/polls", "post"),
    ("/api/rooms/{room_id}/polls/{poll_id}", "post"),
    ("/api/rooms/{room_id}/polls/{poll_id}/answers", "post"),
    ("/api/rooms/{room_id}/polls/{poll_id}/results", "get"),
    ("/api/rooms/{room_id}/students", "get"),
    ("/api/rooms/{room_id}/students/{student_id}", "delete"),
    ("/api/rooms/{room_id}/assignment", "put"),
    ("/api/rooms/{room_id}/assignment", "delete"),
    ("/api/rooms/{room_id}/assignment/results", "get"),
}
#: A page's time controls (issue 15): an unknown scene, or a session without one yet.
PLAYBACK_ROUTES = {("/api/scenes/{scene_id}/sessions/{session_id}/playback", "put"), ("/api/scenes/{scene_id}/sessions/{session_id}/playback", "get")}
#: Graphs of a session's kept motion (issue 15): an unknown scene or a session without one; a bad since_s or max_points.
GRAPH_ROUTES = {("/api/scenes/{scene_id}/sessions/{session_id}/graph", "get")}
#: Practice (issue 27): an exercise or a resume code that may not exist; a variant, an answer, a section, a token header.
EXERCISE_ROUTES = {
    ("/api/exercises/{exercise_id}", "get"), ("/api/exercises/{exercise_id}/attempts", "post"),
    ("/api/exercises/{exercise_id}/give-up", "post"), ("/api/exercises/{exercise_id}/solution", "get"),
    ("/api/learners/resume", "post"),
}  # fmt: skip
CAN_BE_NOT_FOUND |= ROOM_ROUTES | PLAYBACK_ROUTES | GRAPH_ROUTES | EXERCISE_ROUTES
CAN_BE_UNPROCESSABLE = (CAN_BE_NOT_FOUND - {("/api/bench/work-precision", "get")}) | {
    ("/api/systems/custom/derive", "post"), ("/api/systems/custom/describe", "post"), ("/api/rooms", "post"), ("/api/exercises", "get"), ("/api/progress", "get"),
    ("/api/progress", "delete"),
}  # fmt: skip
#: Instructor-only reads: a student gets 403 (app/api/rooms.py require_instructor), as on every state-changing route.
INSTRUCTOR_ONLY_READS = {
    ("/api/rooms/{room_id}/polls/ready", "get"), ("/api/rooms/{room_id}/polls/{poll_id}/results", "get"), ("/api/rooms/{room_id}/students", "get"),
    ("/api/exercises/{exercise_id}/solution", "get"),  # an instructor's always; a learner's once done with it
    ("/api/rooms/{room_id}/assignment/results", "get"),
}  # fmt: skip
#: Answers the web front's guard gives before any route runs (app/web/guard.py), which FastAPI cannot see by itself.
WITH_BODY = [(path, method) for path, method, op in OPERATIONS if "requestBody" in op]
STATE_CHANGING = [(path, method) for path, method, _ in OPERATIONS if method not in ("get", "head", "options")]
#: Every request is rate limited per device by the guard (app/web/guard.py), before any route runs.
RATE_LIMITED = [(path, method) for path, method, _ in OPERATIONS]
#: Where each error answer may be documented: no route lists one it cannot give.
CAN_ANSWER = {"404": CAN_BE_NOT_FOUND, "422": CAN_BE_UNPROCESSABLE, "413": set(WITH_BODY), "403": set(STATE_CHANGING) | INSTRUCTOR_ONLY_READS, "429": set(RATE_LIMITED)}


def resolve(schema: dict) -> dict:
    """Follow one ``$ref`` into components/schemas."""
    ref = schema.get("$ref")
    return SPEC["components"]["schemas"][ref.rsplit("/", 1)[1]] if ref else schema


def test_every_json_route_is_documented():
    documented = {(path, method) for path, method, _ in OPERATIONS}
    assert CAN_BE_NOT_FOUND <= documented
    assert {("/api/health", "get"), ("/api/chapters", "get"), ("/api/scenes", "get"), ("/api/examples", "get")} <= documented


@pytest.mark.parametrize(("path", "method", "op"), OPERATIONS, ids=[f"{m.upper()} {p}" for p, m, _ in OPERATIONS])
def test_every_route_has_a_typed_200(path, method, op):
    schema = op["responses"]["200"]["content"]["application/json"]["schema"]
    target = resolve(schema.get("items", schema))
    assert target.get("properties"), f"{method.upper()} {path}: the 200 answer has no described fields"


@pytest.mark.parametrize(("path", "method"), sorted(CAN_BE_NOT_FOUND))
def test_404_is_documented_where_it_can_happen(path, method):
    answer = SPEC["paths"][path][method]["responses"]["404"]
    assert answer["description"]
    assert resolve(answer["content"]["application/json"]["schema"])["properties"]["detail"]["type"] == "string"


@pytest.mark.parametrize(("path", "method"), sorted(CAN_BE_UNPROCESSABLE))
def test_422_is_documented_where_it_can_happen(path, method):
    answer = SPEC["paths"][path][method]["responses"]["422"]
    issue = resolve(resolve(answer["content"]["application/json"]["schema"])["properties"]["detail"]["items"])
    assert {"loc", "msg", "type"} <= set(issue["required"])


@pytest.mark.parametrize(("path", "method", "op"), OPERATIONS, ids=[f"{m.upper()} {p}" for p, m, _ in OPERATIONS])
def test_no_error_answer_where_none_can_happen(path, method, op):
    for status, where in CAN_ANSWER.items():
        if (path, method) not in where:
            assert status not in op["responses"], f"{method.upper()} {path} documents a {status} it cannot give"


@pytest.mark.parametrize("path", ["/api/scenes/{scene_id}/sessions/{session_id}", "/api/scenes/{scene_id}/sessions/{session_id}/live"])
def test_session_id_pattern_is_in_the_spec(path):
    for op in SPEC["paths"][path].values():
        (param,) = [p for p in op["parameters"] if p["name"] == "session_id"]
        assert param["in"] == "path"
        assert param["schema"]["pattern"] == SESSION_ID_PATTERN.pattern


def test_a_malformed_session_id_is_a_422_naming_the_path_parameter(client):
    for response in (
        client.put("/api/scenes/four-bar/sessions/short", json={"params": {}}),
        client.get("/api/scenes/four-bar/sessions/short/live"),
    ):
        assert response.status_code == 422
        assert response.json()["detail"][0]["loc"] == ["path", "session_id"]


def assert_error_detail(answer: dict) -> None:
    assert answer["description"]
    assert resolve(answer["content"]["application/json"]["schema"])["properties"]["detail"]["type"] == "string"


def test_the_guarded_routes_are_found():
    assert {("/api/examples/{example_id}/solve", "post"), ("/api/scenes/{scene_id}/simulate", "post")} <= set(WITH_BODY)
    assert ("/api/scenes/{scene_id}/sessions/{session_id}", "put") in STATE_CHANGING


@pytest.mark.parametrize(("path", "method"), WITH_BODY)
def test_413_is_documented_on_every_route_that_reads_a_body(path, method):
    assert_error_detail(SPEC["paths"][path][method]["responses"]["413"])


@pytest.mark.parametrize(("path", "method"), STATE_CHANGING + sorted(INSTRUCTOR_ONLY_READS))
def test_403_is_documented_on_every_state_changing_route(path, method):
    assert_error_detail(SPEC["paths"][path][method]["responses"]["403"])


@pytest.mark.parametrize(("path", "method"), RATE_LIMITED)
def test_429_is_documented_where_a_client_can_be_rate_limited(path, method):
    assert_error_detail(SPEC["paths"][path][method]["responses"]["429"])

