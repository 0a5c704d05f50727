"""``rosreconf validate``: check library and schema files, for people and for CI."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode, Severity
from rosreconf.formats.loader import load_selection, problems_of
from rosreconf.render.report import REPORTERS, OutputFormat


def validate(
    paths: Annotated[
        list[Path] | None,
        typer.Argument(
            help="Library and schema files or folders. Default: libraries/ and schemas/ here, "
            "else the bundled example.",
            show_default=False,
        ),
    ] = None,
    output_format: Annotated[
        OutputFormat, typer.Option("--format", "-f", help="How to report problems.")
    ] = OutputFormat.TEXT,
    strict: Annotated[bool, typer.Option(help="Fail on warnings too.")] = False,
) -> None:
    """Check component libraries and interoperability schemas; exit 0 valid, 1 invalid, 2 usage."""

    loaded = load_selection(paths or [])
    problems = sorted(problems_of(loaded))
    write_stdout(REPORTERS[output_format].render(loaded.files, problems, loaded.note))
    failing = [p for p in problems if strict or p.severity is Severity.ERROR]
    raise typer.Exit(ExitCode.FAILED if failing else ExitCode.OK)
