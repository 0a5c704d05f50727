"""Run an ``ff`` found on PATH (FF 2.3 or Metric-FF) and read the plan it prints.

FF has no Linux build on the registries rosreconf uses, so it is optional: a user who has
compiled it puts it on PATH. FF prints its plan on stdout and its exit code says little (it
exits 1 both for "the empty plan solves it" and for "no plan will solve it"), so the answer
is read from the output::

    ff: found legal plan as follows

    step    0: PICK SENSOR CAM_B POWER IMAGE
            1: PICK PLANNER NAV_B IMAGE PATH
    plan cost: 6.000000                      (Metric-FF only)

FF 2.3 ignores action costs, so ``cost`` is None unless Metric-FF printed a whole cost.
FF has no limits of its own: ``run_program`` applies RLIMIT_AS and RLIMIT_CPU.
"""

from __future__ import annotations

import re
import shutil
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

_PLAN_START = "found legal plan as follows"
_STEP = re.compile(r"^\s*(?:step)?\s*\d+:\s*(\S.*)$", re.IGNORECASE)
_COST = re.compile(r"^plan cost:\s*([0-9.]+)\s*$", re.MULTILINE)
_UNSOLVABLE = ("goal can be simplified to FALSE", "problem proven unsolvable")
_EMPTY_PLAN = "goal can be simplified to TRUE"
_OUT_OF_MEMORY = ("out of memory", "bad_alloc", "memory allocation failed")


class FF(Planner):
    """Run FF (``ff -o DOMAIN -f PROBLEM``) from PATH.

    Attributes:
        executable: the program's name (looked up on PATH) or path; ``ff`` by default.
    """

    name: ClassVar[str] = "ff"
    install_hint: ClassVar[str] = (
        "FF is not packaged for Linux: build FF 2.3 or Metric-FF from source and put 'ff' on "
        "PATH, or use the default planner, Fast Downward (--planner fd), whose 'ehc(ff())' "
        "search is FF's."
    )

    def __init__(self, executable: str = "ff") -> None:
        self.executable = executable

    def command(self, files: TaskFiles, *, timeout: float, memory_limit_mb: int) -> list[str]:
        """Build ``ff -o DOMAIN -f PROBLEM`` with the executable found on PATH."""
        found = shutil.which(self.executable)
        if found is None:
            raise PlannerNotInstalled(f"no '{self.executable}' on PATH. {self.install_hint}")
        return [found, "-o", str(files.domain), "-f", str(files.problem)]

    def interpret(self, run: ProgramResult, files: TaskFiles) -> Verdict:
        """Read FF's verdict from its output; a signal or a timeout overrides what it printed."""
        if run.timed_out:
            return ran_out_of_time(run)
        killed = died_of(run)
        if killed is not None:
            return killed
        text = run.stdout
        if any(marker in text for marker in _UNSOLVABLE):
            return Verdict(PlanStatus.UNSOLVABLE_PROVEN, "FF proved that no plan exists")
        if _EMPTY_PLAN in text:
            return Verdict(PlanStatus.SOLVED, "the goal already holds: the empty plan", (), 0)
        actions = parse_ff_plan(text)
        if actions is not None:
            return Verdict(PlanStatus.SOLVED, "found a plan", actions, _cost(text))
        if any(marker in (text + run.stderr).lower() for marker in _OUT_OF_MEMORY):
            return Verdict(PlanStatus.MEMOUT, f"FF ran out of memory: {last_words(run)}")
        message = f"FF gave no plan (exit code {run.returncode}): {last_words(run)}"
        return Verdict(PlanStatus.PLANNER_ERROR, message)


def parse_ff_plan(text: str) -> tuple[Action, ...] | None:
    """Return the steps printed after FF's "found legal plan" line, lower case; None if absent.

    Steps run until the first line that is not a step (a blank line, ``plan cost:``, ``time
    spent:``), so the statistics that follow are never mistaken for actions.
    """
    lines = text.splitlines()
    start = next((i for i, line in enumerate(lines) if _PLAN_START in line), None)
    if start is None:
        return None
    actions: list[Action] = []
    for line in lines[start + 1 :]:
        match = _STEP.match(line)
        if match is None:
            if actions or line.strip():
                break
            continue  # the blank line(s) between the heading and the first step
        words = match.group(1).lower().split()
        actions.append((words[0], tuple(words[1:])))
    return tuple(actions)


def _cost(text: str) -> int | None:
    """Return Metric-FF's ``plan cost`` when it is a whole number, else None."""
    match = _COST.search(text)
    if match is None:
        return None
    value = float(match.group(1))
    return int(value) if value.is_integer() else None
