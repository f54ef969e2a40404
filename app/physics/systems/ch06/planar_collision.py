"""Worked example ``planar-collision``: two uniform disks meet in the plane, with restitution and friction.

Frame (m, fixed xyz, plane z = 0): at the instant of contact disk 1's centre is at the origin and
disk 2's centre at ``(r1 + r2) n``, where the unit normal ``n = (cos β, sin β, 0)`` points from
body 1's centre to body 2's (β = ``line_of_centres_deg``). The tangent is ``t = k × n``; the contact
point is ``C = r1 n``. Spins ω (rad/s) are about +z. The impulse ``P = Pn n + Pt t`` (N·s) acts on
disk 2 at C and ``−P`` on disk 1. Each disk is a uniform thin disk, ``I = ½ m r²`` about z.

The impulse law is :func:`~app.physics.systems.ch06.impact.resolve_impact` (Stronge's energetic
restitution with Coulomb friction along the impulse). For two disks the inverse effective mass is
diagonal, so slip never reverses: the contact either slides throughout or stops sliding and sticks.

Disks that are not approaching at contact (normal relative velocity ≥ 0, or an approach below
round-off, 1e-12 of the contact speed) have no impact: the inputs
are refused with a ParameterError naming ``v2_m_s`` (the API's 422), and nothing is computed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.bodies.inertia import thin_disk
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch06.impact import ImpactResult, resolve_impact

_VECTORS = ("v1_m_s", "v2_m_s")
#: An approach speed below this fraction of the contact speed is round-off (β = 90° gives cos β ≈ 6e-17), not an impact.
APPROACH_ROUND_OFF = 1e-12


@dataclass(frozen=True)
class Disk:
    """A uniform disk in the plane: mass (kg), radius (m), its centre's position and velocity (m, m/s, (3,)), spin
    (rad/s about z)."""

    mass_kg: float
    radius_m: float
    centre_m: np.ndarray
    velocity_m_s: np.ndarray
    spin_rad_s: float

    @property
    def inertia_kg_m2(self) -> float:
        """Moment of inertia about the disk's centre, about z (kg·m²)."""
        return float(thin_disk(self.mass_kg, self.radius_m)[2, 2])

    @property
    def momentum_N_s(self) -> np.ndarray:
        return self.mass_kg * self.velocity_m_s

    def angular_momentum_about(self, point_m: np.ndarray) -> float:
        """z component of the angular momentum about a fixed point (kg·m²/s): ``I ω + m (r_G − r_P) × v_G``."""
        arm = self.centre_m - np.asarray(point_m, dtype=float)
        return self.inertia_kg_m2 * self.spin_rad_s + self.mass_kg * float(
            arm[0] * self.velocity_m_s[1] - arm[1] * self.velocity_m_s[0]
        )

    @property
    def kinetic_energy_J(self) -> float:
        return (
            0.5 * self.mass_kg * float(self.velocity_m_s @ self.velocity_m_s)
            + 0.5 * self.inertia_kg_m2 * self.spin_rad_s**2
        )

    def point_velocity(self, point_m: np.ndarray) -> np.ndarray:
        """Velocity (m/s, (3,)) of the body point at ``point_m``: ``v_G + ω k × (r − r_G)``."""
        arm = np.asarray(point_m, dtype=float) - self.centre_m
        return self.velocity_m_s + self.spin_rad_s * np.array([-arm[1], arm[0], 0.0])

    def after_impulse(self, impulse_N_s: np.ndarray, at_m: np.ndarray) -> Disk:
        """The disk just after an impulse (N·s, (3,)) applied at ``at_m``: ``Δv = P/m``,
        ``Δω = ((r − r_G) × P)_z / I``."""
        arm = np.asarray(at_m, dtype=float) - self.centre_m
        spin_change = float(arm[0] * impulse_N_s[1] - arm[1] * impulse_N_s[0]) / self.inertia_kg_m2
        return Disk(
            self.mass_kg,
            self.radius_m,
            self.centre_m,
            self.velocity_m_s + impulse_N_s / self.mass_kg,
            self.spin_rad_s + spin_change,
        )


@dataclass(frozen=True)
class DiskCollision:
    """Two disks at the instant of contact, before and after, with the contact frame and the impulse law's result."""

    before: tuple[Disk, Disk]
    after: tuple[Disk, Disk]
    normal: np.ndarray  # (3,) unit, from disk 1's centre to disk 2's
    tangent: np.ndarray  # (3,) unit, k × n
    contact_point_m: np.ndarray  # (3,)
    inverse_effective_mass: np.ndarray  # (2, 2) 1/kg, [normal, tangent]
    contact_velocity_m_s: np.ndarray  # (2,) [vn, vt] of disk 2's contact point relative to disk 1's, before
    impact: ImpactResult

    @property
    def impulse_N_s(self) -> np.ndarray:
        """Impulse on disk 2 (N·s, (3,) world frame)."""
        return self.impact.impulse_N_s[0] * self.normal + self.impact.impulse_N_s[1] * self.tangent

    @property
    def energy_before_J(self) -> float:
        return sum(d.kinetic_energy_J for d in self.before)


def contact_frame(line_of_centres_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Unit normal n (from body 1 to body 2) and tangent t = k × n, both (3,) in the plane z = 0."""
    beta = math.radians(line_of_centres_deg)
    normal = np.array([math.cos(beta), math.sin(beta), 0.0])
    return normal, np.array([-normal[1], normal[0], 0.0])


def disks_before(inputs: Mapping[str, Any]) -> tuple[Disk, Disk, np.ndarray, np.ndarray, np.ndarray]:
    """The two disks at contact (before), the normal, the tangent and the contact point."""
    normal, tangent = contact_frame(inputs["line_of_centres_deg"])
    r1, r2 = inputs["r1_m"], inputs["r2_m"]
    disk1 = Disk(inputs["m1_kg"], r1, np.zeros(3), np.asarray(inputs["v1_m_s"], dtype=float), inputs["omega1_rad_s"])
    disk2 = Disk(
        inputs["m2_kg"], r2, (r1 + r2) * normal, np.asarray(inputs["v2_m_s"], dtype=float), inputs["omega2_rad_s"]
    )
    return disk1, disk2, normal, tangent, r1 * normal


def relative_contact_velocity(
    disk1: Disk, disk2: Disk, normal: np.ndarray, tangent: np.ndarray, contact_m: np.ndarray
) -> np.ndarray:
    """[vn, vt] (m/s) of disk 2's contact point relative to disk 1's; vn < 0 means approaching."""
    relative = disk2.point_velocity(contact_m) - disk1.point_velocity(contact_m)
    return np.array([float(relative @ normal), float(relative @ tangent)])


def inverse_effective_mass(disk1: Disk, disk2: Disk) -> np.ndarray:
    """W (1/kg, (2, 2), [normal, tangent]) with Δv_contact = W P for disks touching on their line of centres.

    Both lever arms lie along n, so a normal impulse turns neither disk and W is diagonal:
    ``W_nn = 1/m1 + 1/m2``, ``W_tt = W_nn + r1²/I1 + r2²/I2``.
    """
    w_nn = 1.0 / disk1.mass_kg + 1.0 / disk2.mass_kg
    w_tt = w_nn + disk1.radius_m**2 / disk1.inertia_kg_m2 + disk2.radius_m**2 / disk2.inertia_kg_m2
    return np.array([[w_nn, 0.0], [0.0, w_tt]])


def collide(inputs: Mapping[str, Any]) -> DiskCollision:
    """Resolve the impact of two disks for validated inputs (see the module docstring for the frame)."""
    disk1, disk2, normal, tangent, contact = disks_before(inputs)
    W = inverse_effective_mass(disk1, disk2)
    v_contact = relative_contact_velocity(disk1, disk2, normal, tangent, contact)
    impact = resolve_impact(
        inverse_effective_mass=W,
        contact_velocity_m_s=v_contact,
        restitution=inputs["restitution"],
        friction_coefficient=inputs["friction_coefficient"],
    )
    impulse = impact.impulse_N_s[0] * normal + impact.impulse_N_s[1] * tangent
    after = (disk1.after_impulse(-impulse, contact), disk2.after_impulse(impulse, contact))
    return DiskCollision((disk1, disk2), after, normal, tangent, contact, W, v_contact, impact)


def _check(values: Mapping[str, Any]) -> None:
    for name in _VECTORS:
        if values[name][2] != 0.0:
            raise ParameterError(
                name, f"must lie in the plane: its z component must be 0 (got {values[name][2]:g} m/s)"
            )
    disk1, disk2, normal, tangent, contact = disks_before(values)
    vn, vt = relative_contact_velocity(disk1, disk2, normal, tangent, contact)
    if not vn < -APPROACH_ROUND_OFF * math.hypot(vn, vt):
        raise ParameterError(
            "v2_m_s",
            f"the disks are not approaching at contact: (v2 − v1)·n = {vn:.4g} m/s, not below zero along the "
            "line of centres, "
            "so there is no impact; make v2 − v1 point against n",
        )


INPUTS = ParameterSet(
    (
        Parameter("m1_kg", "kg", 2.0, 0.01, 1000.0, "Mass of disk 1", "m₁", scale="log"),
        Parameter("m2_kg", "kg", 1.0, 0.01, 1000.0, "Mass of disk 2", "m₂", scale="log"),
        Parameter("r1_m", "m", 0.3, 0.01, 10.0, "Radius of disk 1", "r₁", step=0.01),
        Parameter("r2_m", "m", 0.2, 0.01, 10.0, "Radius of disk 2", "r₂", step=0.01),
        Parameter(
            "v1_m_s",
            "m/s",
            (3.0, 0.0, 0.0),
            -100.0,
            100.0,
            "Velocity of disk 1's centre before impact (z = 0)",
            "v₁",
            kind="vector",
            step=0.1,
        ),
        Parameter(
            "v2_m_s",
            "m/s",
            (-1.0, 0.0, 0.0),
            -100.0,
            100.0,
            "Velocity of disk 2's centre before impact (z = 0)",
            "v₂",
            kind="vector",
            step=0.1,
        ),
        Parameter("omega1_rad_s", "rad/s", 0.0, -500.0, 500.0, "Spin of disk 1 about z before impact", "ω₁", step=0.5),
        Parameter("omega2_rad_s", "rad/s", 0.0, -500.0, 500.0, "Spin of disk 2 about z before impact", "ω₂", step=0.5),
        Parameter(
            "line_of_centres_deg",
            "deg",
            40.0,
            -180.0,
            180.0,
            "Direction from disk 1's centre to disk 2's at contact, from +x",
            "β",
            step=1,
        ),
        Parameter(
            "restitution",
            "",
            0.8,
            0.0,
            1.0,
            "Energetic coefficient of restitution e (1: no loss in the normal direction)",
            "e",
            step=0.01,
        ),
        Parameter(
            "friction_coefficient", "", 0.1, 0.0, 10.0, "Coulomb friction coefficient μ at the contact", "μ", step=0.01
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    c = collide(inputs)
    (d1, d2), (a1, a2) = c.before, c.after
    W = c.inverse_effective_mass
    vn, vt = c.contact_velocity_m_s
    p_n, p_t = c.impact.impulse_N_s
    mu, e = inputs["friction_coefficient"], inputs["restitution"]
    steps = (
        Step(
            "Contact frame and contact point",
            r"\bar n = \cos\beta\,\bar i + \sin\beta\,\bar j,\quad \bar t = \bar k\times\bar n,\quad \bar r_C = "
            r"r_1\,\bar n",
            {"n": c.normal, "t": c.tangent, "r_C": c.contact_point_m},
            {"n": "", "t": "", "r_C": "m"},
        ),
        Step(
            "Relative velocity of the contact points before impact",
            r"\bar v_{C2} - \bar v_{C1} = (\bar v_2 - \omega_2 r_2\,\bar t) - (\bar v_1 + \omega_1 r_1\,\bar t),"
            r"\quad v_n = (\bar v_{C2}-\bar v_{C1})\cdot\bar n < 0,\quad v_t = (\bar v_{C2}-\bar v_{C1})\cdot\bar t",
            {"v_n": vn, "v_t": vt},
            {"v_n": "m/s", "v_t": "m/s"},
        ),
        Step(
            "Inverse effective mass at the contact (I = ½ m r²)",
            r"\Delta\begin{bmatrix}v_n\\v_t\end{bmatrix} = W\begin{bmatrix}P_n\\P_t\end{bmatrix},\quad "
            r"W = \begin{bmatrix}\frac1{m_1}+\frac1{m_2} & 0\\ 0 & "
            r"\frac1{m_1}+\frac1{m_2}+\frac{r_1^2}{I_1}+\frac{r_2^2}{I_2}\end{bmatrix}",
            {"I_1": d1.inertia_kg_m2, "I_2": d2.inertia_kg_m2, "W_nn": W[0, 0], "W_tt": W[1, 1]},
            {"I_1": "kg·m²", "I_2": "kg·m²", "W_nn": "1/kg", "W_tt": "1/kg"},
        ),
        Step(
            "Impulse (energetic restitution; friction stops the slip or caps Pt at μ Pn)",
            r"P_n = (1+e)\,\frac{-v_n}{W_{nn}},\quad P_t = -\operatorname{sign}(v_t)\,\min\!\left(\mu "
            r"P_n,\ \frac{|v_t|}{W_{tt}}\right)",
            {"e": e, "mu": mu, "P_n": p_n, "P_t": p_t, "P": c.impulse_N_s},
            {"e": "", "mu": "", "P_n": "N·s", "P_t": "N·s", "P": "N·s"},
        ),
        Step(
            "Velocities and spins after",
            r"\bar v_1' = \bar v_1 - \frac{\bar P}{m_1},\quad \bar v_2' = \bar v_2 + \frac{\bar P}{m_2},\quad "
            r"\omega_1' = \omega_1 - \frac{r_1 P_t}{I_1},\quad \omega_2' = \omega_2 - \frac{r_2 P_t}{I_2}",
            {"v_1'": a1.velocity_m_s, "v_2'": a2.velocity_m_s, "omega_1'": a1.spin_rad_s, "omega_2'": a2.spin_rad_s},
            {"v_1'": "m/s", "v_2'": "m/s", "omega_1'": "rad/s", "omega_2'": "rad/s"},
        ),
        Step(
            "Energy lost",
            r"\Delta T = -\tfrac12\,P^{\mathsf T}(v_{\rm before} + v_{\rm after}) = T - T' \ge 0",
            {
                "T": c.energy_before_J,
                "T'": c.energy_before_J - c.impact.energy_loss_J,
                "Delta_T": c.impact.energy_loss_J,
            },
            {"T": "J", "T'": "J", "Delta_T": "J"},
        ),
        Step(
            "Check: the impulse is internal to the pair and acts at C",
            r"m_1\bar v_1 + m_2\bar v_2 = m_1\bar v_1' + m_2\bar v_2',\quad H_{C,i} = I_i\omega_i + "
            r"m_i\,[(\bar r_i - \bar r_C)\times\bar v_i]_z \text{ unchanged for each disk}",
            {
                "p_before": d1.momentum_N_s + d2.momentum_N_s,
                "p_after": a1.momentum_N_s + a2.momentum_N_s,
                "H_C1_before": d1.angular_momentum_about(c.contact_point_m),
                "H_C1_after": a1.angular_momentum_about(c.contact_point_m),
                "H_C2_before": d2.angular_momentum_about(c.contact_point_m),
                "H_C2_after": a2.angular_momentum_about(c.contact_point_m),
            },
            {
                "p_before": "N·s",
                "p_after": "N·s",
                "H_C1_before": "kg·m²/s",
                "H_C1_after": "kg·m²/s",
                "H_C2_before": "kg·m²/s",
                "H_C2_after": "kg·m²/s",
            },
        ),
    )
    outputs = {
        "v1_after_m_s": a1.velocity_m_s,
        "v2_after_m_s": a2.velocity_m_s,
        "omega1_after_rad_s": a1.spin_rad_s,
        "omega2_after_rad_s": a2.spin_rad_s,
        "impulse_N_s": c.impulse_N_s,
        "energy_loss_J": c.impact.energy_loss_J,
        "slip_state": c.impact.slip_state,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="planar-collision",
    title="Two disks collide: restitution, friction and the impulse",
    chapter=6,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "v1_after_m_s": "m/s",
        "v2_after_m_s": "m/s",
        "omega1_after_rad_s": "rad/s",
        "omega2_after_rad_s": "rad/s",
        "impulse_N_s": "N·s",
        "energy_loss_J": "J",
        "slip_state": "",
    },
    section="6.4",
    story=ExampleStory(
        situation=(
            "Two uniform disks slide on a smooth horizontal table and strike each other. Before the impact we know "
            "each disk's mass, radius, velocity and spin, and the direction $\\beta$ of the line from disk 1's "
            "centre to disk 2's at the instant of contact. The contact has a restitution coefficient $e$ and a "
            "friction coefficient $\\mu$."
        ),
        wanted=(
            "Both disks' velocities and spins just after the impact, the impulse that passed between them, and the "
            "kinetic energy the impact took."
        ),
        approach=(
            "The impact lasts so short a time that the disks do not move while it acts: only the impulse "
            "$\\bar P$ at the contact changes their velocities, and every finite force (gravity and the "
            "table's support) can be left out. So we work with impulse and momentum, not with forces and "
            "accelerations. "
            "We resolve everything along the contact's own normal $\\bar n$ and tangent $\\bar t$, where "
            "restitution and friction are stated, and describe how the impulse changes the contact's relative "
            "velocity with one $2\\times2$ matrix $W$, the inverse effective mass. Tracking each disk's "
            "velocity separately through the impact would take twice the unknowns and hide the one number "
            "friction cares about, the contact's slip speed $v_t$."
        ),
        check=(
            "The impulse on disk 2 is the opposite of the one on disk 1, so the pair's linear momentum cannot "
            "change. Each impulse acts at the contact point $C$, so each disk's angular momentum about $C$ cannot "
            "change either. The last step computes all three before and after: they agree to round-off, while the "
            "energy drops by $\\Delta T \\ge 0$."
        ),
        what_if=(
            "Move the **friction coefficient** from 0 to about 1 with the disks striking off-centre. With "
            "$\\mu = 0$ the impulse is purely normal: only the velocities' normal parts change and the spins stay "
            "as they were. As $\\mu$ grows, $P_t$ grows until the slip stops during the impact (the slip "
            "state says *stick*); beyond that, more friction changes nothing. In the scene, watch the disks "
            "leave spinning."
        ),
    ),
)
