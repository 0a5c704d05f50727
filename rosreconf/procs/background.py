"""Own long-running programs (roslaunch) and everything they fork, until they are stopped.

``run_program`` waits for its program; a ``Background`` program keeps running after
``start_program`` returns, under the same rules (an argument list, a new session, SIGINT's
default action): ``stop`` or ``stop_all`` ends it and every process it started, even those
that left its process group with ``setsid``.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
from collections.abc import Mapping, Sequence
from pathlib import Path

from rosreconf.errors import ExternalToolError
from rosreconf.procs.child import ALIVE_PIPES, LINUX, preexec, release
from rosreconf.procs.ladder import climb, wait_all
from rosreconf.procs.procstat import PROC, read_stat
from rosreconf.procs.signals import signal_group


class Background:
    """Own a long-running program (roslaunch) and every process it forks, until ``stop``.

    Programs like roslaunch start their children with ``setsid``, so the children leave the
    program's process group: ``remember`` records every descendant (read from /proc) so that
    ``stop`` can kill their groups too. Call ``remember`` while the program runs (``poll``
    does); ``stop`` calls it once more before signalling.

    Attributes:
        argv: the argument list that was run.
        process: the running program (leader of its own session and group).
        pids: every descendant seen so far.
        log: the file its stdout and stderr go to, if known.
    """

    def __init__(
        self,
        argv: tuple[str, ...],
        process: subprocess.Popen[bytes],
        log: Path | None = None,
        alive: int = -1,
    ) -> None:
        self.argv = argv
        self.process = process
        self.pids: set[int] = set()
        self.log = log
        self.alive = alive
        """The write end of the watchdog's pipe (-1: none), released once the group is dead."""
        self._read_to = 0

    def new_output(self, limit: int = 64 << 10) -> str:
        """Return what the program wrote to its log since the last call (its last ``limit`` bytes).

        For reporting a program's own error messages while it runs: the log may grow
        without bound, so only its tail is read, decoded with replacements (the caller
        must still escape it before showing it).
        """
        if self.log is None:
            return ""
        try:
            with self.log.open("rb") as f:
                size = f.seek(0, os.SEEK_END)
                f.seek(max(self._read_to, size - limit))
                data = f.read(limit)
                self._read_to = f.tell()
        except OSError:
            return ""
        return data.decode("utf-8", errors="replace")

    def remember(self) -> None:
        """Record the program's living descendants, which ``stop`` will also kill."""
        self.pids |= descendants(self.process.pid)

    def poll(self) -> int | None:
        """Return the exit status, or None while it runs (recording its descendants)."""
        self.remember()
        return self.process.poll()

    def stop(self, grace: float = 5.0, sig: signal.Signals = signal.SIGINT) -> int:
        """Ask the program to stop (``sig``: roslaunch stops its nodes on SIGINT), then kill.

        After ``grace`` seconds the program's group and the group of every recorded
        descendant get SIGKILL, so nothing it started outlives this call.
        """
        stop_all([self], grace, sig)
        return self.process.wait()


def stop_all(programs: Sequence[Background], grace: float = 5.0, sig: int = signal.SIGINT) -> None:
    """Stop several ``Background`` programs: signal all, share one ``grace``, then kill all.

    One rung of the ladder (``sig``), then SIGKILL whatever it came to: a program's
    descendants may have left its group (``setsid``) and outlive it, so every recorded one
    is killed too, even when the program itself has ended.
    """

    def send(step: signal.Signals) -> bool:
        running = [prog for prog in programs if prog.process.poll() is None]
        for prog in running:
            prog.remember()
            signal_group(prog.process.pid, step)
        return bool(running)

    def gone(wait: float) -> bool:
        return wait_all([prog.process for prog in programs], wait)

    climb(send, gone, grace, (signal.Signals(sig),))
    for prog in programs:
        for pid in (prog.process.pid, *prog.pids):
            signal_group(pid, signal.SIGKILL)
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGKILL)
        prog.process.wait()
        if prog.alive >= 0:
            release(prog.alive)  # after the kill: the watchdog died with its group
            prog.alive = -1


def start_program(
    argv: Sequence[str], *, log: Path, env: Mapping[str, str] | None = None, cwd: Path | None = None
) -> Background:
    """Start ``argv`` in a new session with output to ``log``; the caller must ``stop`` it.

    The same rules as ``run_program`` (argument list, new session, the whole group killed at
    the end, and on Linux the parent-death signal and the group watchdog of
    ``rosreconf.procs.child``, so the program's group dies with rosreconf even on SIGKILL) hold,
    but the program keeps running after the call: use it for roslaunch and ROS 2 nodes.

    Raises:
        ExternalToolError: the program is missing or cannot be run.
    """
    args = tuple(str(a) for a in argv)
    alive_read, alive_write = os.pipe() if LINUX else (-1, -1)
    with log.open("ab") as out:
        try:
            proc = subprocess.Popen(
                args,
                stdin=subprocess.DEVNULL,
                stdout=out,
                stderr=subprocess.STDOUT,
                cwd=cwd,
                env=None if env is None else dict(env),
                start_new_session=True,
                pass_fds=(alive_read,) if LINUX else (),
                preexec_fn=preexec(None, None, alive_read),
            )
        except FileNotFoundError:
            release(alive_write)
            raise ExternalToolError(f"{args[0]} was not found (is it installed?)") from None
        except OSError as exc:
            release(alive_write)
            raise ExternalToolError(f"cannot run {args[0]}: {exc.strerror or exc}") from exc
        finally:
            if LINUX:
                os.close(alive_read)  # the write end closes when rosreconf ends, however
    if LINUX:
        ALIVE_PIPES.append(alive_write)
    return Background(args, proc, log, alive_write)


def descendants(root: int) -> set[int]:
    """Return the pids of every living process below ``root`` (Linux /proc)."""
    parents: dict[int, int] = {}
    with contextlib.suppress(OSError):
        for entry in os.scandir(PROC):
            stat = read_stat(entry.name) if entry.name.isdigit() else None
            if stat is not None:
                parents[stat.pid] = stat.ppid
    found: set[int] = set()
    frontier = {root}
    while frontier:
        frontier = {p for p, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found
