"""The classroom's rules the page scripts need, as JSON-ready data: each rule is written once, here in Python.

:func:`classroom_page_config` is handed to the lesson, join and projector pages' scripts in their page
configuration (as ``config.classroom``, added by ``app.main``), so a script reads how often a listening page pings
its room socket and the limits of what a student or the instructor may type from here instead of writing them a
second time. The time scales a page offers and how every socket reconnects are the web layer's, for every page
(:mod:`app.web.page_config`).
"""

from __future__ import annotations

from typing import Any

from app.classroom.polls import CHOICES_RANGE, MAX_CHOICE_CHARS, MAX_QUESTION_CHARS, MAX_UNIT_CHARS
from app.classroom.room import CODE_LENGTH, MAX_NAME_LENGTH

#: How often a page that only listens (the projector) pings its room socket (ms), so an idle proxy keeps it open.
SOCKET_PING_INTERVAL_MS = 20_000


def classroom_page_config() -> dict[str, Any]:
    """The classroom's rules for the page scripts (JSON-ready: numbers, lists and dicts only)."""
    return {
        "socket_ping_interval_ms": SOCKET_PING_INTERVAL_MS,
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
