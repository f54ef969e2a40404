"""Acceleration of a point that moves on a moving body: the five terms of the moving-frame formula.

The body is a turntable (a disc of radius ``table_radius_m``) carried by a cart.
Frames and motion, all closed forms in time ``t`` (s):

* world frame XYZ, +Z up;
* the table's centre O rides on the cart, which shakes along world X:
  ``r_O = (A_c sin 2π f_c t, 0, H)``;
* the table's attitude is ``R_world_body = Rz(Ω_p t) · Rx(β) · Rz(θ(t))``: it spins
  about its own axis (body z) through ``θ = ω₀ t + ½ α₀ t²``, and that axis,
  tilted by β from the vertical, precesses about world Z at the constant rate Ω_p;
* the point P is a slider in a straight groove cut along body x at a distance d
  from the centre: ``r_P/O = (s(t), d, 0)`` in body axes with
  ``s = A_s sin 2π f_s t``.

The body's angular velocity and acceleration (world components) are
``ω = Ω_p Z + θ̇ k`` and ``α = θ̈ k + θ̇ Ω_p Z × k``, where ``k`` is the spin axis;
so α is not parallel to ω when the axis precesses. The acceleration of P is

``a_P = a_O + α × r + ω × (ω × r) + 2 ω × v_rel + a_rel``

with ``r = r_P/O`` and ``v_rel``, ``a_rel`` the slider's velocity and acceleration
relative to the table (world components). :func:`acceleration_terms` returns each
term; :func:`position_world` composes the motion directly (no derivatives), which
is what the tests differentiate numerically to check the formula.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import matrix_from_angles, quaternion_from_angles

#: Height of the table's centre above the floor (m): where the cart carries it.
TABLE_HEIGHT_M = 0.8

#: The five terms in the order they are drawn head to tail, with the words a lesson uses.
TERM_NAMES = ("reference", "angular", "centripetal", "coriolis", "relative")
TERM_LABELS = {
    "reference": "a_O (reference point)",
    "angular": "α × r (angular acceleration)",
    "centripetal": "ω × (ω × r) (centripetal)",
    "coriolis": "2 ω × v_rel (Coriolis)",
    "relative": "a_rel (relative)",
    "total": "a_P (absolute)",
}


def _check(values: Mapping[str, Any]) -> None:
    reach = math.hypot(values["slider_amplitude_m"], values["groove_offset_m"])
    if reach > values["table_radius_m"] * (1.0 + 1e-12):
        raise ParameterError(
            "slider_amplitude_m",
            f"the slider would leave the table: at the ends of its stroke it is {reach:.3g} m from the centre "
            f"(√(amplitude² + groove offset²)), more than the table radius {values['table_radius_m']:.3g} m",
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "spin_rate_rad_s",
            "rad/s",
            1.0,
            -6.0,
            6.0,
            "Spin rate θ̇ of the table about its own axis at t = 0",
            "spin ω₀",
            step=0.05,
        ),
        Parameter(
            "spin_acceleration_rad_s2",
            "rad/s²",
            0.0,
            -2.0,
            2.0,
            "Constant spin acceleration θ̈ of the table",
            "spin-up α₀",
            step=0.02,
        ),
        Parameter(
            "tilt_deg", "deg", 0.0, 0.0, 60.0, "Tilt β of the table's axis from the vertical", "axis tilt β", step=0.5
        ),
        Parameter(
            "precession_rate_rad_s",
            "rad/s",
            0.0,
            -3.0,
            3.0,
            "Rate Ω_p at which the tilted axis turns about the vertical",
            "axis precession Ω_p",
            step=0.05,
        ),
        Parameter("table_radius_m", "m", 1.0, 0.2, 3.0, "Radius of the turntable", "table radius", step=0.05),
        Parameter(
            "groove_offset_m",
            "m",
            0.3,
            -2.0,
            2.0,
            "Distance d of the straight groove from the table's centre (0: a radial groove)",
            "groove offset d",
            step=0.01,
        ),
        Parameter(
            "slider_amplitude_m",
            "m",
            0.6,
            0.0,
            3.0,
            "Amplitude A_s of the slider's oscillation along the groove",
            "slider amplitude",
            step=0.01,
        ),
        Parameter(
            "slider_frequency_hz",
            "Hz",
            0.25,
            0.0,
            2.0,
            "Frequency f_s of the slider's oscillation along the groove",
            "slider frequency",
            step=0.01,
        ),
        Parameter(
            "cart_amplitude_m",
            "m",
            0.0,
            0.0,
            2.0,
            "Amplitude A_c of the cart's shaking along world X",
            "cart amplitude",
            step=0.01,
        ),
        Parameter(
            "cart_frequency_hz", "Hz", 0.0, 0.0, 2.0, "Frequency f_c of the cart's shaking", "cart frequency", step=0.01
        ),
    ),
    check=_check,
)


@dataclass(frozen=True)
class MovingFrameMotion:
    """The turntable's motion and the slider's motion on it (see the module docstring)."""

    spin_rate_rad_s: float
    spin_acceleration_rad_s2: float
    tilt_rad: float
    precession_rate_rad_s: float
    groove_offset_m: float
    slider_amplitude_m: float
    slider_frequency_hz: float
    cart_amplitude_m: float
    cart_frequency_hz: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> MovingFrameMotion:
        return cls(
            spin_rate_rad_s=params["spin_rate_rad_s"],
            spin_acceleration_rad_s2=params["spin_acceleration_rad_s2"],
            tilt_rad=math.radians(params["tilt_deg"]),
            precession_rate_rad_s=params["precession_rate_rad_s"],
            groove_offset_m=params["groove_offset_m"],
            slider_amplitude_m=params["slider_amplitude_m"],
            slider_frequency_hz=params["slider_frequency_hz"],
            cart_amplitude_m=params["cart_amplitude_m"],
            cart_frequency_hz=params["cart_frequency_hz"],
        )

    # -- the body: attitude, angular velocity and acceleration ------------------------
    def spin_angle_rad(self, t_s: np.ndarray) -> np.ndarray:
        t = np.asarray(t_s, dtype=float)
        return self.spin_rate_rad_s * t + 0.5 * self.spin_acceleration_rad_s2 * t * t

    def spin_rate_now_rad_s(self, t_s: np.ndarray) -> np.ndarray:
        return self.spin_rate_rad_s + self.spin_acceleration_rad_s2 * np.asarray(t_s, dtype=float)

    def euler_313_angles(self, t_s: np.ndarray) -> np.ndarray:
        """3-1-3 angles (Ω_p t, β, θ(t)) in rad, shape (N, 3): precession, tilt, spin."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        return np.stack(
            [self.precession_rate_rad_s * t, np.full_like(t, self.tilt_rad), self.spin_angle_rad(t)], axis=-1
        )

    def attitude(self, t_s: np.ndarray) -> np.ndarray:
        """``R_world_body`` at times ``t_s`` (shape (N, 3, 3)): Rz(Ω_p t) Rx(β) Rz(θ)."""
        return matrix_from_angles(self.euler_313_angles(t_s), "3-1-3")

    def spin_axis_world(self, t_s: np.ndarray) -> np.ndarray:
        """Unit spin axis k (body z) in world components, shape (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        phi = self.precession_rate_rad_s * t
        sb, cb = math.sin(self.tilt_rad), math.cos(self.tilt_rad)
        return np.stack([sb * np.sin(phi), -sb * np.cos(phi), np.full_like(phi, cb)], axis=-1)

    def angular_velocity_world(self, t_s: np.ndarray) -> np.ndarray:
        """ω = Ω_p Z + θ̇ k (rad/s, world), shape (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        omega = self.spin_rate_now_rad_s(t)[:, None] * self.spin_axis_world(t)
        omega[:, 2] += self.precession_rate_rad_s
        return omega

    def angular_acceleration_world(self, t_s: np.ndarray) -> np.ndarray:
        """α = θ̈ k + θ̇ (Ω_p Z × k) (rad/s², world), shape (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        k = self.spin_axis_world(t)
        k_dot = self.precession_rate_rad_s * np.cross([0.0, 0.0, 1.0], k)
        return self.spin_acceleration_rad_s2 * k + self.spin_rate_now_rad_s(t)[:, None] * k_dot

    # -- the reference point O (the cart) ----------------------------------------------
    def origin(self, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position (m), velocity (m/s) and acceleration (m/s²) of O, world, each (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        w = 2.0 * math.pi * self.cart_frequency_hz
        a = self.cart_amplitude_m
        zero = np.zeros_like(t)
        position = np.stack([a * np.sin(w * t), zero, np.full_like(t, TABLE_HEIGHT_M)], axis=-1)
        velocity = np.stack([a * w * np.cos(w * t), zero, zero], axis=-1)
        acceleration = np.stack([-a * w * w * np.sin(w * t), zero, zero], axis=-1)
        return position, velocity, acceleration

    # -- the slider relative to the table ----------------------------------------------
    def relative_body(self, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Slider position (m), velocity (m/s), acceleration (m/s²) relative to the table, body axes, each (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        w = 2.0 * math.pi * self.slider_frequency_hz
        a = self.slider_amplitude_m
        zero = np.zeros_like(t)
        position = np.stack([a * np.sin(w * t), np.full_like(t, self.groove_offset_m), zero], axis=-1)
        velocity = np.stack([a * w * np.cos(w * t), zero, zero], axis=-1)
        acceleration = np.stack([-a * w * w * np.sin(w * t), zero, zero], axis=-1)
        return position, velocity, acceleration

    # -- composition ------------------------------------------------------------------
    def position_world(self, t_s: np.ndarray) -> np.ndarray:
        """World position of P (m), shape (N, 3): ``r_O + R r_P/O`` (no derivatives taken)."""
        r_origin, _, _ = self.origin(t_s)
        r_body, _, _ = self.relative_body(t_s)
        return r_origin + np.einsum("nij,nj->ni", self.attitude(t_s), r_body)

    def kinematics(self, t_s: np.ndarray) -> Kinematics:
        """Everything about P and the body at times ``t_s``, each quantity computed once."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        angles = self.euler_313_angles(t)
        rotation = matrix_from_angles(angles, "3-1-3")
        r_origin, v_origin, a_origin = self.origin(t)
        r_body, v_body, a_body = self.relative_body(t)
        r = np.einsum("nij,nj->ni", rotation, r_body)
        v_rel = np.einsum("nij,nj->ni", rotation, v_body)
        omega = self.angular_velocity_world(t)
        alpha = self.angular_acceleration_world(t)
        omega_cross_r = np.cross(omega, r)
        terms = {
            "reference": a_origin,
            "angular": np.cross(alpha, r),
            "centripetal": np.cross(omega, omega_cross_r),
            "coriolis": 2.0 * np.cross(omega, v_rel),
            "relative": np.einsum("nij,nj->ni", rotation, a_body),
        }
        terms["total"] = sum(terms[name] for name in TERM_NAMES)
        return Kinematics(
            t_s=t,
            attitude_wxyz=quaternion_from_angles(angles, "3-1-3"),
            origin_m=r_origin,
            slider_body_m=r_body,
            position_m=r_origin + r,
            velocity_m_s=v_origin + omega_cross_r + v_rel,
            omega_rad_s=omega,
            alpha_rad_s2=alpha,
            terms_m_s2=terms,
        )

    def velocity_world(self, t_s: np.ndarray) -> np.ndarray:
        """``v_P = v_O + ω × r + v_rel`` (m/s, world), shape (N, 3)."""
        return self.kinematics(t_s).velocity_m_s

    def acceleration_terms(self, t_s: np.ndarray) -> dict[str, np.ndarray]:
        """The five terms of ``a_P`` and their sum ``total`` (m/s², world), each (N, 3)."""
        return self.kinematics(t_s).terms_m_s2


@dataclass(frozen=True)
class Kinematics:
    """The moving-frame quantities at N instants (world components unless said otherwise).

    ``attitude_wxyz`` (N, 4) is ``q_world_body``; ``origin_m`` is O; ``slider_body_m``
    is P relative to O in body axes; ``position_m``/``velocity_m_s`` are P's;
    ``terms_m_s2`` maps each term name (and ``total``) to an (N, 3) array.
    """

    t_s: np.ndarray
    attitude_wxyz: np.ndarray
    origin_m: np.ndarray
    slider_body_m: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    omega_rad_s: np.ndarray
    alpha_rad_s2: np.ndarray
    terms_m_s2: dict[str, np.ndarray]


class MovingFrameAcceleration(ClosedFormModel):
    """The slider on the shaking, spinning, precessing turntable, evaluated in closed form."""

    parameters = PARAMETERS
    description = "closed-form kinematics: a_P = a_O + α × r + ω × (ω × r) + 2 ω × v_rel + a_rel"
    series_units = {
        **{f"position_{c}": "m" for c in "xyz"},
        **{f"omega_{c}": "rad/s" for c in "xyz"},
        **{f"alpha_{c}": "rad/s²" for c in "xyz"},
        **{f"a_{name}_{c}": "m/s²" for name in (*TERM_NAMES, "total") for c in "xyz"},
    }

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        k = MovingFrameMotion.from_params(params).kinematics(t_s)
        series: dict[str, np.ndarray] = {}
        vectors = {
            "position": k.position_m,
            "omega": k.omega_rad_s,
            "alpha": k.alpha_rad_s2,
            **{f"a_{name}": value for name, value in k.terms_m_s2.items()},
        }
        for name, value in vectors.items():
            for i, c in enumerate("xyz"):
                series[f"{name}_{c}"] = value[:, i]
        return ClosedFormSolution(series=series)
