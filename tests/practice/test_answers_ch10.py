"""Chapter 10's exercises against independent computations: the free bodies and the tops integrated as rigid bodies
(Euler's equations and the attitude matrix, scipy's DOP853 at rtol = atol = 1e-12), their inertia summed over grids of
particles, the tumbling box's growth rate from the eigenvalues of Euler's equations linearized by finite differences,
the steady top from Lagrange's equation derived by sympy, the gyrocompass and the rate gyro from their equations
integrated numerically, and the free gyroscope's attitude integrated from its body rate. Each test states its
tolerance and why."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from app.physics.systems.ch10 import gyrocompass, heavy_top, rate_gyro
from app.physics.systems.ch10.heavy_top_quadrature import heavy_top_quadrature
from app.practice.variants import variant
from app.scenes import SCENES
from tests.practice.shipped import EXERCISES

VARIANTS = range(0, 100, 9)
#: The integrators' tolerances: far below every check's tolerance.
TIGHT = {"method": "DOP853", "rtol": 1e-12, "atol": 1e-12}


def _cross_matrix(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _rot_x(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rigid_body(inertia: np.ndarray, attitude: np.ndarray, omega: np.ndarray, t_end: float, *, weight=None, **options):
    """Integrate a rigid body turning about a fixed point: I ω̇ = M − ω × Iω (body axes), Ṙ = R [ω×]. ``weight`` is
    (m g, l): gravity −m g Z acting at l along body z. The state is R (row by row) then ω."""
    moments = np.asarray(inertia, dtype=float)

    def rates(_t, y):
        r, w = y[:9].reshape(3, 3), y[9:]
        moment = np.zeros(3)
        if weight is not None:
            mg, lever = weight
            moment = np.cross([0.0, 0.0, lever], r.T @ np.array([0.0, 0.0, -mg]))
        w_dot = (moment - np.cross(w, moments * w)) / moments
        return np.concatenate([(r @ _cross_matrix(w)).ravel(), w_dot])

    y0 = np.concatenate([np.asarray(attitude, dtype=float).ravel(), np.asarray(omega, dtype=float)])
    return solve_ivp(rates, (0.0, t_end), y0, **TIGHT, **options)


def _euler_313(r: np.ndarray) -> tuple[float, float, float]:
    """(φ, θ, ψ) of R = Rz(φ) Rx(θ) Rz(ψ), read from its third row and column."""
    return math.atan2(r[0, 2], -r[1, 2]), math.acos(np.clip(r[2, 2], -1, 1)), math.atan2(r[2, 0], r[2, 1])


def _free_axisymmetric_rates(i_t: float, i_a: float, spin: float, theta: float):
    """Start the free body with H along Z at θ from the axis (the definition of θ), integrate it for 20 s, and fit
    the slopes of φ and ψ. Returns (|H|, φ̇, ψ̇, ω_body at t = 0, R at t = 0)."""
    omega_perp = i_a * spin * math.tan(theta) / i_t  # H = (0, I_t ω⊥, I_a ω_z) makes the angle θ with the axis
    omega0 = np.array([0.0, omega_perp, spin])
    attitude = _rot_x(theta)  # carries (0, sin θ, cos θ), the direction of H in body axes, onto Z
    moments = np.array([i_t, i_t, i_a])
    h_world = attitude @ (moments * omega0)
    assert h_world[:2] == pytest.approx([0.0, 0.0], abs=1e-12 * np.linalg.norm(h_world))
    times = np.linspace(0.0, 20.0, 2001)
    run = _rigid_body(moments, attitude, omega0, 20.0, t_eval=times)
    angles = np.array([_euler_313(run.y[:9, k].reshape(3, 3)) for k in range(times.size)])
    assert np.ptp(angles[:, 1]) < 1e-9  # the nutation stays constant
    phi, psi = np.unwrap(angles[:, 0]), np.unwrap(angles[:, 2])
    return float(np.linalg.norm(h_world)), np.polyfit(times, phi, 1)[0], np.polyfit(times, psi, 1)[0], omega0, attitude


@pytest.mark.parametrize("number", VARIANTS)
def test_the_canisters_rates_come_out_of_its_integrated_motion(number):
    """|H| from I ω at the start and φ̇, ψ̇ as straight-line fits to the Euler angles of the integrated attitude over
    20 s (several precessions). The integration's error in the angles is below 1e-9 rad over the run, so the fitted
    slopes are good to 1e-10 rad/s: 1e-8 relative."""
    drawn = variant(EXERCISES["10-1-canister-precession"], number)
    g = drawn.given
    h, phi_dot, psi_dot, _, _ = _free_axisymmetric_rates(
        g["i_transverse"], g["i_axial"], g["spin_rad_s"], math.radians(g["nutation_deg"])
    )
    assert drawn.answers["h"].value == pytest.approx(h, rel=1e-12)
    assert drawn.answers["precession"].value == pytest.approx(phi_dot, rel=1e-8)
    assert drawn.answers["spin"].value == pytest.approx(psi_dot, rel=1e-8)


def _cylinder_ratio(radius: float, length: float, n: int = 4000) -> float:
    """I_a / I_t of a uniform cylinder from midpoint sums: rings of equal width (mass ∝ r dr) and slices along z."""
    r = (np.arange(n) + 0.5) * radius / n
    z = (np.arange(n) + 0.5) * length / n - length / 2
    mean_r2 = np.sum(r**3) / np.sum(r)  # ⟨x² + y²⟩ over the disk
    mean_z2 = np.mean(z**2)
    return mean_r2 / (mean_r2 / 2 + mean_z2)  # I_t/m = ⟨y²⟩ + ⟨z²⟩ with ⟨y²⟩ = ⟨x² + y²⟩/2 by symmetry


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cylinders_cones_are_the_angles_of_its_angular_velocity(number):
    """The inertia ratio from midpoint sums (4000 rings and slices: relative error below 1e-7); β and γ as the angles
    of ω (set up from the definition of θ) from the axis and from H; ω in XYZ as R ω_body at the start; the sense
    from the signs of the fitted φ̇ and ψ̇ of the integrated motion. Tolerance 1e-6 relative, ten times the error of
    the sums."""
    drawn = variant(EXERCISES["10-1-tossed-cylinder"], number)
    g = drawn.given
    ratio = _cylinder_ratio(g["radius_m"], g["length_m"])
    theta = math.radians(g["nutation_deg"])
    _, phi_dot, psi_dot, omega0, attitude = _free_axisymmetric_rates(1.0, ratio, g["spin_rad_s"], theta)
    omega_world = attitude @ omega0
    beta = math.degrees(math.acos(omega0[2] / np.linalg.norm(omega0)))
    gamma = math.degrees(math.acos(omega_world[2] / np.linalg.norm(omega_world)))
    assert drawn.answers["beta"].value == pytest.approx(beta, rel=1e-6)
    assert drawn.answers["gamma"].value == pytest.approx(gamma, rel=1e-6)
    assert np.allclose(drawn.answers["omega"].value, omega_world, rtol=1e-6, atol=1e-6 * np.linalg.norm(omega_world))
    assert drawn.answers["sense"].value == ("direct" if phi_dot * psi_dot > 0 else "retrograde")


def _box_moments(m: float, a: float, b: float, c: float, n: int = 4000) -> np.ndarray:
    """(I_x, I_y, I_z) of a uniform box from midpoint sums of the squares of each coordinate: each mean square falls
    short by the factor 1 − 1/n² (6e-8 at n = 4000), the same for every side."""
    square = [np.mean(((np.arange(n) + 0.5) / n - 0.5) ** 2) * side**2 for side in (a, b, c)]
    return m * np.array([square[1] + square[2], square[0] + square[2], square[0] + square[1]])


@pytest.mark.parametrize("number", VARIANTS)
def test_the_box_tumbles_about_the_axis_whose_linearized_spin_has_a_growing_mode(number):
    """For a spin Ω about each axis in turn, the Jacobian of Euler's equations by central differences (exact for
    these quadratic equations, up to rounding) and its eigenvalues: one axis has a real positive one, s. Then the
    linearized equations integrated from that eigenvector until the wobble is 100 times larger. Tolerances: 1e-6 on
    s (the moments' sums), 1e-6 on the time."""
    drawn = variant(EXERCISES["10-1-tumbling-box"], number)
    g = drawn.given
    moments = _box_moments(g["mass_kg"], g["length_m"], g["width_m"], g["height_m"])
    spin = g["spin_rad_s"]

    def euler(w):
        return -np.cross(w, moments * w) / moments

    growth = []
    jacobians = []
    for axis in range(3):
        w0 = spin * np.eye(3)[axis]
        step = 1e-4 * spin
        jacobian = np.column_stack([(euler(w0 + step * e) - euler(w0 - step * e)) / (2 * step) for e in np.eye(3)])
        jacobians.append(jacobian)
        growth.append(float(np.max(np.linalg.eigvals(jacobian).real)))
    unstable = int(np.argmax(growth))
    assert sorted(growth)[1] < 1e-9 * spin  # only one axis is unstable
    assert drawn.answers["axis"].value == "xyz"[unstable]
    rate = growth[unstable]
    assert drawn.answers["rate"].value == pytest.approx(rate, rel=1e-6)
    values, vectors = np.linalg.eig(jacobians[unstable])
    mode = np.real(vectors[:, int(np.argmax(values.real))])
    mode /= np.linalg.norm(mode)

    def hundredfold(_t, y):
        return np.linalg.norm(y) - 100.0

    hundredfold.terminal = True
    run = solve_ivp(lambda _t, y: jacobians[unstable] @ y, (0.0, 1e3), mode, events=hundredfold, **TIGHT)
    assert drawn.answers["time"].value == pytest.approx(run.t_events[0][0], rel=1e-6)


def _lagrange_theta_residual():
    """The heavy top's Lagrange equation for θ (3-1-3 angles, θ from the upward vertical), from its Lagrangian by
    sympy, as a function of (θ, θ̇, θ̈, φ̇, ψ̇, I_t, I_a, m g l)."""
    t = sympy.Symbol("t")
    theta, phi, psi = (sympy.Function(n)(t) for n in ("theta", "phi", "psi"))
    i_t, i_a, mgl = sympy.symbols("I_t I_a mgl", positive=True)
    spin = sympy.diff(psi, t) + sympy.diff(phi, t) * sympy.cos(theta)
    kinetic = (
        i_t * (sympy.diff(theta, t) ** 2 + sympy.diff(phi, t) ** 2 * sympy.sin(theta) ** 2) / 2 + i_a * spin**2 / 2
    )
    lagrangian = kinetic - mgl * sympy.cos(theta)
    equation = sympy.diff(sympy.diff(lagrangian, sympy.diff(theta, t)), t) - sympy.diff(lagrangian, theta)
    names = sympy.symbols("th thd thdd phid psid")
    replaced = equation.subs(
        {
            sympy.diff(theta, t, 2): names[2],
            sympy.diff(theta, t): names[1],
            sympy.diff(phi, t): names[3],
            sympy.diff(psi, t): names[4],
        }
    ).subs(theta, names[0])
    return sympy.lambdify((*names, i_t, i_a, mgl), replaced)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_steady_top_satisfies_lagranges_equation_and_the_quadrature_holds_it_steady(number):
    """Lagrange's θ equation (sympy) vanishes with θ̇ = θ̈ = 0, ψ̇ = ω_z − φ̇ cos θ at the answer's φ̇, to 1e-10 of
    m g l sin θ; the answer is the smaller of the equation's two roots; the project's quadrature started at that φ̇
    keeps θ within 1e-6 rad (its double root splits only by rounding) and precesses at the answer's rate to 1e-9.
    The moment from l k × (−m g K) and the estimate from |M| = φ̇ |K × H| with H = I_a ω_z k, to 1e-12."""
    drawn = variant(EXERCISES["10-2-steady-precession"], number)
    g = drawn.given
    m, l, grav, i_t, i_a, spin = (
        g["mass_kg"],
        g["cg_distance_m"],
        g["g_m_s2"],
        g["i_transverse_pivot"],
        g["i_axial"],
        g["spin_rad_s"],
    )
    theta = math.radians(g["theta0_deg"])
    mgl = m * grav * l
    k = np.array([0.0, -math.sin(theta), math.cos(theta)])
    moment = np.cross(l * k, [0.0, 0.0, -m * grav])
    assert drawn.answers["moment"].value == pytest.approx(np.linalg.norm(moment), rel=1e-12)
    turning = np.linalg.norm(np.cross([0.0, 0.0, 1.0], i_a * spin * k))
    assert drawn.answers["estimate"].value == pytest.approx(np.linalg.norm(moment) / turning, rel=1e-12)
    residual = _lagrange_theta_residual()
    exact = drawn.answers["exact"].value
    for rate in (exact, drawn.answers["exact"].mistakes["fast-root"]):
        value = residual(theta, 0.0, 0.0, rate, spin - rate * math.cos(theta), i_t, i_a, mgl)
        assert abs(value) < 1e-10 * mgl * math.sin(theta)
    assert 0 < exact < drawn.answers["exact"].mistakes["fast-root"]
    steady = heavy_top_quadrature(
        I_transverse=i_t, I_axial=i_a, mgl=mgl, spin_rad_s=spin, theta0_rad=theta, phi_dot0=exact, theta_dot0=0.0
    )
    assert steady.theta_max_rad - steady.theta_min_rad < 1e-6
    assert steady.mean_precession_rate_rad_s == pytest.approx(exact, rel=1e-9)


def _disk_on_stem(m: float, r: float, l: float, rings: int = 200, sectors: int = 64) -> tuple[float, float]:
    """(I about a horizontal axis through the pivot, I about the axis) of a thin disk whose centre is l above the
    pivot, summed over particles: each ring's particles sit at the radius of its mean square, √((r₁² + r₂²)/2), on
    equally spaced sectors, which makes both sums exact up to rounding."""
    edges = np.linspace(0.0, r, rings + 1)
    radius = np.sqrt((edges[1:] ** 2 + edges[:-1] ** 2) / 2)
    ring_mass = m * (edges[1:] ** 2 - edges[:-1] ** 2) / r**2
    angle = (np.arange(sectors) + 0.5) * 2 * np.pi / sectors
    rr, aa = np.meshgrid(radius, angle)
    x, y = (rr * np.cos(aa)).ravel(), (rr * np.sin(aa)).ravel()
    masses = np.broadcast_to(ring_mass / sectors, rr.shape).ravel()
    return float(np.sum(masses * (y**2 + l**2))), float(np.sum(masses * (x**2 + y**2)))


def _sleeping_threshold_formula() -> sympy.Expr:
    """The threshold from the cubic f(u) of an upright top (θ0 = 0, at rest but for the spin): f has the double
    root u = 1, and the remaining factor must be negative just below u = 1."""
    u, omega = sympy.symbols("u omega", positive=True)
    m, g, l, i_t, i_a = sympy.symbols("m g l It Ia", positive=True)
    beta, c = 2 * m * g * l / i_t, i_a * omega / i_t
    alpha, b = beta, c  # energy E' = m g l and H_Z = I_a ω_z at u0 = 1, so α = β and b = c
    f = sympy.expand((1 - u**2) * (alpha - beta * u) - (b - c * u) ** 2)
    quotient, remainder = sympy.div(f, sympy.expand((1 - u) ** 2), u)
    assert remainder == 0
    boundary = sympy.solve(sympy.Eq(quotient.subs(u, 1), 0), omega)
    assert len(boundary) == 1
    return boundary[0]


@pytest.mark.parametrize("number", VARIANTS)
def test_the_sleeping_top_threshold_from_particles_the_cubic_and_the_quadrature(number):
    """I_t from the disk's particles (exact sums, 1e-12); the formula equal to the threshold found by sympy from the
    factored cubic, at 50 random points (1e-12); the number equal to the project's own threshold; and the choice
    confirmed by the project's quadrature started 1e-4 rad off the vertical: a sleeping top's axis stays within
    0.05 rad, a falling one's passes 0.3 rad (the spins are at least 5 % from the threshold)."""
    exercise = EXERCISES["10-2-sleeping-top"]
    drawn = variant(exercise, number)
    g = drawn.given
    m, r, l, grav, spin = g["mass_kg"], g["radius_m"], g["cg_distance_m"], g["g_m_s2"], g["spin_rad_s"]
    i_t, i_a = _disk_on_stem(m, r, l)
    assert drawn.answers["it"].value == pytest.approx(i_t, rel=1e-12)
    derived = _sleeping_threshold_formula()
    formula = drawn.answers["formula"].value
    ours = {s.name: s for s in formula.free_symbols}
    theirs = {s.name: s for s in derived.free_symbols}
    rng = np.random.default_rng(10)
    for _ in range(50):
        point = {"m": rng.uniform(0.05, 2), "g": rng.uniform(1, 20), "l": rng.uniform(0.005, 0.2)}
        point |= {"It": rng.uniform(1e-5, 1e-2), "Ia": rng.uniform(1e-5, 1e-2)}
        mine = float(formula.subs({ours[n]: v for n, v in point.items()}))
        expected = float(derived.subs({theirs[n]: v for n, v in point.items()}))
        assert mine == pytest.approx(expected, rel=1e-12)
    params = {"mass_kg": m, "cg_distance_m": l, "I_transverse_pivot": i_t, "I_axial": i_a, "g_m_s2": grav}
    critical = heavy_top.critical_spin_rad_s(params)
    assert drawn.answers["critical"].value == pytest.approx(critical, rel=1e-12)
    nudged = heavy_top_quadrature(
        I_transverse=i_t, I_axial=i_a, mgl=m * grav * l, spin_rad_s=spin, theta0_rad=1e-4, phi_dot0=0.0, theta_dot0=0.0
    )
    if drawn.answers["sleeps"].value == "sleeps":
        assert nudged.theta_max_rad < 0.05
    else:
        assert nudged.theta_max_rad > 0.3


@pytest.mark.parametrize("number", VARIANTS)
def test_the_released_tops_lowest_point_comes_out_of_its_integrated_motion(number):
    """The top integrated as a rigid body about its pivot from rest in θ and φ; the first minimum of cos θ (an event
    on its rate) gives θ_max, and φ̇ there follows from ω in space and ω_z: with θ̇ = 0, ω = φ̇ K + ψ̇ k so
    φ̇ = (ω_Z − ω_z cos θ)/sin²θ. H_Z from R I ω at the start. At a minimum the event's timing error does not reach θ,
    so 1e-8 relative holds with room; the project's quadrature agrees on θ_max to 1e-9."""
    exercise = EXERCISES["10-2-top-released-at-rest"]
    drawn = variant(exercise, number)
    g = drawn.given
    m, l, grav, i_t, i_a, spin = (
        g["mass_kg"],
        g["cg_distance_m"],
        g["g_m_s2"],
        g["i_transverse_pivot"],
        g["i_axial"],
        g["spin_rad_s"],
    )
    theta0 = math.radians(g["theta0_deg"])
    moments = np.array([i_t, i_t, i_a])
    attitude = _rot_x(theta0)
    omega0 = np.array([0.0, 0.0, spin])
    assert drawn.answers["hz"].value == pytest.approx((attitude @ (moments * omega0))[2], rel=1e-12)

    def lowest(_t, y):  # d(cos θ)/dt = d R₃₃/dt = R₃₁ ω_y − R₃₂ ω_x
        return y[6] * y[10] - y[7] * y[9]

    lowest.direction = 1.0
    lowest.terminal = True
    run = _rigid_body(moments, attitude, omega0, 100.0, weight=(m * grav, l), events=lowest)
    state = run.y_events[0][0]
    r, w = state[:9].reshape(3, 3), state[9:]
    cos_theta = r[2, 2]
    assert drawn.answers["theta-max"].value == pytest.approx(math.degrees(math.acos(cos_theta)), rel=1e-8)
    phi_dot = ((r @ w)[2] - w[2] * cos_theta) / (1.0 - cos_theta**2)
    assert drawn.answers["phi-dot"].value == pytest.approx(phi_dot, rel=1e-8)
    params = SCENES["heavy-top"].parameters.validate(exercise.scene.at(g)["params"])
    quadrature = heavy_top.quadrature(params)
    assert drawn.answers["theta-max"].value == pytest.approx(math.degrees(quadrature.theta_max_rad), rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_gyrocompass_moment_from_vectors_and_its_periods_from_integrated_swings(number):
    """K as the vertical component of Ω × H at α = 90° (site axes east, north, up), to 1e-12; T₀ and T as the time
    between successive maxima of α from the linear and the full pendulum equations integrated at tolerance 1e-12,
    to 1e-8; and the project's gyrocompass model at the scene's parameters, to 1e-12."""
    exercise = EXERCISES["10-3-gyrocompass-swing"]
    drawn = variant(exercise, number)
    g = drawn.given
    latitude = math.radians(g["latitude_deg"])
    earth = gyrocompass.EARTH_RATE_RAD_S * np.array([0.0, math.cos(latitude), math.sin(latitude)])
    h = g["rotor_inertia_kg_m2"] * g["spin_rad_s"] * np.array([1.0, 0.0, 0.0])  # spin axis east, α = 90°
    k = -np.cross(earth, h)[2]
    assert drawn.answers["moment"].value == pytest.approx(k, rel=1e-12)
    i_t = g["vertical_inertia_kg_m2"]
    alpha0 = math.radians(g["alpha0_deg"])

    def period(restoring) -> float:
        def at_maximum(_t, y):
            return y[1]

        at_maximum.direction = -1.0
        guess = 2 * math.pi * math.sqrt(i_t / k)
        run = solve_ivp(
            lambda _t, y: [y[1], -restoring(y[0]) * k / i_t],
            (0.0, 12 * guess),
            [alpha0, 0.0],
            events=at_maximum,
            **TIGHT,
        )
        maxima = run.t_events[0]
        return float(maxima[1] - maxima[0])

    assert drawn.answers["small-period"].value == pytest.approx(period(lambda a: a), rel=1e-8)
    assert drawn.answers["period"].value == pytest.approx(period(math.sin), rel=1e-8)
    params = SCENES["gyrocompass"].parameters.validate(exercise.scene.at(g)["params"])
    assert drawn.answers["moment"].value == pytest.approx(gyrocompass.restoring_moment_N_m(params), rel=1e-12)
    assert drawn.answers["period"].value == pytest.approx(
        gyrocompass.large_amplitude_period_s(params, alpha0), rel=1e-12
    )


@pytest.mark.parametrize("number", VARIANTS)
def test_the_rate_gyros_response_from_its_integrated_equation(number):
    """I_g β̈ + c β̇ + k β = I_a ω_s Ω₀ integrated from rest at tolerance 1e-12, its extremes found as events on β̇:
    the peak is the first maximum; the steady value is the level β_ss about which successive extremes shrink by a
    constant ratio, (β₂ − β_ss)² = (β₁ − β_ss)(β₃ − β_ss); ζ comes from the logarithmic decrement between the first
    two maxima. 1e-7 relative (the events are located far more finely); and the project's own gyro model at the
    scene's parameters gives the same ζ to 1e-12."""
    exercise = EXERCISES["10-3-rate-gyro-step"]
    drawn = variant(exercise, number)
    g = drawn.given
    i_g, c, k = g["gimbal_inertia_kg_m2"], g["damping_nms_rad"], g["stiffness_nm_rad"]
    drive = g["rotor_inertia_kg_m2"] * g["spin_rad_s"] * g["input_rate_rad_s"]

    def extreme(_t, y):
        return y[1]

    run = solve_ivp(
        lambda _t, y: [y[1], (drive - c * y[1] - k * y[0]) / i_g],
        (0.0, 6 * 2 * math.pi * math.sqrt(i_g / k)),
        [0.0, 0.0],
        events=extreme,
        **TIGHT,
    )
    values = run.y_events[0][:, 0]
    values = values[np.abs(run.t_events[0]) > 1e-9]  # not the start, where β̇ = 0 too
    first, second, third = values[:3]  # maximum, minimum, maximum
    steady = (first * third - second**2) / (first + third - 2 * second)
    decrement = math.log((first - steady) / (third - steady))
    zeta = decrement / math.sqrt(4 * math.pi**2 + decrement**2)
    assert drawn.answers["peak"].value == pytest.approx(math.degrees(first), rel=1e-7)
    assert drawn.answers["steady"].value == pytest.approx(math.degrees(steady), rel=1e-7)
    assert drawn.answers["zeta"].value == pytest.approx(zeta, rel=1e-7)
    params = SCENES["rate-gyro"].parameters.validate(exercise.scene.at(g)["params"])
    assert drawn.answers["zeta"].value == pytest.approx(rate_gyro.damping_ratio(params), rel=1e-12)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_free_gyroscopes_reading_from_the_integrated_vehicle_attitude(number):
    """Ṙ = R [ω_B×] integrated from R = 1 at tolerance 1e-12; the spin axis fixed in space read in vehicle axes as
    Rᵀ s_N, and the gimbal angles from it; 1e-9 on the vector, 1e-8 relative on the angles. The named mistake is the
    axis turned the other way, R s_N."""
    drawn = variant(EXERCISES["10-3-free-gyro-readout"], number)
    g = drawn.given
    rate = np.array([g["roll_rate_rad_s"], 0.0, g["yaw_rate_rad_s"]])
    elevation = math.radians(g["elevation_deg"])
    s_n = np.array([0.0, math.cos(elevation), math.sin(elevation)])
    run = solve_ivp(
        lambda _t, y: (y.reshape(3, 3) @ _cross_matrix(rate)).ravel(), (0.0, g["time_s"]), np.eye(3).ravel(), **TIGHT
    )
    r = run.y[:, -1].reshape(3, 3)
    s_b = r.T @ s_n
    assert np.allclose(drawn.answers["axis"].value, s_b, rtol=0, atol=1e-9)
    assert np.allclose(drawn.answers["axis"].mistakes["turned-with-vehicle"], r @ s_n, rtol=0, atol=1e-9)
    assert drawn.answers["inner"].value == pytest.approx(math.degrees(math.asin(s_b[2])), rel=1e-8)
    assert drawn.answers["outer"].value == pytest.approx(math.degrees(math.atan2(-s_b[0], s_b[1])), rel=1e-8)
