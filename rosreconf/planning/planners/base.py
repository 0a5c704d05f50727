"""Run a planner adapter on one PDDL task: the statuses, the result and the one run loop.

``solve`` owns the run: it writes the domain and problem into a private temp dir, runs the
planner there through ``rosreconf.procs.run_program`` and lets the adapter read the answer
before the dir is removed. Adapters (``Planner`` subclasses) only build the command line and
map the exit code, output and plan file onto a ``Verdict``.
"""

from __future__ import annotations

import abc
import enum
import math
import signal
from dataclasses import dataclass
from pathlib import Path
from typing import ClassVar

from rosreconf.errors import ExternalToolError
from rosreconf.procs import ProgramResult, private_workdir, run_program

Action = tuple[str, tuple[str, ...]]
"""One plan step: the action's name and its arguments, lower case (``("pick", ("r1", "c2"))``)."""

TAIL_CHARS = 4000
"""How much of a planner's stdout and stderr a ``PlanResult`` keeps (the end)."""


class PlanStatus(enum.StrEnum):
    """Say how a planner run ended; only SOLVED carries a plan."""

    SOLVED = "solved"
    UNSOLVABLE_PROVEN = "unsolvable-proven"
    """The planner proved that no plan exists."""
    UNSOLVABLE_INCOMPLETE = "unsolvable-incomplete"
    """An incomplete search gave up: a plan may still exist (try another search)."""
    TIMEOUT = "timeout"
    MEMOUT = "memout"
    PLANNER_ERROR = "planner-error"
    """The planner rejected the task, crashed, or wrote an incomplete plan."""
    PLANNER_MISSING = "planner-missing"


@dataclass(frozen=True)
class PlanResult:
    """Report one planner run: the outcome, the plan if any, and what was run.

    Attributes:
        status: how the run ended.
        actions: the plan's steps in order (empty unless SOLVED; may be empty when SOLVED).
        cost: the plan's cost as the planner reported it, or None when it reported none.
        planner: the adapter and its configuration, e.g. ``fd (lama-first)``.
        command: the argument list that was run (empty if the planner was missing).
        elapsed: wall-clock seconds of the run.
        returncode: the planner's exit status (negative: killed by that signal), or None.
        stdout_tail: the last ``TAIL_CHARS`` characters of its stdout.
        stderr_tail: the last ``TAIL_CHARS`` characters of its stderr.
        message: the outcome in plain words, for the user.
    """

    status: PlanStatus
    actions: tuple[Action, ...]
    cost: int | None
    planner: str
    command: tuple[str, ...]
    elapsed: float
    returncode: int | None
    stdout_tail: str
    stderr_tail: str
    message: str

    @property
    def solved(self) -> bool:
        """Tell whether the run produced a plan."""
        return self.status is PlanStatus.SOLVED


@dataclass(frozen=True)
class Verdict:
    """Carry what an adapter read from a finished run, before ``solve`` adds the run's facts."""

    status: PlanStatus
    message: str
    actions: tuple[Action, ...] = ()
    cost: int | None = None


@dataclass(frozen=True)
class TaskFiles:
    """Name the files of one run inside its private temp dir.

    Attributes:
        workdir: the private temp dir, also the planner's working directory.
        domain: the PDDL domain file.
        problem: the PDDL problem file.
        plan: where the planner should write its plan (adapters may add suffixes).
    """

    workdir: Path
    domain: Path
    problem: Path
    plan: Path


class PlannerNotInstalled(ExternalToolError):
    """Say that a planner cannot run here, and how to install it."""


class Planner(abc.ABC):
    """Adapt one external planner: build its command line, read its answer.

    Subclasses set ``name`` and ``install_hint`` and implement ``command`` and ``interpret``;
    they never start processes or touch files outside ``TaskFiles``.
    """

    name: ClassVar[str]
    install_hint: ClassVar[str]

    @property
    def label(self) -> str:
        """Name the planner and its configuration for reports."""
        return self.name

    @abc.abstractmethod
    def command(self, files: TaskFiles, *, timeout: float, memory_limit_mb: int) -> list[str]:
        """Return the argument list; raise ``PlannerNotInstalled`` if it cannot run here."""

    @abc.abstractmethod
    def interpret(self, run: ProgramResult, files: TaskFiles) -> Verdict:
        """Map a finished run (exit code, output, plan files) onto a ``Verdict``."""

    def limits(self, timeout: float, memory_limit_mb: int) -> tuple[int | None, int | None]:
        """Return the (memory MB, CPU seconds) rlimits ``run_program`` should set.

        By default both, so that a planner without limits of its own is contained; planners
        that enforce the limits themselves return ``(None, None)``.
        """
        return memory_limit_mb, max(1, math.ceil(timeout))


def solve(
    planner: Planner,
    domain_text: str,
    problem_text: str,
    *,
    timeout: float,
    memory_limit_mb: int,
    workdir_parent: Path | None = None,
) -> PlanResult:
    """Solve one PDDL task with ``planner`` in a private temp dir; never leave anything behind.

    Args:
        planner: the adapter to run.
        domain_text: the PDDL domain.
        problem_text: the PDDL problem.
        timeout: wall-clock seconds for the whole run.
        memory_limit_mb: the memory the planner may use.
        workdir_parent: where to make the private temp dir (default: the system temp dir).

    Raises:
        ExternalToolError: the planner exists but could not be started at all.
        KeyboardInterrupt, Terminated: after the planner's process group was killed and the
            temp dir removed.
    """
    if memory_limit_mb < 1:
        raise ValueError(f"memory_limit_mb must be positive, got {memory_limit_mb}")
    with private_workdir(workdir_parent) as workdir:
        files = TaskFiles(
            workdir, workdir / "domain.pddl", workdir / "problem.pddl", workdir / "plan"
        )
        files.domain.write_text(domain_text, encoding="utf-8")
        files.problem.write_text(problem_text, encoding="utf-8")
        try:
            argv = planner.command(files, timeout=timeout, memory_limit_mb=memory_limit_mb)
        except PlannerNotInstalled as exc:
            return _result(planner, Verdict(PlanStatus.PLANNER_MISSING, str(exc)), None)
        memory, cpu = planner.limits(timeout, memory_limit_mb)
        run = run_program(
            argv, timeout=timeout, memory_limit_mb=memory, cpu_limit_s=cpu, cwd=workdir
        )
        if run.missing:
            message = f"{argv[0]} was not found. {planner.install_hint}"
            verdict = Verdict(PlanStatus.PLANNER_MISSING, message)
        else:
            verdict = planner.interpret(run, files)
        return _result(planner, verdict, run)


def _result(planner: Planner, verdict: Verdict, run: ProgramResult | None) -> PlanResult:
    """Join an adapter's verdict with the facts of the run into the public result."""
    return PlanResult(
        status=verdict.status,
        actions=verdict.actions if verdict.status is PlanStatus.SOLVED else (),
        cost=verdict.cost if verdict.status is PlanStatus.SOLVED else None,
        planner=planner.label,
        command=run.argv if run else (),
        elapsed=run.elapsed if run else 0.0,
        returncode=None if run is None or run.missing else run.returncode,
        stdout_tail=run.stdout[-TAIL_CHARS:] if run else "",
        stderr_tail=run.stderr[-TAIL_CHARS:] if run else "",
        message=verdict.message,
    )


def died_of(run: ProgramResult) -> Verdict | None:
    """Map a run ended by a signal onto a verdict (SIGXCPU is the CPU limit: TIMEOUT)."""
    sig = run.signal
    if sig is None or run.timed_out:
        return None
    if sig is signal.SIGXCPU:
        return Verdict(PlanStatus.TIMEOUT, "the planner used up its CPU-time limit")
    message = f"the planner was killed by {sig.name}: {last_words(run)}"
    return Verdict(PlanStatus.PLANNER_ERROR, message)


def last_words(run: ProgramResult, lines: int = 3) -> str:
    """Return the planner's last few meaningful output lines, for error messages.

    Progress chatter (Fast Downward's ``INFO`` lines, exit-code echoes, parser ``->`` trace)
    is skipped so that what remains is the planner's own complaint.
    """
    noise = ("INFO", "translate exit code", "search exit code", "Driver aborting", "Peak memory")
    kept = [
        line.strip()
        for line in (run.stdout + "\n" + run.stderr).splitlines()
        if line.strip() and not line.strip().startswith(noise) and "->" not in line
    ]
    return "; ".join(kept[-lines:]) or "no output"


def ran_out_of_time(run: ProgramResult) -> Verdict:
    """Explain a run that rosreconf stopped at its wall-clock limit without a plan."""
    message = f"no plan within the time limit (stopped after {run.elapsed:.2f} s)"
    return Verdict(PlanStatus.TIMEOUT, message)
