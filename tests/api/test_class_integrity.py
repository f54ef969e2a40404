"""A class's integrity, against ``dynlab serve`` as a user runs it (issue 24, Found item 10 and Build item 7; the
stale-tab 409 of Found item 9).

Each device here is its own ``httpx.Client`` with its own cookie jar, as a browser is, and its own loopback address
(Linux routes all of 127/8 to lo), as a class's devices are: the shared ``served`` app, in its default configuration,
sees each as a different client, so one test can be a hundred devices. The log is read from a server of its own,
started with ``--log-level info`` (uvicorn's access lines on).
"""

from __future__ import annotations

import csv
import io
import itertools
import json
import re
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor

import httpx
import pytest
from websockets.sync.client import connect as websocket_connect

from app.settings import Settings
from tests.conftest import wait_until
from tests.served import ServedApp

HEAVY_TOP_LESSON = "10-2-spinning-top"
FOUR_BAR_LESSON = "4-3-four-bar-linkage"
#: Cells a spreadsheet reads as a formula (OWASP, "CSV Injection"): they must reach results.csv with a leading '.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


_devices = itertools.count()


def device_address() -> str:
    """A loopback address no other device of these tests has (127.3.x.y; tests/served.py's devices use 127.1.x.y)."""
    n = next(_devices)
    return f"127.3.{n // 250 % 250}.{n % 250 + 1}"


def device(app: ServedApp, address: str | None = None) -> httpx.Client:
    """A new browser at an address of its own (or ``address``): its own cookie jar, so a device cookie set on joining
    stays with it. Plain HTTP on loopback: ``verify=False`` only skips loading the CA bundle (60 ms a client)."""
    transport = httpx.HTTPTransport(local_address=address or device_address(), verify=False)
    return httpx.Client(base_url=app.url, timeout=60.0, transport=transport)


def join_answer(client: httpx.Client, code: str, name: str = "") -> httpx.Response:
    """The join route's answer, a 429 waited out as the join page does (each device here has an address of its own,
    so this is only a safeguard)."""
    answers: list[httpx.Response] = []

    def let_through() -> bool:
        answers.append(client.post("/api/rooms/join", json={"code": code, "name": name}))
        return answers[-1].status_code != 429

    wait_until(let_through, timeout_s=120, interval_s=1.0, what="the join to be let through")
    return answers[-1]


def join(client: httpx.Client, code: str, name: str = "") -> dict:
    """Join as a student would: the answer's JSON."""
    answer = join_answer(client, code, name)
    assert answer.status_code == 200, answer.text
    return answer.json()


def open_room(served, lesson_id: str = HEAVY_TOP_LESSON) -> dict:
    answer = served.client.post("/api/rooms", json={"lesson_id": lesson_id}, headers=served.instructor_headers)
    assert answer.status_code == 200, answer.text
    return answer.json()


@pytest.fixture
def room(served) -> Iterator[dict]:
    room = open_room(served)
    yield room
    served.client.delete(f"/api/rooms/{room['room_id']}", headers=served.instructor_headers)


def state_of(served, room_id: str) -> dict:
    return served.client.get(f"/api/rooms/{room_id}/state").json()


def room_socket(served, room_id: str, *, instructor: bool = False):
    """The room socket as a page opens it (the instructor's carries the instructor key, as its cookie would)."""
    headers = served.instructor_headers if instructor else {}
    return websocket_connect(f"ws://127.0.0.1:{served.port}/api/rooms/{room_id}/socket", additional_headers=headers, open_timeout=30)


def messages_until(socket, wanted, *, timeout_s: float = 15.0) -> dict:
    """Read the socket until a message for which ``wanted`` holds (state and readouts arrive in between)."""
    deadline = time.monotonic() + timeout_s
    while True:
        message = json.loads(socket.recv(timeout=max(0.1, deadline - time.monotonic())))
        if wanted(message):
            return message
        if time.monotonic() > deadline:
            raise AssertionError(f"no wanted message within {timeout_s} s")


# ---- one device is one student ------------------------------------------------------------------------------------
def test_one_device_is_one_student_however_often_it_joins(served, room):
    """Found 10: re-scanning the QR code made a new student each time, so one device voted again and again."""
    phone, other = device(served), device(served)
    first = join(phone, room["code"])
    again = [join(phone, room["code"].lower()) for _ in range(3)]  # re-scans, the code typed again
    named = join(phone, room["code"], name="Ada")
    assert {j["student_token"] for j in again + [named]} == {first["student_token"]}, "the same device is the same student"
    assert join(other, room["code"])["student_token"] != first["student_token"]
    assert state_of(served, room["room_id"])["students"]["joined"] == 2

    poll = served.client.post(
        f"/api/rooms/{room['room_id']}/polls", json={"question": "Which way?", "kind": "choice", "choices": ["left", "right"]},
        headers=served.instructor_headers,
    ).json()  # fmt: skip
    answers_url = f"/api/rooms/{room['room_id']}/polls/{poll['poll_id']}/answers"
    for joined in [first, *again, named]:  # every token the device was given votes
        answer = phone.post(answers_url, json={"choice": 0}, headers={"X-Student-Token": joined["student_token"]})
        assert answer.status_code == 200, answer.text
    results = served.client.get(f"/api/rooms/{room['room_id']}/polls/{poll['poll_id']}/results", headers=served.instructor_headers).json()
    assert results["answers"] == 1 and [b["count"] for b in results["histogram"]] == [1, 0]
    students = served.client.get(f"/api/rooms/{room['room_id']}/students", headers=served.instructor_headers).json()
    assert sorted(s["name"] for s in students["students"]) == ["", "Ada"], "a name given on re-joining is kept"


def test_the_device_cookie_is_httponly_and_only_sent_to_joining(served, room):
    answer = join_answer(device(served), room["code"])
    assert answer.status_code == 200
    cookie = answer.headers["set-cookie"].lower()
    assert "httponly" in cookie and "path=/api/rooms/join" in cookie and "samesite=strict" in cookie
    assert answer.json()["student_token"] not in answer.headers["set-cookie"], "the cookie is not the student's token"


# ---- the instructor removes a student -----------------------------------------------------------------------------
def test_the_instructor_removes_a_student_whose_token_then_stops_working(served, room):
    """Found 10: the instructor could not remove anyone. Removed: the socket is closed, answers are refused, their
    answers leave the results, and their device cannot join again."""
    room_id = room["room_id"]
    phones = {name: device(served) for name in ("Ada", "Ben", "Cy")}
    joined = {name: join(phone, room["code"], name=name) for name, phone in phones.items()}
    poll = served.client.post(
        f"/api/rooms/{room_id}/polls", json={"question": "How fast?", "kind": "number", "unit": "rad/s"}, headers=served.instructor_headers
    ).json()
    answers_url = f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers"
    for (name, phone), value in zip(phones.items(), (10.0, 999.0, 12.0), strict=True):
        assert phone.post(answers_url, json={"value": value}, headers={"X-Student-Token": joined[name]["student_token"]}).status_code == 200

    listed = served.client.get(f"/api/rooms/{room_id}/students", headers=served.instructor_headers)
    assert listed.status_code == 200
    students = {s["name"]: s for s in listed.json()["students"]}
    assert set(students) == {"Ada", "Ben", "Cy"}
    assert all(j["student_token"] not in listed.text for j in joined.values()), "the list never shows a token"
    ben = students["Ben"]["student_id"]
    assert ben not in {j["student_token"] for j in joined.values()}

    # Only the instructor lists or removes.
    assert phones["Ada"].get(f"/api/rooms/{room_id}/students").status_code == 403
    refused = phones["Ada"].delete(f"/api/rooms/{room_id}/students/{ben}", headers={"X-Student-Token": joined["Ada"]["student_token"]})
    assert refused.status_code == 403

    with room_socket(served, room_id) as socket:
        messages_until(socket, lambda m: m["type"] == "state")
        socket.send(json.dumps({"type": "hello", "student_token": joined["Ben"]["student_token"], "following": True}))
        wait_until(lambda: state_of(served, room_id)["students"]["connected"] == 1, what="Ben's socket to count as connected")
        removed = served.client.delete(f"/api/rooms/{room_id}/students/{ben}", headers=served.instructor_headers)
        assert removed.status_code == 200 and removed.json() == {"removed": ben}
        notice = messages_until(socket, lambda m: m["type"] == "removed")
        assert "removed you" in notice["detail"]
        closed = False
        try:
            messages_until(socket, lambda m: False, timeout_s=10)
        except Exception as exc:  # the server closes the socket
            closed = "ConnectionClosed" in type(exc).__name__
        assert closed, "the removed student's socket is closed"

    state = state_of(served, room_id)
    assert (state["students"]["joined"], state["students"]["connected"]) == (2, 0)
    again = phones["Ben"].post(answers_url, json={"value": 5.0}, headers={"X-Student-Token": joined["Ben"]["student_token"]})
    assert again.status_code == 403 and "removed" in again.json()["detail"]
    rejoin = join_answer(phones["Ben"], room["code"], "Ben")
    assert rejoin.status_code == 403 and "removed" in rejoin.json()["detail"]
    results = served.client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results", headers=served.instructor_headers).json()
    assert results["answers"] == 2 and sum(b["count"] for b in results["histogram"]) == 2
    assert all(b["hi"] < 999.0 for b in results["histogram"]), "the removed student's answer is out of the histogram"
    served.client.post(f"/api/rooms/{room_id}/polls/{poll['poll_id']}", json={"show_names": True}, headers=served.instructor_headers)
    table = served.client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results.csv", headers=served.instructor_headers).text
    assert "Ben" not in table and "999" not in table and "Ada" in table and "Cy" in table
    assert served.client.delete(f"/api/rooms/{room_id}/students/{ben}", headers=served.instructor_headers).status_code == 404
    assert served.client.delete(f"/api/rooms/{room_id}/students/not-an-id!", headers=served.instructor_headers).status_code == 422


# ---- results.csv: no formula reaches a spreadsheet ------------------------------------------------------------------
def test_results_csv_neutralises_formulas_but_keeps_numbers_numbers(served, room):
    """Found 10: names, questions and choices such as =HYPERLINK(…) reached results.csv raw (formula injection).
    OWASP's rule: a text cell starting with = + - @ tab or CR gets a leading single quote. A number answer (−3.2) is
    written by the server from a float, not from anyone's text: it stays a plain number a spreadsheet can average."""
    room_id, instructor = room["room_id"], served.instructor_headers
    names = ['=HYPERLINK("http://e.vil","x")', "+SUM(1,2)", "@SUM(A1)", "-3.2", "Ada"]
    phones = [device(served) for _ in names]
    tokens = [join(phone, room["code"], name=name)["student_token"] for phone, name in zip(phones, names, strict=True)]

    choices = ["=cmd|' /C calc'!A0", "+SUM(A1:A9)", "-1+2", "@SUM(A1)", "plain"]
    choice_poll = served.client.post(
        f"/api/rooms/{room_id}/polls",
        json={"question": '=HYPERLINK("http://e.vil","Which?")', "kind": "choice", "choices": choices, "show_names": True},
        headers=instructor,
    ).json()
    for k, (phone, token) in enumerate(zip(phones, tokens, strict=True)):
        headers = {"X-Student-Token": token}
        assert phone.post(f"/api/rooms/{room_id}/polls/{choice_poll['poll_id']}/answers", json={"choice": k}, headers=headers).status_code == 200
    number_poll = served.client.post(  # closes the choice poll: one poll is open at a time
        f"/api/rooms/{room_id}/polls", json={"question": "-How fast?", "kind": "number", "unit": "=1+1", "show_names": True}, headers=instructor
    ).json()
    for phone, token, value in zip(phones[:3], tokens[:3], (-3.2, 4.5, -1e-7), strict=True):
        headers = {"X-Student-Token": token}
        assert phone.post(f"/api/rooms/{room_id}/polls/{number_poll['poll_id']}/answers", json={"value": value}, headers=headers).status_code == 200

    def rows(poll_id: str) -> list[dict]:
        answer = served.client.get(f"/api/rooms/{room_id}/polls/{poll_id}/results.csv", headers=instructor)
        assert answer.status_code == 200
        return list(csv.DictReader(io.StringIO(answer.text)))

    choice_rows = rows(choice_poll["poll_id"])
    assert [r["student"] for r in choice_rows] == ["'" + n if n[0] in FORMULA_STARTS else n for n in names]
    assert [r["answer"] for r in choice_rows] == ["'" + c if c[0] in FORMULA_STARTS else c for c in choices]
    assert {r["question"] for r in choice_rows} == {"'" + '=HYPERLINK("http://e.vil","Which?")'}
    number_rows = rows(number_poll["poll_id"])
    assert [r["answer"] for r in number_rows] == ["-3.2", "4.5", "-1e-07"], "a number answer stays a number"
    assert [float(r["answer"]) for r in number_rows] == [-3.2, 4.5, -1e-7]
    assert {r["unit"] for r in number_rows} == {"'=1+1"} and {r["question"] for r in number_rows} == {"'-How fast?"}
    for row in choice_rows + number_rows:
        for column, cell in row.items():
            if not (column == "answer" and row in number_rows):
                assert not cell.startswith(FORMULA_STARTS), (column, cell)


# ---- a stale instructor tab (Found 9) -------------------------------------------------------------------------------
def test_a_change_meant_for_a_scene_the_room_has_left_is_refused_with_409(served, room):
    """Found 9: a tab still on the heavy top sent mass_kg to a room now on the four-bar ("mass_kg: unknown input").
    A change carrying the lesson and scene its page shows is refused with 409 once the room has moved, and changes
    nothing; the same change for the room's own scene applies."""
    room_id, instructor = room["room_id"], served.instructor_headers
    moved = served.client.post(f"/api/rooms/{room_id}/state", json={"lesson_id": FOUR_BAR_LESSON}, headers=instructor)
    assert moved.status_code == 200 and moved.json()["scene_id"] == "four-bar"
    before = state_of(served, room_id)
    stale = {"params": {"mass_kg": 2.0}, "if_lesson_id": HEAVY_TOP_LESSON, "if_scene_id": "heavy-top"}
    answer = served.client.post(f"/api/rooms/{room_id}/state", json=stale, headers=instructor)
    assert answer.status_code == 409, answer.text
    assert FOUR_BAR_LESSON in answer.json()["detail"] and "nothing changed" in answer.json()["detail"]
    for also_stale in ({"playing": False, "if_scene_id": "heavy-top"}, {"mode": "explore", "if_lesson_id": HEAVY_TOP_LESSON, "if_scene_id": "four-bar"}):
        assert served.client.post(f"/api/rooms/{room_id}/state", json=also_stale, headers=instructor).status_code == 409
    after = state_of(served, room_id)
    assert (after["revision"], after["params"], after["playing"], after["mode"]) == (before["revision"], before["params"], True, "follow")

    with room_socket(served, room_id, instructor=True) as socket:
        messages_until(socket, lambda m: m["type"] == "state")
        socket.send(json.dumps({"type": "set_state", **stale}))
        refusal = messages_until(socket, lambda m: m["type"] == "error")
        assert refusal["status"] == 409 and refusal["action"] == "set_state" and FOUR_BAR_LESSON in refusal["detail"]
    assert state_of(served, room_id)["revision"] == before["revision"]

    current = {"playing": False, "if_lesson_id": FOUR_BAR_LESSON, "if_scene_id": "four-bar"}
    applied = served.client.post(f"/api/rooms/{room_id}/state", json=current, headers=instructor)
    assert applied.status_code == 200 and applied.json()["playing"] is False


# ---- joining is rate limited ----------------------------------------------------------------------------------------
def _join_from(app: ServedApp, code: str, address: str) -> httpx.Response:
    """One join from a new device at ``address`` (no cookie yet: a script, or a phone joining for the first time)."""
    with device(app, address) as phone:
        return phone.post("/api/rooms/join", json={"code": code, "name": ""})


def test_a_class_of_100_gets_in_at_once_but_one_address_cannot_fill_a_room(served):
    """Found 10: 498 joins in 3.9 s from one client filled a room to its 500 students. A class of 100 devices scanning
    the QR code together all get in; one address gets a burst, then 429 with Retry-After."""
    room = open_room(served)
    code, room_id = room["code"], room["room_id"]
    addresses = [device_address() for _ in range(100)]
    started = time.monotonic()
    with ThreadPoolExecutor(max_workers=20) as pool:
        class_answers = list(pool.map(lambda address: _join_from(served, code, address), addresses))
    took_s = time.monotonic() - started
    assert [a.status_code for a in class_answers].count(200) == 100, (took_s, {a.status_code for a in class_answers})
    assert took_s < 20.0

    # One client without a cookie (a script): a burst, then refused with Retry-After.
    script = device_address()
    attacker = [_join_from(served, code, script) for _ in range(40)]
    statuses = [a.status_code for a in attacker]
    granted = statuses.count(200)
    assert granted == Settings().join_burst or granted == Settings().join_burst + 1, statuses  # + 1: a token refilled meanwhile
    refused = next(a for a in attacker if a.status_code == 429)
    assert int(refused.headers["Retry-After"]) >= 1 and "try again" in refused.json()["detail"]
    assert state_of(served, room_id)["students"]["joined"] == 100 + granted

    # One device (its cookie) re-joining often is one student, and a few re-joins stay within its address's burst.
    with device(served) as phone:
        tokens = {phone.post("/api/rooms/join", json={"code": code, "name": ""}).json()["student_token"] for _ in range(5)}
    assert len(tokens) == 1
    served.client.delete(f"/api/rooms/{room_id}", headers=served.instructor_headers)


def test_a_flood_from_many_addresses_is_slowed_per_room(served):
    """Many addresses at once (a script rotating addresses): the room admits a lecture hall's burst of new students,
    then a few a second, whatever the addresses; its 429 says when to try again."""
    room = open_room(served)
    addresses = [device_address() for _ in range(400)]
    started = time.monotonic()
    with ThreadPoolExecutor(max_workers=20) as pool:
        answers = list(pool.map(lambda address: _join_from(served, room["code"], address), addresses))
    took_s = time.monotonic() - started
    statuses = [a.status_code for a in answers]
    granted = statuses.count(200)
    defaults = Settings()  # the served app runs with the defaults
    burst, rate = defaults.room_join_burst, defaults.room_join_rate_per_s
    assert burst >= 100, "a class of 100 at once is within the room's burst"
    assert burst <= granted <= burst + rate * took_s + 1, (granted, took_s)
    refused = next(a for a in answers if a.status_code == 429)
    assert int(refused.headers["Retry-After"]) >= 1
    assert state_of(served, room["room_id"])["students"]["joined"] == granted
    served.client.delete(f"/api/rooms/{room['room_id']}", headers=served.instructor_headers)


# ---- the instructor key never reaches a log -----------------------------------------------------------------------
def test_the_instructor_key_never_reaches_the_log():
    """Found 10: ``GET /instructor?key=…`` was written to uvicorn's access log. The served app logs at info level
    (access lines on); the instructor link, a mistyped key and a socket opened with the key leave no trace of it."""
    with ServedApp(name="log-redaction", args=("--log-level", "info")) as app:
        key = app.instructor_key
        assert httpx.get(app.instructor_link, follow_redirects=False).status_code == 303
        assert httpx.get(f"{app.url}/instructor", params={"key": key[:-1] + "X"}, follow_redirects=False).status_code == 403
        try:
            with websocket_connect(f"ws://127.0.0.1:{app.port}/api/rooms/{'0' * 16}/socket?key={key}", open_timeout=10):
                pass
        except Exception:
            pass  # no such room: closed; what matters is what the log says about it
        wait_until(lambda: app.log_path.read_text(errors="replace").count("/instructor?key") >= 2, timeout_s=10, what="both requests in the log")
        output = app.log_path.read_text(errors="replace")
    # dynlab serve prints the link on its console at start-up, on purpose (the served app's console is this file too);
    # everything else is the logging module's.
    printed = [line for line in output.splitlines() if line.startswith("Instructor link")]
    assert len(printed) == 1 and printed[0].endswith(f"/instructor?key={key}")
    log = "\n".join(line for line in output.splitlines() if not line.startswith("Instructor link"))
    assert key not in log and key[:-1] not in log, "the key (or nearly all of it) is in the log"
    assert re.search(r'"GET /instructor\?key=… HTTP/1\.1" 303', log), log[-2000:]


def test_a_number_poll_takes_json_numbers_only(served, room):
    """A number poll's answer is a JSON number: "1" and true were taken as numbers (an outside attack found it)."""
    phone = device(served)
    token = join(phone, room["code"])["student_token"]
    poll = served.client.post(
        f"/api/rooms/{room['room_id']}/polls", json={"question": "How fast?", "kind": "number", "unit": "rad/s"}, headers=served.instructor_headers
    ).json()
    answers_url = f"/api/rooms/{room['room_id']}/polls/{poll['poll_id']}/answers"
    for wrong in ("1", True):
        refused = phone.post(answers_url, json={"value": wrong}, headers={"X-Student-Token": token})
        assert refused.status_code == 422 and refused.json()["detail"][0]["loc"] == ["body", "value"], refused.text
    assert phone.post(answers_url, json={"value": 12}, headers={"X-Student-Token": token}).status_code == 200
    results = served.client.get(f"/api/rooms/{room['room_id']}/polls/{poll['poll_id']}/results", headers=served.instructor_headers).json()
    assert results["answers"] == 1


def test_a_change_to_a_room_deleted_behind_the_servers_back_is_409_and_the_room_stays_closed(served):
    """The room's row deleted while the server holds it (another server sharing the database closed it, or an
    operator's ``dynlab rooms delete``): the instructor's next change is refused as closed, 409, never a 500, and
    the room stays closed."""
    import sqlalchemy as sa

    from app.storage.database import sqlite_url

    room = open_room(served)
    engine = sa.create_engine(sqlite_url(served.data_dir), connect_args={"timeout": 30})
    with engine.begin() as connection:
        connection.execute(sa.text("DELETE FROM rooms WHERE room_id = :room_id"), {"room_id": room["room_id"]})
    engine.dispose()
    question = {"question": "Still there?", "kind": "choice", "choices": ["yes", "no"]}
    answer = served.client.post(f"/api/rooms/{room['room_id']}/polls", json=question, headers=served.instructor_headers)
    assert answer.status_code == 409 and "closed" in answer.json()["detail"]
    again = served.client.post(f"/api/rooms/{room['room_id']}/polls", json=question, headers=served.instructor_headers)
    assert again.status_code == 404  # and the server has let it go
