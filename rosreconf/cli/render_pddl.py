"""``rosreconf render-pddl``: write each schema's PDDL domain and problem to a folder."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.cli.common import (
    CurrentOption,
    FailOption,
    LibraryOption,
    ObjectiveOption,
    OnlyOption,
    SchemaOption,
    select,
    weights_of,
)
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode
from rosreconf.outfiles import output_folder
from rosreconf.planning.replan import write_tasks
from rosreconf.solve.running import running_mappings


def render_pddl(
    output: Annotated[
        str,
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

    The pair is written into a temp folder and moved into place as one, so concurrent runs
    never leave a domain and a problem from different runs. Exit 0 on success, 2 when the
    output is not a folder.
    """

    sel = select(library, schema, fail, only)
    weights = weights_of(objective, sel.library)
    running = running_mappings(sel, current, weights)
    folder = output_folder(output)  # made only once the input is known good
    written = write_tasks(sel.library, sel.schemas, sel.failed, running, weights, folder)
    write_stdout("".join(f"{path}\n" for path in written))
    raise typer.Exit(ExitCode.OK)
