from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, Query
from fastapi.responses import Response

from app.api.deps import CatalogueDep
from app.api.errors import unprocessable
from app.api.schemas.errors import error_responses
from app.api.schemas.examples import ExampleSummary, SolveAnswer, SolveRequest
from app.course.scripts import MAX_PARAMS_TEXT, example_script, script_file_name, script_values
from app.physics.core.parameters import ParameterError

router = APIRouter(prefix="/api/examples", tags=["examples"])

#: The ``params`` query of a script route: the page's current values as JSON text.
ScriptParams = Annotated[
    str | None,
    Query(
        max_length=MAX_PARAMS_TEXT,
        description='The values as a JSON object, e.g. {"mass_kg": 2}; omitted names take their defaults',
    ),
]
#: A script is served as Python text, named for the example or scene it reproduces.
PYTHON_MEDIA_TYPE = "text/x-python; charset=utf-8"


def python_file(text: str, file_name: str) -> Response:
    """``text`` as a Python file the browser shows or saves as ``file_name``."""
    return Response(
        text, media_type=PYTHON_MEDIA_TYPE, headers={"Content-Disposition": f'inline; filename="{file_name}"'}
    )


@router.get("", response_model=list[ExampleSummary], response_model_exclude_unset=True)
def list_examples(catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """Every worked example with its input schema (name, unit, default, range)."""
    return [example.schema() for example in catalogue.examples.values()]


@router.post(
    "/{example_id}/solve",
    response_model=SolveAnswer,
    responses=error_responses(
        not_found="No worked example has this id",
        unprocessable=(
            "An input is unknown, not finite, out of range, or the inputs cannot exist together; `loc` names it"
        ),
    ),
)
def solve_example(example_id: str, request: SolveRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """Solve a worked example: ``outputs`` (SI; vectors as [x, y, z]), ``steps`` and ``plots``."""
    example = catalogue.examples.get(example_id)
    if example is None:
        raise HTTPException(
            status_code=404, detail=f"no worked example {example_id!r}; known: {', '.join(catalogue.examples)}"
        )
    inputs = example.inputs.validate(request.inputs)
    try:
        result = example.solve(inputs).as_dict()
    except ParameterError:
        raise  # names its input: the handler's 422
    except ValueError as exc:  # in range, but impossible together (WorkedExample.solve's contract): a 422, not a 500
        raise unprocessable(["body", "inputs"], str(exc)) from None
    result["inputs"] = inputs
    return result


@router.get("/{example_id}/script.py", include_in_schema=False)
def example_script_file(example_id: str, catalogue: CatalogueDep, params: ScriptParams = None) -> Response:
    """A Python script reproducing the worked solution for ``params`` with the project's own package ("Open as Python").

    A bad ``params`` gets a 422 naming the field (``loc`` ``["query", "params", name]``) and no script.
    """
    example = catalogue.examples.get(example_id)
    if example is None:
        raise HTTPException(
            status_code=404, detail=f"no worked example {example_id!r}; known: {', '.join(catalogue.examples)}"
        )
    try:
        inputs = script_values(example.inputs, params)
    except ParameterError as exc:
        raise unprocessable(["query", *exc.path], str(exc)) from None
    return python_file(example_script(example, inputs), script_file_name(f"example_{example.id}"))
