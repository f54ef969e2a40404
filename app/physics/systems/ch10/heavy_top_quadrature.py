"""Heavy symmetric top on a fixed pivot, solved by quadrature (elliptic functions and integrals).

Frames and units: world +Z up, gravity along −Z; body axis 3 is the symmetry axis
with the centre of mass on it at distance l from the pivot. ``I_transverse`` and
``I_axial`` are the principal moments about the pivot (kg·m²), ``mgl`` = m·g·l
(N·m). 3-1-3 Euler angles (rad): precession φ about world Z, nutation θ (tilt of
the axis from +Z), spin ψ about body 3; ``q_world_body`` = Rz(φ) Rx(θ) Rz(ψ).
``spin_rad_s`` is ω3 = ψ̇ + φ̇ cos θ (the body-3 component of ω), not ψ̇.

Integrals: p_ψ = I_a ω3, p_φ = I_t φ̇ sin²θ + I_a ω3 cos θ (kg·m²/s), E (J). With
u = cos θ, b = p_φ/I_t, c = p_ψ/I_t, β = 2 mgl/I_t::

    u̇² = f(u) = (1 − u²)(α − β u) − (b − c u)² = β (u − u1)(u − u2)(u − u3),   −1 ≤ u1 ≤ u2 ≤ 1 ≤ u3,
    φ̇ = (b − c u)/(1 − u²) = (b − c)/(2(1 − u)) + (b + c)/(2(1 + u)),
    ψ̇ = p_ψ/I_a − u φ̇ = (ω3 − c) − (b − c)/(2(1 − u)) + (b + c)/(2(1 + u)).

With u = u1 + (u2 − u1) sin²s, du/√f = 2 ds/√(β(u3 − u)), so s = am(x | m) with
x = λ t + x0, λ = √(β(u3 − u1))/2, m = (u2 − u1)/(u3 − u1): u = u1 + (u2 − u1) sn²x,
and the nutation period is 2K(m)/λ. The two pole terms of φ̇ and ψ̇ integrate in
closed form to elliptic integrals of the third kind (Carlson R_F, R_J), the 1 + u
one after a quarter-period shift that keeps all terms positive, and whole periods
are counted with the complete integrals: no step size, no error growth beyond
rounding (φ agrees with 40-digit quadrature to ~1e-14 rad over tens of radians).

The roots are found from the cubic expanded about u0 = cos θ0 (whose coefficients
come straight from the initial rates) and about u = 1, so that 1 − u2, 1 + u1 and
u3 − 1 keep relative precision when small (a top passing near the vertical).

Degenerate cases: steady precession (u1 = u2: constant θ and rates); the vertical
equilibria θ0 ∈ {0, π} with θ̇0 = 0 (a sleeping top above the critical spin stays
up, and so does one exactly upright below it — an unstable equilibrium, nutation
period inf); the axis passing exactly through a pole (p_φ = ±p_ψ with the motion
reaching u = ±1), where θ ≥ 0 makes φ jump by +π at each pass and ψ by −π at the
top, +π at the bottom — the limit of a near miss with p_φ ∓ p_ψ → 0⁺; φ + ψ (top),
φ − ψ (bottom) and the attitude stay continuous. A motion exactly on the separatrix
(approaching the upright position in infinite time) raises ValueError.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from app.physics.math.rotations import quaternion_from_euler_313
from app.physics.systems.ch10.free_body_elliptic import (
    complete_elliptic_k,
    complete_elliptic_pi,
    elliptic_f_from_sn_cn,
    elliptic_pi_reduced,
    jacobi_reduced,
)


def _check_positive(name: str, value: float, *, allow_zero: bool = False) -> None:
    if not math.isfinite(value) or value < 0.0 or (value == 0.0 and not allow_zero):
        bound = "≥ 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be a finite number {bound} (got {value!r})")


def _check_top(I_transverse: float, I_axial: float, mgl: float) -> None:
    _check_positive("I_transverse (kg·m²)", I_transverse)
    _check_positive("I_axial (kg·m²)", I_axial)
    _check_positive("mgl (N·m)", mgl, allow_zero=True)
    if I_axial > 2.0 * I_transverse * (1.0 + 1e-12):
        raise ValueError(
            f"I_axial = {I_axial:g} kg·m² exceeds 2·I_transverse = {2.0 * I_transverse:g} kg·m² "
            "(triangle inequality of the principal moments; no rigid body has these)"
        )


def critical_spin_rad_s(I_transverse: float, I_axial: float, mgl: float) -> float:
    """Sleeping-top threshold ω3 (rad/s): the upright top is stable for ω3² > 4 mgl I_t / I_a²."""
    _check_top(I_transverse, I_axial, mgl)
    return math.sqrt(4.0 * mgl * I_transverse) / I_axial


def _theta_from(one_minus_u: np.ndarray | float, one_plus_u: np.ndarray | float) -> np.ndarray:
    """θ = 2 atan2(√(1 − u), √(1 + u)): full precision near both poles."""
    return 2.0 * np.arctan2(np.sqrt(np.maximum(one_minus_u, 0.0)), np.sqrt(np.maximum(one_plus_u, 0.0)))


@dataclass(frozen=True)
class _Orbit:
    """Everything the time functions need (internal)."""

    constant: bool  # θ constant, rates constant
    phi_start: float
    psi_start: float
    theta_const: float
    phi_rate: float  # constant case
    psi_rate: float  # constant case
    # Elliptic case:
    delta_u: float = 0.0  # u2 − u1
    one_minus_u2: float = 0.0
    one_plus_u1: float = 0.0
    one_minus_u1: float = 0.0
    one_plus_u2: float = 0.0
    m: float = 0.0
    mc: float = 1.0
    K: float = 0.5 * math.pi
    rate: float = 0.0  # λ (1/s)
    x0: float = 0.0
    b_minus_c: float = 0.0  # (p_φ − p_ψ)/I_t, rad/s
    b_plus_c: float = 0.0  # (p_φ + p_ψ)/I_t, rad/s
    spin_offset: float = 0.0  # ω3 − c = p_ψ (1/I_a − 1/I_t), rad/s
    n_top: float = 0.0  # Π characteristic of the 1/(1 − u) term
    pi_top: float = 0.0  # complete Π for it
    n_bottom: float = 0.0  # Π characteristic of the shifted 1/(1 + u) term
    pi_bottom: float = 0.0
    linear_bottom: float = 0.0  # coefficient of (x − K) in the 1/(1 + u) integral
    weight_bottom: float = 0.0  # coefficient of Π in it
    jump_top: bool = False  # passes exactly through u = +1 (p_φ = p_ψ, u2 = 1)
    jump_bottom: bool = False  # passes exactly through u = −1 (p_φ = −p_ψ, u1 = −1)
    top_at_x0: float = 0.0
    bottom_at_x0: float = 0.0

    # ∫ dx / (1 − u(x)) and ∫ dx / (1 + u(x)) from an arbitrary fixed origin.
    def top_integral(self, x: np.ndarray) -> np.ndarray:
        k, sn, cn, dn = jacobi_reduced(x, m=self.m, mc=self.mc, K=self.K)
        one_minus_n = self.one_minus_u2 / self.one_minus_u1
        reduced = elliptic_pi_reduced(
            sn, cn * cn, n=self.n_top, one_minus_n=one_minus_n, m=self.m, mc=self.mc, dn2=dn * dn
        )
        return (2.0 * k * self.pi_top + reduced) / self.one_minus_u1

    def bottom_integral(self, x: np.ndarray) -> np.ndarray:
        # 1 + u = (1 + u1) + Δ sn²x; with x' = x − K, sn x = cd x', which turns the
        # negative characteristic into N = (m(1 + u1) + Δ)/(1 + u2) in [0, 1].
        shifted = np.asarray(x, dtype=float) - self.K
        k, sn, cn, dn = jacobi_reduced(shifted, m=self.m, mc=self.mc, K=self.K)
        one_minus_n = self.mc * self.one_plus_u1 / self.one_plus_u2
        reduced = elliptic_pi_reduced(
            sn, cn * cn, n=self.n_bottom, one_minus_n=one_minus_n, m=self.m, mc=self.mc, dn2=dn * dn
        )
        return self.linear_bottom * shifted + self.weight_bottom * (2.0 * k * self.pi_bottom + reduced)

    def passes(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact pole passages in (x0, x] (negative for x < x0): top at x = K + 2Kj, bottom at x = 2Kj."""
        period = 2.0 * self.K
        top = (
            np.floor((x - self.K) / period) - math.floor((self.x0 - self.K) / period)
            if self.jump_top
            else np.zeros_like(x)
        )
        bottom = np.floor(x / period) - math.floor(self.x0 / period) if self.jump_bottom else np.zeros_like(x)
        return top, bottom


@dataclass(frozen=True)
class HeavyTopQuadrature:
    """Closed-form / quadrature motion of a heavy symmetric top (see the module docstring).

    Inputs are stored as given. Conserved: ``p_phi``, ``p_psi`` (kg·m²/s) and
    ``energy_J`` (J, potential zero at the pivot height). ``u1 ≤ u2`` bound
    u = cos θ; ``u3 ≥ 1`` is the third root (inf when mgl = 0). Angles in rad,
    rates in rad/s, times in s from t = 0.
    """

    I_transverse: float
    I_axial: float
    mgl: float
    spin_rad_s: float
    theta0_rad: float
    phi_dot0: float
    theta_dot0: float
    phi0: float
    psi0: float
    p_phi: float
    p_psi: float
    energy_J: float
    u1: float
    u2: float
    u3: float
    theta_min_rad: float
    theta_max_rad: float
    nutation_period_s: float  # time between successive θ maxima; inf for the unstable upright top
    mean_precession_rate_rad_s: float  # Δφ over one nutation period / period
    mean_spin_rate_rad_s: float  # Δψ over one nutation period / period
    _orbit: _Orbit = field(repr=False)

    def _x(self, t: np.ndarray) -> np.ndarray:
        return self._orbit.rate * t + self._orbit.x0

    def _one_minus_plus_u(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        o = self._orbit
        _, sn, cn, _ = jacobi_reduced(self._x(t), m=o.m, mc=o.mc, K=o.K)
        return o.one_minus_u2 + o.delta_u * cn * cn, o.one_plus_u1 + o.delta_u * sn * sn

    def theta(self, t: np.ndarray) -> np.ndarray:
        """Nutation angle θ(t) in [0, π] (rad)."""
        t = np.asarray(t, dtype=float)
        if self._orbit.constant:
            return np.full(t.shape, self._orbit.theta_const)
        return _theta_from(*self._one_minus_plus_u(t))

    def cos_theta(self, t: np.ndarray) -> np.ndarray:
        """u(t) = cos θ(t)."""
        return np.cos(self.theta(t))

    def _phi_psi(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        o = self._orbit
        t = np.asarray(t, dtype=float)
        if o.constant:
            return o.phi_start + o.phi_rate * t, o.psi_start + o.psi_rate * t
        x = self._x(t)
        phi = np.full(t.shape, o.phi_start)
        psi = o.psi_start + o.spin_offset * t
        if o.b_minus_c != 0.0:
            top = (o.b_minus_c / (2.0 * o.rate)) * (o.top_integral(x) - o.top_at_x0)
            phi, psi = phi + top, psi - top
        if o.b_plus_c != 0.0:
            bottom = (o.b_plus_c / (2.0 * o.rate)) * (o.bottom_integral(x) - o.bottom_at_x0)
            phi, psi = phi + bottom, psi + bottom
        top_passes, bottom_passes = o.passes(x)
        phi = phi + math.pi * (top_passes + bottom_passes)
        psi = psi + math.pi * (bottom_passes - top_passes)
        return phi, psi

    def phi(self, t: np.ndarray) -> np.ndarray:
        """Precession angle φ(t) (rad), continuous (unwrapped) except for the π jump of an exact pole pass."""
        return self._phi_psi(t)[0]

    def psi(self, t: np.ndarray) -> np.ndarray:
        """Spin angle ψ(t) (rad), continuous (unwrapped) except for the π jump of an exact pole pass."""
        return self._phi_psi(t)[1]

    def euler_angles(self, t: np.ndarray) -> np.ndarray:
        """(φ, θ, ψ) in rad, shape t.shape + (3,)."""
        phi, psi = self._phi_psi(t)
        return np.stack([phi, self.theta(t), psi], axis=-1)

    def symmetry_axis(self, t: np.ndarray) -> np.ndarray:
        """World components of the unit symmetry axis (body e3), shape t.shape + (3,)."""
        theta = self.theta(t)
        phi = self.phi(t)
        s = np.sin(theta)
        return np.stack([s * np.sin(phi), -s * np.cos(phi), np.cos(theta)], axis=-1)

    def quaternion(self, t: np.ndarray) -> np.ndarray:
        """``q_world_body`` (wxyz, unit), shape t.shape + (4,)."""
        phi, psi = self._phi_psi(t)
        return quaternion_from_euler_313(phi, self.theta(t), psi)


def _largest_root_right(coefficients: tuple[float, float, float]) -> float:
    """Largest real root of w³ + a w² + b w + c (all roots real), by Newton from the right.

    To the right of the largest root the cubic is increasing and convex (its inflection is
    at the mean of the roots), so the iterates decrease monotonically onto it.
    """
    a, b, c = coefficients
    w = 1.0 + max(abs(a), abs(b), abs(c))  # Cauchy bound
    for _ in range(500):
        value = ((w + a) * w + b) * w + c
        if value <= 0.0:
            break
        slope = (3.0 * w + 2.0 * a) * w + b
        if slope <= 0.0:
            break
        w_next = w - value / slope
        if not w_next < w:
            break
        w = w_next
    return w


def heavy_top_quadrature(
    *,
    I_transverse: float,
    I_axial: float,
    mgl: float,
    spin_rad_s: float,
    theta0_rad: float,
    phi_dot0: float,
    theta_dot0: float,
    phi0: float = 0.0,
    psi0: float = 0.0,
) -> HeavyTopQuadrature:
    """Solve the heavy top for the given initial state (see the module docstring).

    At θ0 = 0 (or π) φ0 and ψ0 are only defined through φ0 + ψ0 (φ0 − ψ0); θ̇0 ≥ 0
    (≤ 0) means the axis leaves the pole towards azimuth φ0, a rate of the other sign
    towards φ0 + π; φ̇0 has no effect there (it multiplies sin²θ0 = 0).
    """
    _check_top(I_transverse, I_axial, mgl)
    for name, value in (
        ("spin_rad_s", spin_rad_s),
        ("phi_dot0", phi_dot0),
        ("theta_dot0", theta_dot0),
        ("phi0", phi0),
        ("psi0", psi0),
    ):
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite (got {value!r})")
    if not (math.isfinite(theta0_rad) and 0.0 <= theta0_rad <= math.pi):
        raise ValueError(f"theta0_rad must lie in [0, π] (tilt of the axis from +Z), got {theta0_rad!r}")

    It, Ia = I_transverse, I_axial
    beta = 2.0 * mgl / It
    c = Ia * spin_rad_s / It
    at_top, at_bottom = theta0_rad == 0.0, theta0_rad == math.pi
    sin0 = 0.0 if at_bottom else math.sin(theta0_rad)
    u0 = math.cos(theta0_rad)
    h = 2.0 * math.sin(0.5 * theta0_rad) ** 2  # 1 − u0
    g = 0.0 if at_bottom else 2.0 * math.cos(0.5 * theta0_rad) ** 2  # 1 + u0
    sin2 = sin0 * sin0

    p_psi = Ia * spin_rad_s
    p_phi = It * phi_dot0 * sin2 + p_psi * u0
    energy = 0.5 * It * (theta_dot0**2 + phi_dot0**2 * sin2) + 0.5 * Ia * spin_rad_s**2 + mgl * u0
    b_minus_c = phi_dot0 * sin2 - c * h
    b_plus_c = phi_dot0 * sin2 + c * g
    spin_offset = spin_rad_s - c

    # At a pole a rate "through" it is the same motion with the axis leaving towards φ0 + π.
    phi_start, psi_start, theta_dot = phi0, psi0, theta_dot0
    if (at_top and theta_dot0 < 0.0) or (at_bottom and theta_dot0 > 0.0):
        phi_start, psi_start, theta_dot = phi0 + math.pi, psi0 - math.pi, -theta_dot0

    kinetic = theta_dot**2 + phi_dot0**2 * sin2  # 2 T_transverse / I_t
    common = dict(
        I_transverse=It,
        I_axial=Ia,
        mgl=mgl,
        spin_rad_s=spin_rad_s,
        theta0_rad=theta0_rad,
        phi_dot0=phi_dot0,
        theta_dot0=theta_dot0,
        phi0=phi0,
        psi0=psi0,
        p_phi=p_phi,
        p_psi=p_psi,
        energy_J=energy,
    )

    def constant(
        u1: float, u2: float, u3: float, period: float, phi_rate: float, psi_rate: float
    ) -> HeavyTopQuadrature:
        orbit = _Orbit(True, phi_start, psi_start, theta0_rad, phi_rate, psi_rate)
        return HeavyTopQuadrature(
            **common,
            u1=u1,
            u2=u2,
            u3=u3,
            theta_min_rad=theta0_rad,
            theta_max_rad=theta0_rad,
            nutation_period_s=period,
            mean_precession_rate_rad_s=phi_rate,
            mean_spin_rate_rad_s=psi_rate,
            _orbit=orbit,
        )

    # Vertical equilibria: φ̇ = ±c/2 is the limit of (b − c u)/(1 − u²) at the pole.
    if (at_top or at_bottom) and theta_dot == 0.0:
        if at_top:
            u_other = c * c / beta - 1.0 if beta > 0.0 else math.inf
            stable = u_other > 1.0
            # A top at rest with no gravity (c = β = 0) never moves: no oscillation, an infinite period.
            period = 2.0 * math.pi / math.sqrt(c * c - 2.0 * beta) if stable and c * c - 2.0 * beta > 0.0 else math.inf
            roots = (1.0, 1.0, u_other) if stable else (u_other, 1.0, 1.0)
            return constant(*roots, period, 0.5 * c, spin_rad_s - 0.5 * c)
        u3 = 1.0 + c * c / beta if beta > 0.0 else math.inf
        period = 2.0 * math.pi / math.sqrt(c * c + 2.0 * beta) if c * c + 2.0 * beta > 0.0 else math.inf
        return constant(-1.0, -1.0, u3, period, -0.5 * c, spin_rad_s - 0.5 * c)

    # f(u0 + δ) = β δ³ + A2 δ² + A1 δ + A0, coefficients straight from the initial rates (A2 is not needed below).
    A1 = -beta * sin2 - 2.0 * u0 * kinetic + 2.0 * c * phi_dot0 * sin2
    A0 = sin2 * theta_dot**2
    # Largest root from f(1 + w) = β w³ + B2 w² + B1 w + B0 (B0 = −(b − c)²).
    if beta > 0.0:
        excess = kinetic - beta * h  # α − β: energy above the upright position, per I_t/2
        B2 = -excess + 2.0 * beta - c * c
        B1 = -2.0 * excess + 2.0 * c * b_minus_c
        w3 = _largest_root_right((B2 / beta, B1 / beta, -(b_minus_c**2) / beta))
        beta_w3 = beta * w3  # β (u3 − 1)
        u3 = 1.0 + w3
    else:  # mgl = 0: f is quadratic; β u3 → α + c² = kinetic + c²
        beta_w3 = kinetic + c * c
        u3 = math.inf
    beta_d3 = beta_w3 + beta * h  # β (u3 − u0)
    if beta_d3 == 0.0:  # nothing moves (mgl = 0, no rates, no spin)
        return constant(u0, u0, u3, math.inf, phi_dot0, spin_rad_s - phi_dot0 * u0)
    # Vieta for the two small roots: δ1 δ2 = P ≤ 0, δ1 + δ2 = S.
    P = -A0 / beta_d3
    S = (A1 - beta * P) / beta_d3
    root = math.sqrt(S * S - 4.0 * P)
    if S >= 0.0:
        d2 = 0.5 * (S + root)
        d1 = P / d2 if d2 != 0.0 else 0.0
    else:
        d1 = 0.5 * (S - root)
        d2 = P / d1
    delta_u = d2 - d1
    one_minus_u1 = h - d1
    one_plus_u2 = g + d2
    one_minus_u2 = h - d2
    if one_minus_u2 < 0.25 * h and beta_w3 > 0.0:  # cancellation: use f(1) = −β(1 − u1)(1 − u2)(u3 − 1)
        one_minus_u2 = b_minus_c**2 / (one_minus_u1 * beta_w3)
    one_plus_u1 = g + d1
    if one_plus_u1 < 0.25 * g:  # f(−1) = −β(1 + u1)(1 + u2)(u3 + 1), u3 + 1 ≥ 2: always well conditioned
        one_plus_u1 = b_plus_c**2 / (one_plus_u2 * (beta_w3 + 2.0 * beta))
    one_minus_u2, one_plus_u1 = max(one_minus_u2, 0.0), max(one_plus_u1, 0.0)
    u1, u2 = u0 + d1, u0 + d2

    beta_span = beta_w3 + beta * one_minus_u1  # β (u3 − u1)
    rate = 0.5 * math.sqrt(beta_span)
    if delta_u == 0.0:  # steady precession
        period = math.pi / rate
        return constant(u1, u2, u3, period, phi_dot0, spin_rad_s - phi_dot0 * u0)

    m = beta * delta_u / beta_span
    mc = (beta_w3 + beta * one_minus_u2) / beta_span
    if mc <= 0.0:
        raise ValueError(
            "the top is exactly on the separatrix (u2 = u3 = 1): it approaches the upright position in "
            "infinite time and the nutation period is infinite; perturb the initial state slightly"
        )
    K = complete_elliptic_k(m=m, mc=mc)
    # sn² x0 = (u0 − u1)/Δ, cn² x0 = (u2 − u0)/Δ; θ̇0 > 0 (u falling) puts x0 in the falling half.
    sn0 = math.sqrt(-d1 / delta_u)
    cn0 = math.sqrt(d2 / delta_u)
    if theta_dot > 0.0:
        cn0 = -cn0
    x0 = elliptic_f_from_sn_cn(sn0, cn0, m=m, mc=mc, K=K)

    n_top = delta_u / one_minus_u1 if one_minus_u1 > 0.0 else 0.0
    pi_top = (
        complete_elliptic_pi(n=n_top, one_minus_n=one_minus_u2 / one_minus_u1, m=m, mc=mc) if b_minus_c != 0.0 else 0.0
    )
    scaled = m * one_plus_u1 + delta_u
    n_bottom = scaled / one_plus_u2
    pi_bottom = (
        complete_elliptic_pi(n=n_bottom, one_minus_n=mc * one_plus_u1 / one_plus_u2, m=m, mc=mc)
        if b_plus_c != 0.0
        else 0.0
    )
    orbit = _Orbit(
        False,
        phi_start,
        psi_start,
        theta0_rad,
        0.0,
        0.0,
        delta_u=delta_u,
        one_minus_u2=one_minus_u2,
        one_plus_u1=one_plus_u1,
        one_minus_u1=one_minus_u1,
        one_plus_u2=one_plus_u2,
        m=m,
        mc=mc,
        K=K,
        rate=rate,
        x0=x0,
        b_minus_c=b_minus_c,
        b_plus_c=b_plus_c,
        spin_offset=spin_offset,
        n_top=n_top,
        pi_top=pi_top,
        n_bottom=n_bottom,
        pi_bottom=pi_bottom,
        linear_bottom=m / scaled,
        weight_bottom=delta_u * mc / (one_plus_u2 * scaled),
        jump_top=b_minus_c == 0.0 and one_minus_u2 == 0.0,
        jump_bottom=b_plus_c == 0.0,
    )
    x0_array = np.array(x0)
    orbit = replace(
        orbit,
        top_at_x0=float(orbit.top_integral(x0_array)) if b_minus_c != 0.0 else 0.0,
        bottom_at_x0=float(orbit.bottom_integral(x0_array)) if b_plus_c != 0.0 else 0.0,
    )

    # One nutation period: x advances by 2K; each pole integral by its complete value.
    period = 2.0 * K / rate
    top_per_period = (b_minus_c / (2.0 * rate)) * 2.0 * pi_top / one_minus_u1 if b_minus_c != 0.0 else 0.0
    bottom_per_period = (
        (b_plus_c / (2.0 * rate)) * (orbit.linear_bottom * 2.0 * K + orbit.weight_bottom * 2.0 * pi_bottom)
        if b_plus_c != 0.0
        else 0.0
    )
    jumps_phi = math.pi * (int(orbit.jump_top) + int(orbit.jump_bottom))
    jumps_psi = math.pi * (int(orbit.jump_bottom) - int(orbit.jump_top))
    dphi = top_per_period + bottom_per_period + jumps_phi
    dpsi = spin_offset * period - top_per_period + bottom_per_period + jumps_psi
    return HeavyTopQuadrature(
        **common,
        u1=u1,
        u2=u2,
        u3=u3,
        theta_min_rad=float(_theta_from(one_minus_u2, one_plus_u2)),
        theta_max_rad=float(_theta_from(one_minus_u1, one_plus_u1)),
        nutation_period_s=period,
        mean_precession_rate_rad_s=dphi / period,
        mean_spin_rate_rad_s=dpsi / period,
        _orbit=orbit,
    )
