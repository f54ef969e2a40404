"""A mechanical system described as data, once, for every formulation to derive from.

Frames and units: one inertial frame N with +Z up; every position, force and
direction is a 3-vector of N components (a ``sympy.Matrix`` of shape (3, 1)) in
metres, newtons; a rigid body's orientation is a sequence of simple rotations
(body components → N components), its inertia a 3×3 matrix about its mass
centre in body components (kg·m²). Expressions use the coordinate symbols
``q``, the time ``t`` (a rheonomic system names ``t`` explicitly) and the
parameter symbols; never rates: velocities are derived.

Speeds: by default the generalized speeds are the coordinates' rates (u = q̇).
A nonholonomic system (a rolling disk) instead names fewer speeds and gives
every coordinate rate as an expression of (q, u, t): the velocity constraints
are then built in, and ``speeds_from_rates`` recovers u from a state's q̇.

Potential energy comes from a uniform gravity field, linear springs and an
optional extra term (a typed Lagrangian's V). Newton–Euler needs forces, not a
potential, so it is offered only for systems without the extra term and with
their constraint reactions declared (:class:`Reaction`).
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TypeAlias

import sympy

from app.physics.core.parameters import Parameter, ParameterSet

#: Time, s.
TIME = sympy.Symbol("t", real=True)

Vector: TypeAlias = sympy.Matrix  # (3, 1), N components


def vector(x: sympy.Expr | float, y: sympy.Expr | float, z: sympy.Expr | float) -> sympy.Matrix:
    """A column of N components."""
    return sympy.Matrix([x, y, z])


def dotted(latex: str, order: int) -> str:
    """``\\theta_1`` with ``order`` dots over the letter, not the subscript: ``\\dot{\\theta}_1``."""
    base, underscore, subscript = latex.partition("_")
    accent = "\\dot" if order == 1 else "\\ddot"
    return f"{accent}{{{base}}}" + (f"_{subscript}" if underscore else "")


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate: ``name`` is the API's (``theta1``), ``latex`` the page's (``\\theta_1``)."""

    name: str
    latex: str
    unit: str = "rad"

    @property
    def symbol(self) -> sympy.Symbol:
        return sympy.Symbol(self.name, real=True)

    @property
    def rate(self) -> sympy.Symbol:
        """q̇ as a plain symbol (``theta1_d``)."""
        return sympy.Symbol(f"{self.name}_d", real=True)

    @property
    def acceleration(self) -> sympy.Symbol:
        """q̈ (``theta1_d_d``: the rate's own derivative, so that u̇ = q̈ when u = q̇)."""
        return sympy.Symbol(f"{self.name}_d_d", real=True)

    @property
    def rate_unit(self) -> str:
        return f"{self.unit}/s"


@dataclass(frozen=True)
class Speed:
    """A generalized speed (quasi-velocity) u, with its time derivative u̇ as a plain symbol."""

    name: str
    latex: str
    unit: str = "rad/s"

    @property
    def symbol(self) -> sympy.Symbol:
        return sympy.Symbol(self.name, real=True)

    @property
    def derivative(self) -> sympy.Symbol:
        return sympy.Symbol(f"{self.name}_d", real=True)


@dataclass(frozen=True)
class Particle:
    """A point mass (kg) at ``position`` (m, N components)."""

    name: str
    mass: sympy.Expr
    position: Vector


@dataclass(frozen=True)
class RigidBody:
    """A rigid body: mass (kg), mass-centre position (m, N), orientation and central inertia.

    ``rotations`` are simple rotations applied in order, each ``(axis, angle)``
    with axis ``"x"``, ``"y"`` or ``"z"`` of the frame reached so far:
    ``R_NB = R_1(a_1) R_2(a_2) …``. ``inertia`` is about the mass centre in body
    components (kg·m²).
    """

    name: str
    mass: sympy.Expr
    mass_centre: Vector
    rotations: tuple[tuple[str, sympy.Expr], ...]
    inertia: sympy.Matrix


@dataclass(frozen=True)
class Spring:
    """A linear spring (N/m) of free length (m) between two points (N vector expressions, m).

    With ``axis`` (a constant unit N vector) the spring stays along that line and
    its stretch is signed: axis·(b − a) − free length; otherwise it is the
    distance between the ends minus the free length.
    """

    stiffness: sympy.Expr
    free_length: sympy.Expr
    end_a: Vector
    end_b: Vector
    axis: Vector | None = None
    #: The particle or body each end is fixed to (None: the ground), for Newton–Euler's free-body diagrams.
    on_a: str | None = None
    on_b: str | None = None


@dataclass(frozen=True)
class AppliedForce:
    """A non-conservative force (N, N components) acting at ``point`` (m, N components)."""

    name: str
    point: Vector
    force: Vector
    #: The particle or body it acts on (for Newton–Euler's free-body diagrams).
    on: str = ""


@dataclass(frozen=True)
class Reaction:
    """A constraint reaction for Newton–Euler: unknown magnitudes along given directions.

    It acts on ``on`` (a particle or body name) at ``point`` and, reversed, on
    ``against`` (another one, or ``None`` for the ground). ``forces`` and
    ``moments`` are N-component direction vectors; each gets one unknown
    magnitude (N or N·m), named ``name`` with an index.
    """

    name: str
    on: str
    point: Vector
    forces: tuple[Vector, ...] = ()
    moments: tuple[Vector, ...] = ()
    against: str | None = None


@dataclass(frozen=True)
class Singularity:
    """Where the coordinates fail though the body does not (gimbal lock): ``where`` (an expression of q) is zero there.

    ``label`` names ``where`` as a page prints it (``sin θ``); ``text`` says what happens there and what to do.
    """

    where: sympy.Expr
    label: str
    text: str


@dataclass(frozen=True)
class SystemDescription:
    """Everything a formulation needs, and nothing about how to derive it."""

    id: str
    title: str
    chapter: int
    coordinates: tuple[Coordinate, ...]
    parameters: ParameterSet
    #: Parameter name → its symbol in the expressions.
    symbols: Mapping[str, sympy.Symbol]
    particles: tuple[Particle, ...] = ()
    bodies: tuple[RigidBody, ...] = ()
    #: Gravitational acceleration as an N vector (m/s²), or None.
    gravity: Vector | None = None
    springs: tuple[Spring, ...] = ()
    forces: tuple[AppliedForce, ...] = ()
    #: A potential energy (J) beyond gravity and springs; systems with one have no Newton–Euler form.
    extra_potential: sympy.Expr = sympy.Integer(0)
    #: Kinetic energy (J) given directly instead of particles and bodies (a typed Lagrangian).
    kinetic_energy: sympy.Expr | None = None
    #: Nonholonomic: the independent speeds, each coordinate rate as an expression of (q, u, t), and u from (q, q̇).
    speeds: tuple[Speed, ...] | None = None
    coordinate_rates: tuple[sympy.Expr, ...] | None = None
    speeds_from_rates: tuple[sympy.Expr, ...] | None = None
    reactions: tuple[Reaction, ...] = ()
    #: Names of ignorable (cyclic) coordinates that Routh's method removes.
    ignorable: tuple[str, ...] = ()
    #: A line the lesson shows about what the model assumes.
    assumptions: str = ""
    #: What each formulation cannot do here, by formulation id (shown instead of equations).
    unavailable: Mapping[str, str] = field(default_factory=dict)
    #: Where the coordinates are singular (the equations divide by zero there whatever the formulation).
    singularities: tuple[Singularity, ...] = ()
    #: Where random test states are drawn: coordinate name → (low, high) in its unit; others span ±π rad or ±1 m.
    #: Rates are drawn in ±3 per second. Keep singular configurations (gimbal lock) out.
    state_ranges: Mapping[str, tuple[float, float]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        names = [c.name for c in self.coordinates]
        if len(set(names)) != len(names):
            raise ValueError(f"{self.id}: coordinate names repeat: {names}")
        if (self.speeds is None) != (self.coordinate_rates is None) or (self.speeds is None) != (
            self.speeds_from_rates is None
        ):
            raise ValueError(f"{self.id}: give speeds, coordinate_rates and speeds_from_rates together, or none")
        if self.coordinate_rates is not None and len(self.coordinate_rates) != len(self.coordinates):
            raise ValueError(f"{self.id}: one rate expression per coordinate")
        unknown = set(self.ignorable) - set(names)
        if unknown:
            raise ValueError(f"{self.id}: ignorable names no coordinate: {sorted(unknown)}")
        if set(self.symbols) != {p.name for p in self.parameters.parameters}:
            raise ValueError(f"{self.id}: symbols and parameters must name the same things")

    # --- symbols -----------------------------------------------------------------------------------------------
    @property
    def q(self) -> list[sympy.Symbol]:
        return [c.symbol for c in self.coordinates]

    @property
    def qd(self) -> list[sympy.Symbol]:
        return [c.rate for c in self.coordinates]

    @property
    def qdd(self) -> list[sympy.Symbol]:
        return [c.acceleration for c in self.coordinates]

    @property
    def holonomic(self) -> bool:
        return self.speeds is None

    @property
    def speed_list(self) -> tuple[Speed, ...]:
        """The generalized speeds: the declared ones, or u_i = q̇_i (named like the rates)."""
        if self.speeds is not None:
            return self.speeds
        return tuple(Speed(c.rate.name, dotted(c.latex, 1), c.rate_unit) for c in self.coordinates)

    @property
    def u(self) -> list[sympy.Symbol]:
        return [s.symbol for s in self.speed_list]

    @property
    def ud(self) -> list[sympy.Symbol]:
        return [s.derivative for s in self.speed_list]

    @property
    def rates_in_speeds(self) -> list[sympy.Expr]:
        """q̇ as expressions of (q, u, t)."""
        return list(self.coordinate_rates) if self.coordinate_rates is not None else list(self.u)

    @property
    def parameter_symbols(self) -> list[sympy.Symbol]:
        """In the order of ``parameters`` (the order of the numeric parameter array)."""
        return [self.symbols[p.name] for p in self.parameters.parameters]

    def parameter_array(self, params: Mapping[str, float]) -> list[float]:
        return [float(params[p.name]) for p in self.parameters.parameters]

    def body_names(self) -> list[str]:
        return [p.name for p in self.particles] + [b.name for b in self.bodies]

    @property
    def latex_names(self) -> dict[sympy.Symbol, str]:
        """How symbols print on the page: θ₁, θ̇₁, θ̈₁, the speeds and their rates."""
        names: dict[sympy.Symbol, str] = {}
        for c in self.coordinates:
            names[c.symbol] = c.latex
            names[c.rate] = dotted(c.latex, 1)
            names[c.acceleration] = dotted(c.latex, 2)
        for s in self.speed_list:
            names.setdefault(s.symbol, s.latex)
            names.setdefault(s.derivative, dotted(s.latex, 1))
        return names

    def fingerprint(self) -> str:
        """A hash of everything that shapes the equations (not the parameter values): the cache key (computed once)."""
        cached = self.__dict__.get("_fingerprint")
        if cached is None:
            cached = self._compute_fingerprint()
            object.__setattr__(self, "_fingerprint", cached)  # frozen: the hash of immutable data never changes
        return cached

    def _compute_fingerprint(self) -> str:
        parts = [
            self.id,
            repr([(c.name, c.unit) for c in self.coordinates]),
            repr([(p.name, p.unit) for p in self.parameters.parameters]),
            sympy.srepr(tuple(self.symbols.values())),
            sympy.srepr([(p.name, p.mass, p.position) for p in self.particles]),
            sympy.srepr([(b.name, b.mass, b.mass_centre, b.rotations, b.inertia) for b in self.bodies]),
            sympy.srepr(self.gravity),
            sympy.srepr([(s.stiffness, s.free_length, s.end_a, s.end_b, s.axis) for s in self.springs])
            + repr([(s.on_a, s.on_b) for s in self.springs]),
            sympy.srepr([(f.name, f.point, f.force) for f in self.forces]) + repr([f.on for f in self.forces]),
            sympy.srepr(self.extra_potential),
            sympy.srepr(self.kinetic_energy),
            repr(self.speeds),
            sympy.srepr(self.coordinate_rates),
            sympy.srepr(self.speeds_from_rates),
            sympy.srepr([(r.name, r.on, r.point, r.forces, r.moments, r.against) for r in self.reactions]),
            repr(self.ignorable),
        ]
        return hashlib.sha256("\n".join(parts).encode()).hexdigest()[:20]


def parameter(
    name: str, unit: str, default: float, *, low: float, high: float, label: str, description: str
) -> Parameter:
    """A physical parameter of a catalogue system (a float in [low, high])."""
    return Parameter(name, unit, default, min=low, max=high, label=label, description=description)
