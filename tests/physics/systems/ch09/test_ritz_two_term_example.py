"""The two-term Ritz cantilever example against sympy and the project's general Ritz model.

Independent computation: sympy integrates T and V of w = q₁ξ² + q₂ξ³ symbolically (nothing from the example's
fractions), solves det(K − λM) = 0 exactly, and evaluates it at the inputs; the exact β_n L come from mpmath's root
of cos β cosh β = −1 at 30 digits. Tolerance 1e-12 relative: the example's arithmetic is a few dozen floating-point
operations on numbers of one scale (about 1e-15 each) and its quadratic's small root is taken without cancellation,
so 1e-12 leaves a thousandfold margin for rounding and none for a wrong fraction (which would be off by percents).
"""

from __future__ import annotations

import math

import mpmath
import pytest
import sympy

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch09.ritz_beam import Cantilever, RitzCantilever
from app.physics.systems.ch09.ritz_two_term_example import EXAMPLE

RTOL = 1e-12

CASES = [
    {},  # defaults
    {"length_m": 0.35, "flexural_rigidity_N_m2": 2.0, "mass_per_length_kg_m": 0.4},
    {"length_m": 4.2, "flexural_rigidity_N_m2": 900.0, "mass_per_length_kg_m": 18.0},
    {"length_m": 2.0, "flexural_rigidity_N_m2": 13.0, "mass_per_length_kg_m": 0.15},
]


def _sympy_ritz(L: float, EI: float, rhoA: float) -> tuple[float, float, float, float]:
    """(one-term ω, ω₁, ω₂, q₂/q₁ of mode 1) from energies integrated by sympy."""
    xi, lam = sympy.symbols("xi lambda", positive=True)
    psi = [xi**2, xi**3]
    M = sympy.Matrix(2, 2, lambda i, j: rhoA * L * sympy.integrate(psi[i] * psi[j], (xi, 0, 1)))
    K = sympy.Matrix(
        2,
        2,
        lambda i, j: EI / L**3 * sympy.integrate(sympy.diff(psi[i], xi, 2) * sympy.diff(psi[j], xi, 2), (xi, 0, 1)),
    )
    roots = sorted(sympy.Poly((K - lam * M).det(), lam).nroots(n=30))
    low = roots[0]
    ratio = -(K[0, 0] - low * M[0, 0]) / (K[0, 1] - low * M[0, 1])
    return (
        float(sympy.sqrt(K[0, 0] / M[0, 0])),
        float(sympy.sqrt(low)),
        float(sympy.sqrt(roots[1])),
        float(ratio),
    )


def _exact_beta_L(n: int) -> float:
    mpmath.mp.dps = 30
    return float(mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) + 1, (n - 0.5) * mpmath.pi))


@pytest.mark.parametrize("change", CASES)
def test_frequencies_match_an_independent_symbolic_ritz_and_the_exact_roots(change):
    inputs = EXAMPLE.inputs.validate(change)
    out = EXAMPLE.solve(inputs).outputs
    L, EI, rhoA = inputs["length_m"], inputs["flexural_rigidity_N_m2"], inputs["mass_per_length_kg_m"]
    one, w1, w2, ratio = _sympy_ritz(L, EI, rhoA)
    assert out["one_term_omega_rad_s"] == pytest.approx(one, rel=RTOL)
    assert out["omega1_rad_s"] == pytest.approx(w1, rel=RTOL)
    assert out["omega2_rad_s"] == pytest.approx(w2, rel=RTOL)
    assert out["f1_Hz"] == pytest.approx(w1 / (2 * math.pi), rel=RTOL)
    assert out["mode1_ratio"] == pytest.approx(ratio, rel=RTOL)
    scale = math.sqrt(EI / (rhoA * L**4))
    for n, name in ((1, "exact_omega1_rad_s"), (2, "exact_omega2_rad_s")):
        assert out[name] == pytest.approx(_exact_beta_L(n) ** 2 * scale, rel=RTOL)
    # The upper bound the check shows, and the project's general Ritz model (monomials, N = 2: the same span).
    assert out["exact_omega1_rad_s"] < out["omega1_rad_s"] < out["one_term_omega_rad_s"]
    assert out["exact_omega2_rad_s"] < out["omega2_rad_s"]
    general = RitzCantilever.build(Cantilever(L, EI, rhoA), basis="monomial", terms=2).ritz_omega_rad_s
    assert [out["omega1_rad_s"], out["omega2_rad_s"]] == pytest.approx(list(general), rel=RTOL)


def test_a_beam_without_length_is_refused():
    """Every in-range beam exists; a zero length (out of range, reached by calling solve directly) is refused."""
    with pytest.raises(ParameterError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "length_m": 0.0})
    with pytest.raises(ValueError):
        EXAMPLE.inputs.validate({"length_m": 0.1})
