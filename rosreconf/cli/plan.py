"""``rosreconf plan``: re-plan every schema after failures with a PDDL planner, and explain it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

from rosreconf.cli.common import (
    FailOption,
    JsonOption,
    LibraryOption,
    ObjectiveOption,
    OnlyOption,
    SchemaOption,
    Selection,
    select,
    weights_of,
)
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.errors import ExitCode, UsageError
from rosreconf.formats.configfile import read_configurations
from rosreconf.model import Configuration
from rosreconf.planning.planners import PLANNERS, FastDownward, Planner, PlanStatus
from rosreconf.planning.replan import ReplanResult, current_configuration, plan
from rosreconf.render.pictures import RosPicture, ros_dot, write_picture

DEFAULT_SEARCH = "seq-sat-lama-2011"
"""Cost-aware and anytime: proves the minimal change on the paper's example in 0.4 s."""

CurrentOption = Annotated[
    Path | None,
    typer.Option(
        "--current",
        metavar="FILE",
        help="What runs now (a configuration file, or the JSON of enumerate/plan). Default: "
        "each schema's declared nominal configuration, else its best by --objective.",
        show_default=False,
    ),
]


def currents(
    sel: Selection, path: Path | None, weights: dict[str, float]
) -> dict[str, dict[str, str]]:
    """Return per schema what runs now: from ``--current``, else nominal, else the best."""
    given = read_configurations(path) if path is not None else {}
    return {
        s.name: given.get(s.name) or current_configuration(sel.library, s, weights)
        for s in sel.schemas
    }


def make_planner(name: str, search: str | None) -> Planner:
    """Build the planner the options name."""
    if name not in PLANNERS:
        raise UsageError(f"--planner {name}: choose one of {', '.join(PLANNERS)}")
    if name == "fd" or issubclass(PLANNERS[name], FastDownward):
        return PLANNERS[name](search or DEFAULT_SEARCH)  # type: ignore[call-arg]
    if search:
        raise UsageError(f"--search is for Fast Downward only, not --planner {name}")
    return PLANNERS[name]()


def plan_command(
    fail: FailOption = None,
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
    timeout: Annotated[float, typer.Option(min=1, help="Seconds per schema.")] = 60.0,
    keep_pddl: Annotated[
        Path | None, typer.Option("--keep-pddl", help="Also write the PDDL into this folder.")
    ] = None,
    objective: ObjectiveOption = None,
    as_json: JsonOption = False,
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

    Exit 0 when every schema has a new configuration, 1 when some schema has none (its
    task is no longer possible; the others are still planned and reported), 2 on usage
    errors, 3 when the planner is missing, fails or runs out of time.
    """

    sel = select(library, schema, fail, only)
    if not sel.failed:
        raise UsageError("give at least one --fail COMPONENT")
    weights = weights_of(objective)
    chosen = make_planner(planner, search)
    running = currents(sel, current, weights)
    results = [
        plan(
            sel.library,
            s,
            sel.failed,
            running[s.name],
            chosen,
            weights=weights,
            timeout=timeout,
            keep_pddl=keep_pddl,
        )
        for s in sel.schemas
    ]
    if graph is not None:
        _draw(graph, sel, results)
    if as_json:
        write_stdout(json.dumps(_document(sel, chosen, results), indent=2) + "\n")
    else:
        for r in results:
            write_stdout(_text(r))
    for r in results:
        if r.status not in (PlanStatus.SOLVED, PlanStatus.UNSOLVABLE_PROVEN):
            stderr.print(f"rosreconf: {r.schema.name}: {r.message}", markup=False)
    statuses = {r.status for r in results}
    if statuses - {PlanStatus.SOLVED, PlanStatus.UNSOLVABLE_PROVEN}:
        raise typer.Exit(ExitCode.PLANNER)
    raise typer.Exit(ExitCode.FAILED if PlanStatus.UNSOLVABLE_PROVEN in statuses else ExitCode.OK)


def _text(r: ReplanResult) -> str:
    out = [f"{r.schema.display_name} ({r.schema.name}):"]
    if r.status is PlanStatus.UNSOLVABLE_PROVEN:
        out.append("  no configuration is possible")
    elif r.configuration is None:
        out.append(f"  planner failed ({r.status}): {r.message}")
    else:
        run = r.planner
        if r.unaffected:
            out.append(f"  unaffected, keeps running: {r.unaffected}")
        if run is not None:
            out.append(f"  plan ({run.planner}, {run.elapsed:.2f} s, cost {run.cost}):")
        out += [f"  {n:>4}. {step}" for n, step in enumerate(r.steps, start=1)]
        out.append("  new configuration:")
        out += [f"    {role:<20} {comp}" for role, comp in r.configuration.assignment]
        out.append("  change:")
        out += [f"    {c}" for c in r.changes]
    if r.explanation:
        out.append("  why:")
        out += [f"    {line}" for line in r.explanation]
    return "\n".join(out) + "\n\n"


def _document(sel: Selection, planner: Planner, results: list[ReplanResult]) -> dict[str, Any]:
    """Build the JSON document; each schema's first configuration is the new one."""
    return {
        "library": {"name": sel.library.name, "components": len(sel.library)},
        "files": sel.loaded.files,
        "failed": list(sel.failed),
        "planner": planner.label,
        "schemas": [_schema_doc(r) for r in results],
    }


def _schema_doc(r: ReplanResult) -> dict[str, Any]:
    run = r.planner
    configs = [] if r.configuration is None else [{"assignment": r.configuration.mapping}]
    return {
        "name": r.schema.name,
        "title": r.schema.display_name,
        "status": str(r.status),
        "configurations": configs,
        "current": dict(r.current),
        "steps": list(r.steps),
        "actions": list(r.actions),
        "changes": [
            {"role": c.role, "before": c.before, "after": c.after, "kind": c.kind}
            for c in r.changes
        ],
        "fewest_changes": r.fewest_changes,
        "explanation": list(r.explanation),
        "why_not": r.why_not or None,
        "message": r.message,
        "cost": run.cost if run else None,
        "elapsed": round(run.elapsed, 3) if run else None,
        "unaffected": r.unaffected or None,
    }


def _draw(path: Path, sel: Selection, results: list[ReplanResult]) -> None:
    """Draw the new ROS-graphs against the running ones (schemas without one are left out)."""

    pictures = [
        RosPicture(
            r.schema,
            r.configuration,
            before=Configuration.of(r.schema.name, dict(r.current), r.schema.graph.roles)
            if set(r.current) == {role.name for role in r.schema.graph.roles}
            else None,
        )
        for r in results
        if r.configuration is not None
    ]
    if not pictures:
        stderr.print("rosreconf: no new configuration to draw", markup=False)
        return
    fmt = write_picture(path, ros_dot(sel.library, pictures, sel.failed))
    stderr.print(f"rosreconf: wrote {path} ({fmt})", markup=False)
