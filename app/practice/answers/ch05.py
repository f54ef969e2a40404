"""Answers of chapter 5's exercises: inertia properties and angular momentum."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from app.physics.bodies import inertia
from app.practice.exercise import PartAnswer


def plate_about_corner(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin rectangular plate, sides a along x and b along y, axes xyz at corner O with the plate in the first
    quadrant of the xy plane: I_xx, I_xy (products with the minus sign, I = Σ m(ρ²1 − ρρᵀ)) and I_zz about O."""
    m, a, b = given["mass_kg"], given["length_m"], given["width_m"]
    centroidal = inertia.thin_plate(m, a, b)
    offset = np.array([a / 2, b / 2, 0.0])
    about_corner = inertia.parallel_axis(centroidal, m, offset)
    ixx, ixy, izz = float(about_corner[0, 0]), float(about_corner[0, 1]), float(about_corner[2, 2])
    return {
        "ixx": PartAnswer(
            ixx,
            r"I_{xx} = \tfrac{1}{12} m b^2 + m \left(\tfrac{b}{2}\right)^2 = \tfrac13 m b^2"
            rf" = {ixx:.4g}\ \mathrm{{kg\,m^2}}",
            {"no-parallel-axis": float(centroidal[0, 0]), "wrong-side": m * a**2 / 3},
        ),
        "ixy": PartAnswer(
            ixy,
            rf"I_{{xy}} = -m\,x_G\,y_G = -m \tfrac{{a}}{{2}} \tfrac{{b}}{{2}} = {ixy:.4g}\ \mathrm{{kg\,m^2}}",
            {"product-sign": -ixy, "centroidal-product": 0.0},
        ),
        "izz": PartAnswer(
            izz,
            r"I_{zz} = \tfrac{1}{12} m (a^2 + b^2) + m \tfrac{a^2 + b^2}{4} = \tfrac13 m (a^2 + b^2)"
            rf" = {izz:.4g}\ \mathrm{{kg\,m^2}}",
            {"no-parallel-axis": float(centroidal[2, 2])},
        ),
    }


def tilted_disk_bearings(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) on a shaft through its centre G, its axis tilted β from the shaft, spun at constant Ω;
    bearings a span L apart, G midway. |H_G|, the angle between H_G and ω, and the force on each bearing."""
    m, r, beta, omega, span = (
        given["mass_kg"],
        given["radius_m"],
        math.radians(given["tilt_deg"]),
        given["spin_rate_rad_s"],
        given["bearing_span_m"],
    )
    axial, transverse = 0.5 * m * r**2, 0.25 * m * r**2
    # ω in the disk's axes (axis z, the tilt about x): Ω (0, sin β, cos β); H_G = I ω.
    h_body = omega * np.array([0.0, transverse * math.sin(beta), axial * math.cos(beta)])
    h = float(np.linalg.norm(h_body))
    omega_body = omega * np.array([0.0, math.sin(beta), math.cos(beta)])
    cos_angle = float(np.dot(omega_body, h_body)) / (abs(omega) * h)
    angle = math.degrees(math.acos(min(1.0, cos_angle)))
    moment = omega**2 * (axial - transverse) * math.sin(beta) * math.cos(beta)
    force = abs(moment) / span
    return {
        "h": PartAnswer(
            h,
            r"\mathbf H_G = \Omega\,(0,\ I_t \sin\beta,\ I_a \cos\beta),"
            rf"\ |\mathbf H_G| = {h:.4g}\ \mathrm{{kg\,m^2/s}}",
            {
                "h-along-axis": axial * abs(omega),
                "h-along-shaft": (axial * math.cos(beta) ** 2 + transverse * math.sin(beta) ** 2) * abs(omega),
            },
        ),
        "angle": PartAnswer(
            angle,
            r"\cos\gamma = \frac{\boldsymbol\omega \cdot \mathbf H_G}{|\boldsymbol\omega|\,|\mathbf H_G|},"
            rf"\ \gamma = {angle:.4g}^\circ",
            {"radian-number": math.radians(angle)},
        ),
        "force": PartAnswer(
            force,
            r"|\dot{\mathbf H}_G| = |\boldsymbol\omega \times \mathbf H_G| = \Omega^2 (I_a - I_t) \sin\beta\cos\beta"
            rf" = {abs(moment):.4g}\ \mathrm{{N\,m}},\ F = |\dot{{\mathbf H}}_G| / L = {force:.4g}\ \mathrm{{N}}",
            {"half-span": 2 * force, "moment-not-force": abs(moment)},
        ),
    }
