"""The instructor key never reaches a log: every record of every logger is made without it (app/web/log_redaction.py).

The served app's own log is read in tests/api/test_class_integrity.py; here each way a record can carry the key is
tried on the logging module itself: uvicorn's access record (five positional arguments its formatter unpacks), a
message, a mapping of arguments, a URL-encoded key, a mistyped key, a traceback."""

from __future__ import annotations

import logging
from collections.abc import Iterator

import pytest
from uvicorn.logging import AccessFormatter

from app.web import log_redaction

SECRET = "chalk and/talk-2026"  # characters URL encoding changes


@pytest.fixture
def caught() -> Iterator[list[str]]:
    """Records of the logger 'redaction-test' as formatted text (uvicorn's access formatter for uvicorn.access)."""
    factory = logging.getLogRecordFactory()
    log_redaction.install(SECRET)
    lines: list[str] = []

    class Keep(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            lines.append(self.format(record))

    handler = Keep()
    access = Keep()
    access.setFormatter(AccessFormatter('%(client_addr)s - "%(request_line)s" %(status_code)s', use_colors=False))
    loggers = (logging.getLogger("redaction-test"), logging.getLogger("uvicorn.access"))
    for logger, h in zip(loggers, (handler, access), strict=True):
        logger.addHandler(h)
        logger.setLevel(logging.INFO)
    try:
        yield lines
    finally:
        for logger, h in zip(loggers, (handler, access), strict=True):
            logger.removeHandler(h)
        logging.setLogRecordFactory(factory)


def test_no_record_carries_the_key(caught):
    from urllib.parse import quote, quote_plus

    access = logging.getLogger("uvicorn.access")
    access.info('%s - "%s %s HTTP/%s" %d', "10.0.0.5:5000", "GET", f"/instructor?key={quote(SECRET, safe='')}", "1.1", 303)
    access.info('%s - "%s %s HTTP/%s" %d', "10.0.0.5:5000", "GET", "/instructor?key=chalk-and-talk-2025&x=1", "1.1", 403)
    log = logging.getLogger("redaction-test")
    log.warning("the key is %s", SECRET)
    log.warning("opened /api/rooms/x/socket?a=1&key=%s;", quote_plus(SECRET))
    log.warning("%(who)s used %(key)s", {"who": "someone", "key": SECRET})
    try:
        raise ValueError(f"bad URL http://h/instructor?key={SECRET}")
    except ValueError:
        log.exception("failed")
    text = "\n".join(caught)
    assert '10.0.0.5:5000 - "GET /instructor?key=… HTTP/1.1" 303' in text
    assert '"GET /instructor?key=…&x=1 HTTP/1.1" 403' in text, "a mistyped key is redacted too"
    assert "the key is …" in text and "socket?a=1&key=…;" in text and "someone used …" in text
    assert "ValueError: bad URL http://h/instructor?key=…" in text
    for form in (SECRET, quote(SECRET, safe=""), quote_plus(SECRET), "chalk-and-talk-2025"):
        assert form not in text


def test_installing_again_replaces_the_redaction_rather_than_stacking_it():
    base = logging.getLogRecordFactory()
    original = getattr(base, "unredacted", base)  # another test in this process may have installed one already
    try:
        log_redaction.install("first-secret-0001")
        log_redaction.install("second-secret-0002")
        factory = logging.getLogRecordFactory()
        assert factory.unredacted is original
        record = factory("x", logging.INFO, __file__, 1, "%s and %s", ("first-secret-0001", "second-secret-0002"), None)
        assert record.getMessage() == "first-secret-0001 and …"
    finally:
        logging.setLogRecordFactory(base)
