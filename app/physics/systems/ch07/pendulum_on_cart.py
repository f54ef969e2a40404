"""A pendulum hanging from a cart that slides on a horizontal rail, held by a spring and pushed by a force.

Frame N: x along the rail, z up. The cart (a particle, mass M) is at x; the
spring (stiffness k, relaxed at x = 0) ties it to the wall; a horizontal force
F0 cos(Ω t) drives it. The bob (mass m) hangs on a massless rod of length l
at angle θ from the downward vertical. Rheonomic only through the force.
"""

from __future__ import annotations

import sympy

from app.physics.core.parameters import ParameterSet
from app.physics.mechanics.description import (
    TIME,
    AppliedForce,
    Coordinate,
    Particle,
    Reaction,
    Spring,
    SystemDescription,
    parameter,
    vector,
)

M, m, l, k, F0, Omega, g = sympy.symbols("M m l k F_0 Omega g", positive=True)
x = Coordinate("x", "x", unit="m")
theta = Coordinate("theta", "\\theta")
cart = vector(x.symbol, 0, 0)
bob = cart + vector(l * sympy.sin(theta.symbol), 0, -l * sympy.cos(theta.symbol))
ex, ey, ez = vector(1, 0, 0), vector(0, 1, 0), vector(0, 0, 1)

SYSTEM = SystemDescription(
    id="pendulum-on-cart",
    title="Pendulum hanging from a sprung, driven cart",
    chapter=7,
    coordinates=(x, theta),
    parameters=ParameterSet(
        (
            parameter("cart_mass_kg", "kg", 2.0, low=0.01, high=100.0, label="M", description="Mass of the cart"),
            parameter("bob_mass_kg", "kg", 1.0, low=0.01, high=100.0, label="m", description="Mass of the bob"),
            parameter("length_m", "m", 1.0, low=0.05, high=10.0, label="l", description="Length of the rod"),
            parameter(
                "stiffness_N_m",
                "N/m",
                20.0,
                low=0.0,
                high=10000.0,
                label="k",
                description="Stiffness of the spring holding the cart",
            ),
            parameter(
                "force_amplitude_N",
                "N",
                0.0,
                low=0.0,
                high=1000.0,
                label="F₀",
                description="Amplitude of the horizontal force on the cart",
            ),
            parameter(
                "force_frequency_rad_s",
                "rad/s",
                3.0,
                low=0.0,
                high=100.0,
                label="Ω",
                description="Angular frequency of that force",
            ),
            parameter("g_m_s2", "m/s²", 9.81, low=0.0, high=100.0, label="g", description="Gravitational acceleration"),
        )
    ),
    symbols={
        "cart_mass_kg": M,
        "bob_mass_kg": m,
        "length_m": l,
        "stiffness_N_m": k,
        "force_amplitude_N": F0,
        "force_frequency_rad_s": Omega,
        "g_m_s2": g,
    },
    particles=(Particle("cart", M, cart), Particle("bob", m, bob)),
    gravity=vector(0, 0, -g),
    springs=(Spring(k, sympy.Integer(0), vector(0, 0, 0), cart, axis=ex, on_b="cart"),),
    forces=(AppliedForce("drive", cart, F0 * sympy.cos(Omega * TIME) * ex, on="cart"),),
    reactions=(
        Reaction("rail", on="cart", point=cart, forces=(ey, ez)),
        Reaction("rod", on="bob", point=bob, forces=((cart - bob) / l,), against="cart"),
        Reaction("plane", on="bob", point=bob, forces=(ey,)),
    ),
    assumptions="Frictionless rail and pin, massless rod, the cart and the bob as particles, a linear spring.",
)
