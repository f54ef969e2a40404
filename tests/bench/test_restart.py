"""``dynlab restart`` on a tiny class: it starts its own server, restarts it under three followers with a poll
answered, finds everything kept, measures each part coming back, and writes its report and plot."""

from __future__ import annotations

import json

from app.bench.restart import main


def test_a_tiny_restart_run_finds_the_class_kept_and_writes_its_report(tmp_path, capsys):
    assert main(["--students", "3", "--restarts", "1", "--workers", "1", "--out", str(tmp_path)]) == 0
    report = json.loads((tmp_path / "restart.json").read_text())
    assert report["lost_nothing"] is True and report["students"] == 3
    (restart,) = report["restarts"]
    assert restart["followers_back"] == 3
    assert 0 < restart["health_s"] <= restart["state_s"] <= 90 and restart["follower_back_last_s"] <= 90
    assert restart["stop_s"] is not None and restart["stop_s"] < 5.0  # Ctrl+C stops it within 5 s
    svg = (tmp_path / "restart.svg").read_text()
    assert svg.startswith("<svg") and "restart 1" in svg and "3 followers" in svg
    assert "lost nothing: True" in capsys.readouterr().out
