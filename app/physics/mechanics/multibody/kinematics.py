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
    EllipsoidContact,
    MultibodySystem,
    Prismatic,
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
    #: The angular acceleration (rad/s²) and the origin's acceleration (m/s²) with every u̇ = 0: the velocity terms.
    angular_acceleration: sympy.Matrix
    origin_acceleration: sympy.Matrix
    #: ∂ω/∂u and ∂v/∂u (3, n): the partial angular velocities and the origin's partial velocities, column by speed.
    angular_velocity_partials: sympy.Matrix
    origin_velocity_partials: sympy.Matrix


def skew(a: sympy.Matrix) -> sympy.Matrix:
    """[a]×: skew(a) b = a × b."""
    return sympy.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def cross(a: sympy.Matrix, b: sympy.Matrix) -> sympy.Matrix:
    return sympy.Matrix([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def component_rate(expression: sympy.Matrix, q: list[sympy.Symbol], u: list[sympy.Symbol]) -> sympy.Matrix:
    """d/dt of components that are expressions of (q, u), with u̇ = 0 and q̇ = u: Σ ∂e/∂q_k u_k."""
    return sum((expression.diff(qk) * uk for qk, uk in zip(q, u)), sympy.zeros(*expression.shape))


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


def _ground(n: int) -> Frame:
    zero = column(0, 0, 0)
    none = sympy.zeros(3, n)
    return Frame(GROUND, None, sympy.eye(3), zero, zero, column(0, 0, 1), sympy.Integer(0), zero, zero, none, none)


def _child(
    parent: Frame,
    name: str,
    rotation: sympy.Matrix,
    axis: sympy.Matrix,
    speed: sympy.Symbol,
    column_of_speed: int,
    at: sympy.Matrix,
) -> Frame:
    """The frame at ``at`` on ``parent`` turned by ``rotation`` about ``axis`` (parent's components) at the rate
    ``speed`` (the column ``column_of_speed`` of the partials). The partial velocities and the accelerations follow
    the same recursion as the velocities, nothing differentiated: W = Rᵀ(W_p + axis·e), V = Rᵀ(V_p − [at]× W_p),
    α = α_p + ω_p × rate and a = a_p + α_p × at + ω_p × (ω_p × at), with every u̇ = 0."""
    back = rotation.T
    omega = parent.angular_velocity
    rate = axis * speed
    reach = cross(omega, at)
    turning = parent.angular_velocity_partials.copy()
    turning[:, column_of_speed] += axis
    return Frame(
        name,
        parent.name,
        rotation,
        back * (omega + rate),
        back * (parent.origin_velocity + reach),
        back * parent.up,
        parent.height + (parent.up.T * at)[0],
        back * (parent.angular_acceleration + cross(omega, rate)),
        back * (parent.origin_acceleration + cross(parent.angular_acceleration, at) + cross(omega, reach)),
        back * turning,
        back * (parent.origin_velocity_partials - skew(at) * parent.angular_velocity_partials),
    )


def _slid(
    parent: Frame,
    name: str,
    axis: sympy.Matrix,
    slide: sympy.Expr,
    speed: sympy.Symbol,
    column_of_speed: int,
    at: sympy.Matrix,
) -> Frame:
    """The frame at ``at + axis·slide`` on ``parent`` (parent's components), its axes the parent's, sliding at the rate
    ``speed`` (the column ``column_of_speed`` of the partials): v = v_p + ω_p × r + axis·ṡ, a = a_p + α_p × r +
    ω_p × (ω_p × r) + 2 ω_p × axis·ṡ (every u̇ = 0), V = V_p − [r]× W_p + axis·e."""
    omega = parent.angular_velocity
    reach = at + axis * slide
    rate = axis * speed
    sliding = parent.origin_velocity_partials - skew(reach) * parent.angular_velocity_partials
    sliding[:, column_of_speed] += axis
    return Frame(
        name,
        parent.name,
        sympy.eye(3),
        omega,
        parent.origin_velocity + cross(omega, reach) + rate,
        parent.up,
        parent.height + (parent.up.T * reach)[0],
        parent.angular_acceleration,
        parent.origin_acceleration
        + cross(parent.angular_acceleration, reach)
        + cross(omega, cross(omega, reach))
        + 2 * cross(omega, rate),
        parent.angular_velocity_partials,
        sliding,
    )


@dataclass(frozen=True)
class Kinematics:
    """Every frame, and the constraints: configuration ones (expressions of q, zero when met) and the nonholonomic
    velocity ones (linear in u, zero when met; the configuration constraints' rates are not among them)."""

    frames: dict[str, Frame]
    configuration_constraints: tuple[sympy.Expr, ...]
    velocity_constraints: tuple[sympy.Expr, ...]

    def rotation_to_ground(self, name: str) -> sympy.Matrix:
        """R (3, 3): the frame ``name``'s components → the ground's, the product of the rotations up its chain."""
        rotation = sympy.eye(3)
        frame = self.frames[name]
        while frame.parent is not None:
            rotation = frame.rotation_to_parent * rotation
            frame = self.frames[frame.parent]
        return rotation

    def point_velocity_partials(self, body: str, point: sympy.Matrix) -> sympy.Matrix:
        """∂v_P/∂u (3, n) of the body-fixed point at ``point`` (m, the body's components), its own components."""
        frame = self.frames[body]
        return frame.origin_velocity_partials - skew(point) * frame.angular_velocity_partials

    def mass_centre_velocity(self, system: MultibodySystem, body: str) -> sympy.Matrix:
        """The body's mass-centre velocity (m/s), its own components."""
        frame = self.frames[body]
        centre = next(b for b in system.bodies if b.name == body).mass_centre
        return frame.origin_velocity + cross(frame.angular_velocity, centre)

    def mass_centre_partials(self, system: MultibodySystem, body: str) -> sympy.Matrix:
        """∂v_G/∂u (3, n), the body's own components."""
        frame = self.frames[body]
        centre = next(b for b in system.bodies if b.name == body).mass_centre
        return frame.origin_velocity_partials - skew(centre) * frame.angular_velocity_partials

    def mass_centre_acceleration(self, system: MultibodySystem, body: str) -> sympy.Matrix:
        """The body's mass-centre acceleration with every u̇ = 0 (m/s²), its own components."""
        frame = self.frames[body]
        centre = next(b for b in system.bodies if b.name == body).mass_centre
        omega = frame.angular_velocity
        return (
            frame.origin_acceleration + cross(frame.angular_acceleration, centre) + cross(omega, cross(omega, centre))
        )


def kinematics(system: MultibodySystem) -> Kinematics:
    """The frames of every body (and axle frame), and the rolling constraints."""
    u = system.u
    frames = {GROUND: _ground(len(u))}
    velocity: list[sympy.Expr] = []
    configuration: list[sympy.Expr] = []
    for joint in system.joints:
        if isinstance(joint, Revolute | Prismatic) and joint.parent not in frames:
            raise ValueError(f"{system.id}: {joint.child!r} hangs on {joint.parent!r}, which comes later or not at all")
        if isinstance(joint, Prismatic):
            coordinate = joint.coordinate
            frames[joint.child] = _slid(
                frames[joint.parent],
                joint.child,
                joint.axis,
                coordinate.symbol,
                coordinate.rate,
                system.index(coordinate.name),
                joint.at,
            )
        elif isinstance(joint, Revolute):
            parent = frames[joint.parent]
            coordinate = joint.coordinate
            frames[joint.child] = _child(
                parent,
                joint.child,
                rotation_about(joint.axis, coordinate.symbol),
                joint.axis,
                coordinate.rate,
                system.index(coordinate.name),
                joint.at,
            )
        else:
            frames.update(_rolling_wheel(joint, u, system.index(joint.spin.name)))
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
        if isinstance(contact, EllipsoidContact):
            configuration_row, velocity_rows = _ellipsoid_contact(frames[contact.body], contact)
        else:
            configuration_row, velocity_rows = _contact(frames[contact.wheel], contact)
        configuration.append(configuration_row)
        velocity += velocity_rows
    return Kinematics(frames, tuple(configuration), tuple(velocity))


def _rolling_wheel(joint: RollingWheel, u: list[sympy.Symbol], spin_column: int) -> dict[str, Frame]:
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
    # Its components' rates (short expressions of yaw and lean), with the transport term for the centre's.
    own_q, own_u = [c.symbol for c in joint.coordinates], [c.rate for c in joint.coordinates]
    angular_acceleration = component_rate(angular_velocity, own_q, own_u)
    centre_acceleration = component_rate(centre_velocity, own_q, own_u) + cross(angular_velocity, centre_velocity)
    axle = Frame(
        joint.axle_frame,
        GROUND,
        to_ground,
        angular_velocity,
        centre_velocity,
        up,
        joint.radius * sympy.cos(lean),
        angular_acceleration,
        centre_acceleration,
        angular_velocity.jacobian(u),
        centre_velocity.jacobian(u),
    )
    spin = rotation_about(column(0, 1, 0), joint.spin.symbol)
    wheel = _child(axle, joint.wheel, spin, column(0, 1, 0), joint.spin.rate, spin_column, column(0, 0, 0))
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


def _ellipsoid_contact(body: Frame, contact: EllipsoidContact) -> tuple[sympy.Expr, list[sympy.Expr]]:
    """An ellipsoid's contact: with n = up and E = diag(a², b², c²) (body components), the lowest point is
    s = centre − E n / √(nᵀ E n), where the outward normal E⁻¹(s − centre) points along −n; its height is the body's
    origin's plus n·s, and the material point there moves at v_O + ω × s. The two rows are that velocity along
    e_x − n_x n and n × e_x, horizontal and independent while the body's x axis is not vertical."""
    n = body.up
    squares = [axis**2 for axis in contact.semi_axes]
    reach = sympy.sqrt(sum((e * component**2 for e, component in zip(squares, n)), sympy.Integer(0)))
    touching = contact.centre - column(*(e * component for e, component in zip(squares, n))) / reach
    height = body.height + (n.T * contact.centre)[0] - reach
    velocity = body.origin_velocity + cross(body.angular_velocity, touching)
    along_x = column(1, 0, 0) - n * n[0]
    across = cross(n, column(1, 0, 0))
    return height, [(velocity.T * along_x)[0], (velocity.T * across)[0]]
