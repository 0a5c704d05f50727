"""``rosreconf redundancy``: Theorem 10's redundancy level, exact and approximate."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.analysis.redundancy import redundancy
from rosreconf.cli.common import JsonOption
from rosreconf.cli.console import write_stdout
from rosreconf.render.reports import Output
from rosreconf.render.reports.redundancy import REPORTERS


def redundancy_command(
    p: Annotated[float, typer.Option("--p", help="Failure probability of one component.")],
    n: Annotated[int, typer.Option("--n", help="Number of abstraction labels N.")],
    q: Annotated[float, typer.Option("--q", help="Required probability of reconfigurability.")],
    as_json: JsonOption = False,
) -> None:
    """Compute the redundancy r with (1 - p^r)^N >= q (Theorem 10), beside the approximation."""

    a = redundancy(p, n, q)
    write_stdout(REPORTERS[Output.of(as_json)].render(a))
