"""The packages of app/ import one way: no circle between them, kits below the scenes that use them, tools above.

Read from the source with ``ast`` (imports inside functions included; nothing is imported), so it is fast and
needs no server. The graph's nodes are found, not listed: every top-level package or module of ``app/`` (api,
bench, course, physics, scenes, web, cli, main, settings, … and any package added later), except that
``app/physics`` and ``app/scenes`` count each of their subpackages and modules as a node of its own (core,
solvers, …; kit, host, chNN, viser_boundary). An edge is an import from a module of one node to a module of
another. The rules:

* no circle in that graph;
* a scene's chapter folder (``app/scenes/chNN``) imports nothing from another chapter's scenes: what several
  chapters draw lives in ``app/scenes/kit`` (the physics they study may be imported from any chapter of
  ``app/physics/systems``);
* ``app/scenes/kit`` imports nothing from ``app/scenes/host`` (the host runs scenes; the kit builds them) nor from a
  chapter folder;
* ``app/bench`` is a command-line tool above the app: only ``app/cli.py`` imports it, inside the command functions.

Layers inside ``app/physics`` are checked by ``tests/physics/test_layering.py``.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest

APP = Path(__file__).resolve().parents[1] / "app"
#: Packages whose subpackages and modules are nodes of their own.
SPLIT_PACKAGES = ("physics", "scenes")
#: The one module outside app/bench that may import it (lazily, in its command functions).
BENCH_ENTRY = "app.cli"
CHAPTER = re.compile(r"ch\d+")


@dataclass(frozen=True)
class Import:
    """One imported module: who imports it (dotted module name, file, line) and whether inside a function."""

    importer: str
    path: Path
    line: int
    module: str
    in_function: bool


def module_names(app_dir: Path) -> dict[str, Path]:
    """Every module of the package at ``app_dir`` by dotted name (a package by its own name, for its __init__)."""
    names = {}
    for path in sorted(app_dir.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        parts = path.relative_to(app_dir.parent).with_suffix("").parts
        names[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return names


def _statements(tree: ast.AST) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
    """Every import statement in ``tree`` and whether it sits inside a function."""

    def visit(node: ast.AST, in_function: bool) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                yield child, in_function
            inside = in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            yield from visit(child, inside)

    yield from visit(tree, False)


@cache
def imports(app_dir: Path) -> tuple[Import, ...]:
    """Every import of a module of the package at ``app_dir`` made by one of its modules (relative imports resolved;
    ``from package import name`` names the submodule where ``name`` is one). Read once per tree."""
    modules = module_names(app_dir)
    root = app_dir.name
    found = []
    for importer, path in modules.items():
        package = importer if path.name == "__init__.py" else importer.rpartition(".")[0]
        for statement, in_function in _statements(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
            if isinstance(statement, ast.Import):
                targets = [alias.name for alias in statement.names]
            else:
                base = statement.module or ""
                if statement.level:
                    anchor = package.split(".")[: len(package.split(".")) - (statement.level - 1)]
                    base = ".".join(anchor + ([statement.module] if statement.module else []))
                targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in statement.names]
            for target in targets:
                if target == root or target.startswith(root + "."):
                    found.append(Import(importer, path, statement.lineno, target, in_function))
    return tuple(found)


def node_of(module: str, app_dir: Path) -> str | None:
    """The graph node holding ``module``: its top-level package or module under app, or for the split packages
    their subpackage or module (``scenes.kit``); ``None`` for the root package itself."""
    parts = module.split(".")[1:]
    if not parts:
        return None
    if parts[0] in SPLIT_PACKAGES and len(parts) > 1:
        inside = app_dir / parts[0]
        if (inside / parts[1]).is_dir() or (inside / f"{parts[1]}.py").is_file():
            return ".".join(parts[:2])
    return parts[0]


def import_graph(app_dir: Path) -> dict[tuple[str, str], list[Import]]:
    """The edges between nodes, each with the imports that make it."""
    edges: dict[tuple[str, str], list[Import]] = {}
    for found in imports(app_dir):
        source, target = node_of(found.importer, app_dir), node_of(found.module, app_dir)
        if source and target and source != target:
            edges.setdefault((source, target), []).append(found)
    return edges


def circles(edges: dict[tuple[str, str], list[Import]]) -> list[list[str]]:
    """The graph's strongly connected components of more than one node (Tarjan), each sorted."""
    successors: dict[str, list[str]] = {}
    for source, target in sorted(edges):
        successors.setdefault(source, []).append(target)
        successors.setdefault(target, [])
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in successors[node]:
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    for node in sorted(successors):
        if node not in index:
            visit(node)
    return sorted(components)


def describe_circle(component: list[str], edges: dict[tuple[str, str], list[Import]], app_dir: Path) -> str:
    """The circle's nodes and, for each edge inside it, where the imports are."""
    lines = [" <-> ".join(component)]
    for (source, target), found in sorted(edges.items()):
        if source in component and target in component:
            places = list(dict.fromkeys(f"{f.path.relative_to(app_dir.parent)}:{f.line}" for f in found))
            where = ", ".join(places[:4])
            more = f" and {len(places) - 4} more" if len(places) > 4 else ""
            lines.append(f"  {source} -> {target}: {where}{more}")
    return "\n".join(lines)


def _scenes_part(module: str) -> str | None:
    """``kit``, ``host``, ``chNN``, … for a module under app.scenes; ``None`` elsewhere."""
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[1] == "scenes" else None


def scene_rule_breaks(app_dir: Path) -> list[str]:
    """Chapter folders importing another chapter's scenes, and the kit importing the host or a chapter folder."""
    problems = []
    for found in imports(app_dir):
        source, target = _scenes_part(found.importer), _scenes_part(found.module)
        if source is None or target is None or source == target:
            continue
        where = f"{found.path.relative_to(app_dir.parent)}:{found.line} imports {found.module}"
        if CHAPTER.fullmatch(source) and CHAPTER.fullmatch(target):
            problems.append(f"{where}: a chapter's scenes import another chapter's (shared drawing goes in scenes/kit)")
        elif source == "kit" and (target == "host" or CHAPTER.fullmatch(target)):
            problems.append(f"{where}: the kit sits below the host and the chapters")
    return problems


def bench_importers(app_dir: Path) -> list[str]:
    """Imports of app.bench from outside it, other than the CLI's lazy ones in its command functions."""
    bench = f"{app_dir.name}.bench"
    return [
        f"{found.path.relative_to(app_dir.parent)}:{found.line} imports {found.module}"
        for found in imports(app_dir)
        if (found.module == bench or found.module.startswith(bench + "."))
        and not (found.importer == bench or found.importer.startswith(bench + "."))
        and not (found.importer == BENCH_ENTRY and found.in_function)
    ]


# ---- the tree as it is -------------------------------------------------------------------------------------------


def test_the_graph_really_reads_the_tree():
    edges = import_graph(APP)
    nodes = {node for edge in edges for node in edge}
    assert {"api", "web", "course", "settings", "scenes.kit", "scenes.host", "physics.core", "scenes.ch04"} <= nodes
    assert ("scenes.host", "scenes.kit") in edges  # the host runs what the kit builds


def test_no_import_circle_between_the_packages_of_app():
    edges = import_graph(APP)
    found = circles(edges)
    assert not found, "import circles:\n" + "\n".join(describe_circle(c, edges, APP) for c in found)


def test_chapter_folders_import_no_other_chapters_scenes_and_the_kit_sits_below_host_and_chapters():
    problems = scene_rule_breaks(APP)
    assert not problems, "\n".join(problems)


def test_bench_is_a_tool_above_the_app():
    problems = bench_importers(APP)
    assert not problems, "only app/cli.py imports app.bench, inside its command functions:\n" + "\n".join(problems)


# ---- the checks catch what they are for ----------------------------------------------------------------------------


def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    app_dir = tmp_path / "app"
    for name, source in {"__init__.py": "", **files}.items():
        path = app_dir / name
        path.parent.mkdir(parents=True, exist_ok=True)
        for parent in path.relative_to(app_dir).parents:
            (app_dir / parent / "__init__.py").touch()
        path.write_text(source, encoding="utf-8")
    return app_dir


def test_a_circle_through_a_function_level_import_is_found(tmp_path):
    app_dir = _tree(tmp_path, {
        "web/pages.py": "from app.tool import report\n",
        "tool/report.py": "def run():\n    from app import main\n",
        "main.py": "from app.web import pages\n",
    })  # fmt: skip
    edges = import_graph(app_dir)
    assert circles(edges) == [["main", "tool", "web"]]
    assert "app/tool/report.py:2" in describe_circle(["main", "tool", "web"], edges, app_dir)


def test_relative_imports_and_subpackages_of_the_split_packages_are_nodes(tmp_path):
    app_dir = _tree(tmp_path, {
        "scenes/kit/scene.py": "from ..viser_boundary import move_node\n",
        "scenes/viser_boundary.py": "from app.scenes import host\n",
        "scenes/host/host.py": "from app.scenes.kit import scene\n",
    })  # fmt: skip
    edges = import_graph(app_dir)
    assert set(edges) == {
        ("scenes.kit", "scenes.viser_boundary"), ("scenes.viser_boundary", "scenes.host"), ("scenes.host", "scenes.kit")
    }
    assert circles(edges) == [["scenes.host", "scenes.kit", "scenes.viser_boundary"]]


def test_a_chapter_importing_another_chapters_scene_and_a_kit_importing_the_host_are_caught(tmp_path):
    app_dir = _tree(tmp_path, {
        "scenes/ch04/four_bar.py": "from app.scenes.kit.planar import to_world\n",
        "scenes/ch06/rotor.py": "def f():\n    from app.scenes.ch04.four_bar import to_world\n",
        "scenes/ch06/ladder.py": "from app.physics.systems.ch04 import four_bar\nfrom app.scenes.ch06 import rotor\n",
        "scenes/kit/trail.py": "from app.scenes.host.viser_compat import update_node\n",
        "scenes/host/viser_compat.py": "",
        "scenes/kit/planar.py": "",
        "physics/systems/ch04/four_bar.py": "",
    })  # fmt: skip
    problems = scene_rule_breaks(app_dir)
    assert len(problems) == 2
    assert problems[0].startswith("app/scenes/ch06/rotor.py:2 imports app.scenes.ch04.four_bar")
    assert problems[1].startswith("app/scenes/kit/trail.py:1 imports app.scenes.host.viser_compat")


def test_only_the_clis_command_functions_may_import_bench(tmp_path):
    app_dir = _tree(tmp_path, {
        "bench/capacity.py": "from app.api import access\n",
        "cli.py": "from app.bench import capacity\n\ndef load():\n    from app.bench.capacity import run\n",
        "web/pages.py": "from app.bench import capacity\n",
    })  # fmt: skip
    assert bench_importers(app_dir) == [
        "app/cli.py:1 imports app.bench.capacity", "app/web/pages.py:1 imports app.bench.capacity"
    ]


if __name__ == "__main__":  # print the graph: python -m tests.test_import_layers
    graph = import_graph(APP)
    for (source, target), made_by in sorted(graph.items()):
        print(f"{source} -> {target} ({len(made_by)})")
    for component in circles(graph):
        print("circle:", describe_circle(component, graph, APP))
