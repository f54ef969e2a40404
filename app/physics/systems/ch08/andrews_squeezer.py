"""Andrews' squeezing mechanism: seven planar rigid bodies, seven angles, six holonomic constraints.

The standard multibody test problem (Hairer & Wanner, *Solving ODEs II*, section
VII.7; the "Test Set for IVP Solvers" of Bari/CWI, problem ``andrews``). A motor
torque ``mom`` on the crank (body 1, turning about the origin O) drives a
linkage whose two triangles (bodies 3 and 5–4, 7–6) end at the fixed points A
and B; a spring of stiffness ``c0`` and free length ``l0`` pulls the point D of
body 3 towards the fixed point C.

Coordinates ``q`` (rad), in this order, as in the test set:
``β`` (crank 1 about O, from the x axis), ``Θ`` (rod 2 relative to the crank),
``γ`` (body 3 about B), ``Φ`` (body 4 relative to body 5), ``δ`` (body 5 about A),
``Ω`` (body 6 relative to body 7), ``ε`` (body 7 about A). Rates ``v = q̇`` (rad/s).

Equations, in the sign convention of :mod:`app.physics.constrained.system`:
``M(q) q̈ = f(q, q̇) + Gᵀ(q) λ`` with ``g(q) = 0`` (6 rows, in m): the point E at the
end of rod 2 must coincide with the point of body 3 at distance ``ss`` from B
(rows 1–2), with the end of body 4 (rows 3–4) and with the end of body 6
(rows 5–6), each as an x and a y component. The test set writes
``M q̈ = f − Gᵀ λ``, so our multipliers are the negatives of the published ones
(N: every residual is a length, every coordinate an angle).

``c = −Ġ v``: each constraint row is a sum of terms ``a·cos(φ)`` or ``a·sin(φ)``
of an angle ``φ`` (a coordinate or a sum of two) with rate ``ω``; its second
time derivative has the velocity part ``−a·cos(φ) ω²`` (resp. ``−a·sin(φ) ω²``), so
``c`` is the same sum with every term multiplied by its ``ω²``.

Where every number comes from (all in SI units):

* the 42 parameters (masses, inertias, fixed points, lengths, ``c0``, ``l0``,
  ``mom``), the mass matrix, forces and constraints: the test set's Fortran
  ``andrews.f`` (revision ``andrews.F,v 1.2 2006/10/02``) as shipped by the R
  package deTestSet, repository ``cran/deTestSet``, files ``src/Ex_andrews.f``
  (``andfunc``) and ``R/ex_andrews.R`` (the parameter vector, in the order used
  here), the same values as Hairer & Wanner, Table VII.7.1;
* the consistent initial values (positions to 30 digits, rates zero) and the
  accelerations and multipliers that go with them: ``R/ex_andrews.R``
  (``andrewsinit``);
* the reference solution at t = 0.03 s: ``src/Ex_andrews.f`` (``andsoln``),
  computed by the test set's authors with PSIDE at rtol = atol = 1e-14 on a
  Cray C90.
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass, fields

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, kernel

COORDINATE_NAMES = ("beta_rad", "Theta_rad", "gamma_rad", "Phi_rad", "delta_rad", "Omega_rad", "epsilon_rad")

#: Consistent initial positions (rad) of the test set; the mechanism starts at rest.
INITIAL_POSITIONS_RAD = np.array(
    [
        -0.0617138900142764496358948458001,
        0.0,
        0.455279819163070380255912382449,
        0.222668390165885884674473185609,
        0.487364979543842550225598953530,
        -0.222668390165885884674473185609,
        1.23054744454982119249735015568,
    ]
)
#: Initial accelerations (rad/s²) of the test set, consistent with the positions above at rest.
INITIAL_ACCELERATIONS_RAD_S2 = np.array(
    [14222.4439199541138705911625887, -10666.8329399655854029433719415, 0.0, 0.0, 0.0, 0.0, 0.0]
)
#: Initial multipliers in the test set's sign (M q̈ = f − Gᵀλ, N); ours are their negatives.
PUBLISHED_INITIAL_MULTIPLIERS_N = np.array(
    [98.5668703962410896057654982170, -6.12268834425566265503114393122, 0.0, 0.0, 0.0, 0.0]
)

#: The published reference at t = 0.03 s (PSIDE, rtol = atol = 1e-14): positions (rad) ...
REFERENCE_TIME_S = 0.03
REFERENCE_POSITIONS_RAD = np.array(
    [
        0.1581077119629904e2,
        -0.1575637105984298e2,
        0.4082224013073101e-1,
        -0.5347301163226948e0,
        0.5244099658805304e0,
        0.5347301163226948e0,
        0.1048080741042263e1,
    ]
)
#: ... and rates (rad/s).
REFERENCE_RATES_RAD_S = np.array(
    [
        0.1139920302151208e4,
        -0.1424379294994111e4,
        0.1103291221937134e2,
        0.1929337464421385e2,
        0.5735699284790808e0,
        -0.1929337464421385e2,
        0.3231791658026955e0,
    ]
)


@dataclass(frozen=True)
class AndrewsParameters:
    """The 42 parameters, in the test set's order (its symbols, with the unit in the name).

    Masses (kg) and moments of inertia about each body's centre of mass (kg·m²)
    of bodies 1–7; the fixed points A, B, C (m, in the frame with the crank's
    pivot O at the origin, y up); link lengths and centre-of-mass offsets (m);
    the spring stiffness ``c0`` (N/m) and free length ``l0`` (m); the motor torque
    ``mom`` on the crank (N·m). Defaults: the standard values.
    """

    m1_kg: float = 0.04325
    m2_kg: float = 0.00365
    m3_kg: float = 0.02373
    m4_kg: float = 0.00706
    m5_kg: float = 0.07050
    m6_kg: float = 0.00706
    m7_kg: float = 0.05498
    xa_m: float = -0.06934
    ya_m: float = -0.00227
    xb_m: float = -0.03635
    yb_m: float = 0.03273
    xc_m: float = 0.014
    yc_m: float = 0.072
    c0_N_m: float = 4530.0
    i1_kg_m2: float = 2.194e-6
    i2_kg_m2: float = 4.410e-7
    i3_kg_m2: float = 5.255e-6
    i4_kg_m2: float = 5.667e-7
    i5_kg_m2: float = 1.169e-5
    i6_kg_m2: float = 5.667e-7
    i7_kg_m2: float = 1.912e-5
    d_m: float = 28e-3
    da_m: float = 115e-4
    e_m: float = 2e-2
    ea_m: float = 1421e-5
    rr_m: float = 7e-3
    ra_m: float = 92e-5
    l0_m: float = 7785e-5
    ss_m: float = 35e-3
    sa_m: float = 1874e-5
    sb_m: float = 1043e-5
    sc_m: float = 18e-3
    sd_m: float = 2e-2
    ta_m: float = 2308e-5
    tb_m: float = 916e-5
    u_m: float = 4e-2
    ua_m: float = 1228e-5
    ub_m: float = 449e-5
    zf_m: float = 2e-2
    zt_m: float = 4e-2
    fa_m: float = 1421e-5
    mom_N_m: float = 33e-3

    def __post_init__(self) -> None:
        for item in fields(self):
            value = getattr(self, item.name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ValueError(f"{item.name} must be a finite number (got {value!r})")
            if (item.name.endswith(("_kg", "_kg_m2")) or item.name == "l0_m") and value <= 0.0:
                raise ValueError(f"{item.name} must be positive (got {value!r})")
        if self.c0_N_m < 0.0:
            raise ValueError(f"c0_N_m (spring stiffness) must be ≥ 0 N/m (got {self.c0_N_m!r})")

    def array(self) -> np.ndarray:
        """The flat parameter array ``p`` (42,) both kernels read, in field order."""
        return np.array(astuple(self), dtype=float)


@kernel(DYNAMICS_SIGNATURE)
def andrews_dynamics(t, q, v, p, M_out, f_out):
    """Mass matrix (7, 7; kg·m²) and generalized forces (7,; N·m): motor, spring, Coriolis terms."""
    m1, m2, m3, m4, m5, m6, m7 = p[0], p[1], p[2], p[3], p[4], p[5], p[6]
    xb, yb, xc, yc, c0 = p[9], p[10], p[11], p[12], p[13]
    i1, i2, i3, i4, i5, i6, i7 = p[14], p[15], p[16], p[17], p[18], p[19], p[20]
    da, e, ea, rr, ra, l0 = p[22], p[23], p[24], p[25], p[26], p[27]
    sa, sb, sc, sd, ta, tb = p[29], p[30], p[31], p[32], p[33], p[34]
    u, ua, ub, zf, zt, fa, mom = p[35], p[36], p[37], p[38], p[39], p[40], p[41]
    cos_theta, sin_theta = np.cos(q[1]), np.sin(q[1])
    sin_gamma, cos_gamma = np.sin(q[2]), np.cos(q[2])
    sin_phi, cos_phi = np.sin(q[3]), np.cos(q[3])
    sin_omega, cos_omega = np.sin(q[5]), np.cos(q[5])
    e_ea, zf_fa = e - ea, zf - fa
    for i in range(7):
        for j in range(7):
            M_out[i, j] = 0.0
    M_out[0, 0] = m1 * ra * ra + m2 * (rr * rr - 2.0 * da * rr * cos_theta + da * da) + i1 + i2
    M_out[1, 0] = m2 * (da * da - da * rr * cos_theta) + i2
    M_out[1, 1] = m2 * da * da + i2
    M_out[2, 2] = m3 * (sa * sa + sb * sb) + i3
    M_out[3, 3] = m4 * e_ea * e_ea + i4
    M_out[4, 3] = m4 * (e_ea * e_ea + zt * e_ea * sin_phi) + i4
    M_out[4, 4] = m4 * (zt * zt + 2.0 * zt * e_ea * sin_phi + e_ea * e_ea) + m5 * (ta * ta + tb * tb) + i4 + i5
    M_out[5, 5] = m6 * zf_fa * zf_fa + i6
    M_out[6, 5] = m6 * (zf_fa * zf_fa - u * zf_fa * sin_omega) + i6
    M_out[6, 6] = m6 * (zf_fa * zf_fa - 2.0 * u * zf_fa * sin_omega + u * u) + m7 * (ua * ua + ub * ub) + i6 + i7
    M_out[0, 1] = M_out[1, 0]
    M_out[3, 4] = M_out[4, 3]
    M_out[5, 6] = M_out[6, 5]
    # The spring from D (on body 3) to the fixed point C.
    x_d = sd * cos_gamma + sc * sin_gamma + xb
    y_d = sd * sin_gamma - sc * cos_gamma + yb
    spring_length = np.sqrt((x_d - xc) ** 2 + (y_d - yc) ** 2)
    tension_per_length = -c0 * (spring_length - l0) / spring_length
    force_x = tension_per_length * (x_d - xc)
    force_y = tension_per_length * (y_d - yc)
    f_out[0] = mom - m2 * da * rr * v[1] * (v[1] + 2.0 * v[0]) * sin_theta
    f_out[1] = m2 * da * rr * v[0] * v[0] * sin_theta
    f_out[2] = force_x * (sc * cos_gamma - sd * sin_gamma) + force_y * (sd * cos_gamma + sc * sin_gamma)
    f_out[3] = m4 * zt * e_ea * v[4] * v[4] * cos_phi
    f_out[4] = -m4 * zt * e_ea * v[3] * (v[3] + 2.0 * v[4]) * cos_phi
    f_out[5] = -m6 * u * zf_fa * v[6] * v[6] * cos_omega
    f_out[6] = m6 * u * zf_fa * v[5] * (v[5] + 2.0 * v[6]) * cos_omega


@kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)
def andrews_constraints(q, v, p, g_out, C_out, c_out):
    """Loop closures ``g`` (6,; m), their Jacobian ``G`` (6, 7; m/rad) and ``c = −Ġ v`` (6,; m/s²)."""
    xa, ya, xb, yb = p[7], p[8], p[9], p[10]
    d, e, rr, ss, u, zf, zt = p[21], p[23], p[25], p[28], p[35], p[38], p[39]
    sin_beta, cos_beta = np.sin(q[0]), np.cos(q[0])
    sin_gamma, cos_gamma = np.sin(q[2]), np.cos(q[2])
    sin_delta, cos_delta = np.sin(q[4]), np.cos(q[4])
    sin_epsilon, cos_epsilon = np.sin(q[6]), np.cos(q[6])
    sin_bt, cos_bt = np.sin(q[0] + q[1]), np.cos(q[0] + q[1])
    sin_pd, cos_pd = np.sin(q[3] + q[4]), np.cos(q[3] + q[4])
    sin_oe, cos_oe = np.sin(q[5] + q[6]), np.cos(q[5] + q[6])
    # The end E of rod 2, common to the three loops.
    e_x = rr * cos_beta - d * cos_bt
    e_y = rr * sin_beta - d * sin_bt
    g_out[0] = e_x - ss * sin_gamma - xb
    g_out[1] = e_y + ss * cos_gamma - yb
    g_out[2] = e_x - e * sin_pd - zt * cos_delta - xa
    g_out[3] = e_y + e * cos_pd - zt * sin_delta - ya
    g_out[4] = e_x - zf * cos_oe - u * sin_epsilon - xa
    g_out[5] = e_y - zf * sin_oe + u * cos_epsilon - ya
    for i in range(6):
        for j in range(7):
            C_out[i, j] = 0.0
    for row in (0, 2, 4):  # x components: ∂e_x/∂(β, Θ)
        C_out[row, 0] = -rr * sin_beta + d * sin_bt
        C_out[row, 1] = d * sin_bt
    for row in (1, 3, 5):  # y components: ∂e_y/∂(β, Θ)
        C_out[row, 0] = rr * cos_beta - d * cos_bt
        C_out[row, 1] = -d * cos_bt
    C_out[0, 2] = -ss * cos_gamma
    C_out[1, 2] = -ss * sin_gamma
    C_out[2, 3] = -e * cos_pd
    C_out[2, 4] = -e * cos_pd + zt * sin_delta
    C_out[3, 3] = -e * sin_pd
    C_out[3, 4] = -e * sin_pd - zt * cos_delta
    C_out[4, 5] = zf * sin_oe
    C_out[4, 6] = zf * sin_oe - u * cos_epsilon
    C_out[5, 5] = -zf * cos_oe
    C_out[5, 6] = -zf * cos_oe - u * sin_epsilon
    w_beta2 = v[0] * v[0]
    w_bt2 = (v[0] + v[1]) ** 2
    w_gamma2 = v[2] * v[2]
    w_pd2 = (v[3] + v[4]) ** 2
    w_delta2 = v[4] * v[4]
    w_oe2 = (v[5] + v[6]) ** 2
    w_epsilon2 = v[6] * v[6]
    e_x_c = rr * cos_beta * w_beta2 - d * cos_bt * w_bt2
    e_y_c = rr * sin_beta * w_beta2 - d * sin_bt * w_bt2
    c_out[0] = e_x_c - ss * sin_gamma * w_gamma2
    c_out[1] = e_y_c + ss * cos_gamma * w_gamma2
    c_out[2] = e_x_c - e * sin_pd * w_pd2 - zt * cos_delta * w_delta2
    c_out[3] = e_y_c + e * cos_pd * w_pd2 - zt * sin_delta * w_delta2
    c_out[4] = e_x_c - zf * cos_oe * w_oe2 - u * sin_epsilon * w_epsilon2
    c_out[5] = e_y_c - zf * sin_oe * w_oe2 + u * cos_epsilon * w_epsilon2


def andrews_system(params: AndrewsParameters | None = None) -> ConstrainedSystem:
    """The mechanism as a :class:`ConstrainedSystem` (7 coordinates, 6 holonomic constraints, 1 degree of freedom)."""
    params = AndrewsParameters() if params is None else params
    return ConstrainedSystem(
        dynamics=andrews_dynamics,
        constraints=andrews_constraints,
        parameters=params.array(),
        coordinate_names=COORDINATE_NAMES,
        n_holonomic=6,
    )


def andrews_initial_state() -> tuple[np.ndarray, np.ndarray]:
    """The test set's consistent start: positions (7,; rad) and rates (7,; rad/s, all zero), fresh copies."""
    return INITIAL_POSITIONS_RAD.copy(), np.zeros(7)
