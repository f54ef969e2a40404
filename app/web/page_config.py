"""The configuration every page hands its scripts: one JSON object in ``<script type="application/json"
id="dynlab-config">`` (read by ``static/js/config.js``), so a rule the server keeps is written once, here or where
this module imports it, and never again in a page script."""

from __future__ import annotations

import json
from typing import Any

from app.scenes.host.host import TIME_SCALE_RANGE

#: The speeds (× real time) a page offers: the time controls' menu and the instructor's in a room.
TIME_SCALES = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0)
assert all(TIME_SCALE_RANGE[0] <= scale <= TIME_SCALE_RANGE[1] for scale in TIME_SCALES), "a scale the host refuses"

#: How a page's websocket to the app reconnects when it drops (``static/js/socket.js``): the first wait (ms), the
#: factor each further try multiplies it by, and the longest wait (ms); an open socket starts again at the first.
SOCKET_RECONNECT = {"initial_ms": 500, "factor": 2, "cap_ms": 10_000}


#: Sections that a feature above the web layer adds to every page's configuration, by name (the classroom's rules:
#: ``app.main`` adds ``"classroom"`` from :func:`app.classroom.page_config.classroom_page_config`), so this layer
#: hands them on without importing the feature.
_SECTIONS: dict[str, dict[str, Any]] = {}


def add_page_config_section(name: str, values: dict[str, Any]) -> None:
    """Hand ``values`` (JSON-ready) to every page's scripts as ``config[name]``; adding the same name again replaces
    it."""
    _SECTIONS[name] = values


def page_config(**extra: Any) -> dict[str, Any]:
    """What every page's scripts are handed, plus ``extra`` (a lesson page's lesson: its id, scene, examples and
    derivations)."""
    return {
        "time_scales": list(TIME_SCALES),
        "socket_reconnect": SOCKET_RECONNECT,
        **_SECTIONS,
        **extra,
    }


def config_script(config: dict[str, Any]) -> str:
    """``config`` as the page's ``<script type="application/json" id="dynlab-config">``; every ``<`` is written
    ``\\u003c`` (the same JSON), so no text in it (``</script>``, ``<!--``) can end or change the script element."""
    text = json.dumps(config, ensure_ascii=False).replace("<", "\\u003c")
    return f'<script type="application/json" id="dynlab-config">{text}</script>'
