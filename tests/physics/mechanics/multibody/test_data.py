"""A multibody system's data form (JSON/TOML): the shipped systems survive the round trip with the same equations,
and hostile or mistaken descriptions are refused naming the field, before sympy sees anything."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import sympy
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.mechanics.multibody import data
from app.physics.mechanics.multibody.compiled import compiled
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch08 import rattleback
from app.physics.systems.ch09 import whipple_bicycle as bicycle
from app.physics.systems.ch09.n_link_pendulum import chain

#: The bicycle's data form, shipped as the example of a description (written by system_to_toml, checked below).
BICYCLE_TOML = Path(bicycle.__file__).with_suffix(".toml")


def _bicycle_reference_state() -> list:
    symbols = bicycle.SYSTEM.symbols
    rates = [0, 0, 0, 0, symbols["speed_m_s"] / symbols["rear_wheel_radius_m"], 0, 0, 0]
    return [0] * 8 + rates


def test_the_shipped_bicycle_toml_is_what_the_writer_writes():
    """Regenerate with: python -c "from tests.physics.mechanics.multibody.test_data import write; write()"."""
    assert BICYCLE_TOML.read_text() == data.system_to_toml(bicycle.SYSTEM, reference_state=_bicycle_reference_state())


def write() -> None:
    BICYCLE_TOML.write_text(data.system_to_toml(bicycle.SYSTEM, reference_state=_bicycle_reference_state()))


def test_the_bicycle_read_from_its_toml_has_the_published_eigenvalues_to_1e_12_of_the_original():
    described = data.system_from_toml(BICYCLE_TOML.read_text())
    original, copy_ = compiled(bicycle.SYSTEM), compiled(described)
    for speed_m_s in (0.0, 3.0, 5.0, 8.0):
        params = {**bicycle.PARAMETERS.defaults(), "speed_m_s": speed_m_s}
        ours = eigenvalues(state_matrix(original, params, bicycle.REFERENCE))
        theirs = eigenvalues(state_matrix(copy_, params, described.reference))
        assert np.max(np.abs(ours - theirs)) < 1e-12


def test_the_rattleback_and_a_spatial_chain_survive_the_json_round_trip_to_1e_12():
    symbols = rattleback.SYSTEM.symbols
    height = symbols["semi_axis_c_m"] - symbols["mass_centre_drop_m"]
    reference = [0, 0, height, 0, 0, 0, 0, 0, 0, symbols["spin_rad_s"], 0, 0]
    for system, state in ((rattleback.SYSTEM, reference), (chain(3, False), None)):
        described = data.system_from_data(data.system_to_data(system, reference_state=state))
        a, b = compiled(system), compiled(described)
        p = a.parameter_array(system.parameters.defaults())
        rng = np.random.default_rng(5)
        for _ in range(5):
            q, u = a.assemble(rng.uniform(-0.3, 0.3, a.n), rng.uniform(-2, 2, a.n), p)
            assert np.max(np.abs(a.accelerations(q, u, p) - b.accelerations(q, u, p))) < 1e-12


DOUBLE_PENDULUM = {
    "id": "two-rods",
    "title": "Two rods",
    "parameters": [
        {"name": "m", "value": 1.0, "unit": "kg", "low": 0.01, "high": 10, "description": "rod mass"},
        {"name": "g", "value": 9.81, "unit": "m/s²", "low": 0, "high": 30, "description": "gravity"},
    ],
    "gravity": "g",
    "bodies": [
        {"name": "rod1", "mass": "m", "mass_centre": [0, 0, -0.25],
         "inertia": {"ixx": {"div": ["m", 48]}, "iyy": {"div": ["m", 48]}, "izz": 0}},
        {"name": "rod2", "mass": "m", "mass_centre": [0, 0, -0.25],
         "inertia": {"ixx": {"div": ["m", 48]}, "iyy": {"div": ["m", 48]}, "izz": 0}},
    ],
    "joints": [
        {"type": "revolute", "parent": "ground", "child": "rod1", "coordinate": "theta1", "axis": [0, 1, 0]},
        {"type": "revolute", "parent": "rod1", "child": "rod2", "coordinate": "theta2", "axis": [0, 1, 0],
         "at": [0, 0, -0.5]},
    ],
}  # fmt: skip


def test_a_described_double_pendulum_is_the_shipped_two_link_chain():
    described = data.system_from_data(DOUBLE_PENDULUM)
    shipped = compiled(chain(2, True))
    ours = compiled(described)
    p_shipped = shipped.parameter_array({"link_mass_kg": 1.0, "link_length_m": 0.5, "gravity_m_s2": 9.81})
    p_ours = ours.parameter_array(described.parameters.defaults())
    q, u = np.array([0.3, -0.7]), np.array([1.1, 0.4])
    assert np.max(np.abs(shipped.accelerations(q, u, p_shipped) - ours.accelerations(q, u, p_ours))) < 1e-12


def _changed(path: tuple, value) -> dict:
    described = copy.deepcopy(DOUBLE_PENDULUM)
    target = described
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value
    return described


@pytest.mark.parametrize(
    ("described", "where"),
    [
        (_changed(("bodies", 0, "mass"), -1.0), ("bodies", 0, "mass")),
        (_changed(("bodies", 0, "mass"), "__import__('os').system('id')"), ("bodies", 0, "mass")),
        (_changed(("bodies", 0, "mass"), float("nan")), ("bodies", 0, "mass")),
        (_changed(("bodies", 0, "mass"), 1e308), ("bodies", 0, "mass")),
        (_changed(("bodies", 1, "name"), "rod1"), ("bodies", 1, "name")),
        (_changed(("bodies", 0, "inertia"), {"ixx": 1, "iyy": 0.1, "izz": 0.1}), ("bodies", 0, "inertia")),
        (_changed(("joints", 0, "axis"), [0, 0, 0]), ("joints", 0, "axis")),
        (_changed(("joints", 1, "parent"), "rod3"), ("joints", 1, "parent")),
        (_changed(("joints", 0, "type"), "teleport"), ("joints", 0, "type")),
        (_changed(("joints", 0, "coordinate"), "θ; rm -rf"), ("joints", 0, "coordinate")),
        (_changed(("bodies", 0, "shape"), "cube"), ("bodies", 0)),
        (_changed(("gravity",), {"pow": ["g", 100]}), ("gravity", "pow", 1)),
        (_changed(("gravity",), {"sin": {"sin": {"sin": {"sin": {"sin": {"sin": {"sin": "g"}}}}}}}), ("gravity",)),
        (_changed(("bodies",), [DOUBLE_PENDULUM["bodies"][0]] * 13), ("bodies",)),
    ],
)
def test_a_bad_description_is_refused_naming_the_field(described, where):
    with pytest.raises(ParameterError) as refused:
        data.system_from_data(described)
    assert tuple(refused.value.path[1 : 1 + len(where)]) == where and refused.value.path[0] == "description", (
        refused.value.path
    )


@pytest.mark.parametrize(
    "text",
    ["id = ", "x" * 30_000, "a = " + "[" * 600 + "]" * 600, 42],
)
def test_bad_toml_is_refused_as_toml(text):
    with pytest.raises(ParameterError) as refused:
        data.parse_toml(text)
    assert refused.value.path[0] == "toml"


def test_an_infinite_number_in_toml_is_refused_where_it_stands():
    with pytest.raises(ParameterError) as refused:
        data.system_from_toml(data.to_toml(DOUBLE_PENDULUM).replace("value = 9.81", "value = inf"))
    assert refused.value.path[:3] == ("toml", "parameters", 1)


def test_a_symbolic_axis_is_never_multiplied_out_in_the_server():
    """A hostile axis, an 8-term sum to the 9th power: reading it must not expand (a² would have 18th powers of the
    sum, minutes of sympy in the server's own thread); it is checked at sampled parameter values instead."""
    described = copy.deepcopy(DOUBLE_PENDULUM)
    names = [f"a{i}" for i in range(8)]
    described["parameters"] += [
        {"name": n, "value": 1.0, "unit": "", "low": 0.5, "high": 2.0, "description": "a weight"} for n in names
    ]
    described["joints"][0]["axis"] = [{"pow": [{"pow": [{"add": names}, 3]}, 3]}, 0, 0]
    system = data.system_from_data(described)
    assert system.joints[0].axis[0].has(sympy.Pow)  # divided by its length, never expanded


@pytest.mark.parametrize(
    ("change", "where"),
    [
        ((("bodies", 0, "mass"), {"add": [2, {"sin": {"pow": [{"pow": [{"pow": [1e6, 4]}, 4]}, 4]}}]}),
         ("bodies", 0, "mass")),
        ((("reference",), {"coordinates": ["theta1"], "speeds": ["theta1"],
                           "sweep": {"parameter": ["m"], "low": 0, "high": 1}}), ("reference", "sweep", "parameter")),
    ],
)  # fmt: skip
def test_numbers_too_large_for_the_code_and_misshapen_sweeps_are_refused(change, where):
    with pytest.raises(ParameterError) as refused:
        data.system_from_data(_changed(*change))
    assert tuple(refused.value.path[1 : 1 + len(where)]) == where, refused.value.path
