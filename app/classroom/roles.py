"""Who is the instructor: whoever holds the secret printed by ``dynlab serve``.

The instructor link (``/instructor?key=<secret>``) sets an HttpOnly cookie
holding a token derived from the secret; API clients may send the secret itself
in the ``X-Instructor-Key`` header. Everyone else is a student, with no account.
Every instructor-only route and socket action asks :meth:`InstructorKey.is_instructor`;
comparisons are constant-time.
"""

from __future__ import annotations

import hashlib
import hmac
import secrets
from collections.abc import Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from app.storage import Database

COOKIE = "dynlab_instructor"
#: The name the instructor's secret is kept under in the database's server values.
KEPT_SECRET = "instructor_secret"
HEADER = "X-Instructor-Key"
#: Shortest secret accepted from ``--instructor-key`` or ``DYNLAB_INSTRUCTOR_KEY`` (characters).
MIN_KEY_LENGTH = 12


class InstructorKey:
    """The server's instructor secret and the cookie token derived from it."""

    def __init__(self, secret: str | None = None) -> None:
        if secret is not None and len(secret) < MIN_KEY_LENGTH:
            raise ValueError(f"instructor key: at least {MIN_KEY_LENGTH} characters (got {len(secret)})")
        self.secret = secret or new_secret()
        self.cookie_token = hmac.new(self.secret.encode(), b"dynlab instructor cookie", hashlib.sha256).hexdigest()

    def matches(self, key: str | None) -> bool:
        """True if ``key`` is the secret (as typed into the instructor link or the header)."""
        return key is not None and hmac.compare_digest(key.encode(), self.secret.encode())

    def is_instructor(self, *, cookies: Mapping[str, str], headers: Mapping[str, str]) -> bool:
        """True for a request or websocket handshake carrying the instructor's cookie or key."""
        token = cookies.get(COOKIE)
        if token is not None and hmac.compare_digest(token.encode(), self.cookie_token.encode()):
            return True
        return self.matches(headers.get(HEADER))

    def link(self, base_url: str) -> str:
        """The instructor link printed beside the server's address."""
        return f"{base_url.rstrip('/')}/instructor?key={self.secret}"


def new_secret() -> str:
    """A new instructor secret: 18 random bytes, URL-safe (24 characters)."""
    return secrets.token_urlsafe(18)


def kept_instructor_secret(database: Database | None) -> str | None:
    """The instructor's secret kept in ``database`` (made and kept on its first start); None with no database."""
    return database.kept_value(KEPT_SECRET, new_secret) if database is not None else None


def rotate_instructor_secret(database: Database) -> str:
    """A new instructor secret, kept in place of the old one (the server takes it at its next start)."""
    secret = new_secret()
    database.set_value(KEPT_SECRET, secret)
    return secret
