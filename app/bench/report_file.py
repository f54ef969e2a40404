"""Reading a committed benchmark report (JSON) back: missing is ``None``, unusable is a ``ValueError`` saying why."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any


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
