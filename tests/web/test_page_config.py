"""The configuration every page hands its scripts (app/web/page_config.py)."""

from __future__ import annotations

import json
import re

from fastapi.testclient import TestClient

from app.main import create_app
from app.scenes.host.host import TIME_SCALE_RANGE
from app.web.page_config import TIME_SCALES, config_script, page_config

CONFIG = re.compile(r'<script type="application/json" id="dynlab-config">(.*?)</script>', re.S)


def test_the_time_scales_offered_are_the_ones_the_host_accepts():
    low, high = TIME_SCALE_RANGE
    assert page_config()["time_scales"] == list(TIME_SCALES)
    assert all(low <= scale <= high for scale in TIME_SCALES) and 1.0 in TIME_SCALES


def test_the_socket_reconnect_rule_grows_to_a_cap():
    rule = page_config()["socket_reconnect"]
    assert 0 < rule["initial_ms"] <= rule["cap_ms"] and rule["factor"] > 1


def test_no_text_in_the_configuration_can_end_its_script_element():
    hostile = {"title": "</script><script>alert(1)</script><!--", "also": "</SCRIPT>"}
    script = config_script(page_config(**hostile))
    body = CONFIG.fullmatch(script).group(1)
    assert "<" not in body
    assert json.loads(body)["title"] == hostile["title"] and json.loads(body)["also"] == hostile["also"]


def test_every_page_carries_the_configuration_and_loads_its_scripts_as_modules():
    client = TestClient(create_app())
    for path in ("/", "/lessons/10-2-spinning-top", "/solver-lab", "/join"):
        html = client.get(path).text
        config = json.loads(CONFIG.search(html).group(1))
        assert config["time_scales"] == list(TIME_SCALES), path
        assert '<script src=' not in html and '<script type="module" src="/static/js/' in html, path
