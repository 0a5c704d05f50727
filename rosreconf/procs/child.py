"""Prepare a program's process between ``fork`` and ``exec``: death signal, watchdog, limits.

This is everything ``run_program``'s ``preexec_fn`` does, and why each piece is there:

- ``PR_SET_PDEATHSIG`` (SIGKILL): the program dies with rosreconf, even when rosreconf is
  killed with SIGKILL and no cleanup code can run (Linux);
- a watchdog forked into the program's group, because that signal reaches only the program
  and not the workers it forks (Fast Downward's driver runs its translator and search as
  children): it waits on a pipe whose only writer is rosreconf, and when the pipe closes
  without a word it kills the whole group;
- SIGINT's default action, when rosreconf runs with SIGINT ignored;
- the address-space and CPU-time limits (``setrlimit``).

Everything that needs Python objects is computed in the parent: the function handed to
``subprocess`` only calls ``prctl``, ``fork``, ``signal`` and ``setrlimit``.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import resource
import signal
import sys
from collections.abc import Callable

from rosreconf.procs.signals import STOPS, sigint_ignored

LINUX = sys.platform.startswith("linux")
"""The parent-death signal and the watchdog exist on Linux only."""

PR_SET_PDEATHSIG = 1
"""``prctl`` option: the signal a process gets when the thread that started it ends."""

ALIVE_PIPES: list[int] = []
"""Write ends of the pipes the watchdogs wait on, held until their program's group is dead."""


def release(fd: int) -> None:
    """Close a watchdog pipe's write end once its group is dead (EOF then means nothing)."""
    with contextlib.suppress(ValueError):
        ALIVE_PIPES.remove(fd)
    with contextlib.suppress(OSError):
        os.close(fd)


def preexec(
    memory_limit_mb: int | None, cpu_limit_s: int | None, alive_read: int
) -> Callable[[], None] | None:
    """Return the child's setup: parent-death signal, group watchdog, rlimits (see module doc).

    Everything that needs Python objects is computed here in the parent; the returned
    function only calls ``prctl``, ``fork`` and ``setrlimit``.
    """
    set_limits = limits(memory_limit_mb, cpu_limit_s)
    reset_sigint = sigint_ignored()
    if not LINUX:
        if not reset_sigint:
            return set_limits

        def portable_setup() -> None:
            signal.signal(signal.SIGINT, signal.SIG_DFL)
            if set_limits is not None:
                set_limits()

        return portable_setup
    prctl = ctypes.CDLL(None, use_errno=True).prctl
    parent = os.getpid()
    max_fd = os.sysconf("SC_OPEN_MAX") if hasattr(os, "sysconf") else 1024

    def setup() -> None:
        prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
        if os.getppid() != parent:  # rosreconf died before prctl took effect
            os.kill(os.getpid(), signal.SIGKILL)
        middle = os.fork()
        if middle == 0:  # fork twice, so that the watchdog is no child of the program
            if os.fork() == 0:
                _watchdog(alive_read, max_fd)
            os._exit(0)
        os.waitpid(middle, 0)
        os.close(alive_read)
        if reset_sigint:
            signal.signal(signal.SIGINT, signal.SIG_DFL)
        if set_limits is not None:
            set_limits()

    return setup


def pool_worker_setup(parent: int) -> None:
    """Make a pool worker die with rosreconf and leave every stop to it (run in the worker).

    The initializer of ``simulate``'s and ``whatif``'s worker processes, for the same reason
    as the planners' setup: a worker gets ``PR_SET_PDEATHSIG`` (SIGKILL), so it dies with
    rosreconf even when rosreconf is killed with SIGKILL (Linux). It ignores SIGINT (a
    terminal's Ctrl-C reaches the whole foreground group; rosreconf alone decides, and
    kills its workers, so no worker prints a traceback) and gets SIGTERM's default action
    back (a forked worker inherits rosreconf's handler, which would raise in it).
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOPS)  # forked with them held (stops_held)
    if LINUX:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    if os.getppid() != parent:  # rosreconf died before prctl took effect
        os.kill(os.getpid(), signal.SIGKILL)


def _watchdog(alive_read: int, max_fd: int) -> None:
    """Wait until rosreconf's end of the pipe closes, then kill this process group; never return.

    Runs in a process forked (twice, so that no program waiting for all of its children waits
    for it) from the child before ``exec``, so it is in the program's group.
    It closes every other descriptor first: it must not hold the program's output files or
    subprocess's exec-status pipe open. When rosreconf ends the program normally it kills the
    group (and this watchdog) before closing its end; an EOF read here therefore means
    rosreconf died without cleaning up.
    """
    try:
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.closerange(0, alive_read)
        os.closerange(alive_read + 1, max_fd)
        while os.read(alive_read, 64):
            pass
        os.killpg(0, signal.SIGKILL)
    finally:
        os._exit(0)


def limits(memory_limit_mb: int | None, cpu_limit_s: int | None) -> Callable[[], None] | None:
    """Compute the rlimits in the parent; return a function that only calls setrlimit."""
    wanted: list[tuple[int, tuple[int, int]]] = []
    if memory_limit_mb is not None:
        size = memory_limit_mb << 20
        wanted.append((resource.RLIMIT_AS, _clamp(resource.RLIMIT_AS, size, size)))
    if cpu_limit_s is not None:  # SIGXCPU at the soft limit, SIGKILL at the hard one
        wanted.append(
            (resource.RLIMIT_CPU, _clamp(resource.RLIMIT_CPU, cpu_limit_s, cpu_limit_s + 1))
        )
    if not wanted:
        return None

    def set_limits() -> None:
        for which, limit in wanted:
            resource.setrlimit(which, limit)

    return set_limits


def _clamp(which: int, soft: int, hard: int) -> tuple[int, int]:
    """Clamp limits to the current hard limit, which an unprivileged child cannot raise."""
    ceiling = resource.getrlimit(which)[1]
    if ceiling == resource.RLIM_INFINITY:
        return soft, hard
    return min(soft, ceiling), min(hard, ceiling)
