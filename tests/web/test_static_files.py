"""The pages' static files (app/web/static_files.py): each page preloads its whole module graph, and the lesson page
inlines the script that starts its viewer."""

from __future__ import annotations

import re

from fastapi.testclient import TestClient

from app.main import create_app
from app.web.static_files import STATIC_DIR, inline_module, module_graph

PRELOADED = re.compile(r'<link rel="modulepreload" href="([^"]+)">')
ENTRIES = re.compile(r'<script type="module" src="([^"]+)"></script>')


def test_each_page_preloads_every_module_its_scripts_import_and_each_exists():
    client = TestClient(create_app())
    for path in ("/", "/lessons/10-2-spinning-top", "/solver-lab", "/join"):
        html = client.get(path).text
        entries = tuple(ENTRIES.findall(html))
        preloaded = PRELOADED.findall(html)
        assert preloaded == list(module_graph(entries)), path
        for url in (*entries, *preloaded):
            assert (STATIC_DIR / url.removeprefix("/static/")).is_file(), url
            assert client.get(url).status_code == 200, url


def test_the_lesson_graph_reaches_every_lesson_module_and_katex():
    graph = module_graph(("/static/js/lesson_page.js",))
    for name in ("lesson", "katex", "time_controls", "graphs", "derivations", "room", "config", "format", "socket"):
        assert f"/static/js/{name}.js" in graph
    assert "/static/vendor/katex/katex.min.js" in graph
    assert len(graph) == len(set(graph)) and "/static/js/lesson_page.js" not in graph


def test_a_lesson_with_a_scene_starts_its_viewer_from_an_inline_module_right_after_the_frame():
    client = TestClient(create_app())
    html = client.get("/lessons/10-2-spinning-top").text
    frame = html.index('<iframe id="viewer"')
    script_at = html.index(inline_module("js/viewer_preload.js"), frame)
    assert html[html.index("</iframe>", frame) + len("</iframe>") : script_at].strip() == ""  # right after the frame
    no_scene = client.get("/lessons/1-3-biographical-perspective").text  # a lesson with no scene: nothing to start
    assert '<iframe id="viewer"' in no_scene and inline_module("js/viewer_preload.js") not in no_scene
