"""``rosreconf enumerate``: list or count the valid configurations of every schema."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

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
from rosreconf.model import Configuration, InteroperabilitySchema
from rosreconf.model.validity import graph_dict, ros_graph
from rosreconf.render.pictures import RosPicture, ros_dot, write_picture
from rosreconf.solve.counting import CountTooHard, count
from rosreconf.solve.factors import paused_gc
from rosreconf.solve.instance import Instance, compile_instance, explain
from rosreconf.solve.solver import ClingoEngine, Objective, first_configuration, optimise


def enumerate_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    only: OnlyOption = None,
    limit: Annotated[
        int | None, typer.Option(min=1, help="Stop after N configurations per schema.")
    ] = None,
    count_only: Annotated[
        bool, typer.Option("--count", help="Count exactly without listing.")
    ] = False,
    best: Annotated[
        bool,
        typer.Option(
            "--best", help="Print only the optimal configuration for --objective (proven)."
        ),
    ] = False,
    objective: ObjectiveOption = None,
    as_json: JsonOption = False,
    graph: Annotated[
        Path | None,
        typer.Option(
            "--graph",
            help="Also draw the ROS-graph of each schema's first configuration into this file "
            "(.dot, .svg or .png).",
            show_default=False,
        ),
    ] = None,
) -> None:
    """List every valid configuration of each schema (or count them), with why-not reasons.

    Exit 0 when every schema has a configuration, 1 when some schema has none.
    """

    if best and (count_only or limit is not None):
        raise UsageError("--best prints one configuration: leave out --count and --limit")
    if objective and not best:
        raise UsageError("--objective says what --best minimises: add --best")
    goal = Objective(weights=weights_of(objective)) if best else None
    sel = select(library, schema, fail, only)
    if "bundled" in sel.loaded.note and not as_json:
        stderr.print(f"rosreconf: {sel.loaded.note}", markup=False)
    empty = 0
    firsts: list[RosPicture] = []
    out = _JsonStream(sel, write_stdout) if as_json else None
    for s in sel.schemas:
        with paused_gc():  # compiling allocates many small tuples; collections would find none
            inst = compile_instance(sel.library, s, sel.failed)
        total: int | None = None
        if count_only:
            try:
                total = count(inst)
            except CountTooHard:
                total = sum(1 for _ in ClingoEngine().configurations(inst))
        n = 0
        if out:
            out.begin_schema(s)
        else:
            write_stdout(_heading(s))
        optimum: dict[str, object] | None = None
        if goal is not None:
            found = optimise(inst, goal)
            n = 0 if found.configuration is None else 1
            if found.configuration is not None:
                firsts.append(RosPicture(s, found.configuration))
                metric = goal.score(inst, found.configuration)[1]
                optimum = {"weights": dict(goal.weights), "weighted_sum": metric}
                optimum["engine"] = found.engine
                if out:
                    out.configuration(sel, s, found.configuration, 1)
                else:
                    write_stdout(f"    1. {', '.join(found.configuration.components)}\n")
                    write_stdout(_optimum_line(goal, metric, found.engine))
            total = None if n else 0
        elif not count_only:
            with _progress(stderr, s, quiet=as_json) as tick:
                for n, config in enumerate(_configurations(inst, limit), start=1):
                    if n == 1:
                        firsts.append(RosPicture(s, config))
                    if out:
                        out.configuration(sel, s, config, n)
                    else:
                        write_stdout(f"  {n:>3}. {', '.join(config.components)}\n")
                    tick()
            total = n if limit is None or n < limit else None
        elif graph is not None and total and (first := first_configuration(inst)):
            firsts.append(RosPicture(s, first))
        why = explain(inst) if (total == 0) else None
        empty += total == 0
        if out:
            out.end_schema(
                total, limit_reached=total is None and goal is None, why=why, optimum=optimum
            )
        elif goal is None or why:
            write_stdout(_summary(total, n, why))
        else:
            write_stdout("\n")
    if out:
        out.close()
    if graph is not None:
        write_picture(graph, ros_dot(sel.library, firsts, sel.failed))
    raise typer.Exit(ExitCode.FAILED if empty else ExitCode.OK)


def _configurations(inst: Instance, limit: int | None) -> Iterator[Configuration]:
    """Yield configurations in enumeration order; the first alone comes without clingo."""
    if limit == 1:
        found = first_configuration(inst)
        yield from () if found is None else (found,)
        return
    yield from ClingoEngine().configurations(inst, limit)


def _optimum_line(goal: Objective, metric: float, engine: str) -> str:
    """Say what the printed configuration is optimal for, and who proved it."""
    weights = ", ".join(f"{m}={w:g}" for m, w in goal.weights.items()) or "no metric"
    return f"  optimal for {weights}: weighted sum {metric:g} (proven by {engine})\n"


def _heading(s: InteroperabilitySchema) -> str:
    return f"{s.display_name} ({s.name}):\n"


def _summary(total: int | None, listed: int, why: str | None) -> str:
    if total is None:
        return f"  {listed} configuration(s) listed; stopped at --limit\n\n"
    if why:
        return f"  no configuration: {why}\n\n"
    digits = str(total)
    # Counts can have a thousand digits, far beyond a float: write the estimate from the digits.
    size = f" (about {digits[0]}.{digits[1:4]}e{len(digits) - 1}, {len(digits)} digits)"
    size = size if len(digits) > 15 else ""
    return f"  {total} configuration(s){size}\n\n"


class _JsonStream:
    """Write one JSON document incrementally, so memory stays flat however many there are."""

    def __init__(self, sel: Selection, write: Callable[[str], None]) -> None:
        self.write = write
        self.first_schema = True
        self.first_config = True
        head = {
            "library": {"name": sel.library.name, "components": len(sel.library)},
            "files": sel.loaded.files,
            "note": sel.loaded.note,
            "failed": list(sel.failed),
        }
        self._w(json.dumps(head)[:-1] + ', "schemas": [')

    def _w(self, text: str) -> None:
        self.write(text)

    def begin_schema(self, s: InteroperabilitySchema) -> None:
        sep = "" if self.first_schema else ", "
        self.first_schema = False
        self.first_config = True
        head = {"name": s.name, "title": s.display_name, "roles": [r.name for r in s.graph.roles]}
        self._w(sep + json.dumps(head)[:-1] + ', "configurations": [')

    def configuration(
        self, sel: Selection, s: InteroperabilitySchema, config: Configuration, n: int
    ) -> None:
        sep = "" if self.first_config else ", "
        self.first_config = False
        doc = {
            "index": n,
            "assignment": config.mapping,
            "components": list(config.components),
            "ros_graph": graph_dict(ros_graph(config, sel.library, s)),
        }
        self._w(sep + json.dumps(doc))

    def end_schema(
        self,
        total: int | None,
        *,
        limit_reached: bool,
        why: str | None,
        optimum: dict[str, object] | None = None,
    ) -> None:
        tail: dict[str, object] = {
            "count": total,
            "count_text": None if total is None else str(total),
            "limit_reached": limit_reached,
            "why_not": why,
        }
        if optimum is not None:  # --best: what the configuration is optimal for
            tail["optimum"] = optimum
        self._w("], " + json.dumps(tail, allow_nan=False)[1:])

    def close(self) -> None:
        self._w("]}\n")


@contextmanager
def _progress(
    console: Console, s: InteroperabilitySchema, *, quiet: bool
) -> Iterator[Callable[[], None]]:
    """Show a live counter on stderr for long enumerations (terminals only)."""
    progress = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TextColumn("{task.completed} found"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=quiet or not console.is_terminal,
    )
    with progress:
        task = progress.add_task(f"enumerating {s.display_name}", total=None)
        yield lambda: progress.advance(task)
