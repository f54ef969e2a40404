"""The command line: options reach the command they belong to."""

from __future__ import annotations

import pytest

from app import cli


def test_bench_options_reach_the_benchmark(monkeypatch):
    received = []
    monkeypatch.setattr("app.bench.work_precision.main", lambda args: received.append(list(args)) or 0)
    assert cli.main(["bench", "--quick", "--case", "heavy-top"]) == 0
    assert received == [["--quick", "--case", "heavy-top"]]


def test_serve_refuses_an_unknown_option():
    with pytest.raises(SystemExit):
        cli.main(["serve", "--quick"])


def test_the_default_worker_count_is_the_cores_unless_set(monkeypatch):
    monkeypatch.delenv("DYNLAB_WORKERS", raising=False)
    monkeypatch.setattr("os.cpu_count", lambda: 6)
    assert cli.default_worker_count() == 6
    monkeypatch.setenv("DYNLAB_WORKERS", "3")
    assert cli.default_worker_count() == 3


def test_serve_prints_the_instructor_link_with_the_key_given_or_a_new_one(monkeypatch, capsys):
    """The link beside the address carries the secret: --instructor-key's, else the environment's, else a random one."""
    served = []
    monkeypatch.setattr("uvicorn.run", lambda app, **options: served.append(app))
    monkeypatch.delenv("DYNLAB_INSTRUCTOR_KEY", raising=False)
    assert cli.main(["serve", "--workers", "0", "--port", "8123", "--instructor-key", "chalk-and-talk-2026"]) == 0
    out = capsys.readouterr().out
    assert "http://127.0.0.1:8123/instructor?key=chalk-and-talk-2026" in out
    assert served[-1].state.instructor_key.matches("chalk-and-talk-2026")
    monkeypatch.setenv("DYNLAB_INSTRUCTOR_KEY", "from-the-environment")
    cli.main(["serve", "--workers", "0"])
    assert "/instructor?key=from-the-environment" in capsys.readouterr().out
    monkeypatch.delenv("DYNLAB_INSTRUCTOR_KEY")
    cli.main(["serve", "--workers", "0"])
    cli.main(["serve", "--workers", "0"])
    first, second = (app.state.instructor_key.secret for app in served[-2:])
    assert first != second and len(first) >= 20  # a new random secret each start
    with pytest.raises(ValueError, match="at least 12"):
        cli.main(["serve", "--workers", "0", "--instructor-key", "short"])


def test_a_lan_server_prints_links_students_can_reach(monkeypatch, capsys):
    monkeypatch.setattr("uvicorn.run", lambda app, **options: None)
    monkeypatch.setattr(cli, "lan_address", lambda: "10.1.2.3")
    monkeypatch.delenv("DYNLAB_PUBLIC_URL", raising=False)
    cli.main(["serve", "--workers", "0", "--host", "0.0.0.0", "--port", "8000", "--instructor-key", "chalk-and-talk-2026"])
    assert "http://10.1.2.3:8000/instructor?key=chalk-and-talk-2026" in capsys.readouterr().out
