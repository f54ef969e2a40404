"""The time derivative of one vector seen from a fixed frame and from a rotating frame.

Frames, all closed forms in time ``t`` (s):

* the fixed frame XYZ, +Z up;
* the rotating frame xyz turns at the constant rate ``Ω`` about the fixed unit axis
  ``n = (sin β, 0, cos β)`` (tilted by β from Z towards X):
  ``R_world_frame(t) = Rodrigues(n, Ω t)``, so ``ω = Ω n`` (rad/s) in both frames' components;
* the vector ``A`` (m) is given by its components in xyz: length
  ``L(t) = L₀ + a sin 2π f t`` along the direction at elevation ``e`` above the xy plane
  and azimuth ``ψ = ψ̇ t`` about z:
  ``{A}_xyz = L (cos e cos ψ, cos e sin ψ, sin e)``.

Then ``(dA/dt)_fixed = (dA/dt)_rel + ω × A`` (m/s, world components), where
``(dA/dt)_rel = [R] d{A}_xyz/dt`` is the rate an observer riding with xyz sees.
:meth:`VectorMotion.vector_world` composes ``A`` without any derivative, which is
what the tests differentiate numerically to check the formula.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import matrix_from_axis_angle, quaternion_from_axis_angle

#: The three rates, in the order they are drawn head to tail from A's tip (the fixed-frame rate closes them).
TERM_NAMES = ("relative", "transport", "fixed")
TERM_LABELS = {
    "relative": "(dA/dt)_rel, seen riding with xyz",
    "transport": "ω × A, carried round by the frame",
    "fixed": "(dA/dt)_fixed, seen from XYZ",
}


def _check(values: Mapping[str, Any]) -> None:
    if values["stretch_amplitude_m"] >= values["length_m"]:
        raise ParameterError(
            "stretch_amplitude_m",
            f"the stretch amplitude a = {values['stretch_amplitude_m']:.3g} m must be smaller than the length "
            f"L₀ = {values['length_m']:.3g} m, or A would shrink through zero",
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "frame_rate_rad_s",
            "rad/s",
            0.8,
            -3.0,
            3.0,
            "Rate Ω at which the frame xyz turns about its axis",
            "frame rate Ω",
            step=0.05,
        ),
        Parameter(
            "frame_axis_tilt_deg",
            "deg",
            20.0,
            0.0,
            90.0,
            "Tilt β of the frame's turning axis from Z towards X",
            "axis tilt β",
            step=1.0,
        ),
        Parameter("length_m", "m", 1.0, 0.2, 2.0, "Mean length L₀ of the vector A", "length L₀", step=0.05),
        Parameter(
            "stretch_amplitude_m", "m", 0.3, 0.0, 1.9, "Amplitude a of the change of A's length", "stretch a", step=0.01
        ),
        Parameter(
            "stretch_frequency_hz",
            "Hz",
            0.2,
            0.0,
            2.0,
            "Frequency f of the change of A's length",
            "stretch frequency f",
            step=0.01,
        ),
        Parameter(
            "relative_turn_rate_rad_s",
            "rad/s",
            0.5,
            -3.0,
            3.0,
            "Rate ψ̇ at which A turns about z relative to the frame xyz",
            "turn in the frame ψ̇",
            step=0.05,
        ),
        Parameter(
            "elevation_deg",
            "deg",
            30.0,
            -80.0,
            80.0,
            "Elevation e of A above the frame's xy plane",
            "elevation e",
            step=1.0,
        ),
    ),
    check=_check,
)


@dataclass(frozen=True)
class VectorMotion:
    """The rotating frame and the vector A in it (see the module docstring)."""

    frame_rate_rad_s: float
    frame_axis_world: np.ndarray
    length_m: float
    stretch_amplitude_m: float
    stretch_frequency_hz: float
    relative_turn_rate_rad_s: float
    elevation_rad: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> VectorMotion:
        tilt = math.radians(params["frame_axis_tilt_deg"])
        return cls(
            frame_rate_rad_s=params["frame_rate_rad_s"],
            frame_axis_world=np.array([math.sin(tilt), 0.0, math.cos(tilt)]),
            length_m=params["length_m"],
            stretch_amplitude_m=params["stretch_amplitude_m"],
            stretch_frequency_hz=params["stretch_frequency_hz"],
            relative_turn_rate_rad_s=params["relative_turn_rate_rad_s"],
            elevation_rad=math.radians(params["elevation_deg"]),
        )

    @property
    def omega_world_rad_s(self) -> np.ndarray:
        """ω = Ω n (rad/s, world components, (3,)); constant, and equal to its xyz components."""
        return self.frame_rate_rad_s * self.frame_axis_world

    def frame_angle_rad(self, t_s: np.ndarray) -> np.ndarray:
        return self.frame_rate_rad_s * np.atleast_1d(np.asarray(t_s, dtype=float))

    def attitude(self, t_s: np.ndarray) -> np.ndarray:
        """``R_world_frame`` (N, 3, 3): the frame turned by Ω t about n."""
        return matrix_from_axis_angle(self.frame_axis_world, self.frame_angle_rad(t_s))

    def attitude_wxyz(self, t_s: np.ndarray) -> np.ndarray:
        """``q_world_frame`` (N, 4)."""
        return quaternion_from_axis_angle(self.frame_axis_world, self.frame_angle_rad(t_s))

    def vector_frame(self, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``{A}_xyz`` (m) and its rate ``d{A}_xyz/dt`` (m/s), each (N, 3), components on xyz."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        w = 2.0 * math.pi * self.stretch_frequency_hz
        length = self.length_m + self.stretch_amplitude_m * np.sin(w * t)
        length_rate = self.stretch_amplitude_m * w * np.cos(w * t)
        psi = self.relative_turn_rate_rad_s * t
        ce, se = math.cos(self.elevation_rad), math.sin(self.elevation_rad)
        direction = np.stack([ce * np.cos(psi), ce * np.sin(psi), np.full_like(psi, se)], axis=-1)
        direction_rate = self.relative_turn_rate_rad_s * np.stack(
            [-ce * np.sin(psi), ce * np.cos(psi), np.zeros_like(psi)], axis=-1
        )
        return length[:, None] * direction, length_rate[:, None] * direction + length[:, None] * direction_rate

    def vector_world(self, t_s: np.ndarray) -> np.ndarray:
        """``{A}_XYZ = [R] {A}_xyz`` (m, (N, 3)): composed, no derivative taken."""
        vector, _ = self.vector_frame(t_s)
        return np.einsum("nij,nj->ni", self.attitude(t_s), vector)

    def rates(self, t_s: np.ndarray) -> VectorRates:
        """A and the three rates at times ``t_s``, each computed once."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        R = self.attitude(t)
        vector_frame, rate_frame = self.vector_frame(t)
        vector = np.einsum("nij,nj->ni", R, vector_frame)
        relative = np.einsum("nij,nj->ni", R, rate_frame)
        transport = np.cross(self.omega_world_rad_s, vector)
        return VectorRates(
            t_s=t,
            attitude_wxyz=self.attitude_wxyz(t),
            vector_frame_m=vector_frame,
            vector_world_m=vector,
            rate_frame_m_s=rate_frame,
            terms_m_s={"relative": relative, "transport": transport, "fixed": relative + transport},
        )


@dataclass(frozen=True)
class VectorRates:
    """A and its rates at N instants: ``vector_frame_m`` and ``rate_frame_m_s`` on xyz, the rest on XYZ.

    ``terms_m_s`` maps ``relative``, ``transport`` (ω × A) and ``fixed`` to (N, 3) arrays (m/s).
    """

    t_s: np.ndarray
    attitude_wxyz: np.ndarray
    vector_frame_m: np.ndarray
    vector_world_m: np.ndarray
    rate_frame_m_s: np.ndarray
    terms_m_s: dict[str, np.ndarray]


class VectorDerivative(ClosedFormModel):
    """A vector moving in a turning frame; its rate from both frames, in closed form."""

    parameters = PARAMETERS
    description = "closed-form kinematics: (dA/dt)_fixed = (dA/dt)_rel + ω × A"
    series_units = {
        **{f"A_{c}": "m" for c in "xyz"},
        **{f"dA_{name}_{c}": "m/s" for name in TERM_NAMES for c in "xyz"},
    }

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        rates = VectorMotion.from_params(params).rates(t_s)
        vectors = {"A": rates.vector_world_m, **{f"dA_{name}": value for name, value in rates.terms_m_s.items()}}
        series = {f"{name}_{c}": value[:, i] for name, value in vectors.items() for i, c in enumerate("xyz")}
        return ClosedFormSolution(series=series)
