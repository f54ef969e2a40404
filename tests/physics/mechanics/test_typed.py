"""A typed Lagrangian: parsed, never evaluated; derived; refused clearly."""

from __future__ import annotations

import builtins
import importlib

import pytest
import sympy
from sympy.parsing import sympy_parser

from app.physics.core.parameters import ParameterError
from app.physics.mechanics import typed


def test_deriving_typed_energies_never_evaluates_text(monkeypatch):
    """eval and sympify/parse_expr of a string all raise while a typed pendulum is parsed."""
    real_sympify = sympy.sympify

    def sympify_objects_only(value, *args, **kwargs):
        if isinstance(value, str):
            raise AssertionError(f"sympify was given text: {value!r}")
        return real_sympify(value, *args, **kwargs)

    def forbidden(*args, **kwargs):
        raise AssertionError("text was evaluated")

    monkeypatch.setattr(sympy, "sympify", sympify_objects_only)
    monkeypatch.setattr(importlib.import_module("sympy.core.sympify"), "sympify", sympify_objects_only)
    monkeypatch.setattr(sympy_parser, "parse_expr", forbidden)
    monkeypatch.setattr(builtins, "eval", forbidden)
    system = typed.typed_system(["q1"], "m*l^2*q1d^2/2", "-m*g*l*cos(q1)", {"m": 2.0, "l": 0.5, "g": 9.81})
    assert system.kinetic_energy == sympy.Symbol("m", real=True) * sympy.Symbol("l", real=True) ** 2 * system.qd[0] ** 2 / 2


def test_the_check_state_answer_is_the_pendulum_equation():
    answer = typed.derive_typed({"coordinates": ["q1"], "kinetic_energy": "m*l^2*q1d^2/2", "potential_energy": "-m*g*l*cos(q1)",
                                 "parameters": {"m": 2.0, "l": 0.5, "g": 9.81}})  # fmt: skip
    q, rate = answer["rhs_check"]["state"]
    assert answer["rhs_check"]["state_derivative"] == pytest.approx([rate, -9.81 / 0.5 * sympy.sin(q).evalf()], rel=1e-14)


@pytest.mark.parametrize(
    ("coordinates", "kinetic", "potential", "parameters", "field"),
    [
        (["q1"], "m*q1d^2", "0", {"m": float("nan")}, "parameters"),
        (["q1"], "m*q1d^2", "0", {"q1": 1.0}, "parameters"),
        (["q1", "q2"], "q1d^2", "0", {}, "kinetic_energy"),
        (["q1"], "q1d^2", "exp(", {}, "potential_energy"),
        ([], "q1d^2", "0", {}, "coordinates"),
    ],
)
def test_bad_typed_input_names_its_field(coordinates, kinetic, potential, parameters, field):
    with pytest.raises(ParameterError) as error:
        typed.typed_system(coordinates, kinetic, potential, parameters)
    assert error.value.field == field


# -- issue 24: energies with no finite value at the check state, and a kinetic energy that is not positive definite ----
@pytest.mark.parametrize(
    ("kinetic", "potential", "field", "what", "because"),
    [
        # Found 11: each was an OverflowError or a "math domain error" inside the derivation child, answered 500.
        ("q1d^2*exp(exp(exp(exp(exp(q1)))))", "0", "kinetic_energy", "the kinetic energy T", "overflows"),
        ("q1d^2/2", "sqrt(-q1)", "potential_energy", "the potential energy V", "outside its domain"),
        ("q1d^2*(1+exp(999999999*q1^3))", "0", "kinetic_energy", "the kinetic energy T", "overflows"),
        # A derivative Lagrange's equations take, not the energy itself: ∂V/∂q1 = 1/(2√q1) is fine at q1 = 0.3, ∂²… too.
        ("q1d^2/2", "log(q1 - 0.3)", "potential_energy", "the potential energy V", "divides by zero"),
    ],
)
def test_an_energy_with_no_finite_value_at_the_check_state_is_refused_naming_it(kinetic, potential, field, what, because):
    request = {"coordinates": ["q1"], "kinetic_energy": kinetic, "potential_energy": potential, "parameters": {}}
    with pytest.raises(ParameterError) as refused:
        typed.derive_typed(request)
    assert refused.value.field == field
    message = str(refused.value)
    assert "check state q1 = 0.3, q1d = 0.2" in message and what in message and because in message, message


@pytest.mark.parametrize(
    ("coordinates", "kinetic", "words"),
    [
        # Found 12: −q̇²/2 derived and simulated "ok"; M = −1 < 0.
        (["q1"], "-q1d^2/2", "negative eigenvalue -1 (mostly along q1d)"),
        # Indefinite in two rates: M = diag(1, −2) at every state.
        (["q1", "q2"], "q1d^2/2 - q2d^2", "negative eigenvalue -2 (mostly along q2d)"),
        # Singular at the check state q1 = 0.3 only (M = diag(q1 − 0.3, 1)), not everywhere.
        (["q1", "q2"], "(q1 - 0.3)*q1d^2/2 + q2d^2/2", "singular"),
    ],
)
def test_a_kinetic_energy_not_positive_definite_at_the_check_state_is_refused(coordinates, kinetic, words):
    request = {"coordinates": coordinates, "kinetic_energy": kinetic, "potential_energy": "0", "parameters": {}}
    with pytest.raises(ParameterError) as refused:
        typed.derive_typed(request)
    assert refused.value.field == "kinetic_energy"
    assert "positive definite" in str(refused.value) and words in str(refused.value), str(refused.value)
