"""The classroom's rules the page scripts need, as JSON-ready data: each rule is written once, here in Python.

:func:`classroom_page_config` is handed to the lesson, join and projector pages' scripts in their page
configuration, so a script reads the time scales it offers, how its room socket reconnects and the limits of what a
student or the instructor may type from here instead of writing them a second time.
"""

from __future__ import annotations

from typing import Any

from app.classroom.polls import CHOICES_RANGE, MAX_CHOICE_CHARS, MAX_QUESTION_CHARS, MAX_UNIT_CHARS
from app.classroom.room import CODE_LENGTH, MAX_NAME_LENGTH
from app.scenes.host.host import TIME_SCALE_RANGE

#: The speeds a page's time controls offer (× real time): from the slowest to the fastest of
#: :data:`~app.scenes.host.host.TIME_SCALE_RANGE`, with real time among them.
TIME_SCALES_OFFERED = (0.1, 0.25, 0.5, 1, 2, 4)
#: How a page reconnects its room socket when it drops (a phone that slept, a server restart): the first wait
#: (ms), multiplied by the factor after each failed try, never longer than the longest wait (ms).
RECONNECT_FIRST_WAIT_MS = 500
RECONNECT_FACTOR = 2
RECONNECT_LONGEST_WAIT_MS = 10_000
#: How often a page that only listens (the projector) pings its room socket (ms), so an idle proxy keeps it open.
SOCKET_PING_INTERVAL_MS = 20_000


def classroom_page_config() -> dict[str, Any]:
    """The classroom's rules for the page scripts (JSON-ready: numbers, lists and dicts only)."""
    return {
        "time_scale_range": list(TIME_SCALE_RANGE),
        "time_scales": list(TIME_SCALES_OFFERED),
        "room_socket": {
            "reconnect_first_wait_ms": RECONNECT_FIRST_WAIT_MS,
            "reconnect_factor": RECONNECT_FACTOR,
            "reconnect_longest_wait_ms": RECONNECT_LONGEST_WAIT_MS,
            "ping_interval_ms": SOCKET_PING_INTERVAL_MS,
        },
        "room_code_length": CODE_LENGTH,
        "student_name_max_chars": MAX_NAME_LENGTH,
        "poll": {
            "question_max_chars": MAX_QUESTION_CHARS,
            "choice_max_chars": MAX_CHOICE_CHARS,
            "choices_min": CHOICES_RANGE[0],
            "choices_max": CHOICES_RANGE[1],
            "unit_max_chars": MAX_UNIT_CHARS,
        },
    }
