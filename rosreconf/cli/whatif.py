"""``rosreconf whatif``: which schemas survive every set of up to K failed components."""

from __future__ import annotations

import functools
import json
import os
from concurrent.futures import ProcessPoolExecutor
from typing import Annotated, Any

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from rosreconf.analysis.whatif import SchemaReport, analyse
from rosreconf.cli.common import JsonOption, LibraryOption, OnlyOption, SchemaOption, select
from rosreconf.cli.console import stderr, stdout, write_stdout
from rosreconf.errors import ExitCode


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
    as_json: JsonOption = False,
) -> None:
    """Show which schemas survive each set of up to K failures: critical parts and pairs."""

    sel = select(library, schema, None, only)
    if "bundled" in sel.loaded.note and not as_json:
        stderr.print(f"rosreconf: {sel.loaded.note}", markup=False)
    n = workers or os.cpu_count() or 1
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
    with progress, ProcessPoolExecutor(max_workers=n) as pool:
        for s in sel.schemas:
            bar = progress.add_task(f"what if: {s.display_name}", total=None)
            report = analyse(
                sel.library,
                s,
                max_failures,
                pool if n > 1 else None,
                functools.partial(progress.advance, bar),
            )
            progress.update(bar, visible=False)
            reports.append(report)
    if as_json:
        write_stdout(json.dumps(_document(reports, max_failures)) + "\n")
    else:
        for s, report in zip(sel.schemas, reports, strict=True):
            stdout.print(_table(report, s.display_name, max_failures))
    raise typer.Exit(ExitCode.OK)


def _table(report: SchemaReport, title: str, k: int) -> Table:
    table = Table(title=f"{title} ({report.schema})", title_justify="left", show_header=False)
    table.add_column("what")
    table.add_column("value", overflow="fold")
    table.add_row(
        "relevant components",
        f"{len(report.relevant)} of {report.components} (the others are in no valid "
        "configuration, so their failure changes nothing)",
    )
    table.add_row("critical components", ", ".join(report.critical) or "none")
    pairs = report.critical_pairs
    table.add_row("critical pairs", ", ".join(f"{{{a}, {b}}}" for a, b in pairs) or "none")
    for size in range(1, k + 1):
        alive, total = report.survived(size)
        table.add_row(f"survives {size} failure(s)", f"{alive / total:.2%} ({alive} of {total})")
    table.add_row("solver calls", f"{report.solver_calls} (the rest decided by pruning)")
    return table


def _document(reports: list[SchemaReport], k: int) -> dict[str, Any]:
    out = []
    for r in reports:
        shares = []
        for size in range(1, k + 1):
            alive, total = r.survived(size)
            shares.append({"k": size, "survived": alive, "total": total, "share": alive / total})
        out.append(
            {
                "name": r.schema,
                "components": r.components,
                "relevant": list(r.relevant),
                "critical": r.critical,
                "critical_pairs": [list(p) for p in r.critical_pairs],
                "shares": shares,
                "solver_calls": r.solver_calls,
                "failure_sets": [
                    {
                        "failed": list(o.failed),
                        "survives": o.survives,
                        "configuration": list(o.configuration) if o.configuration else None,
                    }
                    for o in sorted(r.outcomes.values(), key=lambda o: (len(o.failed), o.failed))
                ],
            }
        )
    return {"max_failures": k, "schemas": out}
