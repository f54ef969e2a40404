"""A collar sliding along an arm that turns in the horizontal plane: a mixed description.

Frame: the fixed frame XYZ, +Z up; the arm turns about Z through the pivot at
the origin, in the plane z = 0. Lengths in m, angles in rad, time t in s.

The motion is given in two parts, each a closed form:

* the arm's angle from +X toward +Y: θ(t) = Ω t + ½ α t² (θ̇ = Ω + α t, θ̈ = α);
* the collar's position along the arm, measured from the pivot along the arm's
  unit vector e_r: r(t) = r₀ + b sin(ω_c t). A negative r puts the collar on the
  arm's other half, beyond the pivot.

The unit vectors ride on the arm, e_r = (cos θ, sin θ, 0) and
e_θ = (−sin θ, cos θ, 0), so they are defined even when the collar passes
through the pivot (r = 0), unlike the polar unit vectors of the collar's own
position. The collar's velocity and acceleration are::

    v = ṙ e_r + r θ̇ e_θ
    a = (r̈ − r θ̇²) e_r + (r θ̈ + 2 ṙ θ̇) e_θ

with four named terms: r̈ (sliding along the arm), −r θ̇² (centripetal),
r θ̈ (the arm's angular acceleration) and 2 ṙ θ̇ (Coriolis). The path variables
follow from v and a: speed |v|, a_t = v·a/|v|, a_n = |v × a|/|v|.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

#: The arm reaches this far (m) each side of the pivot.
ARM_HALF_LENGTH_M = 2.0
#: One run of the scene (s): after it the motion starts again from t = 0.
RUN_S = 4.0 * math.pi


@dataclass(frozen=True)
class ArmState:
    """The collar at N instants: arm angle and rates, position along the arm and rates, the terms of v and a.

    ``e_r``, ``e_theta`` (N, 3): the arm's unit vectors on XYZ. Terms (N,) in m/s²:
    ``sliding`` r̈, ``centripetal`` −r θ̇², ``angular`` r θ̈, ``coriolis`` 2 ṙ θ̇.
    """

    t_s: np.ndarray
    theta_rad: np.ndarray
    theta_dot_rad_s: np.ndarray
    theta_ddot_rad_s2: np.ndarray
    r_m: np.ndarray
    r_dot_m_s: np.ndarray
    r_ddot_m_s2: np.ndarray
    e_r: np.ndarray
    e_theta: np.ndarray

    @property
    def position_m(self) -> np.ndarray:
        return self.r_m[:, None] * self.e_r

    @property
    def v_radial_m_s(self) -> np.ndarray:
        return self.r_dot_m_s

    @property
    def v_transverse_m_s(self) -> np.ndarray:
        return self.r_m * self.theta_dot_rad_s

    @property
    def sliding_m_s2(self) -> np.ndarray:
        return self.r_ddot_m_s2

    @property
    def centripetal_m_s2(self) -> np.ndarray:
        return -self.r_m * self.theta_dot_rad_s**2

    @property
    def angular_m_s2(self) -> np.ndarray:
        return self.r_m * self.theta_ddot_rad_s2

    @property
    def coriolis_m_s2(self) -> np.ndarray:
        return 2.0 * self.r_dot_m_s * self.theta_dot_rad_s

    @property
    def a_radial_m_s2(self) -> np.ndarray:
        return self.sliding_m_s2 + self.centripetal_m_s2

    @property
    def a_transverse_m_s2(self) -> np.ndarray:
        return self.angular_m_s2 + self.coriolis_m_s2

    @property
    def velocity_m_s(self) -> np.ndarray:
        """v on XYZ (N, 3), m/s."""
        return self.v_radial_m_s[:, None] * self.e_r + self.v_transverse_m_s[:, None] * self.e_theta

    @property
    def acceleration_m_s2(self) -> np.ndarray:
        """a on XYZ (N, 3), m/s²."""
        return self.a_radial_m_s2[:, None] * self.e_r + self.a_transverse_m_s2[:, None] * self.e_theta

    def path_variables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Speed (m/s), a_t and a_n (m/s²); a_t and a_n are NaN where the collar is at rest."""
        v, a = self.velocity_m_s, self.acceleration_m_s2
        speed = np.linalg.norm(v, axis=1)
        moving = speed > 1e-12 * (1.0 + np.linalg.norm(a, axis=1))
        with np.errstate(all="ignore"):
            a_t = np.where(moving, np.einsum("ij,ij->i", v, a) / speed, np.nan)
            a_n = np.where(moving, np.abs(np.cross(v, a)[:, 2]) / speed, np.nan)
        return speed, a_t, a_n


@dataclass(frozen=True)
class RotatingArm:
    """Arm rate Ω (rad/s) and angular acceleration α (rad/s²); collar r = r₀ + b sin(ω_c t) (m)."""

    arm_rate_rad_s: float
    arm_acceleration_rad_s2: float
    collar_mean_m: float
    collar_amplitude_m: float
    collar_frequency_rad_s: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> RotatingArm:
        return cls(
            params["arm_rate_rad_s"],
            params["arm_acceleration_rad_s2"],
            params["collar_mean_m"],
            params["collar_amplitude_m"],
            params["collar_frequency_rad_s"],
        )

    def at(self, t_s: np.ndarray | float) -> ArmState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        omega, alpha = self.arm_rate_rad_s, self.arm_acceleration_rad_s2
        b, w = self.collar_amplitude_m, self.collar_frequency_rad_s
        theta = omega * t + 0.5 * alpha * t**2
        zeros = np.zeros_like(t)
        c, s = np.cos(theta), np.sin(theta)
        return ArmState(
            t_s=t,
            theta_rad=theta,
            theta_dot_rad_s=omega + alpha * t,
            theta_ddot_rad_s2=np.full_like(t, alpha),
            r_m=self.collar_mean_m + b * np.sin(w * t),
            r_dot_m_s=b * w * np.cos(w * t),
            r_ddot_m_s2=-b * w**2 * np.sin(w * t),
            e_r=np.stack([c, s, zeros], axis=1),
            e_theta=np.stack([-s, c, zeros], axis=1),
        )


def _check(values: Mapping[str, Any]) -> None:
    reach = abs(values["collar_mean_m"]) + values["collar_amplitude_m"]
    if reach > ARM_HALF_LENGTH_M:
        raise ParameterError(
            "collar_amplitude_m",
            f"the collar would slide off the arm: |r₀| + b = {reach:g} m, but the arm reaches "
            f"{ARM_HALF_LENGTH_M:g} m each side of the pivot",
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "arm_rate_rad_s", "rad/s", 1.0, -3.0, 3.0, "Ω: the arm's angular velocity θ̇ at t = 0", "Ω", step=0.05
        ),
        Parameter(
            "arm_acceleration_rad_s2",
            "rad/s²",
            0.0,
            -0.3,
            0.3,
            "α: the arm's constant angular acceleration θ̈",
            "α",
            step=0.01,
        ),
        Parameter(
            "collar_mean_m",
            "m",
            0.8,
            -1.5,
            1.5,
            "r₀: the collar's middle position along the arm, from the pivot",
            "r₀",
            step=0.01,
        ),
        Parameter(
            "collar_amplitude_m", "m", 0.6, 0.0, 1.5, "b: how far the collar slides each way from r₀", "b", step=0.01
        ),
        Parameter(
            "collar_frequency_rad_s",
            "rad/s",
            1.5,
            0.0,
            5.0,
            "ω_c: the angular frequency of the collar's sliding, r = r₀ + b sin(ω_c t)",
            "ω_c",
            step=0.05,
        ),
    ),
    check=_check,
)


class CollarOnRotatingArm(ClosedFormModel):
    """A collar sliding along a turning arm: polar components of v and a, each term of a, and path variables."""

    parameters = PARAMETERS
    series_units = {
        "theta": "rad",
        "theta_dot": "rad/s",
        "r": "m",
        "r_dot": "m/s",
        "v_r": "m/s",
        "v_theta": "m/s",
        "a_r": "m/s^2",
        "a_theta": "m/s^2",
        "a_sliding": "m/s^2",
        "a_centripetal": "m/s^2",
        "a_angular": "m/s^2",
        "a_coriolis": "m/s^2",
        "speed": "m/s",
        "a_tangential": "m/s^2",
        "a_normal": "m/s^2",
    }
    description = (
        "θ = Ω t + α t²/2 and r = r₀ + b sin(ω_c t) in closed form; v and a from the polar formulas on "
        "the arm's unit vectors"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        state = RotatingArm.from_params(params).at(t_s)
        speed, a_t, a_n = state.path_variables()
        series = {
            "theta": state.theta_rad,
            "theta_dot": state.theta_dot_rad_s,
            "r": state.r_m,
            "r_dot": state.r_dot_m_s,
            "v_r": state.v_radial_m_s,
            "v_theta": state.v_transverse_m_s,
            "a_r": state.a_radial_m_s2,
            "a_theta": state.a_transverse_m_s2,
            "a_sliding": state.sliding_m_s2,
            "a_centripetal": state.centripetal_m_s2,
            "a_angular": state.angular_m_s2,
            "a_coriolis": state.coriolis_m_s2,
            "speed": speed,
            "a_tangential": a_t,
            "a_normal": a_n,
        }
        warning = ""
        if np.any(np.isnan(a_t)):
            warning = (
                "The collar is momentarily at rest at some frames: a_t and a_n (the path variables) are "
                "undefined there (null)."
            )
        return ClosedFormSolution(series=series, warning=warning)
