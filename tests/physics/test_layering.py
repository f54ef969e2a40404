"""app/physics is pure numerics: it imports nothing above it, and its layers import only downwards.

Layers in order (see app/physics/__init__.py): core, math, solvers, bodies, mechanics, systems.
A module may import from its own layer and the layers before it, never from a later one, and
never from app.scenes, app.api, app.web, app.course, viser or fastapi. The check reads every
module's import statements (function-level imports included) with ``ast``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PHYSICS = Path(__file__).resolve().parents[2] / "app" / "physics"
LAYERS = ("core", "math", "solvers", "bodies", "mechanics", "constrained", "systems")
FORBIDDEN_TOP = ("app.scenes", "app.api", "app.web", "app.course", "app.main", "app.bench", "viser", "fastapi", "starlette", "uvicorn")


def imported_modules(source: str) -> list[str]:
    """Every module named by an ``import`` or ``from … import`` statement in ``source`` (absolute names)."""
    names = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.append(node.module)
            names += [f"{node.module}.{alias.name}" for alias in node.names]
    return names


def layer_of(module: str) -> str | None:
    parts = module.split(".")
    if parts[:2] != ["app", "physics"] or len(parts) < 3:
        return None
    return parts[2] if parts[2] in LAYERS else None


def violations(path: Path, *, physics_dir: Path = PHYSICS) -> list[str]:
    """What is wrong with the imports of the module at ``path`` inside ``physics_dir`` (app/physics)."""
    relative = path.relative_to(physics_dir.parent.parent).with_suffix("")
    own_layer = layer_of(".".join(relative.parts))
    found = []
    for name in imported_modules(path.read_text(encoding="utf-8")):
        if any(name == top or name.startswith(top + ".") for top in FORBIDDEN_TOP):
            found.append(f"{relative}: imports {name} (a layer above app/physics)")
        layer = layer_of(name)
        if own_layer is not None and layer is not None and LAYERS.index(layer) > LAYERS.index(own_layer):
            found.append(f"{relative}: {own_layer} imports {name} from the later layer {layer}")
    return found


def physics_modules() -> list[Path]:
    return sorted(p for p in PHYSICS.rglob("*.py") if "__pycache__" not in p.parts)


def test_every_physics_module_belongs_to_a_layer():
    stray = [str(p.relative_to(PHYSICS)) for p in physics_modules() if p.parent != PHYSICS and p.relative_to(PHYSICS).parts[0] not in LAYERS]
    assert not stray, f"modules outside the layers {LAYERS}: {stray}"
    assert [p.name for p in PHYSICS.glob("*.py")] == ["__init__.py"], "app/physics holds only its layers"


def test_physics_imports_nothing_above_it_and_layers_import_downwards():
    modules = physics_modules()
    assert len(modules) > 40  # the check really read the package
    problems = [v for path in modules for v in violations(path)]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize(
    ("module_path", "source", "expected"),
    [
        ("core/x.py", "from app.scenes.kit import Scene", "a layer above"),
        ("math/x.py", "def f():\n    import viser\n", "a layer above"),
        ("core/x.py", "from app.physics.solvers import simulate", "later layer solvers"),
        ("solvers/x.py", "from app.physics.systems.ch10 import heavy_top", "later layer systems"),
    ],
)
def test_the_check_catches_an_upward_import(tmp_path, module_path, source, expected):
    fake_physics = tmp_path / "app" / "physics"
    path = fake_physics / module_path
    path.parent.mkdir(parents=True)
    path.write_text(source, encoding="utf-8")
    found = violations(path, physics_dir=fake_physics)
    assert found and expected in found[0]


def test_systems_import_downwards_is_allowed(tmp_path):
    fake_physics = tmp_path / "app" / "physics"
    path = fake_physics / "systems" / "ch05" / "x.py"
    path.parent.mkdir(parents=True)
    path.write_text("from app.physics.bodies.rigid_body import PivotedBody\nfrom app.physics.math.rotations import rotate_vector\n")
    assert violations(path, physics_dir=fake_physics) == []
