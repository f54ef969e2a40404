"""Each exercise's answer function against an independent computation (tolerances stated at each check): the plate's
inertia by summing its area on a grid, the tilted disk by summing it as particles and by the scene's own shaft-spin
model, the bead's energies from its position vector and its equation from the derivation engine."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from app.physics.mechanics.description import TIME
from app.physics.mechanics.engine import derived
from app.physics.systems.ch05.angular_momentum import ShaftSpin
from app.physics.systems.ch07 import bead_on_hoop
from app.practice.variants import variant
from app.scenes import SCENES
from tests.practice.shipped import EXERCISES

VARIANTS = range(0, 100, 7)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_plates_inertia_about_its_corner_is_the_sum_over_its_area(number):
    """Midpoint rule on an 800 × 800 grid: exact for the products; for a moment it falls short of ∫y² dA by exactly
    1/(4·800²) = 3.9e-7 of it, so 4e-7 relative."""
    drawn = variant(EXERCISES["5-2-plate-about-corner"], number)
    m, a, b = drawn.given["mass_kg"], drawn.given["length_m"], drawn.given["width_m"]
    n = 800
    x = (np.arange(n) + 0.5) * a / n
    y = (np.arange(n) + 0.5) * b / n
    X, Y = np.meshgrid(x, y)
    dm = m / n**2
    sums = {"ixx": dm * np.sum(Y**2), "ixy": -dm * np.sum(X * Y), "izz": dm * np.sum(X**2 + Y**2)}
    for part, expected in sums.items():
        assert drawn.answers[part].value == pytest.approx(expected, rel=4e-7), part


def _disk_particles(mass_kg: float, radius_m: float, rings: int = 300, sectors: int = 360):
    """The disk (its own axes, normal z) as point masses on a polar grid of equal-area cells' centroids."""
    edges = np.linspace(0.0, radius_m, rings + 1)
    r = (2 / 3) * (edges[1:] ** 3 - edges[:-1] ** 3) / (edges[1:] ** 2 - edges[:-1] ** 2)  # each ring's centroid
    ring_mass = mass_kg * (edges[1:] ** 2 - edges[:-1] ** 2) / radius_m**2
    phi = (np.arange(sectors) + 0.5) * 2 * np.pi / sectors
    R, PHI = np.meshgrid(r, phi)
    points = np.stack([R * np.cos(PHI), R * np.sin(PHI), np.zeros_like(R)], axis=-1).reshape(-1, 3)
    masses = np.broadcast_to(ring_mass / sectors, R.shape).reshape(-1)
    return points, masses


@pytest.mark.parametrize("number", VARIANTS)
def test_the_tilted_disk_matches_its_particles_and_the_scenes_own_model(number):
    """H = Σ mᵢ ρᵢ × (ω × ρᵢ) over 108 000 particles (relative error of the ring centroids' second moment < 1e-5);
    the scene's ShaftSpin model at the exercise's "See it" parameters agrees to 1e-12."""
    exercise = EXERCISES["5-3-tilted-disk-bearings"]
    drawn = variant(exercise, number)
    g = drawn.given
    beta = math.radians(g["tilt_deg"])
    omega_body = g["spin_rate_rad_s"] * np.array([0.0, math.sin(beta), math.cos(beta)])
    points, masses = _disk_particles(g["mass_kg"], g["radius_m"])
    h = np.sum(masses[:, None] * np.cross(points, np.cross(omega_body, points)), axis=0)
    angle = math.degrees(math.acos(np.dot(h, omega_body) / (np.linalg.norm(h) * np.linalg.norm(omega_body))))
    force = np.linalg.norm(np.cross(omega_body, h)) / g["bearing_span_m"]
    assert drawn.answers["h"].value == pytest.approx(np.linalg.norm(h), rel=1e-5)
    assert drawn.answers["angle"].value == pytest.approx(angle, rel=1e-4)
    assert drawn.answers["force"].value == pytest.approx(force, rel=1e-5)
    params = SCENES["angular-momentum"].parameters.validate(exercise.scene.at(g)["params"])
    model = ShaftSpin.from_params(params)
    assert drawn.answers["h"].value == pytest.approx(model.angular_momentum_magnitude_kg_m2_s, rel=1e-12)
    assert drawn.answers["force"].value == pytest.approx(model.bearing_moment_N_m / g["bearing_span_m"], rel=1e-12)
    assert drawn.answers["angle"].value == pytest.approx(math.degrees(model.angle_between_omega_and_H), rel=1e-12)


def test_the_beads_energies_come_from_its_position_and_its_equation_from_the_derivation_engine():
    """T and V from the bead's position vector (sympy, exactly); θ̈ against the engine's Lagrange derivation at 50
    random states (1e-12 relative); the steady angle makes the engine's θ̈ vanish (to 1e-9 rad/s²)."""
    exercise = EXERCISES["7-5-bead-on-hoop-lagrange"]
    drawn = variant(exercise, 3)
    theta, thetad, m, R, Omega, g = sympy.symbols("theta thetad m R Omega g", real=True)
    system = bead_on_hoop.SYSTEM
    rename = {
        bead_on_hoop.th: theta,
        bead_on_hoop.m: m,
        bead_on_hoop.R: R,
        bead_on_hoop.Omega: Omega,
        bead_on_hoop.g: g,
    }
    t = TIME  # the description's own time symbol (the hoop's angle is Ω t)
    position = bead_on_hoop.bead.subs(bead_on_hoop.th, sympy.Function("q")(t))
    velocity = [sympy.diff(c, t) for c in position]
    q = sympy.Function("q")(t)
    kinetic = sum(v**2 for v in velocity) * bead_on_hoop.m / 2
    kinetic = kinetic.subs(sympy.Derivative(q, t), thetad).subs(q, theta).subs(rename)
    assert sympy.simplify(kinetic - drawn.answers["kinetic"].value) == 0
    height = position[2].subs(q, theta).subs(rename)
    assert sympy.simplify(m * g * height - drawn.answers["potential"].value) == 0
    engine = derived(system, "lagrange")
    rng = np.random.default_rng(5)
    acceleration = drawn.answers["equation"].value
    for _ in range(50):
        radius, spin, gravity, mass = rng.uniform(0.1, 2), rng.uniform(0.5, 20), rng.uniform(1, 20), rng.uniform(0.1, 2)
        state = np.array([rng.uniform(0.1, 3.0), rng.uniform(-5, 5)])
        p = np.array(
            system.parameter_array(
                {"hoop_radius_m": radius, "hoop_speed_rad_s": spin, "g_m_s2": gravity, "bead_mass_kg": mass}
            )
        )
        expected = engine.state_derivative(0.3, state, p)[1]
        ours = float(acceleration.subs({theta: state[0], R: radius, Omega: spin, g: gravity}))
        assert ours == pytest.approx(expected, rel=1e-12, abs=1e-12 * (spin**2 + gravity / radius))
    given = drawn.given
    p = np.array(
        system.parameter_array(
            {
                "hoop_radius_m": given["hoop_radius_m"],
                "hoop_speed_rad_s": given["hoop_speed_rad_s"],
                "g_m_s2": given["g_m_s2"],
                "bead_mass_kg": 0.1,
            }
        )
    )
    steady = math.radians(drawn.answers["steady"].value)
    assert abs(engine.state_derivative(0.0, np.array([steady, 0.0]), p)[1]) < 1e-9
