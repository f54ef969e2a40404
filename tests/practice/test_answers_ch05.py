"""Chapter 5's new answer functions (sections 5.1–5.3) against independent computations, over several variants each
(tolerances stated and justified at each check): brute-force particle sums over bodies cut into many small masses,
motions built from rotation matrices and differentiated numerically (complex-step velocities, central differences
for rates of angular momentum), sympy integration of a cylinder's tensor, a scan for the least moment of a bent bar,
and the angular-momentum scene's own model at the exercise's "See it" numbers.

The checks of 5-2-plate-about-corner and 5-3-tilted-disk-bearings stay in test_answers.py."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy
from scipy.optimize import brentq

from app.physics.systems.ch05.angular_momentum import ShaftSpin
from app.practice.exercise import parse_exercise
from app.practice.variants import variant
from app.scenes import SCENES

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch05" / "exercises"
VARIANTS = range(0, 100, 9)


def _exercise(exercise_id: str):
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=5)


def _close_vector(answer, expected, rel: float) -> bool:
    expected = np.asarray(expected, dtype=float)
    return float(np.linalg.norm(np.asarray(answer, dtype=float) - expected)) <= rel * float(np.linalg.norm(expected))


def _rot_x(angle):
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    return np.array([[one, zero, zero], [zero, c, -s], [zero, s, c]])


def _rot_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    return np.array([[c, -s, zero], [s, c, zero], [zero, zero, one]])


def _grid(length: float, n: int) -> np.ndarray:
    """Midpoints of n equal pieces of [−length/2, length/2]: the midpoint rule is exact for first moments, and its
    Σ x² is exactly (1 − 1/n²) times ∫x² over the piece, so a grid body's centroidal tensor is exactly (1 − 1/n²)
    times the solid's."""
    return (np.arange(n) + 0.5) * length / n - length / 2


def _box_particles(mass: float, a: float, b: float, c: float, n: int = 60):
    X, Y, Z = np.meshgrid(_grid(a, n), _grid(b, n), _grid(c, n), indexing="ij")
    points = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=-1)
    return points, np.full(len(points), mass / len(points))


def _plate_particles(mass: float, a: float, b: float, n: int = 400):
    X, Y = np.meshgrid(_grid(a, n), _grid(b, n), indexing="ij")
    points = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=-1)
    return points, np.full(len(points), mass / len(points))


def _disk_particles(mass: float, radius: float, rings: int = 300, sectors: int = 360):
    """The disk in the plane normal to x (its axis along x), as point masses at the centroids of equal-angle cells of
    rings; each ring's second moment about the axis is exact to < 1e-5 relative with these centroids."""
    edges = np.linspace(0.0, radius, rings + 1)
    r = (2 / 3) * (edges[1:] ** 3 - edges[:-1] ** 3) / (edges[1:] ** 2 - edges[:-1] ** 2)
    ring_mass = mass * (edges[1:] ** 2 - edges[:-1] ** 2) / radius**2
    phi = (np.arange(sectors) + 0.5) * 2 * np.pi / sectors
    R, PHI = np.meshgrid(r, phi)
    points = np.stack([np.zeros_like(R), R * np.cos(PHI), R * np.sin(PHI)], axis=-1).reshape(-1, 3)
    return points, np.broadcast_to(ring_mass / sectors, R.shape).reshape(-1)


def _momentum_and_energy(positions_of_t, masses, t: float):
    """H about the origin (a fixed point) and T of particles whose world positions are ``positions_of_t(t)``
    (N, 3), analytic in t: velocities by the complex step (exact to round-off, no cancellation)."""
    step = 1e-30
    positions = np.real(positions_of_t(complex(t, 0.0)))
    velocities = np.imag(positions_of_t(complex(t, step))) / step
    h = np.sum(masses[:, None] * np.cross(positions, velocities), axis=0)
    energy = 0.5 * float(np.sum(masses * np.sum(velocities**2, axis=1)))
    return h, energy, velocities


def _rate_of_momentum(positions_of_t, masses, dt: float = 1e-6):
    """dH/dt at t = 0 by a central difference of H (complex-step velocities inside): truncation (ω dt)² < 1e-8 for the
    rates used here, round-off ≈ 1e-16/dt = 1e-10 relative."""
    ahead, _, _ = _momentum_and_energy(positions_of_t, masses, dt)
    behind, _, _ = _momentum_and_energy(positions_of_t, masses, -dt)
    return (ahead - behind) / (2 * dt)


# -- 5.1 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_tilted_box_matches_the_scenes_model_and_its_particles(number):
    """The angular-momentum scene's ShaftSpin model at the exercise's "See it" numbers (H_G(0) and T by its own route,
    R_z(Ωt) R_x(β) and its sweep coefficients): round-off only, 1e-12. Then 216 000 particles on a 60³ grid, whose
    tensor is exactly (1 − 1/60²) times the box's (see _grid), so 1.05/60² = 2.9e-4; and about the bearing A (0.3 m
    below G) the particle sum
    Σ (rᵢ − A) × mᵢ vᵢ equals H_G to round-off (1e-12 of |H_G|), which is the choice "equal"."""
    exercise = _exercise("5-1-tilted-box-momentum")
    drawn = variant(exercise, number)
    g = drawn.given
    params = SCENES["angular-momentum"].parameters.validate(exercise.scene.at(g)["params"])
    model = ShaftSpin.from_params(params)
    state = model.at(np.array([0.0]))
    assert _close_vector(drawn.answers["h"].value, state.angular_momentum_G[0], 1e-12)
    assert drawn.answers["energy"].value == pytest.approx(model.kinetic_energy_about_centre_J, rel=1e-12)

    points, masses = _box_particles(g["mass_kg"], g["length_m"], g["width_m"], g["height_m"])
    beta, spin = math.radians(g["tilt_deg"]), g["spin_rate_rad_s"]

    def positions(t):
        return points @ (_rot_z(spin * t) @ _rot_x(beta)).T

    h, energy, velocities = _momentum_and_energy(positions, masses, 0.0)
    assert _close_vector(drawn.answers["h"].value, h, 1.05 / 60**2)
    assert drawn.answers["energy"].value == pytest.approx(energy, rel=1.05 / 60**2)
    bearing = np.array([0.0, 0.0, -0.3])
    h_a = np.sum(masses[:, None] * np.cross(positions(0.0).real - bearing, velocities), axis=0)
    assert np.linalg.norm(h_a - h) <= 1e-12 * np.linalg.norm(h)
    assert drawn.answers["bearing"].value == "equal"


@pytest.mark.parametrize("number", VARIANTS)
def test_the_dumbbell_is_two_particles_summed(number):
    """The two balls as particles at this instant (rod along x, m₁ on the −x side of G), each velocity v_G + ω × ρ:
    H_G, H_O and T summed directly, and the expression evaluated at the given numbers. Same arithmetic by another
    route: 1e-12."""
    drawn = variant(_exercise("5-1-dumbbell-moving-centre"), number)
    g = drawn.given
    m1, m2, length = g["mass1_kg"], g["mass2_kg"], g["length_m"]
    centre = np.array([0.0, g["offset_m"], 0.0])
    v_g = np.array([g["speed_m_s"], 0.0, 0.0])
    omega = np.array([0.0, 0.0, g["spin_rad_s"]])
    rho = [np.array([-m2 * length / (m1 + m2), 0.0, 0.0]), np.array([m1 * length / (m1 + m2), 0.0, 0.0])]
    h_g, h_o, energy = np.zeros(3), np.zeros(3), 0.0
    for mass, arm in zip((m1, m2), rho, strict=True):
        velocity = v_g + np.cross(omega, arm)
        h_g += mass * np.cross(arm, velocity)
        h_o += mass * np.cross(centre + arm, velocity)
        energy += 0.5 * mass * float(velocity @ velocity)
    assert drawn.answers["hg"].value == pytest.approx(h_g[2], rel=1e-12)
    assert drawn.answers["ho"].value == pytest.approx(h_o[2], rel=1e-12)
    symbols = {str(s): s for s in drawn.answers["energy"].value.free_symbols}
    values = {symbols["m1"]: m1, symbols["m2"]: m2, symbols["L"]: length, symbols["v"]: g["speed_m_s"]}
    values[symbols["omega"]] = g["spin_rad_s"]
    assert float(drawn.answers["energy"].value.subs(values)) == pytest.approx(energy, rel=1e-12)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_edge_mill_roller_from_its_rotating_particles(number):
    """The roller as 108 000 particles moved by R(t) = R_z(vt/R) R_x(s t), G(t) = R_z(vt/R)(R, 0, r), with the spin
    rate s solved from the rolling condition (the contact point's velocity is linear in s: two evaluations).
    ω from Ṙ Rᵀ (complex step, exact to round-off): 1e-12. H_O = Σ mᵢ rᵢ × vᵢ and T = Σ ½ mᵢ vᵢ²: the ring
    centroids' second moments are within 1e-5, so 2e-5."""
    drawn = variant(_exercise("5-1-edge-mill-roller"), number)
    g = drawn.given
    mass, r, speed, circle = g["mass_kg"], g["radius_m"], g["speed_m_s"], g["circle_m"]
    turn = speed / circle

    def contact_velocity(spin):
        def contact(t):
            return _rot_z(turn * t) @ np.array([circle, 0.0, r]) + _rot_z(turn * t) @ _rot_x(spin * t) @ [0, 0, -r]

        step = 1e-30
        return np.imag(contact(complex(0.0, step))) / step

    base = contact_velocity(0.0)
    slope = contact_velocity(1.0) - base
    spin = -float(base @ slope) / float(slope @ slope)
    assert np.linalg.norm(contact_velocity(spin)) <= 1e-12 * speed

    step = 1e-30
    rate = np.imag(_rot_z(turn * complex(0, step)) @ _rot_x(spin * complex(0, step))) / step
    skew = rate  # Ṙ Rᵀ at t = 0, where R = 1
    omega = np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
    assert _close_vector(drawn.answers["omega"].value, omega, 1e-12)

    points, masses = _disk_particles(mass, r)

    def positions(t):
        return (_rot_z(turn * t) @ np.array([circle, 0.0, r]))[None, :] + points @ (
            _rot_z(turn * t) @ _rot_x(spin * t)
        ).T

    h_o, energy, _ = _momentum_and_energy(positions, masses, 0.0)
    assert _close_vector(drawn.answers["ho"].value, h_o, 2e-5)
    assert drawn.answers["energy"].value == pytest.approx(energy, rel=2e-5)


# -- 5.2 --------------------------------------------------------------------------------------------------------


def _bent_bar_particles(mass: float, a: float, b: float, n: int = 4000):
    """Each arm cut into n equal pieces at their midpoints (equal mass per length): second moments about any point
    within 1/n² = 6e-8 relative."""
    s = (np.arange(n) + 0.5) / n
    arm1 = np.stack([a * s, np.zeros(n)], axis=-1)
    arm2 = np.stack([np.zeros(n), b * s], axis=-1)
    points = np.concatenate([arm1, arm2])
    masses = np.concatenate([np.full(n, mass * a / (a + b) / n), np.full(n, mass * b / (a + b) / n)])
    return points, masses


@pytest.mark.parametrize("number", VARIANTS)
def test_the_bent_bars_principal_axis_is_where_its_moment_is_least(number):
    """The product Σ m (x − x_G)(y − y_G) over 8000 particles (1e-7); the least in-plane moment found by scanning the
    moment I(θ) = Σ m d(θ)² about lines through G at 3600 angles and polishing the minimum with brentq on dI/dθ
    (also a particle sum): angle to 1e-6 relative, moment to 1e-7."""
    drawn = variant(_exercise("5-2-bent-bar-principal"), number)
    g = drawn.given
    points, masses = _bent_bar_particles(g["mass_kg"], g["length_a_m"], g["length_b_m"])
    centre = masses @ points / masses.sum()
    x, y = (points - centre).T
    assert drawn.answers["product"].value == pytest.approx(float(np.sum(masses * x * y)), rel=1e-7)

    def moment(theta):
        return float(np.sum(masses * (-x * np.sin(theta) + y * np.cos(theta)) ** 2))

    def slope(theta):
        d = -x * np.sin(theta) + y * np.cos(theta)
        return float(np.sum(masses * 2 * d * (-x * np.cos(theta) - y * np.sin(theta))))

    angles = np.linspace(-np.pi / 2, np.pi / 2, 3601)
    k = int(np.argmin([moment(t) for t in angles]))
    best = brentq(slope, angles[k] - 2e-3, angles[k] + 2e-3, xtol=1e-15)
    expected_deg = (math.degrees(best) + 90.0) % 180.0 - 90.0
    answer = drawn.answers["angle"].value
    assert min(abs(answer - expected_deg), 180.0 - abs(answer - expected_deg)) <= 1e-6 * max(1.0, abs(answer))
    assert drawn.answers["least"].value == pytest.approx(moment(best), rel=1e-7)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cylinders_turned_components_come_from_integrating_it(number):
    """The tensor integrated exactly by sympy over the cylinder in cylindrical coordinates, turned by the exact
    R_x(α) (I' = Rᵀ I R); evaluated in floats: 1e-12. The ellipsoid's longest semi-axis found by sampling
    ρ(e) = 1/√(eᵀ I e) over 20 000 directions and reading whether the longest one lies along the axis."""
    drawn = variant(_exercise("5-2-cylinder-turned-frame"), number)
    g = drawn.given
    rho, phi, z = sympy.symbols("rho phi z", real=True)
    radius, length = sympy.Rational(str(g["radius_m"])), sympy.Rational(str(g["length_m"]))
    density = sympy.Rational(str(g["mass_kg"])) / (sympy.pi * radius**2 * length)
    x_, y_ = rho * sympy.cos(phi), rho * sympy.sin(phi)

    def integral(f):
        return sympy.integrate(
            f * density * rho, (rho, 0, radius), (phi, 0, 2 * sympy.pi), (z, -length / 2, length / 2)
        )

    ixx, izz = integral(y_**2 + z**2), integral(x_**2 + y_**2)
    tensor = sympy.diag(ixx, ixx, izz)  # the products vanish by symmetry
    assert integral(y_ * z) == 0 and integral(x_ * y_) == 0
    alpha = sympy.rad(sympy.Rational(str(g["angle_deg"])))
    turn = sympy.Matrix([[1, 0, 0], [0, sympy.cos(alpha), -sympy.sin(alpha)], [0, sympy.sin(alpha), sympy.cos(alpha)]])
    turned = turn.T * tensor * turn
    assert drawn.answers["izz"].value == pytest.approx(float(turned[2, 2]), rel=1e-12)
    assert drawn.answers["product"].value == pytest.approx(-float(turned[1, 2]), rel=1e-12)

    numeric = np.array(tensor, dtype=float)
    rng = np.random.default_rng(number)
    directions = rng.normal(size=(20000, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    reach = 1 / np.sqrt(np.einsum("ni,ij,nj->n", directions, numeric, directions))
    longest = directions[np.argmax(reach)]
    assert drawn.answers["ellipsoid"].value == ("along-axis" if abs(longest[2]) > 0.9 else "across-axis")


# -- 5.3 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_wheels_momentum_rate_is_the_derivative_of_its_particles_momentum(number):
    """The wheel as 108 000 particles moved by R(t) = R_z(Ωt) R_x(ω_s t + ½ω̇_s t²), H(t) = Σ mᵢ rᵢ × vᵢ with
    complex-step velocities, dH/dt by a central difference (see _rate_of_momentum); at t = 0 the turntable's axes are
    the fixed ones. Ring centroids' second moments within 1e-5, so 2e-5; the bearing force is |dH_y/dt|/s."""
    drawn = variant(_exercise("5-3-wheel-on-turntable"), number)
    g = drawn.given
    points, masses = _disk_particles(g["mass_kg"], g["radius_m"])
    table, spin, spin_rate = g["table_rad_s"], g["spin_rad_s"], g["spin_accel_rad_s2"]

    def positions(t):
        return points @ (_rot_z(table * t) @ _rot_x(spin * t + 0.5 * spin_rate * t * t)).T

    h, _, _ = _momentum_and_energy(positions, masses, 0.0)
    rate = _rate_of_momentum(positions, masses)
    assert _close_vector(drawn.answers["h"].value, h, 2e-5)
    assert _close_vector(drawn.answers["rate"].value, rate, 2e-5)
    assert drawn.answers["force"].value == pytest.approx(abs(rate[1]) / g["span_m"], rel=2e-5)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_plates_moment_is_the_derivative_of_its_particles_momentum(number):
    """The plate as 160 000 particles moved by R(t) = R_z(Ωt + ½Ω̇t²) R_x(β); ΣM_G = dH_G/dt by a central difference
    of the particle sum (see _rate_of_momentum). The grid's tensor is (1 − 1/400²) times the plate's (see _grid), 6.3e-6
    short, so 1e-5; torque and
    bearing force read off that vector."""
    drawn = variant(_exercise("5-3-plate-spin-up"), number)
    g = drawn.given
    points, masses = _plate_particles(g["mass_kg"], g["length_m"], g["width_m"])
    beta, spin, spin_rate = math.radians(g["tilt_deg"]), g["spin_rate_rad_s"], g["spin_accel_rad_s2"]

    def positions(t):
        return points @ (_rot_z(spin * t + 0.5 * spin_rate * t * t) @ _rot_x(beta)).T

    moment = _rate_of_momentum(positions, masses)
    assert _close_vector(drawn.answers["moment"].value, moment, 1e-5)
    assert drawn.answers["torque"].value == pytest.approx(moment[2], rel=1e-5)
    across = math.hypot(moment[0], moment[1]) / g["bearing_span_m"]
    assert drawn.answers["force"].value == pytest.approx(across, rel=1e-5)
