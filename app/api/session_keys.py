"""Which page owns which scene session: a per-session secret, required to change it.

A lesson page makes up a random session id and a random key and sends the key
(header ``X-Session-Key``) with every change. The first successful change that
carries a key claims the session for it; from then on a change without that key
is refused with 403, so someone who learns a session id (from a URL, a screen
share) can watch its viewer but never drive it. A session no page has claimed
stays open to keyless changes (scripts, the API's own examples). Only a hash of
each key is kept, for the most recent ``max_sessions`` sessions.
"""

from __future__ import annotations

import hashlib
import hmac
import re
import threading
from collections import OrderedDict

#: 16–128 letters, digits, '-' or '_' (the lesson page sends 32 hex digits from crypto.getRandomValues).
SESSION_KEY_PATTERN = re.compile(r"^[A-Za-z0-9_-]{16,128}$")
HEADER = "X-Session-Key"


class SessionKeyError(PermissionError):
    """The session belongs to another page (its key is missing or wrong)."""


class SessionKeys:
    """Session id -> hash of the key that claimed it (thread-safe, bounded)."""

    def __init__(self, *, max_sessions: int = 2000) -> None:
        self.max_sessions = max_sessions
        self._hashes: OrderedDict[str, bytes] = OrderedDict()
        self._lock = threading.Lock()

    @staticmethod
    def _hash(key: str) -> bytes:
        return hashlib.sha256(key.encode()).digest()

    def check(self, session_id: str, key: str | None) -> None:
        """Raise :class:`SessionKeyError` unless ``key`` may change ``session_id``."""
        with self._lock:
            owner = self._hashes.get(session_id)
        if owner is None:
            return
        if key is None:
            raise SessionKeyError(f"session {session_id!r} belongs to another page: changing it needs its {HEADER} header")
        if not hmac.compare_digest(owner, self._hash(key)):
            raise SessionKeyError(f"session {session_id!r} belongs to another page: the {HEADER} does not match")

    def claim(self, session_id: str, key: str | None) -> None:
        """After a successful change: the first key seen claims the session (no key claims nothing)."""
        if key is None:
            return
        with self._lock:
            self._hashes.setdefault(session_id, self._hash(key))
            self._hashes.move_to_end(session_id)
            while len(self._hashes) > self.max_sessions:
                self._hashes.popitem(last=False)

    def is_claimed(self, session_id: str) -> bool:
        with self._lock:
            return session_id in self._hashes
