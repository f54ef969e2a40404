"""Page sessions kept across a restart, in process: the directory of the next run knows each kept session, its claim
and its creator's share; it opens a kept session in the host once, when first asked, with its kept parameters
(the defaults if this version refuses them; again on the next ask if the host was busy); an evicted session is
forgotten in the database too."""

from __future__ import annotations

import pytest
import sqlalchemy as sa

from app.api.access import Refused, SessionDirectory
from app.api.kept_sessions import SqlSessionStore
from app.scenes.host.host import UnknownSceneError
from app.scenes.host.interface import HostBusy
from app.storage import open_database
from app.storage.database import sqlite_url
from app.storage.tables import sessions

KEY = "a-page-key-0123456789"


def directory(tmp_path, reopened: list, *, refuse: set[str] = frozenset(), max_sessions: int = 10) -> SessionDirectory:
    def reopen(session_id: str, scene_id: str, params: dict) -> None:
        if "busy" in refuse:
            raise HostBusy("scene worker 0 is restarting")
        if "params" in refuse and params:
            raise ValueError("spin_rad_s: out of range")
        reopened.append((session_id, scene_id, params))

    store = SqlSessionStore(open_database(sqlite_url(tmp_path / "data")))
    return SessionDirectory(max_sessions=max_sessions, store=store, reopen=reopen)


def test_a_kept_session_is_claimed_still_and_opens_once_with_its_parameters(tmp_path):
    before = directory(tmp_path, [])
    before.changed("s" * 32, "heavy-top", KEY, client="10.0.0.7", params={"spin_rad_s": 66.0})
    before.changed("u" * 32, "heavy-top", None, client="10.0.0.8", params={})
    reopened: list = []
    after = directory(tmp_path, reopened)
    assert after.is_claimed("s" * 32) and not after.is_claimed("u" * 32)
    assert after.sessions_of("10.0.0.7") == 0 and after.scene_of("s" * 32) == "heavy-top"  # no address is kept
    assert b"10.0.0.7" not in b"".join(path.read_bytes() for path in (tmp_path / "data").iterdir())
    with pytest.raises(Refused) as refused:
        after.check_change("s" * 32, None, client="10.0.0.9")
    assert refused.value.status == 403
    after.check_change("s" * 32, KEY, client="10.0.0.7")
    after.reopen_kept("s" * 32)
    after.reopen_kept("s" * 32)
    after.reopen_kept("never-seen")
    assert reopened == [("s" * 32, "heavy-top", {"spin_rad_s": 66.0})]


def test_a_busy_host_is_asked_again_and_refused_parameters_give_the_defaults(tmp_path):
    directory(tmp_path, []).changed("s" * 32, "heavy-top", KEY, client=None, params={"spin_rad_s": 66.0})
    reopened: list = []
    busy = directory(tmp_path, reopened, refuse={"busy"})
    with pytest.raises(HostBusy):
        busy.reopen_kept("s" * 32)
    busy._reopen = lambda session_id, scene_id, params: reopened.append(params)  # the worker is back
    busy.reopen_kept("s" * 32)
    assert reopened == [{"spin_rad_s": 66.0}]
    refused: list = []
    directory(tmp_path, refused, refuse={"params"}).reopen_kept("s" * 32)
    assert refused == [("s" * 32, "heavy-top", {})]


def test_an_evicted_session_is_forgotten_in_the_database_too(tmp_path):
    full = directory(tmp_path, [], max_sessions=2)
    for n in range(3):
        full.changed(f"{n}" * 32, "heavy-top", None, client=None, params={})
    after = directory(tmp_path, [], max_sessions=2)
    assert after.scene_of("0" * 32) is None and after.scene_of("2" * 32) == "heavy-top" and len(after) == 2


def test_a_kept_session_of_a_scene_this_version_lacks_is_forgotten_and_a_malformed_row_is_left_out(tmp_path):
    kept = directory(tmp_path, [])
    kept.changed("g" * 32, "heavy-top", KEY, client=None, params={})
    kept.changed("m" * 32, "heavy-top", KEY, client=None, params={})
    with kept._store.database.transaction() as connection:
        connection.execute(sa.update(sessions).where(sessions.c.session_id == "m" * 32).values(params=[1, 2]))

    def no_such_scene(session_id, scene_id, params):
        raise UnknownSceneError(scene_id)

    after = SessionDirectory(store=kept._store, reopen=no_such_scene)
    assert after.scene_of("m" * 32) is None  # not an object: not restored
    after.reopen_kept("g" * 32)  # no 500 on every ask: forgotten, its page starts afresh
    assert after.scene_of("g" * 32) is None
    with kept._store.database.engine.connect() as connection:
        assert connection.execute(sa.select(sessions.c.session_id)).scalars().all() == ["m" * 32]


def test_a_session_another_server_claimed_is_claimed_here_too(tmp_path):
    """Two servers sharing one database: a page's session claimed on the first, its page then sent to the second
    (the first died), is refused to anyone without its key there, and opens there with its parameters."""
    reopened: list = []
    there = directory(tmp_path, reopened)  # started before the session existed
    here = directory(tmp_path, [])
    here.changed("s" * 32, "heavy-top", KEY, client="10.0.0.7", params={"spin_rad_s": 66.0})
    with pytest.raises(Refused) as refused:
        there.check_change("s" * 32, None, client="10.0.0.9")
    assert refused.value.status == 403
    there.reopen_kept("s" * 32)
    assert reopened == [("s" * 32, "heavy-top", {"spin_rad_s": 66.0})]
    there.check_change("n" * 32, None, client="10.0.0.9")  # a session nobody kept is new, as before


def test_kept_parameters_survive_a_busy_host_after_their_refusal(tmp_path):
    directory(tmp_path, []).changed("s" * 32, "heavy-top", KEY, client=None, params={"spin_rad_s": 66.0})
    asked: list = []

    def refuse_then_busy(session_id, scene_id, params):
        asked.append(params)
        if params:
            raise ValueError("spin_rad_s: out of range")
        raise HostBusy("scene worker 0 is restarting")

    after = SessionDirectory(store=directory(tmp_path, [])._store, reopen=refuse_then_busy)
    with pytest.raises(HostBusy):
        after.reopen_kept("s" * 32)
    with pytest.raises(HostBusy):
        after.reopen_kept("s" * 32)  # asked again, with the kept parameters first
    assert asked == [{"spin_rad_s": 66.0}, {}, {"spin_rad_s": 66.0}, {}]
