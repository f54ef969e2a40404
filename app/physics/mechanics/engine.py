"""Derive, generate, load: one system by one formulation, done once and cached.

:func:`derived` is the one entry point. It keeps every result in memory and
on disk, keyed by the description's fingerprint and the formulation: the
equations as LaTeX, the steps and the generated right-hand side (a Python
module). A later call — in this process or the next — answers from the cache
without sympy. The right-hand side runs as plain Python for the API and the
tests; :meth:`Derived.kernel` compiles it with numba for live scenes (cached
on disk by numba beside the generated module).
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import sys
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import ModuleType
from typing import Any

import numba
import numpy as np
import sympy

from app.physics.mechanics.codegen import CodeSystem, generate_source
from app.physics.mechanics.derivation import FORMULATIONS, Derivation, FormulationUnavailable
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.gibbs_appell import derive_gibbs_appell
from app.physics.mechanics.hamilton import derive_hamilton
from app.physics.mechanics.kane import derive_kane
from app.physics.mechanics.lagrange import derive_lagrange
from app.physics.mechanics.newton_euler import derive_newton_euler
from app.physics.mechanics.routh import derive_routh
from app.physics.mechanics.shown import SimplifyOutcome, shown_forms
from app.physics.solvers.kernels import RHS_SIGNATURE, Kernel


def _source_digest() -> str:
    """A hash of this package's source: any change to a formulation or the generator makes new cache keys."""
    digest = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        digest.update(path.name.encode() + path.read_bytes())
    return digest.hexdigest()[:10]


#: Part of every cache key: the package's source digest, so a changed engine never reads an old derivation.
ENGINE_VERSION = _source_digest()

DERIVERS: dict[str, Callable[[SystemDescription], Derivation]] = {
    "newton-euler": derive_newton_euler,
    "lagrange": derive_lagrange,
    "hamilton": derive_hamilton,
    "routh": derive_routh,
    "gibbs-appell": derive_gibbs_appell,
    "kane": derive_kane,
}
assert tuple(DERIVERS) == FORMULATIONS

#: In-memory results kept (catalogue systems and typed Lagrangians alike).
MEMORY_ENTRIES = 128


def cache_directory() -> Path:
    """Where derivations are kept: ``$DYNLAB_DERIVATION_CACHE`` or ``~/.cache/dynlab/derivations``."""
    configured = os.environ.get("DYNLAB_DERIVATION_CACHE")
    return Path(configured) if configured else Path.home() / ".cache" / "dynlab" / "derivations"


#: The catalogue systems' derivations, every formulation that applies, shipped with the app in the cache's own form
#: (:func:`ship_catalogue_derivations` writes them): a fresh install reads them instead of spending sympy's minutes.
#: Their names hold :data:`ENGINE_VERSION` and each system's fingerprint, so a changed engine or system never reads
#: them; ``tests/physics/mechanics/test_shipped_derivations.py`` fails until they are derived again.
SHIPPED_DIRECTORY = Path(__file__).with_name("shipped")


#: Why a derivation's right-hand side has no finite value at a state, in words that finish "… because …".
NOT_FINITE_BECAUSE = {
    "overflow": "a number overflows (exceeds 1.8e308, the largest double-precision number)",
    "divide": "it divides by zero",
    "domain": (
        "a square root, logarithm or other function is taken outside its domain (of a negative or infinite number)"
    ),
    "singular": "the mass matrix is singular there, so the accelerations cannot be solved for",
    "not_finite": "a value is infinite or undefined",
}


def not_finite_because(error: BaseException) -> str:
    """Why (:data:`NOT_FINITE_BECAUSE`) for an error plain Python's ``math`` or numpy raised while evaluating
    (numpy's under ``np.errstate(over="raise", divide="raise", invalid="raise")``)."""
    text = str(error)
    if isinstance(error, ZeroDivisionError) or "divide by zero" in text:
        return NOT_FINITE_BECAUSE["divide"]
    if isinstance(error, OverflowError) or "overflow" in text or "out of range" in text:
        return NOT_FINITE_BECAUSE["overflow"]
    if "domain" in text or "invalid value" in text:
        return NOT_FINITE_BECAUSE["domain"]
    return NOT_FINITE_BECAUSE["not_finite"]


@dataclass
class Derived:
    """A derivation ready to use: what the page shows and the generated right-hand side."""

    system_id: str
    formulation: str
    coordinates: list[str]
    speeds: list[str]
    equations_latex: list[str]
    mass_matrix_latex: str
    forcing_latex: str
    steps: list[dict[str, str]]
    variables: str
    derive_s: float
    compile_s: float
    source_path: Path
    rhs_python: Callable[..., None]
    from_cache: bool = False
    derivation: Derivation | None = field(default=None, repr=False)
    _kernel: Kernel | None = field(default=None, repr=False)
    _answered: bool = field(default=False, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)
    #: Set while what is shown awaits its simplification (refused for the machine's load): tries it again, True once
    #: done (see :func:`_derive_and_store`).
    _pending_shown: Callable[[], bool] | None = field(default=None, repr=False)
    _shown_lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def state_derivative(self, t_s: float, state: np.ndarray, parameters: np.ndarray) -> np.ndarray:
        """(q̇, q̈) at the state (q, q̇) and time t (plain Python: no compile needed); NaN where they have no finite
        value, as the compiled kernel gives (:meth:`evaluate` also says why)."""
        return self.evaluate(t_s, state, parameters)[0]

    def evaluate(self, t_s: float, state: np.ndarray, parameters: np.ndarray) -> tuple[np.ndarray, str]:
        """``(derivative, why)``: (q̇, q̈) at the state (q, q̇) and time t, and "" if every component is finite, else
        why not in words (:data:`NOT_FINITE_BECAUSE`), with the derivative NaN.

        Plain Python's ``math`` raises where the compiled kernel (numpy's error model) gives inf or NaN: an overflow,
        a division by zero, a square root or logarithm of a negative number. Those errors are the reason given here;
        numpy's own are raised too (an overflow in a product of numpy scalars), underflow to zero is not an error.
        """
        out = np.empty(len(state))
        try:
            with np.errstate(over="raise", divide="raise", invalid="raise", under="ignore"):
                self.rhs_python(
                    float(t_s),
                    np.ascontiguousarray(state, dtype=float),
                    np.ascontiguousarray(parameters, dtype=float),
                    out,
                )
        except (ArithmeticError, ValueError) as error:
            out[:] = np.nan
            return out, not_finite_because(error)
        if np.all(np.isnan(out)):  # the generated code's singular solve writes NaN everywhere, the rates included
            return out, NOT_FINITE_BECAUSE["singular"]
        if not np.all(np.isfinite(out)):
            return out, NOT_FINITE_BECAUSE["not_finite"]
        return out, ""

    def kernel(self) -> Kernel:
        """The right-hand side as a numba C callback for the integrators (compiled once; numba caches it on disk)."""
        with self._lock:
            if self._kernel is None:
                # numba's stubs leave out nopython, which cfunc still reads: without it object mode is allowed.
                compiled = numba.cfunc(  # type: ignore[call-arg]
                    RHS_SIGNATURE, cache=True, nopython=True, error_model="numpy"
                )(self.rhs_python)
                self._kernel = Kernel(compiled=compiled, python=self.rhs_python)
            return self._kernel

    def finish_shown(self) -> None:
        """Simplify what is shown now if that was refused when it was derived (a busy machine); one try at a time."""
        if self._pending_shown is None:
            return
        with self._shown_lock:
            if self._pending_shown is not None and self._pending_shown():
                self._pending_shown = None

    def answer(self) -> dict:
        """The derive route's body (names are API contracts).

        The timings are this request's: the first answer of a fresh derivation reports sympy's and the code
        generator's seconds; every later one (from memory or disk) reports what it cost then, 0 s to derive.
        """
        self.finish_shown()
        with self._lock:
            first, self._answered = not self._answered, True
        derive_s, compile_s, cached = (self.derive_s, self.compile_s, self.from_cache) if first else (0.0, 0.0, True)
        return {
            "system_id": self.system_id,
            "formulation": self.formulation,
            "coordinates": self.coordinates,
            "speeds": self.speeds,
            "variables": self.variables,
            "equations_latex": self.equations_latex,
            "mass_matrix_latex": self.mass_matrix_latex,
            "forcing_latex": self.forcing_latex,
            "steps": self.steps,
            "derive_s": derive_s,
            "compile_s": compile_s,
            "cached": cached,
        }


_memory: OrderedDict[tuple[str, str], Derived] = OrderedDict()
_memory_lock = threading.Lock()
_key_locks: dict[tuple[str, str], threading.Lock] = {}


def load_generated(path: Path) -> ModuleType:
    """Import a generated module (registered under its own name: numba's cache finds a function's module by it)."""
    name = f"dynlab_derived_{path.stem.replace('-', '_')}"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def _load_module(path: Path) -> Callable[..., None]:
    return load_generated(path).rhs


def load_recipe(system: CodeSystem, recipe, *, formulation: str, path: Path) -> Callable[..., None]:
    """Generate ``recipe``'s source at ``path`` (written atomically) and load its ``rhs(t, y, p, dydt)``."""
    source = generate_source(system, recipe, formulation=formulation)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
    temporary.write_text(source)
    os.replace(temporary, path)
    return _load_module(path)


def _entry_name(system: SystemDescription, formulation: str) -> str:
    return f"{system.id}-{formulation}-{system.fingerprint()}-v{ENGINE_VERSION}"


def derived(system: SystemDescription, formulation: str, *, directory: Path | None = None) -> Derived:
    """The derivation of ``system`` by ``formulation``, from memory, disk, or sympy (in that order). Disk is
    ``directory`` when given, else the cache (:func:`cache_directory`), then the derivations shipped with the app
    (:data:`SHIPPED_DIRECTORY`).

    Raises :class:`FormulationUnavailable` (a ValueError saying why) when the
    formulation does not apply, and ValueError for an unknown formulation.
    """
    if formulation not in DERIVERS:
        raise ValueError(f"unknown formulation {formulation!r}; choose one of {', '.join(FORMULATIONS)}")
    if formulation in system.unavailable:
        raise FormulationUnavailable(system.unavailable[formulation])
    key = (system.fingerprint(), formulation)
    with _memory_lock:
        if key in _memory:
            _memory.move_to_end(key)
            return _memory[key]
        lock = _key_locks.setdefault(key, threading.Lock())
    with lock:  # one derivation per key at a time; others wait for it
        with _memory_lock:
            if key in _memory:
                return _memory[key]
        result = (
            _from_disk(system, formulation, directory)
            or (directory is None and _from_disk(system, formulation, SHIPPED_DIRECTORY))
            or _derive_and_store(system, formulation, directory)
        )
        with _memory_lock:
            _memory[key] = result
            _key_locks.pop(key, None)  # later callers find the result in memory; waiters still hold the lock
            while len(_memory) > MEMORY_ENTRIES:
                _memory.popitem(last=False)
        return result


def entry_paths(system: SystemDescription, formulation: str, directory: Path | None) -> tuple[Path, Path]:
    """A derivation's two files in ``directory`` (default: the cache): what it shows (JSON) and its right-hand side."""
    base = (directory or cache_directory()) / _entry_name(system, formulation)
    return base.with_suffix(".json"), base.with_name(base.name.replace("-", "_").replace(".", "_") + ".py")


def _from_disk(system: SystemDescription, formulation: str, directory: Path | None) -> Derived | None:
    meta_path, source_path = entry_paths(system, formulation, directory)
    if not (meta_path.exists() and source_path.exists()):
        return None
    try:
        meta = json.loads(meta_path.read_text())
        start = time.perf_counter()
        rhs = _load_module(source_path)
        load_s = time.perf_counter() - start
    except (OSError, ValueError, SyntaxError, AttributeError):
        return None  # a damaged entry is derived again and overwritten
    return Derived(
        **meta["derived"], derive_s=0.0, compile_s=load_s, source_path=source_path, rhs_python=rhs, from_cache=True
    )


def _derive_and_store(system: SystemDescription, formulation: str, directory: Path | None) -> Derived:
    """Derive, generate the right-hand side from the recipe, then simplify what is shown (bounded, :mod:`.shown`).

    The code is generated before anything shown is simplified, from the recipe alone: the numbers never depend on
    it. ``derive_s`` counts sympy's derivation and the simplification of what it shows. A simplification refused for
    the machine's load (``outcome.refused``: no slot, the child paused or stopped) shows the derived forms for now and
    stores nothing on disk; the next answer tries again (:meth:`Derived.finish_shown`) and stores it once done.
    """
    meta_path, source_path = entry_paths(system, formulation, directory)
    start = time.perf_counter()
    with shown_forms() as forms:
        derivation = DERIVERS[formulation](system)
        matrices = derivation.latex(derivation.mass_matrix), derivation.latex(derivation.forcing)
    derive_s = time.perf_counter() - start
    start = time.perf_counter()
    rhs = load_recipe(system, derivation.recipe, formulation=formulation, path=source_path)
    compile_s = time.perf_counter() - start
    start = time.perf_counter()
    outcome = forms.simplify()
    derive_s += time.perf_counter() - start
    tokens = derivation  # its LaTeX holds the tokens the forms fill in

    def shown_latex() -> dict[str, Any]:
        return {
            "equations_latex": [forms.fill(e) for e in tokens.equations_latex],
            "mass_matrix_latex": forms.fill(matrices[0]),
            "forcing_latex": forms.fill(matrices[1]),
            "steps": [{"title": s.title, "latex": forms.fill(s.latex)} for s in tokens.steps],
        }

    shown: dict[str, Any] = {
        "system_id": system.id,
        "formulation": formulation,
        "coordinates": [c.name for c in system.coordinates],
        "speeds": [s.name for s in system.speed_list],
        "variables": derivation.variables,
        **shown_latex(),
    }
    result = Derived(**shown, derive_s=derive_s, compile_s=compile_s, source_path=source_path, rhs_python=rhs)

    def store(outcome: SimplifyOutcome) -> None:
        """Show the filled-in forms and write the entry to disk."""
        latex = shown_latex()
        for name, value in latex.items():
            setattr(result, name, value)
        steps = tuple(replace(step, latex=filled["latex"]) for step, filled in zip(tokens.steps, latex["steps"]))
        result.derivation = replace(tokens, equations_latex=tuple(latex["equations_latex"]), steps=steps)
        meta = {
            "derived": {**shown, **latex},
            "derive_s": derive_s,
            "compile_s": compile_s,
            "shown": outcome.as_dict(),
            "sympy": sympy.__version__,
        }
        temporary = meta_path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
        temporary.write_text(json.dumps(meta, ensure_ascii=False, indent=1))
        os.replace(temporary, meta_path)

    def retry() -> bool:
        again = forms.simplify()
        if again.refused:
            return False
        store(again)
        return True

    if outcome.refused:
        result._pending_shown = retry
    else:
        store(outcome)
    return result


def available_formulations(system: SystemDescription) -> dict[str, str]:
    """Formulation id → "" if it applies, else why not (without deriving: from the description's shape)."""
    reasons: dict[str, str] = {}
    for formulation in FORMULATIONS:
        reason = system.unavailable.get(formulation, "")
        if not reason:
            if formulation in ("lagrange", "hamilton", "routh") and not system.holonomic:
                reason = (
                    "needs independent coordinates; the rolling constraints restrict velocities only "
                    "(chapter 8's multipliers)"
                )
            elif formulation == "routh" and not system.ignorable:
                reason = "no ignorable coordinate"
            elif formulation == "newton-euler" and (
                not system.reactions or system.kinetic_energy is not None or system.extra_potential != 0
            ):
                reason = "no free-body diagrams: the system is given by its energies"
            elif formulation in ("kane", "gibbs-appell") and system.kinetic_energy is not None:
                reason = "needs particles and bodies, not only an energy expression"
        reasons[formulation] = reason
    return reasons
