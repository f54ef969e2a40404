"""Frames, velocities and constraints of a :class:`~.parts.MultibodySystem`, built joint by joint.

Every quantity of a frame is kept in that frame's own components, where a body's
inertia is constant and the expressions stay short: its angular velocity ω
(rad/s), its origin's velocity (m/s), the unit vector "up" (N's +z) and its
origin's height above the ground (m). A child's come from its parent's by one
rotation (ω_child = Rᵀ(ω_parent + q̇·axis), v_child = Rᵀ(v_parent + ω_parent ×
at)); nothing is differentiated in time, so no expression grows beyond one
joint's rotation at a step. Velocities are linear in the speeds u = q̇.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy

from app.physics.mechanics.multibody.parts import (
    GROUND,
    MultibodySystem,
    Revolute,
    RollingContact,
    RollingWheel,
    column,
)


@dataclass(frozen=True)
class Frame:
    """One frame's kinematics, in its own components: ``angular_velocity`` (rad/s), ``origin_velocity`` (m/s),
    ``up`` (N's unit +z), ``height`` of the origin above the ground (m), and ``rotation_to_parent`` (own components
    → the parent's)."""

    name: str
    parent: str | None
    rotation_to_parent: sympy.Matrix
    angular_velocity: sympy.Matrix
    origin_velocity: sympy.Matrix
    up: sympy.Matrix
    height: sympy.Expr


def cross(a: sympy.Matrix, b: sympy.Matrix) -> sympy.Matrix:
    return sympy.Matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def rotation_about(axis: sympy.Matrix, angle: sympy.Expr) -> sympy.Matrix:
    """The rotation by ``angle`` about the unit ``axis`` (rotated components → fixed), as short as the axis allows."""
    c, s = sympy.cos(angle), sympy.sin(angle)
    unit = [sympy.Integer(1) if v == 1 else sympy.Integer(0) if v == 0 else None for v in axis]
    if unit == [1, 0, 0]:
        return sympy.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if unit == [0, 1, 0]:
        return sympy.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    if unit == [0, 0, 1]:
        return sympy.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    skew = sympy.Matrix([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return sympy.eye(3) * c + skew * s + (axis * axis.T) * (1 - c)


def _ground() -> Frame:
    zero = column(0, 0, 0)
    return Frame(GROUND, None, sympy.eye(3), zero, zero, column(0, 0, 1), sympy.Integer(0))


def _child(parent: Frame, name: str, rotation: sympy.Matrix, rate: sympy.Matrix, at: sympy.Matrix) -> Frame:
    """The frame at ``at`` on ``parent`` turned by ``rotation`` with relative angular velocity ``rate`` (parent's
    components)."""
    back = rotation.T
    return Frame(
        name,
        parent.name,
        rotation,
        back * (parent.angular_velocity + rate),
        back * (parent.origin_velocity + cross(parent.angular_velocity, at)),
        back * parent.up,
        parent.height + (parent.up.T * at)[0],
    )


@dataclass(frozen=True)
class Kinematics:
    """Every frame, and the constraints: configuration ones (expressions of q, zero when met) and the nonholonomic
    velocity ones (linear in u, zero when met; the configuration constraints' rates are not among them)."""

    frames: dict[str, Frame]
    configuration_constraints: tuple[sympy.Expr, ...]
    velocity_constraints: tuple[sympy.Expr, ...]

    def mass_centre_velocity(self, system: MultibodySystem, body: str) -> sympy.Matrix:
        """The body's mass-centre velocity (m/s), its own components."""
        frame = self.frames[body]
        centre = next(b for b in system.bodies if b.name == body).mass_centre
        return frame.origin_velocity + cross(frame.angular_velocity, centre)


def kinematics(system: MultibodySystem) -> Kinematics:
    """The frames of every body (and axle frame), and the rolling constraints."""
    frames = {GROUND: _ground()}
    velocity: list[sympy.Expr] = []
    configuration: list[sympy.Expr] = []
    for joint in system.joints:
        if isinstance(joint, Revolute):
            if joint.parent not in frames:
                raise ValueError(
                    f"{system.id}: {joint.child!r} hangs on {joint.parent!r}, which comes later or not at all"
                )
            parent = frames[joint.parent]
            q = joint.coordinate.symbol
            frames[joint.child] = _child(
                parent, joint.child, rotation_about(joint.axis, q), joint.axis * joint.coordinate.rate, joint.at
            )
        else:
            frames.update(_rolling_wheel(joint))
            # The contact point is the radius straight below the centre in the axle frame (the disk's plane is
            # upright in it); its material velocity, in the heading's horizontal components, is zero.
            axle = frames[joint.axle_frame]
            spin = joint.spin.rate
            contact = axle.origin_velocity + cross(
                axle.angular_velocity + column(0, spin, 0), column(0, 0, -joint.radius)
            )
            heading = rotation_about(column(1, 0, 0), joint.lean.symbol) * contact
            velocity += [heading[0], heading[1]]
    for contact in system.contacts:
        configuration_row, velocity_rows = _contact(frames[contact.wheel], contact)
        configuration.append(configuration_row)
        velocity += velocity_rows
    return Kinematics(frames, tuple(configuration), tuple(velocity))


def _rolling_wheel(joint: RollingWheel) -> dict[str, Frame]:
    """The axle frame (heading, then lean, origin at the wheel's centre) and the wheel's frame (then spin)."""
    x_d, y_d, yaw, yaw_d = joint.x.rate, joint.y.rate, joint.yaw.symbol, joint.yaw.rate
    lean, lean_d = joint.lean.symbol, joint.lean.rate
    to_heading = rotation_about(column(1, 0, 0), lean)
    to_ground = rotation_about(column(0, 0, 1), yaw) * to_heading
    back = to_heading.T
    angular_velocity = back * column(0, 0, yaw_d) + column(lean_d, 0, 0)
    # The centre is the radius above the contact along the axle frame's z: v = (ẋ, ẏ, 0) + ω × (0, 0, r).
    contact_velocity = back * rotation_about(column(0, 0, 1), yaw).T * column(x_d, y_d, 0)
    centre_velocity = contact_velocity + cross(angular_velocity, column(0, 0, joint.radius))
    up = back * column(0, 0, 1)
    axle = Frame(
        joint.axle_frame, GROUND, to_ground, angular_velocity, centre_velocity, up, joint.radius * sympy.cos(lean)
    )
    spin = rotation_about(column(0, 1, 0), joint.spin.symbol)
    wheel = _child(axle, joint.wheel, spin, column(0, joint.spin.rate, 0), column(0, 0, 0))
    return {joint.axle_frame: axle, joint.wheel: wheel}


def _contact(wheel: Frame, contact: RollingContact) -> tuple[sympy.Expr, list[sympy.Expr]]:
    """A carried wheel's contact: its lowest point's height (zero when it touches) and that material point's
    velocity along the floor, forward and sideways (zero when it rolls; its upward part is the height's rate)."""
    a, up, r = contact.axle, wheel.up, contact.radius
    along = (up.T * a)[0]
    # The lowest point of the disk: from the centre, −r along up's part in the disk's plane, normalised.
    length = sympy.sqrt(1 - along**2)
    offset = -r * (up - a * along) / length
    height = wheel.height - r * length
    velocity = wheel.origin_velocity + cross(wheel.angular_velocity, offset)
    # Horizontal unit vectors in the wheel's components: forward along the disk's track, and sideways.
    forward = cross(a, up) / length
    sideways = cross(up, forward)
    return height, [(velocity.T * forward)[0], (velocity.T * sideways)[0]]
