"""``rosreconf generate``: write a large layered library and schema for benchmarks."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.cli.common import finite
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode, UsageError
from rosreconf.outfiles import output_folder
from rosreconf.synthetic import MAX_COMPONENTS, check_file_sizes, check_sizes, generate, write


def generate_command(
    roles: Annotated[
        int,
        typer.Option(
            "--roles", "-r", min=1, max=MAX_COMPONENTS, help="Number of roles R (R x K <= 200,000)."
        ),
    ],
    candidates: Annotated[
        int,
        typer.Option(
            "--candidates", "-k", min=1, max=MAX_COMPONENTS, help="Candidates per role K."
        ),
    ],
    output: Annotated[
        str, typer.Option("--output", "-o", help="Folder to write libraries/ and schemas/ into.")
    ],
    coupling: Annotated[
        float,
        typer.Option(
            min=0.0,
            max=1.0,
            callback=finite,
            help="Share of edges carrying a needs/excludes coupling.",
        ),
    ] = 0.2,
    seed: Annotated[int, typer.Option(help="Random seed; the same seed gives the same files.")] = 0,
    dynamics: Annotated[
        bool,
        typer.Option(
            "--dynamics",
            help="Also give every component a transfer function and the schema a simulation "
            "block (one loop per actuator), for rosreconf simulate.",
        ),
    ] = False,
) -> None:
    """Generate a layered library and schema shaped like the paper's Figure 2.

    Sensors, perception, control and actuators; interface families so that not every pair
    fits; couplings at density D. The files validate and have a configuration; the same seed
    gives the same bytes.
    """

    try:
        check_sizes(roles, candidates, coupling)  # before the folder is made
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    generated = generate(roles, candidates, coupling, seed, dynamics=dynamics)
    try:
        check_file_sizes(generated)  # before the folder is made, too
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    lib, schema = write(generated, output_folder(output))
    write_stdout(f"wrote {lib} and {schema}\n")
    raise typer.Exit(ExitCode.OK)
