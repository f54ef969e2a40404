"""GET /api/health."""

from __future__ import annotations

from app import __version__


def test_health_reports_ok_and_the_version(client):
    response = client.get("/api/health")
    assert response.status_code == 200
    body = response.json()
    assert body == {"status": "ok", "version": __version__, "workers": [{"index": 0, "state": "answering"}, {"index": 1, "state": "answering"}]}
    assert isinstance(body["version"], str) and body["version"]
