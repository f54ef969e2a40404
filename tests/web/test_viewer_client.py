"""viser's client unpacked on the server (app/web/viewer_client.py): the viewer page runs the same script and style
that viser's single-file page carries, from two cacheable, gzip-compressed files."""

from __future__ import annotations

import gzip
import re
from pathlib import Path

import viser
from fastapi.testclient import TestClient

from app.main import create_app
from app.web.pages import viewer_client_html
from app.web.viewer_client import SCRIPT_URL, STYLE_URL, unpacked_client


def test_the_unpacked_files_have_the_sizes_visers_page_states():
    page = (Path(viser.__file__).resolve().parent / "client" / "build" / "index.html").read_text(encoding="utf-8")
    style_size, script_size = map(int, re.search(r'data-ss="(\d+)" data-cs="(\d+)"', page).groups())
    client = unpacked_client()
    assert len(gzip.decompress(client.style_gz)) == style_size
    script = gzip.decompress(client.script_gz)
    assert len(script) == script_size and f"const B=`{viser.__version__}`" in script.decode()


def test_the_viewer_page_loads_the_files_and_keeps_only_the_loaders_webassembly():
    page = viewer_client_html().decode()  # what every viewer route serves
    assert "data-p=" not in page and len(page) < 60_000  # viser's page is 820 KB
    assert f'<link rel="modulepreload" href="{SCRIPT_URL}">' in page and f'href="{STYLE_URL}"' in page
    assert "globalThis.__viserZstdWasm=m.module" in page and f'e.src="{SCRIPT_URL}"' in page
    assert page.index("<title>3D scene — Dynamics Lab</title>") < page.index(SCRIPT_URL)


def test_the_files_are_gzip_compressed_cached_for_a_year_and_named_by_version():
    client = TestClient(create_app())
    for url, media_type in ((SCRIPT_URL, "text/javascript"), (STYLE_URL, "text/css")):
        assert viser.__version__ in url
        response = client.get(url)  # the test client asks for gzip, as browsers do, and decodes it
        assert response.status_code == 200 and response.headers["content-type"].startswith(media_type)
        assert response.headers["content-encoding"] == "gzip"
        assert (
            "immutable" in response.headers["cache-control"] and "max-age=31536000" in response.headers["cache-control"]
        )
        plain = client.get(url, headers={"Accept-Encoding": "identity"})
        assert "content-encoding" not in plain.headers and plain.content == response.content
    assert client.get("/viewer-client/viser-0.0.0.js").status_code == 404
