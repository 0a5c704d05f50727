"""``rosreconf redundancy``: Theorem 10's redundancy level, exact and approximate."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.analysis.redundancy import redundancy
from rosreconf.cli.common import JsonOption
from rosreconf.cli.console import stderr, write_stdout
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
    if p > 0.5:  # almost surely an availability: say so, and answer both readings
        other = redundancy(1 - p, n, q)
        stderr.print(
            f"rosreconf: warning: p = {p:g} is read as a FAILURE probability (r = {a.r_needed}); "
            f"a value above 0.5 is almost surely an availability: if so, the failure "
            f"probability is {1 - p:g} and r = {other.r_needed} (give --p {1 - p:g})",
            markup=False,
        )
    write_stdout(REPORTERS[Output.of(as_json)].render(a))
