"""``rosreconf render-pddl``: write each schema's PDDL domain and problem to a folder."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.common import (
    FailOption,
    LibraryOption,
    ObjectiveOption,
    OnlyOption,
    SchemaOption,
    select,
    weights_of,
)
from rosreconf.cli.console import write_stdout
from rosreconf.cli.plan import CurrentOption, currents
from rosreconf.errors import ExitCode
from rosreconf.planning.pddl import render
from rosreconf.planning.replan import write_task
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import Objective


def render_pddl(
    output: Annotated[
        Path,
        typer.Option(
            "--output", "-o", help="Folder to write <schema>/domain.pddl and problem.pddl into."
        ),
    ],
    library: LibraryOption = None,
    schema: SchemaOption = None,
    fail: FailOption = None,
    only: OnlyOption = None,
    current: CurrentOption = None,
    objective: ObjectiveOption = None,
) -> None:
    """Write the PDDL task of each schema (pre-grounded STRIPS with action costs; docs/pddl.md).

    Each file is written whole or not at all. Exit 0 on success.
    """

    sel = select(library, schema, fail, only)
    weights = weights_of(objective)
    running = currents(sel, current, weights)
    for s in sel.schemas:
        inst = compile_instance(sel.library, s, sel.failed)
        task = render(inst, Objective(running[s.name], weights))
        folder = write_task(task, output)
        write_stdout(f"{folder / 'domain.pddl'}\n{folder / 'problem.pddl'}\n")
    raise typer.Exit(ExitCode.OK)
