"""/docs works without internet: every script and stylesheet the Swagger UI page loads is served by this app."""

from __future__ import annotations

import re

from fastapi.testclient import TestClient

from app.main import create_app

CLIENT = TestClient(create_app())  # no lifespan: the docs page and static files need no scene host
ASSET_URL = re.compile(r"""<(?:script|link)\b[^>]*?\b(?:src|href)=["']([^"']+)["']""", re.IGNORECASE)


def test_docs_loads_only_local_assets_and_each_is_served():
    page = CLIENT.get("/docs")
    assert page.status_code == 200
    urls = ASSET_URL.findall(page.text)
    assert any(url.endswith("swagger-ui-bundle.js") for url in urls) and any(url.endswith("swagger-ui.css") for url in urls)
    for url in urls:
        assert url.startswith("/") and not url.startswith("//"), f"/docs loads {url} from another host"
        assert CLIENT.get(url).status_code == 200, url
    assert "http://" not in page.text and "https://" not in page.text  # no CDN, no online validator


def test_docs_points_at_this_apps_openapi():
    page = CLIENT.get("/docs").text
    assert "'/openapi.json'" in page
    assert CLIENT.get("/openapi.json").status_code == 200


def test_the_vendored_swagger_ui_says_its_version_and_licence():
    readme = CLIENT.get("/static/vendor/swagger-ui/README").text
    assert re.search(r"Swagger UI \d+\.\d+\.\d+ from the npm registry package swagger-ui-dist", readme)
    assert "Apache License" in CLIENT.get("/static/vendor/swagger-ui/LICENSE").text
