"""Learners and their exercise progress in the database (app.practice.progress), on SQLite (the default) and on a
throwaway PostgreSQL: a learner is known again by their browser's token and, on another browser, by their resume
code; the database keeps only digests of both; attempts, named mistakes, solving and giving up add up per part, a new
variant starts a part afresh; two tabs' first attempts at once keep both; unused learners are forgotten with their
progress; and it all survives a restart (a new store on the same database)."""

from __future__ import annotations

import threading
from datetime import UTC, datetime, timedelta

import pytest
import sqlalchemy as sa

from app.bench.loopback_postgres import postgres_bin, postgres_server
from app.practice.progress import SqlProgressStore, normal_resume_code
from app.storage import open_database
from app.storage.database import sqlite_url
from app.storage.tables import learner_tokens, learners


@pytest.fixture(scope="module", params=["sqlite", "postgresql"])
def url(request, tmp_path_factory):
    if request.param == "sqlite":
        yield sqlite_url(tmp_path_factory.mktemp("progress"))
        return
    if postgres_bin() is None:
        pytest.skip("PostgreSQL is not installed: tests/run.sh installs it")
    with postgres_server() as url:
        yield url


def test_a_learner_is_known_by_token_and_by_resume_code_kept_as_digests_only(url):
    store = SqlProgressStore(open_database(url))
    made = store.new_learner()
    assert made.token and made.resume_code and len(normal_resume_code(made.resume_code)) == 10
    restarted = SqlProgressStore(open_database(url))
    assert restarted.learner(made.token).learner_id == made.learner_id
    assert restarted.learner("not-a-token") is None and restarted.learner("") is None
    other_browser = restarted.resume(made.resume_code.lower().replace("-", " "))  # as a student types it
    assert other_browser.learner_id == made.learner_id and other_browser.token != made.token
    assert restarted.learner(made.token).learner_id == made.learner_id  # the first browser keeps its token
    assert restarted.resume("ABCDE-FGHJK") is None and restarted.resume("I0O1L-?????") is None
    with store.database.engine.connect() as connection:
        kept = " ".join(str(v) for row in connection.execute(sa.select(learners, learner_tokens).join(learner_tokens))
                        for v in row)  # fmt: skip
    for secret in (made.token, other_browser.token, made.resume_code, normal_resume_code(made.resume_code)):
        assert secret not in kept


def test_progress_adds_up_per_part_and_survives_a_restart(url):
    store = SqlProgressStore(open_database(url))
    learner = store.new_learner().learner_id
    record = lambda **kw: store.record(learner, exercise_id="heavy-top-precession", **kw)  # noqa: E731
    record(part_id="a", variant=7, mistake_id="coriolis-omitted")
    record(part_id="a", variant=7, mistake_id="degrees-for-radians")
    assert record(part_id="a", variant=7, correct=True).solved
    assert record(part_id="a", variant=7, mistake_id="coriolis-omitted").solved  # solved stays solved
    record(part_id="b", variant=7, gave_up=True)
    (a, b) = SqlProgressStore(open_database(url)).progress(learner)
    assert (a.part_id, a.attempts, a.solved, a.gave_up) == ("a", 4, True, False)
    assert a.mistakes == ("coriolis-omitted", "degrees-for-radians", "coriolis-omitted")
    assert (b.attempts, b.solved, b.gave_up) == (0, False, True)
    fresh = record(part_id="a", variant=8)  # another variant: the part starts afresh
    assert (fresh.attempts, fresh.solved, fresh.mistakes) == (1, False, ())
    assert a.public() == {"exercise_id": "heavy-top-precession", "part": "a", "variant": 7, "attempts": 4,
                          "solved": True, "gave_up": False, "mistakes": list(a.mistakes)}  # fmt: skip
    for bad in ({"exercise_id": "x" * 33}, {"part_id": ""}, {"variant": -1}, {"variant": True}):
        with pytest.raises(ValueError):
            store.record(learner, **{"exercise_id": "e", "part_id": "a", "variant": 1, **bad})


def test_two_tabs_first_attempts_at_once_are_both_kept(url):
    store = SqlProgressStore(open_database(url))
    learner = store.new_learner().learner_id
    start = threading.Barrier(2)

    def attempt() -> None:
        start.wait()
        store.record(learner, exercise_id="four-bar-velocity", part_id="a", variant=3)

    tabs = [threading.Thread(target=attempt) for _ in range(2)]
    for tab in tabs:
        tab.start()
    for tab in tabs:
        tab.join(timeout=30)
    (part,) = store.progress(learner)
    assert part.attempts == 2


def test_unused_learners_are_forgotten_with_their_progress(url):
    store = SqlProgressStore(open_database(url))
    old, recent = store.new_learner(), store.new_learner()
    store.record(old.learner_id, exercise_id="e", part_id="a", variant=1)
    with store.database.transaction() as connection:
        long_ago = datetime.now(UTC) - timedelta(days=200)
        connection.execute(sa.update(learners).where(learners.c.learner_id == old.learner_id).values(used_at=long_ago))
    assert store.forget_unused(days=180) == 1
    assert store.learner(old.token) is None and store.progress(old.learner_id) == []
    assert store.learner(recent.token).learner_id == recent.learner_id
    assert store.forget(recent.learner_id) and not store.forget(recent.learner_id)
