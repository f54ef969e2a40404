"""Classroom pages: the instructor link, the join page and the projector view (who may open it)."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from app.classroom.roles import COOKIE, HEADER
from app.main import create_app
from app.settings import Settings

KEY = "k" * 16


@pytest.fixture(scope="module")
def app():
    """Pages and rooms need no scene host: no lifespan is run, and rooms are opened on no lesson."""
    return create_app(Settings(instructor_key=KEY))


@pytest.fixture
def client(app) -> TestClient:
    return TestClient(app)


@pytest.fixture
def room(app):
    room, _ = app.state.rooms.create(join_base="http://10.0.0.5:8000")
    yield room
    app.state.rooms.close(room.room_id)


def code_box(html: str) -> str:
    match = re.search(r'<input id="join-code"[^>]*>', html, re.S)
    assert match, "the join page has the code box"
    return match.group(0)


def test_the_join_page_offers_an_empty_code_box_and_an_optional_name(client):
    response = client.get("/join")
    assert response.status_code == 200
    box = code_box(response.text)
    assert 'value=""' in box and 'data-from-url=""' in box, "without a code in the address nothing is joined at once"
    assert 'autocapitalize="characters"' in box and 'inputmode="text"' in box
    assert 'id="join-name"' in response.text and "only if they turn names on" in response.text
    assert 'role="alert"' in response.text, "errors are announced next to the box"
    assert "/static/js/join.js" in response.text


def test_the_qr_codes_address_shows_the_code_and_asks_for_a_name_first(client):
    """Found 10 (issue 24): /join/<code> joined at once, with no chance to give a name. It shows the room's code and
    the name box; join.js joins when the student presses Join (tests/browser/test_class_integrity_in_browser.py)."""
    html = client.get("/join/abc234").text
    box = code_box(html)
    assert 'value="ABC234"' in box and 'data-from-url="ABC234"' in box
    assert 'You are joining room <strong class="join-room">ABC234</strong>' in html
    assert 'id="join-name"' in html and '<button type="submit" id="join-button">Join</button>' in html


def test_a_code_in_the_address_is_escaped(client):
    response = client.get("/join/<script>")
    assert response.status_code == 200
    assert "<SCRIPT>" not in response.text and "<script>" not in response.text.replace('<script src=', "")
    assert 'value="&lt;SCRIPT&gt;"' in code_box(response.text)
    assert '<strong class="join-room">&lt;SCRIPT&gt;</strong>' in response.text
    quoted = client.get('/join/"onfocus=x')
    assert 'value="&quot;ONFOCUS=X"' in code_box(quoted.text), "a quote cannot close the attribute"


def test_the_instructor_link_with_the_right_key_sets_an_httponly_cookie(client):
    response = client.get("/instructor", params={"key": KEY}, follow_redirects=False)
    assert response.status_code == 303
    cookie = response.headers["set-cookie"]
    assert cookie.startswith(f"{COOKIE}=") and "httponly" in cookie.lower()
    assert KEY not in cookie, "the cookie holds a token derived from the key, not the key"


def test_the_instructor_link_with_a_wrong_key_is_refused_and_sets_no_cookie(client):
    response = client.get("/instructor", params={"key": "x" * 16}, follow_redirects=False)
    assert response.status_code == 403
    assert "set-cookie" not in response.headers
    assert client.cookies.get(COOKIE) is None


def test_a_student_cannot_open_the_projector_view(client, room):
    response = client.get(f"/rooms/{room.room_id}/projector")
    assert response.status_code == 403
    assert "text/html" in response.headers["content-type"] and "Instructor only" in response.text
    assert room.code not in response.text, "the refusal does not show the room's code"
    wrong = client.get(f"/rooms/{room.room_id}/projector", headers={HEADER: "x" * 16})
    assert wrong.status_code == 403


def test_the_projector_view_of_an_unknown_room_is_404(client):
    response = client.get("/rooms/0123456789abcdef/projector", headers={HEADER: KEY})
    assert response.status_code == 404
    assert "No such room" in response.text


@pytest.mark.parametrize("how", ["header", "cookie"])
def test_the_instructor_opens_the_projector_view(client, room, how):
    if how == "cookie":
        assert client.get("/instructor", params={"key": KEY}, follow_redirects=False).status_code == 303
        headers = {}
    else:
        headers = {HEADER: KEY}
    response = client.get(f"/rooms/{room.room_id}/projector", headers=headers)
    assert response.status_code == 200
    html = response.text
    assert f'<p class="projector-code" id="projector-code">{room.code}</p>' in html
    assert ">10.0.0.5:8000/join<" in html, "the join address is shown as a student types it, its code beside it"
    assert f'src="/room-viewer/{room.room_id}/?hideViserLogo"' in html
    assert f'src="/api/rooms/{room.room_id}/qr.svg"' in html
    assert "/static/js/projector.js" in html
