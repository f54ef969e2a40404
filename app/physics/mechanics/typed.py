"""A Lagrangian a student types: energies in q1…q3, their rates q1d…q3d, t and named constants.

:func:`typed_system` parses the two energies with the whitelisting parser
(:func:`~app.physics.math.expressions.parse_formula`, never ``eval`` or
``sympify``) into a :class:`SystemDescription` with ``kinetic_energy`` set;
:func:`derive_typed` derives Lagrange's equations for it and checks them at
one state. Deriving what a student typed can be slow or large, so the API
runs :func:`derive_typed` in a bounded child process (see
:mod:`app.physics.core.bounded`); its result is cached on disk like any
derivation, so the parent then loads it without sympy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy

from app.physics.core.bounded import BoundedRunner
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.expressions import check_parameter_name, parse_formula
from app.physics.mechanics.description import TIME, Coordinate, SystemDescription
from app.physics.mechanics.engine import derived
from app.physics.mechanics.lagrange import lagrangian

#: Names a typed Lagrangian may use for its coordinates, in order.
COORDINATE_NAMES = ("q1", "q2", "q3")
#: Most constant parameters a student may name.
MAX_PARAMETERS = 8
#: Largest magnitude of a parameter value.
MAX_PARAMETER_VALUE = 1e6
#: A typed Lagrangian's derivation may take this long (s) and add this much memory (MB) before it is refused.
DERIVE_TIMEOUT_S = 20.0
DERIVE_MEMORY_MB = 1024.0
#: The state the answer checks the equations at: q_i = 0.3·i rad, q̇_i = 0.2 rad/s.
CHECK_COORDINATE_RAD, CHECK_RATE_RAD_S = 0.3, 0.2


def check_state(n: int) -> np.ndarray:
    return np.array([CHECK_COORDINATE_RAD * (i + 1) for i in range(n)] + [CHECK_RATE_RAD_S] * n)


def typed_system(
    coordinates: Sequence[str], kinetic_energy: str, potential_energy: str, parameters: Mapping[str, float]
) -> SystemDescription:
    """Parse and check a typed Lagrangian; raises ParameterError naming the field."""
    coordinates = list(coordinates)
    if not 1 <= len(coordinates) <= len(COORDINATE_NAMES) or coordinates != list(COORDINATE_NAMES[: len(coordinates)]):
        raise ParameterError("coordinates", f"name 1 to 3 coordinates in order: ['q1'], ['q1', 'q2'] or ['q1', 'q2', 'q3'] (got {coordinates!r})")
    if len(parameters) > MAX_PARAMETERS:
        raise ParameterError("parameters", f"at most {MAX_PARAMETERS} named constants (got {len(parameters)})")
    symbols: dict[str, sympy.Symbol] = {}
    coords = tuple(Coordinate(name, f"q_{name[1:]}") for name in coordinates)
    for c in coords:
        symbols[c.name] = c.symbol
    for c in coords:
        symbols[f"{c.name}d"] = c.rate
    symbols["t"] = TIME
    constants: dict[str, sympy.Symbol] = {}
    for name, value in parameters.items():
        try:
            check_parameter_name(name)
        except ValueError as error:
            raise ParameterError("parameters", str(error), path=("parameters", str(name))) from None
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not _finite(value) or abs(float(value)) > MAX_PARAMETER_VALUE:
            raise ParameterError("parameters", f"must be a finite number of magnitude at most {MAX_PARAMETER_VALUE:g} (got {value!r})", path=("parameters", name))
        constants[name] = sympy.Symbol(name, real=True)
    symbols.update(constants)
    energies = {}
    for field, text in (("kinetic_energy", kinetic_energy), ("potential_energy", potential_energy)):
        if not isinstance(text, str):
            raise ParameterError(field, "must be text, e.g. m*l^2*q1d^2/2")
        try:
            energies[field] = parse_formula(text, symbols=symbols)
        except ValueError as error:
            raise ParameterError(field, str(error)) from None
    T, V = energies["kinetic_energy"], energies["potential_energy"]
    rates = {c.rate for c in coords}
    if V.free_symbols & rates:
        raise ParameterError("potential_energy", "the potential energy may not depend on the rates q1d…q3d")
    for c in coords:
        if not T.has(c.rate):
            raise ParameterError("kinetic_energy", f"the kinetic energy does not contain {c.name}d, so {c.name} has no inertia and its equation cannot be solved for its acceleration")
    return SystemDescription(
        id="custom", title="Typed Lagrangian", chapter=7, coordinates=coords,
        parameters=ParameterSet(tuple(Parameter(name, "", float(value), min=-MAX_PARAMETER_VALUE, max=MAX_PARAMETER_VALUE, label=name) for name, value in parameters.items())),
        symbols=constants, kinetic_energy=T, extra_potential=V,
    )  # fmt: skip


def _finite(value: float) -> bool:
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False


def derive_typed(request: Mapping[str, Any]) -> dict[str, Any]:
    """Derive a typed Lagrangian's equations and check them at one state (run this in a bounded process).

    Returns the derive answer plus ``rhs_check``: the state (q, q̇), t = 0 and
    the state derivative there. Raises ParameterError for a singular mass matrix.
    """
    system = typed_system(request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"])
    T, _ = lagrangian(system)
    mass_matrix = sympy.hessian(T, system.qd)
    if sympy.simplify(mass_matrix.det()) == 0:
        raise ParameterError("kinetic_energy", "the mass matrix ∂²T/∂q̇² is singular everywhere: some combination of rates carries no kinetic energy")
    result = derived(system, "lagrange")
    state = check_state(len(system.coordinates))
    derivative = result.state_derivative(0.0, state, np.array(system.parameter_array(request["parameters"])))
    if not np.all(np.isfinite(derivative)):
        raise ParameterError(
            "kinetic_energy",
            f"at the check state q = {state[: len(state) // 2].tolist()} rad, q̇ = {CHECK_RATE_RAD_S} rad/s the mass matrix is singular "
            "or the equations are not finite there",
        )
    answer = result.answer()
    answer["rhs_check"] = {"state": state.tolist(), "t": 0.0, "state_derivative": derivative.tolist()}
    return answer


#: One bounded runner per process for typed derivations (the API's and the typed-Lagrangian scene's): two at once.
runner = BoundedRunner(
    max_jobs=2, timeout_s=DERIVE_TIMEOUT_S, memory_mb=DERIVE_MEMORY_MB, wait_s=2.0,
    preload=("app.physics.core.bounded", "numpy", "sympy", __name__),
)  # fmt: skip


def derive_typed_bounded(request: Mapping[str, Any]) -> dict[str, Any]:
    """:func:`derive_typed` in a bounded child process (raises WorkTimeout, WorkTooLarge, WorkBusy or its ValueError).

    The child writes the derivation to the disk cache, so :func:`typed_derived` then loads it here without sympy.
    """
    return runner.run(derive_typed, (dict(request),), what="deriving these equations")


def typed_derived(request: Mapping[str, Any]):
    """The typed system and its Lagrange derivation, derived in a bounded child if not cached yet."""
    system = typed_system(request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"])
    derive_typed_bounded(request)
    return system, derived(system, "lagrange")
