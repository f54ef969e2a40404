"""``/api/rooms``: the instructor opens a room and drives it; students join by code, follow it and answer polls.

Every instructor-only route depends on :func:`require_instructor`, which answers
403 before the route runs, so a student's request changes nothing. Each change
is published at once on the room's socket (:mod:`app.classroom.hub`), so every
page in the room sees it within a frame or two.
"""

from __future__ import annotations

import contextlib
import json
import re
import secrets
from typing import Annotated, Any, cast

from fastapi import APIRouter, Depends, Header, HTTPException, Path, Request, WebSocket
from fastapi.concurrency import run_in_threadpool
from fastapi.exception_handlers import http_exception_handler
from fastapi.responses import PlainTextResponse, Response
from pydantic import BaseModel, ValidationError
from starlette.requests import HTTPConnection
from starlette.websockets import WebSocketDisconnect

from app.api.deps import CatalogueDep, SceneHostDep, SettingsDep
from app.api.errors import unprocessable
from app.api.schemas.errors import ErrorDetail, error_responses
from app.classroom.hub import REMOVED_MESSAGE, RoomHub, RoomHubDep
from app.classroom.join_limits import JoinLimits
from app.classroom.polls import Poll, PollClosedError, PollError
from app.classroom.qr import qr_svg
from app.classroom.ready_questions import ReadyQuestion
from app.classroom.registry import ROOM_ID_HEX_DIGITS, ROOM_ID_PATTERN, Rooms
from app.classroom.relay import follower_count
from app.classroom.roles import InstructorKey
from app.classroom.room import NotCurrentPoll, Room, RoomError, RoomMovedOn, StudentRemoved
from app.classroom.schemas import (
    POLL_ID_PATTERN,
    STUDENT_ID_PATTERN,
    AnswerAccepted,
    AnswerRequest,
    JoinAnswer,
    JoinRequest,
    PollPublic,
    PollRequest,
    PollResults,
    PollUpdate,
    ReadyQuestionSchema,
    Role,
    RoomClosed,
    RoomCreated,
    RoomCreateRequest,
    RoomState,
    RoomStateChange,
    StudentList,
    StudentRemovedAnswer,
)
from app.scenes.host.interface import HostBusy
from app.settings import Settings
from app.storage.database import StoreUnavailable

router = APIRouter(prefix="/api", tags=["rooms"])

STUDENT_HEADER = "X-Student-Token"
#: The device cookie: set on joining, HttpOnly, sent back only to the join route. A device that joins a room again
#: (the QR code scanned again, the code typed again) is the student it was, with the same token: one device, one vote.
DEVICE_COOKIE = "dynlab_device"
DEVICE_COOKIE_PATH = "/api/rooms/join"
DEVICE_PATTERN = re.compile(r"^[A-Za-z0-9_-]{16,64}$")
#: How long a device cookie lasts (s): a school day and then some; rooms do not outlive the server anyway.
DEVICE_COOKIE_MAX_AGE_S = 24 * 3600
_FORBIDDEN: dict[int | str, dict[str, Any]] = {
    403: {
        "model": ErrorDetail,
        "description": "Instructor only (the instructor link's cookie, or X-Instructor-Key); nothing changed",
    }
}
_NO_ROOM = "No open room has this id"


def get_rooms(request: HTTPConnection) -> Rooms:
    return request.app.state.rooms


def get_instructor_key(request: HTTPConnection) -> InstructorKey:
    return request.app.state.instructor_key


def get_ready_questions(request: HTTPConnection) -> tuple[ReadyQuestion, ...]:
    return request.app.state.ready_questions


def get_join_limits(request: HTTPConnection) -> JoinLimits:
    return request.app.state.join_limits


RoomsDep = Annotated[Rooms, Depends(get_rooms)]
JoinLimitsDep = Annotated[JoinLimits, Depends(get_join_limits)]
InstructorKeyDep = Annotated[InstructorKey, Depends(get_instructor_key)]
ReadyQuestionsDep = Annotated[tuple[ReadyQuestion, ...], Depends(get_ready_questions)]
RoomId = Annotated[str, Path(pattern=ROOM_ID_PATTERN, description=f"The room's id ({ROOM_ID_HEX_DIGITS} hex digits)")]
PollId = Annotated[str, Path(pattern=POLL_ID_PATTERN, description="A poll of the room: p1, p2, …")]
StudentToken = Annotated[
    str | None, Header(alias=STUDENT_HEADER, max_length=64, description="The token the room gave on joining")
]
StudentId = Annotated[
    str,
    Path(pattern=STUDENT_ID_PATTERN, description="A student's public id in the room: s1, s2, … (never their token)"),
]


def is_instructor(connection: HTTPConnection) -> bool:
    return get_instructor_key(connection).is_instructor(cookies=connection.cookies, headers=connection.headers)


def require_instructor(request: Request) -> None:
    """403 unless the request carries the instructor's cookie or key (checked before anything else runs)."""
    if not is_instructor(request):
        raise HTTPException(
            status_code=403, detail="instructor only: open the instructor link that dynlab serve printed"
        )


Instructor = Depends(require_instructor)


def room_of(room_id: RoomId, rooms: RoomsDep) -> Room:
    try:
        return rooms.get(room_id)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None


RoomDep = Annotated[Room, Depends(room_of)]


def join_base(request: Request, settings: Settings) -> str:
    """The address students reach this server at: ``Settings.public_url``, else the one the instructor used."""
    return settings.public_url or str(request.base_url)


def room_error(exc: RoomError) -> HTTPException:
    """A 422 naming the field; a 409 for a change meant for a lesson or scene the room has left."""
    if isinstance(exc, RoomMovedOn):
        return HTTPException(status_code=409, detail=exc.message)
    return unprocessable(["body", *exc.field.split(".")], exc.message)


async def room_error_handler(request: Request, exc: Exception) -> Response:
    """A :class:`RoomError` no route turned into its answer (a room another server closed while this one changed
    it): answered as :func:`room_error` says, never a 500."""
    assert isinstance(exc, RoomError)
    return await http_exception_handler(request, room_error(exc))


def change_room(room: Room, raw: dict[str, Any], *, catalogue: Any, host: Any, hub: RoomHub) -> dict[str, Any]:
    """Apply an instructor's change and publish the new state (routes and the socket share this)."""
    state = room.change(raw, catalogue=catalogue, host=host)
    hub.publish_state(room)
    return state


# ---- who am I ------------------------------------------------------------------------------------
@router.get("/me", response_model=Role)
def whoami(request: Request) -> dict[str, str]:
    """``{"role": "instructor" | "student"}`` for this browser."""
    return {"role": "instructor" if is_instructor(request) else "student"}


# ---- rooms -----------------------------------------------------------------------------------------
@router.post(
    "/rooms",
    response_model=RoomCreated,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(unprocessable="A lesson or scene that does not exist, or too many rooms open"),
    },
)
def create_room(
    body: RoomCreateRequest | None,
    request: Request,
    rooms: RoomsDep,
    settings: SettingsDep,
    catalogue: CatalogueDep,
    host: SceneHostDep,
    hub: RoomHubDep,
) -> dict[str, Any]:
    """Open a room (instructor only), on a lesson if one is named; students join it by its code."""
    try:
        room, closed = rooms.create(join_base=join_base(request, settings))
    except RoomError as exc:
        raise room_error(exc) from None
    for old in closed:
        host.close_stage(old.stage_id)
    wanted = body.model_dump(exclude_none=True) if body is not None else {}
    if wanted:
        try:
            room.change(wanted, catalogue=catalogue, host=host)
        except RoomError as exc:
            rooms.close(room.room_id)
            raise room_error(exc) from None
        except Exception:  # the scene worker busy or restarting (503): no half-made room stays open either
            rooms.close(room.room_id)
            raise
    return {"room_id": room.room_id, "code": room.code, "join_url": room.join_url, "state": room.state()}


@router.delete(
    "/rooms/{room_id}",
    response_model=RoomClosed,
    dependencies=[Instructor],
    responses={**_FORBIDDEN, **error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id")},
)
def close_room(room: RoomDep, rooms: RoomsDep, host: SceneHostDep, hub: RoomHubDep) -> dict[str, str]:
    """Close the room (instructor only): its scene stops and every page in it is told."""
    rooms.close(room.room_id, room=room)
    if room.scene_id is not None:
        host.close_stage(room.stage_id)
    hub.publish(room.room_id, {"type": "closed"})
    return {"closed": room.room_id}


@router.post(
    "/rooms/join",
    response_model=JoinAnswer,
    responses={
        **error_responses(not_found="No open room has this code", unprocessable="A name too long, or the room is full"),
        403: {"model": ErrorDetail, "description": "The instructor removed this device from the room"},
        429: {
            "model": ErrorDetail,
            "description": (
                "Too many joins from this address, or into this room just now; Retry-After says when to try again"
            ),
        },
    },
)
def join_room(
    body: JoinRequest, request: Request, response: Response, rooms: RoomsDep, limits: JoinLimitsDep, hub: RoomHubDep
) -> dict[str, Any]:
    """A student joins by the room's code: the answer's token identifies them (keep it; a reconnect reuses it).

    The device cookie this sets makes a device that joins again the same student, with the same token."""
    limits.check_address(request.scope)
    try:
        room = rooms.by_code(body.code, open_here=False)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    device = request.cookies.get(DEVICE_COOKIE, "")
    if not DEVICE_PATTERN.match(device):
        device = secrets.token_urlsafe(18)
    if room.student_of_device(device) is None:
        limits.check_new_student(room.room_id)
    try:
        student = room.join(body.name, device=device)
    except StudentRemoved as exc:
        raise HTTPException(status_code=403, detail=str(exc)) from None
    except RoomError as exc:
        raise room_error(exc) from None
    response.set_cookie(
        DEVICE_COOKIE,
        device,
        max_age=DEVICE_COOKIE_MAX_AGE_S,
        path=DEVICE_COOKIE_PATH,
        httponly=True,
        samesite="strict",
    )
    hub.publish_state(room, presence_only=True)  # the joined count, and the instructor's list, at the next pump
    return {
        "room_id": room.room_id,
        "student_token": student.token,
        "student_id": student.student_id,
        "state": room.state(),
    }


@router.get(
    "/rooms/{room_id}/students",
    response_model=StudentList,
    dependencies=[Instructor],
    responses={**_FORBIDDEN, **error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id")},
)
def list_students(room: RoomDep) -> dict[str, Any]:
    """Every student in the room, in the order they joined (instructor only): public id, name, connected, following."""
    return {"students": room.student_list()}


@router.delete(
    "/rooms/{room_id}/students/{student_id}",
    response_model=StudentRemovedAnswer,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(not_found="No such room or student", unprocessable="A malformed room or student id"),
    },
)
def remove_student(room: RoomDep, student_id: StudentId, hub: RoomHubDep) -> dict[str, str]:
    """Remove a student (instructor only): their page is told and its socket closed, their token no longer answers,
    their answers leave every poll's results, and their device cannot join this room again."""
    try:
        student = room.remove(student_id)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    hub.dismiss_student(room, student.student_id, REMOVED_MESSAGE)
    hub.publish_state(room)
    hub.publish_students(room)
    poll = room.polls.get(room.poll_id) if room.poll_id else None
    if poll is not None:
        hub.publish_results(room, poll)
    return {"removed": student.student_id}


@router.get(
    "/rooms/{room_id}/state",
    response_model=RoomState,
    responses=error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id"),
)
def room_state(room: RoomDep, request: Request) -> dict[str, Any]:
    """What the room shows now: lesson, scene, parameters, play state, time scale, mode, students, the current poll,
    and how many 3D viewers follow its scene."""
    return {**room.state(), "followers": follower_count(request.app, room.room_id)}


@router.post(
    "/rooms/{room_id}/state",
    response_model=RoomState,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(not_found=_NO_ROOM, unprocessable="A field is bad (named in loc); nothing changed"),
        409: {
            "model": ErrorDetail,
            "description": "if_lesson_id or if_scene_id no longer what the room shows (a stale page); nothing changed",
        },
    },
)
def change_room_state(
    room: RoomDep, body: RoomStateChange, catalogue: CatalogueDep, host: SceneHostDep, hub: RoomHubDep
) -> dict[str, Any]:
    """Change what every follower sees (instructor only): lesson, scene, parameters or preset, play/pause,
    reset, time scale, follow or explore. A page sends the lesson and scene it shows as ``if_lesson_id`` and
    ``if_scene_id``: once the room has moved on, its change is refused (409) instead of reaching another scene."""
    try:
        return change_room(room, body.model_dump(exclude_unset=True), catalogue=catalogue, host=host, hub=hub)
    except RoomError as exc:
        raise room_error(exc) from None


@router.get("/rooms/{room_id}/qr.svg", include_in_schema=False)  # an image, not JSON
def room_qr(room: RoomDep) -> Response:
    """The room's join address as a QR code (SVG), for the projector."""
    return Response(qr_svg(room.join_url), media_type="image/svg+xml", headers={"Cache-Control": "no-store"})


# ---- polls -------------------------------------------------------------------------------------------
@router.get(
    "/rooms/{room_id}/polls/ready",
    response_model=list[ReadyQuestionSchema],
    dependencies=[Instructor],
    responses={**_FORBIDDEN, **error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id")},
)
def ready_polls(room: RoomDep, ready: ReadyQuestionsDep, catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """Ready questions for the room's scene first, then the rest of its chapter (instructor only).

    The chapter is the scene's own, so a scene with no question of its own (the gyrocompass) still offers its
    chapter's; a room on no scene gets every question."""
    scene = catalogue.scenes.get(room.scene_id) if room.scene_id is not None else None
    if scene is None:
        return [q.schema() for q in ready]
    ours = [q for q in ready if q.scene_id == room.scene_id]
    same_chapter = [q for q in ready if q.chapter == scene.chapter and q.scene_id != room.scene_id]
    return [q.schema() for q in (*ours, *same_chapter)]


@router.post(
    "/rooms/{room_id}/polls",
    response_model=PollPublic,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(not_found=_NO_ROOM, unprocessable="A field of the question is bad; no poll was opened"),
    },
)
def open_poll(
    room: RoomDep,
    body: PollRequest,
    ready: ReadyQuestionsDep,
    catalogue: CatalogueDep,
    host: SceneHostDep,
    hub: RoomHubDep,
) -> dict[str, Any]:
    """Ask the room a question (instructor only): it becomes the current poll, closing any open one."""
    return start_poll(room, body.model_dump(exclude_none=True), ready=ready, catalogue=catalogue, host=host, hub=hub)


def start_poll(
    room: Room, raw: dict[str, Any], *, ready: tuple[ReadyQuestion, ...], catalogue: Any, host: Any, hub: RoomHub
) -> dict[str, Any]:
    """Open a poll from a request body (a ready question first sets the room's scene as the question needs it).

    The whole poll (a ready question with the instructor's fields over it) is checked before the room moves to the
    question's scene: a 422 leaves the class where it was."""
    ready_id = raw.pop("ready_id", None)
    question = None
    if ready_id is not None:
        question = next((q for q in ready if q.id == ready_id), None)
        if question is None:
            raise unprocessable(["body", "ready_id"], f"ready_id: no ready question {ready_id!r}")
        raw = question.poll_body() | raw
    try:
        Poll.create(raw, poll_id="p0")  # a check only: the room numbers the poll it opens
    except PollError as exc:
        raise unprocessable(["body", exc.field], str(exc)) from None
    with room.turn(), room.lock:  # the poll opens on the scene its question moved the room to, not one changed since
        if question is not None and (room.scene_id != question.scene_id or question.params or question.preset):
            lesson = next((l for l in catalogue.lessons.values() if question.scene_id in l.scenes), None)
            # The question's whole setting (defaults, its preset, its params): what its wording assumes.
            change: dict[str, Any] = {"params": question.scene_params(host.scenes[question.scene_id])}
            if lesson is not None and room.scene_id != question.scene_id:
                change |= {"lesson_id": lesson.id, "scene_id": question.scene_id}
            try:
                change_room(room, change, catalogue=catalogue, host=host, hub=hub)
            except RoomError as exc:
                raise room_error(exc) from None
        poll = room.open_poll(raw)  # checked above: it cannot be refused now
    hub.publish_poll(room, poll)
    return poll.public()


@router.post(
    "/rooms/{room_id}/polls/{poll_id}",
    response_model=PollResults,
    response_model_exclude_none=True,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(
            not_found="No such room or poll",
            unprocessable="The answer cannot be computed now (the scene has no such quantity)",
        ),
        409: {
            "model": ErrorDetail,
            "description": "open for a poll that is not the room's current one any more; nothing changed",
        },
    },
)
def update_poll(
    room: RoomDep, poll_id: PollId, body: PollUpdate, host: SceneHostDep, hub: RoomHubDep
) -> dict[str, Any]:
    """Close or reopen the current poll, reveal the answer the scene computes, or show names (instructor only)."""
    try:
        poll = room.update_poll(poll_id, body.model_dump(exclude_none=True), host=host)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    except NotCurrentPoll as exc:
        raise HTTPException(status_code=409, detail=exc.message) from None
    except (RoomError, PollError) as exc:
        raise unprocessable(["body", getattr(exc, "field", "reveal")], str(exc)) from None
    hub.publish_poll(room, poll)
    return poll.results()


@router.post(
    "/rooms/{room_id}/polls/{poll_id}/answers",
    response_model=AnswerAccepted,
    responses={
        **error_responses(
            not_found="No such room or poll",
            unprocessable="The answer does not fit the poll (a choice out of range, a number not finite)",
        ),
        403: {"model": ErrorDetail, "description": "No X-Student-Token from this room"},
        409: {"model": ErrorDetail, "description": "The poll is closed"},
    },
)
def answer_poll(
    room: RoomDep, poll_id: PollId, body: AnswerRequest, hub: RoomHubDep, student_token: StudentToken = None
) -> dict[str, Any]:
    """A student's answer: one per student, which they may change until the poll closes."""
    try:
        room.answer(poll_id, student_token, body.model_dump(exclude_none=True))
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    except PermissionError as exc:
        raise HTTPException(status_code=403, detail=str(exc)) from None
    except PollClosedError as exc:
        raise HTTPException(status_code=409, detail=str(exc)) from None
    except PollError as exc:
        raise unprocessable(["body", exc.field], str(exc)) from None
    poll = room.poll(poll_id)
    hub.publish_results(room, poll)
    hub.publish_state(room, presence_only=True)
    return {"accepted": True, "poll": poll.public()}


@router.get(
    "/rooms/{room_id}/polls/{poll_id}/results",
    response_model=PollResults,
    response_model_exclude_none=True,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(not_found="No such room or poll", unprocessable="A malformed room or poll id"),
    },
)
def poll_results(room: RoomDep, poll_id: PollId) -> dict[str, Any]:
    """Counts per choice or per bin (instructor only); names only if the instructor turned them on."""
    try:
        return room.poll(poll_id).results()
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None


@router.get(
    "/rooms/{room_id}/polls/{poll_id}/results.csv", dependencies=[Instructor], include_in_schema=False
)  # CSV, not JSON
def poll_results_csv(room: RoomDep, poll_id: PollId) -> PlainTextResponse:
    """Every answer as CSV (instructor only): anonymous unless names are on."""
    try:
        poll = room.poll(poll_id)
    except KeyError as exc:
        raise HTTPException(status_code=404, detail=str(exc.args[0])) from None
    filename = f"room-{room.code}-{poll_id}.csv"
    return PlainTextResponse(
        poll.to_csv(), media_type="text/csv", headers={"Content-Disposition": f'attachment; filename="{filename}"'}
    )


# ---- the room socket ---------------------------------------------------------------------------------
#: Largest message a page may send on the room socket (characters); the largest real one is a few hundred.
MAX_SOCKET_MESSAGE = 16_384
#: Socket actions only the instructor may take, and the request body each carries.
INSTRUCTOR_ACTIONS: dict[str, type[BaseModel]] = {
    "set_state": RoomStateChange,
    "open_poll": PollRequest,
    "update_poll": PollUpdate,
}


@router.websocket("/rooms/{room_id}/socket")
async def room_socket(websocket: WebSocket, room_id: str) -> None:
    """Every change to the room as it happens, the room's readout twice a second; students say hello and whether
    they follow; the instructor may send the actions of the instructor-only routes (a student's are refused, 403)."""
    app = websocket.app
    try:  # off the event loop: a room not open here is looked up in the database
        room = await run_in_threadpool(app.state.rooms.get, room_id)
    except KeyError:
        await websocket.close(code=1008, reason="no open room has this id")
        return
    except StoreUnavailable:
        await websocket.close(code=1013, reason="the server could not read its rooms just now: try again")
        return
    hub: RoomHub = app.state.room_hub
    await websocket.accept()
    member = hub.join(room, websocket, instructor=is_instructor(websocket))
    try:
        while True:
            text = await websocket.receive_text()
            if len(text) > MAX_SOCKET_MESSAGE:
                hub.reply(
                    member,
                    {
                        "type": "error",
                        "status": 413,
                        "detail": f"a room message is at most {MAX_SOCKET_MESSAGE} characters",
                    },
                )
                continue
            try:
                message = json.loads(text)
            except ValueError:
                message = None
            if not isinstance(message, dict) or not isinstance(message.get("type"), str):
                hub.reply(
                    member, {"type": "error", "status": 400, "detail": 'a room message is a JSON object with a "type"'}
                )
                continue
            await _socket_message(websocket, room, member, message, hub)
    except (WebSocketDisconnect, RuntimeError):
        pass
    finally:
        await hub.leave(room, member)


async def _socket_message(websocket: WebSocket, room: Room, member: Any, message: dict[str, Any], hub: RoomHub) -> None:
    kind = message.pop("type")
    if kind == "hello":
        token = message.get("student_token")
        try:  # off the event loop: a token this server has not seen is looked for in the database's newest version
            student = await run_in_threadpool(room.student, token) if isinstance(token, str) else None
        except StoreUnavailable:
            hub.reply(
                member, {"type": "error", "status": 503, "detail": "the server could not read the room: reconnect"}
            )
            return
        except StudentRemoved as exc:
            hub.dismiss(
                member,
                {"type": "removed", "detail": f"{str(exc)[0].upper()}{str(exc)[1:]}."},
                reason="removed from the room by the instructor",
            )
            return
        if token is not None and student is None:
            hub.reply(
                member,
                {
                    "type": "error",
                    "status": 403,
                    "detail": "this student token is not from this room: join again with the code",
                },
            )
            return
        if student is not None and member.student_token is None:
            with room.lock:
                # The room's own record of the student now (another server's version taken up meanwhile replaces it).
                student = room.students.get(student.student_id, student)
                member.student_token = token
                member.student_id = student.student_id
                student.sockets += 1
                student.following = message.get("following") is not False
        hub.presence_changed(room)
    elif kind == "following":
        with contextlib.suppress(StudentRemoved, StoreUnavailable):  # removed meanwhile: the socket is closing
            student = await run_in_threadpool(room.student, member.student_token)
            if student is not None and isinstance(message.get("value"), bool):
                student.following = message["value"]
                hub.presence_changed(room)
    elif kind in INSTRUCTOR_ACTIONS:
        if not member.instructor:
            hub.reply(
                member,
                {
                    "type": "error",
                    "status": 403,
                    "action": kind,
                    "detail": f"{kind}: only the instructor can change the room; nothing changed",
                },
            )
            return
        try:
            await run_in_threadpool(_instructor_action, websocket, room, kind, message)
        except ValidationError as exc:
            first = exc.errors()[0]
            hub.reply(
                member,
                {
                    "type": "error",
                    "status": 422,
                    "action": kind,
                    "detail": f"{'.'.join(map(str, first['loc']))}: {first['msg']}",
                },
            )
        except HTTPException as exc:
            detail = exc.detail[0]["msg"] if isinstance(exc.detail, list) else exc.detail
            hub.reply(member, {"type": "error", "status": exc.status_code, "action": kind, "detail": detail})
        except HostBusy as exc:  # the room's scene worker is busy or restarting: the instructor's socket stays open
            detail = f"{kind}: the room's scene is busy or restarting; try again in {exc.retry_after_s} s"
            hub.reply(
                member,
                {
                    "type": "error",
                    "status": exc.status,
                    "action": kind,
                    "retry_after_s": exc.retry_after_s,
                    "detail": detail,
                },
            )
    elif kind == "ping":
        hub.reply(member, {"type": "pong"})
    else:
        hub.reply(member, {"type": "error", "status": 400, "detail": f"unknown room message type {kind!r}"})


def _instructor_action(websocket: WebSocket, room: Room, kind: str, message: dict[str, Any]) -> None:
    """The same work as the instructor-only route of that name (run in a thread: it may call a scene worker)."""
    state = websocket.app.state
    body = INSTRUCTOR_ACTIONS[kind].model_validate(
        message if kind != "update_poll" else {k: v for k, v in message.items() if k != "poll_id"}
    )
    host, hub, catalogue = state.scene_host, state.room_hub, state.catalogue
    if kind == "set_state":
        try:
            change_room(room, body.model_dump(exclude_unset=True), catalogue=catalogue, host=host, hub=hub)
        except RoomError as exc:
            raise room_error(exc) from None
    elif kind == "open_poll":
        start_poll(
            room,
            body.model_dump(exclude_none=True),
            ready=state.ready_questions,
            catalogue=catalogue,
            host=host,
            hub=hub,
        )
    else:
        poll_id = message.get("poll_id")
        if not isinstance(poll_id, str):
            raise unprocessable(["poll_id"], "update_poll needs the poll_id")
        update_poll(room, poll_id, cast(PollUpdate, body), host, hub)  # the update_poll action validates a PollUpdate
