"""Classroom pages: the instructor link, joining a room by code, the room's viewer and the projector view."""

from __future__ import annotations

import html
from typing import Annotated

from fastapi import APIRouter, HTTPException, Path, Query, Request
from fastapi.responses import HTMLResponse, RedirectResponse, Response

from app.classroom.roles import COOKIE
from app.classroom.room import CODE_LENGTH, MAX_NAME_LENGTH, MAX_TYPED_CODE_LENGTH
from app.classroom.routes import RoomId, RoomsDep, is_instructor
from app.web.pages import _page, _template, viewer_client_html

router = APIRouter(tags=["pages"], include_in_schema=False)
esc = html.escape


@router.get("/instructor")
def instructor_link(request: Request, key: Annotated[str, Query(max_length=200)] = "") -> Response:
    """The link ``dynlab serve`` prints: the right key sets the instructor's cookie and opens the course."""
    instructor_key = request.app.state.instructor_key
    if not instructor_key.matches(key):
        raise HTTPException(
            status_code=403, detail="this is not the instructor link printed by dynlab serve (the key differs)"
        )
    response = RedirectResponse("/?instructor=1", status_code=303)
    response.set_cookie(
        COOKIE, instructor_key.cookie_token, httponly=True, samesite="strict", max_age=12 * 3600, path="/"
    )
    return response


def _join_page(code: str) -> HTMLResponse:
    """The join page: the code (typed, or from the QR code's address), an optional name, then Join."""
    if code:
        lead = (
            f'You are joining room <strong class="join-room">{esc(code)}</strong>. Give your name if you '
            "like, then press Join."
        )
    else:
        lead = "Type the code shown on the projector."
    fields = {"code": esc(code), "lead": lead, "code_size": CODE_LENGTH, "name_max": MAX_NAME_LENGTH}
    body = _template("join.html").substitute(fields)
    return _page("Join a room — Dynamics Lab", body, scripts=("/static/js/join.js",))


@router.get("/join", response_class=HTMLResponse)
def join_page() -> HTMLResponse:
    """A box for the room's code (the projector shows it, and a QR code of /join/<code>)."""
    return _join_page("")


@router.get("/join/{code}", response_class=HTMLResponse)
def join_code_page(code: Annotated[str, Path(max_length=MAX_TYPED_CODE_LENGTH)]) -> HTMLResponse:
    """The QR code's address: the room's code shown and filled in; the student may give a name, then joins."""
    return _join_page(code.upper())


@router.get("/room-viewer/{room_id}")
def room_viewer_redirect(room_id: RoomId) -> RedirectResponse:
    return RedirectResponse(f"/room-viewer/{room_id}/")


@router.get("/room-viewer/{room_id}/")
def room_viewer_page(room_id: RoomId, rooms: RoomsDep) -> Response:
    """viser's client, connecting to the room's fanned-out scene (:mod:`app.classroom.relay`)."""
    try:
        rooms.get(room_id)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    return Response(viewer_client_html(), media_type="text/html; charset=utf-8")


def _notice_page(status_code: int, title: str, message: str) -> HTMLResponse:
    """A page that says why it cannot show what was asked (a person reads it, not a client)."""
    body = (
        f'<section class="room-notice" role="alert"><h1>{esc(title)}</h1><p>{esc(message)}</p><p><a '
        'href="/">The course</a></p></section>'
    )
    response = _page(f"{title} — Dynamics Lab", body)
    response.status_code = status_code
    return response


@router.get("/rooms/{room_id}/projector", response_class=HTMLResponse)
def projector_page(room_id: RoomId, request: Request, rooms: RoomsDep) -> HTMLResponse:
    """The projector view (instructor only): the room's scene large; the join code, QR code, readout, play state
    and the current poll's anonymous histogram in type readable from the back row."""
    if not is_instructor(request):
        return _notice_page(
            403,
            "Instructor only",
            "The projector view is the instructor's: open the instructor "
            "link that dynlab serve printed, then this page again.",
        )
    try:
        room = rooms.get(room_id)
    except KeyError:
        return _notice_page(
            404,
            "No such room",
            "No open room has this address; it may have been closed. Open a room from a lesson page.",
        )
    join_address = room.join_url.removesuffix(f"/{room.code}").removeprefix("http://")  # as a student types it
    body = _template("projector.html").substitute(room_id=room.room_id, code=esc(room.code), join_url=esc(join_address))
    return _page(f"Room {room.code}: projector — Dynamics Lab", body, scripts=("/static/js/projector.js",))
