"""The input crank's angle in time: a full turn at constant rate, or rocking between two limits.

A motor turns the crank at a constant angular speed. When the linkage lets the
crank turn all the way round, its angle is ``angle0 + speed·t``. When the loop
only closes over an arc ``[lower, upper]`` of crank angles (a non-Grashof
linkage, say), the crank sweeps that arc at the same constant speed and
reverses at each end, so its angle is a triangle wave in time. The reversal is
instantaneous (an idealisation): the rate flips sign and the acceleration is
zero everywhere else.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.systems.ch04.planar_loop import TWO_PI


@dataclass(frozen=True)
class CrankDrive:
    """Crank angle (rad, from the ground line, counterclockwise) as a function of time (s).

    ``limits_rad`` is ``None`` for a crank that turns fully, else ``(lower,
    upper)`` with ``lower <= angle0_rad <= upper`` (rad). ``speed_rad_s`` is
    signed: positive turns counterclockwise first.
    """

    angle0_rad: float
    speed_rad_s: float
    limits_rad: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.angle0_rad) and math.isfinite(self.speed_rad_s)):
            raise ValueError("the crank's start angle and speed must be finite numbers")
        if self.limits_rad is not None:
            lower, upper = self.limits_rad
            if not lower < upper:
                raise ValueError("the crank's angle limits must satisfy lower < upper")
            if not lower - 1e-12 <= self.angle0_rad <= upper + 1e-12:
                raise ValueError("the crank must start between its angle limits")

    @property
    def turns_fully(self) -> bool:
        return self.limits_rad is None

    @property
    def period_s(self) -> float:
        """Time (s) after which the crank's motion repeats (inf when it stands still)."""
        if self.speed_rad_s == 0.0:
            return math.inf
        travel = TWO_PI if self.limits_rad is None else 2.0 * (self.limits_rad[1] - self.limits_rad[0])
        return travel / abs(self.speed_rad_s)

    def _unfolded(self, t_s: np.ndarray) -> np.ndarray:
        """Distance (rad) travelled along the arc from its lower end, before folding."""
        assert self.limits_rad is not None
        return (self.angle0_rad - self.limits_rad[0]) + self.speed_rad_s * np.asarray(t_s, dtype=float)

    def angle(self, t_s: np.ndarray) -> np.ndarray:
        """Crank angle (rad) at times ``t_s`` (s); continuous (not wrapped) for a full turn."""
        t = np.asarray(t_s, dtype=float)
        if self.limits_rad is None:
            return self.angle0_rad + self.speed_rad_s * t
        lower, upper = self.limits_rad
        width = upper - lower
        folded = np.mod(self._unfolded(t), 2.0 * width)
        return lower + width - np.abs(folded - width)

    def rate(self, t_s: np.ndarray) -> np.ndarray:
        """Crank angular velocity (rad/s); at a reversal instant, the rate it leaves with."""
        t = np.asarray(t_s, dtype=float)
        if self.limits_rad is None or self.speed_rad_s == 0.0:
            return np.full(t.shape, self.speed_rad_s)
        width = self.limits_rad[1] - self.limits_rad[0]
        folded = np.mod(self._unfolded(t), 2.0 * width)
        # d(angle)/d(unfolded travel) is +1 on the ascending half of the fold and -1 on the other.
        rate = self.speed_rad_s * np.where(folded < width, 1.0, -1.0)
        # Within round-off of an end, the crank leaves it inwards: up from the lower end, down from the upper.
        tol = 1e-12 * width
        rate = np.where((folded < tol) | (folded > 2.0 * width - tol), abs(self.speed_rad_s), rate)
        return np.where(np.abs(folded - width) < tol, -abs(self.speed_rad_s), rate)

    def acceleration(self, t_s: np.ndarray) -> np.ndarray:
        """Crank angular acceleration (rad/s²): zero (constant speed; reversals are instantaneous)."""
        return np.zeros(np.asarray(t_s, dtype=float).shape)

    def reversal_times(self, t_end_s: float) -> list[tuple[float, float]]:
        """``(t_s, crank_angle_rad)`` of every reversal in ``[0, t_end_s]`` (none for a full turn)."""
        if self.limits_rad is None or self.speed_rad_s == 0.0:
            return []
        lower, upper = self.limits_rad
        width = upper - lower
        u0 = self.angle0_rad - lower
        # Reversals where the unfolded travel is a multiple of the arc width.
        ks = np.arange(
            math.ceil(min(u0, u0 + self.speed_rad_s * t_end_s) / width - 1e-12),
            math.floor(max(u0, u0 + self.speed_rad_s * t_end_s) / width + 1e-12) + 1,
        )
        out = []
        for k in ks:
            t = (k * width - u0) / self.speed_rad_s
            if -1e-12 <= t <= t_end_s + 1e-12:
                out.append((max(float(t), 0.0), lower if k % 2 == 0 else upper))
        return sorted(out)

    def times_at_angle(self, angle_rad: float, t_end_s: float) -> list[float]:
        """Times (s) in ``[0, t_end_s]`` when the crank passes ``angle_rad`` (taken modulo 2π)."""
        if self.speed_rad_s == 0.0:
            return []
        if self.limits_rad is None:
            end = self.angle0_rad + self.speed_rad_s * t_end_s
            lo, hi = min(self.angle0_rad, end), max(self.angle0_rad, end)
            ks = range(math.ceil((lo - angle_rad) / TWO_PI - 1e-12), math.floor((hi - angle_rad) / TWO_PI + 1e-12) + 1)
            return sorted(max(0.0, (angle_rad + TWO_PI * k - self.angle0_rad) / self.speed_rad_s) for k in ks)
        lower, upper = self.limits_rad
        width = upper - lower
        offset = (angle_rad - lower) % TWO_PI
        if offset > width + 1e-12:
            return []
        # The unfolded travel passes this angle at offset + 2Wk (going up) and 2W - offset + 2Wk (coming down).
        u0 = self.angle0_rad - lower
        u1 = u0 + self.speed_rad_s * t_end_s
        lo, hi = min(u0, u1), max(u0, u1)
        times = set()
        for base in (offset, 2.0 * width - offset):
            for k in range(
                math.ceil((lo - base) / (2 * width) - 1e-12), math.floor((hi - base) / (2 * width) + 1e-12) + 1
            ):
                times.add(round(max(0.0, (base + 2 * width * k - u0) / self.speed_rad_s), 12))
        return sorted(t for t in times if t <= t_end_s + 1e-12)
