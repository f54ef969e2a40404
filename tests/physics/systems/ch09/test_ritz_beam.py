"""The Ritz series for the cantilever (app/physics/systems/ch09/ritz_beam.py): exact roots, upper bounds, convergence,
the N = 1 closed form, the monomial basis failing and the simulate model's answer."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch09 import ritz_beam as physics

BEAM = physics.Cantilever(1.0, 50.0, 1.0)
#: Published roots of cos βL cosh βL = −1 (Blevins, *Formulas for natural frequency and mode shape*, table 8-1).
PUBLISHED_BETA_L = (1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547, 14.13716839104647)


def test_exact_roots_match_the_published_values():
    # The published values carry 16 significant figures; the root of a function with slope ≈ 1 is found to a few ulp.
    np.testing.assert_allclose(physics.exact_beta_L(5), PUBLISHED_BETA_L, rtol=1e-14, atol=0.0)


def test_exact_roots_solve_the_frequency_equation_for_high_modes_without_overflow():
    beta = physics.exact_beta_L(200)  # β₂₀₀ L ≈ 627: cosh β itself is ≈ 1e272, near overflow, the cosh-free form is not
    assert np.all(np.isfinite(beta)) and np.all(np.diff(beta) > 0.0)
    # cos β + sech β = 0 to rounding of cos at β (|β| ulp ≈ 1e-13 at 627, slope ≈ 1).
    assert np.max(np.abs(physics.frequency_equation(beta))) < 1e-12
    # For large n the root approaches (n − ½)π from alternate sides by about 2e^{−β}: below 1e-12 from mode 30 on.
    n = np.arange(1, 201)
    assert np.max(np.abs(beta[29:] - (n[29:] - 0.5) * math.pi)) < 1e-12


@pytest.mark.parametrize("mode", [1, 2, 5, 14])
def test_exact_mode_shape_meets_the_boundary_conditions_and_the_beam_equation(mode):
    beta = float(physics.exact_beta_L(mode)[-1])
    xi = np.linspace(0.0, 1.0, 11)
    phi = physics.exact_mode_shape(beta, xi)
    curvature = physics.exact_mode_shape(beta, xi, derivative=2)
    scale = np.max(np.abs(phi))  # ≈ 2: errors are judged against it; 1e-12 allows the e^{±u} terms' rounding at β ≈ 42
    assert abs(phi[0]) < 1e-12 * scale  # clamp: no deflection
    assert abs(curvature[-1]) < 1e-12 * beta**2 * scale  # free end: no bending moment
    # Clamp slope by a central difference: truncation h²|φ'''|/6 ≤ h² β³ scale/6, rounding ≈ u·scale/h.
    h = 1e-5
    slope0 = (physics.exact_mode_shape(beta, np.array([h])) - physics.exact_mode_shape(beta, np.array([-h])))[0] / (2 * h)
    assert abs(slope0) < h * h * beta**3 * scale / 3.0 + 1e-10
    # φ'' against a 5-point stencil of φ: truncation h⁴|φ⁽⁶⁾|/90 ≤ h⁴ β⁶ scale/90, rounding ≈ 64 u·scale/(12 h²); twice their sum.
    h = 1e-3
    stencil = (-physics.exact_mode_shape(beta, xi + 2 * h) + 16 * physics.exact_mode_shape(beta, xi + h) - 30 * phi
               + 16 * physics.exact_mode_shape(beta, xi - h) - physics.exact_mode_shape(beta, xi - 2 * h)) / (12 * h * h)  # fmt: skip
    tolerance = 2.0 * (h**4 * beta**6 * scale / 90.0 + 64 * 1.1e-16 * scale / (12 * h * h))
    np.testing.assert_allclose(stencil, curvature, rtol=0.0, atol=tolerance)


def test_one_monomial_term_gives_omega_squared_twenty_ei_over_rho_a_l4():
    # w = q ξ²: V = ½ EI ∫ (2q/L)² dx = 2 EI q²/L³ and T = ½ ρA L q̇² ∫ ξ⁴ dξ = ρA L q̇²/10, so ω² = (4 EI/L³)/(ρA L/5) = 20 EI/(ρA L⁴).
    beam = physics.Cantilever(2.0, 300.0, 3.0)
    ritz = physics.RitzCantilever.build(beam, basis="monomial", terms=1)
    expected = math.sqrt(20.0 * 300.0 / (3.0 * 2.0**4))
    assert ritz.ritz_omega_rad_s[0] == pytest.approx(expected, rel=1e-15)
    assert ritz.relative_error[0] == pytest.approx(math.sqrt(20.0) / 1.875104068711961**2 - 1.0, rel=1e-13)  # 27.2 % high


@pytest.mark.parametrize("basis", physics.BASES)
def test_ritz_matrices_are_the_integrals_they_claim(basis):
    # Independent adaptive quadrature of ∫ φ_i φ_j and ∫ φ_i'' φ_j'' (quad's absolute error ≈ 1e-14 on these smooth polynomials).
    ritz_basis = physics.ritz_basis(basis, 5)
    for i in range(5):
        for j in range(5):
            mass = quad(lambda x: ritz_basis.values(np.array([x]))[i, 0] * ritz_basis.values(np.array([x]))[j, 0], 0.0, 1.0)[0]
            stiffness = quad(lambda x: ritz_basis.curvatures(np.array([x]))[i, 0] * ritz_basis.curvatures(np.array([x]))[j, 0], 0.0, 1.0)[0]
            assert ritz_basis.mass[i, j] == pytest.approx(mass, rel=1e-12, abs=1e-14)
            assert ritz_basis.stiffness[i, j] == pytest.approx(stiffness, rel=1e-12, abs=1e-12)
    values = ritz_basis.values(np.array([0.0]))
    assert np.all(values == 0.0)  # admissible: φ(0) = 0 (φ'(0) = 0 is built in: the lowest power is ξ²)


def test_orthogonal_ritz_frequencies_are_upper_bounds_that_fall_as_terms_are_added():
    rows = physics.convergence_table(BEAM, basis="orthogonal")
    floor = 1e-13  # rounding floor of a converged frequency (eigh on a matrix of cond ≤ 3e7 whose largest μ is the converged one)
    for row in rows:
        assert row.factorized
        # Rayleigh–Ritz: ω_Ritz ≥ ω_exact for every mode; BOUND_SLACK (1e-12) is the rounding allowance, justified in the module.
        assert np.all(row.relative_error >= -physics.BOUND_SLACK), (row.terms, row.relative_error)
    for mode in range(1, physics.MAX_TERMS + 1):
        errors = np.array([row.relative_error[mode - 1] for row in rows if row.terms >= mode])
        # Nested trial spaces: adding a term never raises a frequency (1e-15 absolute allows ties at the floor).
        assert np.all(np.diff(errors) <= 1e-15), (mode, errors)
        # and two more terms always buy a real gain until the floor is reached.
        for before, after in zip(errors[:-2], errors[2:]):
            if before > floor:
                assert after < 0.5 * before, (mode, errors)
    # The first mode converges to rounding: 1e-15 of the exact value by N = 8.
    assert abs(rows[7].relative_error[0]) < 1e-14
    # cond(M) of the orthogonal basis is the spread of the Ritz frequencies, (λ_N/λ_1)², nothing more.
    for row in rows:
        spread = (row.ritz_omega_rad_s[-1] / row.ritz_omega_rad_s[0]) ** 2
        assert row.condition_mass == pytest.approx(spread, rel=1e-8)


def test_both_bases_span_the_same_space_so_agree_while_monomials_are_well_conditioned():
    # Same polynomials (degrees 2 … N+1): in exact arithmetic identical Ritz values. At N = 5 cond(M) ≈ 3e7 for the
    # monomials, so u·cond ≈ 3e-9 bounds their disagreement.
    for terms in range(1, 6):
        orthogonal = physics.RitzCantilever.build(BEAM, basis="orthogonal", terms=terms)
        monomial = physics.RitzCantilever.build(BEAM, basis="monomial", terms=terms)
        np.testing.assert_allclose(monomial.ritz_omega_rad_s, orthogonal.ritz_omega_rad_s, rtol=1e-8)


def test_the_monomial_basis_fails_as_terms_grow():
    """The hard case, with its pass criteria: cond(M) grows geometrically past 1e16, the upper bound breaks,
    some ω² go negative, and the readout's warning says so; the orthogonal basis does none of this."""
    rows = physics.convergence_table(BEAM, basis="monomial")
    conditions = np.array([row.condition_mass for row in rows])
    assert conditions[10] > 1e16 and conditions[0] == pytest.approx(1.0)  # M is 1×1 at N = 1
    assert np.all(conditions[1:9] / conditions[:8] > 20.0)  # about 40× per term while it can still be measured
    worst_below = min(float(np.nanmin(row.relative_error)) for row in rows)
    assert worst_below < -1e-3  # some frequency ends up more than 0.1 % below its exact value: the bound is gone
    broken = physics.RitzCantilever.build(BEAM, basis="monomial", terms=14)
    assert broken.modes.nonphysical > 0 or not broken.modes.factorized  # imaginary frequencies (or no factor at all)
    assert "Do not trust" in broken.warning()
    assert physics.RitzCantilever.build(BEAM, basis="monomial", terms=7).warning()  # u·cond(M) ≈ 6e-6 > 1e-6: warned
    assert not physics.RitzCantilever.build(BEAM, basis="monomial", terms=5).warning()
    assert not any(physics.RitzCantilever.build(BEAM, basis="orthogonal", terms=n).warning() for n in range(1, 15))


def test_ritz_mode_shapes_approach_the_exact_ones_and_the_energy_is_constant():
    xi = np.linspace(0.0, 1.0, 41)
    ritz = physics.RitzCantilever.build(BEAM, basis="orthogonal", terms=12)
    for mode in (1, 2, 3):
        # Mode shapes converge like the square root of the frequency error or better: 1e-5 at N = 12 for the first three.
        np.testing.assert_allclose(ritz.ritz_shape(mode, xi), BEAM.exact_shape(mode, xi), atol=1e-5)
        assert ritz.ritz_root_curvature(mode) == pytest.approx(BEAM.exact_root_curvature(mode), rel=1e-4)
        energy = ritz.modal_energy_J(mode, 0.1, np.linspace(0.0, 1.0, 50))
        np.testing.assert_allclose(energy, energy[0], rtol=1e-12)  # K v = ω² M v to rounding (cond ≤ 1e7 → ≤ 1e-9 would also pass)
    assert BEAM.exact_root_curvature(1) == pytest.approx(3.516015, rel=1e-6)  # 2 β₁² / (L² φ(1)) with φ(1) = 2


def test_simulate_answer_matches_the_closed_form_and_flags_the_failing_basis():
    model = physics.RitzCantileverModel()
    report = model.simulate(physics.PARAMETERS.defaults(), {}, t_end_s=1.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] == "ok" and list(report["series"]) == list(model.series_units)
    omega = physics.RitzCantilever.from_params(physics.PARAMETERS.defaults()).ritz_omega_rad_s[0]
    np.testing.assert_allclose(report["series"]["tip_deflection_m"], 0.2 * np.cos(omega * np.array(report["t"])), rtol=0, atol=1e-15)
    assert report["stats"]["max_invariant_drift"] < 1e-12
    failing = physics.PARAMETERS.validate({"basis": "monomial", "terms": 14, "mode": 14})
    report = model.simulate(failing, {}, t_end_s=1.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] in ("undefined", "outside_model") and "Do not trust" in report["stats"]["message"]


def test_bad_inputs_name_their_field():
    with pytest.raises(ParameterError) as excinfo:
        physics.PARAMETERS.validate({"terms": 3, "mode": 4})
    assert excinfo.value.field == "mode"
    with pytest.raises(ParameterError) as excinfo:
        physics.PARAMETERS.validate({"terms": 15})
    assert excinfo.value.field == "terms"
    with pytest.raises(ParameterError) as excinfo:
        physics.Cantilever(1.0, -1.0, 1.0)
    assert excinfo.value.field == "flexural_rigidity_N_m2"
