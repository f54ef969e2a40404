"""Worked example ``cantilever-two-term-ritz``: a cantilever's first two frequencies from two Ritz functions, by hand.

A uniform Euler–Bernoulli cantilever (length L, flexural rigidity EI, mass per length ρA) is clamped at x = 0 and free
at x = L; ξ = x/L. Hamilton's principle, restricted to deflections w(x, t) = q₁(t) ξ² + q₂(t) ξ³ (q in m), gives
M q̈ + K q = 0 with M_ij = ρA L ∫₀¹ ψ_i ψ_j dξ and K_ij = (EI/L³) ∫₀¹ ψ_i'' ψ_j'' dξ, whose integrals are written out
exactly here: M = ρA L [[1/5, 1/6], [1/6, 1/7]], K = (EI/L³) [[4, 6], [6, 12]]. The frequencies are the roots of
det(K − ω² M) = 0, a quadratic in ω². The check sets them beside the exact Euler–Bernoulli values
(β_n L)² √(EI/(ρA L⁴)), β_n L the roots of cos β cosh β = −1
(:func:`app.physics.systems.ch09.ritz_beam.exact_beta_L`): the Ritz values must lie above them.

The inputs carry the names of the scene ``ritz-cantilever``'s controls (length, EI, ρA), so that lesson drives them.
The default is a steel strip 1 m long, 26 mm wide and 4.9 mm thick (EI ≈ 50 N·m², ρA ≈ 1.0 kg/m). Every in-range
combination is a real beam; non-positive values are refused by :class:`~app.physics.systems.ch09.ritz_beam.Cantilever`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch09.ritz_beam import Cantilever

#: ∫₀¹ ψ_i ψ_j dξ for ψ = (ξ², ξ³) and ∫₀¹ ψ_i'' ψ_j'' dξ for ψ'' = (2, 6ξ): exact fractions.
MASS_INTEGRALS = np.array([[1.0 / 5.0, 1.0 / 6.0], [1.0 / 6.0, 1.0 / 7.0]])
STIFFNESS_INTEGRALS = np.array([[4.0, 6.0], [6.0, 12.0]])

INPUTS = ParameterSet(
    (
        Parameter("length_m", "m", 1.0, 0.2, 5.0, "Length L of the cantilever, clamp to free end", "L", step=0.01),
        Parameter(
            "flexural_rigidity_N_m2",
            "N·m²",
            50.0,
            1.0,
            1000.0,
            "Flexural rigidity EI of the cross-section",
            "EI",
            scale="log",
        ),
        Parameter("mass_per_length_kg_m", "kg/m", 1.0, 0.1, 20.0, "Mass per unit length ρA", "ρA", scale="log"),
    )
)


def two_term_frequencies(beam: Cantilever) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M (kg), K (N/m), ω (rad/s, shape (2,), ascending)) of the two-term Ritz model w = q₁ ξ² + q₂ ξ³.

    The roots of det(K − λM) = a λ² − b λ + c = 0 (λ = ω²): the smaller as c/(a·λ₊), free of cancellation.
    """
    M = beam.mass_per_length_kg_m * beam.length_m * MASS_INTEGRALS
    K = beam.flexural_rigidity_N_m2 / beam.length_m**3 * STIFFNESS_INTEGRALS
    a = float(np.linalg.det(M))
    b = float(K[0, 0] * M[1, 1] + K[1, 1] * M[0, 0] - 2.0 * K[0, 1] * M[0, 1])
    c = float(np.linalg.det(K))
    high = (b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
    low = c / (a * high)
    return M, K, np.sqrt(np.array([low, high]))


def solve(inputs: Mapping[str, Any]) -> Solution:
    beam = Cantilever(inputs["length_m"], inputs["flexural_rigidity_N_m2"], inputs["mass_per_length_kg_m"])
    scale = beam.frequency_scale_rad_s
    M, K, omega = two_term_frequencies(beam)
    one_term = math.sqrt(K[0, 0] / M[0, 0])
    # Mode 1's shape: (K − ω₁² M) q = 0, first row, with q₁ = 1.
    ratio = -float(K[0, 0] - omega[0] ** 2 * M[0, 0]) / (K[0, 1] - omega[0] ** 2 * M[0, 1])
    exact = beam.exact_omega_rad_s(2)
    error = omega / exact - 1.0
    steps = (
        Step(
            "Hamilton's principle over admissible functions that meet the clamp's conditions w(0) = w′(0) = 0",
            r"\delta\!\int_{t_1}^{t_2}(T - V)\,dt = 0,\quad w = q_1\xi^2 + q_2\xi^3,\quad "
            r"T = \tfrac12\dot q^{\mathsf T}M\dot q,\quad V = \tfrac12 q^{\mathsf T}Kq\ \Rightarrow\ M\ddot q + Kq = 0",
            {"L": beam.length_m, "EI": beam.flexural_rigidity_N_m2, "ρA": beam.mass_per_length_kg_m},
            {"L": "m", "EI": "N·m²", "ρA": "kg/m"},
        ),
        Step(
            "Mass and stiffness matrices from the energy integrals",
            r"M = \rho A L\begin{bmatrix}\frac15 & \frac16\\ \frac16 & \frac17\end{bmatrix},\quad "
            r"K = \frac{EI}{L^3}\begin{bmatrix}4 & 6\\ 6 & 12\end{bmatrix}",
            {"M_11": M[0, 0], "M_12": M[0, 1], "M_22": M[1, 1], "K_11": K[0, 0], "K_12": K[0, 1], "K_22": K[1, 1]},
            {"M_11": "kg", "M_12": "kg", "M_22": "kg", "K_11": "N/m", "K_12": "N/m", "K_22": "N/m"},
        ),
        Step(
            "One term alone (Rayleigh's quotient with w = q₁ξ²)",
            r"\omega \approx \sqrt{\frac{K_{11}}{M_{11}}} = \sqrt{20}\,\sqrt{\frac{EI}{\rho A L^4}}",
            {"√(EI/(ρA L⁴))": scale, "ω (1 term)": one_term},
            {"√(EI/(ρA L⁴))": "rad/s", "ω (1 term)": "rad/s"},
        ),
        Step(
            "Two terms: the frequency determinant, a quadratic in ω², and the first mode's shape",
            r"\det(K - \omega^2 M) = 0,\qquad \frac{q_2}{q_1} = -\frac{K_{11} - \omega_1^2 M_{11}}{K_{12} - "
            r"\omega_1^2 M_{12}}",
            {"ω_1": omega[0], "ω_2": omega[1], "f_1": omega[0] / (2.0 * math.pi), "q_2/q_1": ratio},
            {"ω_1": "rad/s", "ω_2": "rad/s", "f_1": "Hz", "q_2/q_1": ""},
        ),
        Step(
            "Check: the exact Euler–Bernoulli frequencies, which the Ritz values must not undercut",
            r"\cos\beta_nL\,\cosh\beta_nL = -1,\quad \omega_n = (\beta_nL)^2\sqrt{\frac{EI}{\rho A L^4}},\quad "
            r"\omega_1^{\rm exact} \le \omega_1^{\rm Ritz} \le \omega^{\rm 1\,term}",
            {
                "ω_1 exact": exact[0],
                "ω_1 Ritz": omega[0],
                "ω_1 error": 100.0 * error[0],
                "ω_2 exact": exact[1],
                "ω_2 Ritz": omega[1],
                "ω_2 error": 100.0 * error[1],
            },
            {
                "ω_1 exact": "rad/s",
                "ω_1 Ritz": "rad/s",
                "ω_1 error": "%",
                "ω_2 exact": "rad/s",
                "ω_2 Ritz": "rad/s",
                "ω_2 error": "%",
            },
        ),
    )
    outputs = {
        "one_term_omega_rad_s": one_term,
        "omega1_rad_s": float(omega[0]),
        "omega2_rad_s": float(omega[1]),
        "f1_Hz": float(omega[0]) / (2.0 * math.pi),
        "mode1_ratio": ratio,
        "exact_omega1_rad_s": float(exact[0]),
        "exact_omega2_rad_s": float(exact[1]),
        "omega1_error_percent": 100.0 * float(error[0]),
        "omega2_error_percent": 100.0 * float(error[1]),
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="cantilever-two-term-ritz",
    title="A clamped strip's first two frequencies from two Ritz functions",
    chapter=9,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "one_term_omega_rad_s": "rad/s",
        "omega1_rad_s": "rad/s",
        "omega2_rad_s": "rad/s",
        "f1_Hz": "Hz",
        "mode1_ratio": "",
        "exact_omega1_rad_s": "rad/s",
        "exact_omega2_rad_s": "rad/s",
        "omega1_error_percent": "%",
        "omega2_error_percent": "%",
    },
    section="9.1",
    story=ExampleStory(
        situation=(
            "A steel strip 1 m long, 26 mm wide and 4.9 mm thick is clamped in a vice at one end and free at the "
            "other. Its flexural rigidity is $EI \\approx 50$ N·m² and it carries $\\rho A \\approx 1.0$ kg per "
            "metre. Pluck it and it vibrates in bending; we treat it as an Euler–Bernoulli beam, leaving out shear "
            "and the rotary inertia of its cross-sections."
        ),
        wanted=(
            "Its two lowest natural frequencies, found by hand with the fewest admissible functions that can do "
            "the job, the shape of the first mode, and how far these estimates lie from the exact beam frequencies."
        ),
        approach=(
            "Hamilton's principle needs only the energies $T$ and $V$ and trial deflections that respect the clamp "
            "($w = w' = 0$ at $x = 0$); the free end's conditions need not be imposed, because the principle "
            "produces them. With $w = q_1\\xi^2 + q_2\\xi^3$ the energies are quadratic forms in $q$ whose integrals "
            "are simple fractions, and the beam becomes a two-degree-of-freedom system $M\\ddot q + Kq = 0$. "
            "Solving the beam's partial differential equation instead means a transcendental frequency equation "
            "and hyperbolic mode shapes; the Ritz route gives a $2\\times2$ determinant."
        ),
        check=(
            "For this beam the exact frequencies are known: $\\omega_n = (\\beta_nL)^2\\sqrt{EI/(\\rho AL^4)}$ with "
            "$\\beta_nL$ the roots of $\\cos\\beta L\\cosh\\beta L = -1$ (1.8751 and 4.6941). A Ritz model is a "
            "stiffer beam, since it may only bend in the shapes we allow it, so every Ritz frequency must lie at or "
            "above the exact one. The check computes both: the first is within 0.5 %, the second about 58 % high, "
            "and the one-term estimate is higher still."
        ),
        what_if=(
            "Move the **length L**. Every frequency scales as $1/L^2$, so doubling the length divides them all by "
            "four, while the percentage errors in the check do not move at all: they depend only on the trial "
            "functions. In the scene, set the number of terms to 2 and the basis to monomial to see these two "
            "numbers, then add terms and watch the second frequency fall onto the exact value."
        ),
    ),
)
