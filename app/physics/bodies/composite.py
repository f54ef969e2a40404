"""Composite bodies: primitives placed and turned in a reference frame, holes as negative bodies.

A :class:`Part` is one primitive shape (see :data:`SHAPES`) with its mass, the
position of its own centre of mass and its orientation (a rotation sequence and
three angles from the reference frame to the shape's own axes). A hole is a
part whose mass is removed. :func:`combine` adds the parts with the parallel-axis
theorem and refuses a body that cannot exist (a hole outside every solid part or
denser than the part it is cut from, two holes that overlap, no mass left, a
tensor that is not positive definite).

:func:`parts_from_records` turns request data (a list of dicts, as the API and
the scenes receive it) into parts, raising :class:`ParameterError` whose path
names the offending entry and field (``bodies → 2 → radius_m``; :func:`body_place` words it as the page's
body editor does).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from app.physics.bodies import inertia
from app.physics.core.parameters import ParameterError
from app.physics.math.rotations import SEQUENCES, matrix_from_angles

#: Largest number of parts in one composite body.
MAX_PARTS = 24
#: Dimensions and masses a request may give (m, kg): a body from a grain to a building.
DIMENSION_RANGE_M = (1e-4, 100.0)
MASS_RANGE_KG = (1e-6, 1e6)
POSITION_LIMIT_M = 100.0

Extent = Literal["volume", "area", "line"]


@dataclass(frozen=True)
class Shape:
    """A primitive: its dimension names, tensor, extent (volume, area, line) and geometry.

    ``measure`` is its volume (m³), area (m²) or length (m); ``contains`` tests
    points (N, 3) in the shape's own axes; ``outline`` gives points on its
    boundary (own axes) that a hole must keep inside its container; ``corner``
    is the upper corner (3,) of its bounding box in its own axes about its
    centre of mass (``lower`` the other, by default its mirror image).
    """

    name: str
    dimensions: tuple[str, ...]
    tensor: Callable[..., np.ndarray]
    extent: Extent
    measure: Callable[..., float]
    contains: Callable[..., np.ndarray]
    outline: Callable[..., np.ndarray]
    symmetry_axis: str
    description: str
    corner: Callable[..., np.ndarray]
    lower: Callable[..., np.ndarray] | None = None

    def bounds(self, *size: float) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper corners (3,) (3,) of the bounding box in the shape's own axes, m."""
        upper = np.asarray(self.corner(*size), float)
        return (np.asarray(self.lower(*size), float) if self.lower is not None else -upper), upper


def _circle(radius: float, z: float, n: int = 24) -> np.ndarray:
    a = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.full(n, z)])


def _sphere_points(radius: float) -> np.ndarray:
    directions = np.array(
        [[1, 0, 0], [0, 1, 0], [0, 0, 1]] + [[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float
    )
    directions = np.vstack([directions, -directions[:3]])
    return radius * directions / np.linalg.norm(directions, axis=1, keepdims=True)


def _box_corners(a: float, b: float, c: float) -> np.ndarray:
    return np.array([[sx * a / 2, sy * b / 2, sz * c / 2] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])


def _in_cylinder(
    p: np.ndarray, radius: float, z_low: float, z_high: float, tol: float, *, inner: float = 0.0
) -> np.ndarray:
    rho = np.hypot(p[:, 0], p[:, 1])
    return (rho <= radius + tol) & (rho >= inner - tol) & (p[:, 2] >= z_low - tol) & (p[:, 2] <= z_high + tol)


def _flat(p: np.ndarray, tol: float) -> np.ndarray:
    return np.abs(p[:, 2]) <= tol


SHAPES: dict[str, Shape] = {
    s.name: s
    for s in (
        Shape(
            "sphere",
            ("radius_m",),
            inertia.solid_sphere,
            "volume",
            lambda r: 4.0 / 3.0 * math.pi * r**3,
            lambda p, r, tol: np.linalg.norm(p, axis=1) <= r + tol,
            _sphere_points,
            "any axis",
            "solid sphere; every axis through its centre is a symmetry axis",
            lambda r: np.array([r, r, r]),
        ),
        Shape(
            "spherical-shell",
            ("radius_m",),
            inertia.spherical_shell,
            "area",
            lambda r: 4.0 * math.pi * r**2,
            lambda p, r, tol: np.abs(np.linalg.norm(p, axis=1) - r) <= tol,
            _sphere_points,
            "any axis",
            "thin spherical shell",
            lambda r: np.array([r, r, r]),
        ),
        Shape(
            "cylinder",
            ("radius_m", "length_m"),
            inertia.solid_cylinder,
            "volume",
            lambda r, L: math.pi * r**2 * L,
            lambda p, r, L, tol: _in_cylinder(p, r, -L / 2, L / 2, tol),
            lambda r, L: np.vstack([_circle(r, -L / 2), _circle(r, L / 2)]),
            "z",
            "solid cylinder, axis along its own z",
            lambda r, L: np.array([r, r, L / 2]),
        ),
        Shape(
            "tube",
            ("radius_m", "inner_radius_m", "length_m"),
            inertia.tube,
            "volume",
            lambda r, ri, L: math.pi * (r**2 - ri**2) * L,
            lambda p, r, ri, L, tol: _in_cylinder(p, r, -L / 2, L / 2, tol, inner=ri),
            lambda r, ri, L: np.vstack(
                [_circle(r, -L / 2), _circle(r, L / 2), _circle(ri, -L / 2), _circle(ri, L / 2)]
            ),
            "z",
            "thick-walled tube, axis along its own z",
            lambda r, ri, L: np.array([r, r, L / 2]),
        ),
        Shape(
            "box",
            ("length_m", "width_m", "height_m"),
            inertia.box,
            "volume",
            lambda a, b, c: a * b * c,
            lambda p, a, b, c, tol: np.all(np.abs(p) <= np.array([a, b, c]) / 2 + tol, axis=1),
            _box_corners,
            "none",
            "rectangular block: length along x, width along y, height along z",
            lambda a, b, c: np.array([a, b, c]) / 2,
        ),
        Shape(
            "rod",
            ("length_m",),
            inertia.slender_rod,
            "line",
            lambda L: L,
            lambda p, L, tol: (np.hypot(p[:, 0], p[:, 1]) <= tol) & (np.abs(p[:, 2]) <= L / 2 + tol),
            lambda L: np.array([[0.0, 0.0, -L / 2], [0.0, 0.0, L / 2]]),
            "z",
            "slender rod along its own z",
            lambda L: np.array([0.0, 0.0, L / 2]),
        ),
        Shape(
            "plate",
            ("length_m", "width_m"),
            inertia.thin_plate,
            "area",
            lambda a, b: a * b,
            lambda p, a, b, tol: _flat(p, tol) & np.all(np.abs(p[:, :2]) <= np.array([a, b]) / 2 + tol, axis=1),
            lambda a, b: _box_corners(a, b, 0.0)[::2],
            "z (normal)",
            "thin rectangular plate: length along x, width along y, normal along z",
            lambda a, b: np.array([a / 2, b / 2, 0.0]),
        ),
        Shape(
            "disk",
            ("radius_m",),
            inertia.thin_disk,
            "area",
            lambda r: math.pi * r**2,
            lambda p, r, tol: _flat(p, tol) & (np.hypot(p[:, 0], p[:, 1]) <= r + tol),
            lambda r: _circle(r, 0.0),
            "z (normal)",
            "thin disk, normal along its own z",
            lambda r: np.array([r, r, 0.0]),
        ),
        Shape(
            "cone",
            ("radius_m", "height_m"),
            inertia.solid_cone,
            "volume",
            lambda r, h: math.pi * r**2 * h / 3.0,
            # Own origin at the centre of mass: base at z = −h/4, apex at z = +3h/4.
            lambda p, r, h, tol: (
                (p[:, 2] >= -h / 4 - tol)
                & (p[:, 2] <= 3 * h / 4 + tol)
                & (np.hypot(p[:, 0], p[:, 1]) <= r * (3 * h / 4 - p[:, 2]) / h + tol)
            ),
            lambda r, h: np.vstack([_circle(r, -h / 4), [[0.0, 0.0, 3 * h / 4]]]),
            "z",
            "solid right circular cone, axis along its own z, apex towards "
            "+z; its position is its centre of mass (¼ h above the base)",
            lambda r, h: np.array([r, r, 3 * h / 4]),
            lambda r, h: np.array([-r, -r, -h / 4]),
        ),
    )
}


@dataclass(frozen=True)
class Part:
    """One primitive in the reference frame: positions in m, masses in kg.

    ``rotation`` has the shape's own axes as columns (reference components).
    """

    shape: Shape
    mass_kg: float
    dimensions_m: Mapping[str, float]
    position_m: np.ndarray
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    hole: bool = False

    @property
    def size_args(self) -> tuple[float, ...]:
        return tuple(self.dimensions_m[name] for name in self.shape.dimensions)

    @property
    def signed_mass_kg(self) -> float:
        return -self.mass_kg if self.hole else self.mass_kg

    @property
    def inertia_own_kg_m2(self) -> np.ndarray:
        """About its own centre of mass, in its own axes (positive even for a hole)."""
        return self.shape.tensor(self.mass_kg, *self.size_args)

    @property
    def inertia_cm_reference_kg_m2(self) -> np.ndarray:
        """About its own centre of mass, reference components, signed (a hole's is negative)."""
        sign = -1.0 if self.hole else 1.0
        return sign * inertia.rotate_tensor(self.inertia_own_kg_m2, self.rotation)

    @property
    def density(self) -> float:
        """Mass per volume, area or length (kg/m³, kg/m², kg/m)."""
        return self.mass_kg / self.shape.measure(*self.size_args)

    def to_own(self, points_m: np.ndarray) -> np.ndarray:
        """Reference-frame points (N, 3) in this part's own axes about its centre of mass."""
        return (np.asarray(points_m, float) - self.position_m) @ self.rotation

    def outline_reference_m(self) -> np.ndarray:
        return self.shape.outline(*self.size_args) @ self.rotation.T + self.position_m

    def contains(self, points_m: np.ndarray) -> np.ndarray:
        tol = 1e-9 * max(self.size_args)
        return self.shape.contains(self.to_own(points_m), *self.size_args, tol)


@dataclass(frozen=True)
class CompositeBody:
    """Mass properties of a composite body: total mass (kg), centre of mass (m) and inertia about it (kg·m²), reference
    frame."""

    parts: tuple[Part, ...]
    mass_kg: float
    centre_of_mass_m: np.ndarray
    inertia_cm_kg_m2: np.ndarray
    principal: inertia.PrincipalAxes

    def inertia_about_kg_m2(self, point_m: np.ndarray) -> np.ndarray:
        """Inertia about ``point_m`` (reference components), by the parallel-axis theorem."""
        return inertia.parallel_axis(
            self.inertia_cm_kg_m2, self.mass_kg, self.centre_of_mass_m - np.asarray(point_m, float)
        )


def _check_holes(parts: Sequence[Part]) -> None:
    """Each hole must lie inside one solid part of the same extent, and be no denser than it."""
    for index, part in enumerate(parts):
        if not part.hole:
            continue
        points = part.outline_reference_m()
        hosts = [p for p in parts if not p.hole and p.shape.extent == part.shape.extent and np.all(p.contains(points))]
        if not hosts:
            raise ParameterError(
                "bodies",
                f"this hole (a {part.shape.name}) does not lie inside any solid "
                f"{part.shape.extent} part: a hole must be cut from a body of the same kind "
                "(a solid from a solid, a flat shape from a plate or disk, a rod from a rod)",
                path=("bodies", index),
            )
        host = max(hosts, key=lambda p: p.density)
        if part.density > host.density * (1.0 + 1e-6):
            largest = host.density * part.shape.measure(*part.size_args)
            raise ParameterError(
                "bodies",
                f"this hole removes {part.mass_kg:.6g} kg, more than the {largest:.6g} kg the body it is cut from has "
                "in that space (same density)",
                path=("bodies", index, "mass_kg"),
            )


#: Cells per axis of the lattice whose cell centres sample a hole when holes are checked for overlap (by its extent):
#: an overlap thinner than about one cell (1/32 of a solid hole's size, 1/64 of a flat one's, 1/256 of a rod) can pass.
OVERLAP_CELLS: dict[str, int] = {"volume": 32, "area": 64, "line": 256}
#: Points sampling a spherical shell (a Fibonacci spiral).
SHELL_SAMPLES = 2000


def sample_points(part: Part) -> np.ndarray:
    """Points (M, 3) of the reference frame spread through ``part``: the centres of a lattice of cells over its bounding
    box (in its own axes) that lie in it, or a Fibonacci spiral over a spherical shell. Cell centres keep off the box's
    faces, so two parts that only touch share none."""
    size = part.size_args
    if part.shape.name == "spherical-shell":
        k = np.arange(SHELL_SAMPLES) + 0.5
        polar, azimuth = np.arccos(1.0 - 2.0 * k / SHELL_SAMPLES), math.pi * (1.0 + math.sqrt(5.0)) * k
        own = size[0] * np.column_stack(
            [np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)]
        )
    else:
        low, high = part.shape.bounds(*size)
        cells = OVERLAP_CELLS[part.shape.extent]
        axes = [
            np.array([0.0]) if high[i] == low[i] else low[i] + (np.arange(cells) + 0.5) * (high[i] - low[i]) / cells
            for i in range(3)
        ]
        own = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        own = own[part.shape.contains(own, *size, 1e-9 * max(size))]
    return own @ part.rotation.T + part.position_m


def _bounding_radius_m(part: Part) -> float:
    low, high = part.shape.bounds(*part.size_args)
    return float(max(np.linalg.norm(low), np.linalg.norm(high)))


def _check_hole_overlaps(parts: Sequence[Part]) -> None:
    """Holes may touch but not overlap: material removed twice would be subtracted twice (a body lighter than it is).

    Each pair of holes of the same extent is tested both ways: does any of one's :func:`sample_points` lie in the other?
    """
    holes = [(index, part) for index, part in enumerate(parts) if part.hole]
    samples: dict[int, np.ndarray] = {}
    for a, (first_index, first) in enumerate(holes):
        for second_index, second in holes[a + 1 :]:
            if first.shape.extent != second.shape.extent:
                continue
            if np.linalg.norm(first.position_m - second.position_m) > _bounding_radius_m(first) + _bounding_radius_m(
                second
            ):
                continue
            for index in (first_index, second_index):
                if index not in samples:
                    samples[index] = sample_points(parts[index])
            if np.any(second.contains(samples[first_index])) or np.any(first.contains(samples[second_index])):
                raise ParameterError(
                    "bodies",
                    f"this hole (a {second.shape.name}) overlaps the hole at body "
                    f"{first_index + 1}: the material they share would be removed twice. Make "
                    "the holes only touch, or describe the opening as holes that do not overlap",
                    path=("bodies", second_index),
                )


def combine(parts: Sequence[Part]) -> CompositeBody:
    """Total mass, centre of mass and inertia about it of ``parts`` (holes subtracted); refuses bodies that cannot
    exist."""
    if not parts:
        raise ParameterError("bodies", "give at least one body", path=("bodies",))
    if all(p.hole for p in parts):
        raise ParameterError("bodies", "every entry is a hole: give at least one solid body", path=("bodies",))
    _check_holes(parts)
    _check_hole_overlaps(parts)
    masses = np.array([p.signed_mass_kg for p in parts])
    try:
        centre = inertia.centre_of_mass_m(masses, np.array([p.position_m for p in parts]))
    except ValueError as exc:
        raise ParameterError("bodies", str(exc), path=("bodies",)) from None
    total = float(np.sum(masses))
    tensor = np.zeros((3, 3))
    for part in parts:
        tensor += inertia.parallel_axis(part.inertia_cm_reference_kg_m2, part.signed_mass_kg, part.position_m - centre)
    tensor = 0.5 * (tensor + tensor.T)
    try:
        principal = inertia.check_inertia_tensor(
            tensor,
            about="the composite body's centre of mass",
            hint=(
                "a slender rod alone has none about its own axis (use a thin "
                "cylinder), and holes may remove more than the bodies have"
            ),
        )
    except ValueError as exc:
        raise ParameterError("bodies", str(exc), path=("bodies",)) from None
    return CompositeBody(tuple(parts), total, centre, tensor, principal)


# -- request records ---------------------------------------------------------------
RECORD_FIELDS = ("shape", "mass_kg", "position_m", "sequence", "angles_deg", "hole")


def _number(value: Any, path: tuple[Any, ...], low: float, high: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(path[0], f"must be a number between {low:g} and {high:g} {unit}", path=path)
    if not math.isfinite(value):
        raise ParameterError(path[0], "must be a finite number", path=path)
    if not low <= value <= high:
        raise ParameterError(path[0], f"must be between {low:g} and {high:g} {unit} (got {value:g})", path=path)
    return float(value)


def _triple(value: Any, path: tuple[Any, ...], limit: float, unit: str) -> list[float]:
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise ParameterError(path[0], f"must be a list of 3 numbers in {unit}", path=path)
    return [_number(v, (*path, i), -limit, limit, unit) for i, v in enumerate(value)]


def validate_record(raw: Any, index: int, *, name: str = "bodies") -> dict[str, Any]:
    """One body of a request, checked and normalised (defaults filled); ParameterError names
    ``name → index → field``."""
    here = (name, index)
    if not isinstance(raw, Mapping):
        raise ParameterError(
            name, "each body must be an object with a shape, mass_kg, its dimensions and position_m", path=here
        )
    shape_name = raw.get("shape")
    shape = SHAPES.get(shape_name) if isinstance(shape_name, str) else None
    if shape is None:
        raise ParameterError(
            name, f"unknown shape {shape_name!r}; expected one of: {', '.join(SHAPES)}", path=(*here, "shape")
        )
    allowed = set(RECORD_FIELDS) | set(shape.dimensions)
    for key in raw:
        if key not in allowed:
            raise ParameterError(
                name, f"unknown field for a {shape.name}; expected: {', '.join(sorted(allowed))}", path=(*here, key)
            )
    out: dict[str, Any] = {"shape": shape.name}
    if "mass_kg" not in raw:
        raise ParameterError(name, "missing: give the mass in kg", path=(*here, "mass_kg"))
    out["mass_kg"] = _number(raw["mass_kg"], (*here, "mass_kg"), *MASS_RANGE_KG, "kg")
    for dimension in shape.dimensions:
        if dimension not in raw:
            raise ParameterError(
                name, f"missing: a {shape.name} needs {', '.join(shape.dimensions)}", path=(*here, dimension)
            )
        out[dimension] = _number(raw[dimension], (*here, dimension), *DIMENSION_RANGE_M, "m")
    if shape.name == "tube" and out["inner_radius_m"] >= out["radius_m"]:
        raise ParameterError(
            name,
            f"the inner radius ({out['inner_radius_m']:g} m) must "
            f"be less than the outer radius ({out['radius_m']:g} m)",
            path=(*here, "inner_radius_m"),
        )
    out["position_m"] = _triple(raw.get("position_m", [0.0, 0.0, 0.0]), (*here, "position_m"), POSITION_LIMIT_M, "m")
    sequence = raw.get("sequence", "3-2-1")
    if not isinstance(sequence, str) or sequence not in SEQUENCES:
        raise ParameterError(
            name,
            f"unknown rotation sequence {sequence!r}; expected one of: {', '.join(SEQUENCES)}",
            path=(*here, "sequence"),
        )
    out["sequence"] = sequence
    out["angles_deg"] = _triple(raw.get("angles_deg", [0.0, 0.0, 0.0]), (*here, "angles_deg"), 720.0, "deg")
    hole = raw.get("hole", False)
    if not isinstance(hole, bool):
        raise ParameterError(name, "must be true or false", path=(*here, "hole"))
    out["hole"] = hole
    return out


def body_place(path: tuple[str | int, ...]) -> str:
    """Where a refusal points in the page's body editor, in the editor's own words: ``(3, "radius_m")`` →
    ``"body 4, radius (m)"``, ``(0, "position_m", 2)`` → ``"body 1, z (m)"`` (rows count from 1 there)."""
    index, *inside = path
    words = [f"body {index + 1}" if isinstance(index, int) else str(index)]
    if inside:
        field, component = inside[0], inside[1] if len(inside) > 1 else None
        if field == "position_m":
            words.append(f"{'xyz'[component]} (m)" if isinstance(component, int) else "position (m)")
        elif field == "angles_deg":
            words.append(f"angle {component + 1} (deg)" if isinstance(component, int) else "angles (deg)")
        elif field == "mass_kg":
            words.append("mass (kg)")
        elif isinstance(field, str) and field.endswith("_m"):
            words.append(f"{field.removesuffix('_m').replace('_', ' ')} (m)")
        else:
            words.append(str(field))
    return ", ".join(words)


def validate_records(raw: Any, *, name: str = "bodies") -> list[dict[str, Any]]:
    """A whole list of bodies checked and normalised; the composite is formed too, so impossible bodies are refused
    here."""
    if not isinstance(raw, (list, tuple)):
        raise ParameterError(name, "must be a list of bodies", path=(name,))
    if not 1 <= len(raw) <= MAX_PARTS:
        raise ParameterError(name, f"give between 1 and {MAX_PARTS} bodies (got {len(raw)})", path=(name,))
    records = [validate_record(item, i, name=name) for i, item in enumerate(raw)]
    combine(parts_from_records(records))
    return records


def part_from_record(record: Mapping[str, Any]) -> Part:
    """A :class:`Part` from one validated record."""
    shape = SHAPES[record["shape"]]
    return Part(
        shape=shape,
        mass_kg=float(record["mass_kg"]),
        dimensions_m={d: float(record[d]) for d in shape.dimensions},
        position_m=np.asarray(record["position_m"], float),
        rotation=matrix_from_angles(np.radians(record["angles_deg"]), record["sequence"]),
        hole=bool(record["hole"]),
    )


def parts_from_records(records: Sequence[Mapping[str, Any]]) -> list[Part]:
    return [part_from_record(r) for r in records]


def shapes_schema() -> list[dict[str, Any]]:
    """Each shape's name, dimension fields, extent and own axes, for the API schema and the page's body editor."""
    return [
        {
            "shape": s.name,
            "dimensions": list(s.dimensions),
            "extent": s.extent,
            "symmetry_axis": s.symmetry_axis,
            "description": s.description,
        }
        for s in SHAPES.values()
    ]
