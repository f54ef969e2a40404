"""Inertia properties of rigid bodies: the one home for tensors, their transformations and principal axes.

Sign convention (used everywhere in Dynamics Lab): the products of inertia are
``I_xy = ∫ x y dm`` (and likewise ``I_xz``, ``I_yz``), and the inertia tensor is

    [[ I_xx, −I_xy, −I_xz],
     [−I_xy,  I_yy, −I_yz],
     [−I_xz, −I_yz,  I_zz]]

so that ``H = I ω`` and ``T = ½ ωᵀ I ω``. Tensors are 3×3 numpy arrays in kg·m²;
positions in m; a rotation ``R`` has the shape's own axes as its columns, in the
reference frame's components (``v_ref = R v_shape``).

Primitives return the tensor about the shape's own centre of mass in the
shape's own axes. Every axisymmetric shape (cylinder, tube, rod, disk, cone)
has its symmetry axis along its own z; a box has length along x, width along
y, height along z; a thin plate has length along x, width along y and its
normal along z; a cone's origin is its centre of mass, a quarter of the height
above the base, with the apex towards +z.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, cast

import numpy as np

#: Relative gap below which two principal moments are reported as equal.
REPEATED_MOMENT_TOLERANCE = 1e-9


def _diagonal(ixx: float, iyy: float, izz: float) -> np.ndarray:
    return np.diag([float(ixx), float(iyy), float(izz)])


def _axisymmetric(axial: float, transverse: float) -> np.ndarray:
    return _diagonal(transverse, transverse, axial)


# -- primitives (about their own centre of mass, in their own axes) ---------------
def solid_sphere(mass_kg: float, radius_m: float) -> np.ndarray:
    """Uniform solid sphere: ``⅖ m r²`` about every axis."""
    return _diagonal(*(0.4 * mass_kg * radius_m**2,) * 3)


def spherical_shell(mass_kg: float, radius_m: float) -> np.ndarray:
    """Thin uniform spherical shell: ``⅔ m r²`` about every axis."""
    return _diagonal(*(2.0 / 3.0 * mass_kg * radius_m**2,) * 3)


def solid_cylinder(mass_kg: float, radius_m: float, length_m: float) -> np.ndarray:
    """Uniform solid cylinder, axis z: ``½ m r²`` axial, ``m(3r² + L²)/12`` transverse."""
    return _axisymmetric(0.5 * mass_kg * radius_m**2, mass_kg * (3.0 * radius_m**2 + length_m**2) / 12.0)


def tube(mass_kg: float, radius_m: float, inner_radius_m: float, length_m: float) -> np.ndarray:
    """Thick-walled uniform tube, axis z: ``½ m (r² + rᵢ²)`` axial, ``m(3(r² + rᵢ²) + L²)/12`` transverse."""
    squares = radius_m**2 + inner_radius_m**2
    return _axisymmetric(0.5 * mass_kg * squares, mass_kg * (3.0 * squares + length_m**2) / 12.0)


def box(mass_kg: float, length_m: float, width_m: float, height_m: float) -> np.ndarray:
    """Uniform rectangular block (length x, width y, height z): ``m(b² + c²)/12`` about each axis."""
    a2, b2, c2 = length_m**2, width_m**2, height_m**2
    return _diagonal(mass_kg * (b2 + c2) / 12.0, mass_kg * (a2 + c2) / 12.0, mass_kg * (a2 + b2) / 12.0)


def slender_rod(mass_kg: float, length_m: float) -> np.ndarray:
    """Uniform slender rod along z: ``m L²/12`` transverse, zero about its own axis."""
    return _axisymmetric(0.0, mass_kg * length_m**2 / 12.0)


def thin_plate(mass_kg: float, length_m: float, width_m: float) -> np.ndarray:
    """Thin uniform rectangular plate (length x, width y, normal z): ``m b²/12``, ``m a²/12``, ``m(a² + b²)/12``."""
    a2, b2 = length_m**2, width_m**2
    return _diagonal(mass_kg * b2 / 12.0, mass_kg * a2 / 12.0, mass_kg * (a2 + b2) / 12.0)


def thin_disk(mass_kg: float, radius_m: float) -> np.ndarray:
    """Thin uniform disk, normal z: ``½ m r²`` axial, ``¼ m r²`` about any diameter."""
    return _axisymmetric(0.5 * mass_kg * radius_m**2, 0.25 * mass_kg * radius_m**2)


def solid_cone(mass_kg: float, radius_m: float, height_m: float) -> np.ndarray:
    """Uniform solid right circular cone, axis z, about its centre of mass (¼ h above the base).

    ``3/10 m r²`` axial; ``3/20 m r² + 3/80 m h²`` transverse.
    """
    return _axisymmetric(0.3 * mass_kg * radius_m**2, mass_kg * (3.0 * radius_m**2 / 20.0 + 3.0 * height_m**2 / 80.0))


# -- transformations -------------------------------------------------------------
def parallel_axis(inertia_cm_kg_m2: np.ndarray, mass_kg: float, offset_m: np.ndarray) -> np.ndarray:
    """Inertia about a point P: ``I_P = I_G + m (|d|² 1 − d dᵀ)``, ``d`` = centre of mass G minus P (m).

    A negative ``mass_kg`` (a hole) subtracts, as a hole's own tensor does.
    """
    d = np.asarray(offset_m, dtype=float)
    return np.asarray(inertia_cm_kg_m2, dtype=float) + mass_kg * (float(d @ d) * np.eye(3) - np.outer(d, d))


def centroidal_from_point(inertia_point_kg_m2: np.ndarray, mass_kg: float, offset_m: np.ndarray) -> np.ndarray:
    """The parallel-axis theorem backwards: ``I_G = I_P − m (|d|² 1 − d dᵀ)``, ``d`` = G minus P (m)."""
    return parallel_axis(inertia_point_kg_m2, -mass_kg, offset_m)


def rotate_tensor(inertia_kg_m2: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    """Components in the reference frame of a tensor given in a rotated frame: ``R I Rᵀ``.

    ``rotation``'s columns are the rotated frame's axes in reference components.
    """
    R = np.asarray(rotation, dtype=float)
    return R @ np.asarray(inertia_kg_m2, dtype=float) @ R.T


def inertia_about_axis(inertia_kg_m2: np.ndarray, axis: np.ndarray) -> float:
    """Moment of inertia about the line through the tensor's point along ``axis`` (kg·m²): ``eᵀ I e``."""
    e = np.asarray(axis, dtype=float)
    e = e / np.linalg.norm(e)
    return float(e @ np.asarray(inertia_kg_m2, dtype=float) @ e)


# -- principal axes --------------------------------------------------------------
Degeneracy = Literal["distinct", "axisymmetric", "spherical"]


@dataclass(frozen=True)
class PrincipalAxes:
    """Principal moments (ascending, kg·m²) and axes (rows: unit vectors in the tensor's frame, right-handed).

    ``degeneracy`` says how many moments coincide: ``"distinct"``, ``"axisymmetric"``
    (two equal; ``repeated`` names which pair, as indices into ``moments_kg_m2``) or
    ``"spherical"`` (all three; every axis is principal). In a repeated subspace the
    axes chosen are the ones nearest the frame's own axes, so they do not jump
    as the tensor is recomputed.
    """

    moments_kg_m2: np.ndarray
    axes: np.ndarray
    degeneracy: Degeneracy
    repeated: tuple[int, ...] = ()

    def describe(self) -> str:
        if self.degeneracy == "spherical":
            return "all three principal moments are equal: every axis through the point is principal"
        if self.degeneracy == "axisymmetric":
            i, j = self.repeated
            return f"principal moments {i + 1} and {j + 1} are equal: every axis in their plane is principal"
        return "three distinct principal moments: the principal axes are unique"


def _nearest_frame_basis(subspace: np.ndarray) -> np.ndarray:
    """An orthonormal basis (rows) of the span of ``subspace``'s rows, as close as possible to the frame axes.

    Projects x, y, z onto the subspace and orthonormalises the largest projections in order.
    """
    projections = subspace.T @ subspace  # row k: frame axis k projected onto the subspace
    order = np.argsort(-np.linalg.norm(projections, axis=1), kind="stable")
    basis: list[np.ndarray] = []
    for index in order:
        v = projections[index].copy()
        for b in basis:
            v -= (v @ b) * b
        norm = np.linalg.norm(v)
        if norm > 1e-8:
            basis.append(v / norm)
        if len(basis) == subspace.shape[0]:
            break
    # Keep the frame-axis order (x before y before z) so the result is stable.
    return np.array(sorted(basis, key=lambda b: int(np.argmax(np.abs(b)))))


def principal_axes(inertia_kg_m2: np.ndarray) -> PrincipalAxes:
    """Principal moments and axes of a symmetric tensor (see :class:`PrincipalAxes`)."""
    tensor = np.asarray(inertia_kg_m2, dtype=float)
    moments, vectors = np.linalg.eigh(0.5 * (tensor + tensor.T))
    axes = vectors.T.copy()
    scale = max(float(np.max(np.abs(moments))), 1e-300)
    same01 = moments[1] - moments[0] <= REPEATED_MOMENT_TOLERANCE * scale
    same12 = moments[2] - moments[1] <= REPEATED_MOMENT_TOLERANCE * scale
    if same01 and same12:
        degeneracy: Degeneracy = "spherical"
        repeated: tuple[int, ...] = (0, 1, 2)
        mean = float(np.mean(moments))
        moments = np.full(3, mean)
        axes = np.eye(3)
    elif same01 or same12:
        degeneracy = "axisymmetric"
        repeated = (0, 1) if same01 else (1, 2)
        pair = list(repeated)
        mean = float(np.mean(moments[pair]))
        moments[pair] = mean
        axes[pair] = _nearest_frame_basis(axes[pair])
    else:
        degeneracy = "distinct"
        repeated = ()
        # Each axis's sign: its largest component positive (a stable, readable choice).
        for row in axes:
            if row[int(np.argmax(np.abs(row)))] < 0.0:
                row *= -1.0
    if np.linalg.det(axes) < 0.0:
        axes[2] *= -1.0
    return PrincipalAxes(moments_kg_m2=moments, axes=axes, degeneracy=degeneracy, repeated=repeated)


def inertia_ellipsoid_semi_axes_m(principal_moments_kg_m2: np.ndarray, *, size_m: float) -> np.ndarray:
    """Semi-axes of the inertia ellipsoid ``ρᵀ I ρ = const``, scaled so the longest is ``size_m``.

    Each semi-axis is proportional to ``1/√I`` along its principal axis: the
    ellipsoid is longest along the axis of least inertia.
    """
    moments = np.asarray(principal_moments_kg_m2, dtype=float)
    inverse_roots = 1.0 / np.sqrt(moments)
    return size_m * inverse_roots / float(np.max(inverse_roots))


# -- checks ----------------------------------------------------------------------
def check_principal_inertia(inertia_kg_m2: tuple[float, float, float], *, about: str = "the centre of mass") -> None:
    """Raise ValueError unless the three principal moments can belong to a real body.

    Each must be a finite positive number and no one may exceed the sum of the
    other two (a flat plate is the limit ``I3 = I1 + I2``).
    """
    names = ("I1", "I2", "I3")
    for name, value in zip(names, inertia_kg_m2):
        if not math.isfinite(value) or value <= 0.0:
            raise ValueError(
                f"{name} must be a finite positive moment of inertia about {about}, in kg·m² (got {value!r})"
            )
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        slack = inertia_kg_m2[j] + inertia_kg_m2[k] - inertia_kg_m2[i]
        if slack < -1e-12 * max(inertia_kg_m2):
            raise ValueError(
                f"inertia about {about} violates the triangle inequality: {names[i]} = {inertia_kg_m2[i]:g} kg·m² "
                f"exceeds {names[j]} + {names[k]} = {inertia_kg_m2[j] + inertia_kg_m2[k]:g} "
                "kg·m²; no real body has these moments"
            )


def check_inertia_tensor(
    inertia_kg_m2: np.ndarray, *, about: str = "the centre of mass", hint: str = ""
) -> PrincipalAxes:
    """Refuse (ValueError, with the reason) a tensor no real body can have; return its principal axes.

    It must be finite and symmetric, positive definite, and its principal
    moments must satisfy the triangle inequality (``I₁ ≤ I₂ + I₃`` and
    cyclically; a flat plate is the limit). ``hint`` is added to the
    positive-definiteness message (say, what a hole may have done).
    """
    tensor = np.asarray(inertia_kg_m2, dtype=float)
    if tensor.shape != (3, 3) or not np.all(np.isfinite(tensor)):
        raise ValueError(f"the inertia tensor about {about} must be a 3×3 array of finite numbers (kg·m²)")
    scale = max(float(np.max(np.abs(tensor))), 1e-300)
    if np.max(np.abs(tensor - tensor.T)) > 1e-12 * scale:
        raise ValueError(f"the inertia tensor about {about} is not symmetric")
    principal = principal_axes(tensor)
    smallest = float(principal.moments_kg_m2[0])
    if smallest <= 1e-12 * scale:
        raise ValueError(
            f"the inertia tensor about {about} is not positive definite: its "
            f"smallest principal moment is {smallest:.6g} kg·m² (a body with mass "
            f"has positive inertia about every axis{'; ' + hint if hint else ''})"
        )
    moments = cast("tuple[float, float, float]", tuple(float(m) for m in principal.moments_kg_m2))
    check_principal_inertia(moments, about=about)
    return principal


def centre_of_mass_m(masses_kg: np.ndarray, positions_m: np.ndarray) -> np.ndarray:
    """Mass-weighted mean position (m) of point masses or parts (holes carry negative mass)."""
    masses = np.asarray(masses_kg, dtype=float)
    total = float(np.sum(masses))
    if not total > 0.0 or not math.isfinite(total):
        raise ValueError(
            f"the total mass must be positive (got {total:.6g} kg): the holes remove more mass than the body has"
        )
    return np.asarray(positions_m, dtype=float).T @ masses / total
