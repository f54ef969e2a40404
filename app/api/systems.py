"""``/api/systems``: the derivation engine (chapters 7–9) over HTTP.

Derivations are cached (memory and disk), so only the first request for a
system and formulation runs sympy; the routes are plain ``def`` so that work
runs in the thread pool, never on the event loop. A typed Lagrangian is
derived in a bounded child process (time and memory limits) and refused with
a 422 naming the field when it cannot be.
"""

from __future__ import annotations

import json
import math
import threading
from collections import OrderedDict
from typing import Any

import numpy as np
from fastapi import APIRouter, HTTPException

from app.api.deps import CatalogueDep, ClientDep
from app.api.errors import unprocessable
from app.api.schemas.errors import error_responses
from app.api.schemas.systems import (
    CustomDeriveAnswer,
    CustomDeriveRequest,
    DeriveAnswer,
    DeriveRequest,
    DescribeAnswer,
    DescribeRequest,
    EigenvaluesAnswer,
    EigenvaluesRequest,
    RhsAnswer,
    RhsRequest,
    SystemSummary,
)
from app.physics.core.bounded import WorkRefused
from app.physics.core.parameters import ParameterError
from app.physics.mechanics.derivation import FormulationUnavailable
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.engine import available_formulations, derived
from app.physics.mechanics.multibody import data as parts_data
from app.physics.mechanics.multibody.compiled import FORMULATIONS as PARTS_FORMULATIONS
from app.physics.mechanics.multibody.compiled import CompiledSystem, ConstraintsNotMet, NoValueHere
from app.physics.mechanics.multibody.linearise import Sweep, eigenvalues, state_matrix, sweep
from app.physics.mechanics.multibody.parts import MultibodyFamily, MultibodySystem, ReferenceMotion
from app.physics.mechanics.multibody.prepared import (
    description_key,
    prepared,
    prepared_description,
    refused_before,
    shown_derivation,
)
from app.physics.mechanics.typed import derive_typed_bounded
from app.physics.systems import multibody_member

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


#: Rest at a configuration is an equilibrium when every acceleration there is at most this (rad/s², m/s²).
EQUILIBRIUM_TOLERANCE = 1e-8


@router.post(
    "/custom/describe",
    response_model=DescribeAnswer,
    responses=error_responses(
        unprocessable=(
            "The description (JSON or TOML) is refused, a parameter or the state is refused (off the constraints: "
            "by how much), rest there is no equilibrium, or the derivation exceeded its time or memory bound; "
            "`loc` names the field"
        ),
        busy="Every place for a derivation is taken; the `Retry-After` header says when to try again (s)",
        unavailable=(
            "The derivation's process was stopped from outside (not by its limits); the `Retry-After` header says "
            "when to try again (s)"
        ),
    ),
)
def describe_custom(request: DescribeRequest, client: ClientDep) -> dict[str, Any]:
    """A system described by its parts (bodies, joints, contacts) as JSON or TOML: derived in the bounded process
    typed Lagrangians use (its generated code kept on disk), then its size, energies, state derivative and, with
    ``linearise``, its eigenvalues."""
    text = request.toml if request.toml is not None else json.dumps(request.description, sort_keys=True)
    refused_before(description_key(text))  # a description that ran into its limits lately: refused before reading
    try:
        system, data, root = _described_system(request)
        params = _validated(system, request.params)
    except ParameterError as error:
        raise unprocessable(["body", *error.path], error.message) from None
    try:
        model, derived_now = prepared_description(data, root, system, text=text, client=client)
    except ParameterError as error:
        raise unprocessable(["body", *error.path], error.message) from None
    except ValueError as error:
        if isinstance(error, WorkRefused):
            raise
        raise unprocessable(["body", root], str(error)) from None
    cached = not derived_now
    try:
        return _describe_answer(system, model, params, request, cached=cached)
    except ParameterError as error:
        raise unprocessable(["body", *error.path], error.message) from None


def _described_system(request: DescribeRequest) -> tuple[MultibodySystem, dict[str, Any], str]:
    if (request.description is None) == (request.toml is None):
        raise ParameterError("description", "give the system as description (JSON) or as toml, one of the two")
    data: dict[str, Any] | None = request.description
    root = "description"
    if request.toml is not None:
        data, root = parts_data.parse_toml(request.toml), "toml"
    assert data is not None
    return parts_data.system_from_data(data, root=root), data, root


def _validated(system: MultibodySystem, params: dict[str, Any]) -> dict[str, Any]:
    try:
        return system.parameters.validate(params)
    except ParameterError as error:
        if error.path[0] in system.parameters.by_name:
            raise ParameterError("params", error.message, path=("params", *error.path)) from None
        raise ParameterError("params", error.message, path=("params", *error.path[1:])) from None


def _units(system: MultibodySystem) -> tuple[list[str], list[str], list[str]]:
    """The units of q, of q̇ and of q̈, coordinate by coordinate."""
    units = [c.unit for c in system.coordinates]
    return units, [f"{u}/s" for u in units], [f"{u}/s²" for u in units]


def _describe_answer(
    system: MultibodySystem, model: CompiledSystem, params: dict[str, Any], request: DescribeRequest, *, cached: bool
) -> dict[str, Any]:
    n = len(system.coordinates)
    p = model.parameter_array(params)
    q_units, u_units, a_units = _units(system)
    answer: dict[str, Any] = {
        "id": system.id,
        "title": system.title,
        "coordinates": [{"name": c.name, "latex": c.latex, "unit": c.unit} for c in system.coordinates],
        "dependent_coordinates": list(system.dependent_coordinates),
        "dependent_speeds": list(system.dependent_speeds),
        "degrees_of_freedom": {
            "configuration": n - len(system.dependent_coordinates),
            "speeds": n - len(system.dependent_speeds),
        },
        "operations": dict(model.operations),
        "derive_s": model.derive_s,
        "generate_s": model.generate_s,
        "load_s": model.load_s,
        "cached": cached,
        "parameters": system.parameters.schema(),
        "params": params,
        "state_units": q_units + u_units,
    }
    if request.state is not None:
        if len(request.state) != 2 * n:
            names = [c.name for c in system.coordinates]
            raise ParameterError(
                "state", f"give {2 * n} numbers: {', '.join(names)}, then their rates (got {len(request.state)})"
            )
        if not all(math.isfinite(x) and abs(x) <= 1e6 for x in request.state):
            raise ParameterError("state", "every number of the state must be finite, of magnitude at most 1e6")
        answer["state_derivative"] = _state_derivative(model, p, request.state, "state")
        answer["state_derivative_units"] = u_units + a_units
        q, u = np.array(request.state[:n]), np.array(request.state[n:])
        answer["state_is"] = "given"
    else:
        try:
            with np.errstate(all="ignore"):
                q, u = model.assemble(np.zeros(n), np.zeros(n), p)
        except (ConstraintsNotMet, NoValueHere) as error:
            raise ParameterError("description", f"the zero configuration cannot be assembled: {error}") from None
        answer["state_is"] = "rest at the zero configuration (the dependent coordinates solved from the constraints)"
    try:
        translational, rotational, potential = model.energy_parts(q, u, p)
    except NoValueHere as error:
        raise ParameterError("state", f"at this state {error}") from None
    if not all(math.isfinite(x) for x in (translational, rotational, potential)):
        raise ParameterError("state", "the energies have no finite value at this state")
    answer["state"] = [*q.tolist(), *u.tolist()]
    answer["energies"] = {
        "kinetic_J": translational + rotational,
        "potential_J": potential,
        "translational_J": translational,
        "rotational_J": rotational,
        "total_J": translational + rotational + potential,
    }
    if request.linearise:
        answer["linear"] = _described_linear(system, model, params, q)
    return answer


def _described_linear(
    system: MultibodySystem, model: CompiledSystem, params: dict[str, Any], q: np.ndarray
) -> dict[str, Any]:
    """Eigenvalues about the description's reference motion, or about rest at the configuration ``q``."""
    reference = system.reference
    p = model.parameter_array(params)
    n = len(system.coordinates)
    if reference is None:
        try:
            with np.errstate(all="ignore"):
                q0, u0 = model.assemble(q, np.zeros(n), p)
                accelerations = model.accelerations(q0, u0, p)
        except (ConstraintsNotMet, NoValueHere) as error:
            raise ParameterError("state", f"rest at this configuration cannot be assembled: {error}") from None
        worst = int(np.argmax(np.abs(accelerations))) if n else 0
        if not np.all(np.isfinite(accelerations)) or abs(accelerations[worst]) > EQUILIBRIUM_TOLERANCE:
            c = system.coordinates[worst]
            raise ParameterError(
                "linearise",
                f"rest at this configuration is no equilibrium: released there, {c.name} accelerates at "
                f"{accelerations[worst]:.6g} {c.unit}/s² (at most {EQUILIBRIUM_TOLERANCE:g} counts as rest); give a "
                "state at an equilibrium, or a reference motion in the description",
            )
        independent_q = tuple(c.name for c in system.coordinates if c.name not in system.dependent_coordinates)
        independent_u = tuple(c.name for c in system.coordinates if c.name not in system.dependent_speeds)
        reference = ReferenceMotion(
            about="rest at the given configuration" if q.any() else "rest at the zero configuration",
            coordinates=independent_q,
            speeds=independent_u,
            state=lambda _params: (q0, u0),
        )
    try:
        with np.errstate(all="ignore"):
            A = state_matrix(model, params, reference)
    except (ConstraintsNotMet, NoValueHere) as error:
        raise ParameterError("linearise", f"the reference motion cannot be assembled: {error}") from None
    if not np.all(np.isfinite(A)):
        raise ParameterError("linearise", "the equations have no finite value about the reference motion")
    values = eigenvalues(A)
    return {
        "about": reference.about,
        "states": reference.state_names,
        "eigenvalues": _listed(values),
        "stable": bool(np.all(values.real < 0)),
        "unit": "1/s",
    }


@router.post(
    "/{system_id}/derive",
    response_model=DeriveAnswer,
    responses=error_responses(
        not_found="No system has this id",
        unprocessable=(
            "A parameter is out of range, the formulation does not apply (the message says why), or a system built "
            "of parts took longer than its bound to derive the first time"
        ),
        busy="A system built of parts, derived the first time: every place for a derivation is taken (Retry-After)",
        unavailable="A first derivation's process was stopped from outside; the `Retry-After` header says when",
    ),
)
def derive_system(system_id: str, request: DeriveRequest, catalogue: CatalogueDep, client: ClientDep) -> dict[str, Any]:
    """The equations of motion by one formulation, with the steps that lead to them (LaTeX). A system built of parts
    (kane or lagrange, with multipliers) shows each frame's angular velocity and each body's mass-centre velocity,
    the constraint rows and M u̇ = f + Aᵀλ, A u̇ = b, entries written out where short; its first derivation runs in
    the bounded process typed Lagrangians use, and is kept."""
    if system_id in catalogue.multibody:
        return _parts_derive(system_id, catalogue.multibody[system_id], request, client)
    system = _system(catalogue, system_id)
    params = system.parameters.validate(request.params)
    answer = _derived(system, request.formulation).answer()
    answer["params"] = params
    return answer


def _parts_derive(
    system_id: str, entry: MultibodySystem | MultibodyFamily, request: DeriveRequest, client: str | None
) -> dict[str, Any]:
    if request.formulation not in PARTS_FORMULATIONS:
        raise ParameterError(
            "formulation", f"{system_id} is derived by {' and '.join(PARTS_FORMULATIONS)} (with multipliers)"
        )
    params = entry.parameters.validate(request.params)
    system = entry.member(params)
    answer = dict(shown_derivation(multibody_member, system_id, params, system, request.formulation, client=client))
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
def system_rhs(system_id: str, request: RhsRequest, catalogue: CatalogueDep, client: ClientDep) -> dict[str, Any]:
    """The state derivative (q̇, q̈) at a state (q, q̇) by one formulation: every formulation answers the same
    quantity."""
    if system_id in catalogue.multibody:
        return _parts_rhs(catalogue.multibody[system_id], request, client)
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


def _parts_rhs(entry: MultibodySystem | MultibodyFamily, request: RhsRequest, client: str | None) -> dict[str, Any]:
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
    model = prepared(multibody_member, entry.id, params, system, request.formulation, client=client)
    return {"state_derivative": _state_derivative(model, model.parameter_array(params), request.state, "state")}


def _state_derivative(model: CompiledSystem, p: np.ndarray, state: list[float], field: str) -> list[float]:
    """(q̇, q̈) at a state (q, q̇) that meets the constraints; a ParameterError naming ``field`` if it does not (by how
    much) or the equations have no finite value there."""
    system = model.system
    n = len(system.coordinates)
    q, u = np.array(state[:n]), np.array(state[n:])
    try:
        residual = model.constraint_residual(q, u, p)
        accelerations = model.accelerations(q, u, p) if residual <= CONSTRAINT_TOLERANCE else None
    except NoValueHere as error:
        raise ParameterError(field, f"at this state {error}") from None
    if accelerations is None:
        raise ParameterError(
            field,
            f"the state does not meet the constraints (residual {residual:.3g}, in m and m/s; at most "
            f"{CONSTRAINT_TOLERANCE:g}): {', '.join(system.dependent_coordinates)} and the rates of "
            f"{', '.join(system.dependent_speeds)} follow from the others",
        )
    if not np.all(np.isfinite(accelerations)):
        raise ParameterError(field, "at this state the equations have no finite value (a singular mass matrix)")
    return [*u.tolist(), *accelerations.tolist()]


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
def system_eigenvalues(
    system_id: str, request: EigenvaluesRequest, catalogue: CatalogueDep, client: ClientDep
) -> dict[str, Any]:
    """The eigenvalues (1/s) of the system linearised about its reference motion (for the bicycle: upright,
    straight-ahead rolling at ``speed_m_s``), and the states of that linear model."""
    entry = _parts_system(catalogue, system_id)
    params = entry.parameters.validate(request.params)
    system = entry.member(params)
    reference = system.reference
    if reference is None:
        raise ParameterError("system_id", f"{system_id} has no reference motion to linearise about")
    model = prepared(multibody_member, entry.id, params, system, "kane", client=client)
    try:
        with np.errstate(all="ignore"):
            A = state_matrix(model, params, reference)
    except (ConstraintsNotMet, NoValueHere) as error:
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
        except (ConstraintsNotMet, NoValueHere) as error:
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
