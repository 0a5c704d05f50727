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
stand-in like any process it started. Children die with the zygote (a parent-death signal),
which dies with rosreconf (``rosreconf.ros.ros2.helper``). Nothing here prints.
"""

from __future__ import annotations

import contextlib
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


class Forked:
    """A stand-in forked by the zygote, seen as ``subprocess.Popen`` would show it."""

    def __init__(self, pid: int, zygote: Zygote) -> None:
        self.pid = pid
        self.returncode: int | None = None
        self._zygote = zygote

    def poll(self) -> int | None:
        """Return the exit status, or None while it runs."""
        if self.returncode is None:
            self.returncode = self._zygote.code(self.pid)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        """Wait until it has ended; return the exit status.

        Raises:
            subprocess.TimeoutExpired: still running after ``timeout`` seconds.
        """
        if self.returncode is None:
            self.returncode = self._zygote.wait(self.pid, timeout)
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
        self._codes: dict[int, int] = {}
        self._gone = False
        self._changed = threading.Condition()
        self._next = 0
        self.orphans: list[ForkedProgram] = []
        python = ros2_python(env)
        argv = [python, str(ZYGOTE_SCRIPT), " " * TITLE_ROOM]
        super().__init__(argv, env, log, f"the stand-in zygote ({python} {ZYGOTE_SCRIPT.name})")

    def heard(self, said: dict[str, Any]) -> bool:
        """Take a child's exit, which is news, not an answer."""
        if "exited" not in said:
            return False
        with self._changed:
            self._codes[int(said["exited"])] = int(said["code"])
            self._changed.notify_all()
        return True

    def ended(self) -> None:
        """Note that the children are gone (their parent-death signal is SIGKILL)."""
        with self._changed:
            self._gone = True
            self._changed.notify_all()

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
            forked[index] = ForkedProgram(Forked(int(answer["pid"]), self), tuple(argv), log)
        if failure is not None:
            self.orphans = list(forked.values())
            raise ExternalToolError(f"{self.name} cannot fork: {failure}")
        return [forked[i] for i in range(len(programs))]

    def code(self, pid: int) -> int | None:
        """Return how child ``pid`` ended, or None while it runs."""
        with self._changed:
            return self._codes.get(pid, -signal.SIGKILL if self._gone else None)

    def wait(self, pid: int, timeout: float | None) -> int:
        """Wait until child ``pid`` has ended; return how.

        Raises:
            subprocess.TimeoutExpired: it still runs after ``timeout`` seconds.
        """
        with self._changed:
            if not self._changed.wait_for(lambda: pid in self._codes or self._gone, timeout):
                raise subprocess.TimeoutExpired(str(pid), timeout or 0.0)
            return self._codes.get(pid, -signal.SIGKILL)
