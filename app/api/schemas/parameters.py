"""Parameter values and parameter descriptions, shared by scenes and worked examples."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, JsonValue

#: A JSON number as the physics wrote it: integers stay integers (``step: 1``), floats stay floats.
Number = int | float
#: One parameter's value: a number, a choice or text, a vector ``[x, y, z]``, or a list of records (``kind: list``).
ParameterValue = Number | str | list[Number] | list[dict[str, JsonValue]]


class ParameterSpec(BaseModel):
    """One input control: name, unit, default and, by ``kind``, its range, choices or length.

    ``kind`` is ``float``, ``int``, ``choice`` (with ``choices``), ``text`` (with
    ``max_length``), ``vector`` (with ``length``) or ``list`` (records described by
    ``item_schema``); numeric kinds carry ``min``, ``max``, ``scale`` and
    optionally ``step``. Keys a kind does not use are absent.
    """

    name: str
    label: str
    unit: str
    default: ParameterValue
    description: str
    kind: str
    choices: list[str] = []
    max_length: int = 0
    length: int = 0
    min: Number = 0
    max: Number = 0
    scale: str = ""
    step: Number = 0
    item_schema: dict[str, Any] = {}
