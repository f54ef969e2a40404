"""Exact integrals over the bodies of the angular-momentum scene (a thin plate, a box, a thin disk), for the tests of
the chapter 5 worked examples: sympy integrates a quantity over the body's own volume or area, element by element,
with uniform density, so no inertia formula (table, tensor or particles) enters."""

from __future__ import annotations

import sympy as sp

t = sp.Symbol("t", real=True)
x, y, z, r, q = sp.symbols("x y z r q", real=True)


def exact(value):
    """A float input as the exact rational it was typed as (0.4 → 2/5)."""
    return sp.Rational(str(value))


def rot(axis, angle):
    c, s = sp.cos(angle), sp.sin(angle)
    if axis == "x":
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def element(p):
    """(body-axis position of the element (3×1), density × measure factor, integration limits) for the shape."""
    m = exact(p["mass_kg"])
    if p["body"] == "plate":
        a, b = exact(p["length_m"]), exact(p["width_m"])
        return sp.Matrix([x, y, 0]), m / (a * b), [(x, -a / 2, a / 2), (y, -b / 2, b / 2)]
    if p["body"] == "box":
        a, b, c = exact(p["length_m"]), exact(p["width_m"]), exact(p["height_m"])
        return sp.Matrix([x, y, z]), m / (a * b * c), [(x, -a / 2, a / 2), (y, -b / 2, b / 2), (z, -c / 2, c / 2)]
    radius = exact(p["radius_m"])
    return (
        sp.Matrix([r * sp.cos(q), r * sp.sin(q), 0]),
        m * r / (sp.pi * radius**2),
        [(r, 0, radius), (q, 0, 2 * sp.pi)],
    )


def motion(p, moving):
    """(position of the element in world axes, as a function of t; the centre of mass r_G(t)) for the scene's motion:
    R(t) = Rz(Ω t) Rx(tilt), and G moving at v_G from r_G(0) when ``moving`` (the particles view)."""
    local, _, _ = element(p)
    spin, tilt = exact(p["spin_rate_rad_s"]), exact(p["tilt_deg"]) * sp.pi / 180
    if moving:
        centre = sp.Matrix([exact(c) for c in p["centre_position_m"]]) + t * sp.Matrix(
            [exact(c) for c in p["centre_velocity_m_s"]]
        )
    else:
        centre = sp.zeros(3, 1)
    return centre + rot("z", spin * t) * rot("x", tilt) * local, centre


def integrate(p, integrand):
    """∫ integrand dm over the body (integrand: a sympy expression or matrix in the element's coordinates, at t = 0)."""
    _, density, limits = element(p)

    def one(expr):
        return sp.integrate(sp.expand(expr * density), *limits)

    return integrand.applyfunc(one) if isinstance(integrand, sp.MatrixBase) else one(integrand)
