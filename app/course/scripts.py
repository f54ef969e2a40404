"""A worked example's or a scene's numbers as a short runnable Python script ("Open as Python").

Beside each worked solution and each scene the lesson page offers a script that
uses this project's own package to reproduce the numbers the page shows, for the
values the page had. :func:`example_script` writes one for a worked example (its
outputs and every step's values), :func:`scene_script` one for a scene: its
model's ``simulate`` (the one path of every model, closed-form or integrated)
over :data:`SCRIPT_T_END_S`, printing the last frame's series, the invariants
and the drift (and, for the scenes in :data:`_READOUTS`, the readout beside the
scene, row for row); a scene that draws a worked example prints that example; the scenes
drawn from formulas of their own (rotation sequences, configuration space, the
toggle press, finite rotations) print their readout's numbers from the same physics functions.

Values reach a script only through :func:`python_literal`, which writes
validated plain data (numbers, words, true/false, lists and records of them) with
``repr`` and refuses anything else: a script never carries a visitor's text as code.
Every number is printed as ``  name = value unit`` (12 significant figures,
vectors as ``[x, y, z]``) under a heading line ending in ``:``.
"""

from __future__ import annotations

import importlib
import json
import math
from collections.abc import Callable, Mapping
from typing import Any

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import WorkedExample
from app.physics.systems import system_modules
from app.scenes.kit import FRAME_DT_S, Scene

__all__ = [
    "SCRIPT_FRAME_RATE_HZ",
    "SCRIPT_T_END_S",
    "example_script",
    "parse_params",
    "python_literal",
    "scene_script",
    "script_file_name",
    "script_values",
]

#: Simulated time (s) a scene's script runs its model for, and its samples per simulated second (Hz): the live
#: scenes' own frame rate (30 Hz), so a scene's readout, which reads its drawn frames, is reproduced frame for frame.
SCRIPT_T_END_S = 2.0
SCRIPT_FRAME_RATE_HZ = float(round(1.0 / FRAME_DT_S))
#: Longest ``params`` text the script routes read (a composite body's parts are the largest values).
MAX_PARAMS_TEXT = 20_000

_RUN = "Run it in this project's environment:  uv run python {file}"

#: The printing helper every script carries, so its output reads the same for every page.
_SHOW = '''

def formatted(value):
    """A number to 12 significant figures, a vector as [x, y, z], a word as it is; None is undefined."""
    if value is None:
        return "undefined"
    if isinstance(value, (str, bool)):
        return str(value)
    if hasattr(value, "__len__"):
        return "[" + ", ".join(formatted(v) for v in value) + "]"
    return f"{float(value) + 0.0:.12g}"  # (+ 0.0 prints -0.0 as 0)


def show(name, value, unit=""):
    """Print one line: the name, its value and its unit."""
    print(f"  {name} = {formatted(value)} {unit}".rstrip())
'''


def python_literal(value: Any) -> str:
    """``value`` written as a Python literal; only finite numbers, words, booleans, lists and string-keyed records.

    Raises ``TypeError`` for anything else and ``ValueError`` for a non-finite number,
    so only validated plain data ever becomes script text.
    """
    if isinstance(value, bool) or value is None:
        return repr(value)
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise ValueError(f"a script cannot carry the non-finite number {value!r}")
        return repr(int(value) if isinstance(value, int) else float(value))
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(python_literal(v) for v in value) + "]"
    if isinstance(value, Mapping) and all(isinstance(k, str) for k in value):
        return "{" + ", ".join(f"{k!r}: {python_literal(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"a script carries only numbers, words, lists and records, not {type(value).__name__}")


def parse_params(text: str | None) -> dict[str, Any]:
    """The ``params`` query text (a JSON object of parameter values; empty: the defaults) as a dict.

    Raises :class:`ParameterError` naming ``params`` when the text is too long, is
    not JSON, is not an object, or holds NaN or an infinity.
    """
    if text is None or not text.strip():
        return {}
    if len(text) > MAX_PARAMS_TEXT:
        raise ParameterError("params", f"is {len(text)} characters long; the limit is {MAX_PARAMS_TEXT}")

    def refuse_constant(name: str) -> float:
        raise ParameterError("params", f"holds {name}: every value must be a finite number")

    try:
        values = json.loads(text, parse_constant=refuse_constant)
    except json.JSONDecodeError as exc:
        raise ParameterError("params", f"is not JSON ({exc.msg} at character {exc.pos})") from None
    if not isinstance(values, dict):
        raise ParameterError("params", 'must be a JSON object of parameter values, e.g. {"mass_kg": 2}')
    return values


def script_values(parameters: ParameterSet, text: str | None) -> dict[str, Any]:
    """The ``params`` query text validated by ``parameters`` (omitted names take their defaults).

    Raises :class:`ParameterError` whose ``path`` starts at ``params`` and names the bad
    field; values each in range but impossible together are refused naming ``params``.
    """
    raw = parse_params(text)
    try:
        return parameters.validate(raw)
    except ParameterError as exc:
        raise ParameterError("params", exc.message, path=("params", *exc.path)) from None
    except ValueError as exc:
        raise ParameterError("params", str(exc)) from None


def _dict_block(name: str, values: Mapping[str, Any]) -> str:
    """``name = {...}`` with one entry per line."""
    if not values:
        return f"{name} = {{}}"
    lines = "".join(f"    {key!r}: {python_literal(value)},\n" for key, value in values.items())
    return f"{name} = {{\n{lines}}}"


def _display_note(display: Mapping[str, Any]) -> str:
    """A comment naming the scene's display options, which change the drawing and none of the numbers."""
    if not display:
        return ""
    text = ", ".join(f"{key}={python_literal(value)}" for key, value in display.items())
    return f"# The page's display options (they change the drawing, not these numbers): {text}\n"


def script_file_name(identifier: str) -> str:
    """A file name for the script of ``identifier`` (a scene or example id): letters, digits and underscores."""
    return "".join(c if c.isalnum() else "_" for c in identifier).strip("_").lower() + ".py"


def _example_module(example: WorkedExample) -> str:
    """The system module that declares ``example`` as its ``EXAMPLE``."""
    for name in (example.solve.__module__, *system_modules()):
        if getattr(importlib.import_module(name), "EXAMPLE", None) is example:
            return name
    raise ValueError(f"worked example {example.id!r} is declared by no system module")


def _importable(cls: type) -> tuple[str, str]:
    """``(module, name)`` a script imports ``cls`` by; ValueError if that import would not find it."""
    module, name = cls.__module__, cls.__qualname__
    if getattr(importlib.import_module(module), name, None) is not cls:
        raise ValueError(f"{name} cannot be imported from {module}")
    return module, name


def example_script(
    example: WorkedExample, inputs: Mapping[str, Any], *, display: Mapping[str, Any] | None = None
) -> str:
    """A script printing the worked solution of ``example`` for validated ``inputs`` (SI units).

    ``display`` (a scene's display options) is only named in a comment.
    """
    file = script_file_name(f"example_{example.id}")
    return f'''"""Worked example {example.id} ({example.title}, chapter {example.chapter}): the page's numbers.

Solves the example with the project's own package for the inputs the page had, and prints
its outputs (as the page's table lists them) and the values of every step.
{_RUN.format(file=file)}
"""

from {_example_module(example)} import EXAMPLE
{_SHOW}

# The inputs the page had (SI units; angles in degrees where a name ends in _deg).
{_dict_block("inputs", inputs)}
{_display_note(display or {})}
# Check the inputs as the server does (a bad one raises an error naming it), then solve.
solution = EXAMPLE.solve(EXAMPLE.inputs.validate(inputs))

print("outputs:")
for name, value in solution.outputs.items():
    if hasattr(value, "__len__") and not isinstance(value, str) and len(value) > 3:
        continue  # a sweep: the page plots it rather than listing it
    show(name, value, EXAMPLE.output_units.get(name, ""))
for number, step in enumerate(solution.steps, start=1):
    print(f"step {{number}}: {{step.title}}:")
    for symbol, value in step.values.items():
        show(symbol, value, step.units.get(symbol, ""))
'''


def _heavy_top_readout(scene: type[Scene]) -> tuple[str, str]:
    """The heavy top's readout from the run: the quadrature's predictions and the band θ swept over every frame."""
    return (
        "from app.physics.systems.ch10 import heavy_top as readout_physics\n",
        """
# The readout beside the scene at t = T_END_S: the same rows (names, units) from the same functions. The swept band
# is the least and largest θ over every frame from t = 0, as the scene reads it off the frames it draws.
theta = answer["series"]["theta"]  # rad, one per frame
reference, why = readout_physics.reference_or_none(params)
print(f"readout at t = {t[-1]:g} s (the page's table):")
show("t_s", t[-1], "s")
if why:
    print("  " + why)
for quantity in readout_physics.readout_quantities(params, reference, (min(theta), max(theta))):
    if quantity.value is None:  # a word, or why there is no number: shown without a unit
        show(quantity.name, quantity.text)
    else:
        show(quantity.name, quantity.value, quantity.unit)
""",
    )


#: Scenes whose readout a script prints after the model's numbers: ``(import lines, code)`` by scene id. The code
#: runs after the simulation, with ``params``, ``answer`` and ``t`` (the frame times) set.
_READOUTS: Mapping[str, Callable[[type[Scene]], tuple[str, str]]] = {"heavy-top": _heavy_top_readout}


def _model_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    """A scene drawing a model: simulate it, as the simulate route does, and print the last frame (and, for a scene
    in :data:`_READOUTS`, its readout)."""
    model = scene.model
    assert model is not None
    module, name = _importable(model)
    physical = {k: v for k, v in params.items() if k in model.parameters.by_name}
    control_names = {p.name for p in model.controls()}
    controls = {k: v for k, v in params.items() if k in control_names}
    display = {k: v for k, v in params.items() if k not in physical and k not in controls}
    file = script_file_name(scene.id)
    imports = f"from {module} import {name}\n"
    readout_imports, readout = _READOUTS[scene.id](scene) if scene.id in _READOUTS else ("", "")
    imports += readout_imports
    how = model.how_computed
    values = f"{_dict_block('params', physical)}\n"
    check = f"params = {name}.parameters.validate(params)\n"
    if control_names:  # how the motion is found: an integrator's method, steps and tolerance (a formula has none)
        values += (
            "# How the page integrates: the method, steps per frame (0: chosen to meet the accuracy target), the "
            "tolerance.\n"
            f"{_dict_block('controls', controls)}\n"
        )
        check += f"controls = {name}.validate_controls(controls)\n"
    controls_argument = "controls" if control_names else "{}"
    run = f"{name}().simulate(params, {controls_argument}, t_end_s=T_END_S, frame_rate_hz=FRAME_RATE_HZ).as_dict()"
    return f'''"""{scene.title} (scene {scene.id}, chapter {scene.chapter}): the page's numbers.

{how[0].upper()}{how[1:]} with the project's own package for the values the page had, over
T_END_S seconds, and prints {"the readout beside the scene, then " if readout else ""}the last frame's series, the
invariants and how far they drifted.
{_RUN.format(file=file)}
"""

{imports}{_SHOW}

# The values the page had (SI units; angles in degrees where a name ends in _deg).
{values}{_display_note(display)}
T_END_S = {python_literal(SCRIPT_T_END_S)}  # simulated time (s): set it to the page's t to compare with its readout
FRAME_RATE_HZ = {python_literal(SCRIPT_FRAME_RATE_HZ)}  # samples per simulated second, as the page draws them

# Check the values as the server does (a bad one raises an error naming it), then compute.
{check}answer = {run}

t = answer["t"]
{readout}print(f"series at t = {{t[-1]:g}} s (frame {{len(t) - 1}} at {{FRAME_RATE_HZ:g}} Hz):")
for name, values in answer["series"].items():
    show(name, values[-1], {name}.series_units.get(name, ""))
print("invariants at the same instant:")
for name, values in answer["invariants"].items():
    show(name, values[-1], {name}.invariant_units.get(name, ""))
print("how it was computed:")
stats = answer["stats"]
show("method", stats["method"])
show("max_invariant_drift", stats["max_invariant_drift"])  # largest |I(t) - I(0)| / scale over the run
show("status", stats["status"])  # anything but ok: the message says where the answer stops holding
if stats["message"]:
    show("message", stats["message"])
'''


def _rotation_sequence_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    angles = [params["angle1_deg"], params["angle2_deg"], params["angle3_deg"]]
    display = {k: v for k, v in params.items() if k not in ("sequence", "angle1_deg", "angle2_deg", "angle3_deg")}
    return f'''"""{scene.title} (scene {scene.id}, chapter {scene.chapter}): the page's numbers.

Composes the three turns with the project's rotation functions and prints what the readout
shows: the rotation matrix, its quaternion, axis and angle, the angles read back, the distance
to gimbal lock and how fast the angles must turn per unit angular velocity.
{_RUN.format(file=script_file_name(scene.id))}
"""

import numpy as np

from app.physics.math.rotations import (
    angle_rate_matrix_body,
    angles_from_matrix,
    axis_angle_from_quaternion,
    intermediate_frames,
    rotation_sequence,
)
{_SHOW}

# The values the page had.
sequence = rotation_sequence({python_literal(params["sequence"])})  # axes of the three body-fixed turns \
(1 = x, 2 = y, 3 = z)
angles_deg = {python_literal(angles)}  # theta1, theta2, theta3 (deg)
{_display_note(display)}
angles_rad = np.radians(angles_deg)
frames = intermediate_frames(angles_rad, sequence)  # the fixed frame, then after one, two and three turns
R = frames.R_world_frame[3]  # v_XYZ = [R] v_xyz
q = frames.q_world_frame[3]  # the same rotation as a quaternion (w, x, y, z)
axis, angle_rad = axis_angle_from_quaternion(q)
read_back = angles_from_matrix(R, sequence)
# The smallest singular value of the angle-rate matrix: near gimbal lock the angles must turn fast.
smallest = np.linalg.svd(angle_rate_matrix_body(angles_rad, sequence), compute_uv=False)[-1]

print(f"{{sequence.name}} ({{sequence.kind}}):")
for row in range(3):
    show(f"R_row{{row + 1}}", R[row])
for component, value in zip("wxyz", q):
    show(f"q_{{component}}", value)
show("axis", axis)
show("rotation_angle_deg", np.degrees(angle_rad), "deg")
show("gimbal_lock_distance_deg", np.degrees(read_back.lock_distance_rad), "deg")
show("recovered_angles_deg", np.degrees(read_back.angles_rad), "deg")
show("rate_gain", None if read_back.degenerate else 1.0 / smallest, "(rad/s)/(rad/s)")
'''


def _configuration_space_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    kind = params["constraint"]
    if kind == "nonholonomic":
        names: tuple[str, ...] = ("drive_distance_m", "turn_angle_deg")
        body = """park = physics.ParallelParking(values["drive_distance_m"], math.radians(values["turn_angle_deg"]))

print("one manoeuvre: drive s, turn alpha, reverse s, turn back:")
show("sideways_drift_m", park.sideways_drift_m, "m")  # s sin(alpha): no admissible velocity points this way
show("sideways_drift_leading_m", park.drive_distance_m * park.turn_angle_rad, "m")  # s alpha, to leading order
show("forward_drift_m", park.forward_drift_m, "m")  # s (1 - cos alpha)
"""
    else:
        if kind == "scleronomic":
            names = ("semi_axis_a_m", "semi_axis_b_m", "bead_rate_rad_s")
            build = (
                'system = physics.FixedEllipse(values["semi_axis_a_m"], values["semi_axis_b_m"], '
                'values["bead_rate_rad_s"])'
            )
        else:
            names = ("hoop_radius_m", "hoop_amplitude_m", "hoop_rate_rad_s", "bead_rate_rad_s")
            build = (
                'system = physics.SlidingHoop(values["hoop_radius_m"], values["hoop_amplitude_m"], '
                'values["hoop_rate_rad_s"], values["bead_rate_rad_s"])'
            )
        body = f"""{build}
snap = system.snapshot(T_S)

print(f"the bead at t = {{T_S:g}} s:")
show("bead_x_m", snap.position[0], "m")
show("bead_y_m", snap.position[1], "m")
show("bead_speed_m_s", math.hypot(*snap.velocity), "m/s")
show("constraint_value", snap.constraint_value)  # g at the bead: zero on the curve
show("virtual_variation", snap.virtual_variation)  # grad g . delta r for a unit delta r, time frozen
show("gradient_along_velocity_1_s", snap.gradient_along_velocity, "1/s")  # grad g . r'
show("constraint_time_rate_1_s", snap.time_rate, "1/s")  # dg/dt at fixed position
show("actual_variation_1_s", snap.actual_variation, "1/s")  # grad g . r' + dg/dt
show("angle_dr_virtual_deg", snap.angle_between_deg, "deg")  # between the actual dr and delta r
"""
    values = {k: params[k] for k in names}
    display = {k: v for k, v in params.items() if k not in names and k != "constraint"}
    return f'''"""{scene.title} (scene {scene.id}, chapter {scene.chapter}): the page's numbers.

The {kind} case, computed with the project's own package: what the readout shows when the
scene starts (set T_S to another time for a moving bead).
{_RUN.format(file=script_file_name(scene.id))}
"""

import math

from app.physics.systems.ch07 import configuration_space as physics
{_SHOW}

# The values the page had (SI units; angles in degrees where a name ends in _deg).
{_dict_block("values", values)}
{_display_note(display)}T_S = 0.0  # time (s) since the scene started

{body}'''


def _toggle_press_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    from app.physics.systems.ch07.virtual_work import TOGGLE_PARAMETERS

    values = {k: params[k] for k in TOGGLE_PARAMETERS.by_name}
    display = {k: v for k, v in params.items() if k not in values}
    return f'''"""{scene.title} (scene {scene.id}, chapter {scene.chapter}): the page's numbers.

Finds the holding force Q twice with the project's own package, by virtual work (one equation)
and from both bars' equilibrium (six), and prints the readout's numbers.
{_RUN.format(file=script_file_name(scene.id))}
"""

from app.physics.systems.ch07 import virtual_work as physics
{_SHOW}

# The values the page had (SI units; angles in degrees where a name ends in _deg).
{_dict_block("values", values)}
{_display_note(display)}
press = physics.TogglePress.from_params(physics.TOGGLE_PARAMETERS.validate(values))
shifts = press.virtual_displacements()  # each point's virtual displacement per unit delta theta (m/rad)

print("the toggle press:")
show("load_virtual_work_N_m", press.load_virtual_work_N_m(), "N·m")  # of the loads per unit delta theta
show("slider_virtual_displacement_m", shifts["C"][0], "m")
show("knee_virtual_displacement_y_m", shifts["B"][1], "m")
try:
    holding_force_N = physics.holding_force_by_virtual_work(press)
    forces = physics.toggle_equilibrium(press)
except physics.TogglePositionError as exc:  # the bars in line: no finite Q holds the loads
    print("  no holding force:", exc)
else:
    show("holding_force_N", holding_force_N, "N")
    show("holding_force_newtonian_N", forces.holding_force_N, "N")
    show("relative_difference", abs(holding_force_N - forces.holding_force_N) / \
max(abs(forces.holding_force_N), 1e-300))
    if press.load_B_N != 0.0:
        show("force_ratio", holding_force_N / press.load_B_N)
    show("guide_force_C_N", forces.guide_C_N, "N")
'''


def _finite_rotation_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    names = ("sequence", "angle1_deg", "angle2_deg", "angle3_deg", "second_axis", "second_angle_deg")
    values = {k: params[k] for k in names}
    display = {k: v for k, v in params.items() if k not in names}
    return f'''"""{scene.title} (scene {scene.id}, chapter {scene.chapter}): the page's numbers.

Turns A (a rotation sequence) and B (one turn about a fixed axis) with the project's own package:
Euler's theorem gives A as one turn of angle phi about an axis n, and the two orders of A and B
end apart unless the turns commute.
{_RUN.format(file=script_file_name(scene.id))}
"""

import math

from app.physics.systems.ch03 import finite_rotation as physics
{_SHOW}

# The values the page had (angles in degrees).
{_dict_block("values", values)}
{_display_note(display)}
angles_rad = [math.radians(values[f"angle{{k}}_deg"]) for k in (1, 2, 3)]
result = physics.finite_rotation(
    angles_rad, values["sequence"], second_axis=values["second_axis"], \
second_angle_rad=math.radians(values["second_angle_deg"])
)
a = result.turn_a

print(f"A: the {{result.sequence.name}} turns as one turn:")
for component, value in zip("wxyz", a.q_world_body):
    show(f"q_{{component}}", value)
for component, value in zip("xyz", a.axis_world):
    show(f"axis_{{component}}", value if a.angle_rad >= 1e-9 else None)  # no turn at all: no axis
show("rotation_angle_deg", math.degrees(a.angle_rad), "deg")
show("rodrigues_mismatch", result.rodrigues_mismatch)  # Rodrigues' [R] from (n, phi) against the sequence's [R]
if values["second_angle_deg"] != 0.0:
    print("A and B in both orders:")
    for name, turn in (("a_then_b", result.a_then_b), ("b_then_a", result.b_then_a)):
        show(f"{{name}}_angle_deg", math.degrees(turn.angle_rad), "deg")
        show(f"{{name}}_axis", turn.axis_world)
    show("order_gap_deg", math.degrees(result.order_gap_rad), "deg")  # the turn from one result to the other
'''


#: Scenes that draw neither a model nor a worked example: their script, by scene id.
_OWN_FORMULAS: Mapping[str, Callable[[type[Scene], Mapping[str, Any]], str]] = {
    "rotation-sequence": _rotation_sequence_script,
    "configuration-space-constraints": _configuration_space_script,
    "virtual-work-frame": _toggle_press_script,
    "finite-rotation": _finite_rotation_script,
}


def scene_script(scene: type[Scene], params: Mapping[str, Any]) -> str:
    """A script printing the numbers of ``scene`` for its validated ``params`` (the scene's whole parameter set).

    Raises ``ValueError`` for a scene this module cannot write a script for.
    """
    if scene.model is not None:
        return _model_script(scene, params)
    if scene.example is not None:
        example = scene.example
        inputs = {k: v for k, v in params.items() if k in example.inputs.by_name}
        return example_script(example, inputs, display={k: v for k, v in params.items() if k not in inputs})
    own = _OWN_FORMULAS.get(scene.id)
    if own is None:
        raise ValueError(f"scene {scene.id!r} draws neither a model nor a worked example, and has no script of its own")
    return own(scene, params)
