"""Parameter metadata and request validation (app/physics/parameters.py)."""

from __future__ import annotations

import math

import pytest

from app.physics.systems import worked_examples

EXAMPLES = worked_examples()
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

ANGLE = Parameter("angle_deg", "deg", 10.0, -90.0, 90.0, "An angle")
COUNT = Parameter("count", "", 3, 1, 10, "A whole number", kind="int")
METHOD = Parameter("method", "", "rk4", kind="choice", choices=("euler", "rk4"))
SET = ParameterSet((ANGLE, COUNT, METHOD))


def test_unknown_name_is_rejected_and_named():
    with pytest.raises(ParameterError) as info:
        SET.validate({"angel_deg": 5.0})
    assert info.value.field == "angel_deg"
    assert "angel_deg" in str(info.value)
    # The message lists the known names so the typo can be fixed.
    assert "angle_deg" in info.value.message


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, True, False, "5", None, [1.0], {"v": 1}])
def test_non_numbers_and_non_finite_are_rejected(bad):
    with pytest.raises(ParameterError) as info:
        SET.validate({"angle_deg": bad})
    assert info.value.field == "angle_deg"


@pytest.mark.parametrize("bad", [-90.0001, 90.0001, 1e300, -1e300])
def test_out_of_range_message_states_the_range(bad):
    with pytest.raises(ParameterError) as info:
        ANGLE.validate(bad)
    assert info.value.field == "angle_deg"
    assert "between -90 and 90 deg" in info.value.message


@pytest.mark.parametrize("edge", [-90.0, 90.0, -90, 90])
def test_range_is_closed(edge):
    value = ANGLE.validate(edge)
    assert value == float(edge) and type(value) is float


def test_int_kind_accepts_whole_numbers_only():
    assert COUNT.validate(4) == 4 and type(COUNT.validate(4)) is int
    assert COUNT.validate(4.0) == 4 and type(COUNT.validate(4.0)) is int
    with pytest.raises(ParameterError, match="whole number"):
        COUNT.validate(4.5)
    with pytest.raises(ParameterError, match="between 1 and 10"):
        COUNT.validate(11)
    with pytest.raises(ParameterError):
        COUNT.validate(True)


def test_choice_kind_accepts_listed_strings_only():
    assert METHOD.validate("euler") == "euler"
    for bad in ("RK4", "midpoint", 1, None):
        with pytest.raises(ParameterError) as info:
            METHOD.validate(bad)
        assert "one of 'euler', 'rk4'" in info.value.message


def test_invalid_parameter_definitions_are_refused():
    with pytest.raises(ValueError):
        Parameter("x", "m", 5.0, 0.0, 1.0)  # default out of range
    with pytest.raises(ValueError):
        Parameter("x", "", "c", kind="choice", choices=("a", "b"))
    with pytest.raises(ValueError):
        Parameter("x", "s", 1.0, 0.0, 2.0, scale="log")  # log scale needs min > 0


def test_missing_values_take_defaults_and_base_overrides_defaults():
    assert SET.validate(None) == {"angle_deg": 10.0, "count": 3, "method": "rk4"}
    assert SET.validate({}) == SET.defaults()
    base = {"angle_deg": 45.0, "count": 7, "method": "euler"}
    merged = SET.validate({"count": 2}, base=base)
    assert merged == {"angle_deg": 45.0, "count": 2, "method": "euler"}
    assert base == {"angle_deg": 45.0, "count": 7, "method": "euler"}  # base not mutated


def test_whole_request_check_sees_merged_values_and_its_error_propagates():
    seen = []

    def check(values):
        seen.append(dict(values))
        if values["low"] > values["high"]:
            raise ParameterError("low", "must not exceed high")

    pair = ParameterSet(
        (Parameter("low", "m", 1.0, 0.0, 10.0), Parameter("high", "m", 2.0, 0.0, 10.0)),
        check=check,
    )
    assert pair.validate({"high": 5.0}) == {"low": 1.0, "high": 5.0}
    assert seen[-1] == {"low": 1.0, "high": 5.0}
    with pytest.raises(ParameterError) as info:
        pair.validate({"low": 3.0})
    assert info.value.field == "low"
    # The check also runs against a base: an impossible merged result is refused.
    with pytest.raises(ParameterError):
        pair.validate({"high": 0.5}, base={"low": 1.0, "high": 2.0})


def test_schema_carries_name_unit_default_and_range():
    assert ANGLE.schema() == {
        "name": "angle_deg",
        "label": "angle_deg",
        "unit": "deg",
        "default": 10.0,
        "description": "An angle",
        "kind": "float",
        "min": -90.0,
        "max": 90.0,
        "scale": "linear",
    }
    assert METHOD.schema()["choices"] == ["euler", "rk4"]
    assert "min" not in METHOD.schema()


@pytest.mark.parametrize("example_id", sorted(EXAMPLES))
def test_every_example_default_validates_to_itself(example_id):
    inputs = EXAMPLES[example_id].inputs
    assert inputs.validate({}) == inputs.defaults()
    assert inputs.validate(inputs.defaults()) == inputs.defaults()


OMEGA = Parameter("omega0_rad_s", "rad/s", (0.1, 5.0, 0.0), -100.0, 100.0, "Initial angular velocity, body frame", kind="vector")


def _no_digits(text: str) -> None:
    if any(ch.isdigit() for ch in text):
        raise ValueError("digits are not allowed here")


CURVE = Parameter("x_of_t", "m", "cos(t)", kind="text", max_length=20, parse=_no_digits)


def test_vector_parameter_converts_and_defaults_to_a_list():
    values = ParameterSet((OMEGA,)).validate({"omega0_rad_s": [1, 2.5, -3]})
    assert values["omega0_rad_s"] == [1.0, 2.5, -3.0]
    assert ParameterSet((OMEGA,)).defaults()["omega0_rad_s"] == [0.1, 5.0, 0.0]
    schema = OMEGA.schema()
    assert schema["kind"] == "vector" and schema["length"] == 3 and schema["min"] == -100.0


@pytest.mark.parametrize(
    "bad, words",
    [
        ([1.0, 2.0], "list of 3 numbers"),
        ([1.0, 2.0, 3.0, 4.0], "list of 3 numbers"),
        ("1,2,3", "list of 3 numbers"),
        ([1.0, math.nan, 0.0], "component 1 must be a finite number"),
        ([1.0, True, 0.0], "component 1 must be a finite number"),
        ([1.0, 0.0, 500.0], "component 2 must be between -100 and 100"),
    ],
)
def test_vector_parameter_rejects_with_the_component_named(bad, words):
    with pytest.raises(ParameterError) as info:
        OMEGA.validate(bad)
    assert info.value.field == "omega0_rad_s" and words in info.value.message


def test_text_parameter_runs_its_parser_and_limits_length():
    assert CURVE.validate("sin(t)") == "sin(t)"
    with pytest.raises(ParameterError, match="digits are not allowed"):
        CURVE.validate("t^2")
    with pytest.raises(ParameterError, match="21 characters long; the limit is 20"):
        CURVE.validate("t" * 21)
    with pytest.raises(ParameterError, match="must be text"):
        CURVE.validate(3.0)
    assert CURVE.schema()["max_length"] == 20


def test_bad_defaults_are_caught_when_the_parameter_is_declared():
    with pytest.raises(ValueError):
        Parameter("v", "m", (0.0, 0.0), -1.0, 1.0, kind="vector")  # length 2, not 3
    with pytest.raises(ValueError):
        Parameter("v", "m", (0.0, 0.0, 2.0), -1.0, 1.0, kind="vector")  # component out of range
    with pytest.raises(ValueError):
        Parameter("s", "", "x" * 300, kind="text")


@pytest.mark.parametrize("huge", [10**399, -(10**399)])
def test_an_integer_beyond_float_range_is_refused_naming_the_field_not_an_overflow(huge):
    """A JSON number of 400 digits arrives as a Python int that no float can hold."""
    for parameter in (ANGLE, COUNT):
        with pytest.raises(ParameterError) as info:
            SET.validate({parameter.name: huge})
        assert info.value.field == parameter.name and "finite number" in info.value.message
    vector = Parameter("r_m", "m", [0.0, 0.0, 0.0], -1.0, 1.0, "A position", kind="vector")
    with pytest.raises(ParameterError) as info:
        vector.validate([0.0, huge, 0.0])
    assert info.value.field == "r_m" and info.value.message.startswith("component 1 must be a finite number")
