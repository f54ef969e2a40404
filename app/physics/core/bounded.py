"""Run one function in a separate process with a wall-clock limit and a memory limit.

For work whose cost depends on what a student typed, such as deriving and compiling the
equations of motion of a typed Lagrangian: it may take too long or grow too large, and the
server must answer whatever it does. :meth:`BoundedRunner.run` runs ``function(*args)`` in a
child process that has a limit on its address space (``RLIMIT_AS``: the memory it may add
to the warm child's, in MB) and on its CPU time (``RLIMIT_CPU``, a backstop should this
process die), waits at most ``timeout_s`` for the answer and kills the child with SIGKILL
otherwise. The function, its arguments and its result must be picklable (a function is
pickled by reference: define it at module level).

Children are forked from one "forkserver" process per server, started once (by
:meth:`BoundedRunner.warm` or the first call) with numpy, sympy and this module already
imported, so a child starts warm without inheriting this process's threads, sockets or files.
Measured on this 2-core machine while other work ran on it (Python 3.11, 20 calls of a function
that returns at once): 11-14 ms at best and a median of 25-45 ms per call through the warm
forkserver, against a median of 0.4-1.2 s for a "spawn" child, which starts a new interpreter
and imports sympy. The forkserver's own imports take about 0.5 s, once; a warm child's address
space is about 176 MB before the function adds its own.

At most ``max_jobs`` calls run at once (the machine's cores); a call beyond that waits up
to ``wait_s`` and is then refused with :class:`WorkBusy`. Outcomes:

* the result, unpickled;
* ``ValueError`` with the function's message if it raised one (a ``ParameterError`` keeps
  its field, path and label);
* :class:`WorkTimeout` / :class:`WorkTooLarge` (both ``ValueError``: the input asked for
  more than its bounds, a 422 for a route) when the limits stop it: the runner's own kill at
  ``timeout_s``, the CPU limit's SIGXCPU, a ``MemoryError``, or a crash (SIGSEGV, SIGABRT, SIGBUS)
  within the address-space limit, which is how a C library fails when ``RLIMIT_AS`` refuses it memory;
* :class:`WorkBusy` also when the child ran out of time after the server's busy scenes paused it for more than
  :data:`BUSY_PAUSED_SHARE` of it, or kept it waiting for a processor for more than :data:`STARVED_SHARE` of the
  time it wanted one (the server's own work took every processor: the child runs on the server's idle time only):
  load, not the input, stopped it (a 429 with Retry-After);
* :class:`WorkInterrupted` when the child was ended by a signal the runner did not send and its
  limits do not raise (SIGTERM, SIGKILL, SIGINT, SIGHUP…: an administrator, the machine's
  out-of-memory killer, a shutdown): nothing is wrong with the input, so try again (a 503 for a route);
* :class:`WorkFailed` for anything else (the function's bug: a 500).

Every call joins its child and closes its pipe and sentinel before returning, whatever
happened; the forkserver reaps the children it forked.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import multiprocessing.forkserver
import os
import pickle
import resource
import signal
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from app.physics.core.parameters import ParameterError

#: Modules imported once in the forkserver so every child starts with them: this module (each
#: child runs :func:`_child_main`), numpy and sympy. Add the module of the functions you run.
#: Python 3.11's forkserver does not preload "__main__" (it never receives the script's path),
#: so a child started from a script re-runs the script's imports: keep entry scripts light.
DEFAULT_PRELOAD = (__name__, "numpy", "sympy")
#: Longest error message passed back from a child (characters).
MAX_MESSAGE_CHARS = 2000
#: How long a child that has answered may take to exit before it is killed (s).
_EXIT_GRACE_S = 2.0


class WorkRefused(ValueError):
    """The work asked for more than its bounds allow (too long or too large)."""


class WorkTimeout(WorkRefused):
    """The work did not finish within its wall-clock limit and was killed."""


class WorkTooLarge(WorkRefused):
    """The work needed more memory, recursion depth or result size than its limits allow."""


class WorkBusy(RuntimeError):
    """All bounded job slots are taken; ``retry_after_s`` (s) says when to try again."""

    def __init__(self, message: str, *, retry_after_s: int) -> None:
        super().__init__(message)
        self.retry_after_s = retry_after_s


class WorkInterrupted(RuntimeError):
    """The child was ended from outside by a signal the runner did not send; ``retry_after_s`` (s): try again then."""

    def __init__(self, message: str, *, signal_number: int, retry_after_s: int = 2) -> None:
        super().__init__(message)
        self.signal_number = signal_number
        self.retry_after_s = retry_after_s


class WorkFailed(RuntimeError):
    """The function raised something other than ``ValueError``, or its process died unexplained."""


_PRELOAD_LOCK = threading.Lock()


def forkserver_context(preload: Sequence[str]) -> multiprocessing.context.ForkServerContext:
    """The forkserver context, its server started with ``preload`` imported if it is not running yet.

    The process has one forkserver: the preload list of whichever user starts it applies (a server's scene-worker
    pool starts it first, with the scenes: app.scenes.host.pool).
    """
    context = multiprocessing.get_context("forkserver")
    with _PRELOAD_LOCK:
        context.set_forkserver_preload(list(preload))
        multiprocessing.forkserver.ensure_running()
    return context


def _address_space_bytes() -> int:
    """This process's current virtual memory size (bytes), from /proc (0 where there is none)."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def _limit_resources(memory_bytes: int, cpu_seconds: int, *, idle_class: bool) -> None:
    """In the child: allow ``memory_bytes`` more address space than now and ``cpu_seconds`` of CPU time, and (with
    ``idle_class``: in a server) run only on processor time the server's own work does not want (Linux's SCHED_IDLE,
    see :func:`_run_on_idle_time`): work a student typed runs at full speed on a quiet machine and never takes a
    class's frames on a busy one (its wall-clock limit still holds)."""
    if idle_class:
        _run_on_idle_time()
    _, hard_as = resource.getrlimit(resource.RLIMIT_AS)
    limit_as = _address_space_bytes() + memory_bytes
    if hard_as != resource.RLIM_INFINITY:
        limit_as = min(limit_as, hard_as)
    resource.setrlimit(resource.RLIMIT_AS, (limit_as, hard_as))
    _, hard_cpu = resource.getrlimit(resource.RLIMIT_CPU)
    soft_cpu = cpu_seconds if hard_cpu == resource.RLIM_INFINITY else min(cpu_seconds, hard_cpu)
    resource.setrlimit(resource.RLIMIT_CPU, (soft_cpu, hard_cpu))


def _run_on_idle_time() -> None:
    """Let this process take only processor time the server's own processes (its scenes) do not want: the idle
    scheduling class, in the server's session. Linux shares the processors fairly between sessions before it looks
    at a session's processes (autogroups), so the child spends the server's share when the server's scenes leave it
    idle, and yields to them at once when they want it; against other programs on the machine the server keeps its
    fair share. Measured on this 2-core machine beside two CPU-bound programs of another session: a busy loop in the
    idle class got 0.57 of a core in its parent's session, and 0.04 in a session of its own at autogroup nice 19
    (what this did before: a derivation then failed as busy on any machine busy with other work)."""
    try:
        os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    except (AttributeError, OSError):  # no SCHED_IDLE (not Linux): the lowest priority instead
        os.nice(19)


def _answer(function: Callable[..., Any], args: tuple[Any, ...]) -> tuple[str, Any]:
    """``(kind, payload)`` for the outcome of ``function(*args)``, never raising."""
    try:
        return ("result", function(*args))
    except ParameterError as exc:
        field, message, *where = exc.carried()
        return ("parameter_error", (field, message[:MAX_MESSAGE_CHARS], *where))
    except ValueError as exc:
        return ("value_error", str(exc)[:MAX_MESSAGE_CHARS])
    except MemoryError:
        return ("memory", "")
    except RecursionError:
        return ("recursion", "")
    except Exception as exc:  # noqa: BLE001 - the function's bug, reported to the caller as WorkFailed
        return ("error", f"{type(exc).__name__}: {exc}"[:MAX_MESSAGE_CHARS])


def _child_main(
    sender: Any,
    function: Callable[..., Any],
    args: tuple[Any, ...],
    memory_bytes: int,
    cpu_seconds: int,
    idle_class: bool,
) -> None:
    """The child: set the limits, run, send one pickled ``(kind, payload)`` and exit.

    SIGHUP, SIGTERM and SIGINT end it as the signal itself, whatever this server inherited (a server started in the
    background ignores SIGINT, one started under ``nohup`` SIGHUP) and whatever Python made of them (SIGINT as a
    KeyboardInterrupt, an exit status 1 the runner could not tell from a crash): an interrupt from outside is reported
    as one (:class:`WorkInterrupted`). SIGINT is set last, so a child whose SIGINT is the default has set all three.
    """
    for number in (signal.SIGHUP, signal.SIGTERM, signal.SIGINT):
        signal.signal(number, signal.SIG_DFL)
    _limit_resources(memory_bytes, cpu_seconds, idle_class=idle_class)
    kind, payload = _answer(function, args)
    try:
        message = pickle.dumps((kind, payload), protocol=pickle.HIGHEST_PROTOCOL)
    except MemoryError:
        message = pickle.dumps(("memory", ""))
    except Exception as exc:  # noqa: BLE001 - an unpicklable result is the function's bug
        message = pickle.dumps(
            ("error", f"the result could not be pickled: {type(exc).__name__}: {exc}"[:MAX_MESSAGE_CHARS])
        )
    with contextlib.suppress(BrokenPipeError):  # the caller has gone (the server stopped): nobody to tell
        sender.send_bytes(message)
    sender.close()


def _reap(process: Any, *, kill: bool, wait: bool = True) -> None:
    """Kill (if asked, or if it outlives its grace) and join ``process``, then release its sentinel.

    Without ``wait`` (the server is stopping) a killed child is left to die on its own: its forkserver reaps it. A
    child in the idle class dies only when the machine gives it a processor, and beside a busy suite that once took
    2 s of the 5 s a Ctrl+C may take, the server's exit waiting on the request thread that waited on the child.
    """
    if process.pid is None:
        return
    if kill:
        # By pid as well: with its forkserver gone, the process object thinks the child has already exited and its
        # own kill() sends nothing, while the child runs on past its limit.
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(process.pid, signal.SIGKILL)
        process.kill()
        if not wait:
            return
    process.join(_EXIT_GRACE_S)
    if process.exitcode is None:
        process.kill()
        process.join()
    process.close()


class BoundedRunner:
    """Runs functions in child processes, at most ``max_jobs`` at once, each bounded in time and memory.

    ``timeout_s`` (s, wall clock) and ``memory_mb`` (MB of address space beyond the warm child's)
    are the defaults for :meth:`run`; ``max_result_mb`` bounds the pickled result; a call finding
    every slot taken waits up to ``wait_s`` (s) before :class:`WorkBusy`. ``preload`` names the
    modules the forkserver imports once (add the module of the functions you run).
    """

    def __init__(
        self,
        *,
        max_jobs: int = 2,
        timeout_s: float = 10.0,
        memory_mb: float = 512.0,
        max_result_mb: float = 16.0,
        wait_s: float = 0.0,
        preload: Sequence[str] = DEFAULT_PRELOAD,
    ) -> None:
        if max_jobs < 1:
            raise ValueError(f"max_jobs: at least 1 (got {max_jobs})")
        _check_limits(timeout_s, memory_mb)
        if not (math.isfinite(max_result_mb) and max_result_mb > 0.0):
            raise ValueError(f"max_result_mb: a finite size > 0 MB (got {max_result_mb})")
        if not (math.isfinite(wait_s) and wait_s >= 0.0):
            raise ValueError(f"wait_s: a finite time ≥ 0 s (got {wait_s})")
        self.max_jobs = max_jobs
        self.timeout_s = timeout_s
        self.memory_mb = memory_mb
        self.max_result_bytes = int(max_result_mb * 2**20)
        self.wait_s = wait_s
        self.preload = tuple(preload)
        self._slots = threading.BoundedSemaphore(max_jobs)
        self._running = 0
        self._running_lock = threading.Lock()

    @property
    def running(self) -> int:
        """Calls holding a slot now."""
        return self._running

    def warm(self) -> None:
        """Start the forkserver now; it imports ``preload`` in the background (about 0.5 s) before its first child."""
        forkserver_context(self.preload)

    def run(
        self,
        function: Callable[..., Any],
        args: Sequence[Any] = (),
        *,
        timeout_s: float | None = None,
        memory_mb: float | None = None,
        what: str = "the work",
    ) -> Any:
        """``function(*args)`` computed in a bounded child process; ``what`` names the work in refusals.

        Raises ``ValueError`` (the function's own), :class:`WorkTimeout`, :class:`WorkTooLarge`, :class:`WorkBusy` (no
        slot, or out of time after the busy server paused it), :class:`WorkInterrupted` (ended from outside, or the
        server stopping) or :class:`WorkFailed`, as the module docstring says.
        """
        timeout_s = self.timeout_s if timeout_s is None else timeout_s
        memory_mb = self.memory_mb if memory_mb is None else memory_mb
        _check_limits(timeout_s, memory_mb)
        acquired = (
            self._slots.acquire(timeout=self.wait_s) if self.wait_s > 0.0 else self._slots.acquire(blocking=False)
        )
        if not acquired:
            retry_after_s = max(1, math.ceil(timeout_s / 2))
            raise WorkBusy(
                f"busy: {self.max_jobs} such jobs are running already; retry in about {retry_after_s} s",
                retry_after_s=retry_after_s,
            )
        with self._running_lock:
            self._running += 1
        try:
            kind, payload = self._run_in_child(function, tuple(args), timeout_s, memory_mb, what)
        finally:
            with self._running_lock:
                self._running -= 1
            self._slots.release()
        return _outcome(kind, payload, memory_mb=memory_mb, what=what)

    def _run_in_child(
        self, function: Callable[..., Any], args: tuple[Any, ...], timeout_s: float, memory_mb: float, what: str
    ) -> tuple[str, Any]:
        context = forkserver_context(self.preload)
        stops = _stops
        receiver, sender = context.Pipe(duplex=False)
        cpu_seconds = math.ceil(timeout_s) + 1
        process = context.Process(
            target=_child_main,
            # Only a server has frames to spare: elsewhere (a test, a benchmark) the child runs as any program does.
            args=(sender, function, args, int(memory_mb * 2**20), cpu_seconds, _live_scenes is not None),
            name="dynlab-bounded",
            daemon=True,
        )
        answered = False
        try:
            try:
                process.start()
            finally:
                sender.close()
            answer_arrived, paused_s = _await_answer(receiver, process, timeout_s)
            if not answer_arrived:
                if paused_s > BUSY_PAUSED_SHARE * timeout_s:  # the machine's doing, not the work's
                    raise WorkBusy(
                        f"{what} was paused for {paused_s:.0f} s of its {timeout_s:g} s "
                        "while the server was busy with live scenes; try again in a minute",
                        retry_after_s=60,
                    )
                running_s, waiting_s = _processor_times_s(process.pid, paused_s=paused_s)
                # Runnable, but other work had every processor (a child that slept never waits).
                if waiting_s > STARVED_SHARE * (running_s + waiting_s) and waiting_s > BUSY_PAUSED_SHARE * timeout_s:
                    raise WorkBusy(
                        f"{what} waited {waiting_s:.2g} s of its {timeout_s:g} s for a processor that other work "
                        "on the server was using; try again in a minute",
                        retry_after_s=60,
                    )
                raise WorkTimeout(
                    f"{what} took longer than its limit of {timeout_s:g} s and was stopped; try something smaller"
                )
            try:
                message = receiver.recv_bytes(self.max_result_bytes)
            except EOFError:
                return _death(process)
            except OSError as exc:  # the message is longer than max_result_bytes
                raise WorkTooLarge(f"{what} gave a result larger than {self.max_result_bytes / 2**20:g} MB") from exc
            answered = True
            return pickle.loads(message)
        finally:
            receiver.close()
            _reap(process, kill=not answered, wait=_stops == stops)


#: While the server is busy, a child computes in turns of :data:`BUSY_RUN_S` with pauses of :data:`BUSY_PAUSE_S`:
#: even in the idle scheduling class it shares the processors' caches and memory with the live scenes (measured: a
#: busy loop in the idle class cost 100 students half a frame a second). Busy: the server's own processes (those of
#: its session outside the idle class: the front and its scene workers) used more than :data:`BUSY_LOAD_PER_CPU` of
#: the machine's processors since the last look, while the server shows live scenes (:data:`_live_scenes`). Other
#: programs on the machine do not count: pausing for them spares no class a frame.
BUSY_LOAD_PER_CPU = 0.5
BUSY_RUN_S = 0.05
BUSY_PAUSE_S = 0.1
#: A child that ran out of time after being paused for more than this share of it was stopped by the machine's load,
#: not by its own size: the caller hears "busy, try again" (:class:`WorkBusy`), not "try something smaller".
BUSY_PAUSED_SHARE = 0.25
#: A child that ran out of time after spending more than this share of the time it wanted a processor waiting for
#: one got almost none: on the server's idle time only, it yields to the server's other work (three CPU-bound
#: processes of the server's session on this 2-core machine left it 8–15 ms of 2 s). Its time says
#: nothing about the size of the work, so the caller hears "busy", not "try something smaller". (Shares of the
#: child's own life: a busy forkserver may start it late.)
STARVED_SHARE = 0.9


def process_stat_fields(pid: int | str | None) -> list[str]:
    """The fields of Linux's ``/proc/<pid>/stat`` after ``comm`` (which may hold spaces and ``)``): state, ppid, pgrp,
    session, … (``proc(5)``'s field n is index n − 3). Raises OSError if the process is gone or cannot be read."""
    with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as stat:
        return stat.read().rsplit(")", 1)[1].split()


def _processor_times_s(pid: int | None, *, paused_s: float = 0.0) -> tuple[float, float]:
    """``(running, waiting)``: seconds process ``pid`` has run on a processor and has been runnable but waiting for
    one (Linux's ``/proc/<pid>/schedstat``, in ns; a stopped or sleeping process is not waiting); zeros where this
    cannot be read. Linux adds a wait to ``schedstat`` only when the wait ends, so a process runnable now that ran
    less than its life (since it was forked, less ``paused_s``) is taken to have waited the rest: an idle-class child
    among busy programs of its own session may not be given a processor once in two seconds (seen: 8 ms run, 14 ms
    waited, in 2 s). The life is the process's own, from its start time: the time a busy forkserver took to fork it
    was no wait of the child's (counting it once turned a 0.1 s timeout into "busy" on a loaded machine)."""
    try:
        with open(f"/proc/{pid}/schedstat", encoding="ascii") as schedstat:
            running_ns, waiting_ns = (int(field) for field in schedstat.read().split()[:2])
        fields = process_stat_fields(pid)  # state … starttime (the 22nd field, in clock ticks since boot)
        with open("/proc/uptime", encoding="ascii") as uptime:
            now_since_boot_s = float(uptime.read().split()[0])
        runnable = fields[0] == "R"
        life_s = now_since_boot_s - int(fields[19]) / os.sysconf("SC_CLK_TCK") - paused_s
    except (OSError, ValueError, IndexError):
        return 0.0, 0.0
    running_s, waiting_s = running_ns / 1e9, waiting_ns / 1e9
    if runnable:
        waiting_s = max(waiting_s, life_s - running_s)
    return running_s, waiting_s


#: Says whether this process's server is showing live scenes now (set by the scene host when it starts; None in a
#: process without one, e.g. a benchmark or a test, whose children neither pause nor run in the idle class: there is
#: no class to spare). A child is paused for the server's load only while it is true: the pauses protect the frames a
#: class is watching, and with none to protect (a server warming its models before anyone came) they would only make
#: a derivation fail as "busy".
_live_scenes: Callable[[], bool] | None = None
#: How long an answer of :data:`_live_scenes` is used (s): a pool asks its workers, so it is asked at most this often.
LIVE_SCENES_CHECK_S = 1.0
_live_scenes_seen: tuple[float, bool] = (-math.inf, True)


def yield_only_to_live_scenes(live_scenes: Callable[[], bool]) -> None:
    """This process is a server: its children run in the idle class, and pause for its load only while
    ``live_scenes()`` says it shows live scenes."""
    global _live_scenes, _live_scenes_seen
    _live_scenes, _live_scenes_seen = live_scenes, (-math.inf, True)


def _showing_live_scenes() -> bool:
    global _live_scenes_seen
    if _live_scenes is None:
        return False
    asked_at, showing = _live_scenes_seen
    now = time.monotonic()
    if now - asked_at >= LIVE_SCENES_CHECK_S:
        try:
            showing = bool(_live_scenes())
        except Exception:  # a host that cannot answer now (a worker restarting): yield, as without a host
            showing = True
        _live_scenes_seen = (now, showing)
    return showing


#: The last look at the server's processes: (when, monotonic s; CPU seconds of each process, by pid), and whether
#: they were busy since the look before.
_server_seen: tuple[float, dict[int, float], bool] = (-math.inf, {}, False)
_SERVER_SEEN_LOCK = threading.Lock()


def _server_processes_cpu_s() -> dict[int, float]:
    """CPU seconds used so far by each process of this process's session outside the idle class (from /proc; empty
    where there is none)."""
    session = os.getsid(0)
    idle_class = getattr(os, "SCHED_IDLE", -1)
    ticks_per_s = os.sysconf("SC_CLK_TCK")
    used: dict[int, float] = {}
    try:
        entries = [entry for entry in os.listdir("/proc") if entry.isdigit()]
    except OSError:
        return used
    for entry in entries:
        try:
            fields = process_stat_fields(entry)  # state ppid pgrp session … utime stime … policy
            if int(fields[3]) != session or int(fields[38]) == idle_class:
                continue
            used[int(entry)] = (int(fields[11]) + int(fields[12])) / ticks_per_s
        except (OSError, ValueError, IndexError):
            continue
    return used


def _server_busy() -> bool:
    """Whether the server's own processes used more than :data:`BUSY_LOAD_PER_CPU` of the processors since the last
    look (looked at most every :data:`LIVE_SCENES_CHECK_S`; after a long quiet spell the first answer averages over
    it, and the next, a second later, is current) while it shows live scenes."""
    global _server_seen
    if not _showing_live_scenes():
        return False
    with _SERVER_SEEN_LOCK:
        seen_at, seen_cpu_s, busy = _server_seen
        now = time.monotonic()
        if now - seen_at >= LIVE_SCENES_CHECK_S:
            cpu_s = _server_processes_cpu_s()
            if math.isfinite(seen_at):
                used_s = sum(max(0.0, spent - seen_cpu_s.get(pid, 0.0)) for pid, spent in cpu_s.items())
                busy = used_s / (now - seen_at) / (os.cpu_count() or 1) > BUSY_LOAD_PER_CPU
            _server_seen = (now, cpu_s, busy)
        return busy


#: Counts the server's stops: a wait begun before the latest one ends at once (its child is killed), so a stop never
#: waits for a derivation's 20 s; calls begun after it run as usual (a test process starts and stops many apps).
_stops = 0


def stop_all_work() -> None:
    """The server is stopping: every bounded call running now ends at once with :class:`WorkInterrupted` and its child
    is killed; later calls in this process (one that starts and stops apps, such as a test's) run as in a process that
    shows no scenes."""
    global _stops, _live_scenes, _live_scenes_seen
    _stops += 1
    _live_scenes, _live_scenes_seen = None, (-math.inf, True)


def _await_answer(receiver: Any, process: Any, timeout_s: float) -> tuple[bool, float]:
    """Wait up to ``timeout_s`` (wall clock) for the child's answer: (whether it is there, seconds the child was
    paused meanwhile). While the server is busy the child is paused (SIGSTOP, then SIGCONT) for :data:`BUSY_PAUSE_S`
    after each :data:`BUSY_RUN_S` it runs. Raises :class:`WorkInterrupted` when the server stops meanwhile
    (:func:`stop_all_work`)."""
    deadline = time.monotonic() + timeout_s
    stops = _stops
    paused_s = 0.0
    while (left := deadline - time.monotonic()) > 0:
        if _stops != stops:
            raise WorkInterrupted("the server is stopping; try again when it is back", signal_number=signal.SIGTERM)
        if receiver.poll(min(left, BUSY_RUN_S if _server_busy() else 0.5)):
            return True, paused_s
        if not _server_busy() or process.pid is None:
            continue
        try:
            os.kill(process.pid, signal.SIGSTOP)
        except ProcessLookupError:
            continue
        pause_started = time.monotonic()
        try:
            time.sleep(min(BUSY_PAUSE_S, max(0.0, deadline - time.monotonic())))
        finally:
            with contextlib.suppress(ProcessLookupError):
                os.kill(process.pid, signal.SIGCONT)
            paused_s += time.monotonic() - pause_started
    return receiver.poll(0), paused_s


def _check_limits(timeout_s: float, memory_mb: float) -> None:
    if not (math.isfinite(timeout_s) and timeout_s > 0.0):
        raise ValueError(f"timeout_s: a finite time > 0 s (got {timeout_s})")
    if not (math.isfinite(memory_mb) and memory_mb > 0.0):
        raise ValueError(f"memory_mb: a finite size > 0 MB (got {memory_mb})")


#: Signals a child raises on itself when its address-space limit refuses it memory (a C library's failed
#: allocation aborts or faults): a crash inside the limit is taken as the limit's doing.
_MEMORY_SIGNALS = (signal.SIGABRT, signal.SIGSEGV, signal.SIGBUS)


def _death(process: Any) -> tuple[str, Any]:
    """``(kind, payload)`` for a child that closed its pipe without answering, from its exit status.

    The runner kills a child only after it has given up on it (its timeout), so a child found dead
    here was ended by its own limits (SIGXCPU, or a memory signal) or from outside (any other signal).
    """
    process.join(_EXIT_GRACE_S)
    code = process.exitcode
    if code == -signal.SIGXCPU:
        return ("timeout_cpu", "")
    if code is not None and code < 0 and -code in _MEMORY_SIGNALS:
        return ("memory_signal", code)
    if code is not None and code < 0:
        return ("interrupted", -code)
    return ("died", code)


def _outcome(kind: str, payload: Any, *, memory_mb: float, what: str) -> Any:
    """The result for ``kind == "result"``, else the exception that says what happened."""
    if kind == "result":
        return payload
    if kind == "parameter_error":
        raise ParameterError.from_carried(payload)
    if kind == "value_error":
        raise ValueError(payload)
    if kind == "memory":
        raise WorkTooLarge(f"{what} needed more than its memory limit of {memory_mb:g} MB; try something smaller")
    if kind == "recursion":
        raise WorkTooLarge(f"{what} nested deeper than Python's recursion limit; try something smaller")
    if kind == "timeout_cpu":
        raise WorkTimeout(f"{what} used more than its CPU time limit and was stopped; try something smaller")
    if kind == "memory_signal":
        raise WorkTooLarge(
            f"{what} stopped abnormally (signal {-payload}) within its memory limit of {memory_mb:g} MB, "
            "most likely for want of memory; try something smaller"
        )
    if kind == "interrupted":
        raise WorkInterrupted(
            f"{what} was stopped by the system (signal {_signal_name(payload)}), not by its limits; try again",
            signal_number=payload,
        )
    if kind == "died":
        raise WorkFailed(f"{what} ended without an answer (exit status {payload})")
    raise WorkFailed(f"{what} failed: {payload}")


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return str(number)
