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
from app.physics.mechanics.engine import derived, not_finite_because
from app.physics.mechanics.lagrange import lagrangian
from app.physics.mechanics.mass_matrix import mass_matrices, not_positive_definite

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
        raise ParameterError(
            "coordinates",
            f"name 1 to 3 coordinates in order: ['q1'], ['q1', 'q2'] or ['q1', 'q2', 'q3'] (got {coordinates!r})",
        )
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
        if (
            isinstance(value, bool)
            or not isinstance(value, (int, float))
            or not _finite(value)
            or abs(float(value)) > MAX_PARAMETER_VALUE
        ):
            raise ParameterError(
                "parameters",
                f"must be a finite number of magnitude at most {MAX_PARAMETER_VALUE:g} (got {value!r})",
                path=("parameters", name),
            )
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
            raise ParameterError(
                "kinetic_energy",
                f"the kinetic energy does not contain {c.name}d, so {c.name} has no inertia and its equation "
                "cannot be solved for its acceleration",
            )
    return SystemDescription(
        id="custom",
        title="Typed Lagrangian",
        chapter=7,
        coordinates=coords,
        parameters=ParameterSet(
            tuple(
                Parameter(name, "", float(value), min=-MAX_PARAMETER_VALUE, max=MAX_PARAMETER_VALUE, label=name)
                for name, value in parameters.items()
            )
        ),
        symbols=constants,
        kinetic_energy=T,
        extra_potential=V,
    )


def _finite(value: float) -> bool:
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False


def derive_typed(request: Mapping[str, Any]) -> dict[str, Any]:
    """Derive a typed Lagrangian's equations and check them at one state (run this in a bounded process).

    Returns the derive answer plus ``rhs_check``: the state (q, q̇), t = 0 and the state derivative there. Raises
    ParameterError naming the energy at fault for a mass matrix singular everywhere, an energy (or one of the
    derivatives Lagrange's equations take of it) with no finite value at the check state, and a kinetic energy not
    positive definite there.
    """
    system = typed_system(
        request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"]
    )
    T, _ = lagrangian(system)
    mass_matrix = sympy.hessian(T, system.qd)
    if sympy.simplify(mass_matrix.det()) == 0:
        raise ParameterError(
            "kinetic_energy",
            "the mass matrix ∂²T/∂q̇² is singular everywhere: some combination of rates carries no kinetic energy",
        )
    state = check_state(len(system.coordinates))
    parameters = np.array(system.parameter_array(request["parameters"]))
    where = f"at the check state {describe_state(system, state)}, t = 0"
    check_energy_terms(system, state, parameters, where=where)
    check_kinetic_energy(system, state, parameters, where=where)
    result = derived(system, "lagrange")
    derivative, because = result.evaluate(0.0, state, parameters)
    if because:
        raise ParameterError("kinetic_energy", f"{where} Lagrange's equations have no finite value because {because}")
    answer = result.answer()
    answer["rhs_check"] = {"state": state.tolist(), "t": 0.0, "state_derivative": derivative.tolist()}
    return answer


def describe_state(system: SystemDescription, state: np.ndarray) -> str:
    """``q1 = 0.3, q1d = 0.2`` for a state (q, q̇) of a typed system, in the names the student typed."""
    n = len(system.coordinates)
    names = [c.name for c in system.coordinates] + [f"{c.name}d" for c in system.coordinates]
    return ", ".join(f"{name} = {value:.6g}" for name, value in zip(names, state[: 2 * n]))


def energy_terms(system: SystemDescription) -> list[tuple[str, str, sympy.Expr]]:
    """``(field, what, expression)`` for each energy and each derivative of it that Lagrange's equations use:
    T, ∂T/∂q̇ᵢ, ∂²T/∂q̇ᵢ∂q̇ⱼ, ∂²T/∂q̇ᵢ∂qⱼ, ∂²T/∂q̇ᵢ∂t, ∂T/∂qᵢ, then V, ∂V/∂qᵢ (in the student's names)."""
    T, V = system.kinetic_energy, system.extra_potential
    assert T is not None
    names = {c.symbol: c.name for c in system.coordinates} | {c.rate: f"{c.name}d" for c in system.coordinates}
    terms: list[tuple[str, str, sympy.Expr]] = [("kinetic_energy", "the kinetic energy T", T)]
    for rate in system.qd:
        momentum = sympy.diff(T, rate)
        terms.append(("kinetic_energy", f"∂T/∂{names[rate]}", momentum))
        terms += [
            ("kinetic_energy", f"∂²T/∂{names[rate]}∂{names[other]}", sympy.diff(momentum, other))
            for other in (*system.qd, *system.q)
        ]
        terms.append(("kinetic_energy", f"∂²T/∂{names[rate]}∂t", sympy.diff(momentum, TIME)))
    terms += [("kinetic_energy", f"∂T/∂{names[q]}", sympy.diff(T, q)) for q in system.q]
    terms.append(("potential_energy", "the potential energy V", V))
    terms += [("potential_energy", f"∂V/∂{names[q]}", sympy.diff(V, q)) for q in system.q]
    return terms


def check_energy_terms(
    system: SystemDescription, state: np.ndarray, parameters: np.ndarray, *, where: str, t_s: float = 0.0
) -> None:
    """Raise ParameterError naming the energy (``kinetic_energy`` or ``potential_energy``) whose value, or a derivative
    Lagrange's equations take of it, has no finite double-precision value at ``state`` (q, q̇), and why."""
    n = len(system.coordinates)
    arguments = [TIME, *system.q, *system.qd, *system.parameter_symbols]
    values = [float(t_s), *state[: 2 * n], *parameters]
    for field, what, expression in energy_terms(system):
        function = sympy.lambdify(arguments, expression, modules="numpy")
        try:
            with np.errstate(over="raise", divide="raise", invalid="raise", under="ignore"):
                value = complex(function(*values))
        except (ArithmeticError, ValueError) as error:
            raise ParameterError(
                field, f"{where} {what} has no finite value because {not_finite_because(error)}"
            ) from None
        if value.imag != 0.0:
            raise ParameterError(
                field, f"{where} {what} is not a real number ({value:.4g}): e.g. the square root of a negative number"
            )
        if not math.isfinite(value.real):
            raise ParameterError(field, f"{where} {what} is not finite ({value.real})")


def check_kinetic_energy(
    system: SystemDescription, state: np.ndarray, parameters: np.ndarray, *, where: str, t_s: float = 0.0
) -> None:
    """Raise ParameterError naming ``kinetic_energy`` if T is not positive definite in the rates at ``state`` (q, q̇):
    a mass matrix ∂²T/∂q̇² with a negative or zero eigenvalue
    (:func:`~app.physics.mechanics.mass_matrix.not_positive_definite`)."""
    n = len(system.coordinates)
    kinetic = sympy.lambdify(
        [TIME, system.q, system.qd, system.parameter_symbols], system.kinetic_energy, modules="numpy", cse=True
    )
    matrix = mass_matrices(kinetic, np.array([float(t_s)]), state[:n, None], state[n : 2 * n, None], parameters)[0]
    _, why = not_positive_definite(matrix, [f"{c.name}d" for c in system.coordinates])
    if why:
        raise ParameterError(
            "kinetic_energy", f"the kinetic energy must be positive definite in the rates, and {where} it is not: {why}"
        )


#: One bounded runner per process for typed derivations (the API's and the typed-Lagrangian scene's): two at once.
runner = BoundedRunner(
    max_jobs=2,
    timeout_s=DERIVE_TIMEOUT_S,
    memory_mb=DERIVE_MEMORY_MB,
    wait_s=2.0,
    preload=("app.physics.core.bounded", "numpy", "sympy", __name__),
)


def derive_typed_bounded(request: Mapping[str, Any]) -> dict[str, Any]:
    """:func:`derive_typed` in a bounded child process (raises WorkTimeout, WorkTooLarge, WorkBusy or its ValueError).

    The child writes the derivation to the disk cache, so :func:`typed_derived` then loads it here without sympy.
    """
    return runner.run(derive_typed, (dict(request),), what="deriving these equations")


def typed_derived(request: Mapping[str, Any]):
    """The typed system and its Lagrange derivation, derived in a bounded child if not cached yet."""
    system = typed_system(
        request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"]
    )
    derive_typed_bounded(request)
    return system, derived(system, "lagrange")
