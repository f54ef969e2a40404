"""A multibody system's parts as data: the JSON (or TOML) form of :mod:`.parts`, read and written.

:func:`system_from_data` builds a :class:`~.parts.MultibodySystem` from a mapping (parsed JSON, or TOML read by
:func:`system_from_toml` with the standard library's ``tomllib``); :func:`system_to_data` and
:func:`system_to_toml` write one back, so a system and its data give the same equations. The form::

    id = "double-pendulum-parts"            # lower case, digits, hyphens (it names cache files)
    title = "Two rods"
    gravity = "g"                           # a number or a parameter's name (m/s², along −z)
    [[parameters]]                          # name, value, unit, low, high, description (label optional)
    name = "g"; value = 9.81; unit = "m/s²"; low = 0; high = 30; description = "gravity"
    [[bodies]]                              # mass (kg), mass_centre (m, own components), central inertia (kg·m²)
    name = "link1"; mass = "m"; mass_centre = [0, 0, -0.25]; inertia = {ixx = 0.02, iyy = 0.02, izz = 0}
    [[joints]]                              # revolute | prismatic | spherical | rolling_wheel
    type = "revolute"; parent = "ground"; child = "link1"; coordinate = "theta1"; axis = [0, 1, 0]; at = [0, 0, 0]

Joints: ``revolute`` and ``prismatic`` take ``parent``, ``child``, ``coordinate`` (a name, or ``{name, latex}``),
``axis`` (the parent's components; normalised) and ``at`` (m, the parent's components; default the origin); a
``child`` that names no body is a massless frame. ``spherical`` is three revolutes through two massless frames
(``<child>.spherical1``, ``<child>.spherical2``) about x, then the moving y, then the moving z, with
``coordinates`` (three). ``rolling_wheel`` takes ``wheel`` (a body), ``radius`` and the coordinates ``x``, ``y``,
``yaw``, ``lean``, ``spin``, and makes the frame ``<wheel>.axle``. Contacts: ``rolling_contact`` (``wheel``,
``radius``, ``axle`` [x, y, z]) and ``ellipsoid_contact`` (``body``, ``semi_axes`` [a, b, c] and ``centre`` [x, y, z],
m, the body's components). Loads: ``force`` (``body``, ``vector`` N, ``point`` m in the body's components,
``follower``: the vector in the body's components rather than the ground's), ``torque`` (``body``, ``vector`` N·m,
``follower``) and ``spring`` (``coordinate``, ``stiffness``, ``rest``, ``damping``). Then
``dependent_coordinates`` (one per contact), ``dependent_speeds`` (two per rolling wheel, three per contact) and an
optional ``reference`` (``about``, ``coordinates``, ``speeds``, ``state``: 2n
numbers, q then q̇, zero if absent, ``sweep`` {parameter, low, high}, ``crossing_names``).

Every numeric field is a finite number, a declared parameter's name, or a small expression tree of them: an object
with one key, ``{"neg": x}``, ``{"add": [x, y, …]}``, ``{"mul": [x, y, …]}``, ``{"div": [x, y]}``, ``{"pow": [x,
n]}`` (n a whole number, −4 … 4), ``{"sin": x}`` or ``{"cos": x}`` (a bicycle's steer axis is (−sin λ, 0, cos λ)).
Nothing is parsed as text: symbols are made from names the strict :data:`NAME` pattern accepts, numbers from JSON
(or TOML) numbers, and operators from that list. Everything is validated; a refusal is a
:class:`~app.physics.core.parameters.ParameterError` whose ``path`` names the field (``("bodies", 2, "mass")``).
"""

from __future__ import annotations

import json
import math
import re
import tomllib
import unicodedata
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.mechanics.description import Coordinate
from app.physics.mechanics.multibody.parts import (
    GROUND,
    Body,
    EllipsoidContact,
    Force,
    JointSpring,
    Load,
    MultibodySystem,
    Prismatic,
    ReferenceMotion,
    Revolute,
    RollingContact,
    RollingWheel,
    Torque,
    column,
)

# -- bounds ----------------------------------------------------------------------------------------------------------
#: A name (parameter, body, frame, coordinate): an ASCII identifier of at most 32 characters.
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,31}")
#: A system's id: it names the generated module's file.
ID = re.compile(r"[a-z][a-z0-9-]{0,31}")
#: A coordinate's LaTeX: letters, digits, braces, ``_``, ``^``, spaces and commands of letters (Greek letters, \dot…).
LATEX = re.compile(r"(?:[A-Za-z0-9_{}^ ']|\\[A-Za-z]+)*")
LATEX_COMMANDS = frozenset(
    "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu xi pi rho sigma tau "
    "upsilon phi varphi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega dot ddot hat bar "
    "tilde mathrm mathit prime".split()
)
MAX_BODIES = 12
MAX_COORDINATES = 24
MAX_JOINTS = 24
MAX_CONTACTS = 4
MAX_PARAMETERS = 32
MAX_TOML_BYTES = 20_000
#: Largest magnitude of a number in a description (a value, a bound, a literal in an expression).
MAX_NUMBER = 1e6
#: Largest magnitude of a numeric field's value at the parameters' values (m, kg, kg·m², m/s²…).
MAX_FIELD_VALUE = 1e9
#: An expression tree: at most this deep, this many nodes per field, this many operands per add or mul.
MAX_EXPRESSION_DEPTH = 6
MAX_EXPRESSION_NODES = 40
MAX_OPERANDS = 8
MAX_POWER = 4
MAX_TEXT = {"title": 80, "unit": 16, "label": 16, "description": 200, "about": 200, "assumptions": 400, "latex": 40}
#: Relative tolerance of the inertia checks (positive semidefinite, triangle inequality) on the principal moments.
INERTIA_TOLERANCE = 1e-9
#: The frames the spherical joint makes between its parent and its child.
SPHERICAL_FRAMES = (".spherical1", ".spherical2")

_UNARY = ("neg", "sin", "cos")
_OPERATORS = ("neg", "add", "mul", "div", "pow", "sin", "cos")
_TYPES = ("revolute", "prismatic", "spherical", "rolling_wheel")
_CONTACT_TYPES = ("rolling_contact", "ellipsoid_contact")
_LOAD_TYPES = ("force", "torque", "spring")
MAX_LOADS = 24
_WHEEL_COORDINATES = (("x", "m"), ("y", "m"), ("yaw", "rad"), ("lean", "rad"), ("spin", "rad"))

Where = tuple[str | int, ...]


def _refuse(path: Where, message: str) -> ParameterError:
    return ParameterError(str(path[0]), message, path=path)


def _keys(value: Any, path: Where, *, required: Sequence[str], optional: Sequence[str] = ()) -> Mapping[str, Any]:
    """``value`` as a mapping with exactly the keys allowed (the required ones present), or a refusal."""
    if not isinstance(value, Mapping):
        raise _refuse(path, "must be an object (a table)")
    unknown = [str(k) for k in value if k not in (*required, *optional)]
    if unknown:
        raise _refuse((*path, unknown[0][:40]), f"unknown key; expected {', '.join([*required, *optional])}")
    missing = [k for k in required if k not in value]
    if missing:
        raise _refuse((*path, missing[0]), "is required")
    return value


def _list(value: Any, path: Where, *, most: int, least: int = 0) -> list[Any]:
    if not isinstance(value, list):
        raise _refuse(path, "must be a list")
    if not least <= len(value) <= most:
        raise _refuse(path, f"must have {least} to {most} entries (got {len(value)})")
    return value


def _text(value: Any, path: Where, kind: str) -> str:
    limit = MAX_TEXT[kind]
    if not isinstance(value, str):
        raise _refuse(path, "must be text")
    if len(value) > limit:
        raise _refuse(path, f"must be at most {limit} characters (got {len(value)})")
    if any(unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Co", "Cn") for ch in value):
        raise _refuse(path, "must not hold control or unassigned characters")
    return value


def _name(value: Any, path: Where) -> str:
    if not isinstance(value, str) or not NAME.fullmatch(value):
        shown = repr(value)[:40] if isinstance(value, str) else type(value).__name__
        raise _refuse(
            path, f"must be a name: an ASCII letter, then letters, digits or _, at most 32 characters (got {shown})"
        )
    return value


def _plain_number(value: Any, path: Where, *, most: float = MAX_NUMBER) -> float | int:
    """A JSON/TOML number (not a boolean), finite and of magnitude at most ``most``."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _refuse(path, "must be a number")
    try:
        finite = math.isfinite(float(value))
    except OverflowError:
        finite = False
    if not finite or abs(float(value)) > most:
        raise _refuse(path, f"must be a finite number of magnitude at most {most:g}")
    return value


# -- reading ---------------------------------------------------------------------------------------------------------
class _Reader:
    """Numeric fields as sympy expressions: numbers, parameter symbols and the operators of the module docstring."""

    def __init__(self, symbols: Mapping[str, sympy.Symbol]) -> None:
        self.symbols = symbols

    def number(self, value: Any, path: Where) -> sympy.Expr:
        expression = self._node(value, path, 1, [0])
        if expression.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo):
            raise _refuse(path, "has no finite value (a division by zero)")
        return expression

    def _node(self, value: Any, path: Where, depth: int, count: list[int]) -> sympy.Expr:
        node = self._built(value, path, depth, count)
        if node.is_Number and abs(node) > MAX_FIELD_VALUE:  # 1e6 ** 4 ** 4: a literal too large for the code
            raise _refuse(path, f"a number of magnitude above {MAX_FIELD_VALUE:g}")
        return node

    def _built(self, value: Any, path: Where, depth: int, count: list[int]) -> sympy.Expr:
        count[0] += 1
        if count[0] > MAX_EXPRESSION_NODES:
            raise _refuse(path, f"an expression may have at most {MAX_EXPRESSION_NODES} parts")
        if depth > MAX_EXPRESSION_DEPTH:
            raise _refuse(path, f"an expression may nest at most {MAX_EXPRESSION_DEPTH} deep")
        if isinstance(value, str):
            if value not in self.symbols:
                known = ", ".join(self.symbols) or "none"
                raise _refuse(path, f"{value[:40]!r} is no declared parameter (declared: {known})")
            return self.symbols[value]
        if isinstance(value, Mapping):
            if len(value) != 1 or next(iter(value)) not in _OPERATORS:
                raise _refuse(path, f"an expression is an object with one key, one of {', '.join(_OPERATORS)}")
            ((operator, operands),) = value.items()
            inner = (*path, operator)
            if operator in _UNARY:
                argument = self._node(operands, inner, depth + 1, count)
                if operator == "neg":
                    return -argument
                return sympy.sin(argument) if operator == "sin" else sympy.cos(argument)
            if operator == "pow":
                base, exponent = _list(operands, inner, most=2, least=2)
                if isinstance(exponent, bool) or not isinstance(exponent, int) or abs(exponent) > MAX_POWER:
                    raise _refuse((*inner, 1), f"an exponent is a whole number from {-MAX_POWER} to {MAX_POWER}")
                return self._node(base, (*inner, 0), depth + 1, count) ** exponent
            least, most = (2, 2) if operator == "div" else (2, MAX_OPERANDS)
            items = _list(operands, inner, most=most, least=least)
            terms = [self._node(item, (*inner, k), depth + 1, count) for k, item in enumerate(items)]
            if operator == "add":
                return sympy.Add(*terms)
            if operator == "mul":
                return sympy.Mul(*terms)
            if terms[1] == 0:
                raise _refuse((*inner, 1), "a division by zero")
            return terms[0] / terms[1]
        number = _plain_number(value, path)
        if isinstance(number, int) or float(number).is_integer():
            return sympy.Integer(int(number))
        return sympy.Float(float(number))

    def vector(self, value: Any, path: Where) -> sympy.Matrix:
        items = _list(value, path, most=3, least=3)
        return column(*(self.number(item, (*path, k)) for k, item in enumerate(items)))


def _coordinate(value: Any, path: Where, unit: str) -> Coordinate:
    if isinstance(value, Mapping):
        spec = _keys(value, path, required=("name",), optional=("latex",))
        name = _name(spec["name"], (*path, "name"))
        return Coordinate(name, _latex(spec.get("latex", name), (*path, "latex")), unit)
    name = _name(value, path)
    return Coordinate(name, name, unit)


def _latex(value: Any, path: Where) -> str:
    text = _text(value, path, "latex")
    commands = set(re.findall(r"\\([A-Za-z]+)", text))
    if not text or not LATEX.fullmatch(text) or commands - LATEX_COMMANDS:
        raise _refuse(path, "LaTeX of letters, digits, braces, _ and ^, and Greek letters or \\dot, \\hat, \\bar only")
    return text


@dataclass(frozen=True)
class _Check:
    """What must hold at the parameters' values for one part: ``kind`` (positive, inertia, axis, finite)."""

    path: Where
    kind: str
    expressions: tuple[sympy.Expr, ...]


def _values(
    expressions: Sequence[sympy.Expr], symbols: Mapping[str, sympy.Symbol], params: Mapping[str, Any]
) -> list[float | None]:
    """Each expression's value (float) at ``params``; None where it has no finite real value of magnitude at most
    :data:`MAX_FIELD_VALUE`."""
    at = {symbol: float(params[name]) for name, symbol in symbols.items()}
    values = [_value_at(sympy.S(expression), at) for expression in expressions]
    return [v if v is not None and abs(v) <= MAX_FIELD_VALUE else None for v in values]


class _PartsCheck:
    """The ParameterSet's check: at any parameter values, masses and radii are positive, inertias physical, axes of
    non-zero length and every numeric field finite. Raises ParameterError naming the part (its path)."""

    def __init__(self, checks: Sequence[_Check], symbols: Mapping[str, sympy.Symbol]) -> None:
        self.checks = tuple(checks)
        self.symbols = dict(symbols)

    def __call__(self, params: Mapping[str, Any]) -> None:
        for check in self.checks:
            values = _values(check.expressions, self.symbols, params)
            if any(v is None for v in values):
                raise _refuse(
                    check.path, f"has no finite value of magnitude at most {MAX_FIELD_VALUE:g} at these parameters"
                )
            numbers = [float(v) for v in values if v is not None]
            if check.kind == "positive" and not numbers[0] > 0:
                raise _refuse(check.path, f"must be positive (it is {numbers[0]:.6g} at these parameters)")
            if check.kind == "nonnegative" and not numbers[0] >= 0:
                raise _refuse(check.path, f"must not be negative (it is {numbers[0]:.6g} at these parameters)")
            if check.kind == "axis" and math.sqrt(sum(x * x for x in numbers)) < 1e-9:
                raise _refuse(check.path, "an axis of zero length: give a direction")
            if check.kind == "inertia":
                why = _inertia_problem(numbers)
                if why:
                    raise _refuse(check.path, why)


def _inertia_problem(entries: Sequence[float]) -> str:
    """Why (ixx, iyy, izz, ixy, iyz, ixz) (kg·m²) is no rigid body's central inertia, or ''."""
    ixx, iyy, izz, ixy, iyz, ixz = entries
    matrix = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    moments = np.linalg.eigvalsh(matrix)
    scale = max(float(np.max(np.abs(moments))), 1e-300)
    if moments[0] < -INERTIA_TOLERANCE * scale:
        return f"is not positive semidefinite (principal moments {', '.join(f'{m:.6g}' for m in moments)} kg·m²)"
    a, b, c = moments
    if a + b < c - INERTIA_TOLERANCE * scale:
        return (
            f"breaks the triangle inequality: the two smaller principal moments ({a:.6g} + {b:.6g} kg·m²) must add "
            f"up to at least the largest ({c:.6g})"
        )
    return ""


def parse_toml(text: Any) -> dict[str, Any]:
    """TOML text as a mapping, refused (path ``("toml",)``) when too long or not TOML."""
    if not isinstance(text, str):
        raise _refuse(("toml",), "must be text")
    size = len(text.encode("utf-8", errors="replace"))
    if size > MAX_TOML_BYTES:
        raise _refuse(("toml",), f"must be at most {MAX_TOML_BYTES} bytes (got {size})")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise _refuse(("toml",), f"is not TOML: {error}") from None
    except (RecursionError, MemoryError):
        raise _refuse(("toml",), "nests too deep") from None
    except (ValueError, OverflowError) as error:  # e.g. an integer of more digits than Python converts
        raise _refuse(("toml",), f"is not TOML we can read: {str(error)[:120]}") from None


def system_from_toml(text: str) -> MultibodySystem:
    """:func:`system_from_data` of TOML text (at most :data:`MAX_TOML_BYTES`); refusals' paths start ``toml``."""
    return system_from_data(parse_toml(text), root="toml")


def system_from_data(data: Any, *, root: str = "description") -> MultibodySystem:
    """The system a mapping of the module docstring's form describes; raises ParameterError whose path starts with
    ``root`` and names the field at fault."""
    optional = ("parameters", "gravity", "contacts", "loads", "dependent_coordinates", "dependent_speeds", "reference")
    top = _keys(
        data, (root,), required=("id", "title", "bodies", "joints"), optional=(*optional, "chapter", "assumptions")
    )
    r: Where = (root,)
    system_id = top["id"]
    if not isinstance(system_id, str) or not ID.fullmatch(system_id):
        raise _refuse((*r, "id"), "must be lower-case letters, digits and hyphens, starting with a letter, at most 32")
    title = _text(top["title"], (*r, "title"), "title")
    assumptions = _text(top.get("assumptions", ""), (*r, "assumptions"), "assumptions")
    chapter = top.get("chapter", 9)
    if isinstance(chapter, bool) or not isinstance(chapter, int) or not 1 <= chapter <= 10:
        raise _refuse((*r, "chapter"), "must be a chapter number, 1 to 10")

    # Parameters: names, values and bounds.
    parameters: list[Parameter] = []
    symbols: dict[str, sympy.Symbol] = {}
    for k, entry in enumerate(_list(top.get("parameters", []), (*r, "parameters"), most=MAX_PARAMETERS)):
        where = (*r, "parameters", k)
        spec = _keys(entry, where, required=("name", "value", "unit", "low", "high"), optional=("description", "label"))
        name = _name(spec["name"], (*where, "name"))
        if name in symbols:
            raise _refuse((*where, "name"), f"{name!r} is declared twice")
        value, low, high = (_plain_number(spec[key], (*where, key)) for key in ("value", "low", "high"))
        if not low < high:
            raise _refuse((*where, "high"), "must be above low")
        if not low <= value <= high:
            raise _refuse((*where, "value"), f"must lie in [low, high] = [{low:g}, {high:g}] (got {value:g})")
        unit = _text(spec["unit"], (*where, "unit"), "unit")
        label = _text(spec.get("label", ""), (*where, "label"), "label")
        description = _text(spec.get("description", ""), (*where, "description"), "description")
        parameters.append(
            Parameter(name, unit, float(value), min=float(low), max=float(high), label=label, description=description)
        )
        symbols[name] = sympy.Symbol(name, real=True)
    read = _Reader(symbols)
    samples = _parameter_samples(parameters, symbols)
    checks: list[_Check] = []

    gravity = read.number(top.get("gravity", 0), (*r, "gravity"))
    checks.append(_Check((*r, "gravity"), "finite", (gravity,)))

    # Bodies.
    bodies: list[Body] = []
    for k, entry in enumerate(_list(top["bodies"], (*r, "bodies"), most=MAX_BODIES, least=1)):
        where = (*r, "bodies", k)
        spec = _keys(entry, where, required=("name", "mass", "inertia"), optional=("mass_centre",))
        name = _name(spec["name"], (*where, "name"))
        if any(b.name == name for b in bodies):
            raise _refuse((*where, "name"), f"the body {name!r} is named twice")
        mass = read.number(spec["mass"], (*where, "mass"))
        checks.append(_Check((*where, "mass"), "positive", (mass,)))
        centre = read.vector(spec.get("mass_centre", [0, 0, 0]), (*where, "mass_centre"))
        checks.append(_Check((*where, "mass_centre"), "finite", tuple(centre)))
        moments = _keys(
            spec["inertia"], (*where, "inertia"), required=("ixx", "iyy", "izz"), optional=("ixy", "iyz", "ixz")
        )
        entries = [
            read.number(moments.get(key, 0), (*where, "inertia", key))
            for key in ("ixx", "iyy", "izz", "ixy", "iyz", "ixz")
        ]
        checks.append(_Check((*where, "inertia"), "inertia", tuple(entries)))
        ixx, iyy, izz, ixy, iyz, ixz = entries
        tensor = sympy.Matrix([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        bodies.append(Body(name, mass, tensor, centre))
    body_names = {b.name for b in bodies}

    # Joints, in order: every parent exists before its child.
    frames: dict[str, Where] = {GROUND: r}
    carried: dict[str, str] = {}  # frame → its parent frame
    joints: list[Revolute | Prismatic | RollingWheel] = []
    coordinate_names: dict[str, Where] = {}
    wheels = 0

    def new_coordinate(coordinate: Coordinate, path: Where) -> Coordinate:
        if coordinate.name in coordinate_names:
            raise _refuse(path, f"the coordinate {coordinate.name!r} is named twice")
        coordinate_names[coordinate.name] = path
        if len(coordinate_names) > MAX_COORDINATES:
            raise _refuse(path, f"at most {MAX_COORDINATES} coordinates")
        return coordinate

    def new_frame(name: str, parent: str, path: Where) -> None:
        if name == GROUND or name in frames:
            raise _refuse(path, f"the frame {name!r} is made twice (or is the ground)")
        frames[name], carried[name] = path, parent

    def parent_frame(value: Any, path: Where) -> str:
        if isinstance(value, str) and value.endswith(".axle") and NAME.fullmatch(value[: -len(".axle")]):
            name = value
        else:
            name = GROUND if value == GROUND else _name(value, path)
        if name not in frames:
            raise _refuse(path, f"the parent {name!r} is no frame made by an earlier joint (nor the ground)")
        return name

    for k, entry in enumerate(_list(top["joints"], (*r, "joints"), most=MAX_JOINTS, least=1)):
        where = (*r, "joints", k)
        if not isinstance(entry, Mapping) or entry.get("type") not in _TYPES:
            raise _refuse((*where, "type"), f"must be one of {', '.join(_TYPES)}")
        kind = entry["type"]
        if kind == "rolling_wheel":
            spec = _keys(entry, where, required=("type", "wheel", "radius", *(c for c, _ in _WHEEL_COORDINATES)))
            wheel = _name(spec["wheel"], (*where, "wheel"))
            if wheel not in body_names:
                raise _refuse((*where, "wheel"), f"the rolling wheel {wheel!r} is no body")
            radius = read.number(spec["radius"], (*where, "radius"))
            checks.append(_Check((*where, "radius"), "positive", (radius,)))
            coordinates = {
                key: new_coordinate(_coordinate(spec[key], (*where, key), unit), (*where, key))
                for key, unit in _WHEEL_COORDINATES
            }
            new_frame(f"{wheel}.axle", GROUND, (*where, "wheel"))
            new_frame(wheel, f"{wheel}.axle", (*where, "wheel"))
            joints.append(RollingWheel(wheel, radius, **coordinates))
            wheels += 1
            continue
        if kind == "spherical":
            spec = _keys(entry, where, required=("type", "parent", "child", "coordinates"), optional=("at",))
        else:
            spec = _keys(entry, where, required=("type", "parent", "child", "coordinate", "axis"), optional=("at",))
        parent = parent_frame(spec["parent"], (*where, "parent"))
        child = _name(spec["child"], (*where, "child"))
        at = read.vector(spec.get("at", [0, 0, 0]), (*where, "at"))
        checks.append(_Check((*where, "at"), "finite", tuple(at)))
        if kind == "spherical":
            names = _list(spec["coordinates"], (*where, "coordinates"), most=3, least=3)
            turns = [
                new_coordinate(_coordinate(v, (*where, "coordinates", i), "rad"), (*where, "coordinates", i))
                for i, v in enumerate(names)
            ]
            first, second = (f"{child}{suffix}" for suffix in SPHERICAL_FRAMES)
            new_frame(first, parent, (*where, "child"))
            new_frame(second, first, (*where, "child"))
            new_frame(child, second, (*where, "child"))
            joints += [
                Revolute(parent, first, turns[0], column(1, 0, 0), at),
                Revolute(first, second, turns[1], column(0, 1, 0)),
                Revolute(second, child, turns[2], column(0, 0, 1)),
            ]
            continue
        unit = "m" if kind == "prismatic" else "rad"
        coordinate = new_coordinate(
            _coordinate(spec["coordinate"], (*where, "coordinate"), unit), (*where, "coordinate")
        )
        axis = _unit_axis(read.vector(spec["axis"], (*where, "axis")), (*where, "axis"), samples)
        checks.append(_Check((*where, "axis"), "axis", tuple(axis)))
        new_frame(child, parent, (*where, "child"))
        joints.append((Prismatic if kind == "prismatic" else Revolute)(parent, child, coordinate, axis, at))

    for k, body in enumerate(bodies):
        if body.name not in frames:
            raise _refuse((*r, "bodies", k, "name"), f"no joint moves the body {body.name!r}")
    # Every frame a joint turns or slides must carry mass, or that coordinate has no inertia (a singular M).
    loaded: set[str] = set()
    for frame in body_names:
        while frame in carried and frame not in loaded:
            loaded.add(frame)
            frame = carried[frame]
    for frame, path in frames.items():
        if frame != GROUND and frame not in loaded:
            raise _refuse(path, f"the frame {frame!r} carries no body: its coordinate would have no inertia")

    # Contacts.
    contacts: list[RollingContact | EllipsoidContact] = []
    for k, entry in enumerate(_list(top.get("contacts", []), (*r, "contacts"), most=MAX_CONTACTS)):
        where = (*r, "contacts", k)
        if not isinstance(entry, Mapping) or entry.get("type") not in _CONTACT_TYPES:
            raise _refuse((*where, "type"), f"must be one of {', '.join(_CONTACT_TYPES)}")
        if entry["type"] == "rolling_contact":
            spec = _keys(entry, where, required=("type", "wheel", "radius"), optional=("axle",))
            wheel = _name(spec["wheel"], (*where, "wheel"))
            if wheel not in body_names:
                raise _refuse((*where, "wheel"), f"the contact's wheel {wheel!r} is no body")
            radius = read.number(spec["radius"], (*where, "radius"))
            checks.append(_Check((*where, "radius"), "positive", (radius,)))
            axle = _unit_axis(read.vector(spec.get("axle", [0, 1, 0]), (*where, "axle")), (*where, "axle"), samples)
            checks.append(_Check((*where, "axle"), "axis", tuple(axle)))
            contacts.append(RollingContact(wheel, radius, axle))
        else:
            spec = _keys(entry, where, required=("type", "body", "semi_axes"), optional=("centre",))
            touching = _name(spec["body"], (*where, "body"))
            if touching not in body_names:
                raise _refuse((*where, "body"), f"the contact's body {touching!r} is no body")
            semi_axes = read.vector(spec["semi_axes"], (*where, "semi_axes"))
            for i, semi_axis in enumerate(semi_axes):
                checks.append(_Check((*where, "semi_axes", i), "positive", (semi_axis,)))
            centre = read.vector(spec.get("centre", [0, 0, 0]), (*where, "centre"))
            checks.append(_Check((*where, "centre"), "finite", tuple(centre)))
            contacts.append(EllipsoidContact(touching, semi_axes, centre))

    # Loads: forces and couples on bodies, springs and dampers on coordinates.
    loads: list[Load] = []
    for k, entry in enumerate(_list(top.get("loads", []), (*r, "loads"), most=MAX_LOADS)):
        where = (*r, "loads", k)
        if not isinstance(entry, Mapping) or entry.get("type") not in _LOAD_TYPES:
            raise _refuse((*where, "type"), f"must be one of {', '.join(_LOAD_TYPES)}")
        if entry["type"] == "spring":
            spec = _keys(entry, where, required=("type", "coordinate"), optional=("stiffness", "rest", "damping"))
            name = _name(spec["coordinate"], (*where, "coordinate"))
            if name not in coordinate_names:
                raise _refuse((*where, "coordinate"), f"{name!r} is no coordinate")
            stiffness, rest, damping = (
                read.number(spec.get(key, 0), (*where, key)) for key in ("stiffness", "rest", "damping")
            )
            checks.append(_Check((*where, "stiffness"), "nonnegative", (stiffness,)))
            checks.append(_Check((*where, "damping"), "nonnegative", (damping,)))
            checks.append(_Check((*where, "rest"), "finite", (rest,)))
            loads.append(JointSpring(name, stiffness, rest, damping))
            continue
        extras: tuple[str, ...] = ("point", "follower") if entry["type"] == "force" else ("follower",)
        spec = _keys(entry, where, required=("type", "body", "vector"), optional=extras)
        acted_on = _name(spec["body"], (*where, "body"))
        if acted_on not in body_names:
            raise _refuse((*where, "body"), f"the load's body {acted_on!r} is no body")
        follower = spec.get("follower", False)
        if not isinstance(follower, bool):
            raise _refuse((*where, "follower"), "true (it turns with the body) or false (a fixed direction)")
        vector = read.vector(spec["vector"], (*where, "vector"))
        checks.append(_Check((*where, "vector"), "finite", tuple(vector)))
        if entry["type"] == "force":
            point = read.vector(spec.get("point", [0, 0, 0]), (*where, "point"))
            checks.append(_Check((*where, "point"), "finite", tuple(point)))
            loads.append(Force(acted_on, vector, point, follower))
        else:
            loads.append(Torque(acted_on, vector, follower))

    # Dependent coordinates and speeds: one per configuration constraint, one per velocity constraint.
    dependent: dict[str, tuple[str, ...]] = {}
    needed = {"dependent_coordinates": len(contacts), "dependent_speeds": 2 * wheels + 3 * len(contacts)}
    why = {
        "dependent_coordinates": "one per contact (its height is zero)",
        "dependent_speeds": "two per rolling wheel and three per contact (the contact point at rest)",
    }
    for key, count in needed.items():
        listed = _list(top.get(key, []), (*r, key), most=MAX_COORDINATES)
        for i, name in enumerate(listed):
            _name(name, (*r, key, i))
            if name not in coordinate_names:
                raise _refuse((*r, key, i), f"{name!r} is no coordinate")
            if name in listed[:i]:
                raise _refuse((*r, key, i), f"{name!r} is named twice")
        if len(listed) != count:
            raise _refuse((*r, key), f"name {count}: {why[key]} (got {len(listed)})")
        dependent[key] = tuple(listed)

    # A parameter's symbol must not be a coordinate's, its rate's or its acceleration's.
    taken = {n for c in coordinate_names for n in (c, f"{c}_d", f"{c}_d_d")}
    for k, p in enumerate(parameters):
        if p.name in taken:
            raise _refuse((*r, "parameters", k, "name"), f"{p.name!r} is also a coordinate's name (or its rate's)")

    parameter_set = ParameterSet(tuple(parameters), check=_PartsCheck(checks, symbols))
    parameter_set.validate({})  # the declared values must make a physical system
    system = MultibodySystem(
        id=system_id,
        title=title,
        parameters=parameter_set,
        symbols=symbols,
        bodies=tuple(bodies),
        joints=tuple(joints),
        contacts=tuple(contacts),
        loads=tuple(loads),
        gravity=gravity,
        dependent_coordinates=dependent["dependent_coordinates"],
        dependent_speeds=dependent["dependent_speeds"],
        chapter=chapter,
        assumptions=assumptions,
    )
    if "reference" in top:
        reference = _reference(top["reference"], (*r, "reference"), system, read)
        fields = {name: getattr(system, name) for name in system.__dataclass_fields__}
        system = MultibodySystem(**{**fields, "reference": reference})
    return system


def _unit_axis(axis: sympy.Matrix, path: Where, samples: Sequence[Mapping[sympy.Symbol, float]]) -> sympy.Matrix:
    """``axis`` normalised: exactly when its components are numbers; else divided by its length unless that is 1 at
    every one of ``samples`` (parameter values: the declared ones and others within the bounds), as a bicycle's
    (−sin λ, 0, cos λ) is. Nothing is expanded or simplified: a component may be a large power of a sum, and the
    server must not multiply it out."""
    squared = sum((component**2 for component in axis), sympy.Integer(0))
    if squared.is_number:
        if squared == 0 or float(squared) < 1e-18:
            raise _refuse(path, "an axis of zero length: give a direction")
        return axis if squared == 1 else axis / sympy.sqrt(squared)
    values = [_value_at(squared, sample) for sample in samples]
    if all(v is not None and abs(v - 1.0) < 1e-12 for v in values):
        return axis
    return axis / sympy.sqrt(squared)


def _value_at(expression: sympy.Expr, values: Mapping[sympy.Symbol, float]) -> float | None:
    """``expression``'s value (float) with the symbols replaced by ``values``; None where it has none finite."""
    try:
        value = complex(expression.xreplace({k: sympy.Float(v) for k, v in values.items()}).evalf())
    except (TypeError, ValueError, OverflowError, ZeroDivisionError):
        return None
    return value.real if value.imag == 0 and math.isfinite(value.real) else None


def _parameter_samples(parameters: Sequence[Parameter], symbols: Mapping[str, sympy.Symbol]) -> list[dict]:
    """The declared values and four other points within the bounds (fixed, so a description always reads the same)."""
    rng = np.random.default_rng(20261129)
    samples = [{symbols[p.name]: float(p.default) for p in parameters}]  # type: ignore[arg-type]
    for _ in range(4):
        samples.append({symbols[p.name]: float(rng.uniform(p.min, p.max)) for p in parameters})  # type: ignore[arg-type]
    return samples


@dataclass(frozen=True)
class _ReferenceState:
    """A reference state (q, q̇) of expressions of the parameters, evaluated at given values."""

    symbols: tuple[tuple[str, sympy.Symbol], ...]
    expressions: tuple[sympy.Expr, ...]

    def __call__(self, params: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        values = _values(self.expressions, dict(self.symbols), params)
        numbers = np.array([math.nan if v is None else v for v in values], dtype=float)
        n = len(numbers) // 2
        return numbers[:n], numbers[n:]


def _reference(value: Any, path: Where, system: MultibodySystem, read: _Reader) -> ReferenceMotion:
    spec = _keys(
        value, path, required=("coordinates", "speeds"), optional=("about", "state", "sweep", "crossing_names")
    )
    names = [c.name for c in system.coordinates]
    n = len(names)
    chosen: dict[str, tuple[str, ...]] = {}
    for key in ("coordinates", "speeds"):
        entries = _list(spec[key], (*path, key), most=n, least=0)
        for i, name in enumerate(entries):
            if name not in names:
                raise _refuse((*path, key, i), f"{str(name)[:40]!r} is no coordinate")
            if name in entries[:i]:
                raise _refuse((*path, key, i), f"{name!r} is named twice")
        chosen[key] = tuple(entries)
    if not chosen["coordinates"] and not chosen["speeds"]:
        raise _refuse(path, "name at least one coordinate or speed to linearise")
    state = _list(spec.get("state", [0] * (2 * n)), (*path, "state"), most=2 * n, least=2 * n)
    expressions = tuple(read.number(v, (*path, "state", i)) for i, v in enumerate(state))
    sweep = None
    if "sweep" in spec:
        s = _keys(spec["sweep"], (*path, "sweep"), required=("parameter", "low", "high"))
        if _name(s["parameter"], (*path, "sweep", "parameter")) not in system.parameters.by_name:
            raise _refuse((*path, "sweep", "parameter"), "must name a declared parameter")
        low, high = (float(_plain_number(s[key], (*path, "sweep", key))) for key in ("low", "high"))
        if not low < high:
            raise _refuse((*path, "sweep", "high"), "must be above low")
        sweep = (str(s["parameter"]), low, high)
    crossing_names = []
    for i, entry in enumerate(_list(spec.get("crossing_names", []), (*path, "crossing_names"), most=4)):
        c = _keys(entry, (*path, "crossing_names", i), required=("becomes", "oscillating", "name"))
        if c["becomes"] not in ("stable", "unstable") or not isinstance(c["oscillating"], bool):
            raise _refuse((*path, "crossing_names", i), "becomes: stable or unstable; oscillating: true or false")
        crossing_names.append(
            (str(c["becomes"]), c["oscillating"], _text(c["name"], (*path, "crossing_names", i, "name"), "label"))
        )
    return ReferenceMotion(
        about=_text(spec.get("about", "the given reference state"), (*path, "about"), "about"),
        coordinates=chosen["coordinates"],
        speeds=chosen["speeds"],
        state=_ReferenceState(tuple(system.symbols.items()), expressions),
        sweep=sweep,
        crossing_names=tuple(crossing_names),
    )


# -- writing ---------------------------------------------------------------------------------------------------------
def _expression_data(expression: Any, names: Mapping[sympy.Symbol, str]) -> Any:
    """A sympy expression of parameter symbols as the data form's number, name or expression tree."""
    e = sympy.sympify(expression)
    if e.is_Symbol:
        if e not in names:
            raise ValueError(f"{e} is no parameter's symbol")
        return names[e]
    if e.is_Integer:
        return int(e)
    if e.is_Rational:
        return {"div": [int(e.p), int(e.q)]}
    if e.is_Float:
        return float(e)
    if e.is_Add:
        return {"add": [_expression_data(a, names) for a in e.args]}
    if e.is_Mul:
        if e.args[0] == -1:
            rest = e.args[1:]
            inner = rest[0] if len(rest) == 1 else sympy.Mul(*rest, evaluate=False)
            return {"neg": _expression_data(inner, names)}
        return {"mul": [_expression_data(a, names) for a in e.args]}
    if e.is_Pow and e.exp.is_Integer and abs(int(e.exp)) <= MAX_POWER:
        if int(e.exp) < 0:
            return {"div": [1, _expression_data(e.base ** (-e.exp), names)]}
        return {"pow": [_expression_data(e.base, names), int(e.exp)]}
    if isinstance(e, sympy.sin | sympy.cos):
        return {type(e).__name__: _expression_data(e.args[0], names)}
    raise ValueError(f"{e} has no data form (numbers, parameters, +, ×, ÷, whole powers, sin and cos)")


def _coordinate_data(c: Coordinate) -> Any:
    return c.name if c.latex == c.name else {"name": c.name, "latex": c.latex}


def system_to_data(system: MultibodySystem, *, reference_state: Sequence[Any] | None = None) -> dict[str, Any]:
    """The data form of ``system`` (:func:`system_from_data` of it gives the same equations).

    A reference motion's state is a function in Python: give it as ``reference_state`` (2n numbers or expressions
    of the parameter symbols, q then q̇; a system read from data keeps its own); without it, the state at the
    default parameters is written if it does not change when they do (a ValueError if it does)."""
    names = {symbol: name for name, symbol in system.symbols.items()}

    def number(e: Any) -> Any:
        return _expression_data(e, names)

    def vector(v: sympy.Matrix) -> list[Any]:
        return [number(x) for x in v]

    data: dict[str, Any] = {"id": system.id, "title": system.title, "chapter": system.chapter}
    if system.assumptions:
        data["assumptions"] = system.assumptions
    data["parameters"] = [
        {
            "name": p.name,
            "value": p.default,
            "unit": p.unit,
            "low": p.min,
            "high": p.max,
            **({"label": p.label} if p.label else {}),
            "description": p.description,
        }
        for p in system.parameters.parameters
    ]
    data["gravity"] = number(system.gravity)
    data["bodies"] = []
    for body in system.bodies:
        inertia = body.inertia
        moments = {
            "ixx": inertia[0, 0],
            "iyy": inertia[1, 1],
            "izz": inertia[2, 2],
            "ixy": inertia[0, 1],
            "iyz": inertia[1, 2],
            "ixz": inertia[0, 2],
        }
        data["bodies"].append(
            {
                "name": body.name,
                "mass": number(body.mass),
                "mass_centre": vector(body.mass_centre),
                "inertia": {k: number(v) for k, v in moments.items() if k in ("ixx", "iyy", "izz") or v != 0},
            }
        )
    data["joints"] = []
    for joint in system.joints:
        if isinstance(joint, RollingWheel):
            entry: dict[str, Any] = {"type": "rolling_wheel", "wheel": joint.wheel, "radius": number(joint.radius)}
            entry |= {key: _coordinate_data(getattr(joint, key)) for key, _ in _WHEEL_COORDINATES}
        else:
            entry = {
                "type": "prismatic" if isinstance(joint, Prismatic) else "revolute",
                "parent": joint.parent,
                "child": joint.child,
                "coordinate": _coordinate_data(joint.coordinate),
                "axis": vector(joint.axis),
                "at": vector(joint.at),
            }
        data["joints"].append(entry)
    data["contacts"] = []
    for contact in system.contacts:
        if isinstance(contact, RollingContact):
            data["contacts"].append(
                {"type": "rolling_contact", "wheel": contact.wheel, "radius": number(contact.radius),
                 "axle": vector(contact.axle)}
            )  # fmt: skip
        else:
            data["contacts"].append(
                {"type": "ellipsoid_contact", "body": contact.body, "semi_axes": vector(contact.semi_axes),
                 "centre": vector(contact.centre)}
            )  # fmt: skip
    if system.loads:
        data["loads"] = []
    for load in system.loads:
        if isinstance(load, JointSpring):
            data["loads"].append(
                {"type": "spring", "coordinate": load.coordinate, "stiffness": number(load.stiffness),
                 "rest": number(load.rest), "damping": number(load.damping)}
            )  # fmt: skip
        elif isinstance(load, Force):
            data["loads"].append(
                {"type": "force", "body": load.body, "vector": vector(load.vector), "point": vector(load.point),
                 "follower": load.follower}
            )  # fmt: skip
        else:
            data["loads"].append(
                {"type": "torque", "body": load.body, "vector": vector(load.vector), "follower": load.follower}
            )
    data["dependent_coordinates"] = list(system.dependent_coordinates)
    data["dependent_speeds"] = list(system.dependent_speeds)
    reference = system.reference
    if reference is not None:
        if reference_state is None and isinstance(reference.state, _ReferenceState):
            reference_state = reference.state.expressions
        if reference_state is None:
            defaults: dict[str, Any] = system.parameters.defaults()
            moved: dict[str, Any] = dict(defaults)
            for p in system.parameters.parameters:
                if p.kind == "float" and p.max is not None:
                    moved[p.name] = float(p.default) + (p.max - float(p.default)) / 10  # type: ignore[arg-type]
            state, other = (np.concatenate(reference.state(v)) for v in (defaults, moved))
            if not np.array_equal(state, other):
                raise ValueError(f"{system.id}: its reference state depends on the parameters: give reference_state")
            reference_state = [float(x) for x in state]
        written: dict[str, Any] = {
            "about": reference.about,
            "coordinates": list(reference.coordinates),
            "speeds": list(reference.speeds),
            "state": [number(x) for x in reference_state],
        }
        if reference.sweep is not None:
            parameter, low, high = reference.sweep
            written["sweep"] = {"parameter": parameter, "low": low, "high": high}
        if reference.crossing_names:
            written["crossing_names"] = [
                {"becomes": b, "oscillating": o, "name": n} for b, o, n in reference.crossing_names
            ]
        data["reference"] = written
    return data


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError("TOML here holds finite numbers only")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise ValueError(f"no TOML form for {type(value).__name__}")


def _toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key, ensure_ascii=False)


def to_toml(data: Mapping[str, Any]) -> str:
    """The data form as TOML: scalars and lists of values first, then each list of tables as ``[[name]]`` entries,
    then each table (``[reference]``), nested values as inline tables."""
    lines: list[str] = []
    tables = {k: v for k, v in data.items() if isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v)}
    sections = {k: v for k, v in data.items() if isinstance(v, Mapping)}
    for key, value in data.items():
        if key not in tables and key not in sections:
            lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
    for key, entries in tables.items():
        for entry in entries:
            lines += ["", f"[[{_toml_key(key)}]]"]
            lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in entry.items()]
    for key, section in sections.items():
        lines += ["", f"[{_toml_key(key)}]"]
        lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in section.items()]
    return "\n".join(lines) + "\n"


def system_to_toml(system: MultibodySystem, *, reference_state: Sequence[Any] | None = None) -> str:
    """:func:`system_to_data` as TOML text (:func:`system_from_toml` reads it back)."""
    return to_toml(system_to_data(system, reference_state=reference_state))
