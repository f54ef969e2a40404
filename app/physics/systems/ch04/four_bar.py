"""The planar four-bar linkage: loop closure on both assemblies, rates, Grashof class.

Frame (planar, m): the crank's ground pivot O₂ is the origin and the rocker's
ground pivot O₄ is at (d, 0), so the ground link lies along +x. Link lengths:
ground d, crank a (O₂A), coupler b (AB), rocker c (O₄B). Angles θ₂ (crank),
θ₃ (coupler, direction A→B) and θ₄ (rocker, direction O₄→B) are measured
counterclockwise from the ground line, in rad. The loop

    a e^{iθ₂} + b e^{iθ₃} = d + c e^{iθ₄}

closes, for a given crank angle, at the intersections of the circle of radius b
about A with the circle of radius c about O₄. The **open** assembly puts B to
the left of the line from A to O₄, the **crossed** assembly to the right.

Differentiating the loop once gives the coupler and rocker rates from a 2×2
linear system whose determinant is ``b c sin(θ₃ − θ₄)``; it vanishes when the
coupler and rocker are in line. With the crank as input that is a **toggle
position** (the crank is at the end of its travel and the rocker rate is
unbounded) or, when all four links fall in line, a **change point** (the rates
are 0/0 and the linkage could switch assembly). Both are flagged: rates there
are NaN, and the motion reports an :class:`~app.physics.core.closed_form.Event`.
The motion keeps the assembly it started in through both.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.systems.ch04.crank_drive import CrankDrive
from app.physics.systems.ch04.planar_loop import TWO_PI, continuous_angle, solve_2x2

BRANCHES = ("open", "crossed")
#: Coupler and rocker closer to in line than this (|sin(θ₃ − θ₄)|) count as singular.
#: Only a crank angle within about 1e-14 rad of a toggle comes this close; a frame
#: even 1e-10 rad away gets a finite (if enormous) rate.
SINGULAR_SIN = 1e-7
#: Relative tolerance for "equal" lengths in the Grashof test and for the loop just closing.
LENGTH_RTOL = 1e-9
_COS_TOL = 1e-12


@dataclass(frozen=True)
class GrashofClass:
    """Grashof classification: ``s + l`` against ``p + q`` and which link is shortest."""

    name: str
    grashof: bool
    shortest: str
    crank_turns_fully: bool
    description: str


@dataclass(frozen=True)
class CrankRange:
    """Crank angles (rad) at which the loop closes.

    ``arcs_rad`` is empty when the crank turns fully, else one or two
    ``(lower, upper)`` arcs. ``singular_angles_rad`` are crank angles inside the
    travel where all four links fall in line (change points).
    """

    turns_fully: bool
    arcs_rad: tuple[tuple[float, float], ...]
    singular_angles_rad: tuple[float, ...]

    def describe(self) -> str:
        if self.turns_fully:
            return "the crank turns fully"
        arcs = " or ".join(f"{math.degrees(lo):.1f}° to {math.degrees(hi):.1f}°" for lo, hi in self.arcs_rad)
        return f"the crank reaches only {arcs}"

    def arc_containing(self, angle_rad: float) -> tuple[float, float]:
        """The arc (lower, upper) in rad with ``lower <= angle_rad <= upper``; ValueError if none."""
        for lower, upper in self.arcs_rad:
            for k in (-1, 0, 1):
                lo, hi = lower + TWO_PI * k, upper + TWO_PI * k
                if lo - 1e-9 <= angle_rad <= hi + 1e-9:
                    return lo, hi
        raise ValueError(
            f"the loop cannot close with the crank at {math.degrees(angle_rad):.1f}°: with these lengths "
            f"{self.describe()}"
        )


@dataclass(frozen=True)
class FourBarPositions:
    """Configuration at N crank angles: angles (rad; coupler and rocker wrapped to [-π, π)),
    joint positions A (crank pin) and B (rocker pin) as (N, 2) arrays in m on the ground frame."""

    crank_angle: np.ndarray
    coupler_angle: np.ndarray
    rocker_angle: np.ndarray
    crank_pin: np.ndarray
    rocker_pin: np.ndarray


@dataclass(frozen=True)
class FourBar:
    """Link lengths (m) of a four-bar linkage; raises ValueError if the loop can never close."""

    ground_m: float
    crank_m: float
    coupler_m: float
    rocker_m: float

    def __post_init__(self) -> None:
        for name, length in self.links.items():
            if not (math.isfinite(length) and length > 0.0):
                raise ValueError(f"the {name} link must have a positive length (got {length!r} m)")
        links = self.links
        longest = max(links, key=links.__getitem__)
        others = sum(links.values()) - links[longest]
        if links[longest] >= others * (1.0 - LENGTH_RTOL):
            raise ValueError(
                f"these links cannot be assembled: the longest link ({longest}, {links[longest]:g} m) must be shorter "
                f"than the other three together ({others:g} m)"
            )

    @property
    def links(self) -> dict[str, float]:
        return {"ground": self.ground_m, "crank": self.crank_m, "coupler": self.coupler_m, "rocker": self.rocker_m}

    def grashof(self) -> GrashofClass:
        """Grashof class from the shortest (s), longest (l) and other two (p, q) lengths."""
        links = self.links
        s_name = min(links, key=links.__getitem__)
        s, l = links[s_name], max(links.values())
        pq = sum(links.values()) - s - l
        if s + l > pq * (1.0 + LENGTH_RTOL):
            return GrashofClass(
                "non-Grashof",
                False,
                s_name,
                False,
                "s + l > p + q: no link turns fully relative to another, so the crank can only rock (a triple rocker)",
            )
        if s + l >= pq * (1.0 - LENGTH_RTOL):
            turns = links["crank"] <= s * (1.0 + LENGTH_RTOL) or links["ground"] <= s * (1.0 + LENGTH_RTOL)
            return GrashofClass(
                "change point",
                True,
                s_name,
                turns,
                "s + l = p + q: all four links can fall in line, where the linkage may switch assembly",
            )
        names = {
            "crank": ("crank-rocker", True, "the crank is the shortest link: it turns fully while the rocker rocks"),
            "ground": (
                "double-crank",
                True,
                "the ground is the shortest link: crank and rocker both turn fully (a drag link)",
            ),
            "rocker": (
                "rocker-crank",
                False,
                "the rocker is the shortest link: it turns fully while the crank can only rock",
            ),
            "coupler": ("double-rocker", False, "the coupler is the shortest link: crank and rocker can only rock"),
        }
        name, turns, description = names[s_name]
        return GrashofClass(name, True, s_name, turns, description)

    def crank_range(self) -> CrankRange:
        """Crank angles at which the loop closes, from |b − c| ≤ |O₄ − A| ≤ b + c."""
        a, b, c, d = self.crank_m, self.coupler_m, self.rocker_m, self.ground_m
        # |O₄ − A|² = a² + d² − 2ad cos θ₂, so the two bounds are bounds on cos θ₂.
        cos_lower = (a * a + d * d - (b + c) ** 2) / (2.0 * a * d)
        cos_upper = (a * a + d * d - (b - c) ** 2) / (2.0 * a * d)
        singular = []
        if abs(cos_upper - 1.0) <= _COS_TOL:
            singular.append(0.0)
        if abs(cos_lower + 1.0) <= _COS_TOL:
            singular.append(math.pi)
        lo = -1.0 if cos_lower <= -1.0 + _COS_TOL else cos_lower
        hi = 1.0 if cos_upper >= 1.0 - _COS_TOL else cos_upper
        if lo == -1.0 and hi == 1.0:
            return CrankRange(True, (), tuple(singular))
        if hi - lo < 1e-10:
            raise ValueError("these links close only at a single crank angle, so the linkage cannot move")
        arcs: tuple[tuple[float, float], ...]
        if lo == -1.0:
            arcs = ((math.acos(hi), TWO_PI - math.acos(hi)),)
        elif hi == 1.0:
            arcs = ((-math.acos(lo), math.acos(lo)),)
        else:
            arcs = ((math.acos(hi), math.acos(lo)), (-math.acos(lo), -math.acos(hi)))
        return CrankRange(False, arcs, tuple(singular))

    def positions(self, crank_angle_rad: np.ndarray, branch: str) -> FourBarPositions:
        """Closed-form loop closure (intersection of two circles) for the given assembly.

        Crank angles where the loop cannot close give NaN (a tolerance of 1e-10
        of b² lets round-off at a toggle through).
        """
        if branch not in BRANCHES:
            raise ValueError(f"branch must be one of {', '.join(BRANCHES)} (got {branch!r})")
        return self.assemblies(crank_angle_rad)[branch]

    def assemblies(self, crank_angle_rad: np.ndarray) -> dict[str, FourBarPositions]:
        """Both assemblies at once, by branch name (the circle intersection is shared)."""
        a, b, c, d = self.crank_m, self.coupler_m, self.rocker_m, self.ground_m
        theta2 = np.asarray(crank_angle_rad, dtype=float)
        pin_a = np.stack([a * np.cos(theta2), a * np.sin(theta2)], axis=-1)
        to_o4 = np.array([d, 0.0]) - pin_a
        s = np.hypot(to_o4[..., 0], to_o4[..., 1])
        s_safe = np.where(s > 1e-12 * d, s, np.nan)  # A on O₄: B is anywhere on a circle (undetermined)
        along = (s_safe * s_safe + b * b - c * c) / (2.0 * s_safe)
        h2 = b * b - along * along
        h = np.sqrt(np.where(h2 >= -1e-10 * b * b, np.maximum(h2, 0.0), np.nan))
        unit = to_o4 / s_safe[..., None]
        left = np.stack([-unit[..., 1], unit[..., 0]], axis=-1)
        foot = pin_a + along[..., None] * unit
        out = {}
        for branch, sign in zip(BRANCHES, (1.0, -1.0)):
            pin_b = foot + sign * h[..., None] * left
            coupler = pin_b - pin_a
            rocker = pin_b - np.array([d, 0.0])
            out[branch] = FourBarPositions(
                crank_angle=theta2,
                coupler_angle=np.arctan2(coupler[..., 1], coupler[..., 0]),
                rocker_angle=np.arctan2(rocker[..., 1], rocker[..., 0]),
                crank_pin=pin_a,
                rocker_pin=pin_b,
            )
        return out

    def rates(
        self, theta2: np.ndarray, theta3: np.ndarray, theta4: np.ndarray, omega2: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Coupler and rocker rates (rad/s) from the differentiated loop; and the singular mask.

        ``[-b sinθ₃, c sinθ₄; b cosθ₃, -c cosθ₄] [ω₃, ω₄] = [a ω₂ sinθ₂, -a ω₂ cosθ₂]``.
        """
        a, b, c = self.crank_m, self.coupler_m, self.rocker_m
        return solve_2x2(
            -b * np.sin(theta3),
            c * np.sin(theta4),
            b * np.cos(theta3),
            -c * np.cos(theta4),
            a * omega2 * np.sin(theta2),
            -a * omega2 * np.cos(theta2),
            singular_below=SINGULAR_SIN * b * c,
        )

    def accelerations(
        self,
        theta2: np.ndarray,
        theta3: np.ndarray,
        theta4: np.ndarray,
        omega2: np.ndarray,
        omega3: np.ndarray,
        omega4: np.ndarray,
        alpha2: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Coupler and rocker angular accelerations (rad/s²) from the twice-differentiated loop.

        Same matrix as :meth:`rates`; the right side collects the crank's
        acceleration and every centripetal term ``ω² × length``.
        """
        a, b, c = self.crank_m, self.coupler_m, self.rocker_m
        r1 = (
            a * alpha2 * np.sin(theta2)
            + a * omega2**2 * np.cos(theta2)
            + b * omega3**2 * np.cos(theta3)
            - c * omega4**2 * np.cos(theta4)
        )
        r2 = (
            -a * alpha2 * np.cos(theta2)
            + a * omega2**2 * np.sin(theta2)
            + b * omega3**2 * np.sin(theta3)
            - c * omega4**2 * np.sin(theta4)
        )
        alpha3, alpha4, _ = solve_2x2(
            -b * np.sin(theta3),
            c * np.sin(theta4),
            b * np.cos(theta3),
            -c * np.cos(theta4),
            r1,
            r2,
            singular_below=SINGULAR_SIN * b * c,
        )
        return alpha3, alpha4

    def transmission_angle(self, crank_angle_rad: np.ndarray) -> np.ndarray:
        """Angle μ (rad, 0…π) between coupler and rocker at B: cos μ = (b² + c² − |AO₄|²)/(2bc)."""
        a, b, c, d = self.crank_m, self.coupler_m, self.rocker_m, self.ground_m
        s2 = a * a + d * d - 2.0 * a * d * np.cos(np.asarray(crank_angle_rad, dtype=float))
        return np.arccos(np.clip((b * b + c * c - s2) / (2.0 * b * c), -1.0, 1.0))

    def loop_residual(self, positions: FourBarPositions) -> np.ndarray:
        """|a e^{iθ₂} + b e^{iθ₃} − d − c e^{iθ₄}| (m): zero when the loop closes."""
        a, b, c, d = self.crank_m, self.coupler_m, self.rocker_m, self.ground_m
        t2, t3, t4 = positions.crank_angle, positions.coupler_angle, positions.rocker_angle
        x = a * np.cos(t2) + b * np.cos(t3) - d - c * np.cos(t4)
        y = a * np.sin(t2) + b * np.sin(t3) - c * np.sin(t4)
        return np.hypot(x, y)


def coupler_point(positions: FourBarPositions, *, distance_m: float, angle_rad: float) -> np.ndarray:
    """(N, 2) position (m) of the point fixed to the coupler at ``distance_m`` from A,
    ``angle_rad`` counterclockwise from the line A→B."""
    direction = positions.coupler_angle + angle_rad
    return positions.crank_pin + distance_m * np.stack([np.cos(direction), np.sin(direction)], axis=-1)


@dataclass(frozen=True)
class FourBarState:
    """Everything at N instants: angles (rad, continuous in time), rates (rad/s),
    accelerations (rad/s²), transmission angle (rad), joints and coupler point ((N, 2), m),
    and the mask of singular instants (toggle or change point: rates undefined there)."""

    t_s: np.ndarray
    positions: FourBarPositions
    crank_angle: np.ndarray
    coupler_angle: np.ndarray
    rocker_angle: np.ndarray
    crank_rate: np.ndarray
    coupler_rate: np.ndarray
    rocker_rate: np.ndarray
    coupler_acceleration: np.ndarray
    rocker_acceleration: np.ndarray
    transmission_angle: np.ndarray
    coupler_point: np.ndarray
    singular: np.ndarray


@dataclass(frozen=True)
class FourBarMotion:
    """A four-bar driven by its crank (see :class:`CrankDrive`), kept in one assembly."""

    linkage: FourBar
    branch: str
    drive: CrankDrive
    coupler_point_m: float = 0.0
    coupler_point_rad: float = 0.0

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> FourBarMotion:
        """Build from the scene/API parameters; ValueError says why a linkage cannot move."""
        linkage = FourBar(params["ground_m"], params["crank_m"], params["coupler_m"], params["rocker_m"])
        if params["branch"] not in BRANCHES:
            raise ValueError(f"branch must be 'open' or 'crossed' (got {params['branch']!r})")
        crank_range = linkage.crank_range()
        angle0 = math.radians(params["crank_angle0_deg"])
        limits = None if crank_range.turns_fully else crank_range.arc_containing(angle0)
        if limits is not None:
            angle0 = min(max(angle0, limits[0]), limits[1])
        return cls(
            linkage,
            params["branch"],
            CrankDrive(angle0, params["crank_speed_rad_s"], limits),
            params.get("coupler_point_m", 0.0),
            math.radians(params.get("coupler_point_deg", 0.0)),
        )

    @cached_property
    def crank_range(self) -> CrankRange:
        return self.linkage.crank_range()

    @cached_property
    def _reference(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, float]:
        """Dense crank grid over one travel with unwrapped coupler and rocker angles, and their
        windings (turns) per crank turn: the reference that makes the angles continuous in time."""
        if self.drive.limits_rad is None:  # the crank turns fully
            grid = self.drive.angle0_rad + np.linspace(0.0, TWO_PI, 4097)
        else:
            grid = np.linspace(*self.drive.limits_rad, 4097)
        pos = self.linkage.positions(grid, self.branch)
        coupler = _unwrap_finite(pos.coupler_angle)
        rocker = _unwrap_finite(pos.rocker_angle)
        winding3 = round((coupler[-1] - coupler[0]) / TWO_PI) if self.drive.turns_fully else 0
        winding4 = round((rocker[-1] - rocker[0]) / TWO_PI) if self.drive.turns_fully else 0
        return grid, coupler, rocker, winding3, winding4

    def _reference_angles(self, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        grid, coupler, rocker, w3, w4 = self._reference
        if not self.drive.turns_fully:
            return np.interp(theta2, grid, coupler), np.interp(theta2, grid, rocker)
        travel = theta2 - grid[0]
        turns = np.floor(travel / TWO_PI)
        phase = grid[0] + travel - TWO_PI * turns
        return (
            np.interp(phase, grid, coupler) + TWO_PI * turns * w3,
            np.interp(phase, grid, rocker) + TWO_PI * turns * w4,
        )

    def at(self, t_s: np.ndarray) -> FourBarState:
        """The linkage at times ``t_s`` (s): closed form, no integration."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        theta2 = self.drive.angle(t)
        omega2 = self.drive.rate(t)
        alpha2 = self.drive.acceleration(t)
        pos = self.linkage.positions(theta2, self.branch)
        ref3, ref4 = self._reference_angles(theta2)
        theta3 = continuous_angle(pos.coupler_angle, ref3)
        theta4 = continuous_angle(pos.rocker_angle, ref4)
        omega3, omega4, singular = self.linkage.rates(theta2, theta3, theta4, omega2)
        alpha3, alpha4 = self.linkage.accelerations(theta2, theta3, theta4, omega2, omega3, omega4, alpha2)
        return FourBarState(
            t_s=t,
            positions=pos,
            crank_angle=theta2,
            coupler_angle=theta3,
            rocker_angle=theta4,
            crank_rate=omega2,
            coupler_rate=omega3,
            rocker_rate=omega4,
            coupler_acceleration=alpha3,
            rocker_acceleration=alpha4,
            transmission_angle=self.linkage.transmission_angle(theta2),
            coupler_point=coupler_point(pos, distance_m=self.coupler_point_m, angle_rad=self.coupler_point_rad),
            singular=singular | ~np.isfinite(theta3),
        )

    def events(self, t_end_s: float) -> list[Event]:
        """Toggle positions (crank reversals) and change points passed in ``[0, t_end_s]``."""
        events = []
        for t, angle in self.drive.reversal_times(t_end_s):
            events.append(
                Event(
                    t,
                    "toggle",
                    (
                        f"toggle position at crank angle {math.degrees(angle):.1f}°: the coupler and rocker are "
                        "in line, so the "
                        "rocker rate is unbounded here; the crank cannot turn further, so it reverses and the "
                        "linkage stays "
                        f"in the {self.branch} assembly"
                    ),
                )
            )
        for angle in self.crank_range.singular_angles_rad:
            for t in self.drive.times_at_angle(angle, t_end_s):
                events.append(
                    Event(
                        t,
                        "change-point",
                        (
                            f"change point at crank angle {math.degrees(angle):.1f}°: all four links are in "
                            "line, so the coupler "
                            "and rocker rates are undefined (0/0) and the linkage could switch assembly; this "
                            "motion stays in "
                            f"the {self.branch} assembly"
                        ),
                    )
                )
        return sorted(events, key=lambda e: e.t_s)

    def travel_positions(self, branch: str | None = None, samples: int = 721) -> FourBarPositions:
        """Configurations at ``samples`` crank angles spanning the crank's whole travel, in ``branch``."""
        if self.drive.limits_rad is None:  # the crank turns fully
            grid = np.linspace(0.0, TWO_PI, samples)
        else:
            grid = np.linspace(*self.drive.limits_rad, samples)
        return self.linkage.positions(grid, branch or self.branch)

    def coupler_curve(self, branch: str | None = None, samples: int = 721) -> np.ndarray:
        """(samples, 2) path (m) of the coupler point over the crank's whole travel in ``branch``."""
        pos = self.travel_positions(branch, samples)
        return coupler_point(pos, distance_m=self.coupler_point_m, angle_rad=self.coupler_point_rad)

    @property
    def other_branch(self) -> str:
        return BRANCHES[1 - BRANCHES.index(self.branch)]


def _unwrap_finite(angles: np.ndarray) -> np.ndarray:
    """np.unwrap that skips NaN samples (an undetermined configuration) by interpolating over them."""
    finite = np.isfinite(angles)
    if finite.all():
        return np.unwrap(angles)
    index = np.arange(len(angles))
    filled = np.interp(index, index[finite], np.unwrap(angles[finite]))
    return filled


def _check(params: Mapping[str, Any]) -> None:
    FourBarMotion.from_params(params)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "ground_m",
            "m",
            1.0,
            0.05,
            20.0,
            "Ground link d: distance between the two fixed pivots O₂ and O₄",
            "ground d",
            step=0.01,
        ),
        Parameter("crank_m", "m", 0.3, 0.05, 20.0, "Crank a (O₂A), the driven input link", "crank a", step=0.01),
        Parameter("coupler_m", "m", 1.0, 0.05, 20.0, "Coupler b (AB), the floating link", "coupler b", step=0.01),
        Parameter("rocker_m", "m", 0.9, 0.05, 20.0, "Rocker c (O₄B), the output link", "rocker c", step=0.01),
        Parameter(
            "crank_speed_rad_s",
            "rad/s",
            1.5,
            -10.0,
            10.0,
            "Constant crank speed ω₂ (counterclockwise positive)",
            "ω₂",
            step=0.05,
        ),
        Parameter(
            "crank_angle0_deg",
            "deg",
            60.0,
            -180.0,
            180.0,
            "Crank angle θ₂ at t = 0, from the ground line",
            "θ₂(0)",
            step=1,
        ),
        Parameter(
            "branch",
            "",
            "open",
            description="Assembly: B left (open) or right (crossed) of the line from A to O₄",
            label="assembly",
            kind="choice",
            choices=BRANCHES,
        ),
        Parameter(
            "coupler_point_m", "m", 0.6, 0.0, 20.0, "Distance of the traced coupler point P from A", "AP", step=0.01
        ),
        Parameter(
            "coupler_point_deg",
            "deg",
            40.0,
            -180.0,
            180.0,
            "Angle of AP from the coupler line AB (counterclockwise)",
            "∠BAP",
            step=1,
        ),
    ),
    check=_check,
)


class FourBarLinkage(ClosedFormModel):
    """Four-bar linkage driven by a constant-speed crank, evaluated by loop closure at each instant."""

    parameters = PARAMETERS
    series_units = {
        "crank_angle": "rad",
        "coupler_angle": "rad",
        "rocker_angle": "rad",
        "crank_rate": "rad/s",
        "coupler_rate": "rad/s",
        "rocker_rate": "rad/s",
        "coupler_acceleration": "rad/s²",
        "rocker_acceleration": "rad/s²",
        "transmission_angle": "rad",
        "coupler_point_x": "m",
        "coupler_point_y": "m",
    }
    invariant_units = {"loop_closure_residual": "m"}
    description = (
        "loop closure (two-circle intersection) for positions; differentiated loop equations (2×2 "
        "linear solves) for rates"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = FourBarMotion.from_params(params)
        state = motion.at(t_s)
        series = {name: getattr(state, name) for name in self.series_units if hasattr(state, name)}
        series["coupler_point_x"] = state.coupler_point[:, 0]
        series["coupler_point_y"] = state.coupler_point[:, 1]
        residual = motion.linkage.loop_residual(state.positions)
        return ClosedFormSolution(series, {"loop_closure_residual": residual}, motion.events(float(np.max(t_s))))

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        """The residual is measured against the ground length (its natural size)."""
        return {"loop_closure_residual": float(params["ground_m"])}
