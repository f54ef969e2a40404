"""CPU, memory, file descriptors and threads of a process and all its descendants, read from Linux's /proc.

The descendants are found through ``/proc/<pid>/task/<tid>/children``,
recursively, so a server that runs scene workers as child processes is measured
whole. A process that exits between two reads is skipped.
:func:`process_group_members` lists a process group's live members (what is left
of a server the load tool started, after it was stopped).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

PROC = Path("/proc")
_CLOCK_TICKS_PER_S = os.sysconf("SC_CLK_TCK")


@dataclass(frozen=True)
class TreeUsage:
    """One reading of a process tree: CPU (utime + stime, s), resident memory (MB), open fds, threads, processes."""

    cpu_s: float
    rss_mb: float
    fds: int
    threads: int
    processes: int


def tree_pids(root_pid: int) -> list[int]:
    """``root_pid`` followed by every live descendant (breadth first)."""
    pids, queue, seen = [], [root_pid], set[int]()
    while queue and len(seen) < 10_000:  # bounded: a fork bomb must not hang the load tool
        pid = queue.pop(0)
        if pid in seen or not (PROC / str(pid)).is_dir():
            continue
        seen.add(pid)
        pids.append(pid)
        try:
            tasks = list((PROC / str(pid) / "task").iterdir())
        except OSError:
            continue
        for task in tasks:
            try:
                queue.extend(int(child) for child in (task / "children").read_text().split())
            except OSError:
                continue
    return pids


def process_group_members(group_id: int) -> list[int]:
    """Live processes (not zombies) whose process group is ``group_id``, from /proc."""
    members = []
    for entry in PROC.iterdir():
        if not entry.name.isdigit():
            continue
        try:
            # Fields after comm (which may hold spaces and parentheses): state, ppid, pgrp, …
            state, _ppid, pgrp = (entry / "stat").read_text().rsplit(")", 1)[1].split()[:3]
        except (OSError, ValueError):
            continue
        if int(pgrp) == group_id and state != "Z":
            members.append(int(entry.name))
    return members


def _cpu_s(pid: int) -> float:
    # Field 2 (comm) may contain spaces and parentheses: split after its closing parenthesis.
    fields = (PROC / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()
    utime, stime = int(fields[11]), int(fields[12])  # fields 14 and 15 of proc(5), counted from 1
    return (utime + stime) / _CLOCK_TICKS_PER_S


def _status(pid: int) -> tuple[float, int]:
    """(VmRSS in MB, Threads) from /proc/<pid>/status."""
    rss_kb, threads = 0, 0
    for line in (PROC / str(pid) / "status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            rss_kb = int(line.split()[1])
        elif line.startswith("Threads:"):
            threads = int(line.split()[1])
    return rss_kb / 1024.0, threads


def tree_usage(root_pid: int) -> TreeUsage:
    """Summed usage of ``root_pid`` and its descendants; ValueError naming ``server_pid`` if it is not running."""
    if not (PROC / str(root_pid)).is_dir():
        raise ValueError(f"server_pid: no running process {root_pid}")
    cpu_s, rss_mb, fds, threads, processes = 0.0, 0.0, 0, 0, 0
    for pid in tree_pids(root_pid):
        try:
            pid_cpu = _cpu_s(pid)
            pid_rss, pid_threads = _status(pid)
            pid_fds = len(os.listdir(PROC / str(pid) / "fd"))
        except (OSError, IndexError, ValueError):
            continue  # exited while being read
        cpu_s += pid_cpu
        rss_mb += pid_rss
        threads += pid_threads
        fds += pid_fds
        processes += 1
    return TreeUsage(cpu_s=cpu_s, rss_mb=rss_mb, fds=fds, threads=threads, processes=processes)
