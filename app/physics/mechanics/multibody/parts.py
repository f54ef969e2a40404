"""A multibody system described by its parts: rigid bodies, the joints between them, wheels that roll.

Frames and units: the ground frame N has +Z up. Every body has its own frame; a
joint says where the child's frame sits on the parent's and how it turns
(vectors in the parent's components, m), so a body's mass centre (m) and central
inertia (kg·m²) are constants in its own components. Angles in rad, masses in
kg, forces in N.

The parts say nothing about how the equations are derived: :mod:`.kinematics`
turns them into frames, velocities and constraints, and :mod:`.kane` into
equations of motion with dependent coordinates and speeds.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import Coordinate

#: The ground's name as a joint's parent.
GROUND = "ground"


def column(x: sympy.Expr | float, y: sympy.Expr | float, z: sympy.Expr | float) -> sympy.Matrix:
    """A 3-vector of components (a (3, 1) matrix)."""
    return sympy.Matrix([x, y, z])


def inertia(
    ixx: sympy.Expr | float,
    iyy: sympy.Expr | float,
    izz: sympy.Expr | float,
    *,
    ixy: sympy.Expr | float = 0,
    iyz: sympy.Expr | float = 0,
    ixz: sympy.Expr | float = 0,
) -> sympy.Matrix:
    """A central inertia tensor (kg·m²) from its moments and products, in the body's components."""
    return sympy.Matrix([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


@dataclass(frozen=True)
class Body:
    """A rigid body: mass (kg), mass centre (m, from its frame's origin, its own components), central inertia."""

    name: str
    mass: sympy.Expr
    inertia: sympy.Matrix
    mass_centre: sympy.Matrix = field(default_factory=lambda: column(0, 0, 0))


@dataclass(frozen=True)
class Revolute:
    """The child's frame turns about ``axis`` (a unit vector, the parent's components) through the point ``at`` (m,
    from the parent frame's origin, the parent's components) by ``coordinate``; the child's origin is that point,
    and its axes are the parent's when the coordinate is zero. ``parent`` is a body, a massless frame another joint
    made, a wheel's axle frame (``"<wheel>.axle"``) or :data:`GROUND`; a ``child`` that names no body is a massless
    frame (two revolutes through one point make a universal joint)."""

    parent: str
    child: str
    coordinate: Coordinate
    axis: sympy.Matrix
    at: sympy.Matrix = field(default_factory=lambda: column(0, 0, 0))


@dataclass(frozen=True)
class Prismatic:
    """The child's frame slides along ``axis`` (a unit vector, the parent's components) by ``coordinate`` (m) from
    the point ``at`` (m, the parent's components); its axes stay the parent's. Three of them on the ground carry a
    body that moves anywhere (the rattleback's mass centre)."""

    parent: str
    child: str
    coordinate: Coordinate
    axis: sympy.Matrix
    at: sympy.Matrix = field(default_factory=lambda: column(0, 0, 0))


@dataclass(frozen=True)
class RollingWheel:
    """A wheel (the body ``wheel``, a thin disk of radius ``radius``, m) rolling on the ground plane z = 0 without
    slipping, its axle along its frame's y axis.

    Coordinates (in this order): the contact point's ``x`` and ``y`` (m), the heading ``yaw`` about N's z axis, the
    ``lean`` about the heading's x axis (both rad), and the wheel's ``spin`` about its axle. The joint also makes the
    frame ``"<wheel>.axle"``: origin at the wheel's centre, turned by yaw and lean but not spin, on which other
    bodies (a bicycle's frame) hang. No slip at the contact gives two velocity constraints.
    """

    wheel: str
    radius: sympy.Expr
    x: Coordinate
    y: Coordinate
    yaw: Coordinate
    lean: Coordinate
    spin: Coordinate

    @property
    def axle_frame(self) -> str:
        return f"{self.wheel}.axle"

    @property
    def coordinates(self) -> tuple[Coordinate, ...]:
        return (self.x, self.y, self.yaw, self.lean, self.spin)


@dataclass(frozen=True)
class RollingContact:
    """A wheel that some other joint carries (a bicycle's front wheel) touches the ground plane and rolls on it
    without slipping: its lowest point stays at z = 0 (a configuration constraint) and the material point there is
    at rest (three velocity constraints, one of them the configuration constraint's rate). ``axle`` is the axle's
    unit vector in the wheel's components; the disk's centre is its frame's origin."""

    wheel: str
    radius: sympy.Expr
    axle: sympy.Matrix = field(default_factory=lambda: column(0, 1, 0))


@dataclass(frozen=True)
class EllipsoidContact:
    """A body whose surface is the ellipsoid with semi-axes ``semi_axes`` (a, b, c along its frame's x, y, z, m) and
    centre ``centre`` (m, from the frame's origin, its own components) touches the ground plane and rolls on it
    without slipping: its lowest point's height is zero (a configuration constraint) and the material point there is
    at rest (two velocity constraints along the floor, the third being the height's rate). The touching point moves
    over the surface as the body tilts: it is where the outward normal points straight down (a rattleback)."""

    body: str
    semi_axes: sympy.Matrix
    centre: sympy.Matrix = field(default_factory=lambda: column(0, 0, 0))


@dataclass(frozen=True)
class Force:
    """A force (N) on ``body`` applied at ``point`` (m, from the body frame's origin, its own components): ``vector``
    in the ground's components (a fixed direction, as a weight or a pull on a rope over a distant pulley) or, with
    ``follower``, in the body's own (it turns with the body, as a thrust)."""

    body: str
    vector: sympy.Matrix
    point: sympy.Matrix = field(default_factory=lambda: column(0, 0, 0))
    follower: bool = False


@dataclass(frozen=True)
class Torque:
    """A couple (N·m) on ``body``: ``vector`` in the ground's components or, with ``follower``, in the body's own."""

    body: str
    vector: sympy.Matrix
    follower: bool = False


@dataclass(frozen=True)
class JointSpring:
    """A spring and a damper on one coordinate: the generalized force −stiffness·(q − rest) − damping·q̇ (N for a
    sliding coordinate, N·m for a turning one). The spring stores ½·stiffness·(q − rest)² of potential energy (J); the
    damper takes energy out. Stiffness in N/m or N·m/rad, damping in N·s/m or N·m·s/rad."""

    coordinate: str
    stiffness: sympy.Expr = sympy.Integer(0)
    rest: sympy.Expr = sympy.Integer(0)
    damping: sympy.Expr = sympy.Integer(0)


#: What may act on a system besides gravity and its contacts.
Load = Force | Torque | JointSpring


@dataclass(frozen=True)
class ReferenceMotion:
    """A motion to linearise about (an equilibrium or a steady motion): what it is, in words (``about``), the linear
    model's states (coordinate names, then speed names: the rates of those coordinates) and the reference state for
    given parameters (q, u: arrays over every coordinate; the dependent entries are solved from the constraints)."""

    about: str
    coordinates: tuple[str, ...]
    speeds: tuple[str, ...]
    state: Callable[[Mapping[str, float]], tuple[np.ndarray, np.ndarray]]
    #: The parameter a page plots the eigenvalues against, and over what range (its unit): a bicycle's speed.
    sweep: tuple[str, float, float] | None = None
    #: Names of the stability changes along the sweep: (what it becomes, whether an oscillating pair crosses, name),
    #: as a bicycle's ("stable", True, "weave speed") and ("unstable", False, "capsize speed").
    crossing_names: tuple[tuple[str, bool, str], ...] = ()

    @property
    def state_names(self) -> list[str]:
        return [*self.coordinates, *(f"{name}_d" for name in self.speeds)]


@dataclass(frozen=True)
class MultibodySystem:
    """Bodies, joints and contacts; which coordinates the configuration constraints fix and which speeds the velocity
    constraints fix (dependent ones); gravity; parameters.

    The generalized speeds are the coordinates' rates (u = q̇), independent and dependent together.
    """

    id: str
    title: str
    parameters: ParameterSet
    #: Parameter name → its symbol in the expressions.
    symbols: Mapping[str, sympy.Symbol]
    bodies: tuple[Body, ...]
    joints: tuple[Revolute | Prismatic | RollingWheel, ...]
    contacts: tuple[RollingContact | EllipsoidContact, ...] = ()
    #: Applied forces and couples, and springs and dampers on coordinates.
    loads: tuple[Load, ...] = ()
    #: Gravitational acceleration (m/s²) along −z, as an expression of the parameters.
    gravity: sympy.Expr = sympy.Integer(0)
    #: Coordinates the configuration constraints fix (one per configuration constraint), by name.
    dependent_coordinates: tuple[str, ...] = ()
    #: Rates the velocity constraints fix (one per velocity constraint), by coordinate name.
    dependent_speeds: tuple[str, ...] = ()
    #: The chapter that studies it, and a line the page shows about what the model assumes.
    chapter: int = 9
    assumptions: str = ""
    #: The motion its linear model is about (None: it has none).
    reference: ReferenceMotion | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        names = [c.name for c in self.coordinates]
        if len(set(names)) != len(names):
            raise ValueError(f"{self.id}: coordinate names repeat: {names}")
        for name in (*self.dependent_coordinates, *self.dependent_speeds):
            if name not in names:
                raise ValueError(f"{self.id}: {name!r} is no coordinate")
        if set(self.symbols) != {p.name for p in self.parameters.parameters}:
            raise ValueError(f"{self.id}: symbols and parameters must name the same things")
        bodies = {b.name for b in self.bodies}
        moved = [joint.wheel if isinstance(joint, RollingWheel) else joint.child for joint in self.joints]
        for body in bodies - set(moved):
            raise ValueError(f"{self.id}: no joint moves the body {body!r}")
        for joint in self.joints:
            if isinstance(joint, RollingWheel) and joint.wheel not in bodies:
                raise ValueError(f"{self.id}: the rolling wheel {joint.wheel!r} is no body")
        for contact in self.contacts:
            touching = contact.body if isinstance(contact, EllipsoidContact) else contact.wheel
            if touching not in bodies:
                raise ValueError(f"{self.id}: the contact's body {touching!r} is no body")
        for load in self.loads:
            if isinstance(load, JointSpring):
                if load.coordinate not in names:
                    raise ValueError(f"{self.id}: the spring's coordinate {load.coordinate!r} is no coordinate")
            elif load.body not in bodies:
                raise ValueError(f"{self.id}: the load's body {load.body!r} is no body")

    @property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """Every coordinate, in the joints' order."""
        found: list[Coordinate] = []
        for joint in self.joints:
            found += joint.coordinates if isinstance(joint, RollingWheel) else [joint.coordinate]
        return tuple(found)

    @property
    def q(self) -> list[sympy.Symbol]:
        return [c.symbol for c in self.coordinates]

    @property
    def u(self) -> list[sympy.Symbol]:
        """The speeds: u_i = q̇_i (named like the rates, ``theta_d``)."""
        return [c.rate for c in self.coordinates]

    @property
    def ud(self) -> list[sympy.Symbol]:
        return [c.acceleration for c in self.coordinates]

    @property
    def parameter_symbols(self) -> list[sympy.Symbol]:
        """In the order of ``parameters`` (the order of the numeric parameter array)."""
        return [self.symbols[p.name] for p in self.parameters.parameters]

    def parameter_array(self, params: Mapping[str, float]) -> list[float]:
        return [float(params[p.name]) for p in self.parameters.parameters]

    def fingerprint(self) -> str:
        """A hash of everything that shapes the equations (not the parameter values)."""
        parts = [self.id, repr(self.bodies), repr(self.joints), repr(self.contacts), repr(self.gravity)]
        parts += [repr(self.loads)] if self.loads else []
        parts += [repr(self.dependent_coordinates), repr(self.dependent_speeds), repr(self.parameter_symbols)]
        return hashlib.sha256("\n".join(parts).encode()).hexdigest()[:16]

    def member(self, params: Mapping[str, Any]) -> MultibodySystem:
        """The system itself (a :class:`MultibodyFamily` picks one of its members by its parameters)."""
        return self

    def index(self, name: str) -> int:
        """The position of a coordinate (and its speed) in q and u."""
        return [c.name for c in self.coordinates].index(name)


@dataclass(frozen=True)
class MultibodyFamily:
    """Systems built of parts whose structure parameters choose the member (an N-link chain's N and whether it is
    planar): one id and one parameter set, the structure's and every member's physical ones."""

    id: str
    title: str
    chapter: int
    assumptions: str
    parameters: ParameterSet
    #: The member for validated parameters (kept: the same structure gives the same object).
    build: Callable[[Mapping[str, Any]], MultibodySystem] = field(compare=False)

    def member(self, params: Mapping[str, Any]) -> MultibodySystem:
        return self.build(params)
