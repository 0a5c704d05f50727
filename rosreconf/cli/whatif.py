"""``rosreconf whatif``: which schemas survive every set of up to K failed components."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Annotated

import typer
from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)

from rosreconf.analysis.whatif import SWEEP_TIME, SchemaProgress, sweep
from rosreconf.cli.common import (
    ContextOption,
    IgnoreContextOption,
    JsonOption,
    LibraryOption,
    OnlyOption,
    SchemaOption,
    SolveClusterOption,
    WorkersOption,
    finite,
    select,
)
from rosreconf.cli.console import stderr, stdout, write_stdout
from rosreconf.errors import ExitCode
from rosreconf.model import InteroperabilitySchema
from rosreconf.render.reports.context import context_doc, context_text
from rosreconf.render.reports.whatif import document, table


def whatif_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    context: ContextOption = None,
    ignore_context: IgnoreContextOption = False,
    max_failures: Annotated[
        int, typer.Option("--max-failures", "-k", min=1, max=4, help="Largest failure set.")
    ] = 2,
    workers: WorkersOption = None,
    cluster: SolveClusterOption = None,
    search_time: Annotated[
        float,
        typer.Option(
            "--search-time",
            min=1,
            max=7 * 24 * 3600.0,
            callback=finite,
            help="The most seconds the sweep takes (then exit 3, saying which failure sets "
            "were decided).",
        ),
    ] = SWEEP_TIME,
    as_json: JsonOption = False,
) -> None:
    """Show which schemas survive each set of up to K failures: critical parts and pairs."""

    sel = select(library, schema, None, only, context or [], ignore_context=ignore_context)
    if "bundled" in sel.loaded.note and not as_json:
        stderr.print(f"rosreconf: {sel.loaded.note}", markup=False)
    with _bars(stderr) as progress:
        reports = sweep(
            sel.library,
            sel.schemas,
            max_failures,
            workers,
            cluster,
            progress,
            search_time,
            failed=sel.failed,
        )
    if as_json:
        write_stdout(document(reports, max_failures, context_doc(sel)))
    else:
        if sel.has_context:
            write_stdout(context_text(sel))
        for s, report in zip(sel.schemas, reports, strict=True):
            stdout.print(table(report, s.display_name, max_failures))
    raise typer.Exit(ExitCode.OK)


@contextmanager
def _bars(console: Console) -> Iterator[SchemaProgress]:
    """Show one bar of failure sets decided for the schema being analysed (terminals only)."""
    progress = Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=not console.is_terminal,
    )
    bars: dict[str, TaskID] = {}

    def advance(schema: InteroperabilitySchema, decided: int) -> None:
        if schema.name not in bars:
            for bar in bars.values():  # the schema before is done
                progress.update(bar, visible=False)
            label = f"what if: {schema.display_name}"
            bars[schema.name] = progress.add_task(label, total=None)
        progress.advance(bars[schema.name], decided)

    with progress:
        yield advance
