"""A Lagrangian the student types, integrated live from the equations the engine derives for it.

The student gives the number of coordinates n (1 to 3, named q1…q3, rates
q1d…q3d), the kinetic energy T(q, q̇, t) and potential energy V(q, t) as text,
and named constants (``"m = 1, l = 0.5, g = 9.81"``). The energies are parsed
and Lagrange's equations derived only through :mod:`app.physics.mechanics.typed`
(a whitelisting parser, then sympy in a bounded child process); the generated
right-hand side is compiled by numba in a bounded child too, so the parent
loads numba's disk cache and never runs unbounded work on what was typed.

State: (q1…qn, q̇1…q̇n), in the units the energies give the coordinates (rad
for an angle, m for a length). The conserved quantity, when t does not appear
in T or V, is the energy function (Jacobi integral) h = Σ q̇ᵢ ∂L/∂q̇ᵢ − L,
which equals T + V when T is quadratic in the rates. When t appears,
nothing general is conserved and the model reports no invariant.
"""

from __future__ import annotations

import math
import re
import threading
import time
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.bounded import WorkBusy, WorkInterrupted, WorkRefused
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.expressions import check_parameter_name
from app.physics.mechanics.description import TIME, SystemDescription
from app.physics.mechanics.engine import Derived, derived
from app.physics.mechanics.mass_matrix import (
    SingularCrossing,
    first_singular_crossing,
    mass_matrices,
    not_positive_definite,
)
from app.physics.mechanics.model import DerivedModel, energy_functions
from app.physics.mechanics.typed import (
    COORDINATE_NAMES,
    MAX_PARAMETER_VALUE,
    MAX_PARAMETERS,
    derive_typed_bounded,
    describe_state,
    runner,
    typed_system,
)
from app.physics.solvers.integrated_model import ModelLimit

#: The defaults: a double pendulum of two equal bobs m on two equal rods l (q1, q2 from the downward vertical).
DEFAULT_KINETIC_ENERGY = "m*l^2*(2*q1d^2 + q2d^2 + 2*cos(q1 - q2)*q1d*q2d)/2"
DEFAULT_POTENTIAL_ENERGY = "-m*g*l*(2*cos(q1) + cos(q2))"
DEFAULT_PARAMETERS = "m = 1, l = 0.5, g = 9.81"
#: Longest energy text (characters).
MAX_ENERGY_LENGTH = 400
#: Step of the complex-step derivative d/dε T(q, (1 + iε) q̇): exact to rounding for any analytic T.
_COMPLEX_STEP = 1e-20
#: Prepared (derived and compiled) Lagrangians kept in this process.
PREPARED_ENTRIES = 32

_CONSTANT = re.compile(r"\s*([^=\s]*)\s*=\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*", re.ASCII)


def parse_constants(text: str) -> dict[str, float]:
    """``"m = 1, l = 0.5"`` → ``{"m": 1.0, "l": 0.5}``: comma-separated name = number pairs (never evaluated).

    Names must pass :func:`check_parameter_name`; numbers are plain decimals, finite, of
    magnitude at most MAX_PARAMETER_VALUE. Raises ValueError saying which pair is wrong.
    """
    if not isinstance(text, str):
        raise ValueError("must be text such as m = 1, l = 0.5")
    if not text.strip():
        return {}
    constants: dict[str, float] = {}
    for index, item in enumerate(text.split(","), start=1):
        match = _CONSTANT.fullmatch(item)
        shown = item.strip() if len(item.strip()) <= 24 else item.strip()[:21] + "..."
        if match is None:
            raise ValueError(f"pair {index} ({shown!r}) is not name = number, e.g. m = 1.5 or k = 2e3")
        name, number = match.groups()
        check_parameter_name(name)
        if name in constants:
            raise ValueError(f"{name!r} is named twice")
        value = float(number)
        if not math.isfinite(value) or abs(value) > MAX_PARAMETER_VALUE:
            raise ValueError(
                f"{name} = {number}: a value must be finite and at most {MAX_PARAMETER_VALUE:g} in magnitude"
            )
        constants[name] = value
    if len(constants) > MAX_PARAMETERS:
        raise ValueError(f"at most {MAX_PARAMETERS} named constants (got {len(constants)})")
    return constants


def typed_request(params: Mapping[str, Any]) -> dict[str, Any]:
    """The typed-derivation request (as :mod:`~app.physics.mechanics.typed` takes it) for the scene's values."""
    try:
        constants = parse_constants(params["parameters"])
    except ValueError as error:
        raise ParameterError("parameters", str(error)) from None
    return {
        "coordinates": list(COORDINATE_NAMES[: int(params["coordinates"])]),
        "kinetic_energy": params["kinetic_energy"],
        "potential_energy": params["potential_energy"],
        "parameters": constants,
    }


def compile_typed_kernel(request: Mapping[str, Any]) -> float:
    """In a bounded child: load the (already derived) right-hand side and compile it with numba; the compile time (s).

    numba writes the compiled kernel to its disk cache beside the generated module, so
    the parent's :meth:`Derived.kernel` then loads it instead of compiling.
    """
    system = typed_system(
        request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"]
    )
    result = derived(system, "lagrange")
    start = time.perf_counter()
    result.kernel()
    return time.perf_counter() - start


@dataclass(frozen=True)
class PreparedLagrangian:
    """A typed Lagrangian ready to run: its system, its compiled derivation and how it was obtained."""

    system: SystemDescription
    derived: Derived
    parameter_values: tuple[float, ...]
    #: Whether t appears explicitly in T or V.
    explicit_time: bool
    #: Time sympy took to derive the equations (s; 0 when they came from the disk cache).
    derive_s: float
    #: Whether the derivation came from the disk cache.
    cached: bool
    #: Time numba took to compile the right-hand side in the bounded child (s).
    compile_s: float


_prepared: OrderedDict[str, PreparedLagrangian] = OrderedDict()
_prepared_lock = threading.Lock()


def _request_key(request: Mapping[str, Any]) -> str:
    return repr(
        (
            request["coordinates"],
            request["kinetic_energy"],
            request["potential_energy"],
            sorted(request["parameters"].items()),
        )
    )


def prepare_typed_lagrangian(request: Mapping[str, Any]) -> PreparedLagrangian:
    """Derive (bounded, :func:`derive_typed_bounded`) and compile (bounded) a typed Lagrangian, once per request per
    process.

    Raises ParameterError naming the field for a bad formula, a singular mass matrix or
    a derivation over its bounds (``kinetic_energy``), as the whole-set check must; WorkBusy or WorkInterrupted
    (answered 429 / 503 with Retry-After) when the server could not derive it now.
    """
    key = _request_key(request)
    with _prepared_lock:
        if key in _prepared:
            _prepared.move_to_end(key)
            return _prepared[key]
    try:
        answer = derive_typed_bounded(request)
        compile_s = runner.run(compile_typed_kernel, (dict(request),), what="compiling these equations")
    except (
        ParameterError,
        WorkBusy,
        WorkInterrupted,
    ):  # busy or stopped from outside: "try again", not the input's fault
        raise
    except (WorkRefused, ValueError) as error:
        raise ParameterError("kinetic_energy", str(error)) from None
    system = typed_system(
        request["coordinates"], request["kinetic_energy"], request["potential_energy"], request["parameters"]
    )
    assert system.kinetic_energy is not None  # typed_system always gives T as typed
    result = derived(system, "lagrange")
    result.kernel()
    prepared = PreparedLagrangian(
        system=system,
        derived=result,
        parameter_values=tuple(system.parameter_array(request["parameters"])),
        explicit_time=bool(system.kinetic_energy.has(TIME) or system.extra_potential.has(TIME)),
        derive_s=float(answer["derive_s"]),
        cached=bool(answer["cached"]),
        compile_s=float(compile_s),
    )
    with _prepared_lock:
        _prepared[key] = prepared
        while len(_prepared) > PREPARED_ENTRIES:
            _prepared.popitem(last=False)
    return prepared


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """(2n,) the first n components of ``q0_rad`` then of ``qd0_rad_s``."""
    n = int(params["coordinates"])
    return np.array([*params["q0_rad"][:n], *params["qd0_rad_s"][:n]], dtype=float)


def check_typed_lagrangian(values: Mapping[str, Any]) -> None:
    """The whole-set check: derive and compile (bounded), then insist the kinetic energy is positive definite in the
    rates at the initial state: a negative eigenvalue is the kinetic energy's fault (naming ``kinetic_energy``), a
    singular mass matrix the start's (naming ``q0_rad``, as are equations with no finite value there)."""
    prepared = prepare_typed_lagrangian(typed_request(values))
    start = initial_state(values)
    where = f"at the initial state {describe_state(prepared.system, start)}"
    kind, why = not_positive_definite(
        start_mass_matrix(prepared, start), [f"{c.name}d" for c in prepared.system.coordinates]
    )
    if kind == "negative":
        raise ParameterError(
            "kinetic_energy", f"the kinetic energy must be positive definite in the rates, and {where} it is not: {why}"
        )
    if why:
        raise ParameterError("q0_rad", f"{where} the mass matrix is not positive definite: {why}; start somewhere else")
    _, because = prepared.derived.evaluate(0.0, start, np.array(prepared.parameter_values))
    if because:
        raise ParameterError(
            "q0_rad", f"{where} Lagrange's equations have no finite value because {because}: start somewhere else"
        )


def start_mass_matrix(prepared: PreparedLagrangian, start: np.ndarray) -> np.ndarray:
    """∂²T/∂q̇² (n, n) at the state (q, q̇) ``start`` and t = 0, from T numerically
    (:mod:`~app.physics.mechanics.mass_matrix`)."""
    n = len(prepared.system.coordinates)
    kinetic, _ = energy_functions(prepared.system)
    return mass_matrices(
        kinetic, np.zeros(1), start[:n, None], start[n : 2 * n, None], np.array(prepared.parameter_values)
    )[0]


#: ``stats.status`` of a motion stopped where the mass matrix became singular.
SINGULAR_MASS_MATRIX = "singular_mass_matrix"


def singular_message(system: SystemDescription, t_before_s: float, t_after_s: float, crossing: SingularCrossing) -> str:
    """What a student reads when the motion between two frames meets a singular mass matrix."""
    n = len(system.coordinates)
    # Where the parabola puts the point: to rounding (1e-12 of the segment), so what is below 1e-9 is shown as 0.
    where = ", ".join(
        f"{c.name} = {value if abs(value) > 1e-9 else 0.0:.3g}" for c, value in zip(system.coordinates, crossing.q[:n])
    )
    rate = f"{system.coordinates[crossing.rate_index].name}d"
    lost = (
        f"stops being positive definite (the inertia along {rate} turns negative)"
        if crossing.indefinite
        else (f"becomes singular (the inertia along {rate} vanishes)")
    )
    return (
        f"Stopped at t = {t_before_s:.2f} s: before t = {t_after_s:.2f} s the motion reaches {where}, where the "
        "mass matrix "
        f"∂²T/∂q̇² {lost}. There "
        "Lagrange's equations cannot give the accelerations: the coordinates themselves fail (as polar "
        "coordinates do at "
        f"r = 0), and the motion beyond is not this Lagrangian's."
    )


class TypedLagrangianMotion(DerivedModel):
    """The typed Lagrangian started from ``q0_rad`` and ``qd0_rad_s`` (its first n components)."""

    parameters = ParameterSet(
        (
            Parameter(
                "coordinates",
                "",
                2,
                1,
                3,
                "How many generalized coordinates: q1, q1…q2 or q1…q3",
                "n",
                kind="int",
                step=1,
            ),
            Parameter(
                "kinetic_energy",
                "J",
                DEFAULT_KINETIC_ENERGY,
                kind="text",
                max_length=MAX_ENERGY_LENGTH,
                label="T",
                description=(
                    "Kinetic energy in q1…q3, their rates q1d…q3d, t and your constants; + - * / ^ ( ) "
                    "sqrt sin cos tan exp log pi"
                ),
            ),
            Parameter(
                "potential_energy",
                "J",
                DEFAULT_POTENTIAL_ENERGY,
                kind="text",
                max_length=MAX_ENERGY_LENGTH,
                label="V",
                description="Potential energy in q1…q3, t and your constants (no rates)",
            ),
            Parameter(
                "parameters",
                "",
                DEFAULT_PARAMETERS,
                kind="text",
                max_length=200,
                label="constants",
                parse=parse_constants,
                description=(
                    f"Named constants, comma-separated: name = number (at most {MAX_PARAMETERS}), e.g. m "
                    "= 1, l = 0.5, g = 9.81"
                ),
            ),
            Parameter(
                "q0_rad",
                "rad",
                [1.0, 0.0, 0.0],
                -100.0,
                100.0,
                "Initial q1, q2, q3 (only the first n are used)",
                "q₀",
                kind="vector",
            ),
            Parameter(
                "qd0_rad_s",
                "rad/s",
                [0.0, 0.0, 0.0],
                -1000.0,
                1000.0,
                "Initial rates q̇1, q̇2, q̇3 (only the first n are used)",
                "q̇₀",
                kind="vector",
            ),
        ),
        check=check_typed_lagrangian,
    )
    series_units = {
        **{f"{q}_rad": "rad" for q in COORDINATE_NAMES},
        **{f"{q}_rate_rad_s": "rad/s" for q in COORDINATE_NAMES},
        "kinetic_energy_J": "J",
        "potential_energy_J": "J",
        "energy_J": "J",
        "jacobi_integral_J": "J",
    }
    invariant_units = {"jacobi_integral": "J"}

    def prepared(self, params: Mapping[str, Any]) -> PreparedLagrangian:
        """The prepared Lagrangian for ``params`` (from this process's cache after the check); sets
        :attr:`description`."""
        prepared = prepare_typed_lagrangian(typed_request(params))
        self.description = prepared.system
        return prepared

    def derived(self, params: Mapping[str, Any]) -> Derived:
        return self.prepared(params).derived

    def parameter_array(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.array(self.prepared(params).parameter_values)

    def system(self, params: Mapping[str, Any]):
        self.prepared(params)
        return super().system(params)

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return initial_state(params)

    def energies_and_jacobi_J(
        self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(T, V, h) in J along ``states`` (N, 2n) at ``t_s`` (N,), with h = Σ q̇ᵢ ∂T/∂q̇ᵢ − T + V.

        Σ q̇ᵢ ∂T/∂q̇ᵢ = d/dε T(q, (1 + ε) q̇) at ε = 0, taken as a complex step:
        Im T(q, (1 + iη) q̇) / η with η = 1e-20, exact to rounding (no subtraction).
        """
        prepared = self.prepared(params)
        T, V = energy_functions(prepared.system)
        n = len(prepared.system.coordinates)
        q, qd, p = states[:, :n].T, states[:, n:].T, np.array(prepared.parameter_values)
        shape = np.shape(t_s)
        kinetic = np.broadcast_to(np.asarray(T(t_s, q, qd, p), dtype=float), shape)
        potential = np.broadcast_to(np.asarray(V(t_s, q, qd, p), dtype=float), shape)
        stepped = np.asarray(T(t_s, q.astype(complex), qd * (1.0 + 1j * _COMPLEX_STEP), p))
        rates_times_momenta = np.broadcast_to(stepped.imag / _COMPLEX_STEP, shape)
        return np.array(kinetic), np.array(potential), rates_times_momenta - kinetic + potential

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        n = int(params["coordinates"])
        kinetic, potential, jacobi = self.energies_and_jacobi_J(params, t_s, states)
        out = {f"{COORDINATE_NAMES[i]}_rad": states[:, i] for i in range(n)}
        out.update({f"{COORDINATE_NAMES[i]}_rate_rad_s": states[:, n + i] for i in range(n)})
        out.update(
            kinetic_energy_J=kinetic,
            potential_energy_J=potential,
            energy_J=kinetic + potential,
            jacobi_integral_J=jacobi,
        )
        return out

    def energy_note(self, params: Mapping[str, Any]) -> str | None:
        note = "kinetic energy as you typed it (not split into translation and rotation)"
        if self.prepared(params).explicit_time:
            note += (
                "; t appears in T or V, so whatever drives that time dependence does work: dissipated shows E(0) − E(t)"
            )
        return note

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where the motion meets a singular mass matrix between two frames (status ``singular_mass_matrix``)."""
        prepared, kinetic, reference = self._singularity_reference(params)
        if reference is None:
            return None  # a start the whole-set check refuses; nothing to measure against
        crossing = first_singular_crossing(
            kinetic, t_s, states, np.array(prepared.parameter_values), reference=reference
        )
        if crossing is None:
            return None
        k = crossing.frame
        after = min(k + 1, len(t_s) - 1)
        return ModelLimit(
            k + 1, SINGULAR_MASS_MATRIX, singular_message(prepared.system, float(t_s[k]), float(t_s[after]), crossing)
        )

    def _singularity_reference(self, params: Mapping[str, Any]):
        """(prepared, T as a numpy function, M at the start or None if it is not positive definite), kept per start: a
        live scene asks once per batch of frames."""
        start = initial_state(params)
        key = (_request_key(typed_request(params)), tuple(start))
        cached = getattr(self, "_reference_cache", None)
        if cached is None or cached[0] != key:
            prepared = self.prepared(params)
            kinetic, _ = energy_functions(prepared.system)
            reference = start_mass_matrix(prepared, start)
            usable = not not_positive_definite(reference, [""] * len(reference))[0]
            cached = (key, (prepared, kinetic, reference if usable else None))
            self._reference_cache = cached
        return cached[1]

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """The Jacobi integral h (J) when t does not appear in T or V; nothing otherwise."""
        if self.prepared(params).explicit_time:
            return {}
        _, _, jacobi = self.energies_and_jacobi_J(params, np.zeros(len(states)), states)
        return {"jacobi_integral": jacobi}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """h's scale (J): the largest of |T|, |V| at the start and |ΔV| for ±1 (rad or m) in each coordinate."""
        n = int(params["coordinates"])
        probes = np.repeat(state[None, :], 2 * n + 1, axis=0)
        for i in range(n):
            probes[1 + 2 * i, i] += 1.0
            probes[2 + 2 * i, i] -= 1.0
        with np.errstate(
            divide="ignore", invalid="ignore", over="ignore"
        ):  # a probe may land where V is singular (−k/q1 at 0)
            kinetic, potential, _ = self.energies_and_jacobi_J(params, np.zeros(len(probes)), probes)
        swings = np.abs(potential - potential[0])
        scale = max(
            abs(float(kinetic[0])),
            abs(float(potential[0])),
            float(np.max(swings[np.isfinite(swings)], initial=0.0)),
            1e-12,
        )
        return {"jacobi_integral": scale}
