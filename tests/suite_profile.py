"""Where the suite's time and CPU go: a pytest plugin that logs each test's start and end on each xdist worker, and a
sampler of every process's CPU by kind. Neither runs unless asked; README's issue-25 figures came from them.

    python -m tests.suite_profile sample &                  # CPU by kind of process, once a second
    bash tests/run.sh -p tests.suite_profile                # the timeline of every test on every worker
    kill %1; python -m tests.suite_profile report           # CPU by kind, busy fraction, longest and dearest files

Everything goes to ``test-results/suite-profile/`` (``cpu.jsonl`` and one ``<worker>.jsonl`` per xdist worker).
"""

from __future__ import annotations

import json
import os
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

OUT = Path(__file__).resolve().parents[1] / "test-results" / "suite-profile"
_log = None


def _write(event: str, nodeid: str) -> None:
    global _log
    if _log is None:
        OUT.mkdir(parents=True, exist_ok=True)
        _log = (OUT / f"{os.environ.get('PYTEST_XDIST_WORKER', 'main')}.jsonl").open("a", buffering=1)
    _log.write(json.dumps({"t": time.time(), "cpu": time.process_time(), "ev": event, "id": nodeid}) + "\n")


_enabled = False


def pytest_configure(config) -> None:
    """Log where the tests run: on each xdist worker, or in the one process of a run without xdist (xdist's
    controller only relays the workers' reports)."""
    global _enabled
    _enabled = hasattr(config, "workerinput") or getattr(config.option, "dist", "no") == "no"


def pytest_runtest_logstart(nodeid: str, location) -> None:
    if _enabled:
        _write("start", nodeid)


def pytest_runtest_logfinish(nodeid: str, location) -> None:
    if _enabled:
        _write("end", nodeid)


def _kind(pid: str) -> str | None:
    """What a process is, for the suite's CPU: Chromium's parts, the served app's, the tests' own, or other."""
    try:
        command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        name = Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return None
    if "chromium" in command:
        return next((f"chromium {k}" for k in ("gpu", "renderer") if f"--type={k}" in command), "chromium other")
    if name.startswith("dynlab-worker"):
        return "scene workers"
    if "forkserver" in command:
        return "forkserver children (bounded work, restored workers)"
    if " serve " in command and ("dynlab" in command or "app.cli" in command):
        return "served apps' fronts"
    if "exec(eval(sys.stdin.readline()))" in command:
        return "test workers"
    if "pytest" in command:
        return "xdist's controller"
    return f"other: {name}"


def sample(period_s: float = 1.0) -> None:
    """Every ``period_s``: the CPU seconds each kind of process used since the last look (a new process: all of its)."""
    ticks_per_s = os.sysconf("SC_CLK_TCK")
    seen: dict[str, int] = {}
    OUT.mkdir(parents=True, exist_ok=True)
    with (OUT / "cpu.jsonl").open("a", buffering=1) as out:
        while True:
            used: Counter[str] = Counter()
            for pid in filter(str.isdigit, os.listdir("/proc")):
                try:
                    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
                except OSError:
                    continue
                ticks = int(fields[11]) + int(fields[12])
                if ticks > seen.get(pid, 0) and (kind := _kind(pid)):
                    used[kind] += (ticks - seen.get(pid, 0)) / ticks_per_s
                seen[pid] = ticks
            out.write(json.dumps({"t": time.time(), "cpu": used}) + "\n")
            time.sleep(period_s)


def report() -> None:
    """CPU by kind over the tests' span, how busy the machine was, the longest files and tests, and the dearest files."""
    spans, cpu_of_test = defaultdict(lambda: [float("inf"), 0.0]), {}
    started: dict[str, tuple[float, float]] = {}
    for path in OUT.glob("*.jsonl"):
        if path.name == "cpu.jsonl":
            continue
        for line in path.read_text().splitlines():
            row = json.loads(line)
            span = spans[row["id"].split("::")[0]]
            span[0], span[1] = min(span[0], row["t"]), max(span[1], row["t"])
            if row["ev"] == "start":
                started[row["id"]] = (row["t"], row["cpu"])
            elif row["id"] in started:
                t0, cpu0 = started[row["id"]]
                cpu_of_test[row["id"]] = (row["t"] - t0, row["cpu"] - cpu0)
    first, last = min(s[0] for s in spans.values()), max(s[1] for s in spans.values())
    samples = [json.loads(line) for line in (OUT / "cpu.jsonl").read_text().splitlines()[1:]]
    used: Counter[str] = Counter()
    for s in samples:
        if first <= s["t"] <= last + 1:
            used.update(s["cpu"])
    total = sum(used.values())
    print(f"tests' span {last - first:.0f} s; CPU {total:.0f} s, {total / (last - first) / os.cpu_count():.0%} busy")
    for kind, seconds in used.most_common():
        print(f"  {seconds:7.0f} CPU-s  {kind}")
    print("longest files (wall s):")
    for name, (a, b) in sorted(spans.items(), key=lambda kv: kv[1][0] - kv[1][1])[:20]:
        print(f"  {b - a:7.1f}  {name}")
    print("longest tests (wall s, the worker's own CPU s):")
    for nodeid, (wall, cpu) in sorted(cpu_of_test.items(), key=lambda kv: -kv[1][0])[:20]:
        print(f"  {wall:7.1f} {cpu:7.1f}  {nodeid}")
    print("dearest files (CPU-s of every process; see _cpu_by_file):")
    for name, seconds in _cpu_by_file(samples, cpu_of_test).most_common(25):
        print(f"  {seconds:7.1f}  {name}")


def _cpu_by_file(samples: list[dict], cpu_of_test: dict[str, tuple[float, float]]) -> Counter[str]:
    """Each file's CPU over every process, estimated: a test's own CPU in its worker exactly; each second's CPU of the
    other processes shared equally among the tests running in that second (Chromium's among the browser tests
    running, if any). Two tests side by side on a served app they share cannot be told apart any better."""
    running: dict[str, list[tuple[float, float, str]]] = defaultdict(list)
    for path in OUT.glob("*.jsonl"):
        if path.name == "cpu.jsonl":
            continue
        started: dict[str, float] = {}
        for line in path.read_text().splitlines():
            row = json.loads(line)
            if row["ev"] == "start":
                started[row["id"]] = row["t"]
            elif row["id"] in started:
                running[path.stem].append((started.pop(row["id"]), row["t"], row["id"]))
    by_file: Counter[str] = Counter()
    for nodeid, (_, cpu) in cpu_of_test.items():
        by_file[nodeid.split("::")[0]] += cpu
    for sample in samples:
        at = sample["t"] - 0.5  # the middle of the second the sample covers
        now = [nodeid for spans in running.values() for a, b, nodeid in spans if a - 1 <= at <= b + 1][: len(running)]
        if not now:
            continue
        in_browser = [nodeid for nodeid in now if nodeid.startswith("tests/browser/")]
        for kind, seconds in sample["cpu"].items():
            if kind == "test workers":
                continue  # counted exactly above
            sharing = in_browser if kind.startswith("chromium") and in_browser else now
            for nodeid in sharing:
                by_file[nodeid.split("::")[0]] += seconds / len(sharing)
    return by_file


if __name__ == "__main__":
    {"sample": sample, "report": report}[sys.argv[1] if len(sys.argv) > 1 else "report"]()
