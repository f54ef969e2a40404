"""Server settings, in one place. Environment variables override the defaults."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

#: Where ``dynlab bench`` writes work_precision.json and one <scene_id>.svg per scene.
DEFAULT_BENCH_DIR = Path(__file__).resolve().parent.parent / "docs" / "bench"
#: Where the course outline (course.toml) and the lesson files (chNN/*.md) live.
DEFAULT_LESSONS_DIR = Path(__file__).resolve().parent.parent / "lessons"


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

    @classmethod
    def from_env(cls, **overrides: object) -> "Settings":
        env = {
            "host": os.environ.get("DYNLAB_HOST"),
            "port": os.environ.get("DYNLAB_PORT"),
            "frame_rate_hz": os.environ.get("DYNLAB_FRAME_RATE_HZ"),
            "bench_dir": os.environ.get("DYNLAB_BENCH_DIR"),
            "lessons_dir": os.environ.get("DYNLAB_LESSONS_DIR"),
        }
        values: dict[str, object] = {}
        for name, raw in env.items():
            if raw is not None:
                values[name] = type(getattr(cls, name))(raw)
        values.update({k: v for k, v in overrides.items() if v is not None})
        return cls(**values)  # type: ignore[arg-type]
