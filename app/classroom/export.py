"""``dynlab export``: a room's, or every kept room's, data as files an instructor can keep or open in a spreadsheet.

For each room, ``room-<CODE>.json`` (the room: lesson, scene, parameters, its students' public ids and names, and
every poll with its question, its answer if revealed, and its results) and ``room-<CODE>-answers.csv`` (every answer
to every poll, one row each; names only where the poll showed them). Never a token or a device id.
"""

from __future__ import annotations

import json
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from app.classroom.polls import CSV_HEADER
from app.classroom.room import Room


def room_document(room: Room) -> dict[str, Any]:
    """What ``room-<CODE>.json`` holds."""
    state = room.state()
    return {
        "room_id": room.room_id,
        "code": room.code,
        "created_at": datetime.fromtimestamp(room.created_at, UTC).isoformat(),
        "lesson_id": state["lesson_id"],
        "scene_id": state["scene_id"],
        "params": state["params"],
        "playing": state["playing"],
        "time_scale": state["time_scale"],
        "mode": state["mode"],
        "students": [{"student_id": s["student_id"], "name": s["name"]} for s in room.student_list()],
        "polls": [
            {**poll.public(), "answer_given": poll.record()["answer_value"], "results": poll.results()}
            for poll in room.polls.values()
        ],
    }


def answers_csv(room: Room) -> str:
    """Every answer of every poll of the room, one CSV (one header)."""
    rows = [",".join(CSV_HEADER) + "\n"]
    for poll in room.polls.values():
        rows.extend(poll.to_csv().splitlines(keepends=True)[1:])
    return "".join(rows)


def export_rooms(rooms: list[Room], out_dir: Path) -> list[Path]:
    """Write each room's two files into ``out_dir`` (made if missing); returns the files written."""
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for room in rooms:
        document = out_dir / f"room-{room.code}.json"
        document.write_text(json.dumps(room_document(room), indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        table = out_dir / f"room-{room.code}-answers.csv"
        table.write_text(answers_csv(room), encoding="utf-8")
        written += [document, table]
    return written
