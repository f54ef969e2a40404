"""A multibody system's derivation shown as LaTeX: what the derive route answers for a system built of parts.

Each frame's angular velocity and each body's mass-centre velocity in its own components, the constraint rows, and
M u̇ = f + Aᵀλ, A u̇ = b, with an entry written out only where it is short (:data:`SHORT_OPERATIONS`; a longer one is
shown by its operation count). A body is kept in memory and as JSON beside the generated code, so only the first
request derives: in a bounded child process (:func:`derive_shown`, through :mod:`.prepared`).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import threading
import time
import unicodedata
from collections import OrderedDict
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import sympy

from app.physics.mechanics.engine import cache_directory
from app.physics.mechanics.multibody.compiled import MULTIBODY_VERSION, compiled, operations_written_out
from app.physics.mechanics.multibody.kane import equations, lagrange_form
from app.physics.mechanics.multibody.kinematics import kinematics
from app.physics.mechanics.multibody.parts import GROUND, MultibodySystem

#: An entry with at most this many operations is written out; a longer one is shown by its count.
SHORT_OPERATIONS = 60
_SHOWN_VERSION = hashlib.sha256(Path(__file__).read_bytes()).hexdigest()[:10]
_shown: OrderedDict[tuple[str, str], dict[str, Any]] = OrderedDict()
_shown_lock = threading.Lock()
SHOWN_KEPT = 64

_GREEK = {
    unicodedata.lookup(f"GREEK SMALL LETTER {n}"): "\\" + ("lambda" if n == "LAMDA" else n.lower())
    for n in ("ALPHA BETA GAMMA DELTA EPSILON ZETA ETA THETA IOTA KAPPA LAMDA MU NU XI PI RHO SIGMA TAU UPSILON PHI "
              "CHI PSI OMEGA").split()
}  # fmt: skip


def _symbol_latex(system: MultibodySystem) -> dict[sympy.Symbol, str]:
    """How each symbol is written: coordinates by their LaTeX, rates dotted, parameters by their label."""
    names: dict[sympy.Symbol, str] = {}
    for c in system.coordinates:
        names[c.symbol] = c.latex
        names[c.rate] = f"\\dot{{{c.latex}}}"
        names[c.acceleration] = f"\\ddot{{{c.latex}}}"
    for p in system.parameters.parameters:
        label = p.label or p.name
        head, _, tail = label.partition("_")
        head = "".join(_GREEK.get(ch, ch) for ch in head)
        if re.fullmatch(r"(\\[a-z]+|[A-Za-z])", head) and re.fullmatch(r"[A-Za-z0-9]*", tail):
            names[system.symbols[p.name]] = f"{head}_{{{tail}}}" if tail else head
        else:
            names[system.symbols[p.name]] = "\\mathrm{" + p.name.replace("_", "\\_") + "}"
    return names


class _Writer:
    def __init__(self, system: MultibodySystem) -> None:
        self.names = _symbol_latex(system)

    def entry(self, expression: sympy.Expr) -> str:
        operations = operations_written_out([expression])
        if operations > SHORT_OPERATIONS:
            return f"\\boxed{{{operations}\\ \\text{{operations}}}}"
        return sympy.latex(expression, symbol_names=self.names)

    def short(self, expression: sympy.Expr) -> bool:
        return operations_written_out([expression]) <= SHORT_OPERATIONS

    def matrix(self, values: sympy.Matrix) -> str:
        rows = [" & ".join(self.entry(values[i, j]) for j in range(values.shape[1])) for i in range(values.shape[0])]
        return "\\begin{bmatrix}" + " \\\\ ".join(rows) + "\\end{bmatrix}"


def _frame_latex(name: str) -> str:
    return "\\mathrm{" + name.replace("_", "\\_") + "}"


def _shown_path(system: MultibodySystem, formulation: str) -> Path:
    return cache_directory() / (
        f"multibody_shown_{system.id.replace('-', '_')}_{formulation}_{system.fingerprint()}_v{MULTIBODY_VERSION}"
        f"_{_SHOWN_VERSION}.json"
    )


def _remember(key: tuple[str, str], body: dict[str, Any]) -> None:
    with _shown_lock:
        _shown[key] = body
        while len(_shown) > SHOWN_KEPT:
            _shown.popitem(last=False)


def shown_cached(system: MultibodySystem, formulation: str) -> dict[str, Any] | None:
    """The derive route's body for a parts system from memory or the disk cache (None if it was never derived)."""
    key = (system.fingerprint(), formulation)
    with _shown_lock:
        found = _shown.get(key)
        if found is not None:
            _shown.move_to_end(key)
            return found
    try:
        found = json.loads(_shown_path(system, formulation).read_text())
    except (OSError, ValueError):
        return None
    _remember(key, found)
    return found


def shown(system: MultibodySystem, formulation: str) -> dict[str, Any]:
    """The derive route's body for a parts system, derived now unless cached (then kept in memory and on disk):
    steps as LaTeX, M and f written out where short (an entry longer than :data:`SHORT_OPERATIONS` is shown by its
    operation count), the generated code's operation counts, and the seconds this call spent (``derive_s``: sympy;
    ``compile_s``: generating and loading the code)."""
    found = shown_cached(system, formulation)
    if found is not None:
        return {**found, "derive_s": 0.0, "compile_s": 0.0, "cached": True}
    started = time.perf_counter()
    body = _shown_body(system, formulation)
    derive_s = time.perf_counter() - started
    started = time.perf_counter()
    body["operations"] = dict(compiled(system, formulation=formulation).operations)
    compile_s = time.perf_counter() - started
    path = _shown_path(system, formulation)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
    temporary.write_text(json.dumps(body))
    os.replace(temporary, path)
    _remember((system.fingerprint(), formulation), body)
    return {**body, "derive_s": derive_s, "compile_s": compile_s, "cached": False}


def derive_shown(
    member_of: Callable[[str, Mapping[str, Any]], MultibodySystem],
    system_id: str,
    params: Mapping[str, Any],
    formulation: str,
) -> dict[str, Any]:
    """:func:`shown` for the catalogue system ``system_id``'s member for ``params`` (``member_of`` finds it: a
    module-level function of the catalogue's layer, pickled by reference): run this in a bounded child process, which
    writes the answer to the disk cache for the server to read."""
    return shown(member_of(system_id, params), formulation)


def _shown_body(system: MultibodySystem, formulation: str) -> dict[str, Any]:
    frames = kinematics(system)
    derived = equations(system, frames)
    if formulation == "lagrange":
        derived = lagrange_form(derived)
    write = _Writer(system)
    n = len(system.coordinates)
    bodies = {b.name for b in system.bodies}
    steps: list[dict[str, str]] = []
    for name, frame in frames.frames.items():
        if name == GROUND:
            continue
        kind = "body" if name in bodies else "frame"
        steps.append(
            {
                "title": f"Angular velocity of the {kind} {name} (rad/s, its own components)",
                "latex": f"\\boldsymbol{{\\omega}}_{{{_frame_latex(name)}}} = {write.matrix(frame.angular_velocity)}",
            }
        )
        if name in bodies:
            velocity = frames.mass_centre_velocity(system, name)
            steps.append(
                {
                    "title": f"Velocity of the mass centre of {name} (m/s, its own components)",
                    "latex": f"\\mathbf{{v}}_{{G,{_frame_latex(name)}}} = {write.matrix(velocity)}",
                }
            )
    ud = [c.acceleration for c in system.coordinates]
    g = derived.configuration_constraints
    for i in range(g.shape[0]):
        steps.append(
            {
                "title": f"Configuration constraint {i + 1}: the contact's height (m) is zero",
                "latex": f"g_{{{i + 1}}}(q) = {write.entry(g[i])} = 0",
            }
        )
    A, b = derived.constraint_matrix, derived.constraint_rate
    for k in range(A.shape[0]):
        terms = [_term(write, A[k, j], f"A_{{{k + 1},{j + 1}}}", write.names[system.u[j]]) for j in range(n)]
        what = f"the rate of configuration constraint {k + 1}" if k < g.shape[0] else "no slip: a contact point at rest"
        steps.append(
            {
                "title": f"Velocity constraint {k + 1} ({what})",
                "latex": (" + ".join(t for t in terms if t) or "0") + " = 0",
            }
        )
    if formulation == "kane":
        steps.append(
            {
                "title": "Kane's equations with every speed, partial velocities V = ∂v_G/∂u and W = ∂ω/∂u",
                "latex": (
                    "M = \\sum_B m_B V_B^{T} V_B + W_B^{T} I_B W_B,\\quad "
                    "f = \\sum_B V_B^{T}(m_B \\mathbf{g} - m_B \\mathbf{a}_B) - W_B^{T}(I_B \\boldsymbol{\\alpha}_B + "
                    "\\boldsymbol{\\omega}_B \\times I_B \\boldsymbol{\\omega}_B)"
                ),
            }
        )
    else:
        steps += [
            {"title": "Kinetic energy (J)", "latex": f"T = {write.entry(derived.kinetic_energy)}"},
            {"title": "Potential energy (J)", "latex": f"V = {write.entry(derived.potential_energy)}"},
            {
                "title": "Lagrange's equations with multipliers, from the energies alone",
                "latex": (
                    "M = \\frac{\\partial^2 T}{\\partial \\dot q^2},\\quad f = \\frac{\\partial (T - V)}{\\partial q}"
                    " - \\frac{\\partial^2 T}{\\partial \\dot q\\, \\partial q}\\, \\dot q"
                ),
            },
        ]
    M, f = derived.mass_matrix, derived.forcing
    equations_latex = []
    for i in range(n):
        left = [_term(write, M[i, j], f"M_{{{i + 1},{j + 1}}}", write.names[ud[j]]) for j in range(n)]
        right = [write.entry(f[i]) if write.short(f[i]) else f"f_{{{i + 1}}}"]
        right += [_term(write, A[k, i], f"A_{{{k + 1},{i + 1}}}", f"\\lambda_{{{k + 1}}}") for k in range(A.shape[0])]
        shown_right = [t for t in right if t and t != "0"]
        equations_latex.append((" + ".join(t for t in left if t) or "0") + " = " + (" + ".join(shown_right) or "0"))
    for k in range(A.shape[0]):
        left = [_term(write, A[k, j], f"A_{{{k + 1},{j + 1}}}", write.names[ud[j]]) for j in range(n)]
        rate = write.entry(b[k]) if write.short(b[k]) else f"b_{{{k + 1}}}"
        equations_latex.append((" + ".join(t for t in left if t) or "0") + f" = {rate}")
    steps.append(
        {
            "title": "The equations: M u̇ = f + Aᵀλ and A u̇ = b (u = q̇, λ the constraint forces), solved together",
            "latex": "M(q)\\,\\dot{u} = f(q, u) + A(q)^{T}\\lambda,\\qquad A(q)\\,\\dot{u} = b(q, u) = -\\dot{A}\\,u",
        }
    )
    if A.shape[0]:
        steps.append({"title": "The constraint rows' rate b", "latex": f"b = {write.matrix(b)}"})
    return {
        "system_id": system.id,
        "formulation": formulation,
        "coordinates": [c.name for c in system.coordinates],
        "speeds": [c.rate.name for c in system.coordinates],
        "variables": "q, u = q̇, λ",
        "equations_latex": equations_latex,
        "mass_matrix_latex": write.matrix(M),
        "forcing_latex": write.matrix(f),
        "steps": steps,
    }


def _term(write: _Writer, coefficient: sympy.Expr, name: str, variable: str) -> str:
    """``coefficient · variable`` in LaTeX ('' for a zero coefficient; the coefficient by ``name`` when long)."""
    if coefficient == 0:
        return ""
    if coefficient == 1:
        return variable
    if not write.short(coefficient):
        return f"{name}\\, {variable}"
    text = write.entry(coefficient)
    return f"\\left({text}\\right) {variable}" if coefficient.is_Add else f"{text}\\, {variable}"
