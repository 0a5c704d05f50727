"""Start rclpy stand-ins as forks of one warm process, ``standin_zygote.py``.

A stand-in started on its own spends about 0.5 s of CPU importing rclpy and the messages
before it does anything (measured on this machine: 0.47 s, and 0.09 s to start the
interpreter, against 0.04 s for ``rclpy.init`` and the node); nine at once on two busy cores
take seconds. The zygote, run once under the ROS 2 Python, has imported them and
forks one child per stand-in on request: still one process, one pid and one DDS participant
per node, in a session of its own, with its output in its log and the command line it would
have had (``pgrep -f '__node:=NSM3'`` finds it). The zygote reaps its children and reports
each exit at once over its stdout; ``Forked`` turns that into what ``subprocess.Popen``
offers (``poll``, ``wait``, ``returncode``), so ``rosreconf.ros.ros2.nodes`` treats a forked
stand-in like any process it started.

A helper's death is not a component's failure: the children outlive the zygote. They die
with rosreconf instead, by a watchdog each forks, waiting on a pipe only rosreconf writes to
(``standin_alive``; see ``standin_zygote.py``). Each child is also held by a pidfd from its
fork on, so that once the zygote has died its exit is still seen at once (its status is then
unknown: ``UNKNOWN_EXIT``), and the next stand-in is forked by a new zygote. Nothing here
prints.

Forking is safe here: the only threads in the zygote at a fork are its libraries' own, each
stopped or guarded by that library's fork hooks (see ``standin_zygote.py``). Kilted's
stand-ins that died of SIGSEGV as they started died of a race inside Fast DDS 3's type
lookup service, in a thread the child starts itself; rosreconf's participants run without
that service (``rosreconf.ros.ros2.runtime.NO_TYPE_LOOKUP``; docs/live.md has the figures).
"""

from __future__ import annotations

import contextlib
import os
import select
import signal
import subprocess
import threading
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.procs.signals import signal_group
from rosreconf.ros.ros2.helper import Helper
from rosreconf.ros.ros2.runtime import ros2_python

ZYGOTE_SCRIPT = Path(__file__).parent / "scripts" / "standin_zygote.py"
TITLE_ROOM = 32768
"""Bytes of argument the zygote is given, for its children's command lines (as its own)."""
DISABLE_ENV = "ROSRECONF_STANDIN_ZYGOTE"
"""Set to ``0`` to start every stand-in as a process of its own (as before the zygote)."""
ALIVE_ENV = "ROSRECONF_STANDIN_ALIVE_FD"
UNKNOWN_EXIT = 255
"""The exit status said of a stand-in that ended after its zygote: nobody could reap it."""
_ALIVE: list[int] = []


def standin_alive() -> int:
    """Return the read end of the pipe the stand-ins' watchdogs wait on (made once).

    Its write end stays open, in this process only, until rosreconf ends: then the kernel
    closes it and every stand-in's watchdog kills its stand-in, however rosreconf ended.
    """
    if not _ALIVE:
        _ALIVE.extend(os.pipe())
    return _ALIVE[0]


def _pidfd(pid: int) -> int | None:
    """Return a pidfd for ``pid`` (None where there are none: then only the zygote tells)."""
    try:
        return os.pidfd_open(pid)
    except (AttributeError, OSError):
        return None


class Forked:
    """A stand-in forked by the zygote, seen as ``subprocess.Popen`` would show it."""

    def __init__(self, pid: int, zygote: Zygote) -> None:
        self.pid = pid
        self.returncode: int | None = None
        self.said: int | None = None
        """How it ended as the zygote said it (set by ``Zygote``, under its lock)."""
        self._zygote = zygote
        self._fd = _pidfd(pid)

    def _ended(self, code: int | None) -> int | None:
        if code is not None:
            self.returncode = code
            if self._fd is not None:
                os.close(self._fd)
                self._fd = None
        return self.returncode

    def _orphan_ended(self, timeout: float | None) -> bool:
        """Tell whether it ended, read from its pidfd (after the zygote died)."""
        if self._fd is None:
            return True  # no way to tell: taken as gone, as the zygote said before
        return bool(select.select([self._fd], [], [], timeout)[0])

    def poll(self) -> int | None:
        """Return the exit status, or None while it runs."""
        if self.returncode is None:
            code = self._zygote.code(self)
            if code is None and self._zygote.gone and self._orphan_ended(0.0):
                late = self._zygote.code(self)  # said just before the zygote ended
                code = UNKNOWN_EXIT if late is None else late
            self._ended(code)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        """Wait until it has ended; return the exit status.

        Raises:
            subprocess.TimeoutExpired: still running after ``timeout`` seconds.
        """
        if self.returncode is None:
            code = self._zygote.wait(self, timeout)
            if code is None:  # the zygote died before it: its pidfd tells
                if not self._orphan_ended(timeout):
                    raise subprocess.TimeoutExpired(str(self.pid), timeout or 0.0)
                code = UNKNOWN_EXIT
            self._ended(code)
        assert self.returncode is not None
        return self.returncode


class ForkedProgram:
    """One forked stand-in, as ``rosreconf.procs.Background`` offers a program it started."""

    def __init__(self, process: Forked, argv: tuple[str, ...], log: Path) -> None:
        self.process = process
        self.argv = argv
        self.log = log

    def remember(self) -> None:
        """Nothing to record: a stand-in forks no processes of its own."""

    def stop(self, grace: float = 5.0, sig: signal.Signals = signal.SIGINT) -> int:
        """Signal its group, wait ``grace`` seconds, then SIGKILL it; return the exit status."""
        if self.process.poll() is None:  # never signal a pid that may be reused already
            signal_group(self.process.pid, sig)
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.process.wait(grace)
            if self.process.poll() is None:
                signal_group(self.process.pid, signal.SIGKILL)
        return self.process.wait()


class Zygote(Helper):
    """Own the zygote process: ask it for stand-ins, hear of their exits (module docstring)."""

    close_wait = 2.0

    def __init__(self, env: Mapping[str, str], log: Path) -> None:
        self._running: dict[int, Forked] = {}
        """The children not yet said to have ended, by pid: a pid is one child's at a time."""
        self._early: dict[int, int] = {}
        """Exits said before ``spawn`` took their fork's answer (the reader runs ahead)."""
        self._gone = False
        self._changed = threading.Condition()
        self._next = 0
        self.orphans: list[ForkedProgram] = []
        python = ros2_python(env)
        argv = [python, str(ZYGOTE_SCRIPT), " " * TITLE_ROOM]
        alive = standin_alive()
        name = f"the stand-in zygote ({python} {ZYGOTE_SCRIPT.name})"
        super().__init__(argv, {**env, ALIVE_ENV: str(alive)}, log, name, keep_fds=(alive,))

    def heard(self, said: dict[str, Any]) -> bool:
        """Take a child's exit, which is news, not an answer.

        The exit is that of the child holding that pid now: the kernel gives a pid again only
        once the zygote has reaped its last holder, and the zygote says that exit before it
        answers a later fork, so one child's exit is never taken for a later child's with
        the same pid (pids wrap at ``pid_max``: here after about 1,600 stand-in starts).
        """
        if "exited" not in said:
            return False
        pid, code = int(said["exited"]), int(said["code"])
        with self._changed:
            child = self._running.pop(pid, None)
            if child is None:
                self._early[pid] = code
            else:
                child.said = code
            self._changed.notify_all()
        return True

    def _adopt(self, child: Forked) -> None:
        """Hold ``child`` as the one running with its pid (its exit may be said already)."""
        with self._changed:
            code = self._early.pop(child.pid, None)
            if code is None:
                self._running[child.pid] = child
            else:
                child.said = code

    def ended(self) -> None:
        """Note that the zygote is gone (its children run on: their pidfds tell their exits)."""
        with self._changed:
            self._gone = True
            self._changed.notify_all()

    @property
    def gone(self) -> bool:
        """Tell whether the zygote has ended (closed, killed or crashed)."""
        with self._changed:
            return self._gone

    def spawn(
        self, programs: Sequence[tuple[Sequence[str], Path]], timeout: float = 30.0
    ) -> list[ForkedProgram]:
        """Fork one stand-in per (argv, log): all asked for at once, then every pid read.

        Raises:
            ExternalToolError: the zygote has exited, failed to fork, or did not answer
                (the stand-ins it did fork are in ``self.orphans``: stop them).
        """
        first = self._next + 1
        requests = []
        for argv, log in programs:
            self._next += 1
            requests.append({"id": self._next, "argv": list(argv), "log": str(log)})
        self.send(requests)
        forked: dict[int, ForkedProgram] = {}
        failure = None
        for _ in programs:
            answer = self.answer(None, timeout, "fork")
            index = int(answer.get("id", 0)) - first
            if "pid" not in answer:
                failure = failure or str(answer.get("error"))
                continue
            argv, log = programs[index]
            child = Forked(int(answer["pid"]), self)
            self._adopt(child)
            forked[index] = ForkedProgram(child, tuple(argv), log)
        if failure is not None:
            self.orphans = list(forked.values())
            raise ExternalToolError(f"{self.name} cannot fork: {failure}")
        return [forked[i] for i in range(len(programs))]

    def code(self, child: Forked) -> int | None:
        """Return how ``child`` ended as the zygote said it, or None (running, or unsaid)."""
        with self._changed:
            return child.said

    def wait(self, child: Forked, timeout: float | None) -> int | None:
        """Wait until ``child`` has ended; return how, or None if the zygote died first.

        Raises:
            subprocess.TimeoutExpired: it still runs after ``timeout`` seconds.
        """
        with self._changed:
            if not self._changed.wait_for(lambda: child.said is not None or self._gone, timeout):
                raise subprocess.TimeoutExpired(str(child.pid), timeout or 0.0)
            return child.said
