"""Options and input selection shared by the solving commands (enumerate, analyse, plan...).

Every command picks its files the same way (``loader.load_split``) and checks ``--fail``
names the same way, so their answers are always about the same library and schemas.
"""

from __future__ import annotations

import difflib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated

import typer

from rosreconf.errors import UsageError
from rosreconf.formats.loader import Loaded, load_checked
from rosreconf.model import ComponentLibrary, InteroperabilitySchema

ObjectiveOption = Annotated[
    list[str] | None,
    typer.Option(
        "--objective",
        metavar="METRIC=WEIGHT",
        help="metric=weight: after the fewest changes, minimise the weighted metric sum "
        "(repeatable).",
        show_default=False,
    ),
]


def weights_of(objective: Sequence[str] | None) -> dict[str, float]:
    """Parse ``metric=weight`` options (shared by plan, render-pddl and enumerate --best)."""
    weights: dict[str, float] = {}
    for item in objective or []:
        name, sep, value = item.partition("=")
        try:
            weights[name.strip()] = float(value)
        except ValueError:
            sep = ""
        if not sep or not name.strip():
            raise UsageError(f"--objective {item}: write metric=weight, e.g. cost=1")
    return weights


LibraryOption = Annotated[
    list[Path] | None,
    typer.Option(
        "--library",
        "-l",
        metavar="FILE",
        help="Component library file or folder (repeatable). Default: libraries/ here, "
        "else the bundled example.",
        show_default=False,
    ),
]
SchemaOption = Annotated[
    list[Path] | None,
    typer.Option(
        "--schema",
        "-s",
        metavar="FILE",
        help="Interoperability schema file or folder (repeatable). Default: schemas/ here, "
        "else the bundled example.",
        show_default=False,
    ),
]
FailOption = Annotated[
    list[str] | None,
    typer.Option(
        "--fail",
        metavar="COMPONENT",
        help="Treat this component as failed (repeatable).",
        show_default=False,
    ),
]
OnlyOption = Annotated[
    list[str] | None,
    typer.Option(
        "--only",
        metavar="SCHEMA",
        help="Only this schema, by name (repeatable). Default: every schema.",
        show_default=False,
    ),
]
JsonOption = Annotated[bool, typer.Option("--json", help="Print one JSON document on stdout.")]
ConfigurationOption = Annotated[
    Path | None,
    typer.Option(
        "--configuration",
        "-c",
        metavar="FILE",
        help="Configuration file (enumerate/plan --json, or format: rosreconf/configuration). "
        "Default: the schema's nominal configuration (under --fail, the valid one nearest to it).",
        show_default=False,
    ),
]
OutputOption = Annotated[
    Path, typer.Option("--output", "-o", metavar="FILE", help="File to write.", show_default=False)
]
MasterOption = Annotated[
    str,
    typer.Option("--master", help="The ROS master's URI, e.g. http://127.0.0.1:11311/."),
]


@dataclass(frozen=True)
class Selection:
    """The checked input of a solving command.

    Attributes:
        loaded: what was loaded (files, note).
        library: L, all library files joined.
        schemas: the schemas to work on, in file order.
        failed: the failed components, as given (validated against L).
    """

    loaded: Loaded
    library: ComponentLibrary
    schemas: tuple[InteroperabilitySchema, ...]
    failed: tuple[str, ...]


def select(
    libraries: Sequence[Path] | None,
    schemas: Sequence[Path] | None,
    failed: Sequence[str] | None = None,
    only: Sequence[str] | None = None,
) -> Selection:
    """Load and check the input, and validate ``--fail`` and ``--only`` names.

    Raises:
        InvalidInputError: the files have errors.
        UsageError: an unknown component or schema name was given.
    """
    loaded = load_checked(libraries or [], schemas or [])
    library = loaded.library
    if not library.components:
        raise UsageError("no component library was given or found")
    if not loaded.schemas:
        raise UsageError("no interoperability schema was given or found")
    names = [c.name for c in library]
    for name in failed or []:
        if name not in library:
            raise UsageError(f"--fail {name}: no such component{_did_you_mean(name, names)}")
    chosen = list(loaded.schemas)
    if only:
        known = [s.name for s in chosen]
        for name in only:
            if name not in known:
                raise UsageError(f"--only {name}: no such schema{_did_you_mean(name, known)}")
        chosen = [s for s in chosen if s.name in only]
    return Selection(loaded, library, tuple(chosen), tuple(dict.fromkeys(failed or [])))


def _did_you_mean(name: str, choices: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, choices, n=1)
    return f" (did you mean {close[0]}?)" if close else ""
