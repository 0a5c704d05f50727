"""``rosreconf validate``: check library and schema files, for people and for CI."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.common import JsonOption, LibraryOption, SchemaOption
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode, Severity
from rosreconf.formats.loader import load_paths, load_selection, load_split, problems_of
from rosreconf.render.report import REPORTERS, OutputFormat
from rosreconf.solve.unfillable import schemas_without_configuration


def validate(
    paths: Annotated[
        list[Path] | None,
        typer.Argument(
            help="Library and schema files or folders. Default: libraries/ and schemas/ here, "
            "else the bundled example.",
            show_default=False,
        ),
    ] = None,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    output_format: Annotated[
        OutputFormat,
        typer.Option("--format", "-f", help="How to report problems (--json: json)."),
    ] = OutputFormat.TEXT,
    json_output: JsonOption = False,
    strict: Annotated[bool, typer.Option(help="Fail on warnings too.")] = False,
) -> None:
    """Check component libraries and interoperability schemas; exit 0 valid, 1 invalid, 2 usage.

    Files are given as PATHS (either kind, told apart by their 'format' key) or, as the
    other commands take them, with -l/--library and -s/--schema; --json is --format json.
    """
    if library or schema:
        libraries, schemas = library or [], schema or []
        loaded = (
            load_paths([*(paths or []), *libraries, *schemas])
            if paths
            else load_split(libraries, schemas)
        )
    else:
        loaded = load_selection(paths or [])
    found = problems_of(loaded)
    clean = not any(p.severity is Severity.ERROR for p in found)
    if clean and loaded.library_complete and loaded.libraries:
        found = [*found, *schemas_without_configuration(loaded.library, loaded.schemas)]
    problems = sorted(found)
    shown = OutputFormat.JSON if json_output else output_format
    write_stdout(REPORTERS[shown].render(loaded.files, problems, loaded.note))
    failing = [p for p in problems if strict or p.severity is Severity.ERROR]
    raise typer.Exit(ExitCode.FAILED if failing else ExitCode.OK)
