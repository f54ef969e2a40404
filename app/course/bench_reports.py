"""The committed benchmark reports (``docs/bench/*.json`` and their SVG plots), read back for the Solver lab page and
``GET /api/bench/work-precision``.

The command-line tools in :mod:`app.bench` write them (``dynlab bench``, ``dynlab load``, ``dynlab load --room``,
``dynlab load --attack``); reading one needs none of those tools, so the pages import this module, never
:mod:`app.bench`. The files are read on each request, so a new run shows up without restarting the server. A missing
report is ``None``; an unusable one a ``ValueError`` (or :class:`BenchResultsError`) saying why.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from app.settings import Settings

#: The reports' file names in ``Settings.bench_dir``.
WORK_PRECISION_REPORT = "work_precision.json"
CAPACITY_REPORT = "capacity.json"
#: A ``dynlab load --room`` run: students following one room's shared scene.
CLASSROOM_REPORT = "classroom.json"
ATTACK_REPORT = "attack.json"
#: The derivation engine at scale: written by ``dynlab derivations --scaling``.
SCALING_REPORT = "scaling.json"
#: The class size whose cost ``classroom.json``'s ``follow_cost`` gives beside one follower's.
FOLLOW_COST_CLASS = 100

#: Scene ids that may name a diagram file; anything else (dots, slashes, capitals, or a name longer than
#: any scene id and than a file name may be) is refused.
SCENE_ID_PATTERN = re.compile(r"[a-z0-9-]{1,64}")
HOW_TO_MEASURE = "run `uv run --group bench dynlab bench` to measure the integrators and write it"


class BenchResultsError(Exception):
    """work_precision.json exists but cannot be used."""


def read_report_file(path: Path, *, list_key: str, shown_as: str) -> dict[str, Any] | None:
    """The parsed report at ``path``; ``None`` if there is no file; ``ValueError`` if it cannot be read or has no
    ``list_key`` list.

    ``shown_as`` is how messages name the file (a path relative to the project, or just its name).
    """
    if not path.is_file():
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"{shown_as} cannot be read: {exc}") from None
    if not isinstance(data, dict) or not isinstance(data.get(list_key), list):
        raise ValueError(f"{shown_as} has no list of {list_key}")
    return data


def results_path(settings: Settings) -> Path:
    """Where ``dynlab bench`` writes ``work_precision.json``."""
    return Path(settings.bench_dir) / WORK_PRECISION_REPORT


def missing_message(settings: Settings) -> str:
    return f"No benchmark results: `{_shown(results_path(settings))}` does not exist; {HOW_TO_MEASURE}."


def _shown(path: Path) -> str:
    """The path as a reader should see it: relative to the project when it lies inside it."""
    root = Path(__file__).resolve().parents[2]
    try:
        return str(path.resolve().relative_to(root))
    except ValueError:
        return str(path)


def load_results(settings: Settings) -> dict[str, Any] | None:
    """The parsed work-precision results, ``None`` if the file is missing; ``BenchResultsError`` if it is unreadable."""
    path = results_path(settings)
    try:
        return read_report_file(path, list_key="scenes", shown_as=f"`{_shown(path)}`")
    except ValueError as exc:
        raise BenchResultsError(str(exc)) from None


def diagram_path(settings: Settings, scene_id: str) -> Path | None:
    """The SVG for a scene (or ``capacity``, ``classroom``, ``attack``), or ``None`` if the id is not a safe file name
    or the file is missing."""
    if not isinstance(scene_id, str) or not SCENE_ID_PATTERN.fullmatch(scene_id):
        return None
    path = Path(settings.bench_dir) / f"{scene_id}.svg"
    return path if path.is_file() else None


def diagram_size(path: Path) -> tuple[str, str] | None:
    """The ``width`` and ``height`` (px) the SVG at ``path`` declares; ``None`` if it declares none or is unreadable."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return None
    width, height = root.get("width"), root.get("height")
    return (width, height) if width and height else None


def read_capacity_report(path: Path) -> dict | None:
    """A saved capacity report (``capacity.json`` or ``classroom.json``), None if the file is missing; ValueError if
    it is unreadable or has no steps."""
    return read_report_file(path, list_key="steps", shown_as=path.name)


def read_scaling_report(path: Path) -> dict | None:
    """The derivation engine's scaling report, None if the file is missing; ValueError if unreadable or rowless."""
    return read_report_file(path, list_key="rows", shown_as=path.name)


def read_attack_report(path: Path) -> dict | None:
    """A saved attack report, None if the file is missing; ValueError if it is unreadable or has no attacks list."""
    return read_report_file(path, list_key="attacks", shown_as=path.name)


def describe_workers(workers: object) -> str:
    """A report's ``server.workers`` in words: serve's default (None), none (0: one process), or the count."""
    return "serve's default" if workers is None else "none (one process)" if workers == 0 else str(workers)


def listed_attacks(report: dict) -> list[dict]:
    """The attack report's attacks in the order of their items of "Found" (the order they ran in within an item)."""
    return sorted((a for a in report.get("attacks") or () if isinstance(a, dict)), key=lambda a: str(a.get("item")))
