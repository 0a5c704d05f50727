"""Watch processes rosreconf did not start for their exit, in milliseconds, and for being stopped.

A DDS lease says a killed node is gone after 20 s (Fast DDS); the kernel says it at once. A
pidfd (``pidfd_open``, Linux 5.3) becomes readable when its process exits, whoever its
parent is, and it names one process for ever: a recycled pid is never mistaken for it. So
``ProcessWatch.poll`` sleeps in ``select.poll`` on every watched pidfd and wakes on the first
exit. Without pidfds (older kernels, other systems) it checks /proc every ``FALLBACK_STEP``.

A process stopped by SIGSTOP (or under a tracer) never exits, and its lease runs out only
after 20 s: nothing on the network says it is hung sooner. Its state letter in
/proc/<pid>/stat (``T``, ``t``) does, so a poll reads it for every watched process every
``STOP_EVERY`` s while it waits.
"""

from __future__ import annotations

import os
import select
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.procs.procstat import PROC, read_stat
from rosreconf.ros.ros2.hostprocs import ProcId, read_proc_id

FALLBACK_STEP = 0.02
"""Seconds between /proc checks when pidfds are not available."""

STOP_EVERY = 0.05
"""Seconds between reads of the watched processes' states during a wait (a stop is seen
within this; reading one /proc/<pid>/stat takes microseconds)."""

STOPPED_STATES = frozenset("Tt")
"""/proc/<pid>/stat states of a process that runs no code until continued."""


def pidfd_supported() -> bool:
    """Return True when this Python and kernel give pidfds."""
    if not hasattr(os, "pidfd_open"):
        return False
    try:
        os.close(os.pidfd_open(os.getpid()))
    except OSError:
        return False
    return True


def open_pidfd(proc: ProcId, proc_root: Path = PROC) -> int | None:
    """Return a pidfd for exactly ``proc`` (None: it has exited, or its pid is another's now).

    The start time is read after the pidfd is opened: equal, the pidfd names ``proc``.
    """
    try:
        fd = os.pidfd_open(proc.pid)
    except OSError:
        return None
    if read_proc_id(proc.pid, proc_root) != proc:
        os.close(fd)
        return None
    return fd


def proc_state(pid: int, proc_root: Path = PROC) -> str | None:
    """Return a process's state letter (``R``, ``S``, ``T``, ``Z``...), None when gone."""
    stat = read_stat(pid, proc_root)
    return None if stat is None else stat.state


@dataclass(frozen=True)
class WatchEvents:
    """What changed during one poll.

    Attributes:
        exited: watched processes that exited (no longer watched afterwards).
        stopped: processes found stopped (SIGSTOP, a tracer) that were running before.
        resumed: processes found running again after being reported stopped.
        at: ``time.monotonic()`` when the poll returned (to measure detection times).
    """

    exited: tuple[ProcId, ...] = ()
    stopped: tuple[ProcId, ...] = ()
    resumed: tuple[ProcId, ...] = ()
    at: float = 0.0

    def __bool__(self) -> bool:
        return bool(self.exited or self.stopped or self.resumed)


@dataclass
class ProcessWatch:
    """Processes watched for exit (pidfd, else /proc polling) and for being stopped.

    Not thread safe; close it (or use ``with``) to give the pidfds back.

    Attributes:
        use_pidfd: None picks pidfds when the kernel has them; False forces /proc polling.
    """

    use_pidfd: bool | None = None
    proc_root: Path = PROC
    _fds: dict[ProcId, int] = field(default_factory=dict, repr=False)
    _by_fd: dict[int, ProcId] = field(default_factory=dict, repr=False)
    _watched: set[ProcId] = field(default_factory=set, repr=False)
    _stopped: set[ProcId] = field(default_factory=set, repr=False)
    _gone: list[ProcId] = field(default_factory=list, repr=False)
    _poller: select.poll = field(default_factory=select.poll, repr=False)

    def __post_init__(self) -> None:
        if self.use_pidfd is None:
            self.use_pidfd = pidfd_supported()

    def __enter__(self) -> ProcessWatch:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @property
    def watched(self) -> frozenset[ProcId]:
        """Return the processes watched now."""
        return frozenset(self._watched)

    def add(self, proc: ProcId) -> bool:
        """Watch ``proc``; False when it is gone already (the next poll reports it exited)."""
        if proc in self._watched:
            return True
        self._watched.add(proc)
        if self.use_pidfd:
            fd = open_pidfd(proc, self.proc_root)
            if fd is None:
                self._gone.append(proc)
                return False
            self._fds[proc] = fd
            self._by_fd[fd] = proc
            self._poller.register(fd, select.POLLIN)
            return True
        if read_proc_id(proc.pid, self.proc_root) != proc:
            self._gone.append(proc)
            return False
        return True

    def add_all(self, procs: Iterable[ProcId]) -> None:
        """Watch every process of ``procs``."""
        for p in procs:
            self.add(p)

    def remove(self, proc: ProcId) -> None:
        """Stop watching ``proc`` (its pidfd is closed)."""
        self._watched.discard(proc)
        self._stopped.discard(proc)
        fd = self._fds.pop(proc, None)
        if fd is not None:
            self._poller.unregister(fd)
            del self._by_fd[fd]
            os.close(fd)

    def close(self) -> None:
        """Stop watching everything."""
        for proc in list(self._watched):
            self.remove(proc)

    def poll(self, timeout: float) -> WatchEvents:
        """Wait at most ``timeout`` s for a watched process to exit, stop or resume.

        Returns at the first exit (milliseconds: the kernel wakes the wait); stops and
        resumes are read every ``STOP_EVERY`` s of the wait, so a long timeout still sees a
        SIGSTOP within that.
        """
        deadline = time.monotonic() + timeout
        while True:
            exited = list(self._gone)
            self._gone.clear()
            if not exited:
                exited = self._wait(min(STOP_EVERY, max(0.0, deadline - time.monotonic())))
            for proc in exited:
                self.remove(proc)
            stopped, resumed = self._states()
            now = time.monotonic()
            if exited or stopped or resumed or now >= deadline:
                return WatchEvents(tuple(exited), tuple(stopped), tuple(resumed), now)

    def _states(self) -> tuple[list[ProcId], list[ProcId]]:
        """Return the watched processes newly stopped and newly running again."""
        stopped: list[ProcId] = []
        resumed: list[ProcId] = []
        for proc in sorted(self._watched):
            state = proc_state(proc.pid, self.proc_root)
            if state is None or state in "ZX":
                continue  # exiting: the pidfd or the next wait reports it
            if state in STOPPED_STATES and proc not in self._stopped:
                self._stopped.add(proc)
                stopped.append(proc)
            elif state not in STOPPED_STATES and proc in self._stopped:
                self._stopped.discard(proc)
                resumed.append(proc)
        return stopped, resumed

    def _wait(self, timeout: float) -> list[ProcId]:
        """Return the processes that exited within ``timeout`` s (empty: none did)."""
        if self.use_pidfd:
            ready = self._poller.poll(max(0, int(timeout * 1000)))
            return [self._by_fd[fd] for fd, _ in ready if fd in self._by_fd]
        deadline = time.monotonic() + timeout
        while True:
            gone = [p for p in self._watched if not _alive(p, self.proc_root)]
            if gone or time.monotonic() >= deadline:
                return gone
            time.sleep(min(FALLBACK_STEP, max(0.0, deadline - time.monotonic())))


def _alive(proc: ProcId, proc_root: Path) -> bool:
    """Return True while ``proc`` runs (a zombie has exited; a recycled pid is another's)."""
    if read_proc_id(proc.pid, proc_root) != proc:
        return False
    return proc_state(proc.pid, proc_root) not in ("Z", "X", None)
