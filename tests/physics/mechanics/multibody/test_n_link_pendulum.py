"""The N-link pendulum built of parts: its small oscillations against an independent linear computation.

Independent: for N uniform rods (mass m, length l) hanging at rest, the linearised kinetic energy is ½ θ̇ᵀ M₀ θ̇ with
M₀ = Σ_k m a_k a_kᵀ + diag(m l²/12), a_k the horizontal velocity of rod k's centre per unit θ̇_j (l for j < k, l/2
for j = k), and V = ½ Σ_j m g l (N − j + ½) θ_j² (j from 1): the frequencies are √eig(M₀⁻¹ K), written out here in
numpy from those formulas, not from the engine.
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.mechanics.multibody.compiled import compiled
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch09.n_link_pendulum import FAMILY, PARAMETERS, chain

PARAMS = {"link_mass_kg": 1.3, "link_length_m": 0.4, "gravity_m_s2": 9.81}


def frequencies_by_hand(links: int, m: float, l: float, g: float) -> np.ndarray:
    mass = np.diag(np.full(links, m * l**2 / 12))
    for k in range(links):
        a = np.array([l if j < k else l / 2 if j == k else 0.0 for j in range(links)])
        mass += m * np.outer(a, a)
    stiffness = np.diag([m * g * l * (links - j - 0.5) for j in range(links)])
    return np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real))


def _frequencies(links: int, planar: bool) -> np.ndarray:
    system = chain(links, planar)
    values = eigenvalues(state_matrix(compiled(system), PARAMS, system.reference))
    assert np.max(np.abs(values.real)) < 1e-6 * np.max(np.abs(values))  # no growth, no decay: ±iω
    return np.sort(np.abs(values.imag))[::2]  # each ω appears as +iω and −iω


@pytest.mark.parametrize("links", [2, 3, 7, 12])
def test_the_planar_chains_frequencies_match_the_independent_linear_computation_to_1e_8(links):
    by_hand = frequencies_by_hand(links, PARAMS["link_mass_kg"], PARAMS["link_length_m"], PARAMS["gravity_m_s2"])
    np.testing.assert_allclose(_frequencies(links, True), by_hand, rtol=1e-8)


def test_a_spatial_chain_swings_the_same_way_in_both_directions():
    """Hanging at rest, small swings about x and about y decouple: each planar frequency, twice."""
    by_hand = frequencies_by_hand(3, PARAMS["link_mass_kg"], PARAMS["link_length_m"], PARAMS["gravity_m_s2"])
    np.testing.assert_allclose(_frequencies(3, False), np.sort(np.repeat(by_hand, 2)), rtol=1e-8)


def test_kane_and_lagrange_agree_on_a_spatial_chain_at_random_states_to_1e_10():
    system = chain(3, False)
    kane, lagrange = compiled(system), compiled(system, formulation="lagrange")
    p = kane.parameter_array(PARAMS)
    rng = np.random.default_rng(5)
    for _ in range(10):
        q, u = rng.uniform(-1.0, 1.0, kane.n), rng.uniform(-2.0, 2.0, kane.n)
        a, b = kane.accelerations(q, u, p), lagrange.accelerations(q, u, p)
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(a)), (a, b)


def test_the_family_builds_each_member_once_and_refuses_a_chain_out_of_range():
    assert FAMILY.member(PARAMETERS.validate({"links": 5})) is chain(5, True)
    assert len(FAMILY.member(PARAMETERS.validate({"links": 4, "planar": "spatial"})).coordinates) == 8
    with pytest.raises(ValueError, match="between 2 and 20") as refused:
        PARAMETERS.validate({"links": 21})
    assert refused.value.field == "links"


def test_a_spatial_chain_longer_than_ten_links_is_refused_naming_links():
    from app.physics.core.parameters import ParameterError

    with pytest.raises(ParameterError, match="at most 10 links") as refused:
        FAMILY.member(PARAMETERS.validate({"links": 11, "planar": "spatial"}))
    assert refused.value.field == "links"
