"""``rosreconf redundancy``: Theorem 10's redundancy level, exact and approximate."""

from __future__ import annotations

import json
from dataclasses import asdict
from typing import Annotated

import typer

from rosreconf.analysis.redundancy import redundancy
from rosreconf.cli.common import JsonOption
from rosreconf.cli.console import write_stdout

NOTE = (
    "p is read as a component's probability of FAILURE: Theorem 10's formula only makes "
    "sense that way (the paper's text calls it availability)."
)


def redundancy_command(
    p: Annotated[float, typer.Option("--p", help="Failure probability of one component.")],
    n: Annotated[int, typer.Option("--n", help="Number of abstraction labels N.")],
    q: Annotated[float, typer.Option("--q", help="Required probability of reconfigurability.")],
    as_json: JsonOption = False,
) -> None:
    """Compute the redundancy r with (1 - p^r)^N >= q (Theorem 10), beside the approximation."""

    a = redundancy(p, n, q)
    if as_json:
        write_stdout(json.dumps({**asdict(a), "note": NOTE}, indent=2) + "\n")
        return
    write_stdout(
        f"Theorem 10 with p = {p:g} (failure), N = {n}, q = {q:g}\n"
        f"  redundancy needed r        {a.r_needed}   ((1 - p^r)^N = {a.achieved:.6f} >= q)\n"
        f"  exact real root            {a.r_exact:.6f}   (of (1 - p^r)^N = q)\n"
        f"  paper's approximation      {a.r_approx:.6f}   "
        f"(log(-log q)/log p - log N/log p)\n"
        f"  approximation error        {a.error:+.6f}   ({a.relative_error:+.3%})\n"
        f"note: {NOTE}\n"
    )
