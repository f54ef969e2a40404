"""``/api/systems``: the derivation engine (chapters 7–9) over HTTP.

Derivations are cached (memory and disk), so only the first request for a
system and formulation runs sympy; the routes are plain ``def`` so that work
runs in the thread pool, never on the event loop. A typed Lagrangian is
derived in a bounded child process (time and memory limits) and refused with
a 422 naming the field when it cannot be.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from fastapi import APIRouter, HTTPException

from app.api.deps import CatalogueDep
from app.api.schemas.errors import error_responses
from app.api.schemas.systems import (
    CustomDeriveAnswer,
    CustomDeriveRequest,
    DeriveAnswer,
    DeriveRequest,
    RhsAnswer,
    RhsRequest,
    SystemSummary,
)
from app.physics.core.parameters import ParameterError
from app.physics.mechanics.derivation import FormulationUnavailable
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.engine import available_formulations, derived
from app.physics.mechanics.typed import derive_typed_bounded

router = APIRouter(prefix="/api/systems", tags=["systems"])


def summary(system: SystemDescription) -> dict[str, Any]:
    reasons = available_formulations(system)
    return {
        "id": system.id,
        "title": system.title,
        "chapter": system.chapter,
        "coordinates": [{"name": c.name, "latex": c.latex, "unit": c.unit} for c in system.coordinates],
        "speeds": [{"name": s.name, "latex": s.latex, "unit": s.unit} for s in system.speed_list],
        "formulations": [f for f, reason in reasons.items() if not reason],
        "unavailable": {f: reason for f, reason in reasons.items() if reason},
        "parameters": system.parameters.schema(),
        "assumptions": system.assumptions,
    }


def _system(catalogue, system_id: str) -> SystemDescription:
    system = catalogue.derivations.get(system_id)
    if system is None:
        raise HTTPException(status_code=404, detail=f"no system {system_id!r}; known: {', '.join(catalogue.derivations)}")
    return system


def _derived(system: SystemDescription, formulation: str):
    try:
        return derived(system, formulation)
    except FormulationUnavailable as error:
        raise ParameterError("formulation", f"{formulation} does not apply to {system.id}: {error}") from None


@router.get("", response_model=list[SystemSummary])
def list_systems(catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """Every catalogue system: id, title, chapter, coordinates, speeds, the formulations available, parameter schema."""
    return [summary(system) for system in catalogue.derivations.values()]


@router.post(
    "/custom/derive",
    response_model=CustomDeriveAnswer,
    responses=error_responses(
        unprocessable="A name, value or formula is refused, the derivation exceeded its time or memory bound, or the mass matrix is singular; `loc` names the field",
        busy="Two typed derivations are already running; the `Retry-After` header says when to try again (s)",
    ),
)
def derive_custom(request: CustomDeriveRequest) -> dict[str, Any]:
    """Lagrange's equations for typed energies T and V (parsed by a whitelisting parser; derived in a bounded process)."""
    answer = derive_typed_bounded(request.model_dump())
    answer["params"] = dict(request.parameters)
    return answer


@router.post(
    "/{system_id}/derive",
    response_model=DeriveAnswer,
    responses=error_responses(not_found="No system has this id", unprocessable="A parameter is out of range, or the formulation does not apply (the message says why)"),
)
def derive_system(system_id: str, request: DeriveRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """The equations of motion by one formulation, with the steps that lead to them (LaTeX)."""
    system = _system(catalogue, system_id)
    params = system.parameters.validate(request.params)
    answer = _derived(system, request.formulation).answer()
    answer["params"] = params
    return answer


@router.post(
    "/{system_id}/rhs",
    response_model=RhsAnswer,
    responses=error_responses(not_found="No system has this id", unprocessable="The state has the wrong length or is not finite, a parameter is out of range, or the formulation does not apply"),
)
def system_rhs(system_id: str, request: RhsRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """The state derivative (q̇, q̈) at a state (q, q̇) by one formulation: every formulation answers the same quantity."""
    system = _system(catalogue, system_id)
    params = system.parameters.validate(request.params)
    n = len(system.coordinates)
    if len(request.state) != 2 * n:
        names = [c.name for c in system.coordinates]
        raise ParameterError("state", f"give {2 * n} numbers: {', '.join(names)}, then their rates (got {len(request.state)})")
    if not all(math.isfinite(x) for x in request.state) or not math.isfinite(request.t):
        raise ParameterError("state", "every number of the state and t must be finite")
    derivative = _derived(system, request.formulation).state_derivative(request.t, np.array(request.state), np.array(system.parameter_array(params)))
    if not np.all(np.isfinite(derivative)):
        raise ParameterError("state", "the equations are singular at this state (e.g. an Euler-angle singularity or a singular mass matrix)")
    return {"state_derivative": derivative.tolist()}
