"""Command line: ``dynlab serve [--host H] [--port P]``, ``dynlab warm``, ``dynlab bench [--quick] [--case C]``,
``dynlab load [--students 10,30] [--scene ID] [--room | --attack]``, ``dynlab soak [--students N] [--minutes M]``,
``dynlab restart [--students N] [--restarts K]``, ``dynlab scale-out [--students N] [--changes K]``,
``dynlab derivations [--no-proofs]``, ``dynlab constrained [--quick] [--case C]``, and for the kept data
``dynlab rooms [delete ID|CODE]``, ``dynlab export [ID|CODE] [--out DIR]``, ``dynlab instructor-key --rotate``."""

from __future__ import annotations

import argparse
import contextlib
import faulthandler
import io
import logging
import os
import signal
import sys
from collections.abc import Callable
from dataclasses import replace
from datetime import UTC
from pathlib import Path
from typing import TYPE_CHECKING

from app.settings import Settings, default_worker_count

if TYPE_CHECKING:
    from app.classroom.store import SqlRoomStore
    from app.storage import Database

#: Ctrl+C ends ``dynlab serve`` within this long (s) whatever is in flight: requests get 1.5 s, the scene workers
#: up to 3 s more (app/scenes/host/pool.py); anything still holding the process then (a thread blocked on a stopped
#: worker, an executor's join) is not waited for: the workers are killed and the process exits.
EXIT_DEADLINE_S = 4.5
#: Once the server has stopped (its requests answered, its workers stopped, its database closed), Python's own exit
#: gets this long (s): it joins every thread and child process still alive, and a bounded child killed in the idle
#: class dies only when a busy machine gives it a processor (beside the test suite that took 2 s of Ctrl+C's 5).
AFTER_STOP_EXIT_S = 0.5


def _exit_by_deadline(deadline_s: float, *, warn: bool = True) -> None:
    """From now on, the process exits within ``deadline_s`` even if something in it would wait longer (saying so in
    the log if ``warn``)."""
    import multiprocessing
    import threading

    def force() -> None:
        if warn:
            logging.getLogger(__name__).warning(
                "still stopping after %.1f s: its child processes are killed and the server exits", deadline_s
            )
        for child in multiprocessing.active_children():
            child.kill()
        logging.shutdown()
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0)

    timer = threading.Timer(deadline_s, force)
    timer.daemon = True
    timer.start()


def _stopping_server_class(on_stop: Callable[[], None]):
    import uvicorn

    class StoppingServer(uvicorn.Server):
        """uvicorn's server, with a deadline on stopping (:data:`EXIT_DEADLINE_S`) from the first Ctrl+C or SIGTERM,
        when ``on_stop`` is called first (the requests still waiting get their answer), and another on the process's
        exit once it has stopped (:data:`AFTER_STOP_EXIT_S`)."""

        def handle_exit(self, sig: int, frame: object) -> None:
            if not self.should_exit:
                _exit_by_deadline(EXIT_DEADLINE_S)
                on_stop()
            super().handle_exit(sig, frame)  # type: ignore[arg-type]

        def run(self, sockets: list | None = None) -> None:
            try:
                super().run(sockets)
            finally:
                if self.started:  # stopped, its state kept: the rest of Python's exit is not waited for long
                    _exit_by_deadline(AFTER_STOP_EXIT_S, warn=False)

    return StoppingServer


def _serve(args: argparse.Namespace) -> int:
    from app.storage.database import DataDirInUse, DataDirLock

    workers = args.workers if args.workers is not None else default_worker_count()
    settings = _kept_settings(args, host=args.host, port=args.port, workers=workers, instructor_key=args.instructor_key)
    try:  # one server per data directory (a database server, DYNLAB_DATABASE_URL, takes several)
        lock = DataDirLock(settings.data_dir) if settings.data_dir is not None and not settings.database_url else None
    except DataDirInUse as exc:
        print(f"dynlab serve: {exc}", file=sys.stderr)
        return 1
    try:
        return _serve_with(settings, args)
    finally:
        if lock is not None:
            lock.release()


def _serve_with(settings: Settings, args: argparse.Namespace) -> int:
    import uvicorn

    from app.main import create_app
    from app.physics.core.bounded import stop_all_work
    from app.scenes.host.worker import tune_garbage_collection

    if not settings.public_url and settings.host in ("0.0.0.0", "::"):
        settings = replace(settings, public_url=f"http://{lan_address()}:{settings.port}")
    app = create_app(settings)
    from app.web import log_redaction

    log_redaction.install(app.state.instructor_key.secret)  # no log line carries the key (uvicorn's access log would)
    tune_garbage_collection()  # the front relays every frame of every viewer: the same allocation pattern as a worker
    where = (
        f"{settings.workers} scene worker{'s' if settings.workers != 1 else ''}"
        if settings.workers
        else "scenes in this process"
    )
    print(f"Dynamics Lab: serving on http://{settings.host}:{settings.port}  ({where}; Ctrl+C to stop)", flush=True)
    print(f"Rooms, polls, answers and the instructor's secret are kept in {app.state.database.url}", flush=True)
    base = settings.public_url or f"http://{settings.host}:{settings.port}"
    print(
        "Instructor link (keep it to yourself: whoever opens it runs the rooms): "
        f"{app.state.instructor_key.link(base)}",
        flush=True,
    )
    from app.web.slow_clients import GuardedHttpProtocol

    # Behind a reverse proxy every connection comes from the proxy: per-address connection caps belong to it there.
    http_protocol = type(
        "ServedHttpProtocol", (GuardedHttpProtocol,), {"cap_connections": not settings.trust_forwarded_for}
    )
    # `kill -USR1 <pid>` writes every thread's stack to the log: what a server that will not stop is waiting for.
    with contextlib.suppress(AttributeError, ValueError, io.UnsupportedOperation):  # a stderr with no file (tests)
        faulthandler.register(signal.SIGUSR1, all_threads=True)
    config = uvicorn.Config(
        app,
        host=settings.host,
        port=settings.port,
        log_level=args.log_level,
        http=http_protocol,
        # Ctrl+C: requests in flight get 1.5 s to finish, then the scene workers are stopped (app/scenes/host/pool.py);
        # the server exits within EXIT_DEADLINE_S whatever is in flight.
        timeout_graceful_shutdown=1.5,  # type: ignore[arg-type]  # annotated int, but asyncio.wait_for takes a float
        # A viewer sends only camera and GUI messages (< 1 kB); scene data is already zstd-compressed by viser,
        # so per-message deflate would spend CPU on every frame of every student for nothing.
        ws_max_size=1024 * 1024,
        ws_per_message_deflate=False,
        # Rate limits key on the client's address; only the guard may take it from X-Forwarded-For
        # (trust_forwarded_for).
        proxy_headers=False,
    )

    def on_stop() -> None:
        stop_all_work()  # a derivation in flight ends now: its request is answered before uvicorn's deadline
        app.state.requests_in_flight.stop()  # every request still waiting gets a 503 with Retry-After, not a 500

    server = _stopping_server_class(on_stop)(config)
    try:
        server.run()
    except KeyboardInterrupt:  # uvicorn raises the captured Ctrl+C again once it has stopped
        pass
    return 0 if server.started else 3  # 3: it never started (uvicorn's STARTUP_FAILURE: a port in use, …)


def lan_address() -> str:
    """This machine's address on the local network (the one its default route leaves by); 127.0.0.1 if none.

    No packet is sent: connecting a UDP socket only chooses the interface.
    """
    import socket

    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect(("10.255.255.255", 1))
            return probe.getsockname()[0]
        except OSError:
            return "127.0.0.1"


def _bench(args: argparse.Namespace) -> int:
    from app.bench.work_precision import main as bench_main

    return bench_main(args.bench_args)


def _derivations(args: argparse.Namespace) -> int:
    from app.bench.derivations import main as derivations_main

    return derivations_main(args.bench_args)


def _constrained(args: argparse.Namespace) -> int:
    from app.bench.constrained_precision import main as constrained_main

    return constrained_main(args.bench_args)


def _load(args: argparse.Namespace) -> int:
    from app.bench.capacity import add_load_arguments, run_load_command

    parser = argparse.ArgumentParser(prog="dynlab load", description=_OWN_OPTIONS["load"][1])
    add_load_arguments(parser)
    return run_load_command(parser.parse_args(args.bench_args), parser)


def _soak(args: argparse.Namespace) -> int:
    from app.bench.soak import add_soak_arguments, run_soak_command

    parser = argparse.ArgumentParser(prog="dynlab soak", description=_OWN_OPTIONS["soak"][1])
    add_soak_arguments(parser)
    return run_soak_command(parser.parse_args(args.bench_args), parser)


def _restart(args: argparse.Namespace) -> int:
    from app.bench.restart import main as run_restart

    return run_restart(args.bench_args)


def _warm(args: argparse.Namespace) -> int:
    import time

    print("dynlab warm: compiling every scene's kernels and deriving its equations into the disk caches…", flush=True)
    started = time.perf_counter()
    from app.scenes.host.warm import warm_caches  # imports every scene: their kernels compile (or load) here

    warmed = warm_caches(started=started)
    print(
        f"dynlab warm: {warmed.scenes} scenes ready: kernels compiled or loaded in {warmed.import_s:.1f} s, "
        f"models prepared in {warmed.models_s:.1f} s"
    )
    return 0


def _scale_out(args: argparse.Namespace) -> int:
    from app.bench.scale_out import main as run_scale_out

    return run_scale_out(args.bench_args)


#: Commands that parse their own options: name → (runner, help, help of the options). Each runner imports its tool
#: (app.bench) only when it runs: nothing else of the app imports the tools.
_OWN_OPTIONS = {
    "bench": (
        _bench,
        "measure speed against error (writes docs/bench/work_precision.json and plots)",
        "options of the benchmark (see dynlab bench --help)",
    ),
    "derivations": (
        _derivations,
        "derivation engine: derive and compile times, agreement, proofs (writes docs/bench/derivations.json and .svg)",
        "options (see dynlab derivations --help)",
    ),
    "constrained": (
        _constrained,
        "work-precision of the DAE algorithms and scipy Radau/BDF (writes docs/bench/constrained_precision.json "
        "and .svg)",
        "options (see dynlab constrained --help)",
    ),
    "load": (
        _load,
        "classroom capacity: N viewers per scene, with --room N followers of one room, with --attack 100 "
        "students before and while one client attacks (writes docs/bench/capacity.json, classroom.json or "
        "attack.json, and .svg)",
        "options (see dynlab load --help)",
    ),
    "soak": (
        _soak,
        "N viewers for M minutes, then all gone: resources back to baseline",
        "options (see dynlab soak --help)",
    ),
    "restart": (
        _restart,
        "dynlab serve restarted under a class: how long it waits, and that it loses nothing (docs/bench/restart.json)",
        "options (see dynlab restart --help)",
    ),
    "scale-out": (
        _scale_out,
        "one class on two dynlab serve behind HAProxy on PostgreSQL, on loopback: cross-server follow latency and "
        "failover time (docs/bench/scale_out.json)",
        "options (see dynlab scale-out --help)",
    ),
}


def _kept_settings(args: argparse.Namespace, **overrides: object) -> Settings:
    """The environment's settings with the command's options; the class's data is always kept by the commands
    (``--data-dir``, else ``DYNLAB_DATA_DIR`` or ``DYNLAB_DATABASE_URL``, else the per-user default)."""
    from app.storage import default_data_dir

    settings = Settings.from_env(data_dir=getattr(args, "data_dir", None), **overrides)
    if settings.data_dir is None and not settings.database_url:
        settings = replace(settings, data_dir=default_data_dir())
    return settings


def _kept_database(args: argparse.Namespace) -> Database:
    """The database a server keeps its class's data in, for the commands that read or change it. A data directory
    that does not exist is refused (a mistyped --data-dir would otherwise show an empty database just made)."""
    from app.storage import open_database
    from app.storage.database import DatabaseUnusable

    settings = _kept_settings(args)
    if not settings.database_url and settings.data_dir is not None and not settings.data_dir.is_dir():
        raise DatabaseUnusable(f"no data directory at {settings.data_dir}: give the --data-dir a server used")
    url = settings.kept_database_url()
    assert url is not None
    return open_database(url)


def _kept_store(args: argparse.Namespace) -> SqlRoomStore:
    from app.classroom.store import SqlRoomStore

    return SqlRoomStore(_kept_database(args))


def _rooms(args: argparse.Namespace) -> int:
    """``dynlab rooms``: the kept rooms; ``dynlab rooms delete ID|CODE``: forget one with all its answers."""
    store = _kept_store(args)
    kept = store.listing()
    if args.action == "delete":
        wanted = args.room.strip()
        if not wanted:
            print("dynlab rooms delete ID|CODE: name the room (dynlab rooms lists them)", file=sys.stderr)
            return 2
        found = next((r for r in kept if wanted in (r["room_id"], r["code"], r["code"].lower())), None)
        if found is None:
            print(f"no kept room has the id or code {wanted!r} (dynlab rooms lists them)", file=sys.stderr)
            return 1
        from app.storage.database import DataDirInUse, DataDirLock

        data_dir = _kept_settings(args).data_dir
        try:  # a running server serves its rooms from memory and would write this one back: it must be stopped
            lock = DataDirLock(data_dir) if data_dir is not None and not _kept_settings(args).database_url else None
        except DataDirInUse as exc:
            print(
                f"dynlab rooms delete: {exc}. Close the room from the instructor's page instead (that forgets it too)",
                file=sys.stderr,
            )
            return 1
        try:
            store.delete(found["room_id"])
        finally:
            if lock is not None:
                lock.release()
        print(f"deleted room {found['code']} ({found['room_id']}) with its {found['answers']} answers")
        return 0
    if not kept:
        print(f"no rooms kept in {store.database.url}")
        return 0
    print(f"{len(kept)} room{'s' if len(kept) != 1 else ''} kept in {store.database.url}:")
    print(f"{'code':<8}{'room id':<18}{'lesson':<34}{'students':>9}{'polls':>6}{'answers':>8}  last used (UTC)")
    for r in kept:
        used_at = r["used_at"]  # naive UTC from SQLite, aware from PostgreSQL
        used = (used_at.astimezone(UTC) if used_at.tzinfo else used_at).strftime("%Y-%m-%d %H:%M")
        print(
            f"{r['code']:<8}{r['room_id']:<18}{(r['lesson_id'] or '-'):<34}{r['students']:>9}{r['polls']:>6}"
            f"{r['answers']:>8}  {used}"
        )
    return 0


def _export(args: argparse.Namespace) -> int:
    """``dynlab export [ROOM] [--out DIR]``: a room's data (or every kept room's) as JSON and CSV files."""
    from app.classroom.export import export_rooms

    store = _kept_store(args)
    kept = store.load()
    wanted = args.room.strip()
    if wanted:
        kept = [room for room in kept if wanted in (room.room_id, room.code, room.code.lower())]
        if not kept:
            print(f"no kept room has the id or code {wanted!r} (dynlab rooms lists them)", file=sys.stderr)
            return 1
    if args.out.exists() and not args.out.is_dir():
        print(f"dynlab export: {args.out} is a file; --out names a folder to write into", file=sys.stderr)
        return 1
    try:
        written = export_rooms(kept, args.out)
    except OSError as exc:
        print(f"dynlab export: cannot write into {args.out}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    print(f"wrote {len(written)} files for {len(kept)} room{'s' if len(kept) != 1 else ''} into {args.out}")
    return 0


def _instructor_key(args: argparse.Namespace) -> int:
    """``dynlab instructor-key --rotate``: a new kept instructor secret (the server takes it at its next start)."""
    from app.classroom.roles import rotate_instructor_secret

    database = _kept_database(args)
    if not args.rotate:
        print("dynlab serve prints the instructor link; --rotate makes a new secret (the old link stops working)")
        return 0
    secret = rotate_instructor_secret(database)
    print(f"new instructor secret kept in {database.url}; restart dynlab serve, then open its new instructor link")
    print(f"(…/instructor?key={secret})")
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if (
        argv[:1] and argv[0] in _OWN_OPTIONS
    ):  # these parse their own options (argparse's REMAINDER refuses a leading --option)
        return _OWN_OPTIONS[argv[0]][0](argparse.Namespace(bench_args=argv[1:]))
    parser = argparse.ArgumentParser(prog="dynlab", description="Dynamics Lab: interactive engineering dynamics.")
    commands = parser.add_subparsers(dest="command", required=True)
    serve = commands.add_parser("serve", help="run the web application")
    serve.add_argument(
        "--host", default=None, help="interface to bind (default 127.0.0.1; 0.0.0.0 for a classroom LAN)"
    )
    serve.add_argument("--port", type=int, default=None, help="port (default 8000)")
    serve.add_argument(
        "--workers",
        type=int,
        default=None,
        help=(
            "scene-worker processes (default: one per core, or DYNLAB_WORKERS); 0 runs the scenes in the front process"
        ),
    )
    serve.add_argument(
        "--instructor-key",
        default=None,
        help=(
            "the instructor's secret in the printed instructor link (default: DYNLAB_INSTRUCTOR_KEY, else the one "
            "kept in the data directory, made on the first start)"
        ),
    )
    serve.add_argument("--log-level", default="info", choices=["critical", "error", "warning", "info", "debug"])
    data_dir_help = (
        "where the class's data is kept (default: DYNLAB_DATA_DIR, else $XDG_DATA_HOME/dynlab or "
        "~/.local/share/dynlab; DYNLAB_DATABASE_URL names another database instead)"
    )
    serve.add_argument("--data-dir", type=Path, default=None, help=data_dir_help)
    serve.set_defaults(run=_serve)
    rooms = commands.add_parser("rooms", help="list the kept rooms, or delete one with all its answers")
    rooms.add_argument("action", nargs="?", choices=["list", "delete"], default="list")
    rooms.add_argument("room", nargs="?", default="", help="the room's id or code (for delete)")
    rooms.add_argument("--data-dir", type=Path, default=None, help=data_dir_help)
    rooms.set_defaults(run=_rooms)
    export = commands.add_parser("export", help="write a kept room's data (or every room's) as JSON and CSV files")
    export.add_argument("room", nargs="?", default="", help="the room's id or code (default: every kept room)")
    export.add_argument(
        "--out", type=Path, default=Path("dynlab-export"), help="folder to write (default ./dynlab-export)"
    )
    export.add_argument("--data-dir", type=Path, default=None, help=data_dir_help)
    export.set_defaults(run=_export)
    warm = commands.add_parser(
        "warm",
        help=(
            "compile every scene's numba kernels and derive its equations into the disk caches, so that the first "
            "server start and the first student do not wait for them (run once after installing)"
        ),
    )
    warm.set_defaults(run=_warm)
    key = commands.add_parser("instructor-key", help="rotate the kept instructor secret (--rotate)")
    key.add_argument("--rotate", action="store_true", help="make and keep a new secret; the old link stops working")
    key.add_argument("--data-dir", type=Path, default=None, help=data_dir_help)
    key.set_defaults(run=_instructor_key)
    for name, (run, help_text, options_help) in _OWN_OPTIONS.items():
        command = commands.add_parser(name, help=help_text, add_help=False)
        command.add_argument("bench_args", nargs=argparse.REMAINDER, help=options_help)
        command.set_defaults(run=run)
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=getattr(logging, getattr(args, "log_level", "warning").upper()),
        format="%(levelname)s %(name)s: %(message)s",
    )
    from app.storage.database import DatabaseUnusable

    try:
        return args.run(args)
    except DatabaseUnusable as exc:  # the data directory or its database: one line saying why, not a traceback
        print(f"dynlab {args.command}: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
