"""How fast students may join rooms: per client address, and per room.

Two token buckets (:class:`~app.api.rate_limit.TokenBuckets`), numbers in :class:`~app.settings.Settings`:

**Per address: 20 join requests at once, then one every 5 s** (``join_burst``, ``join_rate_per_s``). Every request
counts, a wrong code too. A real device joins once per QR scan or typed code: a student who re-scans, reloads and
mistypes the code a few times stays far below 20, and a handful of devices sharing one address (a small NAT) fit
in the burst. A script at one address, which made 498 students in 3.9 s, now makes 20, then 12 a minute: filling a
500-student room takes it 40 minutes, and guessing codes (31⁶ ≈ 9·10⁸ of them) 720 tries an hour. A whole class
behind one address (a reverse proxy without ``DYNLAB_TRUST_FORWARDED_FOR``) would queue: README says to set it.

**Per room: 150 new students at once, then 2 a second** (``room_join_burst``, ``room_join_rate_per_s``), whatever
their addresses; only a new student takes a token (a device joining again is the student it was, and takes no
seat). A class of 100, or 150, scanning the QR code together all get in at once; a lecture hall of 300 within
75 s (the join page waits and tries again by itself). A flood from many addresses (a script rotating them; one
IPv6 host has millions) takes 150 seats, then 2 a second: the room's 500 seats last minutes, not seconds, and the
instructor sees the count climb and can remove students.

A refused join is a 429 with ``Retry-After`` (whole seconds, at least 1).
"""

from __future__ import annotations

from fastapi import HTTPException
from starlette.types import Scope

from app.api.rate_limit import TokenBuckets, client_address, retry_after_s
from app.classroom.registry import MAX_ROOMS
from app.settings import Settings


class JoinLimits:
    """The two join limits of one server (thread-safe, as its buckets are)."""

    def __init__(self, settings: Settings) -> None:
        self.trust_forwarded_for = settings.trust_forwarded_for
        self.per_address = TokenBuckets(
            burst=settings.join_burst, rate_per_s=settings.join_rate_per_s, max_clients=settings.rate_limit_clients
        )
        # Rooms closed long ago are forgotten first; a few times the open rooms is plenty.
        self.per_room = TokenBuckets(
            burst=settings.room_join_burst, rate_per_s=settings.room_join_rate_per_s, max_clients=4 * MAX_ROOMS
        )

    def check_address(self, scope: Scope) -> None:
        """429 if this client's address has joined too often (a peer with no IP address is not limited)."""
        address = client_address(scope, trust_forwarded_for=self.trust_forwarded_for)
        if address is None:
            return
        wait_s = self.per_address.take(address)
        if wait_s > 0:
            raise too_many(wait_s, "too many tries to join from this device or network")

    def check_new_student(self, room_id: str) -> None:
        """429 if the room has let in too many new students just now."""
        wait_s = self.per_room.take(room_id)
        if wait_s > 0:
            raise too_many(wait_s, "many students are joining this room at once")


def too_many(wait_s: float, why: str) -> HTTPException:
    retry_after = retry_after_s(wait_s)
    return HTTPException(
        status_code=429, detail=f"{why}: try again in {retry_after} s", headers={"Retry-After": str(retry_after)}
    )
