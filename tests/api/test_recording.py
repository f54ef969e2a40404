"""GET /api/scenes/{scene_id}/sessions/{session_id}/recording.html: a file to save, or a clear refusal.

The file's content (length, frames, what is drawn) is checked in tests/scenes/host/test_recording.py; here the
route: an HTML attachment named after the scene, 404 for an unknown scene or a session without that scene, 422
for seconds outside 1–60 (or a file over the size limit, which the host reports as a ``seconds`` ValueError),
500 with the reason when the recording fails.
"""

from __future__ import annotations

import pytest

from app.scenes.host.recorder import RecordingError

SESSION = "api-recording-1"


def url(scene_id: str, session_id: str, query: str = "") -> str:
    return f"/api/scenes/{scene_id}/sessions/{session_id}/recording.html{query}"


@pytest.fixture
def four_bar_session(client) -> str:
    assert client.put(f"/api/scenes/four-bar/sessions/{SESSION}", json={"params": {}}).status_code == 200
    return SESSION


def test_a_recording_is_an_html_attachment_named_after_the_scene(client, four_bar_session):
    answer = client.get(url("four-bar", four_bar_session, "?seconds=5"))
    assert answer.status_code == 200
    assert answer.headers["content-type"].startswith("text/html")
    assert answer.headers["content-disposition"] == 'attachment; filename="four-bar-recording.html"'
    assert "window.__VISER_EMBED_DATA__=" in answer.text and "</html>" in answer.text
    assert client.get(url("four-bar", four_bar_session)).status_code == 200  # seconds defaults to 10


@pytest.mark.parametrize(("scene_id", "session_id"), [("no-such-scene", SESSION), ("heavy-top", SESSION), ("four-bar", "api-recording-nobody")])
def test_an_unknown_scene_or_a_session_without_it_is_404(client, four_bar_session, scene_id, session_id):
    answer = client.get(url(scene_id, session_id))
    assert answer.status_code == 404
    assert isinstance(answer.json()["detail"], str) and answer.json()["detail"]


@pytest.mark.parametrize("seconds", ["0", "0.5", "61", "nan", "inf", "ten"])
def test_seconds_outside_1_to_60_is_422_naming_it(client, four_bar_session, seconds):
    answer = client.get(url("four-bar", four_bar_session, f"?seconds={seconds}"))
    assert answer.status_code == 422
    assert answer.json()["detail"][0]["loc"] == ["query", "seconds"]


def test_a_malformed_session_id_is_422(client):
    assert client.get(url("four-bar", "bad id!")).status_code == 422


def test_a_file_over_the_limit_is_422_and_a_failed_recording_is_500_with_the_reason(inprocess_client, monkeypatch):
    client = inprocess_client  # the host's answers are replaced: the app in this process
    four_bar_session = SESSION
    assert client.put(f"/api/scenes/four-bar/sessions/{SESSION}", json={"params": {}}).status_code == 200
    host = client.app.state.scene_host

    def too_large(*args, **kwargs):
        raise ValueError("seconds: this recording would be 41 MB, over the 40 MB limit; record fewer seconds")

    monkeypatch.setattr(host, "recording_html", too_large)
    answer = client.get(url("four-bar", four_bar_session))
    assert answer.status_code == 422 and "record fewer seconds" in answer.json()["detail"][0]["msg"]

    def failing(*args, **kwargs):
        raise RecordingError("four-bar: the recording failed (RuntimeError: boom)")

    monkeypatch.setattr(host, "recording_html", failing)
    answer = client.get(url("four-bar", four_bar_session))
    assert answer.status_code == 500
    assert answer.json()["detail"] == "the recording could not be made: four-bar: the recording failed (RuntimeError: boom)"


def test_recordings_asked_for_all_at_once_are_made_or_refused_with_retry_after_never_500(served):
    """Found 11: 30 concurrent recording.html of one worker's sessions answered 15 × 500 "recorder is busy"."""
    import concurrent.futures
    import secrets

    students = [served.new_client() for _ in range(6)]
    sessions = []
    for student in students:
        sid = "rec-burst-" + secrets.token_hex(6)
        assert student.put(f"/api/scenes/four-bar/sessions/{sid}", json={"params": {}}).status_code == 200
        sessions.append((student, sid))

    def record(n: int):
        student, sid = sessions[n % len(sessions)]
        return student.get(url("four-bar", sid, "?seconds=5"))

    with concurrent.futures.ThreadPoolExecutor(30) as pool:
        answers = list(pool.map(record, range(30)))
    codes = sorted({a.status_code for a in answers})
    # Made, or "try again": the device's previous recording is still being made (429), or the worker's recorder is
    # busy with another device's (503); never a fault.
    assert set(codes) <= {200, 429, 503}, [(a.status_code, a.text[:200]) for a in answers if a.status_code not in (200, 429, 503)]
    assert 200 in codes
    for answer in answers:
        if answer.status_code in (429, 503):
            assert int(answer.headers["Retry-After"]) >= 1 and "recording" in answer.json()["detail"]
    for student in students:
        student.close()
