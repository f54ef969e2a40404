"""Derive once, cache on disk and in memory, generate code that runs compiled and plain."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.mechanics import engine
from app.physics.solvers import RK4, LiveRun
from app.physics.solvers.system import OdeSystem
from app.physics.mechanics.derivation import FormulationUnavailable
from app.physics.systems import analytical_systems

PENDULUM = analytical_systems()["simple-pendulum"]
P = np.array(PENDULUM.parameter_array(PENDULUM.parameters.defaults()))  # m = 1 kg, l = 1 m, g = 9.81 m/s²


@pytest.fixture
def fresh_cache(tmp_path, monkeypatch):
    monkeypatch.setattr(engine, "_memory", engine.OrderedDict())
    return tmp_path


def test_the_pendulum_equation_is_the_textbook_one(fresh_cache):
    result = engine.derived(PENDULUM, "lagrange", directory=fresh_cache)
    y = np.array([0.7, 1.3])
    assert result.state_derivative(0.0, y, P) == pytest.approx([1.3, -9.81 * math.sin(0.7)], rel=1e-15)
    assert not result.from_cache and result.derive_s > 0
    assert any("T =" in step["latex"] for step in result.steps)


def test_a_derivation_is_written_once_and_read_back_without_sympy(fresh_cache, monkeypatch):
    first = engine.derived(PENDULUM, "hamilton", directory=fresh_cache)
    files = sorted(p.name for p in fresh_cache.iterdir())
    assert any(name.endswith(".json") for name in files) and any(name.endswith(".py") for name in files)
    monkeypatch.setattr(engine, "_memory", engine.OrderedDict())  # a new process, as far as the cache can tell

    def no_sympy(system):
        raise AssertionError("derived again although the disk cache has it")

    monkeypatch.setitem(engine.DERIVERS, "hamilton", no_sympy)
    again = engine.derived(PENDULUM, "hamilton", directory=fresh_cache)
    assert again.from_cache and again.derive_s == 0.0
    assert again.equations_latex == first.equations_latex
    y = np.array([-2.0, 0.4])
    assert np.array_equal(again.state_derivative(0.0, y, P), first.state_derivative(0.0, y, P))
    assert engine.derived(PENDULUM, "hamilton", directory=fresh_cache) is again  # then from memory


def test_a_damaged_cache_entry_is_derived_again(fresh_cache, monkeypatch):
    engine.derived(PENDULUM, "kane", directory=fresh_cache)
    meta = next(p for p in fresh_cache.iterdir() if p.suffix == ".json")
    meta.write_text("{not json")
    monkeypatch.setattr(engine, "_memory", engine.OrderedDict())
    result = engine.derived(PENDULUM, "kane", directory=fresh_cache)
    assert not result.from_cache
    json.loads(meta.read_text())


def test_the_compiled_right_hand_side_matches_the_plain_one(fresh_cache):
    result = engine.derived(PENDULUM, "gibbs-appell", directory=fresh_cache)
    kernel = result.kernel()
    y = np.array([0.3, -0.8])
    system = OdeSystem(rhs=kernel, parameters=P, state_names=("theta", "theta_rate"))
    run = LiveRun(system, RK4(steps_per_frame=200), y.copy())
    run.advance(1.0)
    plain = y.copy()
    h = 1.0 / 200
    for _ in range(200):  # the same RK4 in plain Python on the plain right-hand side
        k1 = result.state_derivative(0, plain, P)
        k2 = result.state_derivative(0, plain + h / 2 * k1, P)
        k3 = result.state_derivative(0, plain + h / 2 * k2, P)
        k4 = result.state_derivative(0, plain + h * k3, P)
        plain = plain + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    assert run.y == pytest.approx(plain, rel=1e-12, abs=1e-12)


def test_a_singular_state_gives_nan_not_an_exception(fresh_cache):
    """The spherical pendulum's Lagrange mass matrix is singular at θ = 0 (φ undefined there)."""
    spherical = analytical_systems()["spherical-pendulum"]
    result = engine.derived(spherical, "lagrange", directory=fresh_cache)
    p = np.array(spherical.parameter_array(spherical.parameters.defaults()))
    assert np.all(np.isnan(result.state_derivative(0.0, np.array([0.0, 0.3, 0.1, 0.2]), p)))


def test_an_unavailable_or_unknown_formulation_is_refused_with_the_reason(fresh_cache):
    with pytest.raises(FormulationUnavailable, match="ignorable"):
        engine.derived(PENDULUM, "routh", directory=fresh_cache)
    with pytest.raises(ValueError, match="unknown formulation"):
        engine.derived(PENDULUM, "euler", directory=fresh_cache)
