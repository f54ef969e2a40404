from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, ConfigDict, Field

from app.physics.systems import worked_examples

EXAMPLES = worked_examples()

router = APIRouter(prefix="/api/examples", tags=["examples"])


class SolveRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    inputs: dict[str, Any] = Field(default_factory=dict, description="Inputs by name; omitted ones take their defaults")


@router.get("")
def list_examples() -> list[dict[str, Any]]:
    """Every worked example with its input schema (name, unit, default, range)."""
    return [example.schema() for example in EXAMPLES.values()]


@router.post("/{example_id}/solve")
def solve_example(example_id: str, request: SolveRequest) -> dict[str, Any]:
    """Solve a worked example: ``outputs`` (SI; vectors as [x, y, z]), ``steps`` and ``plots``."""
    example = EXAMPLES.get(example_id)
    if example is None:
        raise HTTPException(status_code=404, detail=f"no worked example {example_id!r}; known: {', '.join(EXAMPLES)}")
    inputs = example.inputs.validate(request.inputs)
    result = example.solve(inputs).as_dict()
    result["inputs"] = inputs
    return result
