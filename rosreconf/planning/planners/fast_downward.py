"""Run Fast Downward (the default planner) through its driver, and read its exit codes.

Fast Downward comes from the ``up-fast-downward`` wheel. Importing that package imports
unified-planning, which rosreconf does not install, so the files are located with
``importlib.util.find_spec`` and never imported. The driver applies the time and memory limits
to each of its components (translator, search) itself, so ``run_program`` adds only the
wall-clock timeout, which is the real limit. The driver's CPU-time limit is one second looser:
it rounds each component's remaining time down to whole seconds, and with a limit of 1 s the
translator gets 0 s and dies of SIGXCPU at once (measured: exit code 232).

The exit codes are those of ``downward/driver/returncodes.py``. When a component dies of a
signal the driver exits with 256 minus the signal number (232 is SIGXCPU, 245 SIGSEGV).
"""

from __future__ import annotations

import importlib.util
import math
import re
import signal
import sys
from pathlib import Path
from typing import ClassVar

from rosreconf.planning.planners.base import (
    Action,
    Planner,
    PlannerNotInstalled,
    PlanStatus,
    TaskFiles,
    Verdict,
    died_of,
    last_words,
    ran_out_of_time,
)
from rosreconf.procs import ProgramResult

_COST_LINE = re.compile(r"; cost = (\d+) \((?:unit|general) cost\)\n")
"""The last line of a complete plan, newline included (as the driver's plan_manager.py has it)."""

EXIT_CODES: dict[int, tuple[PlanStatus, str]] = {
    0: (PlanStatus.SOLVED, "found a plan"),
    1: (PlanStatus.SOLVED, "found a plan, then ran out of memory looking for a cheaper one"),
    2: (PlanStatus.SOLVED, "found a plan, then ran out of time looking for a cheaper one"),
    3: (PlanStatus.SOLVED, "found a plan, then ran out of time and memory"),
    10: (PlanStatus.UNSOLVABLE_PROVEN, "the translator proved that no plan exists"),
    11: (PlanStatus.UNSOLVABLE_PROVEN, "the search explored every reachable state: no plan"),
    12: (
        PlanStatus.UNSOLVABLE_INCOMPLETE,
        "the (incomplete) search gave up; a plan may still exist: try another search",
    ),
    13: (PlanStatus.UNSOLVABLE_INCOMPLETE, "no plan within the cost bound"),
    20: (PlanStatus.MEMOUT, "the translator ran out of memory"),
    21: (PlanStatus.TIMEOUT, "the translator ran out of time"),
    22: (PlanStatus.MEMOUT, "the search ran out of memory"),
    23: (PlanStatus.TIMEOUT, "the search ran out of time"),
    24: (PlanStatus.MEMOUT, "the search ran out of memory and time"),
    30: (PlanStatus.PLANNER_ERROR, "the translator crashed"),
    31: (PlanStatus.PLANNER_ERROR, "the translator rejected the PDDL"),
    32: (PlanStatus.PLANNER_ERROR, "the search crashed"),
    33: (PlanStatus.PLANNER_ERROR, "the search rejected its input or its --search string"),
    34: (PlanStatus.PLANNER_ERROR, "the search does not support this task"),
    35: (PlanStatus.PLANNER_ERROR, "the driver crashed"),
    36: (PlanStatus.PLANNER_ERROR, "the driver rejected its options or input files"),
    37: (PlanStatus.PLANNER_ERROR, "the driver does not support this platform or request"),
}
"""Fast Downward's exit codes: the status each maps to and what it means, in plain words."""

FF_FIRST = (
    "let(hff, eval_modify_costs(ff(), cost_type=one), "
    "lazy_greedy([hff], preferred=[hff], cost_type=one, reopen_closed=false))"
)
"""``lama-first`` without its landmark heuristic: lazy greedy search on FF, unit costs.

Our encoding fills and checks the roles in one fixed order, so the landmarks form one long
chain and each is ordered before all later ones: at 1000 roles x 2 candidates lama-first was
still generating landmarks (lm_rhw) when its 60 s ran out (with per-role flags instead of the
token: 8,177 landmarks, 6.3 million orderings, 27 s), while FF alone searched 1.7 s
(docs/pddl.md). Unit costs (``cost_type=one``) as in lama-first: our choices of kept
components and all connect and finish actions cost 0, so a cost-aware FF is 0 in most states
and the greedy search is blind.
"""

SEARCHES: dict[str, tuple[str, ...]] = {
    "ff-first": (
        "--translate-options",
        "--skip-variable-reordering",
        "--search-options",
        "--search",
        FF_FIRST,
    ),
}
"""Named driver arguments, used like the driver's aliases (after DOMAIN PROBLEM).

``--skip-variable-reordering``: the order token puts nearly every variable into one cycle of
the causal graph, and the translator's ordering of that cycle is quadratic (``target in scc``
on a list): 5.6 s of 26 s at 1000 x 10. Only the causal-graph heuristic needs that order,
and FF search ran faster without it (3.4 s instead of 5.2 s).
"""


def fast_downward_root() -> Path | None:
    """Find the installed ``up_fast_downward`` files without importing the package."""
    try:
        spec = importlib.util.find_spec("up_fast_downward")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    root = Path(next(iter(spec.submodule_search_locations)))
    return root if (root / "downward" / "fast-downward.py").is_file() else None


class FastDownward(Planner):
    """Run Fast Downward with a named search (``ff-first``), an alias or a ``--search`` string.

    Attributes:
        search: a name from ``SEARCHES`` (``ff-first``, the default), an alias such as
            ``lama-first`` or ``seq-sat-lama-2011`` (anytime), or a search string such as
            ``astar(lmcut())`` or ``ehc(ff())``, told apart by the parenthesis.
    """

    name: ClassVar[str] = "fd"
    install_hint: ClassVar[str] = (
        "Install Fast Downward with: pip install 'up-fast-downward>=1.0' "
        "(or pip install 'rosreconf[planners]')."
    )

    def __init__(self, search: str = "ff-first") -> None:
        if not search.strip():
            raise ValueError("FastDownward needs an alias or a --search string")
        self.search = search.strip()

    @property
    def label(self) -> str:
        """Name the planner and its search for reports: ``fd (lama-first)``."""
        return f"{self.name} ({self.search})"

    def command(self, files: TaskFiles, *, timeout: float, memory_limit_mb: int) -> list[str]:
        """Build the driver's command line; the driver limits CPU time and memory itself."""
        root = fast_downward_root()
        if root is None:
            raise PlannerNotInstalled(f"Fast Downward is not installed. {self.install_hint}")
        argv = [
            sys.executable,
            str(root / "downward" / "fast-downward.py"),
            "--plan-file",
            str(files.plan.absolute()),
            "--overall-time-limit",
            str(math.ceil(timeout) + 1),
            "--overall-memory-limit",
            f"{memory_limit_mb}M",
        ]
        task = [str(files.domain.absolute()), str(files.problem.absolute())]
        if self.search in SEARCHES:
            return [*argv, *task, *SEARCHES[self.search]]
        if "(" in self.search:
            return [*argv, *task, "--search", self.search]
        return [*argv, "--alias", self.search, *task]

    def limits(self, timeout: float, memory_limit_mb: int) -> tuple[int | None, int | None]:
        """Leave CPU and memory limits to the driver, which sets them per component."""
        return None, None

    def interpret(self, run: ProgramResult, files: TaskFiles) -> Verdict:
        """Map the exit code and the plan files; a plan counts only with its cost line.

        An anytime search writes ``plan.1``, ``plan.2``, ... each cheaper than the last; the
        cheapest complete one is taken, also when rosreconf stopped the run at its timeout.
        """
        plans, incomplete = _read_plans(files.plan)
        best = min(plans, key=lambda plan: plan[1]) if plans else None
        if run.timed_out:
            if best is None:
                return ran_out_of_time(run)
            message = "the time limit stopped the search; this is the cheapest plan found"
            return Verdict(PlanStatus.SOLVED, message, best[0], best[1])
        killed = died_of(run) or _component_died(run)
        if killed is not None:
            return killed
        status, meaning = EXIT_CODES.get(
            run.returncode, (PlanStatus.PLANNER_ERROR, "unknown exit code")
        )
        if status is PlanStatus.SOLVED:
            if incomplete:
                names = ", ".join(path.name for path in incomplete)
                message = f"incomplete plan: {names} lacks its '; cost = N' line or is malformed"
                return Verdict(PlanStatus.PLANNER_ERROR, message)
            if best is None:
                message = f"exit code {run.returncode} but no plan file was written"
                return Verdict(PlanStatus.PLANNER_ERROR, message)
            return Verdict(PlanStatus.SOLVED, meaning, best[0], best[1])
        message = f"Fast Downward exit code {run.returncode}: {meaning}"
        if status is PlanStatus.PLANNER_ERROR:
            message += f": {last_words(run)}"
        return Verdict(status, message)


def _component_died(run: ProgramResult) -> Verdict | None:
    """Map the driver's ``256 - signal`` exit codes (a component killed by a signal)."""
    if not 128 < run.returncode < 256:
        return None
    try:
        sig = signal.Signals(256 - run.returncode)
    except ValueError:
        return None
    if sig is signal.SIGXCPU:
        return Verdict(PlanStatus.TIMEOUT, "a Fast Downward component used up its CPU time")
    message = f"Fast Downward exit code {run.returncode}: a component was killed by {sig.name}"
    return Verdict(PlanStatus.PLANNER_ERROR, f"{message}: {last_words(run)}")


def _read_plans(
    prefix: Path,
) -> tuple[list[tuple[tuple[Action, ...], int]], list[Path]]:
    """Read ``prefix`` and ``prefix.1``, ``prefix.2``, ...: complete plans and incomplete files."""
    paths = [prefix] if prefix.exists() else []
    number = 1
    while (numbered := prefix.with_name(f"{prefix.name}.{number}")).exists():
        paths.append(numbered)
        number += 1
    plans: list[tuple[tuple[Action, ...], int]] = []
    incomplete: list[Path] = []
    for path in paths:
        parsed = parse_plan(path.read_text(encoding="utf-8", errors="replace"))
        if parsed is None:
            incomplete.append(path)
        else:
            plans.append(parsed)
    return plans, incomplete


def parse_plan(text: str) -> tuple[tuple[Action, ...], int] | None:
    """Parse a Fast Downward plan file; return None unless it ends with the cost line.

    Each step is ``(name arg ...)``; names and arguments are lower-cased and kept as written.
    """
    lines = text.splitlines(keepends=True)
    match = _COST_LINE.fullmatch(lines[-1]) if lines else None
    if match is None:
        return None
    actions: list[Action] = []
    for raw in lines[:-1]:
        line = raw.strip()
        if not line or line.startswith(";"):
            continue
        words = line.strip("()").lower().split()
        if not line.startswith("(") or not line.endswith(")") or not words:
            return None
        actions.append((words[0], tuple(words[1:])))
    return tuple(actions), int(match.group(1))
