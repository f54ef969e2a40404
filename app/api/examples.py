from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException

from app.api.deps import CatalogueDep
from app.api.schemas.errors import error_responses
from app.api.schemas.examples import ExampleSummary, SolveAnswer, SolveRequest

router = APIRouter(prefix="/api/examples", tags=["examples"])


@router.get("", response_model=list[ExampleSummary], response_model_exclude_unset=True)
def list_examples(catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """Every worked example with its input schema (name, unit, default, range)."""
    return [example.schema() for example in catalogue.examples.values()]


@router.post(
    "/{example_id}/solve",
    response_model=SolveAnswer,
    responses=error_responses(
        not_found="No worked example has this id",
        unprocessable="An input is unknown, not finite, out of range, or the inputs cannot exist together; `loc` names it",
    ),
)
def solve_example(example_id: str, request: SolveRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """Solve a worked example: ``outputs`` (SI; vectors as [x, y, z]), ``steps`` and ``plots``."""
    example = catalogue.examples.get(example_id)
    if example is None:
        raise HTTPException(status_code=404, detail=f"no worked example {example_id!r}; known: {', '.join(catalogue.examples)}")
    inputs = example.inputs.validate(request.inputs)
    result = example.solve(inputs).as_dict()
    result["inputs"] = inputs
    return result
