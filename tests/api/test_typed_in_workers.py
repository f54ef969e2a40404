"""Found 1 of issue 24: lesson 7.5 "Type a Lagrangian" works on the default server, whose scenes run in workers.

The typed Lagrangian's derivation runs in a bounded child process (20 s, 1 GB); a daemonic scene worker may not
start children, so every PUT answered 500 and every start logged "warming typed-lagrangian failed".
"""

from __future__ import annotations

import secrets

from tests.api.conftest import live_viewer



def test_the_typed_lagrangian_scene_derives_in_a_worker_with_its_bounds(served, client):
    sid = "typed-" + secrets.token_hex(6)
    answer = client.put(f"/api/scenes/typed-lagrangian/sessions/{sid}", json={"params": {}}, headers={"X-Session-Key": secrets.token_hex(16)})
    assert answer.status_code == 200, answer.text
    assert answer.json()["params"]["coordinates"] == 2
    with live_viewer(client, "typed-lagrangian", sid):
        live = client.get(f"/api/scenes/typed-lagrangian/sessions/{sid}/live")
        assert live.status_code == 200 and live.json()["t_s"] >= 0.0
    # A bad expression is refused by the whitelisting parser, in the worker, naming the field.
    bad = client.put(f"/api/scenes/typed-lagrangian/sessions/{sid}-bad", json={"params": {"kinetic_energy": "__import__('os')"}})
    assert bad.status_code == 422 and bad.json()["detail"][0]["loc"][:3] == ["body", "params", "kinetic_energy"]
    assert "warming typed-lagrangian failed" not in served.log_path.read_text(errors="replace")
    assert "daemonic processes" not in served.log_path.read_text(errors="replace")


def test_a_room_can_show_the_typed_lagrangian(served):
    lessons = {lesson["id"] for chapter in served.client.get("/api/chapters").json() for lesson in chapter["lessons"]}
    lesson = next(l for l in lessons if "typed" in l)
    room = served.client.post("/api/rooms", json={"lesson_id": lesson, "scene_id": "typed-lagrangian"}, headers=served.instructor_headers)
    assert room.status_code == 200, room.text
    assert room.json()["state"]["scene_id"] == "typed-lagrangian"
    served.client.delete(f"/api/rooms/{room.json()['room_id']}", headers=served.instructor_headers)
