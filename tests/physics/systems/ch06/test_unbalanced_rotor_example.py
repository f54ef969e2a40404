"""The unbalanced-rotor worked example against particle sums: the disk cut into point masses, Newton's law for each.

The independent computation never forms an inertia tensor: the tilted thin disk is replaced by point masses on a
polar grid (Gauss–Legendre in the radius, equally spaced in angle), each with the centripetal acceleration
``−ω² (0, y, z)`` of a point turning about the shaft, and the reactions follow from the sums ``Σ m a`` and
``Σ r × m a`` about A. The integrands (the second moments of a disk) are polynomials of degree ≤ 3 in the radius and
trigonometric polynomials of degree 2 in the angle, which a 4-point Gauss rule and 8 equally spaced angles integrate
exactly, so both sides agree to round-off: 1e-10 of the force scale (m e ω² + m r² ω² β / L + m g) leaves some 10⁵
ulps for the few hundred products in the sums.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06.unbalanced_rotor_example import EXAMPLE

RTOL = 1e-10


def particles(m, r, e, a, beta):
    """Point masses (N,), positions (N, 3) in the rotor frame of a thin uniform disk centred at (a, e, 0), tilted by
    β about rotor y."""
    nodes, weights = np.polynomial.legendre.leggauss(4)
    rho = 0.5 * r * (nodes + 1.0)
    w_rho = 0.5 * r * weights * rho  # ∫ f ρ dρ
    psi = np.arange(8) * 2.0 * math.pi / 8
    u1 = np.array([0.0, 1.0, 0.0])
    u2 = np.array([-math.sin(beta), 0.0, math.cos(beta)])  # in the disk's plane, ⟂ to its normal (cos β, 0, sin β)
    R, PSI = np.meshgrid(rho, psi, indexing="ij")
    W = np.meshgrid(w_rho, psi, indexing="ij")[0] * (2.0 * math.pi / 8)
    points = np.array([a, e, 0.0]) + R[..., None] * (np.cos(PSI)[..., None] * u1 + np.sin(PSI)[..., None] * u2)
    masses = m * W / (math.pi * r * r)
    return masses.ravel(), points.reshape(-1, 3)


def by_particles(p):
    m, r, e, a = p["disk_mass_kg"], p["disk_radius_m"], p["eccentricity_m"], p["disk_position_m"]
    beta, omega, g, span = math.radians(p["skew_deg"]), p["shaft_speed_rad_s"], p["g_m_s2"], p["bearing_span_m"]
    masses, points = particles(m, r, e, a, beta)
    assert masses.sum() == pytest.approx(m, rel=1e-14)
    acc = -(omega**2) * points * np.array([0.0, 1.0, 1.0])
    force = (masses[:, None] * acc).sum(axis=0)
    moment = np.cross(points, masses[:, None] * acc).sum(axis=0)
    b_rot = np.array([0.0, moment[2] / span, -moment[1] / span])  # L i × R_B = transverse part of Σ r × m a
    a_rot = force - b_rot
    share_b = g * (masses * points[:, 0]).sum() / span
    share_a = m * g - share_b
    return {
        "bearing_A_rotating_N": a_rot,
        "bearing_B_rotating_N": b_rot,
        "bearing_A_N": a_rot + [0.0, 0.0, share_a],
        "bearing_B_N": b_rot + [0.0, 0.0, share_b],
        "bearing_A_peak_N": np.linalg.norm(a_rot) + share_a,
        "bearing_B_peak_N": np.linalg.norm(b_rot) + share_b,
        "driving_torque_Nm": g * (masses * points[:, 1]).sum(),
    }


CASES = [
    {},
    {"eccentricity_m": 0.0, "skew_deg": 5.0, "disk_position_m": 0.45},
    {"eccentricity_m": 0.004, "skew_deg": 0.0, "shaft_speed_rad_s": -250.0, "g_m_s2": 0.0},
    {"disk_mass_kg": 40.0, "disk_radius_m": 0.35, "skew_deg": -12.0, "bearing_span_m": 1.5, "disk_position_m": 1.2},
    {"shaft_speed_rad_s": 0.0, "eccentricity_m": 0.01},
]


@pytest.mark.parametrize("changes", CASES)
def test_the_example_matches_particle_sums(changes):
    p = EXAMPLE.inputs.validate(changes)
    outputs = EXAMPLE.solve(p).outputs
    expected = by_particles(p)
    m, r, omega, g = p["disk_mass_kg"], p["disk_radius_m"], p["shaft_speed_rad_s"], p["g_m_s2"]
    scale = m * (p["eccentricity_m"] + r * r * abs(math.radians(p["skew_deg"])) / p["bearing_span_m"]) * omega**2
    scale += m * g + m * r * omega**2 * 1e-3
    for name, value in expected.items():
        tolerance = RTOL * (scale * r if name == "driving_torque_Nm" else scale)
        np.testing.assert_allclose(outputs[name], value, rtol=0, atol=tolerance, err_msg=name)


def test_the_check_step_agrees_and_the_correction_masses_remove_the_rotating_loads():
    p = EXAMPLE.inputs.validate({"balanced": "on"})
    solution = EXAMPLE.solve(p)
    scale = p["disk_mass_kg"] * p["disk_radius_m"] * p["shaft_speed_rad_s"] ** 2
    for name in ("bearing_A_rotating_N", "bearing_B_rotating_N"):
        assert np.linalg.norm(solution.outputs[name]) <= 1e-12 * scale
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    default = EXAMPLE.solve(EXAMPLE.inputs.defaults())
    values, outputs = default.steps[-1].values, default.outputs
    np.testing.assert_allclose(values["R_A_rot_about_B"], outputs["bearing_A_rotating_N"], rtol=1e-12)
    np.testing.assert_allclose(values["R_A_rot_per_part"], outputs["bearing_A_rotating_N"], rtol=1e-12)
    np.testing.assert_allclose(values["R_B_rot_per_part"], outputs["bearing_B_rotating_N"], rtol=1e-12)


def test_impossible_inputs_are_refused():
    with pytest.raises(ParameterError, match="eccentricity"):
        EXAMPLE.inputs.validate({"eccentricity_m": 0.25, "disk_radius_m": 0.2})
    with pytest.raises(ValueError, match="between the bearings"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "disk_position_m": 0.9, "bearing_span_m": 0.6})
