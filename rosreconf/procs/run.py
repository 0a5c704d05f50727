"""Run an external program to its end: ``run_program`` and the ``ProgramResult`` it returns.

The rules every run follows are listed in the ``rosreconf.procs`` docstring; this module holds
the waiting, the timeout (SIGTERM to the group, a short grace, then SIGKILL), the kill of
whatever is left of the group afterwards, and the tails of the program's output.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import tempfile
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO

from rosreconf.errors import ExternalToolError
from rosreconf.procs.child import ALIVE_PIPES, LINUX, preexec, release
from rosreconf.procs.signals import signal_group, sigterm_raises

GRACE_SECONDS = 0.5
"""How long a stopped program gets between SIGTERM and SIGKILL."""

MAX_OUTPUT_BYTES = 1 << 20
"""How much of each output stream is kept by default (its last MiB)."""

MISSING_RETURNCODE = 127
"""The return code reported for a program that could not be found (the shells' convention)."""


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
        sigterm_raises(),
        tempfile.TemporaryFile() as out,
        tempfile.TemporaryFile() as err,
        tempfile.TemporaryFile() as inp,
    ):
        if stdin is not None:
            inp.write(stdin)
            inp.seek(0)
        start = time.monotonic()
        alive_read, alive_write = os.pipe() if LINUX else (-1, -1)
        try:
            proc = subprocess.Popen(
                args,
                stdin=inp if stdin is not None else subprocess.DEVNULL,
                stdout=out,
                stderr=err,
                cwd=cwd,
                env=None if env is None else dict(env),
                start_new_session=True,
                pass_fds=(alive_read,) if LINUX else (),
                preexec_fn=preexec(memory_limit_mb, cpu_limit_s, alive_read),
            )
        except FileNotFoundError:
            return ProgramResult(args, MISSING_RETURNCODE, "", "", 0.0, missing=True)
        except OSError as exc:
            raise ExternalToolError(f"cannot run {args[0]}: {exc.strerror or exc}") from exc
        finally:
            if LINUX:
                os.close(alive_read)  # the write end closes when rosreconf ends, however
                ALIVE_PIPES.append(alive_write)
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
            signal_group(proc.pid, signal.SIGKILL)  # leftovers, e.g. a forked daemon
            if LINUX:
                release(alive_write)  # after the kill: the watchdog died with its group
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


def _stop_group(proc: subprocess.Popen[bytes]) -> None:
    """Ask the group to stop (SIGTERM), wait a short grace, then kill it (SIGKILL) and reap."""
    try:
        signal_group(proc.pid, signal.SIGTERM)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=GRACE_SECONDS)
    finally:
        signal_group(proc.pid, signal.SIGKILL)
        proc.wait()


def _tail(stream: IO[bytes], limit: int) -> tuple[str, bool]:
    """Read the last ``limit`` bytes of a temp file; say whether anything was cut."""
    size = stream.seek(0, os.SEEK_END)
    stream.seek(max(0, size - limit))
    return stream.read().decode("utf-8", errors="replace"), size > limit
