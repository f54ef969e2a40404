"""A benchmark, not a timed assertion: how long a lesson takes from opening to its scene's first frame.

Skipped unless ``DYNLAB_BENCH_FIRST_FRAME=1`` (it takes about two minutes and the whole machine; run it alone on a
quiet machine, e.g. ``DYNLAB_BENCH_FIRST_FRAME=1 .venv/bin/python -m pytest tests/browser/test_first_frame_bench.py
-n 0 -s``). It opens each lesson of :data:`first_frame.LESSONS` a few times in new browser contexts, then writes
``docs/bench/first_frame.json`` and ``.svg`` (its ``after``; the ``before`` measured on the commit before the viewer
was preloaded is kept from the committed report). It asserts only that every load drew its scene with no console error.
"""

from __future__ import annotations

import json
import os
import platform
from datetime import datetime, timezone
from pathlib import Path

import pytest

from app.bench.first_frame import REPORT_FILE, TARGET_MS, write_report
from tests.browser import first_frame

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(
        os.environ.get("DYNLAB_BENCH_FIRST_FRAME") != "1", reason="a benchmark: DYNLAB_BENCH_FIRST_FRAME=1"
    ),
]

BENCH_DIR = Path(__file__).resolve().parents[2] / "docs" / "bench"


def test_first_frame_of_each_lesson_is_measured_and_reported(browser, live_server):
    measured = first_frame.measure(browser, live_server.url, loads=int(os.environ.get("DYNLAB_BENCH_LOADS", "3")))
    path = BENCH_DIR / REPORT_FILE
    report = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    report.update({
        "created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": {"cores": os.cpu_count(), "cpu": platform.processor() or platform.machine()},
        "target_ms": TARGET_MS,
        "after": measured,
    })
    write_report(report, BENCH_DIR)
    for lesson in measured["lessons"]:
        print(lesson["lesson_id"], lesson["first_frame_ms"], lesson["median_ms"])
        assert None not in lesson["first_frame_ms"], f"{lesson['lesson_id']}: a load drew no frame"
        assert not lesson["console_errors"], lesson["console_errors"]
