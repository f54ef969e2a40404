"""The instructor's key never reaches a log.

The instructor link (``/instructor?key=<secret>``) is a GET, so uvicorn's access log would write the secret with
every line of it, and its websocket log the same for any socket opened with ``?key=``. :func:`install` wraps the
logging module's record factory, the one place every record of every logger (uvicorn's, the app's, a library's)
is made, before any filter, handler or formatter sees it: in the record's message, the value of every ``key=``
query parameter becomes ``…`` (a mistyped key is nearly the key), and the secret itself, wherever else it appears,
becomes ``…`` too. A record that carried either is left as its redacted text; uvicorn's access records keep their
five arguments (its formatter unpacks them by position), the path among them redacted.

``dynlab serve`` installs it; the link it prints on the console at start-up is the one intended copy.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Callable
from typing import Any
from urllib.parse import quote, quote_plus

REDACTED = "…"
ACCESS_LOGGER = "uvicorn.access"
#: The value of a ``key`` query parameter, up to the next parameter, space or quote.
KEY_PARAMETER = re.compile(r"(?<=[?&;]key=)[^&;\s\"']*", re.IGNORECASE)


class KeyRedaction:
    """Rewrites text so that it carries neither ``secret`` (as typed or URL-encoded) nor any ``key=`` value."""

    def __init__(self, secret: str) -> None:
        self.forms = sorted({secret, quote(secret, safe=""), quote_plus(secret)}, key=len, reverse=True)

    def text(self, text: str) -> str:
        text = KEY_PARAMETER.sub(REDACTED, text)
        for form in self.forms:
            text = text.replace(form, REDACTED)
        return text

    def value(self, value: Any) -> Any:
        return self.text(value) if isinstance(value, str) else value

    def record(self, record: logging.LogRecord) -> logging.LogRecord:
        """``record`` with its message and traceback redacted (in place); untouched when it carries no key."""
        try:
            message = record.getMessage()
        except Exception:  # arguments that do not fit the message: logging reports it when the record is emitted
            message = str(record.msg)
        redacted = self.text(message)
        if redacted != message:
            if record.name == ACCESS_LOGGER and isinstance(record.args, tuple):
                # uvicorn's access formatter unpacks the five arguments: redact the path among them.
                record.args = tuple(self.value(arg) for arg in record.args)
            else:
                record.msg, record.args = redacted, None
        if record.exc_info and not record.exc_text:
            # Formatted now, as every handler's formatter would (it reuses exc_text): an exception's message may quote a
            # URL.
            record.exc_text = logging.Formatter().formatException(record.exc_info)
        if record.exc_text:
            record.exc_text = self.text(record.exc_text)
        if record.stack_info:
            record.stack_info = self.text(record.stack_info)
        return record


def install(secret: str) -> KeyRedaction:
    """From now on, every log record of this process is made through :class:`KeyRedaction` of ``secret`` (a second
    call replaces the first one's, never stacks on it)."""
    redaction = KeyRedaction(secret)
    current = logging.getLogRecordFactory()
    make: Callable[..., logging.LogRecord] = getattr(current, "unredacted", current)

    def redacted_record(*args: Any, **kwargs: Any) -> logging.LogRecord:
        return redaction.record(make(*args, **kwargs))

    redacted_record.unredacted = make  # type: ignore[attr-defined]
    logging.setLogRecordFactory(redacted_record)
    return redaction
