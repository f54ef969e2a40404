"""Every catalogue system's formulations give the same motion: numerically at 200 random states, symbolically where quick."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy

from app.physics.mechanics.agreement import formulation_agreement, proves_same_equations, random_states, reference_formulation
from app.physics.mechanics.derivation import Recipe, Solve
from app.physics.mechanics.engine import DERIVERS, available_formulations, derived, load_recipe
from app.physics.systems import analytical_systems

SYSTEMS = analytical_systems()

#: The issue's bound. Observed: 4.7e-14 for the heavy top (Euler angles, θ in 0.2…2.9 rad), ≤ 6e-15 elsewhere:
#: the formulations share no intermediate expression, so this is rounding in independently generated code.
AGREEMENT = 1e-12


def test_the_catalogue_holds_the_issue_systems_with_their_contract_parameters():
    assert {"double-pendulum", "bead-on-rotating-hoop", "simple-pendulum", "pendulum-on-cart", "spherical-pendulum", "heavy-top", "rolling-disk"} <= set(SYSTEMS)
    double = SYSTEMS["double-pendulum"]
    assert [c.name for c in double.coordinates] == ["theta1", "theta2"]
    assert {"m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"} <= set(double.parameters.by_name)
    hoop = SYSTEMS["bead-on-rotating-hoop"]
    assert [c.name for c in hoop.coordinates] == ["theta"]
    assert {"hoop_radius_m", "hoop_speed_rad_s", "g_m_s2"} <= set(hoop.parameters.by_name)


@pytest.mark.parametrize("system_id", sorted(SYSTEMS))
def test_every_formulation_gives_the_same_state_derivative_at_200_random_states(system_id):
    system = SYSTEMS[system_id]
    states = random_states(system, np.random.default_rng(20261123), 200)
    worst = formulation_agreement(system, system.parameters.defaults(), states)
    assert len(worst) >= 3, worst  # at least three independent derivations of every system
    assert max(worst.values()) <= AGREEMENT, worst


@pytest.mark.parametrize("system_id", ["double-pendulum", "spherical-pendulum", "rolling-disk"])
def test_a_wrong_term_in_any_one_formulation_is_caught(system_id, tmp_path):
    """Add 1e-6·q₁ to one equation of one formulation: the agreement check must see it (it would be ~1e-7 or more)."""
    system = SYSTEMS[system_id]
    params = system.parameters.defaults()
    p = np.array(system.parameter_array(params))
    states = random_states(system, np.random.default_rng(7), 20)
    reference = derived(system, reference_formulation(system))
    for formulation, reason in available_formulations(system).items():
        if reason:
            continue
        recipe = DERIVERS[formulation](system).recipe
        solve_index = max(i for i, stage in enumerate(recipe.stages) if isinstance(stage, Solve))
        solve = recipe.stages[solve_index]
        wrong = solve.rhs.copy()
        wrong[0] += sympy.Rational(1, 10**6) * system.q[0]
        stages = list(recipe.stages)
        stages[solve_index] = dataclasses.replace(solve, rhs=wrong)
        rhs = load_recipe(system, Recipe(tuple(stages), recipe.outputs), formulation=formulation, path=tmp_path / f"wrong_{formulation.replace('-', '_')}.py")
        worst = 0.0
        for y in states:
            good = reference.state_derivative(0.37, y, p)
            bad = np.empty(len(y))
            rhs(0.37, y, p, bad)
            worst = max(worst, float(np.linalg.norm(bad - good) / np.linalg.norm(good)))
        assert worst > 100 * AGREEMENT, (formulation, worst)


@pytest.mark.parametrize("system_id", ["simple-pendulum", "bead-on-rotating-hoop"])
def test_sympy_proves_the_formulations_equal_for_one_degree_of_freedom(system_id):
    """M q̈_f − f simplifies to zero for every formulation (a proof, not a sample); < 1 s each for these."""
    system = SYSTEMS[system_id]
    for formulation, reason in available_formulations(system).items():
        if not reason and formulation != reference_formulation(system):
            assert proves_same_equations(system, formulation), formulation


def test_unavailable_formulations_say_why():
    disk = available_formulations(SYSTEMS["rolling-disk"])
    assert "velocities" in disk["lagrange"] and disk["kane"] == "" and disk["gibbs-appell"] == ""
    assert available_formulations(SYSTEMS["double-pendulum"])["routh"] == "no ignorable coordinate"
    assert available_formulations(SYSTEMS["heavy-top"])["routh"] == ""
