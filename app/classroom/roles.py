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

COOKIE = "dynlab_instructor"
HEADER = "X-Instructor-Key"
#: Shortest secret accepted from ``--instructor-key`` or ``DYNLAB_INSTRUCTOR_KEY`` (characters).
MIN_KEY_LENGTH = 12


class InstructorKey:
    """The server's instructor secret and the cookie token derived from it."""

    def __init__(self, secret: str | None = None) -> None:
        if secret is not None and len(secret) < MIN_KEY_LENGTH:
            raise ValueError(f"instructor key: at least {MIN_KEY_LENGTH} characters (got {len(secret)})")
        self.secret = secret or secrets.token_urlsafe(18)
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
