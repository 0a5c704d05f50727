"""``rosreconf enumerate``: list or count the valid configurations of every schema."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console

from rosreconf.cli.common import (
    ContextOption,
    FailOption,
    IgnoreContextOption,
    JsonOption,
    LibraryOption,
    ObjectiveOption,
    OnlyOption,
    SchemaOption,
    select,
    weights_of,
)
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.errors import ExitCode, UsageError
from rosreconf.model import InteroperabilitySchema
from rosreconf.outfiles import output_target
from rosreconf.render.reports import Output
from rosreconf.render.reports.enumerate import REPORTERS
from rosreconf.solve.listing import Listing
from rosreconf.solve.objective import Objective

if TYPE_CHECKING:
    # Pictures (Graphviz, networkx) are imported only when --graph asks for one: a plain
    # listing pays for neither (whole-process time of every command).
    from rosreconf.render.pictures import RosPicture


def enumerate_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    context: ContextOption = None,
    ignore_context: IgnoreContextOption = False,
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
    if graph is not None:
        output_target(graph, stdout_ok=False)  # refuse a bad --graph before the work
    sel = select(library, schema, fail, only, context or [], ignore_context=ignore_context)
    goal = Objective(weights=weights_of(objective, sel.library)) if best else None
    if "bundled" in sel.loaded.note and not as_json:
        stderr.print(f"rosreconf: {sel.loaded.note}", markup=False)
    report = REPORTERS[Output.of(as_json)](sel, write_stdout)
    firsts: list[RosPicture] = []
    empty = 0
    for s in sel.schemas:
        found = Listing(
            sel.library,
            s,
            sel.failed,
            limit=limit,
            count_only=count_only,
            want_first=graph is not None,
            best=goal,
        )
        report.begin_schema(s)
        with _progress(stderr, s, quiet=as_json) as tick:
            for n, config in enumerate(found.configurations(), start=1):
                report.configuration(sel, s, config, n)
                tick()
        if found.counted_by_listing:
            stderr.print(
                f"rosreconf: note: {s.name}: exact counting would need too large a table here; "
                "counted by listing every configuration instead",
                markup=False,
            )
        if graph is not None and found.first is not None:
            from rosreconf.render.pictures import RosPicture

            firsts.append(RosPicture(s, found.first))
        empty += found.total == 0
        report.end_schema(
            found.total,
            found.listed,
            limit_reached=found.total is None and goal is None,
            why=found.why_not,
            optimum=found.optimum,
        )
    report.close()
    if graph is not None:
        from rosreconf.render.pictures import ros_dot, write_picture

        write_picture(graph, ros_dot(sel.library, firsts, sel.failed))
    raise typer.Exit(ExitCode.FAILED if empty else ExitCode.OK)


@contextmanager
def _progress(
    console: Console, s: InteroperabilitySchema, *, quiet: bool
) -> Iterator[Callable[[], None]]:
    """Show a live counter on stderr for long enumerations (terminals only).

    rich.progress is imported only when the counter is shown: piped and --json runs (every
    script and test) do not pay for it.
    """
    if quiet or not console.is_terminal:
        yield lambda: None
        return
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    progress = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TextColumn("{task.completed} found"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    )
    with progress:
        task = progress.add_task(f"enumerating {s.display_name}", total=None)
        yield lambda: progress.advance(task)
