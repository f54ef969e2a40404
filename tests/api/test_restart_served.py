"""Issue 26, point 3: a restart of ``dynlab serve`` loses nothing of a class.

A served app with its own data directory and no instructor key given (so it makes and keeps one) runs a room: a
scene with changed parameters, paused at half speed, two students (one named), a follower's viewer, a poll with their
answers. It is stopped with Ctrl+C and started again on the same port and data directory, as an instructor whose
laptop restarted would. Then the instructor's printed link, cookie and key still work; the room, its state, its
students, its poll and its answers are there; a student's kept token answers again and their device re-joins as the
same student; the follower's viewer is back on the room's scene; the shared scene has its parameters and play state.
How long the class waited (from Ctrl+C until the room's state and its scene answer again) is printed.
"""

from __future__ import annotations

import shutil
import time

import httpx

from tests.conftest import wait_until
from tests.served import RESULTS, ServedApp, Viewer

LESSON = "10-2-spinning-top"
#: A lesson page's session id and the key its page claims it with (the page makes both with crypto.getRandomValues).
SOLO_SESSION = "5e55107e" * 4
SOLO_KEY = "0123456789abcdef" * 2


def instructor(app: ServedApp, link: str) -> httpx.Client:
    """A browser that opened the instructor link (it holds the cookie the link sets)."""
    client = httpx.Client(base_url=app.url, timeout=30.0)
    client.get(link.removeprefix(app.url), follow_redirects=True).raise_for_status()
    assert client.get("/api/me").json() == {"role": "instructor"}
    return client


def test_a_restart_keeps_the_instructor_the_room_its_students_poll_answers_and_scene(tmp_path):
    data_dir = RESULTS / f"data-restart-{tmp_path.name}"
    first = ServedApp(name="restart-before", data_dir=data_dir, env={"DYNLAB_INSTRUCTOR_KEY": ""}).start()
    try:
        link = first.printed_instructor_link()
        teacher = instructor(first, link)
        room = teacher.post("/api/rooms", json={"lesson_id": LESSON}).json()
        room_id, code = room["room_id"], room["code"]
        changed = teacher.post(f"/api/rooms/{room_id}/state", json={"params": {"spin_rad_s": 77.0}, "playing": False, "time_scale": 0.5})
        assert changed.status_code == 200, changed.text
        ada, ben = first.new_client(), first.new_client()
        joined = {name: phone.post("/api/rooms/join", json={"code": code, "name": name}).json() for name, phone in (("Ada", ada), ("", ben))}
        poll = teacher.post(f"/api/rooms/{room_id}/polls", json={"question": "Which way does it precess?", "kind": "choice", "choices": ["left", "right"]}).json()
        for (name, phone), choice in zip((("Ada", ada), ("", ben)), (0, 1)):
            answered = phone.post(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers", json={"choice": choice}, headers={"X-Student-Token": joined[name]["student_token"]})
            assert answered.status_code == 200, answered.text
        results_before = teacher.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results").json()
        state_before = teacher.get(f"/api/rooms/{room_id}/state").json()
        follower = Viewer(first, f"/room-viewer/{room_id}", address=ada.address)
        wait_until(lambda: follower.frames > 0, timeout_s=30, what="the follower's first frame")
        # A student working alone: their lesson page's own scene, claimed by its key, with a parameter changed.
        solo = ben.put(f"/api/scenes/heavy-top/sessions/{SOLO_SESSION}", json={"params": {"spin_rad_s": 66.0}}, headers={"X-Session-Key": SOLO_KEY})
        assert solo.status_code == 200, solo.text
    finally:
        stopped_at = time.monotonic()
        first.stop()

    second = ServedApp(name="restart-after", data_dir=data_dir, env={"DYNLAB_INSTRUCTOR_KEY": ""}, port=first.port).start()
    try:
        # The class is back once the room's state answers and its scene plays (or holds) for its follower again.
        connections = follower.connections
        wait_until(lambda: follower.connections > connections and time.monotonic() - follower.last_frame_s < 1.0, timeout_s=60, what="the follower's viewer to be back on the room's scene")
        waited_s = time.monotonic() - stopped_at
        print(f"the class waited {waited_s:.1f} s from Ctrl+C to the room's scene reaching its follower again")

        assert second.printed_instructor_link() == link
        for client in (teacher, instructor(second, link)):  # the cookie from before, and the link opened again
            assert client.get("/api/me").json() == {"role": "instructor"}
        assert second.client.get("/api/me", headers={"X-Instructor-Key": link.rsplit("=", 1)[1]}).json() == {"role": "instructor"}

        state = teacher.get(f"/api/rooms/{room_id}/state").json()
        for name in ("code", "lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "poll"):
            assert state[name] == state_before[name], name
        assert state["students"]["joined"] == 2 and state["revision"] > state_before["revision"]
        assert teacher.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results").json() == results_before
        students = teacher.get(f"/api/rooms/{room_id}/students").json()["students"]
        assert [s["name"] for s in students] == ["Ada", ""]

        playback = second.client.get(f"/api/scenes/heavy-top/sessions/room-{room_id}/playback").json()
        assert playback["playing"] is False and playback["time_scale"] == 0.5

        # Ada's page kept her token: she changes her answer. Ben's device joins again: the same student.
        changed = ada.post(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers", json={"choice": 1}, headers={"X-Student-Token": joined["Ada"]["student_token"]})
        assert changed.status_code == 200, changed.text
        again = ben.post("/api/rooms/join", json={"code": code}).json()
        assert again["student_id"] == joined[""]["student_id"]
        histogram = teacher.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results").json()["histogram"]
        assert [bar["count"] for bar in histogram] == [0, 2]
        assert teacher.get(f"/api/rooms/{room_id}/state").json()["students"]["joined"] == 2

        # The solo page's scene is back as it was when its viewer reconnects, and still refuses a keyless change.
        solo_viewer = Viewer(second, f"/viewer/heavy-top/{SOLO_SESSION}", address=ben.address)
        try:
            wait_until(lambda: solo_viewer.frames > 0, timeout_s=30, what="the solo page's viewer to reconnect")
        finally:
            solo_viewer.close()
        assert ben.get(f"/api/scenes/heavy-top/sessions/{SOLO_SESSION}").json()["params"]["spin_rad_s"] == 66.0
        keyless = ada.put(f"/api/scenes/heavy-top/sessions/{SOLO_SESSION}", json={"params": {"spin_rad_s": 5.0}})
        assert keyless.status_code == 403, keyless.text
        wrong = ada.put(f"/api/scenes/heavy-top/sessions/{SOLO_SESSION}", json={"params": {"spin_rad_s": 5.0}}, headers={"X-Session-Key": "k" * 32})
        assert wrong.status_code == 403, wrong.text
        owner = ben.put(f"/api/scenes/heavy-top/sessions/{SOLO_SESSION}", json={"params": {"spin_rad_s": 70.0}}, headers={"X-Session-Key": SOLO_KEY})
        assert owner.status_code == 200 and owner.json()["params"]["spin_rad_s"] == 70.0
    finally:
        follower.close()
        second.stop()
        for client in (teacher, ada, ben):
            client.close()
        shutil.rmtree(data_dir, ignore_errors=True)
