"""``rosreconf analyse``: orthogonality, redundancy, failure points and reliability."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.analysis.library import analyse
from rosreconf.analysis.thresholds import thresholds
from rosreconf.cli.common import (
    ContextOption,
    FailOption,
    IgnoreContextOption,
    JsonOption,
    LibraryOption,
    OnlyOption,
    SchemaOption,
    select,
)
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode
from rosreconf.render.reports import Output
from rosreconf.render.reports.analyse import REPORTERS


def analyse_command(
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    context: ContextOption = None,
    ignore_context: IgnoreContextOption = False,
    only: OnlyOption = None,
    samples: Annotated[
        int, typer.Option(min=100, help="Monte Carlo samples when exact is too large.")
    ] = 20_000,
    seed: Annotated[int, typer.Option(help="Monte Carlo seed.")] = 0,
    as_json: JsonOption = False,
) -> None:
    """Analyse orthogonality, redundancy, failure points and reliability of each schema.

    Orthogonality is Def. 8; redundancy per role is the paper's r; single points of failure and
    critical pairs are failures that leave no configuration; the reconfigurability probability
    is exact when the configurations can be listed, else Monte Carlo with its interval.
    With a library that declares context, a table per context variable gives the values at
    which each schema's count of configurations changes (docs/context.md).

    Exit 0 when every schema has a configuration, 1 otherwise.
    """

    sel = select(library, schema, fail, only, context or [], ignore_context=ignore_context)
    results = [analyse(sel.library, s, sel.failed, samples=samples, seed=seed) for s in sel.schemas]
    used = dict.fromkeys(w.name for c in sel.library for w in c.when)
    tables = [
        thresholds(sel.library, s, v, sel.context, sel.fail_given)
        for s in sel.schemas
        for v in used
    ]
    write_stdout(REPORTERS[Output.of(as_json)].render(sel, results, tables))
    raise typer.Exit(ExitCode.FAILED if any(r.valid == 0 for r in results) else ExitCode.OK)
