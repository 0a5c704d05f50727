"""Solve a PDDL task with an external planner and say, in one enum, how it went.

``solve(planner, domain_text, problem_text, timeout=..., memory_limit_mb=...)`` runs one
adapter in a private temp dir and returns a ``PlanResult``; the statuses follow
unified-planning's ``PlanGenerationResultStatus``. Plans come back as lower-case
``(name, args)`` tuples, exactly as the planner wrote them: mapping them back onto model
objects is another module's job. ``PLANNERS`` feeds the CLI's ``--planner`` choices.

How an outcome is named across layers::

    Fast Downward exit code          FF output                         PlanStatus
    -------------------------------  --------------------------------  ---------------------
    0-3 and a complete plan          "found legal plan as follows"     SOLVED
    10, 11                           "simplified to FALSE", "proven"   UNSOLVABLE_PROVEN
    12, 13                           -                                 UNSOLVABLE_INCOMPLETE
    21, 23, wall clock               SIGXCPU, wall clock               TIMEOUT
    20, 22, 24                       "out of memory"                   MEMOUT
    30-37, signal, incomplete plan   anything else                     PLANNER_ERROR
    wheel not installed              no ``ff`` on PATH                 PLANNER_MISSING
"""

from __future__ import annotations

from rosreconf.errors import UsageError
from rosreconf.planning.planners.base import (
    Action,
    Planner,
    PlannerNotInstalled,
    PlanResult,
    PlanStatus,
    TaskFiles,
    Verdict,
    solve,
)
from rosreconf.planning.planners.fast_downward import FastDownward, fast_downward_root
from rosreconf.planning.planners.ff import FF

PLANNERS: dict[str, type[Planner]] = {"fd": FastDownward, "ff": FF}
"""The planners the CLI offers, by the name given to ``--planner``; each builds with no args."""

DEFAULT_SEARCH = "seq-sat-lama-2011"
"""Fast Downward's default search: cost-aware and anytime (the minimal change on the paper's
example in 0.4 s)."""


def planner_named(name: str, search: str | None = None) -> Planner:
    """Build the planner ``--planner NAME`` (and, for Fast Downward, ``--search``) names.

    Raises:
        UsageError: an unknown planner, or a search given to a planner that has none.
    """
    if name not in PLANNERS:
        raise UsageError(f"--planner {name}: choose one of {', '.join(PLANNERS)}")
    if name == "fd" or issubclass(PLANNERS[name], FastDownward):
        return PLANNERS[name](search or DEFAULT_SEARCH)  # type: ignore[call-arg]
    if search:
        raise UsageError(f"--search is for Fast Downward only, not --planner {name}")
    return PLANNERS[name]()


__all__ = [
    "DEFAULT_SEARCH",
    "FF",
    "PLANNERS",
    "Action",
    "FastDownward",
    "PlanResult",
    "PlanStatus",
    "Planner",
    "PlannerNotInstalled",
    "TaskFiles",
    "Verdict",
    "fast_downward_root",
    "planner_named",
    "solve",
]
