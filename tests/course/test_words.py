"""Words a student reads name every input as its control does, with its unit; raw names stay in the API.

A raw name is a parameter name of a scene or worked example, a series or invariant name of a scene's
model, or an output name of a worked example, when it has an underscore (``precession_rate0_rad_s``):
such a name is an API contract, not a word. A one-letter symbol with a one-letter subscript (``v_R``,
``a_z``, ``A_x``) reads as the symbol itself and is not counted. The checks:

* lesson prose (outside fenced code, math, and paragraphs that show an API route such as
  ```POST /api/scenes/…/simulate```, whose inline code is the API) holds no raw name;
* a bad value for any parameter of any scene or worked example is refused with a message that starts
  with the parameter's :meth:`~app.physics.core.parameters.Parameter.display_name` and holds no raw
  name, while the error's ``field`` (the API's ``loc``) keeps the parameter name; the same holds for
  refusals of combinations (each numeric parameter at its ends, alone and in pairs) and through the
  API, across the scene worker's process boundary;
* the labels the page shows (parameters and presets in ``GET /api/scenes``, inputs in ``GET /api/examples``,
  readout quantities and marks written in ``app/scenes``) hold no raw name; the live readouts of every scene are checked too,
  in a slow test (building all scenes takes about a minute).
"""

from __future__ import annotations

import ast
import itertools
import re
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from app.course.lessons import _DISPLAY_MATH, _INLINE_MATH, LESSONS_DIR
from app.main import create_app
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.systems import worked_examples
from app.scenes import SCENES
from app.scenes.host.rpc import encode_error, raise_answer

REPO = Path(__file__).resolve().parents[2]
#: Reads as a symbol: one letter, an underscore, one letter (v_R, a_z, A_x).
SYMBOL_LIKE = re.compile(r"[A-Za-z]_[A-Za-z]")
FENCE = re.compile(r"^(```|~~~).*?^\1", re.MULTILINE | re.DOTALL)
API_ROUTE = re.compile(r"`(?:GET|POST|PUT|DELETE) /api/")
#: An exercise statement's slot for a given number (app.practice.exercise.PLACEHOLDER), replaced by "2.4 kg".
PLACEHOLDER = re.compile(r"\{\{\s*[a-z_][a-z0-9_]*\s*\}\}")
#: Scenes whose whole-set check derives equations in a child process: their single-value refusals
#: are checked like every other scene's, the sweep of combinations is not (it would derive hundreds of times).
DERIVING_SCENES = frozenset({"typed-lagrangian"})


def _raw_names() -> frozenset[str]:
    names: set[str] = set()
    for cls in SCENES.values():
        names |= {p.name for p in cls.parameters.parameters}
        if cls.model is not None:
            names |= set(getattr(cls.model, "series_units", {})) | set(getattr(cls.model, "invariant_units", {}))
    for example in worked_examples().values():
        names |= {p.name for p in example.inputs.parameters} | set(example.output_units)
    return frozenset(n for n in names if "_" in n and not SYMBOL_LIKE.fullmatch(n))


RAW_NAMES = _raw_names()
RAW_NAME = re.compile(r"(?<![\w\\])(" + "|".join(map(re.escape, sorted(RAW_NAMES, key=len, reverse=True))) + r")(?![\w])")


def raw_names_in(text: str) -> list[str]:
    return RAW_NAME.findall(text)


def test_the_list_of_raw_names_is_the_one_the_issue_found():
    """The names the issue saw in lesson text and messages are among those checked (the checks can fail)."""
    assert {"precession_rate0_rad_s", "I_transverse_pivot", "crank_speed_rad_s", "theta_deg"} <= RAW_NAMES
    assert raw_names_in("set `crank_speed_rad_s` to 2") == ["crank_speed_rad_s"]
    assert raw_names_in(r"the speed $v_R$ and v_R, and \theta_deg in TeX") == []


# --- lesson prose -----------------------------------------------------------------------------------------------


def prose_offenders(markdown: str) -> list[str]:
    """Raw names in a lesson body's prose: outside fenced code, math and paragraphs that show an API route."""
    body = markdown.split("+++", 2)[2] if markdown.startswith("+++") else markdown
    body = PLACEHOLDER.sub("", FENCE.sub("", body))  # an exercise's {{name}}: the page shows the number there
    found: list[str] = []
    for paragraph in re.split(r"\n\s*\n", body):
        if API_ROUTE.search(paragraph):
            continue
        found += raw_names_in(_INLINE_MATH.sub("", _DISPLAY_MATH.sub("", paragraph)))
    return found


def test_prose_offenders_are_found_outside_code_math_and_api_examples():
    text = (
        "+++\nid = 'x'\n+++\nSet `spin_rad_s` to 2.\n\n$\\omega_{spin\\_rad\\_s}$ and $$I_axial$$\n\n"
        "```python\nsimulate(crank_speed_rad_s=1)\n```\n\n`POST /api/scenes/heavy-top/simulate` returns `nutation_deg`.\n"
        "\nA disk of mass {{mass_kg}} spins.\n"
    )
    assert prose_offenders(text) == ["spin_rad_s"]


LESSON_FILES = sorted((REPO / LESSONS_DIR if not Path(LESSONS_DIR).is_absolute() else Path(LESSONS_DIR)).rglob("*.md"))


def test_there_are_lessons_to_check():
    assert len(LESSON_FILES) >= 50


def test_no_lesson_prose_uses_a_raw_parameter_series_or_output_name():
    offenders = {
        f"{path.relative_to(REPO)}: {', '.join(sorted(set(found)))}"
        for path in LESSON_FILES
        if (found := prose_offenders(path.read_text(encoding="utf-8")))
    }
    assert not offenders, "lesson prose should name inputs as the controls do, e.g. **φ̇₀** (rad/s):\n" + "\n".join(sorted(offenders))


# --- refusals of single values -----------------------------------------------------------------------------------


def bad_value(parameter: Parameter) -> object:
    """A value ``parameter`` refuses: above its range, not one of its choices, not text, not a list."""
    if parameter.kind in ("float", "int"):
        assert parameter.min is not None and parameter.max is not None
        return parameter.max + (parameter.max - parameter.min) + 1.0
    if parameter.kind == "vector":
        return [0.0] * (parameter.length + 1)
    if parameter.kind == "choice":
        return "no-such-choice"
    if parameter.kind == "text":
        return 12345
    return "not a list"


def parameter_sets() -> Iterator[tuple[str, ParameterSet]]:
    for scene_id, cls in sorted(SCENES.items()):
        yield f"scene {scene_id}", cls.parameters
    for example_id, example in sorted(worked_examples().items()):
        yield f"example {example_id}", example.inputs


PARAMETERS = [(owner, p) for owner, parameters in parameter_sets() for p in parameters.parameters]


def test_display_name_is_the_control_label_and_unit():
    top = SCENES["heavy-top"].parameters.by_name
    assert top["precession_rate0_rad_s"].display_name() == "φ̇₀ (rad/s)"
    assert top["I_transverse_pivot"].display_name() == "I_t (kg·m²)"
    assert Parameter("mu", "", 0.1, 0.0, 1.0, label="μ").display_name() == "μ"


@pytest.mark.parametrize(("owner", "parameter"), PARAMETERS, ids=[f"{o}:{p.name}" for o, p in PARAMETERS])
def test_a_bad_value_is_refused_by_the_name_its_control_shows(owner, parameter):
    sets = dict(parameter_sets())
    with pytest.raises(ParameterError) as refused:
        sets[owner].validate({parameter.name: bad_value(parameter)})
    error = refused.value
    assert error.field == parameter.name and error.path[0] == parameter.name  # the API's loc keeps the name
    message = str(error)
    assert message.startswith(f"{parameter.display_name()}:"), message
    assert raw_names_in(message) == [], message


# --- refusals of combinations ---------------------------------------------------------------------------------


def combination_refusals(parameters: ParameterSet) -> dict[str, dict[str, float]]:
    """Every message refusing a combination: each float or int parameter at its ends, alone and in pairs."""
    numeric = [p for p in parameters.parameters if p.kind in ("float", "int")]
    trials = [{p.name: end} for p in numeric for end in (p.min, p.max)]
    trials += [
        {p.name: a, q.name: b}
        for p, q in itertools.combinations(numeric, 2)
        for a, b in itertools.product((p.min, p.max), (q.min, q.max))
    ]
    messages: dict[str, dict[str, float]] = {}
    for values in trials:
        try:
            parameters.validate(values)
        except ValueError as exc:
            messages.setdefault(str(exc), values)
    return messages


def test_refusals_of_combinations_name_inputs_as_the_controls_do():
    offenders: list[str] = []
    refusals = 0
    for owner, parameters in parameter_sets():
        if owner.removeprefix("scene ") in DERIVING_SCENES:
            continue
        for message, values in combination_refusals(parameters).items():
            refusals += 1
            if raw_names_in(message):
                offenders.append(f"{owner} {values}: {message}")
    assert refusals >= 10  # the sweep reaches the checks it is meant to check
    assert not offenders, "\n".join(offenders)


def _bad_body(edit) -> list[dict]:
    from app.physics.systems.ch05.composite_body import DEFAULT_BODIES

    bodies = [{**body, "position_m": list(body["position_m"]), "angles_deg": list(body["angles_deg"])} for body in DEFAULT_BODIES]
    edit(bodies)
    return bodies


#: One bad entry for each field of the body editor, what the editor calls that spot, and the API's path to it.
BODY_EDITOR_REFUSALS = [
    (lambda b: b[2].__setitem__("length_m", 200.0), "body 3, length (m)", ("bodies", 2, "length_m")),
    (lambda b: b[1].__setitem__("radius_m", -1.0), "body 2, radius (m)", ("bodies", 1, "radius_m")),
    (lambda b: b[0].__setitem__("mass_kg", 0.0), "body 1, mass (kg)", ("bodies", 0, "mass_kg")),
    (lambda b: b[0]["position_m"].__setitem__(2, 1e9), "body 1, z (m)", ("bodies", 0, "position_m", 2)),
    (lambda b: b[2]["angles_deg"].__setitem__(1, 1000.0), "body 3, angle 2 (deg)", ("bodies", 2, "angles_deg", 1)),
    (lambda b: b[0].__setitem__("hole", "yes"), "body 1, hole", ("bodies", 0, "hole")),
    (lambda b: b[1].__setitem__("position_m", [0.3, 0.2, 0.0]), "body 2", ("bodies", 1)),  # the hole off the plate's edge
]


@pytest.mark.parametrize(("edit", "place", "path"), BODY_EDITOR_REFUSALS, ids=[r[1] for r in BODY_EDITOR_REFUSALS])
def test_a_bad_body_is_refused_by_the_words_of_the_body_editor(edit, place, path):
    """The editor labels its rows "body 1, body 2, …" and its fields "radius (m)", "z (m)", "angle 2 (deg)": a refusal
    names the spot the same way (it used to say "bodies → 2 → length_m", a raw name and a row counted from 0), while
    its path, the API's loc, keeps the API's names; the words survive the scene worker's boundary too."""
    scene = SCENES["inertia-explorer"]
    with pytest.raises(ParameterError) as refused:
        scene.parameters.validate({"bodies": _bad_body(edit)})
    error = refused.value
    assert error.path == path and error.field == "bodies"
    assert str(error).startswith(f"bodies, {place}: "), str(error)
    assert not re.search(r"\w_(m|kg|deg)\b", str(error)), str(error)  # no radius_m, mass_kg, angles_deg
    with pytest.raises(ParameterError) as again:
        raise_answer(encode_error(error))
    assert str(again.value) == str(error) and again.value.path == path


def test_a_refusal_keeps_its_display_name_across_the_scene_workers_boundary():
    with pytest.raises(ParameterError) as refused:
        SCENES["heavy-top"].parameters.validate({"precession_rate0_rad_s": 1e9})
    with pytest.raises(ParameterError) as again:
        raise_answer(encode_error(refused.value))
    assert str(again.value) == str(refused.value) and str(again.value).startswith("φ̇₀ (rad/s): must be between")
    assert again.value.field == "precession_rate0_rad_s"


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    with TestClient(create_app()) as client:
        yield client


def test_a_422_from_the_api_names_the_input_as_its_control_does(api):
    """Through the scene worker (PUT …/params) and in the front process (POST …/simulate): ``loc`` keeps the name."""
    answer = api.put("/api/scenes/heavy-top/sessions/words-test-session-1", json={"params": {"I_transverse_pivot": 1e9}})
    assert answer.status_code == 422
    issue = answer.json()["detail"][0]
    assert issue["loc"] == ["body", "params", "I_transverse_pivot"]
    assert issue["msg"].startswith("I_t (kg·m²): must be between") and raw_names_in(issue["msg"]) == []
    answer = api.post("/api/scenes/four-bar/simulate", json={"params": {"crank_speed_rad_s": 1e9}, "t_end": 1.0})
    assert answer.status_code == 422
    issue = answer.json()["detail"][0]
    assert issue["loc"] == ["body", "params", "crank_speed_rad_s"]
    assert issue["msg"].startswith("ω₂ (rad/s): ") and raw_names_in(issue["msg"]) == []


# --- labels the page shows -------------------------------------------------------------------------------------


def test_schema_labels_hold_no_raw_names(api):
    """The labels the page draws controls with, for scenes (and their presets) and worked examples."""
    offenders = [
        f"example {example['id']} input {parameter['name']}: {parameter['label']!r}"
        for example in api.get("/api/examples").json()
        for parameter in example["inputs"]
        if raw_names_in(parameter["label"])
    ]
    for scene in api.get("/api/scenes").json():
        for parameter in scene["parameters"]:
            if raw_names_in(parameter["label"]):
                offenders.append(f"{scene['id']} parameter {parameter['name']}: {parameter['label']!r}")
        for preset in scene["presets"]:
            if raw_names_in(f"{preset['label']} {preset['description']}"):
                offenders.append(f"{scene['id']} preset {preset['name']}: {preset['label']!r} {preset['description']!r}")
    assert len(api.get("/api/scenes").json()) == len(SCENES)
    assert not offenders, "\n".join(offenders)


#: Readout constructors and the positions of their words: ``Quantity(name, label, value, unit, text)``,
#: ``Quantity.word(name, label, text)``, ``Quantity.or_text(name, label, value, unit, text)``, ``Mark(value, label)``.
READOUT_WORDS = {"Quantity": (1, 4), "word": (1, 2), "or_text": (1, 4), "Mark": (1,)}


def readout_label_literals() -> Iterator[tuple[str, str]]:
    """``(where, text)`` for each string literal (f-string parts included) among the words of a readout row or mark
    written in ``app/scenes``."""
    for path in sorted((REPO / "app" / "scenes").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            positions = READOUT_WORDS.get(name, ())
            words = [node.args[i] for i in positions if i < len(node.args)]
            words += [k.value for k in node.keywords if k.arg in ("label", "text")]
            for word in words:
                for text in literal_text(word):
                    yield f"{path.relative_to(REPO)}:{node.lineno}", text


def literal_text(node: ast.expr) -> Iterator[str]:
    """The literal words of an expression that makes text: a string, an f-string's literal parts, either branch
    of a conditional, both sides of a concatenation (not the names or keys inside a replacement field)."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        yield node.value
    elif isinstance(node, ast.JoinedStr):
        yield from (part.value for part in node.values if isinstance(part, ast.Constant) and isinstance(part.value, str))
    elif isinstance(node, ast.IfExp):
        yield from literal_text(node.body)
        yield from literal_text(node.orelse)
    elif isinstance(node, ast.BinOp):
        yield from literal_text(node.left)
        yield from literal_text(node.right)


def test_readout_labels_written_in_the_scenes_hold_no_raw_names():
    literals = list(readout_label_literals())
    assert len(literals) > 200  # every scene's readout rows are found
    offenders = [f"{where}: {text!r}" for where, text in literals if raw_names_in(text)]
    assert not offenders, "\n".join(offenders)


@pytest.mark.slow
def test_every_scenes_live_readout_holds_no_raw_names():
    from tests.scenes.conftest import HeadlessClient, headless_viewer

    offenders = []
    with headless_viewer() as (_, viewer):
        for scene_id, cls in sorted(SCENES.items()):
            scene = cls(HeadlessClient(viewer), cls.parameters.validate({}))
            readout = scene.readout()
            texts = [scene.status]
            if readout is not None:
                shown = readout.as_dict()
                texts += [f"{q['label']} {q.get('text', '')}" for q in shown["quantities"]]
                texts += [mark["label"] for marks in shown["marks"].values() for mark in marks]
                texts.append(shown["message"])
            offenders += [f"{scene_id}: {text!r}" for text in texts if raw_names_in(text)]
            scene.close()
    assert not offenders, "\n".join(offenders)
