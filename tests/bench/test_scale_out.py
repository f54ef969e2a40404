"""Several machines, one class, on loopback (issue 26, point 6): PostgreSQL, two ``dynlab serve`` as the README
starts them (with their scene workers) and HAProxy with deploy/haproxy.cfg. An instructor and 30 students (half on
each server) run a room: they follow it, the instructor changes the spin ten times, a poll is answered; then the
room's server is killed and every student is back in the same room with the same state, and a lesson page's claimed
scene that lived there comes back on the other server with its parameters and its claim (``dynlab scale-out``, whose
committed report is docs/bench/scale_out.json)."""

from __future__ import annotations

import json

import pytest

from app.bench.scale_out import haproxy_binary, main

#: The issue's bounds: a change reaches every student within 200 ms; the class is back within 10 s of the kill.
FOLLOW_LATENCY_MS = 200.0
FAILOVER_S = 10.0


@pytest.mark.skipif(haproxy_binary() is None, reason="HAProxy is not installed: tests/run.sh installs it")
def test_one_class_on_two_servers_follows_answers_and_survives_losing_one(tmp_path, capsys):
    assert main(["--students", "30", "--changes", "10", "--out-dir", str(tmp_path)]) == 0
    report = json.loads((tmp_path / "scale_out.json").read_text())
    # Joining through the balancer's round robin, students arrived on both servers: each took the room up.
    assert sorted(report["students_joined_on"].values()) != [0, 30]
    # The instructor's list counts every student as connected and following, whichever server their page is on.
    assert report["instructor_sees_everyone_s"] is not None
    latency = report["follow_latency_ms"]
    assert latency["samples"] == 300  # every change reached every student's socket (else main raised)
    # The median on each server is held to the bound here, where other tests share the two cores; the committed
    # report (an idle machine) holds its 99th percentile and maximum to it too.
    assert latency["median_on_room_server"] < FOLLOW_LATENCY_MS
    assert latency["median_on_other_server"] < FOLLOW_LATENCY_MS
    assert report["poll_answers_seen_by_instructor"] is True
    assert report["failover_s"] is not None and report["failover_s"] < FAILOVER_S
    after = report["state_after_failover"]
    assert after["same"] is True and after["server"] != report["room_server"]
    assert after["students_reconnected"] == 15  # the room server's half came back through the balancer
    session = report["page_session_after_failover"]  # a lesson page's own scene, claimed, on the killed server
    assert session["server"] != report["room_server"] and session["params_kept"] is True
    assert session["keyless_change"] == 403  # its claim holds on the server that took it up
    assert (tmp_path / "scale_out.svg").read_text().startswith("<svg")
    assert "failover" in capsys.readouterr().out
