"""Run every external program rosreconf needs (planners, graphviz, roslaunch) the same way.

One function owns the subprocess so that each rule below holds for all of them:

- an argument list, never a shell, so no file or component name is ever interpreted;
- a new session (``start_new_session=True``), so the program and everything it forks form one
  process group that can be signalled as a whole, and a terminal's Ctrl-C reaches rosreconf
  only, which then decides what to stop;
- a wall-clock timeout that stops the whole group: SIGTERM, a short grace, then SIGKILL, which
  also ends children that ignore SIGTERM; a KeyboardInterrupt or SIGTERM that reaches
  rosreconf while it waits stops the group the same way and is then re-raised;
- after every run, whatever is left of the group (a daemon the program forked) is killed;
- the group dies with rosreconf, even when rosreconf is killed with SIGKILL and no cleanup
  code can run (Linux): the program gets ``PR_SET_PDEATHSIG`` (SIGKILL), and because that
  signal reaches only the program and not the workers it forks (Fast Downward's driver runs
  its translator and search as children), a watchdog forked into the group before ``exec``
  waits on a pipe whose only writer is rosreconf; when the pipe closes without a word, the
  watchdog kills the whole group;
- optional address-space and CPU-time limits, set with ``setrlimit`` in the child; those, the
  parent-death signal and the watchdog are all the ``preexec_fn`` does;
- stdout and stderr go to anonymous temporary files (no pipe can fill up and block the
  program) and only their last ``max_output_bytes`` are kept;
- an executable that does not exist is a result (``missing``), not an exception, so that a
  planner adapter can say which package to install; ``ProgramResult.check`` turns any failure
  into an ``ExternalToolError`` for callers that only want success.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import FrameType
from typing import IO

from rosreconf.errors import ExternalToolError

GRACE_SECONDS = 0.5
"""How long a stopped program gets between SIGTERM and SIGKILL."""

MAX_OUTPUT_BYTES = 1 << 20
"""How much of each output stream is kept by default (its last MiB)."""

MISSING_RETURNCODE = 127
"""The return code reported for a program that could not be found (the shells' convention)."""


class Terminated(SystemExit):
    """Stop rosreconf cleanly when it receives SIGTERM while a program or a workdir is live.

    Raised from a SIGTERM handler that ``run_program`` and ``private_workdir`` install in the
    main thread (only when SIGTERM still has its default action), so that ``finally`` blocks
    kill the program's group and remove temp dirs. It is a ``SystemExit`` with code 143
    (128 + SIGTERM), so an uncaught one ends rosreconf the way the shell expects, silently.
    """


@dataclass(frozen=True)
class ProgramResult:
    """Describe how one run of an external program ended.

    Attributes:
        argv: the argument list that was run.
        returncode: the exit status; negative (``-signal``) when a signal ended the program;
            ``MISSING_RETURNCODE`` when it could not be found.
        stdout: the (tail of the) standard output, decoded as UTF-8 with replacements.
        stderr: the (tail of the) standard error, decoded likewise.
        elapsed: wall-clock seconds from start to the end of the group.
        timed_out: rosreconf stopped the program because the timeout passed.
        missing: the executable (or its script interpreter) does not exist.
        truncated: an output stream was longer than the bytes kept.
    """

    argv: tuple[str, ...]
    returncode: int
    stdout: str
    stderr: str
    elapsed: float
    timed_out: bool = False
    missing: bool = False
    truncated: bool = False

    @property
    def ok(self) -> bool:
        """Tell whether the program ran and exited 0 within its time."""
        return not (self.missing or self.timed_out) and self.returncode == 0

    @property
    def signal(self) -> signal.Signals | None:
        """Return the signal that ended the program, if one did."""
        if self.returncode >= 0:
            return None
        try:
            return signal.Signals(-self.returncode)
        except ValueError:
            return None

    def check(self) -> ProgramResult:
        """Return self if the program succeeded; otherwise raise ``ExternalToolError``."""
        name = self.argv[0]
        if self.missing:
            raise ExternalToolError(f"{name} was not found (is it installed and on PATH?)")
        if self.timed_out:
            raise ExternalToolError(f"{name} did not finish within {self.elapsed:.1f} s")
        if self.returncode != 0:
            how = f"signal {self.signal.name}" if self.signal else f"exit code {self.returncode}"
            last = self.stderr.strip().splitlines()[-1:] or ["no error output"]
            raise ExternalToolError(f"{name} failed with {how}: {last[0]}")
        return self


def run_program(
    argv: Sequence[str],
    *,
    timeout: float,
    memory_limit_mb: int | None = None,
    cpu_limit_s: int | None = None,
    cwd: Path | None = None,
    stdin: bytes | None = None,
    env: Mapping[str, str] | None = None,
    max_output_bytes: int = MAX_OUTPUT_BYTES,
) -> ProgramResult:
    """Run ``argv`` in its own process group and make sure none of the group outlives the call.

    Args:
        argv: the program and its arguments; ``argv[0]`` is looked up on PATH.
        timeout: wall-clock seconds before the group is stopped (``timed_out``).
        memory_limit_mb: RLIMIT_AS of the program (inherited by its children), or no limit.
        cpu_limit_s: RLIMIT_CPU of the program: SIGXCPU at the limit, SIGKILL a second later.
        cwd: working directory (it must exist); default: the current one.
        stdin: bytes fed to the program; default: an empty stdin (``/dev/null``).
        env: the program's whole environment; default: rosreconf's.
        max_output_bytes: how many trailing bytes of each output stream to keep.

    Raises:
        ExternalToolError: ``cwd`` does not exist, or the program exists but cannot be run.
        KeyboardInterrupt, Terminated: re-raised after the group has been killed.
    """
    if not argv:
        raise ValueError("run_program needs a program to run")
    if timeout <= 0:
        raise ValueError(f"timeout must be positive, got {timeout}")
    if cwd is not None and not Path(cwd).is_dir():
        raise ExternalToolError(f"cannot run {argv[0]}: no directory {cwd}")
    args = tuple(str(a) for a in argv)
    with (
        _sigterm_raises(),
        tempfile.TemporaryFile() as out,
        tempfile.TemporaryFile() as err,
        tempfile.TemporaryFile() as inp,
    ):
        if stdin is not None:
            inp.write(stdin)
            inp.seek(0)
        start = time.monotonic()
        alive_read, alive_write = os.pipe() if _LINUX else (-1, -1)
        try:
            proc = subprocess.Popen(
                args,
                stdin=inp if stdin is not None else subprocess.DEVNULL,
                stdout=out,
                stderr=err,
                cwd=cwd,
                env=None if env is None else dict(env),
                start_new_session=True,
                pass_fds=(alive_read,) if _LINUX else (),
                preexec_fn=_preexec(memory_limit_mb, cpu_limit_s, alive_read),
            )
        except FileNotFoundError:
            return ProgramResult(args, MISSING_RETURNCODE, "", "", 0.0, missing=True)
        except OSError as exc:
            raise ExternalToolError(f"cannot run {args[0]}: {exc.strerror or exc}") from exc
        finally:
            if _LINUX:
                os.close(alive_read)  # the write end closes when rosreconf ends, however
                _ALIVE_PIPES.append(alive_write)
        timed_out = False
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            _stop_group(proc)
        except BaseException:  # KeyboardInterrupt, Terminated: stop the group, then re-raise
            _stop_group(proc)
            raise
        finally:
            _signal_group(proc.pid, signal.SIGKILL)  # leftovers, e.g. a forked daemon
            if _LINUX:
                _release(alive_write)  # after the kill: the watchdog died with its group
        elapsed = time.monotonic() - start
        stdout, cut_out = _tail(out, max_output_bytes)
        stderr, cut_err = _tail(err, max_output_bytes)
    return ProgramResult(
        args,
        proc.returncode,
        stdout,
        stderr,
        elapsed,
        timed_out=timed_out,
        truncated=cut_out or cut_err,
    )


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
        self, argv: tuple[str, ...], process: subprocess.Popen[bytes], log: Path | None = None
    ) -> None:
        self.argv = argv
        self.process = process
        self.pids: set[int] = set()
        self.log = log
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
    """Stop several ``Background`` programs: signal all, share one ``grace``, then kill all."""
    for prog in programs:
        if prog.process.poll() is None:
            prog.remember()
            _signal_group(prog.process.pid, signal.Signals(sig))
    deadline = time.monotonic() + grace
    for prog in programs:
        with contextlib.suppress(subprocess.TimeoutExpired):
            prog.process.wait(timeout=max(0.0, deadline - time.monotonic()))
        for pid in (prog.process.pid, *prog.pids):
            _signal_group(pid, signal.SIGKILL)
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGKILL)
        prog.process.wait()


def start_program(
    argv: Sequence[str], *, log: Path, env: Mapping[str, str] | None = None, cwd: Path | None = None
) -> Background:
    """Start ``argv`` in a new session with output to ``log``; the caller must ``stop`` it.

    The same rules as ``run_program`` (argument list, new session, the whole group killed at
    the end) hold, but the program keeps running after the call: use it for roslaunch.

    Raises:
        ExternalToolError: the program is missing or cannot be run.
    """
    args = tuple(str(a) for a in argv)
    with log.open("ab") as out:
        try:
            proc = subprocess.Popen(
                args, stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT, cwd=cwd,
                env=None if env is None else dict(env), start_new_session=True,
            )  # fmt: skip
        except FileNotFoundError:
            raise ExternalToolError(f"{args[0]} was not found (is it installed?)") from None
        except OSError as exc:
            raise ExternalToolError(f"cannot run {args[0]}: {exc.strerror or exc}") from exc
    return Background(args, proc, log)


def descendants(root: int) -> set[int]:
    """Return the pids of every living process below ``root`` (Linux /proc)."""
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError, ValueError, IndexError):
            if entry.name.isdigit():
                text = (entry / "stat").read_text()
                parents[int(entry.name)] = int(text[text.rindex(")") + 2 :].split()[1])
    found: set[int] = set()
    frontier = {root}
    while frontier:
        frontier = {p for p, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


WORKDIR_PREFIX = "rosreconf-"
"""Every temp dir of ours is named ``rosreconf-<pid>-<random>``: recognisable, with its owner."""

_CLEANED: set[str] = set()


def clean_stale_workdirs(parent: Path | None = None) -> list[Path]:
    """Remove temp dirs of ours whose owning process is dead; return what was removed.

    Only directories named ``rosreconf-<pid>-...``, owned by this user, whose ``<pid>`` is
    no living process are removed: a run killed with SIGKILL leaves its Fast Downward files
    behind (megabytes each), and nothing else can ever remove them. Each parent folder is
    scanned once per process.
    """
    where = Path(parent) if parent is not None else Path(tempfile.gettempdir())
    if str(where) in _CLEANED:
        return []
    _CLEANED.add(str(where))
    removed: list[Path] = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(where):
            owner = _owner_pid(entry.name)
            if owner is None or owner == os.getpid() or _alive(owner):
                continue
            with contextlib.suppress(OSError):
                info = entry.stat(follow_symlinks=False)
                if entry.is_dir(follow_symlinks=False) and info.st_uid == os.getuid():
                    shutil.rmtree(entry.path)
                    removed.append(Path(entry.path))
    return removed


def _owner_pid(name: str) -> int | None:
    """Return the pid in a ``rosreconf-<pid>-<random>`` name, or None for any other name."""
    if not name.startswith(WORKDIR_PREFIX):
        return None
    pid, sep, rest = name[len(WORKDIR_PREFIX) :].partition("-")
    return int(pid) if sep and rest and pid.isdigit() and pid[0] != "0" else None


def _alive(pid: int) -> bool:
    """Tell whether a process ``pid`` exists (one of another user's counts as alive)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


@contextlib.contextmanager
def private_workdir(parent: Path | None = None) -> Iterator[Path]:
    """Give a run its own temp dir (mode 0700), removed on every way out of the block.

    The directory is removed on normal exit, on exceptions, on KeyboardInterrupt and on SIGTERM
    (turned into ``Terminated`` while the block runs in the main thread). ``parent`` chooses
    where it is made (default: the system temp dir); tests use it to check nothing is left.
    Its name carries this process's pid, so that a later run can remove it with
    ``clean_stale_workdirs`` if rosreconf is killed (SIGKILL) and no cleanup code runs.
    """
    with _sigterm_raises():
        clean_stale_workdirs(parent)
        path = Path(tempfile.mkdtemp(prefix=f"{WORKDIR_PREFIX}{os.getpid()}-", dir=parent))
        try:
            yield path
        finally:
            shutil.rmtree(path, ignore_errors=True)


_LINUX = sys.platform.startswith("linux")
PR_SET_PDEATHSIG = 1
"""``prctl`` option: the signal a process gets when the thread that started it ends."""

_ALIVE_PIPES: list[int] = []
"""Write ends of the pipes the watchdogs wait on, held until their program's group is dead."""


def _release(fd: int) -> None:
    """Close a watchdog pipe's write end once its group is dead (EOF then means nothing)."""
    with contextlib.suppress(ValueError):
        _ALIVE_PIPES.remove(fd)
    with contextlib.suppress(OSError):
        os.close(fd)


def _preexec(
    memory_limit_mb: int | None, cpu_limit_s: int | None, alive_read: int
) -> Callable[[], None] | None:
    """Return the child's setup: parent-death signal, group watchdog, rlimits (see module doc).

    Everything that needs Python objects is computed here in the parent; the returned
    function only calls ``prctl``, ``fork`` and ``setrlimit``.
    """
    set_limits = _limits(memory_limit_mb, cpu_limit_s)
    if not _LINUX:
        return set_limits
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
        if set_limits is not None:
            set_limits()

    return setup


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


def _limits(memory_limit_mb: int | None, cpu_limit_s: int | None) -> Callable[[], None] | None:
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
        for which, limits in wanted:
            resource.setrlimit(which, limits)

    return set_limits


def _clamp(which: int, soft: int, hard: int) -> tuple[int, int]:
    """Clamp limits to the current hard limit, which an unprivileged child cannot raise."""
    ceiling = resource.getrlimit(which)[1]
    if ceiling == resource.RLIM_INFINITY:
        return soft, hard
    return min(soft, ceiling), min(hard, ceiling)


def _stop_group(proc: subprocess.Popen[bytes]) -> None:
    """Ask the group to stop (SIGTERM), wait a short grace, then kill it (SIGKILL) and reap."""
    try:
        _signal_group(proc.pid, signal.SIGTERM)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=GRACE_SECONDS)
    finally:
        _signal_group(proc.pid, signal.SIGKILL)
        proc.wait()


def _signal_group(pgid: int, sig: signal.Signals) -> None:
    """Send ``sig`` to a process group; a group that is already gone is fine."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, sig)


def _tail(stream: IO[bytes], limit: int) -> tuple[str, bool]:
    """Read the last ``limit`` bytes of a temp file; say whether anything was cut."""
    size = stream.seek(0, os.SEEK_END)
    stream.seek(max(0, size - limit))
    return stream.read().decode("utf-8", errors="replace"), size > limit


def sigterm_raises() -> contextlib.AbstractContextManager[None]:
    """Turn SIGTERM into ``Terminated`` in a block (for loops that own ``Background`` programs)."""
    return _sigterm_raises()


@contextlib.contextmanager
def _sigterm_raises() -> Iterator[None]:
    """Turn SIGTERM into ``Terminated`` while the block runs, so its cleanup code runs.

    Only in the main thread (Python delivers signals there) and only when SIGTERM still has
    its default action: an application's own handler is never replaced, and nested uses are
    no-ops.
    """
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGTERM) != signal.SIG_DFL
    ):
        yield
        return

    def handler(signum: int, frame: FrameType | None) -> None:
        raise Terminated(128 + signum)

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
