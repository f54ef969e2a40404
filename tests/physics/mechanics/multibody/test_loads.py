"""Applied loads on a system built of parts: forces (fixed in direction or following the body), couples, springs and
dampers on coordinates; against closed forms, Lagrange's equations from the energies, and the data form."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.mechanics.description import Coordinate, parameter
from app.physics.mechanics.multibody import data
from app.physics.mechanics.multibody.compiled import compiled
from app.physics.mechanics.multibody.parts import (
    GROUND,
    Body,
    Force,
    JointSpring,
    MultibodySystem,
    Prismatic,
    Revolute,
    Torque,
    column,
    inertia,
)

m, k, c, F, r, g = (sympy.Symbol(name, positive=True) for name in ("m", "k", "c", "F", "r", "g"))
PARAMETERS = ParameterSet(
    (
        parameter("m", "kg", 2.0, low=0.1, high=10, label="m", description="mass"),
        parameter("k", "N/m", 50.0, low=0, high=1e3, label="k", description="stiffness"),
        parameter("c", "N·s/m", 0.8, low=0, high=10, label="c", description="damping"),
        parameter("F", "N", 3.0, low=-10, high=10, label="F", description="force"),
        parameter("r", "m", 0.4, low=0.01, high=2, label="r", description="arm"),
        parameter("g", "m/s²", 9.81, low=0, high=30, label="g", description="gravity"),
    )
)
SYMBOLS = {"m": m, "k": k, "c": c, "F": F, "r": r, "g": g}
VALUES = PARAMETERS.defaults()


def _system(system_id: str, joints, loads, *, gravity=sympy.Integer(0), body_inertia=None) -> MultibodySystem:
    block = Body("block", m, body_inertia if body_inertia is not None else inertia(0.1, 0.2, 0.3))
    return MultibodySystem(
        id=system_id, title=system_id, parameters=PARAMETERS, symbols=SYMBOLS, bodies=(block,), joints=joints,
        loads=loads, gravity=gravity,
    )  # fmt: skip


#: A block on a damped spring along x, pushed by a constant force F along the ground's x.
OSCILLATOR = _system(
    "damped-oscillator",
    (Prismatic(GROUND, "block", Coordinate("x", "x", unit="m"), column(1, 0, 0)),),
    (JointSpring("x", stiffness=k, rest=sympy.Rational(1, 10), damping=c), Force("block", column(F, 0, 0))),
)
#: A block turning about z with a force F at (0, r, 0) on it: along its own x (a follower) or the ground's x.
TURNING = {
    follower: _system(
        f"turning-{'follower' if follower else 'fixed'}",
        (Revolute(GROUND, "block", Coordinate("theta", "\\theta"), column(0, 0, 1)),),
        (Force("block", column(F, 0, 0), point=column(0, r, 0), follower=follower), Torque("block", column(0, 0, 1))),
    )
    for follower in (True, False)
}


def test_a_damped_spring_and_a_force_give_m_x_dd_equal_to_f_minus_k_stretch_minus_c_x_d_to_1e_12():
    model = compiled(OSCILLATOR)
    p = model.parameter_array(VALUES)
    for x, x_d in ((0.0, 0.0), (0.3, -1.2), (-0.5, 2.0)):
        expected = (VALUES["F"] - VALUES["k"] * (x - 0.1) - VALUES["c"] * x_d) / VALUES["m"]
        assert model.accelerations(np.array([x]), np.array([x_d]), p)[0] == pytest.approx(expected, abs=1e-12)


def test_the_damped_oscillator_follows_its_closed_form_for_5_s_to_1e_9():
    model = compiled(OSCILLATOR)
    p = model.parameter_array(VALUES)
    mass, stiffness, damping, force = (VALUES[key] for key in ("m", "k", "c", "F"))
    rest = 0.1 + force / stiffness  # where the spring balances the force
    zeta_omega, omega_d = damping / (2 * mass), math.sqrt(stiffness / mass - (damping / (2 * mass)) ** 2)
    x0 = 0.0
    run = solve_ivp(lambda _t, y: _rates(model, p, y), (0.0, 5.0), [x0, 0.0], rtol=1e-12, atol=1e-14,
                    method="DOP853", dense_output=True)  # fmt: skip
    t = np.linspace(0.0, 5.0, 51)
    a = x0 - rest
    closed = rest + math.e ** (-zeta_omega * t) * (
        a * np.cos(omega_d * t) + a * zeta_omega / omega_d * np.sin(omega_d * t)
    )
    assert np.max(np.abs(run.sol(t)[0] - closed)) < 1e-9


def _rates(model, p, y):
    out = np.empty(len(y))
    model.rhs(0.0, np.asarray(y, dtype=float), p, out)
    return out


def test_a_follower_force_turns_with_the_body_a_fixed_one_does_not_and_a_couple_adds():
    """θ̈ I_zz = −r F (follower: the arm and the force turn together) or −r F cos θ (fixed along the ground's x), plus
    the 1 N·m couple about z."""
    izz = 0.3
    for follower, model in ((f, compiled(TURNING[f])) for f in (True, False)):
        p = model.parameter_array(VALUES)
        for theta in (0.0, 0.7, 2.5):
            moment = -VALUES["r"] * VALUES["F"] * (1.0 if follower else math.cos(theta)) + 1.0
            got = model.accelerations(np.array([theta]), np.array([0.4]), p)[0]
            assert got == pytest.approx(moment / izz, abs=1e-12), (follower, theta)


def test_kane_and_lagrange_agree_with_loads_on_a_double_pendulum_to_1e_10():
    """Springs enter Lagrange's route through V alone, dampers, forces and couples as generalized forces."""
    rods = _chain_with_loads()
    kane, lagrange = compiled(rods), compiled(rods, formulation="lagrange")
    p = kane.parameter_array(VALUES)
    rng = np.random.default_rng(3)
    for _ in range(10):
        q, u = rng.uniform(-1.5, 1.5, 2), rng.uniform(-3, 3, 2)
        a, b = kane.accelerations(q, u, p), lagrange.accelerations(q, u, p)
        assert np.max(np.abs(a - b)) <= 1e-10 * max(1.0, np.max(np.abs(a)))


def _chain_with_loads() -> MultibodySystem:
    rod = inertia(m * r**2 / 12, m * r**2 / 12, 0)
    return MultibodySystem(
        id="sprung-rods", title="sprung rods", parameters=PARAMETERS, symbols=SYMBOLS,
        bodies=(Body("rod1", m, rod, column(0, 0, -r / 2)), Body("rod2", m, rod, column(0, 0, -r / 2))),
        joints=(
            Revolute(GROUND, "rod1", Coordinate("a", "a"), column(0, 1, 0)),
            Revolute("rod1", "rod2", Coordinate("b", "b"), column(0, 1, 0), column(0, 0, -r)),
        ),
        loads=(
            JointSpring("a", stiffness=k / 10, rest=sympy.Rational(1, 5), damping=c / 10),
            JointSpring("b", stiffness=k / 20),
            Force("rod2", column(F, 0, -F / 2), point=column(0, 0, -r)),
            Torque("rod1", column(0, F / 10, 0), follower=True),
        ),
        gravity=g,
    )  # fmt: skip


def test_with_springs_and_no_dampers_the_energy_is_kept():
    """The springs' potential is part of V: without dampers or other loads, T + V is constant (1e-9 over 5 s)."""
    free = _chain_with_loads()
    springs_only = tuple(
        JointSpring(load.coordinate, load.stiffness, load.rest) for load in free.loads if isinstance(load, JointSpring)
    )
    fields = {name: getattr(free, name) for name in free.__dataclass_fields__}
    system = MultibodySystem(**{**fields, "id": "sprung-rods-free", "loads": springs_only})
    model = compiled(system)
    p = model.parameter_array(VALUES)
    start = np.array([0.9, -0.4, 0.0, 1.0])
    run = solve_ivp(lambda _t, y: _rates(model, p, y), (0.0, 5.0), start, rtol=1e-12, atol=1e-13, method="DOP853")
    energies = [sum(model.energy(y[:2], y[2:], p)) for y in (start, run.y[:, -1])]
    assert abs(energies[1] - energies[0]) < 1e-9 * abs(energies[0])


def test_loads_survive_the_data_form():
    rods = _chain_with_loads()
    described = data.system_from_toml(data.system_to_toml(rods))
    a, b = compiled(rods), compiled(described)
    p = a.parameter_array(VALUES)
    q, u = np.array([0.3, -0.2]), np.array([0.5, 1.5])
    assert np.max(np.abs(a.accelerations(q, u, p) - b.accelerations(q, u, p))) < 1e-12


@pytest.mark.parametrize(
    ("load", "field"),
    [
        ({"type": "spring", "coordinate": "a", "stiffness": -1}, "stiffness"),
        ({"type": "spring", "coordinate": "nowhere", "stiffness": 1}, "coordinate"),
        ({"type": "force", "body": "rod9", "vector": [1, 0, 0]}, "body"),
        ({"type": "torque", "body": "rod1", "vector": [1, 0, 0], "follower": "yes"}, "follower"),
        ({"type": "gravity-off", "body": "rod1"}, "type"),
    ],
)
def test_a_bad_load_is_refused_naming_its_field(load, field):
    described = data.system_to_data(_chain_with_loads())
    described["loads"] = [load]
    with pytest.raises(ParameterError) as refused:
        data.system_from_data(described)
    assert refused.value.path[1:4] == ("loads", 0, field), refused.value.path
