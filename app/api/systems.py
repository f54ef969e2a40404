"""``/api/systems``: the derivation engine (chapters 7–9) over HTTP.

Derivations are cached (memory and disk), so only the first request for a
system and formulation runs sympy; the routes are plain ``def`` so that work
runs in the thread pool, never on the event loop. A typed Lagrangian is
derived in a bounded child process (time and memory limits) and refused with
a 422 naming the field when it cannot be.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
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
    EigenvaluesAnswer,
    EigenvaluesRequest,
    RhsAnswer,
    RhsRequest,
    SystemSummary,
)
from app.physics.core.parameters import ParameterError
from app.physics.mechanics.derivation import FormulationUnavailable
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.engine import available_formulations, derived
from app.physics.mechanics.multibody.compiled import FORMULATIONS as PARTS_FORMULATIONS
from app.physics.mechanics.multibody.compiled import ConstraintsNotMet, compiled
from app.physics.mechanics.multibody.linearise import Sweep, eigenvalues, state_matrix, sweep
from app.physics.mechanics.multibody.parts import MultibodyFamily, MultibodySystem
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


def parts_summary(entry: MultibodySystem | MultibodyFamily) -> dict[str, Any]:
    """A system built of parts, in the same shape, with its dependent coordinates and speeds and reference motion
    (a family's: its default member's coordinates, and the family's parameters, which choose the member)."""
    system = entry.member(entry.parameters.defaults())
    coordinates = [{"name": c.name, "latex": c.latex, "unit": c.unit} for c in system.coordinates]
    reference = system.reference
    return {
        "id": entry.id,
        "title": entry.title,
        "chapter": entry.chapter,
        "coordinates": coordinates,
        "speeds": [
            {"name": c.rate.name, "latex": f"\\dot{{{c.latex}}}", "unit": c.rate_unit} for c in system.coordinates
        ],
        "formulations": list(PARTS_FORMULATIONS),
        "unavailable": {},
        "parameters": entry.parameters.schema(),
        "assumptions": entry.assumptions,
        "dependent_coordinates": list(system.dependent_coordinates),
        "dependent_speeds": list(system.dependent_speeds),
        "reference": None if reference is None else {"about": reference.about, "states": reference.state_names},
    }


def _known(catalogue) -> str:
    return ", ".join([*catalogue.derivations, *catalogue.multibody])


def _system(catalogue, system_id: str) -> SystemDescription:
    system = catalogue.derivations.get(system_id)
    if system is None:
        if system_id in catalogue.multibody:
            raise ParameterError(
                "formulation",
                f"{system_id} is built of parts; its equations are generated code, not shown as LaTeX: ask "
                f"/api/systems/{system_id}/rhs or /eigenvalues",
            )
        raise HTTPException(status_code=404, detail=f"no system {system_id!r}; known: {_known(catalogue)}")
    return system


def _parts_system(catalogue, system_id: str) -> MultibodySystem | MultibodyFamily:
    system = catalogue.multibody.get(system_id)
    if system is None:
        if system_id in catalogue.derivations:
            raise ParameterError("system_id", f"{system_id} has no reference motion to linearise about")
        raise HTTPException(status_code=404, detail=f"no system {system_id!r}; known: {_known(catalogue)}")
    return system


def _derived(system: SystemDescription, formulation: str):
    try:
        return derived(system, formulation)
    except FormulationUnavailable as error:
        raise ParameterError("formulation", f"{formulation} does not apply to {system.id}: {error}") from None


@router.get("", response_model=list[SystemSummary])
def list_systems(catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """Every catalogue system: id, title, chapter, coordinates, speeds, the formulations available, parameter schema."""
    return [summary(system) for system in catalogue.derivations.values()] + [
        parts_summary(system) for system in catalogue.multibody.values()
    ]


@router.post(
    "/custom/derive",
    response_model=CustomDeriveAnswer,
    responses=error_responses(
        unprocessable=(
            "A name, value or formula is refused, the derivation exceeded its time or memory bound, or the mass "
            "matrix is singular; `loc` names the field"
        ),
        busy="Two typed derivations are already running; the `Retry-After` header says when to try again (s)",
        unavailable=(
            "The derivation's process was stopped from outside (not by its "
            "limits); the `Retry-After` header says when to try again (s)"
        ),
    ),
)
def derive_custom(request: CustomDeriveRequest) -> dict[str, Any]:
    """Lagrange's equations for typed energies T and V (parsed by a whitelisting parser; derived in a bounded
    process)."""
    answer = derive_typed_bounded(request.model_dump())
    answer["params"] = dict(request.parameters)
    return answer


@router.post(
    "/{system_id}/derive",
    response_model=DeriveAnswer,
    responses=error_responses(
        not_found="No system has this id",
        unprocessable="A parameter is out of range, or the formulation does not apply (the message says why)",
    ),
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
    responses=error_responses(
        not_found="No system has this id",
        unprocessable=(
            "The state has the wrong length or is not finite, a parameter is out of "
            "range, the formulation does not apply, or the equations have no finite value "
            "at this state or time (`loc` names `state` or `t` and the message says why)"
        ),
    ),
)
def system_rhs(system_id: str, request: RhsRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """The state derivative (q̇, q̈) at a state (q, q̇) by one formulation: every formulation answers the same
    quantity."""
    if system_id in catalogue.multibody:
        return _parts_rhs(catalogue.multibody[system_id], request)
    system = _system(catalogue, system_id)
    params = system.parameters.validate(request.params)
    n = len(system.coordinates)
    if len(request.state) != 2 * n:
        names = [c.name for c in system.coordinates]
        raise ParameterError(
            "state", f"give {2 * n} numbers: {', '.join(names)}, then their rates (got {len(request.state)})"
        )
    if not all(math.isfinite(x) for x in request.state):
        raise ParameterError("state", "every number of the state must be finite")
    if not math.isfinite(request.t):
        raise ParameterError("t", "must be a finite time (s)")
    result, state, p = (
        _derived(system, request.formulation),
        np.array(request.state),
        np.array(system.parameter_array(params)),
    )
    derivative, because = result.evaluate(request.t, state, p)
    if because:
        raise _not_finite(
            system,
            request.formulation,
            request.t,
            state,
            because,
            finite_at_zero_time=not result.evaluate(0.0, state, p)[1],
        )
    return {"state_derivative": derivative.tolist()}


def _not_finite(
    system: SystemDescription,
    formulation: str,
    t_s: float,
    state: np.ndarray,
    because: str,
    *,
    finite_at_zero_time: bool,
) -> ParameterError:
    """The refusal of a state (or a time) where the equations have no finite value: which field, and why.

    The time is to blame when the same state at t = 0 is fine (a drive's angle ω t overflowing); else the state, at the
    coordinates' own singularity when one of the description's is zero there to within :data:`AT_SINGULARITY`.
    """
    if finite_at_zero_time and t_s != 0.0:
        return ParameterError(
            "t",
            f"at t = {t_s:g} s the {formulation} equations have no "
            f"finite value because {because}; this state is fine at t = 0",
        )
    message = f"at this state the {formulation} equations have no finite value because {because}"
    values = dict(zip(system.q, state[: len(system.coordinates)].tolist()))
    for singularity in system.singularities:
        value = float(singularity.where.subs(values))
        if abs(value) <= AT_SINGULARITY:
            return ParameterError(
                "state",
                f"{message}. It is at the coordinates' singularity, {singularity.label} = {value:.3g}: "
                f"{singularity.text}",
            )
    return ParameterError("state", message)


#: A singularity's expression this close to zero (its natural scale is 1: a sine or cosine) counts as being at it.
AT_SINGULARITY = 1e-6


#: A state meets a system's constraints when its configuration residual (m) and velocity residual (m/s) are this small.
CONSTRAINT_TOLERANCE = 1e-8


def _parts_rhs(entry: MultibodySystem | MultibodyFamily, request: RhsRequest) -> dict[str, Any]:
    """(q̇, q̈) of a system built of parts, at a state that meets its constraints (else 422 saying by how much)."""
    if request.formulation not in PARTS_FORMULATIONS:
        raise ParameterError(
            "formulation", f"{entry.id} is derived by {' and '.join(PARTS_FORMULATIONS)} (with multipliers)"
        )
    params = entry.parameters.validate(request.params)
    system = entry.member(params)
    n = len(system.coordinates)
    if len(request.state) != 2 * n:
        names = [c.name for c in system.coordinates]
        raise ParameterError(
            "state", f"give {2 * n} numbers: {', '.join(names)}, then their rates (got {len(request.state)})"
        )
    if not all(math.isfinite(x) for x in request.state):
        raise ParameterError("state", "every number of the state must be finite")
    model = compiled(system, formulation=request.formulation)
    p = model.parameter_array(params)
    q, u = np.array(request.state[:n]), np.array(request.state[n:])
    residual = model.constraint_residual(q, u, p)
    if residual > CONSTRAINT_TOLERANCE:
        raise ParameterError(
            "state",
            f"the state does not meet the constraints (residual {residual:.3g}, in m and m/s; at most "
            f"{CONSTRAINT_TOLERANCE:g}): {', '.join(system.dependent_coordinates)} and the rates of "
            f"{', '.join(system.dependent_speeds)} follow from the others",
        )
    with np.errstate(all="ignore"):
        accelerations = model.accelerations(q, u, p)
    if not np.all(np.isfinite(accelerations)):
        raise ParameterError("state", "at this state the equations have no finite value (a singular mass matrix)")
    return {"state_derivative": [*u.tolist(), *accelerations.tolist()]}


@router.post(
    "/{system_id}/eigenvalues",
    response_model=EigenvaluesAnswer,
    responses=error_responses(
        not_found="No system has this id",
        unprocessable=(
            "A parameter is out of range, the system has no reference motion, or with these parameters the "
            "reference motion cannot be assembled or has no finite linear model (the message says why)"
        ),
    ),
)
def system_eigenvalues(system_id: str, request: EigenvaluesRequest, catalogue: CatalogueDep) -> dict[str, Any]:
    """The eigenvalues (1/s) of the system linearised about its reference motion (for the bicycle: upright,
    straight-ahead rolling at ``speed_m_s``), and the states of that linear model."""
    entry = _parts_system(catalogue, system_id)
    params = entry.parameters.validate(request.params)
    system = entry.member(params)
    reference = system.reference
    if reference is None:
        raise ParameterError("system_id", f"{system_id} has no reference motion to linearise about")
    model = compiled(system)
    try:
        with np.errstate(all="ignore"):
            A = state_matrix(model, params, reference)
    except ConstraintsNotMet as error:
        raise ParameterError(
            "params", f"with these parameters the reference motion cannot be assembled: {error}"
        ) from None
    if not np.all(np.isfinite(A)):
        raise ParameterError("params", "with these parameters the equations have no finite value at the reference")
    values = eigenvalues(A)
    answer: dict[str, Any] = {
        "eigenvalues": _listed(values),
        "states": reference.state_names,
        "about": reference.about,
        "stable": bool(np.all(values.real < 0)),
        "unit": "1/s",
        "params": params,
    }
    if request.sweep is not None:
        answer["sweep"] = _sweep(entry, system, model, params, request.sweep)
    return answer


def _listed(values: np.ndarray) -> list[dict[str, float]]:
    return [{"re": float(v.real), "im": float(v.imag)} for v in values]


#: Sweeps kept (the lesson page asks the same one for every student who opens it).
_SWEEPS: OrderedDict[tuple, Sweep] = OrderedDict()
_SWEEPS_KEPT = 32
_sweeps_lock = threading.Lock()


def _sweep(
    entry: MultibodySystem | MultibodyFamily, system: MultibodySystem, model, params: dict[str, Any], request
) -> dict[str, Any]:
    """The eigenvalues along the sweep the request asks for (each value validated as the parameter's; a family's
    structure, such as a chain's number of links, is not swept)."""
    reference = system.reference
    assert reference is not None
    if request.parameter not in system.parameters.by_name:
        known = ", ".join(system.parameters.by_name)
        raise ParameterError("sweep", f"{request.parameter!r} is no parameter to sweep of {entry.id} (known: {known})")
    if not request.low < request.high:
        raise ParameterError("sweep", f"low ({request.low:g}) must be below high ({request.high:g})")
    for end in (request.low, request.high):
        entry.parameters.validate({**params, request.parameter: end})  # each end in the parameter's range
    key = (
        system.fingerprint(),
        tuple(sorted(params.items())),
        request.parameter,
        request.low,
        request.high,
        request.points,
    )
    with _sweeps_lock:
        found = _SWEEPS.get(key)
    if found is None:
        try:
            with np.errstate(all="ignore"):
                found = sweep(
                    model, params, reference, parameter=request.parameter, low=request.low, high=request.high,
                    points=request.points,
                )  # fmt: skip
        except ConstraintsNotMet as error:
            raise ParameterError(
                "sweep", f"along the sweep the reference motion cannot be assembled: {error}"
            ) from None
        if not np.all(np.isfinite(found.eigenvalues)):
            raise ParameterError("sweep", "along the sweep the equations have no finite value at the reference")
        with _sweeps_lock:
            _SWEEPS[key] = found
            while len(_SWEEPS) > _SWEEPS_KEPT:
                _SWEEPS.popitem(last=False)
    return {
        "parameter": found.parameter,
        "unit": system.parameters.by_name[found.parameter].unit,
        "values": found.values.tolist(),
        "eigenvalues": [_listed(row) for row in found.eigenvalues],
        "crossings": [{"value": c.value, "becomes": c.becomes, "oscillating": c.oscillating} for c in found.crossings],
    }
