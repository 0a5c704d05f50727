"""``rosreconf plan --switch-to``: switch task at design time, with the fewest changes.

The running schema is the one ``--only`` names, else the one schema the ``--current`` file
names (as ``inspect`` and ``watch`` pick theirs); its running configuration comes from that
file, else by the rule of ``rosreconf.solve.running`` (declared nominal, else best by
--objective, else first valid). docs/pddl.md, "Task switches".
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from typing import NoReturn

import typer

from rosreconf.cli.console import stderr, write_stdout
from rosreconf.errors import ExitCode, UsageError
from rosreconf.formats.configfile import read_configurations
from rosreconf.formats.selection import Selection
from rosreconf.model import InteroperabilitySchema
from rosreconf.planning.planners import Planner, PlanStatus
from rosreconf.planning.switch import switch
from rosreconf.render.reports import Output
from rosreconf.render.reports.switch import REPORTERS
from rosreconf.solve.running import running_mappings
from rosreconf.solve.search import Budget


def _named(sel: Selection, name: str, option: str) -> InteroperabilitySchema:
    """Return the schema ``name``, or refuse it (exit 2) with the names there are."""
    for s in sel.schemas:
        if s.name == name:
            return s
    known = [s.name for s in sel.schemas]
    close = difflib.get_close_matches(name, known, n=1)
    hint = f" (did you mean {close[0]}?)" if close else f" (schemas: {', '.join(known)})"
    raise UsageError(f"{option} {name}: no such schema{hint}")


def running_schema(
    sel: Selection, only: Sequence[str] | None, current: Path | None
) -> InteroperabilitySchema:
    """Return S1: the one schema ``--only`` names, else the one schema the file names.

    Raises:
        UsageError: no single running schema is named, or the file has none of it.
    """
    given = read_configurations(current) if current is not None else {}
    if only:
        if len(only) != 1:
            raise UsageError("with --switch-to, --only names the one running schema")
        source = _named(sel, only[0], "--only")
        if current is not None and source.name not in given:
            raise UsageError(f"--current {current}: has no configuration of {source.name}")
        return source
    named = [s for s in sel.schemas if s.name in given]
    if len(named) != 1:
        choices = ", ".join(s.name for s in sel.schemas)
        raise UsageError(f"name the running schema with --only (schemas to choose from: {choices})")
    return named[0]


def switch_command(
    sel: Selection,
    target: str,
    only: Sequence[str] | None,
    current: Path | None,
    planner: Planner,
    *,
    weights: Mapping[str, float],
    timeout: float,
    keep_pddl: Path | None,
    budget: Budget,
    as_json: bool,
    graph: Path | None,
) -> NoReturn:
    """Plan the switch, print it, and exit: 0 done, 1 impossible, 3 the planner failed."""
    s2 = _named(sel, target, "--switch-to")
    s1 = running_schema(sel, only, current)
    before = running_mappings(replace(sel, schemas=(s1,)), current, weights)[s1.name]
    answer = switch(
        sel.library,
        s1,
        before,
        s2,
        sel.failed,
        planner,
        weights=weights,
        timeout=timeout,
        keep_pddl=keep_pddl,
        budget=budget,
    )
    if graph is not None:
        from rosreconf.render.pictures import ros_dot, write_picture  # only when drawing
        from rosreconf.render.reports.plan import pictures

        drawn = pictures([answer.result])
        if drawn:
            fmt = write_picture(graph, ros_dot(sel.library, drawn, sel.failed))
            stderr.print(f"rosreconf: wrote {graph} ({fmt})", markup=False)
        else:
            stderr.print("rosreconf: no new configuration to draw", markup=False)
    write_stdout(REPORTERS[Output.of(as_json)].render(sel, planner, answer))
    status = answer.result.status
    if status is PlanStatus.SOLVED:
        raise typer.Exit(ExitCode.OK)
    if status is PlanStatus.UNSOLVABLE_PROVEN:
        raise typer.Exit(ExitCode.FAILED)
    stderr.print(f"rosreconf: {s2.name}: {answer.result.message}", markup=False)
    raise typer.Exit(ExitCode.PLANNER)
