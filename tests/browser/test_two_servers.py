"""Issue 26, points 5 and 6: one class on two ``dynlab serve`` sharing PostgreSQL behind HAProxy (deploy/haproxy.cfg),
on loopback, as app/bench/scale_out.py starts them. Both tests are in one file so that they run one after the other
(each starts its own PostgreSQL, two servers with their workers and HAProxy; two such stacks at once on two cores
would measure the machine, not the product).

The loopback test (``dynlab scale-out``, whose committed report is docs/bench/scale_out.json): an instructor and 30
students (half on each server) run a room: they follow it, the instructor changes the spin ten times, a poll is
answered; then the room's server is killed and every student is back in the same room with the same state, and a
lesson page's claimed scene that lived there comes back on the other server with its parameters and its claim.

In Chromium:

The instructor's page comes through the balancer (to the server the room's id hashes to); one phone comes through
the balancer too, the other opened the join link straight on the other server. The instructor sees both phones
connected and following; the instructor's change of the spin reaches both phones, and the room's scene runs on both
(the second phone's readout advances). Then the room's server is killed: the instructor's page and the first phone
reconnect through the balancer to the other server, the instructor still sees both phones following and the same
spin, and a new change reaches both phones. No page has an error."""

from __future__ import annotations

import json
import re
import time
from contextlib import ExitStack
from types import SimpleNamespace

import httpx
import pytest
import sqlalchemy as sa

from app.bench.loopback_postgres import postgres_server
from app.bench.ports import free_loopback_port
from app.bench.scale_out import Server, balancer, haproxy_binary, main
from app.classroom.room import PRESENCE_HOLDS_S
from tests.browser.conftest import readout_quantity, screenshot
from tests.browser.test_classroom_in_browser import LESSON, SPIN, _control, _student, instructor_room
from tests.conftest import wait_until

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(haproxy_binary() is None, reason="HAProxy is not installed: tests/run.sh installs it"),
]
PHONE = (390, 844)


@pytest.fixture
def two_servers(tmp_path_factory):
    """The stack, for one test: stopped before the next starts its own."""
    with ExitStack() as stack:
        database_url = stack.enter_context(postgres_server())
        root = tmp_path_factory.mktemp("two-servers")
        balancer_port = free_loopback_port()
        balancer_url = f"http://127.0.0.1:{balancer_port}"
        servers = [Server(n, free_loopback_port(), database_url, str(root / n), balancer_url) for n in ("app1", "app2")]
        for server in servers:
            stack.callback(server.stop)
            server.start()
            server.wait_healthy()  # the first migrates the database and makes the instructor's secret
        engine = sa.create_engine(database_url)
        with engine.connect() as connection:
            secret = connection.execute(sa.text("SELECT value FROM server_values WHERE name = 'instructor_secret'")).scalar_one()
        engine.dispose()
        stack.enter_context(balancer(balancer_port, servers))
        yield SimpleNamespace(url=balancer_url, instructor_link=f"{balancer_url}/instructor?key={secret}", servers=servers)


def test_a_class_split_between_two_servers_is_one_class_and_survives_losing_one(browser, two_servers, shots):
    contexts = []
    try:
        context, teacher, teacher_errors, room_id = instructor_room(browser, two_servers, LESSON)
        contexts.append(context)
        code = teacher.text_content(".room-code")
        answered_by = httpx.get(f"{two_servers.url}/api/rooms/{room_id}/state").headers["x-dynlab-server"]
        home = next(s for s in two_servers.servers if s.name == answered_by)
        other = next(s for s in two_servers.servers if s is not home)
        phones = []
        for site in (two_servers, SimpleNamespace(url=other.base_url)):  # through the balancer; straight to the other
            phone_context, page, errors = _student(browser, site, code, PHONE)
            contexts.append(phone_context)
            phones.append((page, errors))
        teacher.wait_for_selector(".room-presence[data-connected='2'][data-following='2']")

        def spin_reaches_both(value: int) -> None:
            teacher.fill(f"#ctl-{SPIN}", str(value))
            teacher.dispatch_event(f"#ctl-{SPIN}", "change")
            for page, _ in phones:
                wait_until(lambda page=page: _control(page) == value, 10, what=f"the spin {value} on a phone")

        spin_reaches_both(120)
        far_phone = phones[1][0]
        far_phone.wait_for_selector('#readout [data-quantity="t_s"]')
        t_before = readout_quantity(far_phone, "t_s")
        wait_until(lambda: readout_quantity(far_phone, "t_s") > t_before, 10, what="the room's scene to run on the other server")
        teacher.wait_for_function("() => document.querySelector('#readout')?.textContent.includes('120 rad/s')")
        screenshot(teacher, shots / "two-servers-instructor.png")
        screenshot(far_phone, shots / "two-servers-phone-on-the-other-server.png")

        killed_s = time.monotonic()
        home.kill()

        def everyone_on_the_other_server() -> bool:
            """The other server counts the instructor and both phones once the dead server's word on its sockets has
            lapsed: its own sockets hold them all then."""
            state = httpx.get(f"{other.base_url}/api/rooms/{room_id}/state").json()
            lapsed = time.monotonic() - killed_s > PRESENCE_HOLDS_S
            return lapsed and state["instructor_connected"] and state["students"]["following"] == 2

        wait_until(everyone_on_the_other_server, 20, what="the instructor's page and both phones on the other server")
        teacher.wait_for_selector(".room-presence[data-connected='2'][data-following='2']")
        assert _control(teacher) == 120 and teacher.text_content(".room-code") == code
        spin_reaches_both(90)
        assert re.fullmatch(r"[A-Z0-9]{6}", code)
        assert teacher_errors == [] and all(errors == [] for _, errors in phones)
    finally:
        for context in contexts:
            context.close()


#: The issue's bounds: a change reaches every student within 200 ms; the class is back within 10 s of the kill.
FOLLOW_LATENCY_MS = 200.0
FAILOVER_S = 10.0


def test_one_class_on_two_servers_follows_answers_and_survives_losing_one(tmp_path, capsys):
    from concurrent.futures import ThreadPoolExecutor

    # In a thread of its own: the tool runs its requests with asyncio.run, which the browser's loop here forbids.
    with ThreadPoolExecutor(max_workers=1) as own_thread:
        ran = own_thread.submit(main, ["--students", "30", "--changes", "10", "--out-dir", str(tmp_path)])
        assert ran.result(timeout=600) == 0
    report = json.loads((tmp_path / "scale_out.json").read_text())
    # Joining through the balancer's round robin, students arrived on both servers: each took the room up.
    assert sorted(report["students_joined_on"].values()) != [0, 30]
    # The instructor's list counts every student as connected and following, whichever server their page is on.
    assert report["instructor_sees_everyone_s"] is not None
    latency = report["follow_latency_ms"]
    assert latency["samples"] == 300  # every change reached every student's socket (else main raised)
    # The median on each server is held to the bound here, where other tests share the two cores; the committed
    # report (an idle machine) holds its 99th percentile and maximum to it too.
    assert latency["median_on_room_server"] < FOLLOW_LATENCY_MS
    assert latency["median_on_other_server"] < FOLLOW_LATENCY_MS
    assert report["poll_answers_seen_by_instructor"] is True
    assert report["failover_s"] is not None and report["failover_s"] < FAILOVER_S
    after = report["state_after_failover"]
    assert after["same"] is True and after["server"] != report["room_server"]
    assert after["students_reconnected"] == 15  # the room server's half came back through the balancer
    session = report["page_session_after_failover"]  # a lesson page's own scene, claimed, on the killed server
    assert session["server"] != report["room_server"] and session["params_kept"] is True
    assert session["keyless_change"] == 403  # its claim holds on the server that took it up
    assert (tmp_path / "scale_out.svg").read_text().startswith("<svg")
    assert "failover" in capsys.readouterr().out
