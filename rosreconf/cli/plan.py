"""``rosreconf plan``: re-plan every schema after failures with a PDDL planner, and explain it."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.common import (
    ContextOption,
    CurrentOption,
    FailOption,
    IgnoreContextOption,
    JsonOption,
    LibraryOption,
    ObjectiveOption,
    OnlyOption,
    SchemaOption,
    SearchLimitOption,
    SearchTimeOption,
    finite,
    select,
    weights_of,
)
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.cli.switch import switch_command
from rosreconf.errors import ExitCode, UsageError
from rosreconf.outfiles import output_target
from rosreconf.planning.planners import DEFAULT_SEARCH, PlanStatus, planner_named
from rosreconf.planning.replan import replan_all
from rosreconf.render.reports import Output
from rosreconf.render.reports.plan import REPORTERS, pictures
from rosreconf.solve.running import running_mappings
from rosreconf.solve.search import SEARCH_LIMIT, SEARCH_TIME, Budget

MAX_TIMEOUT = 7 * 24 * 3600.0
"""Longest --timeout: a week; beyond it a number is a typo, and ``inf`` crashed the timer."""


def plan_command(
    fail: FailOption = None,
    context: ContextOption = None,
    ignore_context: IgnoreContextOption = False,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    current: CurrentOption = None,
    planner: Annotated[str, typer.Option(help="Planner: fd (Fast Downward) or ff.")] = "fd",
    search: Annotated[
        str | None,
        typer.Option(
            help="Fast Downward alias (ff-first: a first plan fast, costs ignored) or search "
            f"string. Default: {DEFAULT_SEARCH}."
        ),
    ] = None,
    timeout: Annotated[
        float,
        typer.Option(min=1, max=MAX_TIMEOUT, callback=finite, help="Seconds per schema."),
    ] = 60.0,
    keep_pddl: Annotated[
        Path | None, typer.Option("--keep-pddl", help="Also write the PDDL into this folder.")
    ] = None,
    objective: ObjectiveOption = None,
    search_limit: SearchLimitOption = SEARCH_LIMIT,
    search_time: SearchTimeOption = SEARCH_TIME,
    as_json: JsonOption = False,
    switch_to: Annotated[
        str | None,
        typer.Option(
            "--switch-to",
            metavar="SCHEMA",
            help="Switch task: the configuration of SCHEMA reached from the running schema "
            "(--only, or the one schema --current names) with the fewest changes; per "
            "component keep, stop, start or restart, and why. --fail is then optional.",
            show_default=False,
        ),
    ] = None,
    graph: Annotated[
        Path | None,
        typer.Option(
            "--graph",
            metavar="FILE",
            help="Also draw each new configuration's ROS-graph, with the failed, stopped and "
            "started parts marked, into this file (.dot, .svg or .png).",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Re-plan each schema after --fail with a PDDL planner: steps, new configuration, why.

    With --switch-to, switch task instead: the configuration of that schema reached from
    the running one with the fewest changes (docs/pddl.md, "Task switches"); exit 1 when the
    switch is impossible, with the reason.

    Exit 0 when every schema has a new configuration, 1 when some schema has none (its
    task is no longer possible; the others are still planned and reported), 2 on usage
    errors, 3 when the planner is missing, fails or runs out of time, or when the search for
    a configuration that meets the performance requirements runs out of its budget.
    """

    if graph is not None:
        output_target(graph, stdout_ok=False)  # refuse a bad --graph before planning
    if switch_to is not None:
        switching = select(
            library, schema, fail, None, context or [], ignore_context=ignore_context
        )
        switch_command(
            switching,
            switch_to,
            only,
            current,
            planner_named(planner, search),
            weights=weights_of(objective, switching.library),
            timeout=timeout,
            keep_pddl=keep_pddl,
            budget=Budget(search_limit, search_time),
            as_json=as_json,
            graph=graph,
        )
    sel = select(library, schema, fail, only, context or [], ignore_context=ignore_context)
    if not sel.failed:
        ruled = " (--context rules none out)" if sel.context else ""
        raise UsageError(f"give at least one --fail COMPONENT{ruled}")
    weights = weights_of(objective, sel.library)
    chosen = planner_named(planner, search)
    running = running_mappings(sel, current, weights)
    results = replan_all(
        sel.library,
        sel.schemas,
        sel.failed,
        running,
        chosen,
        weights=weights,
        timeout=timeout,
        keep_pddl=keep_pddl,
        budget=Budget(search_limit, search_time),
    )
    if graph is not None:
        from rosreconf.render.pictures import ros_dot, write_picture  # only when drawing

        drawn = pictures(results)
        if drawn:
            fmt = write_picture(graph, ros_dot(sel.library, drawn, sel.failed))
            stderr.print(f"rosreconf: wrote {graph} ({fmt})", markup=False)
        else:
            stderr.print("rosreconf: no new configuration to draw", markup=False)
    write_stdout(REPORTERS[Output.of(as_json)].render(sel, chosen, results))
    for r in results:
        if r.status not in (PlanStatus.SOLVED, PlanStatus.UNSOLVABLE_PROVEN):
            stderr.print(f"rosreconf: {r.schema.name}: {r.message}", markup=False)
    statuses = {r.status for r in results}
    if statuses - {PlanStatus.SOLVED, PlanStatus.UNSOLVABLE_PROVEN}:
        raise typer.Exit(ExitCode.PLANNER)
    raise typer.Exit(ExitCode.FAILED if PlanStatus.UNSOLVABLE_PROVEN in statuses else ExitCode.OK)
