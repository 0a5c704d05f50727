"""``rosreconf whatif``: which schemas survive every set of up to K failed components."""

from __future__ import annotations

import functools
from typing import Annotated

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from rosreconf.analysis.whatif import analyse
from rosreconf.analysis.workers import executor
from rosreconf.cli.common import JsonOption, LibraryOption, OnlyOption, SchemaOption, select
from rosreconf.cli.console import stderr, stdout, write_stdout
from rosreconf.errors import ExitCode
from rosreconf.render.reports.whatif import document, table


def whatif_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    max_failures: Annotated[
        int, typer.Option("--max-failures", "-k", min=1, max=4, help="Largest failure set.")
    ] = 2,
    workers: Annotated[
        int | None,
        typer.Option(min=1, help="Worker processes. Default: one per core.", show_default=False),
    ] = None,
    cluster: Annotated[
        str | None,
        typer.Option(help="Solve on a Dask scheduler at tcp://HOST:PORT.", show_default=False),
    ] = None,
    as_json: JsonOption = False,
) -> None:
    """Show which schemas survive each set of up to K failures: critical parts and pairs."""

    sel = select(library, schema, None, only)
    if "bundled" in sel.loaded.note and not as_json:
        stderr.print(f"rosreconf: {sel.loaded.note}", markup=False)
    progress = Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=stderr,
        transient=True,
        disable=not stderr.is_terminal,
    )
    reports = []
    with progress, executor(workers, cluster) as pool:
        for s in sel.schemas:
            bar = progress.add_task(f"what if: {s.display_name}", total=None)
            report = analyse(
                sel.library,
                s,
                max_failures,
                pool,
                functools.partial(progress.advance, bar),
            )
            progress.update(bar, visible=False)
            reports.append(report)
    if as_json:
        write_stdout(document(reports, max_failures))
    else:
        for s, report in zip(sel.schemas, reports, strict=True):
            stdout.print(table(report, s.display_name, max_failures))
    raise typer.Exit(ExitCode.OK)
