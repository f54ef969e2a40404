"""Torque-free rigid body in closed form: Jacobi elliptic functions for ω, Carlson integrals for the attitude.

Frames and units: body axes are principal axes, ``inertia = (I1, I2, I3)`` in
kg·m² (any order), ``ω`` in rad/s on body axes, attitude ``q_world_body``
(wxyz, body components → world components, see :mod:`app.physics.math.rotations`).

Method. Energy ``2T = Σ Ii ωi²`` and ``L² = Σ Ii² ωi²`` fix ``D = L²/2T``. The
polhode circles the principal axis of largest moment when ``D`` exceeds the
middle moment and the axis of smallest moment when it is below. On a *working
frame* (other axis, middle axis, circled axis) with moments ``(J1, J2, J3)``::

    ω1 = A1 cn(x | m),   ω2 = ε σ A2 sn(x | m),   ω3 = σ A3 dn(x | m),   x = λ t + x0

with ``σ = sign ω3`` and ``ε = sign(J3 − J1)``. The parameter ``m`` and its
complement ``1 − m`` are each computed from differences of the data that never
cancel except through ``D − J2`` (the distance from the separatrix), itself
formed without the large ``J2 ω2²`` term; every elliptic function here takes
both ``m`` and ``1 − m`` so that near the separatrix (``1 − m`` ~ 1e-6, the
intermediate-axis flip) nothing is lost to ``1 − (1 − tiny)``.

Attitude: ``L`` is fixed in the world. 3-1-3 angles of the working frame
relative to an inertial frame with its Z along ``L`` follow from the body
components of ``L`` (``cos Θ = L3/|L|``, ``tan Ψ = L1/L2``) and from

    Φ̇ = |L|/J3 + |L| (J3 − J1) / (J1 J3 (1 − n sn²x)),   n = J3 (J1 − J2) / (J1 (J3 − J2)) ≤ 0,

whose integral is an elliptic integral of the third kind, evaluated in Carlson
form (``scipy.special.elliprf``/``elliprj``) after a quarter-period shift that
keeps every term positive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.special import elliprf, elliprj

from app.physics.bodies.inertia import check_principal_inertia
from app.physics.math.rotations import (
    quaternion_from_axis_angle,
    quaternion_from_euler_313,
    quaternion_from_matrix,
    quaternion_multiply,
    rotation_matrix,
)

_EPS = np.finfo(float).eps


# --------------------------------------------------------------------------------------------
# Elliptic functions with the parameter m and its complement mc = 1 − m passed separately.
# --------------------------------------------------------------------------------------------


def complete_elliptic_k(*, m: float, mc: float) -> float:
    """K(m) = R_F(0, 1 − m, 1), exact in the complement ``mc`` (inf when mc = 0)."""
    if mc == 0.0:
        return math.inf
    return float(elliprf(0.0, mc, 1.0))


def _amplitude_agm(x: np.ndarray, *, m: float, mc: float) -> np.ndarray:
    """am(x | m) by the descending AGM (Cephes' scheme); ~1e-16 absolute for m ≤ 1/2, |x| ≤ K."""
    a = [1.0]
    c = [math.sqrt(m)]
    b = math.sqrt(mc)
    while abs(c[-1]) > _EPS * a[-1] and len(a) < 40:
        a_next = 0.5 * (a[-1] + b)
        c.append(c[-1] ** 2 / (4.0 * a_next))  # (a − b)/2 without the cancellation
        b = math.sqrt(a[-1] * b)
        a.append(a_next)
    steps = len(a) - 1
    phi = (2.0**steps) * a[-1] * x
    for i in range(steps, 0, -1):
        phi = 0.5 * (phi + np.arcsin(c[i] * np.sin(phi) / a[i]))
    return phi


def _sn_cn_dn(y: np.ndarray, *, m: float, mc: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """sn, cn, dn for 0 ≤ y ≤ K/2, each to full *relative* precision (there cn, dn ≥ mc^¼/√2).

    m ≤ 1/2: descending AGM for am, then dn = √(mc + m cn²). m > 1/2: the ascending Landen
    (Gauss) transformation, which moves the parameter towards 1 with complement
    μc = ((1 − k)/(1 + k))⁴ (k = √m) and halves y/K, repeated until μc < 1e-34, where sn, cn,
    dn are tanh, sech, sech to within ~4√μc. No step cancels for y ≤ K/2. (Near m = 1 the AGM
    itself loses relative precision in cn and dn: ~1e-9 at 1 − m = 1e-15.)
    """
    if m <= 0.5:
        ph = y if m == 0.0 else _amplitude_agm(y, m=m, mc=mc)
        cn = np.cos(ph)
        return np.sin(ph), cn, np.sqrt(mc + m * cn * cn)
    if mc < 1e-34:
        sech = 1.0 / np.cosh(y)
        return np.tanh(y), sech, sech
    k = math.sqrt(m)
    s1 = mc / (1.0 + k) ** 2  # √μ1 = (1 − k)/(1 + k), formed from mc without cancellation
    mu = 4.0 * k / (1.0 + k) ** 2
    sn_v, cn_v, dn_v = _sn_cn_dn(y / (1.0 + s1), m=mu, mc=s1 * s1)
    dn_v2 = dn_v * dn_v
    return (
        (1.0 + s1) * sn_v * cn_v / dn_v,
        ((1.0 + s1) / mu) * (dn_v2 - s1) / dn_v,
        ((1.0 - s1) / mu) * (dn_v2 + s1) / dn_v,
    )


def jacobi_reduced(x: np.ndarray, *, m: float, mc: float, K: float) -> tuple[np.ndarray, ...]:
    """``(k, sn, cn, dn)`` of ``x_r`` where ``x = 2Kk + x_r``, ``|x_r| ≤ K`` (so ``cn ≥ 0``).

    Then ``sn(x) = (−1)^k sn``, ``cn(x) = (−1)^k cn``, ``dn(x) = dn``. ``mc = 1 − m`` is passed
    separately and never formed as ``1 − m``; each value keeps its relative precision where it
    is small (cn and dn near ±K fall to ~√mc near the separatrix). Beyond K/2 the values come
    from ``y = K − |x_r|`` through ``sn(K − y) = cd y``, ``cn(K − y) = √mc sd y``,
    ``dn(K − y) = √mc nd y``, so the kernel only sees 0 ≤ y ≤ K/2. scipy's ``ellipj`` takes
    m alone and switches to a first-order series for m > 1 − 1e-9.
    """
    x = np.asarray(x, dtype=float)
    k = np.round(x / (2.0 * K))
    x_r = x - 2.0 * K * k
    ax = np.abs(x_r)
    near = ax > 0.5 * K
    s, c, d = _sn_cn_dn(np.where(near, np.maximum(K - ax, 0.0), ax), m=m, mc=mc)
    root_mc = math.sqrt(mc)
    sn = np.sign(x_r) * np.where(near, c / d, s)
    cn = np.where(near, root_mc * s / d, c)
    dn = np.where(near, root_mc / d, d)
    return k, sn, cn, dn


def elliptic_f_from_sn_cn(sn: float, cn: float, *, m: float, mc: float, K: float) -> float:
    """The x in [−2K, 2K] with sn x = ``sn`` and cn x = ``cn`` (F(φ | m) for φ in [−π, π]).

    Carlson's R_F is well conditioned in *relative* perturbations of its arguments, so a
    small ``cn`` given to full relative precision gives x to full precision — unlike going
    through φ = atan2(sn, cn), where dF/dφ = 1/dn (up to 1/√mc) amplifies the rounding of φ.
    """
    part = sn * float(elliprf(cn * cn, mc + m * cn * cn, 1.0))
    if cn >= 0.0:
        return part
    return math.copysign(2.0 * K, sn) - part


def elliptic_pi_reduced(
    sin_r: np.ndarray | float,
    cos2_r: np.ndarray | float,
    *,
    n: float,
    one_minus_n: float,
    m: float,
    mc: float,
    dn2: np.ndarray | None = None,
) -> np.ndarray:
    """Π(n; r | m) = ∫₀^r dθ / ((1 − n sin²θ) √(1 − m sin²θ)) for |r| ≤ π/2, Carlson form.

    Arguments are ``sin r`` and ``cos² r`` (so r near ±π/2 keeps its precision), ``1 − n``
    and optionally ``dn² = 1 − m sin² r``, each to full relative precision. For 0 ≤ n ≤ 1
    both Carlson terms are positive (no cancellation).
    """
    sin_r = np.asarray(sin_r, dtype=float)
    cos2_r = np.asarray(cos2_r, dtype=float)
    delta = mc + m * cos2_r if dn2 is None else np.asarray(dn2, dtype=float)
    value = sin_r * elliprf(cos2_r, delta, 1.0)
    if n != 0.0:
        value = value + (n / 3.0) * sin_r**3 * elliprj(cos2_r, delta, 1.0, one_minus_n + n * cos2_r)
    return value


def complete_elliptic_pi(*, n: float, one_minus_n: float, m: float, mc: float) -> float:
    """Π(n | m), the integral of :func:`elliptic_pi_reduced` to r = π/2."""
    return float(elliptic_pi_reduced(1.0, 0.0, n=n, one_minus_n=one_minus_n, m=m, mc=mc))


# --------------------------------------------------------------------------------------------
# The torque-free body.
# --------------------------------------------------------------------------------------------


def check_inertia(inertia: tuple[float, float, float] | np.ndarray) -> np.ndarray:
    """Return the principal moments as an array; ValueError unless finite, positive and a real body's."""
    values = np.asarray(inertia, dtype=float)
    if values.shape != (3,):
        raise ValueError(f"inertia must be three principal moments (I1, I2, I3) in kg·m², got shape {values.shape}")
    check_principal_inertia((float(values[0]), float(values[1]), float(values[2])), about="the centre of mass")
    return values


@dataclass(frozen=True)
class _Working:
    """Closed-form data on the working frame (other, middle, circled axis); internal."""

    kind: str  # "steady", "elliptic" or "separatrix"
    P: np.ndarray  # proper signed permutation: ω_work = P @ ω_user
    J: np.ndarray  # moments on the working axes (kg·m²)
    amplitude: np.ndarray = field(default_factory=lambda: np.zeros(3))  # A1, A2, A3 (rad/s)
    sign_circled: float = 1.0  # σ = sign of ω3 (the circled axis)
    sign_other: float = 1.0  # separatrix only: sign of ω1 (no half-period shift of sech to absorb it)
    epsilon: float = 1.0  # sign(J3 − J1)
    m: float = 0.0
    mc: float = 1.0
    K: float = 0.5 * math.pi
    rate: float = 0.0  # λ (1/s)
    x0: float = 0.0
    n: float = 0.0  # characteristic of the Φ integral (≤ 0)
    q_world_L: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0, 0.0]))  # inertial frame, Z along L
    q_work_from_user: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0, 0.0]))  # R(q) = P
    phi_at_x0: float = 0.0  # Q(x0): origin of the Φ integral


@dataclass(frozen=True, eq=False)
class FreeBodyElliptic:
    """Torque-free motion of a rigid body about its centre of mass, in closed form.

    ``inertia`` (kg·m², principal, body axes 1-2-3), ``omega0_body`` (rad/s, body
    frame) and ``q0`` (``q_world_body`` at t = 0, wxyz). Times are seconds from t = 0.
    ``circled_axis`` and ``intermediate_axis`` are 0-based body-axis indices: the
    principal axis the polhode circles (None on the separatrix or for a steady
    rotation) and the axis of the middle principal moment (ties: the lower index
    among the equal pair that is not circled).
    """

    inertia: np.ndarray
    omega0_body: np.ndarray
    q0: np.ndarray
    energy_J: float
    angular_momentum_norm: float  # |L|, kg·m²/s
    angular_momentum_world: np.ndarray  # L in world components (constant), kg·m²/s
    period_s: float  # period of ω(t); inf when ω is constant or on the separatrix
    circled_axis: int | None
    intermediate_axis: int
    kind: str  # "elliptic", "steady" (rotation about a principal axis) or "separatrix"
    _w: _Working = field(repr=False)

    # -- angular velocity ----------------------------------------------------------------------

    def _phase(self, t: np.ndarray) -> np.ndarray:
        return self._w.rate * t + self._w.x0

    def omega_working(self, t: np.ndarray) -> np.ndarray:
        """ω on the working axes (other, middle, circled), shape t.shape + (3,)."""
        w = self._w
        t = np.asarray(t, dtype=float)
        if w.kind == "steady":
            return np.broadcast_to(w.P @ self.omega0_body, t.shape + (3,)).copy()
        x = self._phase(t)
        A1, A2, A3 = w.amplitude
        if w.kind == "separatrix":
            sech = 1.0 / np.cosh(x)
            return np.stack(
                [
                    w.sign_other * A1 * sech,
                    w.epsilon * w.sign_other * w.sign_circled * A2 * np.tanh(x),
                    w.sign_circled * A3 * sech,
                ],
                axis=-1,
            )
        k, sn, cn, dn = jacobi_reduced(x, m=w.m, mc=w.mc, K=w.K)
        parity = 1.0 - 2.0 * np.mod(k, 2.0)
        sn, cn = parity * sn, parity * cn
        return np.stack([A1 * cn, w.epsilon * w.sign_circled * A2 * sn, w.sign_circled * A3 * dn], axis=-1)

    def omega_body(self, t: np.ndarray) -> np.ndarray:
        """Body-frame angular velocity (rad/s) at times ``t`` (s), shape t.shape + (3,)."""
        return self.omega_working(t) @ self._w.P  # ω_user = Pᵀ ω_work, row-vector form

    def angular_momentum_body(self, t: np.ndarray) -> np.ndarray:
        """Body components of L (kg·m²/s), shape t.shape + (3,)."""
        return self.omega_body(t) * self.inertia

    # -- attitude ------------------------------------------------------------------------------

    def _phi_integral(self, x: np.ndarray) -> np.ndarray:
        """Q(x) = ∫₀^x dx'/(1 − n sn² x') up to a constant (Carlson, quarter-period shifted)."""
        w = self._w
        if w.n == 0.0:
            return x
        if w.kind == "separatrix":
            root = math.sqrt(-w.n)
            return (x + root * np.arctan(root * np.tanh(x))) / (1.0 - w.n)
        # sn(x)² = cd(x')², x' = x − K: 1 − n sn² = ((1 − n) − (m − n) sn'²)/dn'², giving
        # Q = m/(m − n)·x' + |n| mc/((1 − n)(m − n))·Π(N; am x'), N = (m − n)/(1 − n) in [0, 1).
        n, m, mc = w.n, w.m, w.mc
        big_n = (m - n) / (1.0 - n)
        one_minus_big_n = mc / (1.0 - n)
        xs = x - w.K
        k, sn, cn, dn = jacobi_reduced(xs, m=m, mc=mc, K=w.K)
        pi_complete = complete_elliptic_pi(n=big_n, one_minus_n=one_minus_big_n, m=m, mc=mc)
        pi_reduced = elliptic_pi_reduced(sn, cn * cn, n=big_n, one_minus_n=one_minus_big_n, m=m, mc=mc, dn2=dn * dn)
        pi_part = 2.0 * k * pi_complete + pi_reduced
        return (m / (m - n)) * xs + (-n * mc / ((1.0 - n) * (m - n))) * pi_part

    def _euler_about_L(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """3-1-3 angles (Φ, Θ, Ψ) of the working frame relative to the L-aligned inertial frame."""
        w = self._w
        x = self._phase(t)
        L = self.angular_momentum_norm
        J1, _, J3 = w.J
        omega = self.omega_working(t)
        l = omega * w.J
        theta = np.arctan2(np.hypot(l[..., 0], l[..., 1]), l[..., 2])
        if w.kind == "separatrix":
            psi = np.arctan2(l[..., 0], l[..., 1])  # l1 never vanishes on the separatrix
        else:
            # (l1, l2) = (J1 A1 cn, ε σ J2 A2 sn) turns by π per 2K: unwrap with the half-period index k.
            A1, A2, _ = w.amplitude
            k, sn, cn, _ = jacobi_reduced(x, m=w.m, mc=w.mc, K=w.K)
            s_b = w.epsilon * w.sign_circled
            psi = -s_b * k * math.pi + np.arctan2(J1 * A1 * cn, s_b * w.J[1] * A2 * sn)
        phi = (L / J3) * t + (L * (J3 - J1) / (J1 * J3 * w.rate)) * (self._phi_integral(x) - w.phi_at_x0)
        return phi, theta, psi

    def quaternion(self, t: np.ndarray) -> np.ndarray:
        """``q_world_body`` (wxyz, unit) at times ``t`` (s), shape t.shape + (4,)."""
        w = self._w
        t = np.asarray(t, dtype=float)
        if w.kind == "steady":  # a turn by |ω| t about the fixed body axis ω
            rate = float(np.linalg.norm(self.omega0_body))
            if rate == 0.0:
                return np.broadcast_to(self.q0, t.shape + (4,)).copy()
            return quaternion_multiply(self.q0, quaternion_from_axis_angle(self.omega0_body, rate * t))
        phi, theta, psi = self._euler_about_L(t)
        e = quaternion_from_euler_313(phi, theta, psi)
        return quaternion_multiply(quaternion_multiply(w.q_world_L, e), w.q_work_from_user)

    # -- flips ---------------------------------------------------------------------------------

    def flip_times(self, t_end: float) -> np.ndarray:
        """Times in (0, t_end] (s) where ω along the intermediate axis changes sign.

        That component is ``ε σ A2 sn(λ t + x0)`` (body axis ``intermediate_axis``), zero
        at ``λ t + x0 = 2K j``; on the separatrix it is a tanh with one zero. Empty for a
        steady rotation. For an axisymmetric body the 'intermediate' axis is one of the
        equal pair (see the class docstring) and these are the zeros of that component.
        """
        w = self._w
        if w.kind == "steady" or not t_end > 0.0:
            return np.empty(0)
        if w.kind == "separatrix":
            t0 = -w.x0 / w.rate
            return np.array([t0]) if 0.0 < t0 <= t_end else np.empty(0)
        period = 2.0 * w.K
        j_first = math.floor(w.x0 / period) + 1
        j_last = math.floor((w.rate * t_end + w.x0) / period)
        j = np.arange(j_first, j_last + 1, dtype=float)
        times = (period * j - w.x0) / w.rate
        return times[(times > 0.0) & (times <= t_end)]


def _proper_signed_permutation(order: tuple[int, int, int]) -> np.ndarray:
    """Rows = user-frame unit vectors of the working axes; the last sign fixes det = +1."""
    P = np.zeros((3, 3))
    for row, axis in enumerate(order):
        P[row, axis] = 1.0
    if np.linalg.det(P) < 0.0:
        P[2] *= -1.0
    return P


def free_body_elliptic(
    *, inertia: tuple[float, float, float] | np.ndarray, omega0_body: np.ndarray, q0: np.ndarray | None = None
) -> FreeBodyElliptic:
    """Build the closed-form torque-free motion (see the module docstring for the method)."""
    I = check_inertia(inertia)
    omega0 = np.asarray(omega0_body, dtype=float)
    if omega0.shape != (3,) or not np.all(np.isfinite(omega0)):
        raise ValueError(f"omega0_body must be three finite body-frame rates in rad/s, got {omega0_body!r}")
    if q0 is None:
        q0 = np.array([1.0, 0.0, 0.0, 0.0])
    q0 = np.asarray(q0, dtype=float)
    if q0.shape != (4,) or not np.all(np.isfinite(q0)) or np.linalg.norm(q0) == 0.0:
        raise ValueError(f"q0 must be a finite non-zero wxyz quaternion, got {q0!r}")
    q0 = q0 / np.linalg.norm(q0)

    two_T = float(np.sum(I * omega0**2))
    L_body = I * omega0
    L_norm = float(np.linalg.norm(L_body))
    L_world = rotation_matrix(q0) @ L_body

    order_by_moment = tuple(int(i) for i in np.argsort(I, kind="stable"))
    i_min, i_mid, i_max = order_by_moment

    def distance_from(j: int) -> float:
        """(L² − 2T·Ij)/(2T) = D − Ij, summed without the j term (which cancels exactly)."""
        return float(sum(I[i] * (I[i] - I[j]) * omega0[i] ** 2 for i in range(3) if i != j)) / two_T

    steady = all(omega0[i] == 0.0 or omega0[j] == 0.0 or I[i] == I[j] for i in range(3) for j in range(i + 1, 3))
    common = dict(
        inertia=I,
        omega0_body=omega0,
        q0=q0,
        energy_J=0.5 * two_T,
        angular_momentum_norm=L_norm,
        angular_momentum_world=L_world,
    )
    if steady:
        w = _Working("steady", np.eye(3), I.copy())
        return FreeBodyElliptic(
            **common, period_s=math.inf, circled_axis=None, intermediate_axis=i_mid, kind="steady", _w=w
        )

    d_mid = distance_from(i_mid)  # D − I_mid: the sign picks the circled axis; zero on the separatrix
    kind = "separatrix" if d_mid == 0.0 else "elliptic"
    circled = i_min if d_mid < 0.0 else i_max
    other = i_max if circled == i_min else i_min
    P = _proper_signed_permutation((other, i_mid, circled))
    J = np.abs(P) @ I
    omega_w = P @ omega0
    J1, J2, J3 = J
    d1, d3 = distance_from(other), distance_from(circled)  # D − J1, D − J3 (no cancellation)
    epsilon = 1.0 if J3 > J1 else -1.0
    A1 = math.sqrt(two_T * (-d3) / (J1 * (J3 - J1)))
    A2 = math.sqrt(two_T * (-d3) / (J2 * (J3 - J2)))
    A3 = math.sqrt(two_T * d1 / (J3 * (J3 - J1)))
    m = (J2 - J1) * (-d3) / ((J3 - J2) * d1) + 0.0  # + 0.0: no −0.0 for an axisymmetric body
    mc = (J3 - J1) * d_mid / ((J3 - J2) * d1)
    if kind == "separatrix":
        m, mc = 1.0, 0.0
    rate = math.sqrt(two_T * (J3 - J2) * d1 / (J1 * J2 * J3))
    sigma = 1.0 if omega_w[2] > 0.0 else -1.0
    n = J3 * (J1 - J2) / (J1 * (J3 - J2))
    K = complete_elliptic_k(m=m, mc=mc)
    if kind == "separatrix":
        sign_other = 1.0 if omega_w[0] > 0.0 else -1.0
        # ω2/(εσ₁σ A2) = tanh x, ω1/(σ₁ A1) = sech x  ⇒  sinh x0 = ratio.
        x0 = math.asinh((omega_w[1] / (epsilon * sign_other * sigma * A2)) / (abs(omega_w[0]) / A1))
        period = math.inf
    else:
        sign_other = 1.0
        # sn x0 and cn x0 straight from the data (a small cn keeps its relative precision).
        sn0, cn0 = omega_w[1] / (epsilon * sigma * A2), omega_w[0] / A1
        norm = math.hypot(sn0, cn0)
        x0 = elliptic_f_from_sn_cn(sn0 / norm, cn0 / norm, m=m, mc=mc, K=K)
        period = 4.0 * K / rate

    w = _Working(
        kind,
        P,
        J,
        amplitude=np.array([A1, A2, A3]),
        sign_circled=sigma,
        sign_other=sign_other,
        epsilon=epsilon,
        m=m,
        mc=mc,
        K=K,
        rate=rate,
        x0=x0,
        n=n,
        q_work_from_user=quaternion_from_matrix(P),
    )
    body = FreeBodyElliptic(
        **common,
        period_s=period,
        circled_axis=None if kind == "separatrix" else circled,
        intermediate_axis=i_mid,
        kind=kind,
        _w=w,
    )
    # Φ counts from t = 0; the inertial frame along L is q_world_L = q0 ⊗ p* ⊗ e(0)*, so that q(0) = q0.
    body = replace(body, _w=replace(w, phi_at_x0=float(body._phi_integral(np.array(x0)))))
    e0 = quaternion_from_euler_313(*body._euler_about_L(np.zeros(())))
    conj = np.array([1.0, -1.0, -1.0, -1.0])
    q_world_L = quaternion_multiply(quaternion_multiply(q0, w.q_work_from_user * conj), e0 * conj)
    return replace(body, _w=replace(body._w, q_world_L=q_world_L))
