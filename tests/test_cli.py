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
