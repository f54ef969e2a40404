"""The configuration every page hands its scripts: one JSON object in ``<script type="application/json"
id="dynlab-config">`` (read by ``static/js/config.js``), so a rule the server keeps is written once, here or where
this module imports it, and never again in a page script."""

from __future__ import annotations

import json
from typing import Any

from app.rooms.room import CODE_LENGTH
from app.scenes.host.host import TIME_SCALE_RANGE

#: The speeds (× real time) a page offers: the time controls' menu and the instructor's in a room.
TIME_SCALES = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0)
assert all(TIME_SCALE_RANGE[0] <= scale <= TIME_SCALE_RANGE[1] for scale in TIME_SCALES), "a scale the host refuses"

#: How a page's websocket to the app reconnects when it drops (``static/js/socket.js``): the first wait (ms), the
#: factor each further try multiplies it by, and the longest wait (ms); an open socket starts again at the first.
SOCKET_RECONNECT = {"initial_ms": 500, "factor": 2, "cap_ms": 10_000}


def page_config(**extra: Any) -> dict[str, Any]:
    """What every page's scripts are handed, plus ``extra`` (a lesson page's lesson: its id, scene, examples and
    derivations)."""
    return {
        "time_scales": list(TIME_SCALES),
        "socket_reconnect": SOCKET_RECONNECT,
        # The classroom's values (the room sockets' pages: lessons in a room, the projector, joining). To come from
        # app.classroom's classroom_page_config() once the classroom is one package.
        "classroom": {"room_code_length": CODE_LENGTH},
        **extra,
    }


def config_script(config: dict[str, Any]) -> str:
    """``config`` as the page's ``<script type="application/json" id="dynlab-config">``; every ``<`` is written
    ``\\u003c`` (the same JSON), so no text in it (``</script>``, ``<!--``) can end or change the script element."""
    text = json.dumps(config, ensure_ascii=False).replace("<", "\\u003c")
    return f'<script type="application/json" id="dynlab-config">{text}</script>'
