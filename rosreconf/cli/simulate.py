"""``rosreconf simulate``: will each valid configuration perform? The paper's M-solution."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.common import (
    ContextOption,
    FailOption,
    IgnoreContextOption,
    JsonOption,
    LibraryOption,
    OnlyOption,
    SchemaOption,
    SimulateClusterOption,
    WorkersOption,
    select,
)
from rosreconf.cli.console import stderr, stdout, write_stdout_pieces
from rosreconf.errors import ExitCode

TOP = 20
"""Rows of the text table by default (rosreconf.render.reports.simulate.TOP, not imported
here so that --help does not import the report's dependencies)."""


def simulate_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    fail: FailOption = None,
    context: ContextOption = None,
    ignore_context: IgnoreContextOption = False,
    limit: Annotated[
        int,
        typer.Option(
            min=1,
            max=100_000_000,
            help="Simulate at most N configurations per schema, in listing order; the output "
            "says when there were more (the ranking is over those simulated). Memory and the "
            "--json document grow with N.",
        ),
    ] = 1000,  # analysis.simulate.DEFAULT_LIMIT (not imported here: it loads numpy)
    pareto: Annotated[
        str | None,
        typer.Option(
            help="List only the Pareto front over these metrics (comma-separated; simulated: "
            "settling_time, steady_state_error, overshoot; or the library's metrics).",
            show_default=False,
        ),
    ] = None,
    plot: Annotated[
        Path | None,
        typer.Option(
            help="Draw the step responses (and the front) to FILE.svg or .png.", show_default=False
        ),
    ] = None,
    workers: WorkersOption = None,
    cluster: SimulateClusterOption = None,
    top: Annotated[
        int,
        typer.Option(
            min=0, help="Rows of the table: the best N configurations (0: all). JSON lists all."
        ),
    ] = TOP,
    as_json: JsonOption = False,
) -> None:
    """Simulate every valid configuration's control loops; rank by settling time and error."""
    from rosreconf.analysis.simulate import sweep  # imports numpy: only when run
    from rosreconf.render.reports.context import context_doc, context_text
    from rosreconf.render.reports.simulate import document, table

    sel = select(library, schema, fail, only, context or [], ignore_context=ignore_context)
    metrics = tuple(m.strip() for m in (pareto or "").split(",") if m.strip())
    result = sweep(
        sel.library, sel.schemas, sel.failed, limit, metrics, workers, cluster, explicit=bool(only)
    )
    if plot is not None:
        from rosreconf.render.plots import draw_sweep

        draw_sweep(plot, sel.library, result)
    if as_json:
        write_stdout_pieces(document(result, context_doc(sel)))
    else:
        for note in result.notes:
            stderr.print(f"rosreconf: {note}", markup=False)
        if sel.has_context:
            stdout.print(context_text(sel).rstrip("\n") + "\n", markup=False, highlight=False)
        for report in result.reports:
            stdout.print(table(report, top))
    ok = all(r.any_meets() for r in result.reports)
    raise typer.Exit(ExitCode.OK if ok else ExitCode.FAILED)
