"""``rosreconf validate``: check library and schema files, for people and for CI."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode, Problem, Severity
from rosreconf.formats.loader import Loaded, load_reported, load_selection
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

    loaded, found = load_reported(
        lambda positions: load_selection(paths or [], positions=positions)
    )
    if not any(p.severity is Severity.ERROR for p in found):
        empty = _without_configuration(loaded)
        if empty and any(s.span.line == 0 for s in loaded.schemas):  # loaded without positions
            loaded = load_selection(paths or [], positions=True)
            empty = _without_configuration(loaded)
        found = [*found, *empty]
    problems = sorted(found)
    write_stdout(REPORTERS[output_format].render(loaded.files, problems, loaded.note))
    failing = [p for p in problems if strict or p.severity is Severity.ERROR]
    raise typer.Exit(ExitCode.FAILED if failing else ExitCode.OK)


def _without_configuration(loaded: Loaded) -> list[Problem]:
    """Warn, at the schema, for each schema the library cannot fill at all, saying why.

    Decided by ``solve.instance``'s pruning (local reasoning, no solver: validate stays fast
    and never loads clingo), and said in ``enumerate``'s words (``explain``). Pruning is
    sound, not complete: a schema whose every role keeps candidates but whose candidates
    never combine is left to ``enumerate``.
    """
    if not loaded.library_complete or not loaded.libraries:
        return []
    from rosreconf.solve.instance import compile_instance, explain, prune

    library = loaded.library
    warnings = []
    for schema in loaded.schemas:
        inst = compile_instance(library, schema)
        if not prune(inst)[2]:
            continue
        warnings.append(
            Problem(
                schema.span,
                f"schema '{schema.name}' has no configuration over the library: {explain(inst)}",
                hint="rosreconf enumerate says the same; add or fix the components it names",
                code="no-configuration",
                severity=Severity.WARNING,
            )
        )
    return warnings
