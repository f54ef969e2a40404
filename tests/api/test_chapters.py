"""GET /api/chapters, the course page and the lesson pages."""

from __future__ import annotations

import html

import pytest

# The ten chapter titles of Ginsberg, Engineering Dynamics, as listed in the project's
# curriculum (CURRICULUM.md), in order.
CHAPTER_TITLES = [
    "Basic Considerations",
    "Particle Kinematics",
    "Relative Motion",
    "Kinematics of Constrained Rigid Bodies",
    "Inertial Effects for a Rigid Body",
    "Newton–Euler Equations of Motion",
    "Introduction to Analytical Mechanics",
    "Constrained Generalized Coordinates",
    "Alternative Formulations",
    "Gyroscopic Effects",
]


@pytest.fixture(scope="module")
def chapters(client):
    response = client.get("/api/chapters")
    assert response.status_code == 200
    return response.json()


def test_ten_chapters_in_order_with_the_books_titles(chapters):
    assert [ch["number"] for ch in chapters] == list(range(1, 11))
    assert [ch["title"] for ch in chapters] == CHAPTER_TITLES


def test_chapter_1_has_sections_1_1_to_1_3(chapters):
    assert [s["number"] for s in chapters[0]["sections"]] == ["1.1", "1.2", "1.3"]
    assert [s["title"] for s in chapters[0]["sections"]] == [
        "Vector operations",
        "Newtonian mechanics",
        "Biographical perspective",
    ]


def test_every_chapter_has_sections_numbered_within_it(chapters):
    for ch in chapters:
        assert ch["sections"], ch["title"]
        for s in ch["sections"]:
            assert s["number"].split(".")[0] == str(ch["number"])


def test_lessons_have_id_title_url(chapters):
    lessons = [lesson for ch in chapters for lesson in ch["lessons"]]
    assert lessons, "chapter 1 has lessons"
    assert len({lesson["id"] for lesson in lessons}) == len(lessons)
    for lesson in lessons:
        assert lesson["id"] and lesson["title"]
        assert lesson["url"] == f"/lessons/{lesson['id']}"


def test_every_lesson_url_serves_its_page(client, chapters):
    for ch in chapters:
        for lesson in ch["lessons"]:
            response = client.get(lesson["url"])
            assert response.status_code == 200, lesson["url"]
            assert response.headers["content-type"].startswith("text/html")
            assert html.escape(lesson["title"]) in response.text
            assert html.escape(ch["title"]) in response.text


def test_unknown_lesson_is_404(client):
    assert client.get("/lessons/no-such-lesson").status_code == 404


def test_course_page_names_all_ten_chapters(client):
    response = client.get("/")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    for title in CHAPTER_TITLES:
        assert html.escape(title) in response.text, title
