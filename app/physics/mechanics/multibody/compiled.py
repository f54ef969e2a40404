"""A multibody system's equations as generated code, derived once and kept on disk.

:func:`compiled` derives the constrained equations (:mod:`.kane`), shares their
common subexpressions and writes one Python module beside the derivation cache
(``$DYNLAB_DERIVATION_CACHE``): the right-hand side ``rhs(t, y, p, dydt)`` (the
state y = (q, q̇); the (n + m) system solved by LU at each call), the
configuration constraints and their Jacobian, the velocity-constraint matrix and
the energies. A later call, in this process or the next, imports the module
without sympy. The operation counts before and after common-subexpression
elimination are kept with it.
"""

from __future__ import annotations

import ast
import hashlib
import json
import os
import threading
import time
import types
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import sympy

from app.physics.mechanics.codegen import generate_function
from app.physics.mechanics.engine import cache_directory, load_generated
from app.physics.mechanics.multibody.kane import ConstrainedEquations, equations, lagrange_form
from app.physics.mechanics.multibody.parts import MultibodySystem
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, Kernel, kernel


def _source_digest() -> str:
    digest = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        digest.update(path.name.encode() + path.read_bytes())
    digest.update((Path(__file__).parents[1] / "codegen.py").read_bytes())
    return digest.hexdigest()[:10]


#: Part of every cache key: this package's source (and the generator's), so a changed engine never reads old code.
MULTIBODY_VERSION = _source_digest()


class NoValueHere(ValueError):
    """The generated code has no value at this state and these parameters: it divided by zero, took the square root
    of a negative number or overflowed (a bicycle lying flat, whose contact geometry degenerates)."""


def _valued(call: Callable[..., None], *args: Any) -> None:
    """``call(*args)``, its arithmetic failures (Python floats raise, numpy's warn) raised as :class:`NoValueHere`."""
    try:
        with np.errstate(all="ignore"):
            call(*args)
    except (ArithmeticError, ValueError) as error:
        raise NoValueHere(f"the equations have no value here ({type(error).__name__}: {error})") from None


class ConstraintsNotMet(ValueError):
    """The dependent coordinates could not be found (the configuration cannot be assembled), or the dependent speeds
    are not determined (the constraint matrix is singular there)."""


def operations_written_out(expressions: list[sympy.Expr]) -> int:
    """Arithmetic operations in ``expressions`` written out in full, as trees: one per argument an addition or a
    product joins, one per power or function. Counted once per distinct subexpression (the count of a tree is the
    sum of its branches'), so a huge count costs no more than the expressions' size in memory."""
    memo: dict[sympy.Basic, int] = {}

    def count(expr: sympy.Basic) -> int:
        found = memo.get(expr)
        if found is None:
            own = len(expr.args) - 1 if isinstance(expr, sympy.Add | sympy.Mul) else (1 if expr.args else 0)
            found = own + sum(count(arg) for arg in expr.args)
            memo[expr] = found
        return found

    return sum(count(sympy.sympify(e)) for e in expressions)


def operations_in_code(source: str) -> int:
    """Arithmetic operations in generated Python: binary and unary operators and function calls."""
    return sum(isinstance(node, ast.BinOp | ast.UnaryOp | ast.Call) for node in ast.walk(ast.parse(source)))


@dataclass
class CompiledSystem:
    """The generated functions of one system, and how long they took (s) and how big they are (operations)."""

    system: MultibodySystem
    rhs: Callable[..., None]
    configuration: Callable[..., None]
    configuration_jacobian: Callable[..., None]
    constraint_matrix: Callable[..., None]
    energies: Callable[..., None]
    dynamics: Callable[..., None]
    constraints: Callable[..., None]
    derive_s: float
    generate_s: float
    load_s: float
    operations: Mapping[str, int]
    from_cache: bool

    _kernels: tuple[Kernel, Kernel] | None = field(default=None, repr=False)
    _kernel_lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    @property
    def n(self) -> int:
        return len(self.system.coordinates)

    def kernels(self) -> tuple[Kernel, Kernel]:
        """``dynamics`` and ``constraints`` as numba C callbacks for the DAE algorithms (compiled once a process;
        numba keeps them on disk beside the generated module)."""
        with self._kernel_lock:
            if self._kernels is None:
                self._kernels = (
                    kernel(DYNAMICS_SIGNATURE)(self.dynamics),
                    kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)(self.constraints),
                )
            return self._kernels

    def parameter_array(self, params: Mapping[str, float]) -> np.ndarray:
        return np.array(self.system.parameter_array(params), dtype=float)

    def assemble(self, q: np.ndarray, u: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(q, u) with the dependent coordinates solved from the configuration constraints (Newton's method, from
        the values given) and the dependent speeds from the velocity constraints; the rest as given.

        Raises :class:`ConstraintsNotMet` where either cannot be done."""
        system = self.system
        dependent_q = [system.index(name) for name in system.dependent_coordinates]
        dependent_u = [system.index(name) for name in system.dependent_speeds]
        independent_u = [i for i in range(self.n) if i not in dependent_u]
        q = np.array(q, dtype=float)
        if dependent_q:
            g = np.empty(len(dependent_q))
            jacobian = np.empty(len(dependent_q) * self.n)
            for _ in range(30):
                _valued(self.configuration, q, p, g)
                _valued(self.configuration_jacobian, q, p, jacobian)
                J = jacobian.reshape(len(dependent_q), self.n)[:, dependent_q]
                try:
                    step = np.linalg.solve(J, g)
                except np.linalg.LinAlgError:
                    raise ConstraintsNotMet("the configuration constraints are singular here") from None
                q[dependent_q] -= step
                if np.max(np.abs(step)) < 1e-14 * (1.0 + np.max(np.abs(q[dependent_q]))):
                    break
            else:
                raise ConstraintsNotMet("no configuration meets the constraints near the one given")
        u = np.array(u, dtype=float)
        if dependent_u:
            entries = np.empty(len(dependent_u) * self.n)
            _valued(self.constraint_matrix, q, p, entries)
            A = entries.reshape(len(dependent_u), self.n)
            try:
                u[dependent_u] = np.linalg.solve(A[:, dependent_u], -A[:, independent_u] @ u[independent_u])
            except np.linalg.LinAlgError:
                raise ConstraintsNotMet("the velocity constraints do not fix the dependent speeds here") from None
        return q, u

    def constraint_residual(self, q: np.ndarray, u: np.ndarray, p: np.ndarray) -> float:
        """The largest violation of a configuration constraint (m) or a velocity constraint (m/s) at (q, u)."""
        system = self.system
        g = np.empty(len(system.dependent_coordinates))
        _valued(self.configuration, q, p, g)
        entries = np.empty(len(system.dependent_speeds) * self.n)
        _valued(self.constraint_matrix, q, p, entries)
        velocity = entries.reshape(len(system.dependent_speeds), self.n) @ u
        return float(max(np.max(np.abs(g), initial=0.0), np.max(np.abs(velocity), initial=0.0)))

    def accelerations(self, q: np.ndarray, u: np.ndarray, p: np.ndarray) -> np.ndarray:
        """u̇ (= q̈) at a state that meets the constraints."""
        out = np.empty(2 * self.n)
        _valued(self.rhs, 0.0, np.concatenate([q, u]), p, out)
        return out[self.n :]

    def energy(self, q: np.ndarray, u: np.ndarray, p: np.ndarray) -> tuple[float, float]:
        """(kinetic, potential), J."""
        translational, rotational, potential = self.energy_parts(q, u, p)
        return translational + rotational, potential

    def energy_parts(self, q: np.ndarray, u: np.ndarray, p: np.ndarray) -> tuple[float, float, float]:
        """(½ Σ m v_G², ½ Σ ω·I_G ω, V), J."""
        out = np.empty(3)
        _valued(self.energies, q, u, p, out)
        return float(out[0]), float(out[1]), float(out[2])


_memory: dict[str, CompiledSystem] = {}
_lock = threading.Lock()
#: One lock per system and formulation: a long derivation of one never holds up another.
_key_locks: dict[str, threading.Lock] = {}


#: How the equations are formed: Kane's (partial velocities) or Lagrange's (from the energies), both with multipliers.
FORMULATIONS = {"kane": equations, "lagrange": lambda system: lagrange_form(equations(system))}


def _paths(system: MultibodySystem, formulation: str, directory: Path | None) -> tuple[Path, Path]:
    name = f"{system.id}_{formulation}".replace("-", "_")
    stem = f"multibody_{name}_{system.fingerprint()}_v{MULTIBODY_VERSION}"
    base = (directory or cache_directory()) / stem
    return base.with_suffix(".py"), base.with_suffix(".json")


_GLUE = """
N_COORDINATES, N_CONSTRAINTS, N_HOLONOMIC = {n}, {m}, {h}


def configuration(q, p, out):
    g, C, c = np.empty(N_HOLONOMIC), np.empty((N_CONSTRAINTS, N_COORDINATES)), np.empty(N_CONSTRAINTS)
    constraints(q, np.zeros(N_COORDINATES), p, g, C, c)
    out[:N_HOLONOMIC] = g


def constraint_matrix(q, p, out):
    g, C, c = np.empty(N_HOLONOMIC), np.empty((N_CONSTRAINTS, N_COORDINATES)), np.empty(N_CONSTRAINTS)
    constraints(q, np.zeros(N_COORDINATES), p, g, C, c)
    out[: N_CONSTRAINTS * N_COORDINATES] = C.ravel()


def rhs(t, y, p, dydt):
    n, m = N_COORDINATES, N_CONSTRAINTS
    q, v = y[:n], y[n:]
    M, f = np.empty((n, n)), np.empty(n)
    dynamics(t, q, v, p, M, f)
    g, C, c = np.empty(N_HOLONOMIC), np.empty((m, n)), np.empty(m)
    constraints(q, v, p, g, C, c)
    A = np.zeros((n + m, n + m))
    A[:n, :n] = M
    A[:n, n:] = C.T
    A[n:, :n] = C
    b = np.concatenate((f, c))
    if not solve_small(A, b):
        dydt[:] = math.nan
        return
    dydt[:n] = v
    dydt[n:] = b[:n]
"""


def _generate(system: MultibodySystem, derived: ConstrainedEquations, formulation: str) -> tuple[str, dict[str, int]]:
    """The module: M, f (``dynamics``) and g, C, c (``constraints``) as the DAE algorithms' kernels, each with its
    common subexpressions shared; ``rhs`` and the constraint helpers are glue over them (the (n + m) solve by LU)."""
    q, u, p = system.q, system.u, system.parameter_symbols
    n = len(q)
    M, f, A, b = derived.mass_matrix, derived.forcing, derived.constraint_matrix, derived.constraint_rate
    g = list(derived.configuration_constraints)
    jacobian = derived.configuration_constraints.jacobian(q) if g else sympy.zeros(0, n)

    def vector(name: str, values) -> list[tuple[str, sympy.Expr]]:
        return [(f"{name}[{i}]", value) for i, value in enumerate(values)]

    def matrix(name: str, values: sympy.Matrix) -> list[tuple[str, sympy.Expr]]:
        return [(f"{name}[{i}, {j}]", values[i, j]) for i in range(values.shape[0]) for j in range(values.shape[1])]

    # The chapter-8 DAE algorithms' kernels (app.physics.constrained.system): M and f; g, C = A and c = b.
    kernels = [
        generate_function(
            "dynamics(t, q, v, p, M_out, f_out)",
            [("q", q), ("v", u), ("p", p)],
            matrix("M_out", M) + vector("f_out", f),
        ),
        generate_function(
            "constraints(q, v, p, g_out, C_out, c_out)",
            [("q", q), ("v", u), ("p", p)],
            vector("g_out", g) + matrix("C_out", A) + vector("c_out", list(b)),
        ),
    ]
    kinetic, rotational = derived.kinetic_energy, derived.rotational_kinetic_energy
    helpers = [
        generate_function("configuration_jacobian(q, p, out)", [("q", q), ("p", p)], vector("out", list(jacobian))),
        generate_function(
            "energies(q, u, p, out)",
            [("q", q), ("u", u), ("p", p)],
            vector("out", [kinetic - rotational, rotational, derived.potential_energy]),
        ),
    ]
    header = (
        f'"""Generated by app.physics.mechanics.multibody.compiled for {system.id} ({formulation} with multipliers); '
        f'fingerprint {system.fingerprint()}. Do not edit."""\n\nimport math\n\nimport numpy as np\n\n'
        "from app.physics.mechanics.linear import solve_small\n\n\n"
    )
    glue = _GLUE.format(n=n, m=A.shape[0], h=len(g))
    source = header + "\n\n".join([*kernels, *helpers]) + "\n" + glue
    operations = {
        "speeds": n,
        "constraints": A.shape[0],
        "before_cse": operations_written_out([*M, *f, *A, *b]),
        "after_cse": operations_in_code("\n".join(kernels)),
    }
    return source, operations


#: Generated modules larger than this are not loaded (bytes): a described system's code could otherwise fill memory.
MAX_MODULE_BYTES = 16 * 2**20


def _private_module(path: Path) -> types.ModuleType:
    """A generated module executed into a module object of its own, not registered in ``sys.modules`` (a described
    system is anyone's: the caller keeps it as long as it wants it)."""
    module = types.ModuleType(f"dynlab_described_{path.stem}")
    exec(compile(path.read_text(), str(path), "exec"), module.__dict__)  # noqa: S102 - our own generated code
    return module


def _load(system: MultibodySystem, module_path: Path, meta_path: Path, *, keep: bool) -> CompiledSystem | None:
    """The generated functions from the disk cache, or None if they are not there (or unreadable)."""
    if not (module_path.exists() and meta_path.exists()):
        return None
    try:
        meta = json.loads(meta_path.read_text())
        size = module_path.stat().st_size
    except (OSError, ValueError):
        return None
    if size > MAX_MODULE_BYTES:
        raise ValueError(f"{system.id}: its generated code is larger than {MAX_MODULE_BYTES // 2**20} MB")
    loading = time.perf_counter()
    module = load_generated(module_path) if keep else _private_module(module_path)
    return CompiledSystem(
        system=system,
        rhs=module.rhs,
        configuration=module.configuration,
        configuration_jacobian=module.configuration_jacobian,
        constraint_matrix=module.constraint_matrix,
        energies=module.energies,
        dynamics=module.dynamics,
        constraints=module.constraints,
        derive_s=float(meta["derive_s"]),
        generate_s=float(meta["generate_s"]),
        load_s=time.perf_counter() - loading,
        operations=meta["operations"],
        from_cache=True,
    )


def loaded(
    system: MultibodySystem, *, formulation: str = "kane", directory: Path | None = None, keep: bool = True
) -> CompiledSystem | None:
    """The system's generated functions from memory or the disk cache, never derived here: None if no process has
    derived them yet. ``keep=False`` loads them privately and keeps nothing (a described system: see
    :mod:`.prepared`)."""
    module_path, meta_path = _paths(system, formulation, directory)
    key = str(module_path)
    with _lock:
        if key in _memory:
            return _memory[key]
    result = _load(system, module_path, meta_path, keep=keep)
    if result is not None and keep:
        with _lock:
            result = _memory.setdefault(key, result)
    return result


def compiled(system: MultibodySystem, *, formulation: str = "kane", directory: Path | None = None) -> CompiledSystem:
    """The system's generated functions by ``formulation`` (:data:`FORMULATIONS`): from memory, the disk cache, or
    derived now (and stored). Deriving a large system takes seconds to minutes: a server derives in a bounded child
    (:mod:`.prepared`) and only loads here."""
    module_path, meta_path = _paths(system, formulation, directory)
    key = str(module_path)
    with _lock:
        if key in _memory:
            return _memory[key]
        key_lock = _key_locks.setdefault(key, threading.Lock())
    with key_lock:
        found = loaded(system, formulation=formulation, directory=directory)
        if found is not None:
            return found
        start = time.perf_counter()
        derived = FORMULATIONS[formulation](system)
        derive_s = time.perf_counter() - start
        source, operations = _generate(system, derived, formulation)
        generate_s = time.perf_counter() - start - derive_s
        meta = {"derive_s": derive_s, "generate_s": generate_s, "operations": operations}
        module_path.parent.mkdir(parents=True, exist_ok=True)
        for path, text in ((module_path, source), (meta_path, json.dumps(meta))):
            temporary = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
            temporary.write_text(text)
            os.replace(temporary, path)
        result = loaded(system, formulation=formulation, directory=directory)
        assert result is not None
        result.from_cache = False
        return result
