"""The static directory the pages refer to: where it is, a page's module graph as ``<link rel="modulepreload">`` tags
(so the browser asks for every page script at once), and a script a page inlines.

A page names only its entry modules (``static/js/<page>.js``); without these links the browser learns of each
module's imports only once it has that module, one round trip per level of the graph (three on a lesson page), and
runs nothing until the last arrives. The graph is read from the files' own ``import`` lines, once per entry tuple.
"""

from __future__ import annotations

import posixpath
import re
from functools import cache, lru_cache
from html import escape
from pathlib import Path

#: Where ``/static/…`` URLs are served from (``app.main`` mounts it).
STATIC_DIR = Path(__file__).resolve().parents[2] / "static"
_STATIC_URL = "/static/"
#: A static import at the start of a line: ``import "./x.js";`` or ``import { a } from "./x.js";``.
_IMPORT = re.compile(r"""^\s*import\s+(?:[^"';]*?\s+from\s+)?["']([^"']+)["']""", re.MULTILINE)


def _imports(url: str) -> list[str]:
    """The URLs that the module at ``url`` (under ``/static/``) imports, in the order written."""
    source = (STATIC_DIR / url.removeprefix(_STATIC_URL)).read_text(encoding="utf-8")
    return [posixpath.normpath(posixpath.join(posixpath.dirname(url), spec)) for spec in _IMPORT.findall(source)]


@lru_cache(maxsize=16)
def module_graph(entries: tuple[str, ...]) -> tuple[str, ...]:
    """Every module that ``entries`` import, directly or not, each once, depth first (the entries excluded)."""
    seen: dict[str, None] = {}

    def visit(url: str) -> None:
        for imported in _imports(url):
            if imported not in seen and imported not in entries:
                seen[imported] = None
                visit(imported)

    for entry in entries:
        visit(entry)
    return tuple(seen)


def modulepreload_links(entries: tuple[str, ...]) -> str:
    """``<link rel="modulepreload">`` for every module the ``entries`` import."""
    return "".join(f'<link rel="modulepreload" href="{escape(url)}">' for url in module_graph(entries))


@cache
def inline_module(path: str) -> str:
    """The script ``static/<path>`` as an inline ``<script type="module" async>``: it runs as soon as the parser has
    read it, without waiting for the page's style sheets (as a classic script would) or for the end of parsing (as a
    module from a file does). Its text must not contain ``</script``."""
    text = (STATIC_DIR / path).read_text(encoding="utf-8")
    if "</script" in text.lower():
        raise ValueError(f"static/{path} cannot be inlined: it contains </script")
    return f'<script type="module" async>{text}</script>'
