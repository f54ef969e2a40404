"""The classroom load tool (app/bench/capacity.py, load_client.py, process_tree.py) and the soak (app/bench/soak.py).

One test runs the tool for real but tiny (3 students, 3 s, its own server
subprocess) and checks the report's shape and that frames arrived; it asserts
no speed, since the machine is shared. The rest check the pieces on synthetic
data: the frame decoder, the per-client rates, the plot, the argument bounds,
the /proc reader, the soak's verdict and the Solver lab section.
"""

from __future__ import annotations

import asyncio
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import msgspec
import pytest
import zstandard

from app.bench.capacity import (
    LoadOptions,
    capacity_svg,
    frame_rate_summary,
    per_client_rates,
    read_report,
    run_load,
    write_report,
)
from app.bench.load_client import ClassroomSnapshot, loopback_base, new_session_id, viser_messages_in_frame
from app.cli import main as cli_main
from app.bench.process_tree import TreeUsage, tree_usage
from app.bench.soak import judge_soak, run_soak, wait_until_settled
from app.scenes.host.host import SESSION_ID_PATTERN
from app.settings import Settings
from app.web.pages import _capacity_section

SVG = "{http://www.w3.org/2000/svg}"


def _step(scene_id: str, students: int, p10: float, median: float) -> dict:
    return {
        "scene_id": scene_id, "students": students, "connected": students, "errors": 0, "error_examples": [],
        "window_s": 10.0, "frames_per_s": {"median": median, "p10": p10, "min": p10 - 1},
        "server_cpu_cores": 0.6, "server_rss_mb": 300.0, "server_fds": 40, "server_threads": 14, "server_processes": 1,
        "load_tool_cpu_cores": 0.1, "health_ms": {"median": 3.0, "p95": 9.0, "max": 12.0, "requests": 40, "failures": 0},
        "messages_per_frame": 6.0, "bytes_per_frame": 550,
    }  # fmt: skip


SYNTHETIC_REPORT = {
    "created": "2026-11-23T10:00:00Z",
    "machine": {"cores": 2, "cpu": "Test CPU <9000>", "python": "3.11.7", "platform": "Linux"},
    "server": {"url": "http://127.0.0.1:1", "started_by_tool": True, "workers": 2, "frame_rate_hz": 30.0},
    "method": {"seconds": 10.0},
    "targets": {"p10_frames_per_s": 28.0, "min_frames_per_s_degraded": 15.0},
    "steps": [
        _step("heavy-top", 10, 29.8, 29.9), _step("heavy-top", 30, 21.5, 22.0), _step("heavy-top", 60, 1.0, 1.2),
        _step("four-bar", 10, 29.9, 30.0), _step("four-bar", 30, 29.0, 29.5),
    ],
}  # fmt: skip


def test_a_tiny_real_run_delivers_frames_to_every_student_and_writes_its_report(tmp_path):
    # About 11 s, most of it the server's start and graceful stop. workers=0 (scenes in the front process) starts
    # in a third of the time scene workers take; the process-tree sum over workers is checked below on a child.
    report = run_load(LoadOptions(scenes=("heavy-top",), students=(3,), seconds=3.0, warmup_s=0.5, workers=0))
    (step,) = report["steps"]
    assert step["scene_id"] == "heavy-top" and step["students"] == 3
    assert step["connected"] == 3 and step["errors"] == 0, step["error_examples"]
    # Frames were delivered to every client (no speed is asserted: the machine is shared).
    assert step["frames_per_s"]["min"] > 0, step
    assert step["frames_per_s"]["min"] <= step["frames_per_s"]["p10"] <= step["frames_per_s"]["median"]
    assert step["bytes_per_frame"] > 16  # at least viser's 16-byte header
    # One frame in 30 is decoded, so a client that got 30 frames in the window gave at least one sample.
    if step["frames_per_s"]["median"] * step["window_s"] >= 30:
        assert step["messages_per_frame"] >= 1, step
    assert step["server_cpu_cores"] > 0 and step["server_rss_mb"] > 0
    assert step["server_fds"] > 0 and step["server_threads"] > 0 and step["server_processes"] >= 1
    assert step["load_tool_cpu_cores"] >= 0
    assert step["health_ms"]["requests"] >= 1 and step["health_ms"]["max"] >= step["health_ms"]["median"] > 0
    assert report["machine"]["cores"] >= 1 and report["server"]["started_by_tool"] is True
    assert report["server"]["workers"] == 0
    assert report["targets"] == {"p10_frames_per_s": 28.0, "min_frames_per_s_degraded": 15.0}
    paths = write_report(report, tmp_path)
    assert [p.name for p in paths] == ["capacity.json", "capacity.svg"]
    assert read_report(tmp_path / "capacity.json") == json.loads(json.dumps(report))
    assert ET.parse(tmp_path / "capacity.svg").getroot().tag == f"{SVG}svg"


def test_the_plot_is_valid_svg_with_a_line_pair_per_scene_and_both_targets():
    root = ET.fromstring(capacity_svg(SYNTHETIC_REPORT))
    assert root.tag == f"{SVG}svg"
    series = root.findall(f".//{SVG}g[@class='series']")
    assert [g.get("data-scene") for g in series] == ["heavy-top", "four-bar"]
    assert all(len(g.findall(f"{SVG}polyline")) == 2 for g in series)  # p10 and median
    assert len(series[0].findall(f"{SVG}circle")) == 2 * 3
    texts = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert "(28)" in texts and "(15)" in texts
    # With nothing measured it still draws a valid, labelled empty plot.
    empty = ET.fromstring(capacity_svg({"steps": []}))
    assert "no step delivered frames" in " ".join(t.text or "" for t in empty.iter(f"{SVG}text"))


@pytest.mark.parametrize(
    ("options", "field"),
    [
        ({"students": (0,)}, "students"),
        ({"students": (501,)}, "students"),
        ({"students": ()}, "students"),
        ({"seconds": 601.0}, "seconds"),
        ({"seconds": float("nan")}, "seconds"),
        ({"warmup_s": -1.0}, "warmup"),
        ({"connect_per_s": 0.0}, "connect_rate"),
        ({"scenes": ("Heavy_Top",)}, "scene"),
        ({"scenes": ()}, "scene"),
        ({"workers": -1}, "workers"),
        ({"url": "http://192.168.1.10:8000"}, "url"),
        ({"url": "ws://127.0.0.1:8000"}, "url"),
        ({"server_pid": 1}, "server_pid"),
        ({"scenes": tuple(f"s{i}" for i in range(9)), "students": (1, 2, 3, 4, 5)}, "students"),
    ],
)
def test_bounds_are_refused_with_a_message_naming_the_option(options, field):
    with pytest.raises(ValueError, match=rf"^{field}:"):
        LoadOptions(**options)


def test_the_command_line_refuses_bounds_before_starting_anything(capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli_main(["load", "--students", "10,600"])
    assert exit_info.value.code == 2
    assert "students: each class size must be 1..500, got 600" in capsys.readouterr().err
    with pytest.raises(ValueError, match="^minutes:"):
        run_soak("heavy-top", 100, 0.0)
    with pytest.raises(ValueError, match="^students:"):
        run_soak("heavy-top", 501, 1.0)
    with pytest.raises(ValueError, match="^server_pid:"):
        run_soak("heavy-top", 10, 1.0, url="http://127.0.0.1:8000")


def test_loopback_urls_and_session_ids():
    assert loopback_base("http://127.0.0.1:8123") == ("127.0.0.1", 8123)
    assert loopback_base("http://localhost:80/") == ("localhost", 80)
    assert all(SESSION_ID_PATTERN.match(new_session_id()) for _ in range(50))
    assert len({new_session_id() for _ in range(50)}) == 50


def _viser_frame(messages: list[dict], *, trailing: bytes = b"") -> bytes:
    inner = msgspec.msgpack.encode({"messages": messages, "timestampSec": 1.0, "binaryBufferLengths": []})
    compressed = zstandard.ZstdCompressor(level=1).compress(inner)
    return len(inner).to_bytes(8, "little") + len(compressed).to_bytes(8, "little") + compressed + trailing


def test_the_frame_decoder_counts_viser_messages_and_refuses_a_truncated_frame():
    frame = _viser_frame([{"type": "SetPosition"}] * 7, trailing=b"\0" * 8)  # binary buffers follow the msgpack
    assert viser_messages_in_frame(frame) == 7
    with pytest.raises(ValueError, match="frame:"):
        viser_messages_in_frame(frame[:10])
    with pytest.raises(ValueError, match="compressed bytes"):
        viser_messages_in_frame(frame[:20])


def test_per_client_rates_come_from_counters_over_the_window_and_skip_failed_clients():
    start = ClassroomSnapshot(at_s=100.0, frames=(0, 10, 5), frame_bytes=0, decoded_frames=0, decoded_messages=0)
    end = ClassroomSnapshot(at_s=110.0, frames=(300, 160, 5), frame_bytes=0, decoded_frames=0, decoded_messages=0)
    assert per_client_rates(start, end, [True, True, False]) == [30.0, 15.0]
    summary = frame_rate_summary([30.0, 15.0, 20.0, 25.0, 10.0])
    assert summary == {"median": 20.0, "p10": 12.0, "min": 10.0}  # numpy's linear percentile: 10 + 0.4 * (15 - 10)
    assert frame_rate_summary([]) is None


def test_the_process_tree_includes_children_and_refuses_a_missing_pid():
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        alone = tree_usage(child.pid)
        together = tree_usage(__import__("os").getpid())
        assert alone.processes == 1 and alone.threads >= 1 and alone.fds >= 3 and alone.rss_mb > 0
        assert together.processes >= 2  # this process and the child
        assert together.rss_mb > alone.rss_mb
    finally:
        child.kill()
        child.wait()
    with pytest.raises(ValueError, match="^server_pid:"):
        tree_usage(2**22 + 12345)  # above Linux's pid_max limit: never a running process


BASELINE = TreeUsage(cpu_s=10.0, rss_mb=300.0, fds=40, threads=14, processes=1)


@pytest.mark.parametrize(
    ("end", "errors", "failed"),
    [
        (TreeUsage(cpu_s=500.0, rss_mb=329.0, fds=40, threads=14, processes=1), 0, set()),  # +9.7 % memory: within 10 %
        (TreeUsage(cpu_s=500.0, rss_mb=290.0, fds=38, threads=12, processes=1), 0, set()),  # below baseline is fine
        (TreeUsage(cpu_s=500.0, rss_mb=331.0, fds=40, threads=14, processes=1), 0, {"rss_within_10_percent"}),
        (TreeUsage(cpu_s=500.0, rss_mb=300.0, fds=41, threads=14, processes=1), 0, {"fds_back_to_baseline"}),
        (TreeUsage(cpu_s=500.0, rss_mb=300.0, fds=40, threads=15, processes=1), 0, {"threads_back_to_baseline"}),
        (TreeUsage(cpu_s=500.0, rss_mb=300.0, fds=40, threads=14, processes=1), 2, {"no_errors"}),
    ],
)
def test_the_soak_verdict_compares_the_end_with_the_baseline(end, errors, failed):
    verdict = judge_soak(BASELINE, end, errors=errors)
    assert {name for name, check in verdict["checks"].items() if not check["passed"]} == failed
    assert verdict["passed"] is (not failed)
    assert verdict["checks"]["rss_within_10_percent"]["ratio_end_to_start"] == round(end.rss_mb / 300.0, 4)


def test_the_soak_waits_for_the_server_to_settle_and_gives_up_at_its_timeout():
    readings = iter([
        TreeUsage(cpu_s=1.0, rss_mb=400.0, fds=140, threads=30, processes=1),
        TreeUsage(cpu_s=1.0, rss_mb=310.0, fds=41, threads=14, processes=1),
        TreeUsage(cpu_s=1.0, rss_mb=305.0, fds=40, threads=14, processes=1),
        TreeUsage(cpu_s=1.0, rss_mb=999.0, fds=999, threads=999, processes=1),  # never read: settled before
    ])  # fmt: skip
    end = asyncio.run(wait_until_settled(lambda: next(readings), BASELINE, timeout_s=10.0, poll_s=0.01))
    assert end.fds == 40 and end.rss_mb == 305.0
    stuck = TreeUsage(cpu_s=1.0, rss_mb=300.0, fds=41, threads=14, processes=1)
    pokes = []

    async def poke() -> None:
        pokes.append(1)

    assert asyncio.run(wait_until_settled(lambda: stuck, BASELINE, timeout_s=0.05, poll_s=0.01, poke=poke)) == stuck
    assert 1 <= len(pokes) <= 6  # one poke per poll, and the loop ends at its timeout


def test_the_solver_lab_section_shows_the_report_or_says_how_to_make_it(tmp_path):
    settings = Settings(bench_dir=tmp_path)
    assert "No classroom measurement yet" in _capacity_section(settings)
    write_report(SYNTHETIC_REPORT, tmp_path)
    section = _capacity_section(settings)
    assert '<img src="/bench/capacity.svg"' in section
    assert section.count("<tr>") == 1 + len(SYNTHETIC_REPORT["steps"])  # header and one row per step
    assert "Test CPU &lt;9000&gt;" in section and "scene workers: 2;" in section
    assert '<td class="num">21.5</td>' in section
    (tmp_path / "capacity.json").write_text("{not json", encoding="utf-8")
    assert "cannot be read" in _capacity_section(settings)
    (tmp_path / "capacity.json").write_text(json.dumps({"steps": [{"frames_per_s": 3}]}), encoding="utf-8")
    assert "malformed" in _capacity_section(settings)
