""""Open as Python": every worked example's and every scene's script, run, prints the numbers the API answers.

Each script is fetched from its route at the defaults (and a few at other values),
run in this process with ``runpy`` (stdout captured) and its printed numbers are
compared with the API's answer for the same inputs: ``POST …/solve`` for a worked
example, ``POST …/simulate`` (same span, frame rate and integration controls) for a
scene with a model, and the scene's own readout (built on a headless viewer) for the
scenes drawn from formulas of their own.

Tolerance: 1e-9 relative. Script and API run the same functions on the same floats in
one process (an automatic step choice reads the same cached pilot), so the only
difference is the script printing 12 significant figures (at most 5e-13 relative);
1e-9 leaves room for that and nothing else: another input, span, method or frame
changes the numbers far more.
"""

from __future__ import annotations

import ast
import contextlib
import io
import json
import math
import runpy
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from app.course.scripts import SCRIPT_FRAME_RATE_HZ, SCRIPT_T_END_S, python_literal
from app.main import create_app
from app.physics.core.closed_form import ClosedFormModel
from app.physics.solvers.controls import CONTROL_NAMES
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.systems import worked_examples
from app.scenes import SCENES
from tests.scenes.conftest import HeadlessClient, headless_viewer

REL_TOL = 1e-9
EXAMPLES = worked_examples()
MODEL_SCENES = [sid for sid, cls in SCENES.items() if cls.model is not None and issubclass(cls.model, (ClosedFormModel, IntegratedModel))]
EXAMPLE_SCENES = [sid for sid, cls in SCENES.items() if sid not in MODEL_SCENES and cls.example is not None]
OWN_FORMULA_SCENES = [sid for sid in SCENES if sid not in MODEL_SCENES and sid not in EXAMPLE_SCENES]
#: What a script may import: the project's package, and numpy/math for its own arithmetic.
ALLOWED_IMPORTS = ("app", "numpy", "math")


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as client:
        yield client


@pytest.fixture(scope="module")
def viewer():
    with headless_viewer() as connected:
        yield connected


def fetch_script(client: TestClient, url: str, values: Mapping[str, Any] | None = None) -> str:
    response = client.get(url, params={"params": json.dumps(values)} if values is not None else None)
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("text/x-python")
    return response.text


class Printed:
    """What a script printed: its ``  name = value unit`` lines, by section (the heading line above them).

    A step's heading ``step N: title:`` is section ``step N``; any other heading's first word names its section.
    Symbols may themselves contain " = " (``H = (C−A)/C``), so a value is found by its name, not by splitting.
    """

    def __init__(self, output: str) -> None:
        self.lines: dict[str, list[str]] = {}
        section = ""
        for line in output.splitlines():
            if not line.startswith("  "):
                section = " ".join(line.split()[:2]).rstrip(":") if line.startswith("step ") else line.split()[0].rstrip(":")
            elif " = " in line:
                self.lines.setdefault(section, []).append(line.strip())

    def names(self, section: str) -> set[str]:
        """The names printed in a section whose names are identifiers (outputs, series, invariants)."""
        return {line.split(" = ", 1)[0] for line in self.lines.get(section, [])}

    def value(self, section: str | None, name: str) -> str:
        """The printed value (and unit) of ``name`` in ``section`` (None: any section)."""
        sections = self.lines.values() if section is None else [self.lines.get(section, [])]
        found = [line[len(name) + 3 :] for lines in sections for line in lines if line.startswith(f"{name} = ")]
        assert found, f"{name} is not printed in section {section}"
        return found[0]


def run_script(text: str, tmp_path: Path) -> Printed:
    """Run a script as ``python script.py`` would and read back what it printed."""
    tree = ast.parse(text)  # a script is valid Python that imports only what it should, and never evals
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            modules = [alias.name for alias in node.names] if isinstance(node, ast.Import) else [node.module or ""]
            assert all(m.split(".")[0] in ALLOWED_IMPORTS for m in modules), f"a script imports {modules}"
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            assert node.func.id not in ("eval", "exec", "compile", "__import__"), "a script evaluates text"
    path = tmp_path / "script.py"
    path.write_text(text, encoding="utf-8")
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        runpy.run_path(str(path), run_name="__main__")
    return Printed(out.getvalue())


def assert_printed(printed: str, expected: Any, unit: str, where: str) -> None:
    """``printed`` (a value, then its unit) shows ``expected`` to REL_TOL (vectors and matrices element by element)."""
    text = printed[: -len(unit) - 1] if unit and printed.endswith(f" {unit}") else printed
    if isinstance(expected, (str, bool)):
        assert text == str(expected), f"{where}: printed {text!r}, the API says {expected!r}"
        return
    assert unit == "" or printed.endswith(f" {unit}"), f"{where}: printed {printed!r} without its unit {unit!r}"
    value = json.loads(text.replace("undefined", "null"))
    assert_close(value, expected, where)


def assert_close(value: Any, expected: Any, where: str) -> None:
    if isinstance(expected, list):
        assert isinstance(value, list) and len(value) == len(expected), f"{where}: printed {value}, the API says {expected}"
        for v, e in zip(value, expected):
            assert_close(v, e, where)
    elif expected is None:
        assert value is None, f"{where}: printed {value}, the API says undefined"
    else:
        assert value is not None and math.isclose(value, expected, rel_tol=REL_TOL), f"{where}: printed {value}, the API says {expected}"


def assert_solution_printed(printed: Printed, answer: dict[str, Any], output_units: Mapping[str, str], where: str) -> None:
    """Every output the page lists (sweeps longer than 3 are plotted, not listed) and every step's values."""
    listed = {name: value for name, value in answer["outputs"].items() if not (isinstance(value, list) and len(value) > 3)}
    assert printed.names("outputs") == set(listed), where
    for name, value in listed.items():
        assert_printed(printed.value("outputs", name), value, output_units.get(name, ""), f"{where} output {name}")
    for number, step in enumerate(answer["steps"], start=1):
        for symbol, value in step["values"].items():
            assert_printed(printed.value(f"step {number}", symbol), value, step["units"].get(symbol, ""), f"{where} step {number} {symbol}")


def assert_motion_printed(printed: Printed, answer: dict[str, Any], where: str) -> None:
    """The last frame's series and invariants (with their units) and the stats a student reads."""
    units = answer["units"]
    for kind, prefix in (("series", ""), ("invariants", "invariants.")):
        assert printed.names(kind) == set(answer[kind]), f"{where}: {kind}"
        for name, values in answer[kind].items():
            assert_printed(printed.value(kind, name), values[-1], units.get(prefix + name, ""), f"{where} {kind} {name}")
    stats = answer["stats"]
    for name in ("method", "status", "max_invariant_drift"):
        assert_printed(printed.value("how", name), stats[name], "", f"{where} {name}")
    if stats["message"]:
        assert_printed(printed.value("how", "message"), stats["message"], "", f"{where} message")


@pytest.mark.parametrize("example_id", list(EXAMPLES))
def test_every_worked_example_script_prints_the_solve_answer(client, tmp_path, example_id):
    example = EXAMPLES[example_id]
    printed = run_script(fetch_script(client, f"/api/examples/{example_id}/script.py"), tmp_path)
    answer = client.post(f"/api/examples/{example_id}/solve", json={"inputs": {}}).json()
    assert_solution_printed(printed, answer, example.output_units, example_id)


def simulate_answer(client: TestClient, scene_id: str, params: Mapping[str, Any]) -> dict[str, Any]:
    """The simulate answer for a scene's validated parameters (its model's, and the integration controls as request fields)."""
    cls = SCENES[scene_id]
    model = cls.model
    body: dict[str, Any] = {"params": {k: v for k, v in params.items() if k in model.parameters.by_name}, "t_end": SCRIPT_T_END_S, "frame_rate": SCRIPT_FRAME_RATE_HZ}
    body |= {k: v for k, v in params.items() if k in CONTROL_NAMES}
    response = client.post(f"/api/scenes/{scene_id}/simulate", json=body)
    assert response.status_code == 200, response.text
    return response.json()


@pytest.mark.parametrize("scene_id", MODEL_SCENES)
def test_every_model_scene_script_prints_the_simulate_answer(client, tmp_path, scene_id):
    printed = run_script(fetch_script(client, f"/api/scenes/{scene_id}/script.py"), tmp_path)
    assert_motion_printed(printed, simulate_answer(client, scene_id, SCENES[scene_id].parameters.defaults()), scene_id)


@pytest.mark.parametrize("scene_id", EXAMPLE_SCENES)
def test_every_example_scene_script_prints_its_worked_solution(client, tmp_path, scene_id):
    example = SCENES[scene_id].example
    printed = run_script(fetch_script(client, f"/api/scenes/{scene_id}/script.py"), tmp_path)
    answer = client.post(f"/api/examples/{example.id}/solve", json={"inputs": {}}).json()
    assert_solution_printed(printed, answer, example.output_units, scene_id)


def readout_numbers(viewer, scene_id: str, values: Mapping[str, Any]) -> dict[str, tuple[float, str]]:
    """The numeric rows (name -> value, unit) of a freshly built scene's readout, time excepted."""
    cls = SCENES[scene_id]
    scene = cls(HeadlessClient(viewer[1]), cls.parameters.validate(values))
    try:
        readout = scene.readout()
    finally:
        scene.close()
    return {q.name: (q.value, q.unit) for q in readout.quantities if q.value is not None and q.name != "t_s"}


@pytest.mark.parametrize("scene_id", OWN_FORMULA_SCENES)
def test_every_own_formula_scene_script_prints_its_readout(client, viewer, tmp_path, scene_id):
    """At the defaults the script prints every number of the scene's readout (time aside: the script is for t = 0)."""
    printed = run_script(fetch_script(client, f"/api/scenes/{scene_id}/script.py"), tmp_path)
    for name, (value, unit) in readout_numbers(viewer, scene_id, {}).items():
        assert_printed(printed.value(None, name), value, unit, f"{scene_id} {name}")


@pytest.mark.parametrize(
    ("scene_id", "values"),
    [
        ("configuration-space-constraints", {"constraint": "rheonomic", "hoop_amplitude_m": 0.5}),
        ("configuration-space-constraints", {"constraint": "nonholonomic", "drive_distance_m": 0.3, "turn_angle_deg": 20.0}),
        ("rotation-sequence", {"sequence": "3-2-1", "angle1_deg": 10.0, "angle2_deg": 90.0, "angle3_deg": -30.0}),  # gimbal lock
        ("virtual-work-frame", {"angle_deg": 3.0, "load_B_N": 500.0}),
        ("finite-rotation", {"sequence": "1-2-3", "angle1_deg": 90.0, "angle2_deg": 0.0, "angle3_deg": 0.0, "second_axis": "Z", "second_angle_deg": 90.0}),
    ],
)
def test_own_formula_scripts_follow_the_values(client, viewer, tmp_path, scene_id, values):
    """Other cases of the same scenes: whatever the script prints equals the readout's row of that name."""
    printed = run_script(fetch_script(client, f"/api/scenes/{scene_id}/script.py", values), tmp_path)
    numbers = readout_numbers(viewer, scene_id, values)
    shared = set(numbers) & set().union(*(printed.names(section) for section in printed.lines))
    assert len(shared) >= 3, f"{scene_id}: the script and the readout share only {shared}"
    for name in shared:
        assert_printed(printed.value(None, name), *numbers[name], f"{scene_id} {name}")


def test_scripts_carry_the_values_asked_for(client, tmp_path):
    """Values other than the defaults, integration controls included, reach the script and its numbers."""
    values = {"mass_kg": 2.0, "spin_rad_s": 40.0, "method": "rk4", "steps_per_frame": 8}
    printed = run_script(fetch_script(client, "/api/scenes/heavy-top/script.py", values), tmp_path)
    answer = simulate_answer(client, "heavy-top", SCENES["heavy-top"].parameters.validate(values))
    assert answer["stats"]["method"] == "rk4"
    assert_motion_printed(printed, answer, "heavy-top at other values")
    inputs = {"tension_N": 1500.0}
    printed = run_script(fetch_script(client, "/api/examples/1.1/script.py", inputs), tmp_path)
    answer = client.post("/api/examples/1.1/solve", json={"inputs": inputs}).json()
    assert_solution_printed(printed, answer, EXAMPLES["1.1"].output_units, "1.1 at other inputs")


@pytest.mark.parametrize(
    ("url", "text", "loc"),
    [
        ("/api/scenes/heavy-top/script.py", '{"mass_kg": -1}', ["query", "params", "mass_kg"]),
        ("/api/scenes/heavy-top/script.py", '{"mass_kg": "__import__(\'os\')"}', ["query", "params", "mass_kg"]),
        ("/api/scenes/heavy-top/script.py", '{"not_a_parameter": 1}', ["query", "params", "not_a_parameter"]),
        ("/api/scenes/heavy-top/script.py", '{"mass_kg": NaN}', ["query", "params"]),
        ("/api/scenes/four-bar/script.py", "[1, 2]", ["query", "params"]),
        ("/api/examples/1.1/script.py", "mass_kg=2", ["query", "params"]),
        ("/api/examples/1.1/script.py", '{"tension_N": 1e999}', ["query", "params", "tension_N"]),
    ],
)
def test_bad_params_get_422_naming_the_field_and_no_script(client, url, text, loc):
    response = client.get(url, params={"params": text})
    assert response.status_code == 422
    assert response.headers["content-type"].startswith("application/json")
    assert response.json()["detail"][0]["loc"] == loc


def test_unknown_ids_get_404(client):
    assert client.get("/api/scenes/no-such-scene/script.py").status_code == 404
    assert client.get("/api/examples/no-such-example/script.py").status_code == 404


def test_values_become_literals_and_nothing_else():
    """Plain validated data round-trips through its literal; anything else is refused."""
    plain = {"text": "t'\"\n); import os  #", "n": 3, "x": -0.1, "v": [1.0, 2.5e-300, 3.0], "records": [{"hole": False, "mass_kg": 2.0}]}
    assert ast.literal_eval(python_literal(plain)) == plain
    with pytest.raises(ValueError):
        python_literal(float("nan"))
    with pytest.raises(TypeError):
        python_literal(object())
    with pytest.raises(TypeError):
        python_literal({1: 2.0})


def test_script_routes_stay_out_of_the_openapi_document(client):
    """They answer text/x-python, not JSON: the document (and tests/api/test_openapi.py's rules) does not list them."""
    paths = client.get("/openapi.json").json()["paths"]
    assert not [path for path in paths if path.endswith("/script.py")]


def test_lesson_pages_carry_the_open_as_python_element(client):
    """lesson.js fills this element's links with the current values once they are accepted."""
    page = client.get("/lessons/1-1-vector-calculus")
    assert page.status_code == 200
    assert 'id="open-as-python"' in page.text
