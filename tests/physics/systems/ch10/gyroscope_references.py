"""Full rigid-body references for the section 10.3 gyroscopes, stored in tests/references/.

Each body's attitude is a product of elementary rotation matrices (base or Earth rotation
prescribed in time, gimbal angles as generalised coordinates), its body-frame angular velocity
comes from ``Rᵀ Ṙ``, and Lagrange's equations of the total kinetic energy (plus spring potential
and Rayleigh damping) are derived with sympy and integrated by scipy's DOP853. Nothing in that
derivation uses the app's formulas (the free gyroscope's start is read off its closed form at
t = 0 only). Deriving and integrating takes about a minute, so the sampled results are stored;
``pytest -m slow`` recomputes them (tests/references/__init__.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from app.physics.systems.ch10 import free_gyroscope as fg
from app.physics.systems.ch10 import gyrocompass as gc
from app.physics.systems.ch10 import rate_gyro as rg
from tests.references import StoredReference

TIGHT = dict(method="DOP853", rtol=1e-12, atol=1e-12)
t_sym = sp.Symbol("t", real=True)


# ---------------------------------------------------------------------------------------------
# Lagrange's equations for rigid bodies given by rotation-matrix chains
# ---------------------------------------------------------------------------------------------
def rot_x(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def rot_y(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


def rot_z(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def rot_axis(axis: Sequence[float], a):
    """Rodrigues matrix for a right-handed turn ``a`` about the unit ``axis`` (numbers)."""
    n = sp.Matrix(axis) / math.sqrt(sum(x * x for x in axis))
    k = sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return sp.eye(3) + sp.sin(a) * k + (1 - sp.cos(a)) * k * k


def lagrange_rhs(coordinates, bodies, potential=0, dissipation=0) -> Callable:
    """``f(t, [q, q̇]) -> [q̇, q̈]`` from Lagrange's equations.

    ``coordinates``: sympy functions of ``t_sym``; ``bodies``: (R_world_body, (I1, I2, I3)) with
    principal moments on the body axes; ``potential`` V(q) and Rayleigh ``dissipation`` D(q̇).
    """
    n = len(coordinates)
    q = sp.symbols(f"q0:{n}")
    u = sp.symbols(f"u0:{n}")
    a = sp.symbols(f"a0:{n}")
    kinetic = 0
    for rotation, inertia in bodies:
        w = rotation.T * rotation.diff(t_sym)  # [ω_body]×
        omega = [w[2, 1], w[0, 2], w[1, 0]]
        kinetic += sum(sp.Rational(1, 2) * inertia[i] * omega[i] ** 2 for i in range(3))
    lagrangian = kinetic - potential
    equations = []
    for qi in coordinates:
        qdot = qi.diff(t_sym)
        eq = lagrangian.diff(qdot).diff(t_sym) - lagrangian.diff(qi) + sp.sympify(dissipation).diff(qdot)
        equations.append(eq)
    # Replace q̈, q̇, q (in that order) by plain symbols.
    eqs = [e.subs({qi.diff(t_sym, 2): a[i] for i, qi in enumerate(coordinates)}) for e in equations]
    eqs = [e.subs({qi.diff(t_sym): u[i] for i, qi in enumerate(coordinates)}) for e in eqs]
    eqs = [e.subs({qi: q[i] for i, qi in enumerate(coordinates)}) for e in eqs]
    mass = sp.Matrix([[e.diff(aj) for aj in a] for e in eqs])
    rest = sp.Matrix([e.subs({aj: 0 for aj in a}) for e in eqs])
    mass_f = sp.lambdify((t_sym, q, u), mass, modules="numpy", cse=True)
    rest_f = sp.lambdify((t_sym, q, u), rest, modules="numpy", cse=True)

    def rhs(t, y):
        qs, us = y[:n], y[n:]
        acc = np.linalg.solve(np.asarray(mass_f(t, qs, us), dtype=float), -np.asarray(rest_f(t, qs, us), dtype=float).ravel())
        return np.concatenate([us, acc])

    return rhs


def _integrate(rhs, y0, t_end_s: float, samples: int | None, integrator: Mapping):
    t_eval = None if samples is None else np.linspace(0.0, t_end_s, samples)
    run = solve_ivp(rhs, (0.0, t_end_s), y0, t_eval=t_eval, **integrator)
    assert run.success, run.message
    return run


# ---------------------------------------------------------------------------------------------
# Free gyroscope: rotor + two gimbals on a tumbling vehicle
# ---------------------------------------------------------------------------------------------
#: The vehicle rolls, pitches and yaws at once; the closest approach to the lock over 12 s is 31°.
TUMBLING_VEHICLE = dict(vehicle_rate_rad_s=[0.3, 0.2, 0.4], inner_gimbal0_deg=15.0, outer_gimbal0_deg=25.0)
ROTOR_MOMENTS_KG_M2 = dict(axial=2e-3, transverse=1.2e-3)


def _free_gyroscope_lagrangian(params, *, spin_rad_s, axial, transverse, gimbal_inertia):
    """Rotor + two gimbals on the turning vehicle; coordinates φ_o, φ_i, ψ (rotor angle in the inner ring)."""
    omega = np.asarray(params["vehicle_rate_rad_s"], dtype=float)
    rate = float(np.linalg.norm(omega))
    outer, inner, spin = (sp.Function(n)(t_sym) for n in ("outer", "inner", "spin"))
    vehicle = rot_axis(omega / rate, rate * t_sym)
    outer_ring = vehicle * rot_z(outer)
    inner_ring = outer_ring * rot_x(inner)
    rotor = inner_ring * rot_y(spin)
    bodies = [(rotor, (transverse, axial, transverse))]
    if gimbal_inertia:
        bodies += [(outer_ring, (gimbal_inertia,) * 3), (inner_ring, (gimbal_inertia,) * 3)]
    rhs = lagrange_rhs([outer, inner, spin], bodies)
    # Start on the torque-free motion: gimbal rates from the closed form, rotor spin ω_s about the axis.
    start = fg.gimbal_motion(params, 0.0)
    s = fg.spin_axis_inertial(params)
    ring_rate = omega + start.outer_rate_rad_s[0] * np.array([0, 0, 1.0]) + start.inner_rate_rad_s[0] * np.array(
        [math.cos(start.outer_rad[0]), math.sin(start.outer_rad[0]), 0.0]
    )
    y0 = [start.outer_rad[0], start.inner_rad[0], 0.0, start.outer_rate_rad_s[0], start.inner_rate_rad_s[0], spin_rad_s - ring_rate @ s]
    return rhs, y0


def _gimbal_angles(inputs: Mapping) -> dict[str, np.ndarray]:
    """Gimbal angles φ_o, φ_i (rad), shape (len(spins), samples), one row per rotor spin."""
    params = fg.PARAMETERS.validate(dict(inputs["vehicle"]))
    outer, inner = [], []
    for spin in inputs["spins_rad_s"]:
        rhs, y0 = _free_gyroscope_lagrangian(
            params, spin_rad_s=spin, gimbal_inertia=inputs["gimbal_inertia_kg_m2"], **inputs["rotor_moments_kg_m2"]
        )
        run = _integrate(rhs, y0, inputs["t_end_s"], inputs["samples"], inputs["integrator"])
        outer.append(run.y[0])
        inner.append(run.y[1])
    return {"outer_rad": np.array(outer), "inner_rad": np.array(inner)}


MASSLESS_GIMBALS = StoredReference(
    name="ch10-free-gyroscope-massless-gimbals",
    note="Gimbal angles of rotor + massless rings on the tumbling vehicle: sympy Lagrange, DOP853 rtol=atol=1e-12.",
    inputs=dict(
        vehicle=TUMBLING_VEHICLE, spins_rad_s=[50.0], rotor_moments_kg_m2=ROTOR_MOMENTS_KG_M2, gimbal_inertia_kg_m2=0.0,
        t_end_s=12.0, samples=121, integrator=TIGHT,
    ),
    compute=_gimbal_angles,
    atol=1e-10,  # the integration's own error is ~3e-13 rad; the tests allow 1e-8 rad
)

HEAVY_GIMBALS = StoredReference(
    name="ch10-free-gyroscope-heavy-gimbals",
    note="Gimbal angles with rings of inertia 2e-4 kg·m², rotor spin 50 and 500 rad/s: sympy Lagrange, DOP853 rtol=atol=1e-10.",
    inputs=dict(
        vehicle=TUMBLING_VEHICLE, spins_rad_s=[50.0, 500.0], rotor_moments_kg_m2=ROTOR_MOMENTS_KG_M2, gimbal_inertia_kg_m2=2e-4,
        t_end_s=6.0, samples=241, integrator=dict(method="DOP853", rtol=1e-10, atol=1e-10),
    ),
    compute=_gimbal_angles,
    atol=1e-8,  # the test compares axis tips of 4.8e-4 and 4.8e-5 rad: 1e-8 moves their ratio by < 0.03 %
)


# ---------------------------------------------------------------------------------------------
# Gyrocompass: housing + spinning rotor carried by the rotating planet
# ---------------------------------------------------------------------------------------------
#: Scaled-up planet: Ω = 0.05 rad/s, so a north-seeking period is 3.3 s instead of minutes.
SCALED = dict(
    latitude_deg=40.0, earth_rate_rad_s=0.05, spin_rad_s=300.0, rotor_axial_inertia_kg_m2=0.02,
    vertical_inertia_kg_m2=0.05, alpha0_deg=30.0, damping_N_m_s_rad=0.0,
)
HOUSING_VERTICAL, ROTOR_TRANSVERSE = 0.04, 0.01  # kg·m²: together the 0.05 kg·m² about the vertical


def compass_start(params) -> list[float]:
    """``[α, ψ, α̇, ψ̇]`` at t = 0: the rotor's spin component ω_s = ψ̇ + (housing rate)·ŝ, and the
    housing rate along ŝ is Ω cos λ cos α."""
    alpha0 = math.radians(params["alpha0_deg"])
    spin_rate0 = params["spin_rad_s"] - params["earth_rate_rad_s"] * math.cos(math.radians(params["latitude_deg"])) * math.cos(alpha0)
    return [alpha0, 0.0, params["alpha_rate0_rad_s"], spin_rate0]


def _compass_lagrangian(params, *, housing_vertical, rotor_transverse):
    """Housing (turns about the local vertical) + rotor (free spin), carried by the rotating planet.

    World frame: Z along the planet's axis. The site frame's columns are east, north and up at
    latitude λ and longitude Ω t. Housing: azimuth α from north toward east, a turn of −α about
    up; rotor: spin angle ψ about the housing's y axis (north when α = 0), axial moment on its y
    axis. Coordinates α, ψ; viscous damping c α̇ about the vertical. Returns (rhs, y0).
    """
    lam = math.radians(params["latitude_deg"])
    omega = params["earth_rate_rad_s"]
    alpha, spin = sp.Function("alpha")(t_sym), sp.Function("psi")(t_sym)
    lon = omega * t_sym
    site = sp.Matrix(
        [
            [-sp.sin(lon), -math.sin(lam) * sp.cos(lon), math.cos(lam) * sp.cos(lon)],
            [sp.cos(lon), -math.sin(lam) * sp.sin(lon), math.cos(lam) * sp.sin(lon)],
            [0, math.cos(lam), math.sin(lam)],
        ]
    )
    housing = site * rot_z(-alpha)
    rotor = housing * rot_y(spin)
    i_a = params["rotor_axial_inertia_kg_m2"]
    bodies = [(housing, (1e-3, 1e-3, housing_vertical)), (rotor, (rotor_transverse, i_a, rotor_transverse))]
    damping = sp.Rational(1, 2) * params["damping_N_m_s_rad"] * alpha.diff(t_sym) ** 2
    return lagrange_rhs([alpha, spin], bodies, dissipation=damping), compass_start(params)


def _compass_azimuth(inputs: Mapping) -> dict[str, np.ndarray]:
    """α (rad) over ``periods`` small-angle periods on ``samples`` points."""
    params = gc.PARAMETERS.validate(dict(inputs["compass"]))
    rhs, y0 = _compass_lagrangian(params, housing_vertical=inputs["housing_vertical_kg_m2"], rotor_transverse=inputs["rotor_transverse_kg_m2"])
    run = _integrate(rhs, y0, inputs["periods"] * gc.small_angle_period_s(params), inputs["samples"], inputs["integrator"])
    return {"alpha_rad": run.y[0]}


COMPASS_SWING = StoredReference(
    name="ch10-gyrocompass-full-swing",
    note="Azimuth α of housing + rotor on the scaled planet over 4 periods: sympy Lagrange, DOP853 rtol=atol=1e-12.",
    inputs=dict(
        compass=SCALED, housing_vertical_kg_m2=HOUSING_VERTICAL, rotor_transverse_kg_m2=ROTOR_TRANSVERSE,
        periods=4, samples=401, integrator=TIGHT,
    ),
    compute=_compass_azimuth,
    atol=1e-11,  # the test asks the full and the hand-derived equations to agree to 1e-9 rad (measured 1.2e-10)
)

#: (ω_s rad/s, α₀ deg) released with damping: north-seeking for ω_s > 0, south-seeking for ω_s < 0.
SEEKING_RELEASES = [(300.0, 60.0), (-300.0, 120.0)]


def _final_azimuths(inputs: Mapping) -> dict[str, np.ndarray]:
    """α (rad) at ``t_end_s`` for each release in ``releases``."""
    finals = []
    for spin, alpha0_deg in inputs["releases"]:
        params = gc.PARAMETERS.validate({**inputs["compass"], "spin_rad_s": spin, "alpha0_deg": alpha0_deg})
        rhs, y0 = _compass_lagrangian(params, housing_vertical=inputs["housing_vertical_kg_m2"], rotor_transverse=inputs["rotor_transverse_kg_m2"])
        finals.append(_integrate(rhs, y0, inputs["t_end_s"], None, inputs["integrator"]).y[0, -1])
    return {"final_alpha_rad": np.array(finals)}


COMPASS_SEEKING = StoredReference(
    name="ch10-gyrocompass-seeks-north",
    note="Final azimuth after 40 s of damped full motion for spin +300 and −300 rad/s: sympy Lagrange, DOP853 rtol=atol=1e-10.",
    inputs=dict(
        compass={**SCALED, "damping_N_m_s_rad": 0.05}, releases=SEEKING_RELEASES, housing_vertical_kg_m2=HOUSING_VERTICAL,
        rotor_transverse_kg_m2=ROTOR_TRANSVERSE, t_end_s=40.0, integrator=dict(method="DOP853", rtol=1e-10, atol=1e-10),
    ),
    compute=_final_azimuths,
    atol=1e-7,  # the test allows 1e-2 rad from north (or south)
)


# ---------------------------------------------------------------------------------------------
# Rate gyro: spring-restrained gimbal + motor-driven rotor in a turning case
# ---------------------------------------------------------------------------------------------
def _rate_gyro_lagrangian(params, *, gimbal_moments, rotor_transverse, input_rate_rad_s):
    """Case turning at Ω about Z; gimbal on the case's x axis (angle β, spring k, damper c); rotor
    driven by its motor at ω_s relative to the gimbal about the gimbal's y axis. One coordinate β."""
    beta = sp.Function("beta")(t_sym)
    case = rot_z(input_rate_rad_s * t_sym)
    gimbal = case * rot_x(beta)
    rotor = gimbal * rot_y(params["spin_rad_s"] * t_sym)
    bodies = [(gimbal, gimbal_moments), (rotor, (rotor_transverse, params["rotor_axial_inertia_kg_m2"], rotor_transverse))]
    spring = sp.Rational(1, 2) * params["stiffness_N_m_rad"] * beta**2
    damper = sp.Rational(1, 2) * params["damping_N_m_s_rad"] * beta.diff(t_sym) ** 2
    return lagrange_rhs([beta], bodies, potential=spring, dissipation=damper)


def _rate_gyro_deflection(inputs: Mapping) -> dict[str, np.ndarray]:
    """β (rad) from rest after the case is stepped to Ω, on ``samples`` points."""
    params = rg.PARAMETERS.validate(dict(inputs["rate_gyro"]))
    rotor_transverse = inputs["rotor_transverse_kg_m2"]
    gimbal_x = params["gimbal_inertia_kg_m2"] - rotor_transverse  # I_g = gimbal + rotor about the output axis
    rhs = _rate_gyro_lagrangian(
        params, gimbal_moments=(gimbal_x, *inputs["gimbal_other_moments_kg_m2"]), rotor_transverse=rotor_transverse,
        input_rate_rad_s=params["input_rate_rad_s"],
    )
    return {"beta_rad": _integrate(rhs, [0.0, 0.0], inputs["t_end_s"], inputs["samples"], inputs["integrator"]).y[0]}


RATE_GYRO_STEP = StoredReference(
    name="ch10-rate-gyro-full-step",
    note="Gimbal deflection β of the full gimbal + rotor (spin 1000 rad/s) after a step to Ω = 0.05 rad/s: sympy Lagrange, DOP853 rtol=atol=1e-12.",
    inputs=dict(
        rate_gyro=dict(input_rate_rad_s=0.05, damping_N_m_s_rad=0.03), rotor_transverse_kg_m2=1.2e-4,
        gimbal_other_moments_kg_m2=[3e-3, 4e-3], t_end_s=8.0, samples=801, integrator=TIGHT,
    ),
    compute=_rate_gyro_deflection,
    atol=1e-11,  # β_ss = 0.02 rad and the test allows 2e-5 rad
)

REFERENCES = (MASSLESS_GIMBALS, HEAVY_GIMBALS, COMPASS_SWING, COMPASS_SEEKING, RATE_GYRO_STEP)
