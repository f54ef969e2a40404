"""Bounded work in a child process: answers, passes ValueError back, is killed at its limits, leaks nothing.

The functions the children run are defined here at module level (a child imports this module
to unpickle them). Time bounds in the tests allow for a loaded 2-core machine: a warm child
starts in tens of ms and a SIGKILL takes effect at once, so a timeout that fires within 2 s of
its limit is the runner's doing, while a missing kill would leave the sleeping child 60 s.
"""

from __future__ import annotations

import contextlib
import math
import os
import resource
import signal
import subprocess
import sys
import threading
import time
from functools import partial

import pytest
import sympy

from app.physics.core import bounded
from app.physics.core.bounded import BoundedRunner, WorkBusy, WorkFailed, WorkInterrupted, WorkRefused, WorkTimeout, WorkTooLarge
from app.physics.core.parameters import ParameterError
from app.physics.math.expressions import parse_formula

#: Slack beyond a timeout for the child's start, the kill and the join on a loaded machine (s).
KILL_SLACK_S = 2.0


# -- what the children run -----------------------------------------------------------------

def square(x: float) -> float:
    return x * x


def refuse(message: str) -> None:
    raise ValueError(message)


def refuse_parameter() -> None:
    raise ParameterError("mass_kg", "must be positive", path=("bodies", 1, "mass_kg"))


def fail() -> None:
    raise KeyError("a bug")


def sleep_for(seconds: float) -> str:
    time.sleep(seconds)
    return "slept"


def spin_forever() -> None:
    while True:
        pass


def hold_megabytes(megabytes: int) -> int:
    """Allocate and touch ``megabytes`` MB; returns the count of bytes held."""
    block = bytearray(megabytes * 2**20)
    block[:: 4096] = b"\x01" * len(block[:: 4096])
    return len(block)


def grow_until_refused() -> int:
    """Allocate 8 MB blocks without end, as a runaway derivation does."""
    blocks = []
    while True:
        blocks.append(bytearray(8 * 2**20))


def recurse(depth: int) -> int:
    return 0 if depth == 0 else 1 + recurse(depth - 1)


def exit_with(status: int) -> None:
    os._exit(status)


def signal_self(number: int) -> None:
    os.kill(os.getpid(), number)
    time.sleep(5)


def large_result(megabytes: int) -> bytes:
    return b"x" * (megabytes * 2**20)


def limits_seen() -> tuple[int, int, int]:
    """The child's (RLIMIT_AS soft, RLIMIT_CPU soft, address space now) in bytes, s, bytes."""
    from app.physics.core.bounded import _address_space_bytes

    return resource.getrlimit(resource.RLIMIT_AS)[0], resource.getrlimit(resource.RLIMIT_CPU)[0], _address_space_bytes()


def session_and_policy() -> tuple[int, int]:
    """The child's session id and scheduling policy."""
    return os.getsid(0), os.sched_getscheduler(0)


def kinetic_energy_rate_derivative(text: str) -> sympy.Expr:
    """∂T/∂q1d of a typed kinetic energy: the kind of work the runner is for."""
    names = {name: sympy.Symbol(name, real=True) for name in ("q1", "q1d", "m", "l")}
    return sympy.diff(parse_formula(text, symbols=names), names["q1d"])


# -- process bookkeeping -------------------------------------------------------------------

def _process_table() -> dict[int, tuple[int, str, str]]:
    """pid -> (parent pid, state letter, command line) for every process we can read."""
    table = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", encoding="utf-8", errors="replace") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
            with open(f"/proc/{entry}/cmdline", "rb") as cmdline:
                command = cmdline.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        table[int(entry)] = (int(fields[1]), fields[0], command)
    return table


def _descendants(*, not_below: set[int] = frozenset()) -> list[tuple[int, int, str, str]]:
    """(pid, parent pid, state, command) of every process below this one, the forkserver's children included, and
    none below the processes ``not_below`` (they are listed themselves)."""
    table = _process_table()
    found, frontier = [], [os.getpid()]
    while frontier:
        parent = frontier.pop()
        for pid, (ppid, state, command) in table.items():
            if ppid == parent:
                found.append((pid, ppid, state, command))
                if pid not in not_below:
                    frontier.append(pid)
    return found


#: Processes below this one before the runner started (in a whole-suite run: the browser tests' Playwright
#: driver and the like), which are not the runner's to clean up.
_BEFORE: set[int] = set()


def _workers_left() -> list[tuple[int, int, str, str]]:
    """Descendants other than the long-lived forkserver and resource tracker (our own children, started
    with ``-c``) and other than what was there before the runner, or below it (a browser of earlier tests in this
    process starts helper processes of its own when it likes): leaked or zombie workers. A worker is
    forked from the forkserver, so it shares its command line but is the forkserver's child, not ours."""
    helpers = ("multiprocessing.forkserver import main", "multiprocessing.resource_tracker import main")
    # Not below an earlier process, unless it is the forkserver (an earlier test's, which this runner then shares).
    foreign = {p[0] for p in _descendants() if p[0] in _BEFORE and helpers[0] not in p[3]}
    return [
        p for p in _descendants(not_below=foreign)
        if p[0] not in _BEFORE and (p[2] == "Z" or p[1] != os.getpid() or not any(helper in p[3] for helper in helpers))
    ]  # fmt: skip


def _open_fds() -> int:
    return len(os.listdir("/proc/self/fd"))


def _wait_for(condition, timeout_s: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.02)
    return condition()


@pytest.fixture(scope="module")
def runner() -> BoundedRunner:
    _BEFORE.update(p[0] for p in _descendants())
    runner = BoundedRunner(max_jobs=2, timeout_s=20.0, memory_mb=256.0, preload=("app.physics.core.bounded", "numpy", "sympy", __name__))
    runner.warm()
    runner.run(square, (1.0,))  # the first call waits for the forkserver's imports
    return runner


@pytest.fixture(autouse=True)
def quiet_machine(monkeypatch):
    """These tests time their children to a tenth of a second: the machine counts as quiet (no pauses), whatever the
    rest of the suite is doing; the pauses have their own test below."""
    monkeypatch.setattr(bounded, "_server_busy", lambda: False)


@pytest.fixture
def as_a_server():
    """This process counts as a server showing live scenes (as the scene host makes it): its children run in the idle
    class."""
    bounded.yield_only_to_live_scenes(lambda: True)
    yield
    bounded._live_scenes, bounded._live_scenes_seen = None, (-math.inf, True)


# -- answers -------------------------------------------------------------------------------

def test_result_is_returned(runner):
    assert runner.run(square, (7.5,)) == 56.25


def test_sympy_work_returns_its_expression(runner):
    m, l, q1, q1d = sympy.symbols("m l q1 q1d", real=True)
    got = runner.run(kinetic_energy_rate_derivative, ("m*l^2*q1d^2/2 + m*l*cos(q1)",))
    assert sympy.simplify(got - m * l**2 * q1d) == 0


def test_value_error_comes_back_with_its_message(runner):
    with pytest.raises(ValueError) as refused:
        runner.run(refuse, ("the mass matrix is singular at q1 = 0",))
    assert type(refused.value) is ValueError
    assert str(refused.value) == "the mass matrix is singular at q1 = 0"


def test_value_error_from_typed_input_comes_back(runner):
    with pytest.raises(ValueError, match="unexpected 'theta' at character 1"):
        runner.run(kinetic_energy_rate_derivative, ("theta",))


def test_parameter_error_keeps_its_field_and_path(runner):
    with pytest.raises(ParameterError) as refused:
        runner.run(refuse_parameter)
    assert refused.value.field == "mass_kg"
    assert refused.value.path == ("bodies", 1, "mass_kg")
    assert refused.value.message == "must be positive"


def test_other_exceptions_are_failures_not_refusals(runner):
    with pytest.raises(WorkFailed, match="KeyError: 'a bug'"):
        runner.run(fail)
    with pytest.raises(WorkFailed, match="exit status 3"):
        runner.run(exit_with, (3,))


def test_refusals_are_value_errors_for_the_routes():
    assert issubclass(WorkTimeout, WorkRefused) and issubclass(WorkTooLarge, WorkRefused)
    assert issubclass(WorkRefused, ValueError)
    assert not issubclass(WorkBusy, ValueError) and not issubclass(WorkFailed, ValueError)


# -- limits --------------------------------------------------------------------------------

@pytest.mark.parametrize("function, args", [(sleep_for, (60.0,)), (spin_forever, ())])
def test_work_is_killed_at_its_timeout(runner, function, args, monkeypatch):
    monkeypatch.setattr(bounded, "STARVED_SHARE", math.inf)  # the kill is tested, not how a busy machine is told apart
    start = time.monotonic()
    with pytest.raises(WorkTimeout, match="took longer than its limit of 0.5 s"):
        runner.run(function, args, timeout_s=0.5, what="deriving the equations")
    elapsed = time.monotonic() - start
    assert 0.5 <= elapsed < 0.5 + KILL_SLACK_S
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()


def test_child_limits_are_set_from_the_call(runner):
    address_space_limit, cpu_limit, address_space_now = runner.run(limits_seen, timeout_s=3.2, memory_mb=100.0)
    # The CPU limit is a backstop one second beyond the wall-clock limit (rounded up).
    assert cpu_limit == math.ceil(3.2) + 1
    # The address-space limit is the warm child's size plus the budget (the child has barely grown since).
    assert 0 <= address_space_limit - address_space_now - 100 * 2**20 < 16 * 2**20


def test_memory_within_the_budget_is_allowed(runner):
    assert runner.run(hold_megabytes, (64,), memory_mb=256.0) == 64 * 2**20


@pytest.mark.parametrize("function, args", [(hold_megabytes, (2048,)), (grow_until_refused, ())])
def test_memory_hog_is_refused(runner, function, args):
    with pytest.raises(WorkTooLarge, match="memory limit of 256 MB"):
        runner.run(function, args, memory_mb=256.0, what="compiling the equations")


def test_runaway_recursion_is_refused(runner):
    with pytest.raises(WorkTooLarge, match="recursion"):
        runner.run(recurse, (10**6,))


def test_child_killed_by_a_signal_is_reported(runner):
    with pytest.raises(WorkTooLarge, match="signal 6"):
        runner.run(signal_self, (signal.SIGABRT,))


def _at_default(pid: int, number: int) -> bool:
    """Whether process ``pid`` neither catches nor ignores signal ``number`` (its SigCgt and SigIgn masks in /proc);
    False once it is gone."""
    try:
        with open(f"/proc/{pid}/status", encoding="ascii") as status:
            masks = {line.split(":")[0]: int(line.split()[1], 16) for line in status if line.startswith(("SigCgt:", "SigIgn:"))}
    except (OSError, IndexError, ValueError):
        return False
    bit = 1 << (number - 1)
    return len(masks) == 2 and not (masks["SigCgt"] | masks["SigIgn"]) & bit


def _running_child(after: set[int]) -> int | None:
    """The pid of a bounded child started since ``after`` was taken: a child of this process's forkserver (not ours,
    and not a process of a browser an earlier test left running), not a zombie."""
    descendants = _descendants()
    server = "multiprocessing.forkserver import main"
    forkservers = {p[0] for p in descendants if p[1] == os.getpid() and server in p[3]}
    found = [p[0] for p in descendants if p[1] in forkservers and p[0] not in after and p[2] != "Z"]
    return found[0] if found else None


def test_a_call_running_when_the_server_stops_ends_at_once_without_waiting_for_its_child_to_die(runner, as_a_server):
    """Ctrl+C once took 5.5 s (its bound: 5): the server's exit waited for a request thread that waited for its killed
    child, which in the idle class on a busy machine died only when it got a processor. Here the child cannot be seen
    to die at all (its forkserver, which reports its exit, is stopped): the call still ends at once."""
    before = {p[0] for p in _descendants()}
    outcome: dict[str, BaseException] = {}

    def call() -> None:
        try:
            runner.run(sleep_for, (30.0,), what="deriving these equations")
        except BaseException as exc:  # noqa: BLE001 - the outcome is what the test reads
            outcome["error"] = exc

    caller = threading.Thread(target=call, daemon=True)
    caller.start()
    assert _wait_for(lambda: _running_child(before) is not None), "no bounded child appeared"
    child = _running_child(before)
    forkserver = next(p[1] for p in _descendants() if p[0] == child)
    os.kill(forkserver, signal.SIGSTOP)
    try:
        stopped = time.monotonic()
        bounded.stop_all_work()
        caller.join(5.0)
        took = time.monotonic() - stopped
    finally:
        os.kill(forkserver, signal.SIGCONT)
        caller.join(10.0)
    assert took < 1.5, f"the call took {took:.1f} s to end after the server stopped"
    assert isinstance(outcome["error"], WorkInterrupted), repr(outcome["error"])
    assert _wait_for(lambda: child not in {p[0] for p in _descendants() if p[2] != "Z"}), "the killed child lives on"


@pytest.mark.parametrize("number", [signal.SIGTERM, signal.SIGKILL, signal.SIGINT, signal.SIGHUP])
def test_a_child_ended_from_outside_is_interrupted_not_blamed_on_its_limits(runner, number):
    """Issue 24, Found 11: SIGTERM from outside gave a 500 (WorkFailed), SIGKILL a 422 blaming memory (WorkTooLarge).
    A signal the runner did not send, and its limits do not raise, is WorkInterrupted (a 503 for a route): try again."""
    before = {p[0] for p in _descendants()}
    outcome: dict[str, BaseException] = {}

    def call() -> None:
        try:
            runner.run(sleep_for, (30.0,), what="deriving these equations")
        except BaseException as exc:  # noqa: BLE001 - the outcome is what the test reads
            outcome["error"] = exc

    caller = threading.Thread(target=call)
    started = time.monotonic()
    caller.start()
    assert _wait_for(lambda: _running_child(before) is not None), "no bounded child appeared"
    pid = _running_child(before)
    assert pid is not None
    # Until the child runs its own code it has the forkserver's SIGINT (ignored, then Python's KeyboardInterrupt, an
    # exit status 1, a crash to the runner). Wait until the child has set the signals it may be ended by to their
    # defaults (its first act, SIGINT last).
    assert _wait_for(lambda: _at_default(pid, signal.SIGINT)), "the child never took the default SIGINT"
    try:
        os.kill(pid, number)
        caller.join(10.0)
        assert not caller.is_alive() and time.monotonic() - started < 10.0  # answered at once, not at the 20 s timeout
    finally:  # a child the signal missed must not outlive this test and be counted by the next one's
        if caller.is_alive():
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            caller.join(10.0)
    error = outcome["error"]
    assert isinstance(error, WorkInterrupted) and not isinstance(error, (ValueError, WorkFailed)), repr(error)
    assert error.signal_number == number and error.retry_after_s >= 1
    assert f"signal {signal.Signals(number).name}" in str(error) and "not by its limits; try again" in str(error)
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()
    assert runner.running == 0


def test_work_that_runs_out_of_time_while_the_machine_paused_it_is_busy_not_too_large(runner, monkeypatch):
    """On a busy machine a child computes in turns (50 ms, then 100 ms paused): out of time after such pauses, the
    caller hears "busy, try again" (429 with Retry-After at the routes), not "try something smaller"."""
    monkeypatch.setattr(bounded, "_server_busy", lambda: True)
    with pytest.raises(WorkBusy, match=r"was paused for \d+ s of its 1 s while the server was busy") as caught:
        runner.run(spin_forever, (), timeout_s=1.0, what="deriving these equations")
    assert caught.value.retry_after_s >= 1
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()


def test_work_starved_of_processors_by_other_programs_is_busy_not_too_large(runner, monkeypatch, as_a_server):
    """Two CPU-bound programs in a server's own session on a 2-core machine (one more than there are cores here: as
    its busy scenes would be) leave a child on idle time almost nothing: out of time, it waited for a
    processor nearly all of it. The caller hears "busy, try again" (a 429 with Retry-After at the routes), not "try
    something smaller", which its size never showed."""
    monkeypatch.setattr(bounded, "_server_busy", lambda: False)  # no pauses: only the other programs
    hogs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range((os.cpu_count() or 1) + 1)]
    try:
        # "waited 2 s" or "waited 1.9 s" (two figures): a child forked from a forkserver that preloaded more (the
        # derivations' runners preload the typed-Lagrangian module) starts a little later in its 2 s.
        with pytest.raises(WorkBusy, match=r"waited \d+(\.\d)? s of its 2 s for a processor that other work") as caught:
            runner.run(spin_forever, (), timeout_s=2.0, what="deriving these equations")
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    assert caught.value.retry_after_s >= 1
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()


def test_the_three_endings_are_told_apart(runner):
    """Its own timeout names the time limit, its memory limit names the memory, a crash within it is taken as memory."""
    with pytest.raises(WorkTimeout, match="limit of 0.3 s"):
        runner.run(sleep_for, (30.0,), timeout_s=0.3, what="deriving these equations")
    with pytest.raises(WorkTooLarge, match="memory limit of 64 MB"):
        runner.run(hold_megabytes, (1024,), memory_mb=64.0, what="deriving these equations")
    with pytest.raises(WorkTooLarge, match="memory limit of 256 MB"):
        runner.run(signal_self, (signal.SIGSEGV,), what="deriving these equations")


def test_result_too_large_is_refused():
    small = BoundedRunner(max_result_mb=1.0, preload=("app.physics.core.bounded", __name__))
    assert len(small.run(large_result, (0,))) == 0
    with pytest.raises(WorkTooLarge, match="larger than 1 MB"):
        small.run(large_result, (4,))
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()


# -- concurrency and hygiene ---------------------------------------------------------------

def test_busy_beyond_max_jobs_then_free_again(runner):
    results: list[str] = []
    threads = [threading.Thread(target=lambda: results.append(runner.run(sleep_for, (1.5,)))) for _ in range(runner.max_jobs)]
    for thread in threads:
        thread.start()
    assert _wait_for(lambda: runner.running == runner.max_jobs)
    with pytest.raises(WorkBusy, match="busy: 2 such jobs are running already; retry in about") as refused:
        runner.run(square, (2.0,))
    assert refused.value.retry_after_s >= 1
    for thread in threads:
        thread.join()
    assert results == ["slept", "slept"]
    assert runner.running == 0
    assert runner.run(square, (2.0,)) == 4.0


def test_a_waiting_call_gets_the_next_free_slot():
    patient = BoundedRunner(max_jobs=1, wait_s=10.0, preload=("app.physics.core.bounded", __name__))
    first = threading.Thread(target=patient.run, args=(sleep_for, (0.5,)))
    first.start()
    assert _wait_for(lambda: patient.running == 1)
    assert patient.run(square, (3.0,)) == 9.0  # waited for the sleeper instead of refusing
    first.join()


def test_no_children_or_descriptors_are_left_after_many_calls(runner):
    runner.run(square, (1.0,))
    fds_before = _open_fds()
    outcomes = {"result": 0, "value_error": 0, "timeout": 0, "memory": 0, "failed": 0}
    for i in range(40):
        kind = i % 5
        try:
            if kind == 0:
                runner.run(square, (float(i),))
                outcomes["result"] += 1
            elif kind == 1:
                runner.run(refuse, ("no",))
            elif kind == 2:
                runner.run(sleep_for, (30.0,), timeout_s=0.1)
            elif kind == 3:
                runner.run(hold_megabytes, (1024,), memory_mb=64.0)
            else:
                runner.run(exit_with, (5,))
        except (WorkTimeout, WorkBusy):  # a child given 0.1 s on a loaded machine may spend it waiting for a processor
            outcomes["timeout"] += 1
        except WorkTooLarge:
            outcomes["memory"] += 1
        except ValueError:
            outcomes["value_error"] += 1
        except WorkFailed:
            outcomes["failed"] += 1
    assert outcomes == {"result": 8, "value_error": 8, "timeout": 8, "memory": 8, "failed": 8}
    assert _wait_for(lambda: not _workers_left(), 5.0), _workers_left()
    assert _open_fds() == fds_before
    assert runner.running == 0


def test_unpicklable_function_is_refused_without_leaking(runner):
    fds_before = _open_fds()
    with pytest.raises(Exception):  # pickle's own error: a programming mistake, not bad input
        runner.run(lambda: 1)
    assert _open_fds() == fds_before
    assert runner.running == 0


def test_partial_functions_carry_keyword_arguments(runner):
    assert runner.run(partial(sleep_for, seconds=0.0)) == "slept"


@pytest.mark.parametrize(
    "options, field",
    [
        ({"max_jobs": 0}, "max_jobs"),
        ({"timeout_s": 0.0}, "timeout_s"),
        ({"timeout_s": math.inf}, "timeout_s"),
        ({"memory_mb": -1.0}, "memory_mb"),
        ({"max_result_mb": math.nan}, "max_result_mb"),
        ({"wait_s": -1.0}, "wait_s"),
    ],
)
def test_bad_options_name_the_field(options, field):
    with pytest.raises(ValueError, match=f"^{field}: "):
        BoundedRunner(**options)


def test_bad_call_limits_name_the_field(runner):
    with pytest.raises(ValueError, match="^timeout_s: "):
        runner.run(square, (1.0,), timeout_s=-1.0)
    with pytest.raises(ValueError, match="^memory_mb: "):
        runner.run(square, (1.0,), memory_mb=math.nan)


#: The real rule (the autouse ``quiet_machine`` replaces it in every test).
SERVER_BUSY = bounded._server_busy


def test_a_busy_server_pauses_children_only_while_it_shows_live_scenes(monkeypatch):
    """The pauses protect the frames a class watches: busy means the server's own processes used more than half the
    processors since the last look (looked at once a second), and only while it shows live scenes; with no viewer (a
    server warming its models) or no server at all (a test, a benchmark) a derivation runs on and is not refused as
    busy."""
    monkeypatch.setattr(bounded, "_server_busy", SERVER_BUSY)
    monkeypatch.setattr(bounded.os, "cpu_count", lambda: 2)
    clock = {"now": 100.0}
    monkeypatch.setattr(bounded.time, "monotonic", lambda: clock["now"])
    server_cpu_s = {41: 10.0, 42: 20.0}
    monkeypatch.setattr(bounded, "_server_processes_cpu_s", lambda: dict(server_cpu_s))
    monkeypatch.setattr(bounded, "_server_seen", (-bounded.math.inf, {}, False))
    monkeypatch.setattr(bounded, "_live_scenes", None)
    asked = []
    viewers = {"count": 3}

    def showing() -> bool:
        asked.append(viewers["count"])
        return viewers["count"] > 0

    try:
        assert not bounded._server_busy()  # no host in this process (a benchmark): nothing to yield to
        bounded.yield_only_to_live_scenes(showing)
        assert not bounded._server_busy()  # the first look: nothing to compare with yet
        server_cpu_s[41] += 0.7
        server_cpu_s[42] += 0.7
        clock["now"] += bounded.LIVE_SCENES_CHECK_S
        assert bounded._server_busy()  # 1.4 of 2 processors in 1 s is busy
        server_cpu_s[41] += 0.7
        assert bounded._server_busy(), "the answer is kept for LIVE_SCENES_CHECK_S"
        clock["now"] += bounded.LIVE_SCENES_CHECK_S
        assert not bounded._server_busy()  # 0.7 of 2 processors: not over half
        server_cpu_s[43] = 1.5  # a process that started since the last look counts from zero
        clock["now"] += bounded.LIVE_SCENES_CHECK_S
        assert bounded._server_busy()
        viewers["count"] = 0
        clock["now"] += bounded.LIVE_SCENES_CHECK_S
        assert not bounded._server_busy()  # busy, but nobody is watching a scene
        assert asked == [3, 3, 3, 3, 0]  # once a second: not at the look that kept its answer
    finally:
        bounded._live_scenes, bounded._live_scenes_seen = None, (-bounded.math.inf, True)


def test_the_server_is_the_session_outside_the_idle_class_and_not_other_programs():
    """What :func:`bounded._server_busy` counts: this process's session (a server's front and scene workers), without
    its idle-class children (the derivations themselves) and without programs of other sessions."""
    spin = [sys.executable, "-c", "while True: pass"]
    same_session = subprocess.Popen(spin)
    other_session = subprocess.Popen(spin, start_new_session=True)
    idle_class = subprocess.Popen(spin, preexec_fn=lambda: os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0)))
    try:
        counted = bounded._server_processes_cpu_s()
        assert os.getpid() in counted and same_session.pid in counted
        assert other_session.pid not in counted and idle_class.pid not in counted
    finally:
        for program in (same_session, other_session, idle_class):
            program.kill()
            program.wait()


def test_a_server_child_runs_in_the_servers_session_in_the_idle_class(runner, as_a_server):
    """In the server's session, so the server keeps its fair share of the machine against other programs; in the idle
    class, so it yields to the server's scenes."""
    session, policy = runner.run(session_and_policy)
    assert session == os.getsid(0)
    assert policy == os.SCHED_IDLE


def test_a_child_of_a_process_that_is_no_server_runs_as_any_program(runner):
    """A test or a benchmark has no class to spare: its children run in the normal class; so do those of a process
    whose server has stopped."""
    assert runner.run(session_and_policy) == (os.getsid(0), os.SCHED_OTHER)
    bounded.yield_only_to_live_scenes(lambda: True)
    assert runner.run(session_and_policy)[1] == os.SCHED_IDLE
    bounded.stop_all_work()
    assert runner.run(session_and_policy)[1] == os.SCHED_OTHER
