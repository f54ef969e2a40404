"""A session belongs to the page that claimed it: without its key nobody else can change it."""

from __future__ import annotations

import secrets

import pytest

from app.api.session_keys import SessionKeyError, SessionKeys


def new_session() -> str:
    return "keys-" + secrets.token_hex(8)


def put(client, session_id: str, params: dict, key: str | None = None):
    headers = {"X-Session-Key": key} if key is not None else {}
    return client.put(f"/api/scenes/heavy-top/sessions/{session_id}", json={"params": params}, headers=headers)


def test_a_claimed_session_refuses_changes_without_its_key_and_keeps_its_values(client):
    sid, owner_key = new_session(), secrets.token_hex(16)
    assert put(client, sid, {"spin_rad_s": 80.0}, owner_key).status_code == 200
    for intruder_key in (None, secrets.token_hex(16)):
        refused = put(client, sid, {"spin_rad_s": 5.0}, intruder_key)
        assert refused.status_code == 403 and "belongs to another page" in refused.json()["detail"]
    kept = put(client, sid, {}, owner_key)
    assert kept.status_code == 200 and kept.json()["params"]["spin_rad_s"] == 80.0


def test_an_unclaimed_session_stays_open_to_keyless_changes(client):
    sid = new_session()
    assert put(client, sid, {"spin_rad_s": 70.0}).status_code == 200
    assert put(client, sid, {"spin_rad_s": 71.0}).json()["params"]["spin_rad_s"] == 71.0


def test_a_refused_change_does_not_claim_the_session(client):
    sid = new_session()
    assert put(client, sid, {"mass_kg": -1.0}, secrets.token_hex(16)).status_code == 422
    assert put(client, sid, {"spin_rad_s": 70.0}).status_code == 200  # still unclaimed


@pytest.mark.parametrize("bad_key", ["short", "x" * 129, "has space in it 0123", "bad!key-0123456789abcdef"])
def test_a_malformed_key_is_a_422_naming_the_header(client, bad_key):
    response = client.put(
        f"/api/scenes/heavy-top/sessions/{new_session()}", json={"params": {}}, headers={"X-Session-Key": bad_key}
    )
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["header", "X-Session-Key"]


def test_the_store_is_bounded_and_keeps_only_hashes():
    keys = SessionKeys(max_sessions=3)
    for n in range(5):
        keys.claim(f"session-{n}", f"key-{n:0>16}")
    assert [keys.is_claimed(f"session-{n}") for n in range(5)] == [False, False, True, True, True]
    assert all(isinstance(h, bytes) and len(h) == 32 for h in keys._hashes.values())
    keys.check("session-4", f"key-{4:0>16}")
    with pytest.raises(SessionKeyError):
        keys.check("session-4", f"key-{3:0>16}")
