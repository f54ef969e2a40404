"""A body spun at constant rate on a shaft that is not a principal axis (sections 5.1 and 5.3).

Frames (m, world +Z up): the shaft is the world Z axis through the centre of
mass G, carried by bearings A (below G) and B (above G), each half the bearing
span from G. Body axes xyz are the shape's own axes (see
:mod:`app.physics.bodies.inertia`: a plate's normal, a box's height and a disk's
axis are z). At spin angle zero the body is turned by ``tilt`` about world X, so
``R_world_body(0) = R_x(tilt)``, and it spins at constant rate Ω:

    R_world_body(t) = R_z(Ω t) R_x(tilt),    ω = Ω Z,
    H_G = R I_body Rᵀ ω = R_z(Ω t) H_G(0),    dH_G/dt = ω × H_G,

so H_G keeps its length and sweeps a cone about the shaft, and ``ω × H_G``
(perpendicular to the shaft, turning with the body) is the moment the bearings
must supply: two equal and opposite forces ``|dH/dt| / span``. Kinetic energy
``T = ½ m |v_G|² + ½ ω·H_G``.

The particle view replaces the body by point masses fixed in it that have the
same mass, centre of mass and centroidal tensor (:func:`equivalent_particles`),
and lets the whole shaft travel at a constant velocity v_G from G(0): then
``p = Σ mᵢ vᵢ = m v_G``, ``H_O = Σ rᵢ × mᵢ vᵢ = H_G + r_G × m v_G`` about the
world origin O, and ``T = ½ m v_G² + Σ ½ mᵢ |vᵢ − v_G|²``. A constant v_G
changes p, H_O and T but not the bearing forces (the shaft's frame is inertial).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Any

import numpy as np

from app.physics.bodies import inertia
from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.report import Event
from app.physics.math.rotations import elementary_rotation_matrix, quaternion_from_matrix

BODIES = ("plate", "box", "disk")
VIEWS = ("rigid body", "particles")
SHAFT_AXIS = np.array([0.0, 0.0, 1.0])
#: Position and velocity (m, m/s) of a centre of mass held on the fixed shaft (the rigid-body view); never written to.
_AT_REST = np.zeros(3)
_AT_REST.flags.writeable = False
#: Relative size of the shaft's products of inertia below which the shaft counts as a principal axis.
PRINCIPAL_SHAFT_TOLERANCE = 1e-12


@dataclass(frozen=True)
class MountedBody:
    """The body on its shaft: shape, mass (kg), its dimensions (m, own axes x, y, z; a disk: diameter, diameter,
    0), its centroidal tensor in its own axes (3×3, kg·m²) and ``R_world_body`` at spin angle zero (3×3)."""

    shape: str
    mass_kg: float
    dimensions_m: tuple[float, float, float]
    inertia_body_kg_m2: np.ndarray
    mounting: np.ndarray

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> MountedBody:
        shape, mass = params["body"], float(params["mass_kg"])
        if shape == "plate":
            dims = (params["length_m"], params["width_m"], 0.0)
            tensor = inertia.thin_plate(mass, params["length_m"], params["width_m"])
        elif shape == "box":
            dims = (params["length_m"], params["width_m"], params["height_m"])
            tensor = inertia.box(mass, *dims)
        elif shape == "disk":
            dims = (2.0 * params["radius_m"], 2.0 * params["radius_m"], 0.0)
            tensor = inertia.thin_disk(mass, params["radius_m"])
        else:
            raise ValueError(f"body must be one of {', '.join(BODIES)} (got {shape!r})")
        mounting = elementary_rotation_matrix(0, math.radians(params["tilt_deg"]))
        tensor.flags.writeable = mounting.flags.writeable = False  # shared by every user of a cached motion
        return cls(shape, mass, (float(dims[0]), float(dims[1]), float(dims[2])), tensor, mounting)

    @cached_property
    def inertia_world0_kg_m2(self) -> np.ndarray:
        """Centroidal tensor in world components at spin angle zero (3×3, kg·m²)."""
        return inertia.rotate_tensor(self.inertia_body_kg_m2, self.mounting)

    @property
    def shaft_is_principal(self) -> bool:
        """True when the shaft's products of inertia vanish: then H ∥ ω and the bearings feel no moment."""
        tensor = self.inertia_world0_kg_m2
        return math.hypot(tensor[0, 2], tensor[1, 2]) <= PRINCIPAL_SHAFT_TOLERANCE * float(np.trace(tensor))

    @property
    def radius_m(self) -> float:
        """Half the diagonal of the body's bounding box (m): a size for drawing and for scales."""
        return 0.5 * math.sqrt(sum(d * d for d in self.dimensions_m))


def equivalent_particles(inertia_principal_kg_m2: np.ndarray, mass_kg: float) -> tuple[np.ndarray, np.ndarray]:
    """Point masses with the body's mass, centre of mass (their mean, at the origin) and diagonal centroidal tensor.

    Eight equal masses at the corners ``(±a, ±b, ±c)`` of a box in the body's own
    axes give ``I_xx = m (b² + c²)`` and cyclically, so ``a² = (I_yy + I_zz − I_xx) / 2m``;
    a body flat in its own z (a plate, a disk: ``c = 0``) needs only the four
    corners of a rectangle. Returns positions (N, 3) in m (body axes) and masses
    (N,) in kg.
    """
    ixx, iyy, izz = (float(x) for x in inertia_principal_kg_m2)
    squares = np.array([iyy + izz - ixx, ixx + izz - iyy, ixx + iyy - izz]) / (2.0 * mass_kg)
    half = np.sqrt(np.clip(squares, 0.0, None))
    flat = squares <= 1e-12 * float(np.max(squares))
    signs = [(sx, sy, sz) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0) for sz in ((0.0,) if flat[2] else (-1.0, 1.0))]
    positions = np.array(signs) * half
    return positions, np.full(len(positions), mass_kg / len(positions))


@dataclass(frozen=True)
class SpinState:
    """The spinning body at N instants (world components).

    ``spin_angle`` (N,) rad; ``omega_rad_s`` (3,); ``angular_momentum_G`` H_G and
    ``angular_momentum_O`` H_O (N, 3) kg·m²/s; ``bearing_moment`` dH_G/dt = ω × H_G
    (N, 3) N·m; ``bearing_force_A`` / ``_B`` (N, 3) N at the lower / upper bearing;
    ``centre_m`` r_G (N, 3) m; ``centre_velocity_m_s`` v_G (3,) m/s;
    ``linear_momentum`` m v_G (3,) kg·m/s; ``bearing_moment_N_m`` |dH_G/dt| (N,) N·m;
    ``angle_between_omega_and_H`` (N,) rad; kinetic energy of the motion of G and of
    the motion about G (N,) J.
    """

    t_s: np.ndarray
    spin_angle: np.ndarray
    omega_rad_s: np.ndarray
    angular_momentum_G: np.ndarray
    angular_momentum_O: np.ndarray
    bearing_moment: np.ndarray
    bearing_force_A: np.ndarray
    bearing_force_B: np.ndarray
    centre_m: np.ndarray
    centre_velocity_m_s: np.ndarray
    linear_momentum: np.ndarray
    bearing_moment_N_m: np.ndarray
    angle_between_omega_and_H: np.ndarray
    kinetic_energy_centre_J: np.ndarray
    kinetic_energy_about_centre_J: np.ndarray

    @property
    def kinetic_energy_J(self) -> np.ndarray:
        return self.kinetic_energy_centre_J + self.kinetic_energy_about_centre_J


@dataclass(frozen=True)
class ParticleState:
    """The equivalent particles at N instants: masses (P,) kg, positions and velocities (N, P, 3) in m and m/s
    (world)."""

    masses_kg: np.ndarray
    positions_m: np.ndarray
    velocities_m_s: np.ndarray

    def linear_momentum(self) -> np.ndarray:
        """``Σ mᵢ vᵢ`` (N, 3) kg·m/s."""
        return np.einsum("p,npk->nk", self.masses_kg, self.velocities_m_s)

    def angular_momentum(self, about_m: np.ndarray) -> np.ndarray:
        """``Σ (rᵢ − about) × mᵢ vᵢ`` (N, 3) kg·m²/s; ``about_m`` (3,) or (N, 3) m."""
        arms = self.positions_m - np.asarray(about_m, dtype=float).reshape(-1, 1, 3)
        return np.einsum("p,npk->nk", self.masses_kg, np.cross(arms, self.velocities_m_s))

    def kinetic_energy(self, *, relative_to_m_s: np.ndarray | None = None) -> np.ndarray:
        """``Σ ½ mᵢ |vᵢ − u|²`` (N,) J, with ``u`` = ``relative_to_m_s`` (3,) or zero."""
        v = (
            self.velocities_m_s
            if relative_to_m_s is None
            else self.velocities_m_s - np.asarray(relative_to_m_s, dtype=float)
        )
        return 0.5 * np.einsum("p,npk,npk->n", self.masses_kg, v, v)


@dataclass(frozen=True)
class ShaftSpin:
    """The mounted body turning at ``spin_rate_rad_s`` on bearings ``bearing_span_m`` apart, the shaft (with G)
    starting at ``centre_start_m`` (3,) and travelling at ``centre_velocity_m_s`` (3,) (zero in the rigid-body view)."""

    body: MountedBody
    spin_rate_rad_s: float
    bearing_span_m: float
    centre_start_m: np.ndarray
    centre_velocity_m_s: np.ndarray

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> ShaftSpin:
        """The motion for validated parameters; the same values give the same (immutable) object from a small cache,
        so a frame or a request at one instant costs only :meth:`at`."""
        return _shaft_spin(tuple((name, tuple(v) if isinstance(v, list) else v) for name, v in sorted(params.items())))

    @property
    def omega_rad_s(self) -> np.ndarray:
        return self.spin_rate_rad_s * SHAFT_AXIS

    def attitude(self, t_s: np.ndarray) -> np.ndarray:
        """``R_world_body(t) = R_z(Ω t) R_x(tilt)`` (N, 3, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        return elementary_rotation_matrix(2, self.spin_rate_rad_s * t) @ self.body.mounting

    @cached_property
    def _mounting_wxyz(self) -> tuple[float, float, float, float]:
        w, x, y, z = quaternion_from_matrix(self.body.mounting)
        return float(w), float(x), float(y), float(z)

    def attitude_wxyz(self, t_s: float) -> tuple[float, float, float, float]:
        """The attitude of :meth:`attitude` at one time as a ``wxyz`` quaternion: the turn Ω t about Z composed with the
        mounting."""
        half = 0.5 * self.spin_rate_rad_s * t_s
        c, s = math.cos(half), math.sin(half)
        w, x, y, z = self._mounting_wxyz
        return c * w - s * z, c * x - s * y, c * y + s * x, c * z + s * w

    @cached_property
    def _sweep(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Constant (2, 3) coefficients on ``[cos Ωt, sin Ωt]`` of H_G, dH_G/dt and F_B, and H_G's shaft part (3,).

        With ``H_G(0) = (h_x, h_y, h_z)``, ``a = (h_x, h_y, 0)`` and ``b = Z × a``:
        ``H_G = a cos + b sin + h_z Z``, ``dH_G/dt = Ω (b cos − a sin)`` and
        ``F_B = (dH_G/dt × Z) / span = Ω (a cos + b sin) / span``.
        """
        R = self.body.mounting
        hx, hy, hz = (float(x) for x in R @ (self.body.inertia_body_kg_m2 @ R[2]) * self.spin_rate_rad_s)
        across = np.array([[hx, hy, 0.0], [-hy, hx, 0.0]])
        moment = self.spin_rate_rad_s * np.array([[-hy, hx, 0.0], [-hx, -hy, 0.0]])
        return across, moment, across * (self.spin_rate_rad_s / self.bearing_span_m), np.array([0.0, 0.0, hz])

    @property
    def angular_momentum_magnitude_kg_m2_s(self) -> float:
        """``|H_G|`` (kg·m²/s), constant."""
        across, _, _, along = self._sweep
        return math.hypot(across[0, 0], across[0, 1], along[2])

    @property
    def bearing_moment_N_m(self) -> float:
        """``|dH_G/dt| = |Ω| |H_G across the shaft|`` (N·m), constant."""
        across = self._sweep[0]
        return abs(self.spin_rate_rad_s) * math.hypot(across[0, 0], across[0, 1])

    @property
    def angle_between_omega_and_H(self) -> float:
        """Angle (rad) between ω and H_G, ``atan2(|ω × H|, ω·H)``; constant. NaN without spin: ω = 0 and H_G = 0 have no
        direction, so there is no angle between them (the report's null, with :data:`NO_SPIN_ANGLE` saying why)."""
        if self.spin_rate_rad_s == 0.0:
            return math.nan
        return math.atan2(self.bearing_moment_N_m, self.spin_rate_rad_s * self._sweep[3][2])

    @property
    def kinetic_energy_about_centre_J(self) -> float:
        """``½ ω·H_G`` (J), constant."""
        return 0.5 * self.spin_rate_rad_s * self._sweep[3][2]

    def at(self, t_s: np.ndarray) -> SpinState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        angle = self.spin_rate_rad_s * t
        phase = np.empty((t.shape[0], 2))
        phase[:, 0] = np.cos(angle)
        phase[:, 1] = np.sin(angle)
        across, moment_coefficients, force_coefficients, along = self._sweep
        h_g = phase @ across + along
        moment = phase @ moment_coefficients
        force_b = phase @ force_coefficients
        mass = self.body.mass_kg
        centre = self.centre_start_m + t[:, None] * self.centre_velocity_m_s
        momentum = mass * self.centre_velocity_m_s
        # r_G × m v_G = r_G(0) × m v_G for a constant v_G (the v_G t part is parallel to v_G).
        moving = self.centre_velocity_m_s is not _AT_REST
        moment_of_momentum = np.cross(self.centre_start_m, momentum) if moving else _AT_REST
        t_centre = 0.5 * mass * float(self.centre_velocity_m_s @ self.centre_velocity_m_s) if moving else 0.0
        n = t.shape[0]
        return SpinState(
            t_s=t,
            spin_angle=angle,
            omega_rad_s=self.omega_rad_s,
            angular_momentum_G=h_g,
            angular_momentum_O=h_g + moment_of_momentum,
            bearing_moment=moment,
            bearing_force_A=-force_b,
            bearing_force_B=force_b,
            centre_m=centre,
            centre_velocity_m_s=self.centre_velocity_m_s,
            linear_momentum=momentum,
            bearing_moment_N_m=np.full(n, self.bearing_moment_N_m),
            angle_between_omega_and_H=np.full(n, self.angle_between_omega_and_H),
            kinetic_energy_centre_J=np.full(n, t_centre),
            kinetic_energy_about_centre_J=np.full(n, self.kinetic_energy_about_centre_J),
        )

    def particles_at(self, state: SpinState) -> ParticleState:
        """The equivalent particles (:func:`equivalent_particles`) moving with the body in ``state``."""
        local, masses = equivalent_particles(np.diag(self.body.inertia_body_kg_m2), self.body.mass_kg)
        arms = np.einsum("nij,pj->npi", self.attitude(state.t_s), local)
        positions = state.centre_m[:, None, :] + arms
        velocities = np.empty_like(arms)
        velocities[..., 0] = -self.spin_rate_rad_s * arms[..., 1]
        velocities[..., 1] = self.spin_rate_rad_s * arms[..., 0]
        velocities[..., 2] = 0.0
        velocities += state.centre_velocity_m_s
        return ParticleState(masses, positions, velocities)


def _read_only(values: Any) -> np.ndarray:
    array = np.array(values, dtype=float)
    array.flags.writeable = False
    return array


@lru_cache(maxsize=64)
def _shaft_spin(items: tuple[tuple[str, Any], ...]) -> ShaftSpin:
    params = dict(items)
    if params["view"] not in VIEWS:
        raise ValueError(f"view must be one of {', '.join(VIEWS)} (got {params['view']!r})")
    moving = params["view"] == "particles"
    start = _read_only(params["centre_position_m"]) if moving else _AT_REST
    velocity = _read_only(params["centre_velocity_m_s"]) if moving else _AT_REST
    return ShaftSpin(
        MountedBody.from_params(params),
        float(params["spin_rate_rad_s"]),
        float(params["bearing_span_m"]),
        start,
        velocity,
    )


def _check(params: Mapping[str, Any]) -> None:
    ShaftSpin.from_params(params)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "body",
            "",
            "plate",
            description="The body on the shaft: a thin rectangular plate, a rectangular box or a thin disk",
            label="body",
            kind="choice",
            choices=BODIES,
        ),
        Parameter("mass_kg", "kg", 4.0, 0.01, 1000.0, "Mass m of the body", "m", scale="log"),
        Parameter(
            "length_m",
            "m",
            0.5,
            0.01,
            5.0,
            "Plate and box: side a along the body's x axis (the tilt axis)",
            "a",
            step=0.01,
        ),
        Parameter("width_m", "m", 0.4, 0.01, 5.0, "Plate and box: side b along the body's y axis", "b", step=0.01),
        Parameter(
            "height_m",
            "m",
            0.1,
            0.01,
            5.0,
            "Box only: side c along the body's z axis (along the shaft at zero tilt)",
            "c",
            step=0.01,
        ),
        Parameter("radius_m", "m", 0.25, 0.01, 5.0, "Disk only: radius r", "r", step=0.01),
        Parameter(
            "tilt_deg",
            "deg",
            30.0,
            -90.0,
            90.0,
            "Tilt of the body's z axis (plate normal, disk axis) from the shaft, about the body's x axis",
            "tilt",
            step=1,
        ),
        Parameter(
            "spin_rate_rad_s", "rad/s", 4.0, -30.0, 30.0, "Constant spin rate Ω of the shaft (0 allowed)", "Ω", step=0.1
        ),
        Parameter(
            "bearing_span_m",
            "m",
            0.8,
            0.05,
            10.0,
            "Distance between the two bearings, which sit symmetrically about G",
            "span",
            step=0.01,
        ),
        Parameter(
            "view",
            "",
            "rigid body",
            description="Show the rigid body on its shaft, or the body as point masses with a moving centre",
            label="view",
            kind="choice",
            choices=VIEWS,
        ),
        Parameter(
            "centre_velocity_m_s",
            "m/s",
            [0.3, 0.0, 0.0],
            -10.0,
            10.0,
            "Particles view only: constant velocity v_G of the centre of mass (and of the shaft), world [x, y, z]",
            "v_G",
            kind="vector",
            step=0.05,
        ),
        Parameter(
            "centre_position_m",
            "m",
            [-0.3, 0.3, 0.0],
            -10.0,
            10.0,
            "Particles view only: position of the centre of mass at t = 0 from the origin O, world [x, y, z]",
            "r_G(0)",
            kind="vector",
            step=0.05,
        ),
    ),
    check=_check,
)


#: Why the angle between ω and H_G is undefined without spin (the readout's text and the simulate answer's event).
NO_SPIN_ANGLE = "undefined (no spin: ω = 0 and H = 0)"


class ShaftSpinModel(ClosedFormModel):
    """A body at constant spin about a fixed shaft through G: H, its rate, the bearing moment and the energy in closed
    form."""

    parameters = PARAMETERS
    series_units = {
        "spin_angle": "rad",
        "angular_momentum_x_kg_m2_s": "kg·m²/s",
        "angular_momentum_y_kg_m2_s": "kg·m²/s",
        "angular_momentum_z_kg_m2_s": "kg·m²/s",
        "bearing_moment_N_m": "N·m",
        "angle_between_omega_and_H": "rad",
        "kinetic_energy_J": "J",
    }
    invariant_units = {"angular_momentum_magnitude_kg_m2_s": "kg·m²/s", "kinetic_energy_J": "J"}
    description = "closed form: R(t) = R_z(Ωt) R_x(tilt), H_G = R I Rᵀ ω, dH_G/dt = ω × H_G"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = ShaftSpin.from_params(params)
        state = motion.at(t_s)
        h = state.angular_momentum_G
        series = {
            "spin_angle": state.spin_angle,
            "angular_momentum_x_kg_m2_s": h[:, 0],
            "angular_momentum_y_kg_m2_s": h[:, 1],
            "angular_momentum_z_kg_m2_s": h[:, 2],
            "bearing_moment_N_m": state.bearing_moment_N_m,
            "angle_between_omega_and_H": state.angle_between_omega_and_H,
            "kinetic_energy_J": state.kinetic_energy_J,
        }
        # Checks recomputed from H_G(t) itself: its length, and ½ m v_G² + ½ ω·H_G.
        invariants = {
            "angular_momentum_magnitude_kg_m2_s": np.sqrt(np.sum(h * h, axis=-1)),
            "kinetic_energy_J": state.kinetic_energy_centre_J + 0.5 * motion.spin_rate_rad_s * h[:, 2],
        }
        events = (
            []
            if motion.spin_rate_rad_s != 0.0
            else [Event(0.0, "undefined", f"angle between ω and H_G: {NO_SPIN_ANGLE}")]
        )
        return ClosedFormSolution(series, invariants, events=events)
