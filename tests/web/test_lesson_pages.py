"""Lesson pages: a lesson that names several scenes offers each, and ``?scene=`` picks which the viewer shows."""

from __future__ import annotations

import json
import re

import pytest
from fastapi.testclient import TestClient

from app.main import create_app


@pytest.fixture(scope="module")
def pages() -> TestClient:
    """Pages need only the catalogue: no lifespan, so no scene host is started."""
    return TestClient(create_app())


def lesson_config(html: str) -> dict:
    match = re.search(r'<script type="application/json" id="dynlab-config">(.*?)</script>', html, re.S)
    assert match, "the lesson page carries its configuration"
    return json.loads(match.group(1))


def test_a_lesson_with_two_scenes_links_both_and_shows_the_first(pages):
    response = pages.get("/lessons/3-4-angular-velocity")
    assert response.status_code == 200
    picker = re.search(r'<nav class="scene-picker"[^>]*>(.*?)</nav>', response.text, re.S)
    assert picker, "a lesson with several scenes shows a scene picker"
    links = re.findall(r'href="([^"]+)"', picker.group(1))
    assert links == [
        "/lessons/3-4-angular-velocity?scene=angle-rates",
        "/lessons/3-4-angular-velocity?scene=rotation-sequence",
        "/lessons/3-4-angular-velocity?scene=moving-frame-acceleration",
    ]
    assert links[0] + '" aria-current="page"' in picker.group(1)
    assert lesson_config(response.text)["scene"]["id"] == "angle-rates"


def test_the_query_picks_the_scene_the_viewer_shows(pages):
    response = pages.get("/lessons/3-4-angular-velocity", params={"scene": "moving-frame-acceleration"})
    assert response.status_code == 200
    assert lesson_config(response.text)["scene"]["id"] == "moving-frame-acceleration"
    assert 'scene=moving-frame-acceleration" aria-current="page"' in response.text


def test_a_scene_the_lesson_does_not_name_is_not_found(pages):
    response = pages.get("/lessons/3-4-angular-velocity", params={"scene": "four-bar"})
    assert response.status_code == 404
    assert "has no scene 'four-bar'" in response.json()["detail"]
    assert "angle-rates, rotation-sequence, moving-frame-acceleration" in response.json()["detail"]


def test_a_lesson_with_one_scene_has_no_picker(pages):
    response = pages.get("/lessons/10-2-spinning-top")
    assert response.status_code == 200
    assert "scene-picker" not in response.text
    assert lesson_config(response.text)["scene"]["id"] == "heavy-top"
