"""How a run ended: the integer codes the kernels return, their names and the text a student reads.

Kernels return the integer codes (numba kernels cannot return strings); the
integrators translate them with :data:`STATUS_NAMES`; a failed run is explained
with :data:`FAILURE_TEXT`. This is the only place these are written.
"""

from __future__ import annotations

OK = 0
NON_FINITE = 1
EVENT = 2
STEP_TOO_SMALL = 3
TOO_MANY_STEPS = 4

#: Code → name used in results and the API (``stats.status``).
STATUS_NAMES: dict[int, str] = {
    OK: "ok",
    NON_FINITE: "non_finite",
    EVENT: "event",
    STEP_TOO_SMALL: "step_too_small",
    TOO_MANY_STEPS: "too_many_steps",
}

#: Statuses that end a run normally (the span was covered, or a terminal event stopped it).
SUCCESSFUL = ("ok", "event")

#: What a failure means, in words a student can act on.
FAILURE_TEXT: dict[str, str] = {
    "non_finite": "the solution stopped being finite (blew up)",
    "step_too_small": "the adaptive step fell below round-off",
    "too_many_steps": "the adaptive solver needed too many steps",
    "event": "a terminal event was reached",
}


def status_name(code: int) -> str:
    """The name of a kernel's status code (ValueError for a code no kernel returns)."""
    try:
        return STATUS_NAMES[int(code)]
    except KeyError:
        raise ValueError(f"unknown status code {code!r}; known: {sorted(STATUS_NAMES)}") from None
