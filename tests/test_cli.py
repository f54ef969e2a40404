"""The command line: options reach the command they belong to."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from app import cli
from app.settings import default_worker_count
from tests.conftest import wait_until


def test_bench_options_reach_the_benchmark(monkeypatch):
    received = []
    monkeypatch.setattr("app.bench.work_precision.main", lambda args: received.append(list(args)) or 0)
    assert cli.main(["bench", "--quick", "--case", "heavy-top"]) == 0
    assert received == [["--quick", "--case", "heavy-top"]]


def test_warm_prepares_every_scenes_model_and_says_how_long_it_took(monkeypatch, capsys):
    from app.scenes import SCENES

    prepared = []
    monkeypatch.setattr("app.scenes.host.warm.warm_compiled_models", lambda scenes: prepared.append(set(scenes)))
    assert cli.main(["warm"]) == 0
    assert prepared == [set(SCENES)]
    out = capsys.readouterr().out
    assert f"{len(SCENES)} scenes ready: kernels compiled or loaded in " in out and "models prepared in " in out


def test_serve_refuses_an_unknown_option():
    with pytest.raises(SystemExit):
        cli.main(["serve", "--quick"])


def test_the_default_worker_count_is_the_cores_unless_set(monkeypatch):
    monkeypatch.delenv("DYNLAB_WORKERS", raising=False)
    monkeypatch.setattr("os.cpu_count", lambda: 6)
    assert default_worker_count() == 6
    monkeypatch.setenv("DYNLAB_WORKERS", "3")
    assert default_worker_count() == 3


def recording_server(served: list):
    """Stands in for the server ``dynlab serve`` runs: keeps the app it was given, serves nothing."""

    class Server:
        started = True

        def __init__(self, config) -> None:
            self.config = config

        def run(self) -> None:
            served.append(self.config.app)

    return Server


def test_serve_prints_the_instructor_link_with_the_key_given_or_the_kept_one(monkeypatch, capsys, tmp_path):
    """The link beside the address carries the secret: --instructor-key's, else the environment's, else the one kept
    in the data directory (made at its first start, the same at every start after, new after a rotation)."""
    monkeypatch.setenv("DYNLAB_DATA_DIR", str(tmp_path / "data"))
    served = []
    monkeypatch.setattr(cli, "_stopping_server_class", lambda on_stop: recording_server(served))
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
    assert first == second and len(first) >= 20  # made at the first start, kept
    assert f"/instructor?key={first}" in capsys.readouterr().out
    assert cli.main(["instructor-key", "--rotate"]) == 0
    assert "restart dynlab serve" in capsys.readouterr().out
    cli.main(["serve", "--workers", "0"])
    cli.main(["serve", "--workers", "0", "--data-dir", str(tmp_path / "other")])
    rotated, elsewhere = (app.state.instructor_key.secret for app in served[-2:])
    assert len({first, rotated, elsewhere}) == 3 and not served[-2].state.instructor_key.matches(first)
    with pytest.raises(ValueError, match="at least 12"):
        cli.main(["serve", "--workers", "0", "--instructor-key", "short"])


def test_a_lan_server_prints_links_students_can_reach(monkeypatch, capsys):
    monkeypatch.setattr(cli, "_stopping_server_class", lambda on_stop: recording_server([]))
    monkeypatch.setattr(cli, "lan_address", lambda: "10.1.2.3")
    monkeypatch.delenv("DYNLAB_PUBLIC_URL", raising=False)
    cli.main(["serve", "--workers", "0", "--host", "0.0.0.0", "--port", "8000", "--instructor-key", "chalk-and-talk-2026"])
    assert "http://10.1.2.3:8000/instructor?key=chalk-and-talk-2026" in capsys.readouterr().out


def test_a_stop_past_its_deadline_kills_the_workers_and_exits_whatever_still_waits(tmp_path):
    """The last guard on "Ctrl+C stops within 5 s": past the deadline a thread that would wait a minute (a call to a
    stopped worker, an executor's join at exit) is not waited for, and child processes are killed, not orphaned."""
    script = tmp_path / "hangs.py"
    script.write_text(
        "import multiprocessing, threading, time, sys\n"
        "from app.cli import _exit_by_deadline\n"
        "if __name__ == '__main__':\n"
        "    child = multiprocessing.get_context('spawn').Process(target=time.sleep, args=(60,))\n"
        "    child.start()\n"
        "    print(child.pid, flush=True)\n"
        "    _exit_by_deadline(0.5)\n"
        "    threading.Thread(target=time.sleep, args=(60,)).start()  # not a daemon: exit would wait for it\n"
    )
    started = time.monotonic()
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=30, cwd=Path(__file__).resolve().parents[1])
    assert time.monotonic() - started < 10.0 and done.returncode == 0, done.stderr
    child = int(done.stdout.split()[0])
    assert "still stopping after 0.5 s" in done.stderr
    wait_until(lambda: not Path(f"/proc/{child}").exists() or "Z" in Path(f"/proc/{child}/stat").read_text().split()[2], 5,
               what="the child to be killed")  # fmt: skip


def test_a_second_server_on_the_same_data_directory_is_refused(monkeypatch, capsys, tmp_path):
    """Two servers writing one SQLite file would each serve rooms the other changes: the second says so and exits."""
    from app.storage.database import DataDirLock

    served = []
    monkeypatch.setattr(cli, "_stopping_server_class", lambda on_stop: recording_server(served))
    monkeypatch.delenv("DYNLAB_INSTRUCTOR_KEY", raising=False)
    held = DataDirLock(tmp_path / "data")  # the first server
    try:
        assert cli.main(["serve", "--workers", "0", "--data-dir", str(tmp_path / "data")]) == 1
        refused = capsys.readouterr().err
        assert f"another dynlab serve (pid {os.getpid()}) keeps its data in {tmp_path / 'data'}" in refused
        assert served == []
    finally:
        held.release()
    assert cli.main(["serve", "--workers", "0", "--data-dir", str(tmp_path / "data")]) == 0  # stopped: free again
    assert cli.main(["serve", "--workers", "0", "--data-dir", str(tmp_path / "data")]) == 0  # and after that one


def test_the_kept_data_commands_say_what_is_wrong_in_one_line(monkeypatch, capsys, tmp_path):
    """A mistyped --data-dir, a file where the directory should be, a file that is not a database, an export onto a
    file, and a delete while a server holds the data: each is refused with one line, never a traceback."""
    from app.storage.database import DataDirLock

    monkeypatch.setattr(cli, "_stopping_server_class", lambda on_stop: recording_server([]))
    data = tmp_path / "data"
    assert cli.main(["rooms", "--data-dir", str(tmp_path / "typo")]) == 1
    assert f"no data directory at {tmp_path / 'typo'}" in capsys.readouterr().err and not (tmp_path / "typo").exists()
    (tmp_path / "a-file").write_text("not a directory")
    assert cli.main(["serve", "--workers", "0", "--instructor-key", "chalk-and-talk-2026", "--data-dir", str(tmp_path / "a-file")]) == 1
    assert "is a file, not a directory" in capsys.readouterr().err
    (tmp_path / "garbage").mkdir()
    (tmp_path / "garbage" / "dynlab.sqlite3").write_bytes(b"this is not a database" * 100)
    assert cli.main(["rooms", "--data-dir", str(tmp_path / "garbage")]) == 1
    assert "cannot be used" in capsys.readouterr().err
    assert cli.main(["serve", "--workers", "0", "--data-dir", str(data)]) == 0  # makes the data directory
    capsys.readouterr()
    assert cli.main(["export", "--out", str(tmp_path / "a-file"), "--data-dir", str(data)]) == 1
    assert "is a file" in capsys.readouterr().err
    from app.classroom.registry import Rooms
    from app.classroom.store import SqlRoomStore
    from app.storage import open_database
    from app.storage.database import sqlite_url

    room, _ = Rooms(store=SqlRoomStore(open_database(sqlite_url(data)))).create(join_base="http://127.0.0.1:8000")
    held = DataDirLock(data)  # a server running on it serves the room from its memory
    try:
        assert cli.main(["rooms", "delete", room.code, "--data-dir", str(data)]) == 1
        assert "Close the room from the instructor's page instead" in capsys.readouterr().err
    finally:
        held.release()
    assert cli.main(["rooms", "delete", room.code, "--data-dir", str(data)]) == 0
