"""Under a memory cap, run the CLI in a forked child, so that dying of memory is still exit 3.

Python's ``MemoryError`` is exit 3 with one line (``app.guard``). But under an address-space
cap (``ulimit -v``, ``prlimit --as``) an allocation can also fail inside C++: clingo then ends
the process through ``std::terminate`` and ``abort`` (seen: "error in
SolveEventHandler::on_statistics going to terminate", SIGABRT, exit 134 or 1, empty stdout, no
word from rosreconf); under a cgroup's ``memory.max`` the kernel sends SIGKILL. A process cannot
outlive its own abort: glibc raises SIGABRT again once any handler returns, and a Python
handler would only run between bytecodes, too late. So, only when such a cap is in force, the
process forks before doing anything (no ``exec``: the child is this very interpreter, about a
millisecond, where starting Python again costs ~0.1 s), and the parent waits for the child:

- the child's exit status is the parent's, and a signal that ended it ends the parent;
- a child killed by SIGABRT, SIGKILL, SIGSEGV or SIGBUS that nobody sent through the parent is
  out of memory: the one-line ``OUT_OF_MEMORY``, exit 3; stdout, when it is a file, is cut back
  to where it was, so it holds no half document (a pipe cannot be taken back);
- SIGINT, SIGTERM, SIGHUP and SIGQUIT sent to the parent's pid are passed on (not those the
  terminal sent to the whole group: the child has those already), so ``watch``'s 130/143
  (``rosreconf.cli.stopping``) stay as they are; the child dies with the parent (SIGKILL).

Without a cap nothing forks: the kernel's OOM killer then sends SIGKILL, which no one can
turn into a message.
"""

from __future__ import annotations

import contextlib
import os
import resource
import signal
import stat
import sys
from collections.abc import Callable
from pathlib import Path

OUT_OF_MEMORY = (
    "rosreconf: error: out of memory: this run needs more than the machine or its limits "
    "(ulimit -v) allow; ask for less (--limit, --only, a smaller library) or allow more"
)
"""The one line an exhausted memory ends with (exit 3: not a failed check, not usage)."""
OUT_OF_MEMORY_EXIT = 3
CHILD_ENV = "ROSRECONF_CAPPED_CHILD"
"""Set in the child (and so in whatever it starts): a nested rosreconf does not fork again."""
PASSED_ON = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)
MEMORY_DEATHS = (signal.SIGABRT, signal.SIGKILL, signal.SIGSEGV, signal.SIGBUS)
_PR_SET_PDEATHSIG = 1
_NO_CGROUP_LIMIT = 1 << 62
"""cgroup v1 shows "no limit" as a huge number (a page-rounded LONG_MAX)."""
_SI_USER, _SI_QUEUE, _SI_TKILL = 0, -1, -6
"""``si_code`` of a signal sent by a process (kill, sigqueue, tgkill), not by the terminal."""


def memory_capped() -> bool:
    """Tell whether an address-space, data or cgroup (v2 ``memory.max``, v1) limit is in force."""
    for limit in (resource.RLIMIT_AS, resource.RLIMIT_DATA):
        if resource.getrlimit(limit)[0] != resource.RLIM_INFINITY:
            return True
    try:
        lines = Path("/proc/self/cgroup").read_text(encoding="ascii").splitlines()
    except OSError:
        return False
    for line in lines:
        _, controllers, group = line.split(":", 2)
        if controllers == "":
            where = Path("/sys/fs/cgroup", group.lstrip("/"), "memory.max")
        elif "memory" in controllers.split(","):
            where = Path("/sys/fs/cgroup/memory", group.lstrip("/"), "memory.limit_in_bytes")
        else:
            continue
        with contextlib.suppress(OSError, ValueError):
            cap = where.read_text(encoding="ascii").strip()
            if cap != "max" and int(cap) < _NO_CGROUP_LIMIT:
                return True
    return False


_start: list[int | None] = [None]
"""Where stdout, a regular file, was when the run began."""


def run(main: Callable[[], object]) -> None:
    """Run ``main``, in a forked child watched from here when a memory cap is in force."""
    start = _start[0] = _stdout_position()
    if os.environ.get(CHILD_ENV) or not hasattr(os, "fork") or not memory_capped():
        main()
        return
    parent = os.getpid()
    signal.pthread_sigmask(signal.SIG_BLOCK, {*PASSED_ON, signal.SIGCHLD})
    child = os.fork()
    if child == 0:
        os.environ[CHILD_ENV] = "1"
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {*PASSED_ON, signal.SIGCHLD})
        _die_with(parent)
        main()
        return
    status = _watch(child, start)
    if status < 0:  # ended by a signal: end by it too, as if there were no parent
        signal.signal(-status, signal.SIG_DFL)
        os.kill(os.getpid(), -status)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {-status})
        status = 128 - status
    os._exit(status)  # the parent wrote nothing buffered; tearing Python down costs ~40 ms


def _die_with(parent: int) -> None:
    """Have the kernel SIGKILL this process when the parent dies (Linux), as the planners do."""
    if sys.platform.startswith("linux"):
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    if os.getppid() != parent:  # the parent died before prctl took effect
        os.kill(os.getpid(), signal.SIGKILL)


def _watch(child: int, start: int | None) -> int:
    """Pass signals on to ``child`` until it ends; return its exit status, or -signal."""
    sent: set[int] = set()
    while True:
        info = signal.sigwaitinfo({*PASSED_ON, signal.SIGCHLD})
        if info.si_signo != signal.SIGCHLD:
            if info.si_code in (_SI_USER, _SI_QUEUE, _SI_TKILL):  # not the terminal's: pass on
                sent.add(info.si_signo)
                with contextlib.suppress(ProcessLookupError):
                    os.kill(child, info.si_signo)
            continue
        pid, status = os.waitpid(child, os.WNOHANG)
        if pid == 0:
            continue
        if os.WIFEXITED(status):
            return os.WEXITSTATUS(status)
        sig = os.WTERMSIG(status)
        if sig in MEMORY_DEATHS and sig not in sent:
            take_back_stdout(start)
            os.write(2, (OUT_OF_MEMORY + "\n").encode())
            return OUT_OF_MEMORY_EXIT
        return -sig


def _stdout_position() -> int | None:
    """Return where stdout, a regular file, is now (to cut back to); None for anything else."""
    try:
        if not stat.S_ISREG(os.fstat(1).st_mode):
            return None
        return os.lseek(1, 0, os.SEEK_CUR)
    except OSError:
        return None


def take_back_stdout(start: int | None = None) -> None:
    """Cut stdout, when a regular file, back to where it was when the run began.

    A run out of memory must not leave half a JSON document; what went down a pipe cannot be
    taken back.
    """
    start = _start[0] if start is None else start
    if start is not None:
        with contextlib.suppress(OSError, ValueError):
            sys.stdout.flush()
        with contextlib.suppress(OSError):
            os.ftruncate(1, start)
            os.lseek(1, start, os.SEEK_SET)
