"""Unit quaternions (``wxyz``) and the rotation matrices they stand for.

``q_world_body`` rotates body components into world components:
``v_world = rotation_matrix(q_world_body) @ v_body``. Every function broadcasts
over leading axes: quaternions have shape ``(..., 4)``, matrices ``(..., 3, 3)``.
"""

from __future__ import annotations

import math

import numpy as np

#: A matrix further than this from orthonormal (max entry of ``RᵀR − I``) is refused.
ORTHONORMAL_TOLERANCE = 1e-6


def quaternion_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product ``a ⊗ b`` of ``wxyz`` quaternions (broadcasts over leading axes).

    For attitudes, ``q_A_C = q_A_B ⊗ q_B_C``: the matrix of the product is the
    product of the matrices.
    """
    a = np.asarray(a, dtype=np.result_type(a, float))  # complex stays complex (complex-step derivatives)
    b = np.asarray(b, dtype=np.result_type(b, float))
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        axis=-1,
    )


def quaternion_conjugate(q: np.ndarray) -> np.ndarray:
    """Conjugate (the inverse rotation for a unit quaternion), ``wxyz``."""
    q = np.asarray(q, dtype=float)
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def rotation_matrix(q: np.ndarray) -> np.ndarray:
    """``R_world_body`` (shape (..., 3, 3)) of a ``wxyz`` quaternion (normalised first)."""
    q = np.asarray(q, dtype=float)
    if q.shape == (4,):  # one attitude (every live frame): plain floats, a tenth of the array path's cost
        norm = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
        norm = norm if norm > 0.0 else math.nan  # a zero quaternion has no rotation: NaN, as the array path gives
        w, x, y, z = (float(c) / norm for c in q)
        return np.array(
            [
                [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
            ]
        )
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=-2,
    )


def rotate_vector(q: np.ndarray, v_body: np.ndarray) -> np.ndarray:
    """World components of the body vector ``v_body`` for attitude ``q`` (broadcasts)."""
    return np.einsum("...ij,...j->...i", rotation_matrix(q), np.asarray(v_body, dtype=float))


def check_rotation_matrix(R: np.ndarray, *, name: str = "R") -> np.ndarray:
    """``R`` as a float array of shape (..., 3, 3); ValueError unless orthonormal with det +1."""
    R = np.asarray(R, dtype=float)
    if R.ndim < 2 or R.shape[-2:] != (3, 3):
        raise ValueError(f"{name} must be a 3×3 rotation matrix (got shape {R.shape})")
    if not np.all(np.isfinite(R)):
        raise ValueError(f"{name} must contain only finite numbers")
    gram_error = np.abs(np.swapaxes(R, -1, -2) @ R - np.eye(3)).max(initial=0.0)
    if gram_error > ORTHONORMAL_TOLERANCE:
        raise ValueError(
            f"{name} is not a rotation matrix: its columns are not orthonormal (RᵀR − I reaches {gram_error:.1e})"
        )
    if np.any(np.linalg.det(R) < 0.0):
        raise ValueError(f"{name} is a reflection (determinant −1), not a rotation")
    return R


def quaternion_from_matrix(R: np.ndarray) -> np.ndarray:
    """Unit ``wxyz`` quaternion with ``w ≥ 0`` of the rotation matrix ``R_world_body`` (..., 3, 3).

    Shepperd's method: of the four ways to read the quaternion off ``R``, use
    the one whose pivot (``1 + trace`` or ``1 + 2 R_kk − trace``) is largest, so
    no division by a small number happens at any attitude, half turns included.
    Raises ValueError if ``R`` is not a rotation matrix.
    """
    R = check_rotation_matrix(R)
    m = {(i, j): R[..., i, j] for i in range(3) for j in range(3)}
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    # Row k is 4 q_k q (k = w, x, y, z); its k-th entry is the pivot 4 q_k².
    candidates = np.stack(
        [
            np.stack([1.0 + trace, m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]], axis=-1),
            np.stack([m[2, 1] - m[1, 2], 1.0 + 2.0 * m[0, 0] - trace, m[0, 1] + m[1, 0], m[0, 2] + m[2, 0]], axis=-1),
            np.stack([m[0, 2] - m[2, 0], m[0, 1] + m[1, 0], 1.0 + 2.0 * m[1, 1] - trace, m[1, 2] + m[2, 1]], axis=-1),
            np.stack([m[1, 0] - m[0, 1], m[0, 2] + m[2, 0], m[1, 2] + m[2, 1], 1.0 + 2.0 * m[2, 2] - trace], axis=-1),
        ],
        axis=-2,
    )
    pivot = np.argmax(np.stack([trace, m[0, 0], m[1, 1], m[2, 2]], axis=-1), axis=-1)
    q = np.take_along_axis(candidates, pivot[..., None, None], axis=-2)[..., 0, :]
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return np.where(q[..., :1] < 0.0, -q, q)
