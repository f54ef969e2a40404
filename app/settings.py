"""Server settings, in one place. Environment variables override the defaults."""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import cast

#: Where ``dynlab bench`` writes work_precision.json and one <scene_id>.svg per scene.
DEFAULT_BENCH_DIR = Path(__file__).resolve().parent.parent / "docs" / "bench"
#: Where the course outline (course.toml) and the lesson files (chNN/*.md) live.
DEFAULT_LESSONS_DIR = Path(__file__).resolve().parent.parent / "lessons"


def default_worker_count() -> int:
    """Scene workers ``dynlab serve`` runs when ``--workers`` is not given: ``DYNLAB_WORKERS``, else one per core."""
    return int(os.environ.get("DYNLAB_WORKERS", os.cpu_count() or 1))


@dataclass(frozen=True)
class Settings:
    host: str = "127.0.0.1"
    port: int = 8000
    #: Frame rate of animated scenes (Hz).
    frame_rate_hz: float = 30.0
    #: Sessions kept for reconnects before the least recently used idle one is dropped.
    max_sessions: int = 2000
    #: Benchmark results shown on the Solver lab page (work_precision.json and the SVG diagrams).
    bench_dir: Path = DEFAULT_BENCH_DIR
    #: Lessons checked into the course catalogue at start-up.
    lessons_dir: Path = DEFAULT_LESSONS_DIR
    #: Scene-worker processes (app/scenes/host/pool.py); 0 runs the scenes inside the front process
    #: (tests, a single user). ``dynlab serve`` defaults to one worker per core.
    workers: int = 0
    #: The instructor's secret (``--instructor-key`` or ``DYNLAB_INSTRUCTOR_KEY``); empty: the one kept in the database
    #: (made on the first start), or with nothing kept a new random one each start.
    instructor_key: str = ""
    #: Where the class's data is kept (``--data-dir`` or ``DYNLAB_DATA_DIR``; ``dynlab serve`` defaults to
    #: app.storage.default_data_dir()): a SQLite database of the instructor's secret, rooms, students, polls and
    #: answers. None keeps nothing (an app made in a test's process).
    data_dir: Path | None = None
    #: A database URL that replaces the data directory's SQLite file (``DYNLAB_DATABASE_URL``, e.g.
    #: ``postgresql+psycopg://dynlab@db/dynlab``).
    database_url: str = ""
    #: Kept rooms (with their answers) and page sessions nobody has used for this many days are forgotten.
    keep_rooms_days: float = 180.0
    #: The address students reach this server at (``http://10.0.0.5:8000``, or a balancer's in front of several),
    #: used in room join links and QR codes, and a ``Host`` this server accepts; empty: the address the instructor's
    #: browser used.
    public_url: str = ""

    # --- The web front's guard (app/web/guard.py): what one client may send, from where, how often ---
    #: Largest HTTP request body (bytes) accepted; a larger one is refused with 413 (the largest real body is a few kB).
    max_body_bytes: int = 1024 * 1024
    #: Extra names the ``Host`` header may carry (``name`` for any port, or ``name:port``); ``*`` accepts any
    #: (behind a reverse proxy that checks Host itself). Environment: comma separated.
    allowed_hosts: tuple[str, ...] = ()
    #: Extra origins (``scheme://host[:port]``) allowed to change state and open viewers from another site.
    allowed_origins: tuple[str, ...] = ()
    #: Simulate requests one client may make at once, and per second after that (token bucket); burst 0 = no limit.
    simulate_burst: int = 10
    simulate_rate_per_s: float = 2.0
    #: Viewer websockets (a page's viewer, a room's scene, the room socket) one client may open at once, and per second
    #: after that: a page opens two or three, and each reconnects after a drop. Burst 0 = no limit.
    viewer_open_burst: int = 30
    viewer_open_rate_per_s: float = 2.0
    #: HTTP requests one client may make at once, and per second after that (a lesson page makes a few a second; a
    #: page load about 25 at once). Burst 0 = no limit.
    request_burst: int = 120
    request_rate_per_s: float = 20.0
    #: The same for static files (/static/…: a page's scripts, styles and fonts, about 15 a page, cheap to serve).
    static_request_burst: int = 600
    static_request_rate_per_s: float = 100.0
    #: Clients the rate limits remember; beyond this the least recently seen is forgotten.
    rate_limit_clients: int = 10_000
    #: Take the client's address from the last ``X-Forwarded-For`` entry (only behind a reverse proxy that sets it).
    trust_forwarded_for: bool = False

    # --- Joining a room (app/classroom/join_limits.py explains the numbers); burst 0 = no limit ---
    #: Join requests one address may make at once, then per second (a re-join from the same device counts too).
    join_burst: int = 20
    join_rate_per_s: float = 0.2
    #: New students one room admits at once, then per second, whatever their addresses.
    room_join_burst: int = 150
    room_join_rate_per_s: float = 2.0

    def __post_init__(self) -> None:
        for name in ("max_body_bytes", "simulate_burst", "viewer_open_burst", "join_burst", "room_join_burst"):
            if getattr(self, name) < 0:
                raise ValueError(f"{name} must be >= 0 (got {getattr(self, name)!r})")
        for name in ("simulate_rate_per_s", "viewer_open_rate_per_s", "join_rate_per_s", "room_join_rate_per_s"):
            if not math.isfinite(getattr(self, name)) or getattr(self, name) <= 0:
                raise ValueError(f"{name} must be a finite rate > 0 per second (got {getattr(self, name)!r})")
        if not 0 <= self.workers <= 64:
            raise ValueError(f"workers must be 0 (scenes in the front process) to 64 (got {self.workers!r})")
        if not 0 < self.keep_rooms_days <= 36_500:
            raise ValueError(f"keep_rooms_days must be a number of days from 0 to 36500 (got {self.keep_rooms_days!r})")
        if self.rate_limit_clients < 1:
            raise ValueError(f"rate_limit_clients must be >= 1 (got {self.rate_limit_clients!r})")

    def kept_database_url(self) -> str | None:
        """The database the class's data is kept in (None: nothing is kept)."""
        if self.database_url:
            return self.database_url
        if self.data_dir is None:
            return None
        from app.storage.database import sqlite_url

        return sqlite_url(self.data_dir)

    @classmethod
    def from_env(cls, **overrides: object) -> Settings:
        env = {
            "host": os.environ.get("DYNLAB_HOST"),
            "port": os.environ.get("DYNLAB_PORT"),
            "frame_rate_hz": os.environ.get("DYNLAB_FRAME_RATE_HZ"),
            "bench_dir": os.environ.get("DYNLAB_BENCH_DIR"),
            "lessons_dir": os.environ.get("DYNLAB_LESSONS_DIR"),
            "workers": os.environ.get("DYNLAB_WORKERS"),
            "instructor_key": os.environ.get("DYNLAB_INSTRUCTOR_KEY"),
            "data_dir": os.environ.get("DYNLAB_DATA_DIR"),
            "database_url": os.environ.get("DYNLAB_DATABASE_URL"),
            "keep_rooms_days": os.environ.get("DYNLAB_KEEP_ROOMS_DAYS"),
            "public_url": os.environ.get("DYNLAB_PUBLIC_URL"),
            **{name: os.environ.get(f"DYNLAB_{name.upper()}") for name in (*_GUARD_FIELDS, *_JOIN_FIELDS)},
        }
        values: dict[str, object] = {}
        for name, raw in env.items():
            if raw is not None:
                values[name] = Path(raw) if name == "data_dir" else _parse(getattr(cls, name), raw, name=name)
        values.update({k: v for k, v in overrides.items() if v is not None})
        return cls(**values)  # type: ignore[arg-type]


#: The guard's settings, each read from ``DYNLAB_<NAME>`` (e.g. ``DYNLAB_ALLOWED_HOSTS=lab.example.org,10.0.0.5``).
_GUARD_FIELDS = (
    "max_body_bytes",
    "allowed_hosts",
    "allowed_origins",
    "simulate_burst",
    "simulate_rate_per_s",
    "viewer_open_burst",
    "viewer_open_rate_per_s",
    "request_burst",
    "request_rate_per_s",
    "static_request_burst",
    "static_request_rate_per_s",
    "rate_limit_clients",
    "trust_forwarded_for",
)
#: Joining a room's limits, each read from ``DYNLAB_<NAME>`` (``DYNLAB_JOIN_BURST=0`` turns the per-address one off).
_JOIN_FIELDS = ("join_burst", "join_rate_per_s", "room_join_burst", "room_join_rate_per_s")


def _parse(default: object, raw: str, *, name: str) -> object:
    """An environment variable's text as the type of the field's default: tuples comma separated, booleans 1/0,
    true/false, yes/no."""
    if isinstance(default, bool):
        word = raw.strip().lower()
        if word not in ("1", "true", "yes", "on", "0", "false", "no", "off", ""):
            raise ValueError(f"DYNLAB_{name.upper()} must be true or false (got {raw!r})")
        return word in ("1", "true", "yes", "on")
    if isinstance(default, tuple):
        return tuple(item.strip() for item in raw.split(",") if item.strip())
    parse_as = cast("Callable[[str], object]", type(default))  # str, int, float or Path: each parses its text
    try:
        return parse_as(raw)
    except ValueError:
        raise ValueError(f"DYNLAB_{name.upper()} must be a {type(default).__name__} (got {raw!r})") from None
