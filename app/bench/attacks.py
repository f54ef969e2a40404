"""The attacking client of ``dynlab load --attack``: one device that tries, at once, everything a hostile student
with a script could do to a class (items 2–6 of "Found" in the class-safety issue), and records what it got.

Each attack is its own coroutine, bounded in count (:class:`AttackBounds`) and cut off when the window ends:

- item 2, **the room's shared scene**: ``PUT …/sessions/room-<room_id>/playback`` with ``playing``, ``time_scale``,
  ``seek_s``, ``go_to_s`` (600 s), ``reset`` and ``camera``, each again and again, without any credential;
- item 3, **a session re-scened through the viewer socket**: ``/viewer/<other scene>/<a student's session id>``
  and viser's first camera message, one student after another (the attacker knows every student's id: the worst
  case);
- item 4, **floods**: session claims (``PUT`` of new ids, each with its own key) as fast as the server answers,
  with a change of a student's session under the attacker's key every few seconds meanwhile (it should be refused:
  403);
  and anonymous ``GET``s of random session ids (``…/playback`` and ``…/live``);
- item 5, **bursts**: 40 concurrent ``GET …/playback`` and, beside them, 40 concurrent ``GET …/recording.html``,
  of the attacker's own session, repeatedly;
- item 6, **expensive requests**: on its own double-pendulum sessions (rk4, 4096 steps per frame, or the most the
  server allows), ``{"go_to_s": 600}`` again and again on one and ``{"step": 300}`` on another; up to 200 viewers
  of its own heavy-top session from its one address; two typed-Lagrangian derivations at once, each a slow one
  (a new expression each time, so no cache answers), again and again.

The attacker honours nothing (no ``Retry-After``) and never stops on a refusal, a closed socket or a timeout: each
is an answer it records (:class:`AttackRecord`: counts per status or close code, an example message per refusal,
latencies). It keeps to one or two connections per attack (about fifteen in all), except the 40-request bursts and the
held viewers.

It runs as its own process (``python -m app.bench.attacks``: it says ``ready`` once loaded, a JSON plan on stdin
starts the window, the records come back as one JSON line), connecting from its own loopback address
(:data:`~app.bench.load_client.ATTACKER_ADDRESS`), so it is one device to the server and its work does not run in
the event loop that counts the students' frames.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import json
import math
import secrets
import sys
import time
from collections import Counter
from collections.abc import Awaitable, Callable
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

from app.bench.load_client import (
    ATTACKER_ADDRESS,
    SESSION_KEY_HEADER,
    HttpAnswer,
    ViewerClient,
    http_request,
    new_session_id,
    new_session_key,
)

#: Seconds a viewer the attacker opens may take to stream its first frame before it counts as "open, no frame".
FIRST_FRAME_S = 2.0
#: The answer of a request or viewer the window's end cut off.
WINDOW_ENDED = "no answer by the window's end"
#: Seconds after the window's end the attacker may take to close its sockets and report.
WIND_DOWN_S = 15.0
#: The double pendulum's expensive settings: rk4 with this many steps per frame, else the most the server allows.
DOUBLE_PENDULUM_STEPS = (4096, 1024, 256, 64)
#: A kinetic energy whose derivation sympy does not finish in 20 s (q1d² + q2d² + q3d² times powers of periodic
#: terms of the coordinates' products); ``{n}`` makes each request's text new, so no cache answers it.
SLOW_KINETIC_ENERGY = "(q1d^2+q2d^2+q3d^2)*({n}+sin(q1*q2+q3))^3*(3+cos(q2*q3+q1))^2"
SLOW_POTENTIAL_ENERGY = "sin(q1)*cos(q2)*sin(q3)"
#: Item 2's changes of the room's shared scene, each its own loop and record.
ROOM_CHANGES: tuple[tuple[str, dict], ...] = (
    ("playing", {"playing": False}),
    ("time_scale", {"time_scale": 0.1}),
    ("seek_s", {"seek_s": 0.0}),
    ("go_to_s", {"go_to_s": 600.0}),
    ("reset", {"reset": True}),
    ("camera", {"camera": {"position": [0.0, -0.4, 9.0], "look_at": [0.0, 0.0, 0.0]}}),
)


@dataclass(frozen=True)
class AttackBounds:
    """The most each attack tries in one window (every loop also stops when the window ends). The floods (claims,
    anonymous GETs, viewers) go as fast as the server answers; every other attack spreads its tries evenly over the
    window, so it keeps the pressure on however fast it is answered (or refused)."""

    #: Item 2: tries of each of the six room changes.
    room_rounds: int = 100
    #: Item 3: students' sessions re-scened, one after another.
    rescenes: int = 200
    #: Item 4: new sessions claimed, over ``claim_connections`` connections at a time.
    claims: int = 2100
    claim_connections: int = 2
    #: Item 4: tries at changing a student's session under the attacker's key.
    takeovers: int = 15
    #: Item 4: anonymous GETs of random session ids, over ``get_connections`` connections at a time.
    anonymous_gets: int = 2100
    get_connections: int = 2
    #: Item 5: concurrent requests in one burst, and bursts of each kind.
    burst: int = 40
    bursts: int = 10
    #: Item 6: long seeks, single steps of 300 frames, held viewers, and derivations by each of the two derivers.
    seeks: int = 20
    steps: int = 500
    viewers: int = 200
    derivations: int = 20
    #: Viewers opened at once while flooding.
    viewers_at_once: int = 20
    #: Seconds one ordinary request may take (a long seek or a derivation may take until the window ends).
    request_timeout_s: float = 10.0

    def __post_init__(self) -> None:
        for item in fields(self):
            value = getattr(self, item.name)
            if item.name == "request_timeout_s":
                if not (isinstance(value, (int, float)) and math.isfinite(value) and 0.1 <= value <= 120.0):
                    raise ValueError(f"attack_bounds: request_timeout_s must be in [0.1, 120] s, got {value!r}")
            elif not (isinstance(value, int) and 1 <= value <= 10_000):
                raise ValueError(f"attack_bounds: {item.name} must be a whole number in 1..10000, got {value!r}")
        if self.burst > 100 or self.viewers > 500:
            raise ValueError("attack_bounds: at most 100 requests in a burst and 500 held viewers")


#: A smaller attack of every kind, for a quick check of the tool (each attack still runs).
QUICK_BOUNDS = AttackBounds(
    room_rounds=3,
    rescenes=3,
    claims=40,
    takeovers=3,
    anonymous_gets=40,
    burst=40,
    bursts=1,
    seeks=2,
    steps=10,
    viewers=10,
    derivations=1,
    request_timeout_s=5.0,
)


@dataclass
class AttackRecord:
    """What one attack got: counts per answer (an HTTP status, ``HTTP 403`` for a refused websocket, ``close 1008``,
    ``streamed``, ``timeout``, …), the first message seen per answer, and the time to each answer (ms)."""

    item: int
    name: str
    request: str
    answers: Counter = field(default_factory=Counter)
    examples: dict[str, str] = field(default_factory=dict)
    latencies_ms: list[float] = field(default_factory=list)

    def add(self, answer: str, elapsed_ms: float, detail: str = "") -> None:
        self.answers[answer] += 1
        self.latencies_ms.append(elapsed_ms)
        if detail and answer not in self.examples:
            self.examples[answer] = detail[:200]

    def add_http(self, answer: HttpAnswer, *, prefix: str = "") -> None:
        self.add(prefix + answer.label, answer.elapsed_ms, answer.detail())

    def summary(self) -> dict:
        values = np.asarray(self.latencies_ms, dtype=float)
        pick = lambda q: round(float(np.percentile(values, q)), 1) if values.size else None  # noqa: E731
        return {
            "item": self.item,
            "name": self.name,
            "request": self.request,
            "count": int(sum(self.answers.values())),
            "answers": dict(sorted(self.answers.items(), key=lambda kv: (-kv[1], kv[0]))),
            "examples": self.examples,
            "latency_ms": {
                "median": pick(50),
                "p95": pick(95),
                "max": round(float(values.max()), 1) if values.size else None,
            },
        }


@dataclass(frozen=True)
class AttackPlan:
    """Whom the attacker attacks: the server, the room, the students' session ids, the scenes; for how long."""

    host: str
    port: int
    scene_id: str
    room_id: str
    victims: tuple[str, ...]
    seconds: float
    bounds: AttackBounds = AttackBounds()
    #: The scene item 3 re-scenes a student's session to.
    other_scene_id: str = "four-bar"
    address: str = ATTACKER_ADDRESS

    def to_json(self) -> str:
        return json.dumps({**asdict(self), "victims": list(self.victims)})

    @classmethod
    def from_json(cls, text: str) -> AttackPlan:
        raw = json.loads(text)
        return cls(**{**raw, "victims": tuple(raw["victims"]), "bounds": AttackBounds(**raw["bounds"])})


class Attacker:
    """Runs every attack of a plan at once for ``plan.seconds``; :meth:`run` returns the records' summaries."""

    def __init__(self, plan: AttackPlan) -> None:
        from app.scenes.viser_boundary import viewer_camera_message  # registers every scene: only a run needs it

        self.plan = plan
        self.bounds = plan.bounds
        self.camera_message = viewer_camera_message()
        self.records: dict[str, AttackRecord] = {}
        self.deadline = math.inf
        self._stop = asyncio.Event()
        self._held: list[asyncio.Task] = []
        #: Keys of the attacker's own sessions, by session id.
        self._keys: dict[str, str] = {}
        #: Students' session ids some attack named (re-scened, or changed under the attacker's key).
        self.victims_named: set[str] = set()

    # ---- the pieces every attack uses ------------------------------------------------------------

    def record(self, item: int, name: str, request: str) -> AttackRecord:
        if name not in self.records:
            self.records[name] = AttackRecord(item, name, request)
        return self.records[name]

    def remaining_s(self) -> float:
        return self.deadline - time.monotonic()

    async def request(
        self, method: str, path: str, *, body: dict | None = None, key: str | None = None, long: bool = False
    ) -> HttpAnswer | None:
        """One request from the attacker's address, cut off at the request timeout (``long``: at the window's end);
        None if the window has ended."""
        limit = self.remaining_s() if long else min(self.bounds.request_timeout_s, self.remaining_s())
        if limit <= 0:
            return None
        answer = await http_request(
            self.plan.host,
            self.plan.port,
            method,
            path,
            body=body,
            headers={SESSION_KEY_HEADER: key} if key else None,
            source_address=self.plan.address,
            timeout_s=limit,
        )
        if answer.failure == "timeout" and (long or limit < self.bounds.request_timeout_s):
            return replace(answer, failure=WINDOW_ENDED)  # cut off by the window, not by the request timeout
        return answer

    async def recorded(self, record: AttackRecord, method: str, path: str, **request: Any) -> bool:
        """:meth:`request`, its answer added to ``record``; False (nothing added) once the window has ended."""
        answer = await self.request(method, path, **request)
        if answer is None:
            return False
        record.add_http(answer)
        return True

    async def open_viewer(self, path: str, *, hold: bool) -> tuple[str, float, ViewerClient, asyncio.Task]:
        """Open a viewer websocket at ``path`` from the attacker's address and send the camera message; wait for its
        first frame (at most :data:`FIRST_FRAME_S`). Returns (what it got, ms, the client, its task); the viewer
        stays open until the window ends if ``hold``, else it is closed now."""
        started = time.perf_counter()
        stop = self._stop if hold else asyncio.Event()
        client = ViewerClient(self.plan.scene_id, path=path, source_address=self.plan.address)
        task = asyncio.create_task(client.run(self.plan.host, self.plan.port, stop, self.camera_message))
        first_frame_by = time.monotonic() + FIRST_FRAME_S
        while not task.done() and client.frames == 0 and self.remaining_s() > 0:
            if client.connected and time.monotonic() > first_frame_by:
                break
            await asyncio.sleep(0.02)
        elapsed_ms = 1e3 * (time.perf_counter() - started)
        if client.frames:
            answer = "streamed"
        elif client.outcome:
            answer = client.outcome
        elif client.connected:
            answer = "open, no frame"
        else:
            answer = WINDOW_ENDED
        if hold:
            self._held.append(task)
        else:
            stop.set()
            _, still = await asyncio.wait({task}, timeout=6.0)
            for pending in still:  # still connecting: stop applies to an open socket only
                pending.cancel()
        return answer, elapsed_ms, client, task

    async def claim(self, scene_id: str, params: dict, record: AttackRecord, *, prefix: str = "") -> tuple[str, str]:
        """A session of the attacker's own, claimed with its own key: (session id, key)."""
        session_id, key = new_session_id(), new_session_key()
        answer = await self.request(
            "PUT", f"/api/scenes/{scene_id}/sessions/{session_id}", body={"params": params}, key=key
        )
        if answer is not None:
            record.add_http(answer, prefix=prefix)
        return session_id, key

    async def until_window_ends(self, count: int, attempt: Callable[[int], Awaitable[bool]]) -> None:
        """``attempt(0)``, ``attempt(1)``, … up to ``count`` times, spread over the window (attempt ``i`` starts no
        earlier than ``i / count`` of the way through it, so the attack lasts the whole window however fast the server
        answers), until the window ends or an attempt returns False."""
        start = self.deadline - self.plan.seconds
        for index in range(count):
            wait_s = start + index * self.plan.seconds / count - time.monotonic()
            if wait_s > 0:
                await asyncio.sleep(min(wait_s, max(0.0, self.remaining_s())))
            if self.remaining_s() <= 0 or not await attempt(index):
                return

    # ---- item 2: the room's shared scene, without credentials --------------------------------------------------

    async def room_change(self, name: str, body: dict) -> None:
        """One of item 2's changes of the room's shared scene, again and again (each change its own loop, so one
        that hangs does not keep the others from being tried)."""
        path = f"/api/scenes/{self.plan.scene_id}/sessions/room-{self.plan.room_id}/playback"
        record = self.record(
            2,
            f"room scene: {name}",
            f"PUT /api/scenes/{self.plan.scene_id}/sessions/room-<room>/playback {json.dumps(body)}, no credential",
        )

        async def change(_: int) -> bool:
            return await self.recorded(record, "PUT", path, body=body)

        await self.until_window_ends(self.bounds.room_rounds, change)

    # ---- item 3: a student's session re-scened through the viewer socket ---------------------------------------

    async def viewer_rescene(self) -> None:
        other = self.plan.other_scene_id
        record = self.record(
            3,
            "viewer re-scenes a student's session",
            f"websocket /viewer/{other}/<a student's session id>, then viser's first camera message",
        )
        victims = itertools.cycle(self.plan.victims) if self.plan.victims else iter(())

        async def visit(_: int) -> bool:
            victim = next(victims, None)
            if victim is None:
                return False
            self.victims_named.add(victim)
            answer, elapsed_ms, client, _task = await self.open_viewer(f"/viewer/{other}/{victim}", hold=False)
            record.add(answer, elapsed_ms, client.error or "")
            return True

        await self.until_window_ends(self.bounds.rescenes, visit)

    # ---- item 4: floods of claims and of anonymous lookups ----------------------------------------------------

    async def claim_flood(self) -> None:
        """Claims as fast as the server answers and, beside them, a student's session changed under the attacker's
        key every so often (a flood that evicts the students' claims lets that through)."""
        scene = self.plan.scene_id
        claims = self.record(
            4, "claim flood", f'PUT /api/scenes/{scene}/sessions/<new id> {{"params": {{}}}} with a new key each'
        )
        takeover = self.record(
            4,
            "a student's session under the attacker's key, during the flood",
            f'PUT /api/scenes/{scene}/sessions/<a student\'s session id>/playback {{"playing": false}} '
            "with the attacker's key, every few seconds while the claims go on",
        )
        counter = itertools.count()
        victims = itertools.cycle(self.plan.victims) if self.plan.victims else iter(())
        attacker_key = new_session_key()

        async def claimer() -> None:
            while self.remaining_s() > 0 and next(counter) < self.bounds.claims:
                if not await self.recorded(
                    claims,
                    "PUT",
                    f"/api/scenes/{scene}/sessions/{new_session_id()}",
                    body={"params": {}},
                    key=new_session_key(),
                ):
                    return

        async def take_over(_: int) -> bool:
            victim = next(victims, None)
            if victim is None:
                return False
            self.victims_named.add(victim)
            path = f"/api/scenes/{scene}/sessions/{victim}/playback"
            return await self.recorded(takeover, "PUT", path, body={"playing": False}, key=attacker_key)

        await asyncio.gather(
            *(claimer() for _ in range(self.bounds.claim_connections)),
            self.until_window_ends(self.bounds.takeovers, take_over),
        )

    async def anonymous_gets(self) -> None:
        scene = self.plan.scene_id
        record = self.record(
            4,
            "anonymous GETs of random session ids",
            f"GET /api/scenes/{scene}/sessions/<random id>/playback and …/live, alternately",
        )
        counter = itertools.count()

        async def getter() -> None:
            while self.remaining_s() > 0 and (index := next(counter)) < self.bounds.anonymous_gets:
                what = "playback" if index % 2 == 0 else "live"
                if not await self.recorded(record, "GET", f"/api/scenes/{scene}/sessions/{new_session_id()}/{what}"):
                    return

        await asyncio.gather(*(getter() for _ in range(self.bounds.get_connections)))

    # ---- item 5 and item 6's viewer flood: the attacker's own heavy-top session --------------------------------

    async def own_session_attacks(self) -> None:
        """Claim an own session of the scene with one held viewer (the attacker's page), then burst requests at it
        and flood it with viewers, both at once."""
        scene = self.plan.scene_id
        viewers = self.record(
            6,
            "viewer flood from one address",
            f"up to {self.bounds.viewers} websockets /viewer/{scene}/<own session>, held open",
        )
        session_id, _key = await self.claim(scene, {}, viewers, prefix="claim own session: ")
        await asyncio.gather(self.bursts(session_id), self.viewer_flood(session_id, viewers))

    async def bursts(self, session_id: str) -> None:
        """Item 5: bursts of concurrent GETs of the session's playback and, in a loop of their own, of its recording."""
        scene = self.plan.scene_id
        n = self.bounds.burst

        async def bursts_of(what: str) -> None:
            path = f"/api/scenes/{scene}/sessions/{session_id}/{what}"
            record = self.record(
                5, f"burst: concurrent GETs of {what}", f"{n} concurrent GET /api/scenes/{scene}/sessions/<own>/{what}"
            )

            async def burst(_: int) -> bool:
                answers = await asyncio.gather(*(self.request("GET", path) for _ in range(n)))
                for answer in answers:
                    if answer is not None:
                        record.add_http(answer)
                return all(answer is not None for answer in answers)

            await self.until_window_ends(self.bounds.bursts, burst)

        await asyncio.gather(bursts_of("playback"), bursts_of("recording.html"))

    async def viewer_flood(self, session_id: str, record: AttackRecord) -> None:
        path = f"/viewer/{self.plan.scene_id}/{session_id}"
        opened = 0
        while opened < self.bounds.viewers and self.remaining_s() > 0:
            wave = min(self.bounds.viewers_at_once, self.bounds.viewers - opened)
            results = await asyncio.gather(*(self.open_viewer(path, hold=True) for _ in range(wave)))
            for answer, elapsed_ms, client, _task in results:
                record.add(answer, elapsed_ms, client.error or "")
            opened += wave

    # ---- item 6: expensive requests on its own double-pendulum sessions, and slow derivations ----------------

    async def expensive_session(self, record: AttackRecord) -> str | None:
        """An own double-pendulum session on rk4 with the most steps per frame the server allows, with a viewer
        (held): its scene runs, so a seek or a step computes now. None if none could be made."""
        for steps in DOUBLE_PENDULUM_STEPS:
            session_id, key = new_session_id(), new_session_key()
            answer = await self.request(
                "PUT",
                f"/api/scenes/double-pendulum/sessions/{session_id}",
                body={"params": {"method": "rk4", "steps_per_frame": steps}},
                key=key,
            )
            if answer is None:
                return None
            record.add_http(answer, prefix=f"setup ({steps} steps/frame): ")
            if answer.status == 200:
                answer_text, elapsed_ms, client, _task = await self.open_viewer(
                    f"/viewer/double-pendulum/{session_id}", hold=True
                )
                record.add(f"setup viewer: {answer_text}", elapsed_ms, client.error or "")
                self._keys[session_id] = key
                return session_id
        return None

    async def expensive_playback(self, name: str, body: dict, *, count: int, long: bool) -> None:
        """``body`` sent to the playback of an expensive session of the attacker's own, again each time it is
        answered."""
        record = self.record(
            6,
            name,
            f"PUT /api/scenes/double-pendulum/sessions/<own>/playback {json.dumps(body)} "
            "(rk4, 4096 steps/frame), again when answered",
        )
        session_id = await self.expensive_session(record)
        if session_id is None:
            return

        async def ask(_: int) -> bool:
            path = f"/api/scenes/double-pendulum/sessions/{session_id}/playback"
            return await self.recorded(record, "PUT", path, body=body, key=self._keys[session_id], long=long)

        await self.until_window_ends(count, ask)

    async def derivations(self) -> None:
        record = self.record(
            6,
            "two slow typed-Lagrangian derivations at once",
            "POST /api/systems/custom/derive, three coordinates, a kinetic energy sympy cannot finish "
            "in 20 s (new text each time), two at once, repeatedly",
        )
        counter = itertools.count(2 + secrets.randbelow(10**6))  # a new constant per request: no cache answers

        async def derive(_: int) -> bool:
            body = {
                "coordinates": ["q1", "q2", "q3"],
                "kinetic_energy": SLOW_KINETIC_ENERGY.format(n=next(counter)),
                "potential_energy": SLOW_POTENTIAL_ENERGY,
                "parameters": {},
            }
            return await self.recorded(record, "POST", "/api/systems/custom/derive", body=body, long=True)

        await asyncio.gather(*(self.until_window_ends(self.bounds.derivations, derive) for _ in range(2)))

    # ---- the run ---------------------------------------------------------------------------------------------

    async def run(self) -> dict:
        """Every attack at once until the window ends; then close every socket. Returns the records' summaries,
        the students' session ids some attack named, and the attacker's own wall time."""
        started = time.monotonic()
        self.deadline = started + self.plan.seconds
        attacks = {
            **{f"room_{name}": self.room_change(name, body) for name, body in ROOM_CHANGES},
            "viewer_rescene": self.viewer_rescene(),
            "claim_flood": self.claim_flood(),
            "anonymous_gets": self.anonymous_gets(),
            "own_session_attacks": self.own_session_attacks(),
            "long_seeks": self.expensive_playback(
                "long seek on an expensive session", {"go_to_s": 600.0}, count=self.bounds.seeks, long=True
            ),
            "repeated_steps": self.expensive_playback(
                "repeated steps of 300 frames", {"step": 300}, count=self.bounds.steps, long=False
            ),
            "derivations": self.derivations(),
        }
        tasks = {asyncio.create_task(coro): name for name, coro in attacks.items()}
        done, pending = await asyncio.wait(tasks, timeout=self.plan.seconds + WIND_DOWN_S / 3)
        for task in pending:  # only a bug keeps an attack past the window: each request is cut off at its end
            task.cancel()
        await asyncio.gather(*pending, return_exceptions=True)
        failures = {}
        for task in done:
            if not task.cancelled() and task.exception() is not None:
                failures[tasks[task]] = f"{type(task.exception()).__name__}: {task.exception()}"
        for task in pending:
            failures[tasks[task]] = "still running after the window: cancelled"
        self._stop.set()
        if self._held:
            _, still = await asyncio.wait(self._held, timeout=WIND_DOWN_S / 2)
            for task in still:
                task.cancel()
            await asyncio.gather(*still, return_exceptions=True)
        return {
            "attacks": [record.summary() for record in self.records.values()],
            "victims_named": sorted(self.victims_named),
            "failures": failures,
            "ran_s": round(time.monotonic() - started, 2),
        }


# ---- the attacker's own process -------------------------------------------------------------------------


def main() -> int:
    """``python -m app.bench.attacks``: load everything and say ``ready``; the next line on stdin is the plan (JSON),
    and it starts the window at once; the result comes back as one JSON line. End of input before a plan: exit."""
    from app.scenes.viser_boundary import viewer_camera_message  # noqa: F401  (the slow import, before "ready")

    print("ready", flush=True)
    line = sys.stdin.readline()
    if not line.strip():
        return 0
    result = asyncio.run(Attacker(AttackPlan.from_json(line)).run())
    print(json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    with contextlib.suppress(KeyboardInterrupt):
        sys.exit(main())
