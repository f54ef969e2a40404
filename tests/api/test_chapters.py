"""GET /api/chapters, the course page and the lesson pages."""

from __future__ import annotations

import html
import re

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
def chapters(served):
    response = served.client.get("/api/chapters")
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


def test_course_page_says_in_words_which_sections_have_a_lesson(client, chapters):
    """Each section in a chapter's list links its lessons or says "no lesson yet" (words, not colour alone)."""
    page = client.get("/").text
    for ch in chapters:
        card = re.search(rf'<section class="chapter" id="chapter-{ch["number"]}".*?</section>', page, re.S).group(0)
        items = re.findall(r'<li data-section="[^"]+"><span class=sec-num>([^<]+)</span>(.*?)</li>', re.search(r'<ul class="sections">(.*?)</ul>', card, re.S).group(1), re.S)
        assert [number for number, _ in items] == [s["number"] for s in ch["sections"]], ch["title"]
        with_lessons = {lesson["section"] for lesson in ch["lessons"]}
        for number, item in items:
            if number in with_lessons:
                assert "no lesson yet" not in item, number
                for lesson in (l for l in ch["lessons"] if l["section"] == number):
                    assert f'<a href="{lesson["url"]}">{html.escape(lesson["title"])}</a>' in item, (number, lesson["id"])
            else:
                assert "no lesson yet" in item and "<a " not in item, number
        assert f"Sections: {len(with_lessons & {s['number'] for s in ch['sections']})} of {len(ch['sections'])} with a lesson" in card


def test_sections_4_1_and_4_2_have_their_lessons(client):
    page = client.get("/").text
    assert re.search(r'4\.1</span> General equations — <span class="sec-status has-lesson">lesson:</span> <a href="/lessons/4-1-general-equations">', page)
    assert re.search(r'4\.2</span> Eulerian angles — <span class="sec-status has-lesson">lesson:</span> <a href="/lessons/4-2-eulerian-angles">', page)
