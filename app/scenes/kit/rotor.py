"""A spinning rotor and its gimbal rings (display units, local frames), as the gyroscopes and the unbalanced rotor
draw them.

The rotor spins about its frame's local +y; its spin is drawn slowed to at most
:data:`DRAWN_SPIN_RAD_S`, and the drawn angle depends on the scene's time alone.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.math.rotations import quaternion_from_axis_angle

#: The rotor's spin is drawn at most this fast (rad/s): thousands of rad/s would only flicker.
DRAWN_SPIN_RAD_S = 6.0


def ring_mesh(
    radius: float, tube: float, *, normal: str, segments: int = 64, sides: int = 10
) -> tuple[np.ndarray, np.ndarray]:
    """A torus of centre-line ``radius`` and tube radius ``tube`` (display units) about the local ``normal`` axis."""
    u = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    v = np.linspace(0.0, 2.0 * math.pi, sides, endpoint=False)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    r = radius + tube * np.cos(vv)
    a, b, n = r * np.cos(uu), r * np.sin(uu), tube * np.sin(vv)
    # (a, b) span the ring's plane, n is along its normal; order them so the normal is the named axis.
    if normal == "x":
        x, y, z = n, a, b
    elif normal == "y":
        x, y, z = a, n, b
    elif normal == "z":
        x, y, z = a, b, n
    else:
        raise ValueError(f"normal must be 'x', 'y' or 'z' (got {normal!r})")
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    faces = []
    for i in range(segments):
        i_next = (i + 1) % segments
        for j in range(sides):
            j_next = (j + 1) % sides
            p00, p01 = i * sides + j, i * sides + j_next
            p10, p11 = i_next * sides + j, i_next * sides + j_next
            faces.append((p00, p10, p11))
            faces.append((p00, p11, p01))
    return vertices, np.asarray(faces, dtype=np.uint32)


#: Turns the local +z axis (a viser cylinder's axis) onto +y.
Z_TO_Y = quaternion_from_axis_angle(np.array([1.0, 0.0, 0.0]), -0.5 * math.pi)


def add_rotor(scene, name: str, *, radius: float, thickness: float, axle_length: float, color=(70, 120, 190)):
    """A rotor spinning about its frame's local +y: returns the frame handle (set its ``wxyz`` to spin it).

    Disc, axle and a light stripe across one face so the spin is visible.
    """
    frame = scene.add_frame(name, show_axes=False)
    scene.add_cylinder(f"{name}/disc", radius=radius, height=thickness, color=color, wxyz=Z_TO_Y, radial_segments=48)
    scene.add_cylinder(f"{name}/axle", radius=0.025, height=axle_length, color=(90, 90, 90), wxyz=Z_TO_Y)
    scene.add_box(
        f"{name}/stripe",
        color=(245, 245, 245),
        dimensions=(0.9 * radius, 0.01, 0.06),
        position=(0.45 * radius, 0.5 * thickness + 0.004, 0.0),
    )
    return frame


def spin_quaternion(angle_rad: float) -> np.ndarray:
    """``wxyz`` of a turn ``angle_rad`` about local +y."""
    return np.array([math.cos(0.5 * angle_rad), 0.0, math.sin(0.5 * angle_rad), 0.0])


def drawn_spin_rate(spin_rad_s: float) -> float:
    """The spin rate the scene draws (rad/s): the true one, capped at ``DRAWN_SPIN_RAD_S``."""
    return math.copysign(min(abs(spin_rad_s), DRAWN_SPIN_RAD_S), spin_rad_s)


def drawn_spin_angle(spin_rad_s: float, t_s: float) -> float:
    """The rotor's drawn spin angle (rad, in [0, 2π)) after ``t_s`` s of wall-clock time: :func:`drawn_spin_rate`
    × t, so the picture of an instant depends on its time alone."""
    return (drawn_spin_rate(spin_rad_s) * t_s) % (2.0 * math.pi)
