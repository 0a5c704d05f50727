"""Options shared by the commands, so that every verb spells and documents them the same way.

The input they select is loaded and checked by ``rosreconf.formats.selection.select`` (kept
importable from here as ``select`` and ``Selection``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Annotated, Any

import typer

from rosreconf.errors import UsageError
from rosreconf.formats.selection import Selection, select
from rosreconf.model import ComponentLibrary

__all__ = [  # the input the options select, then the options
    "ConfigurationOption",
    "ContextOption",
    "CurrentOption",
    "DistroOption",
    "DomainOption",
    "FailOption",
    "IgnoreContextOption",
    "JsonOption",
    "LibraryOption",
    "MasterOption",
    "ObjectiveOption",
    "OnlyOption",
    "OnlySchemaOption",
    "OptionalMasterOption",
    "OutputOption",
    "Ros2Option",
    "SchemaOption",
    "Selection",
    "finite",
    "select",
    "weights_of",
]


def finite(value: float | None) -> float | None:
    """Refuse NaN and infinity for a float option (typer's ``min``/``max`` let NaN through)."""
    if value is not None and not math.isfinite(value):
        raise typer.BadParameter(f"{value} is not a finite number")
    return value


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
ContextOption = Annotated[
    list[str] | None,
    typer.Option(
        "--context",
        metavar="NAME=VALUE",
        help="A measured context value (repeatable): components whose 'when' conditions "
        "fail under it are unusable, as failed ones are (docs/context.md).",
        show_default=False,
    ),
]
IgnoreContextOption = Annotated[
    bool,
    typer.Option(
        "--ignore-context",
        help="Take conditions on context values not given by --context to hold (without it, "
        "such a condition is an error).",
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
        "Default: the schema's nominal configuration, else its first valid one (under --fail, "
        "the valid one nearest to it).",
        show_default=False,
    ),
]
OutputOption = Annotated[
    str,
    typer.Option(
        "--output",
        "-o",
        metavar="FILE",
        help="File to write, or - for stdout. A symlink is written through; devices, FIFOs "
        "and folders are refused.",
        show_default=False,
    ),
]
MasterOption = Annotated[
    str,
    typer.Option("--master", help="The ROS master's URI, e.g. http://127.0.0.1:11311/."),
]
MasterTimeoutOption = Annotated[
    float,
    typer.Option(
        "--master-timeout",
        min=0.1,
        metavar="SECONDS",
        help="Total seconds one call to the master or a node may take, whole answer included.",
    ),
]
MaxAnswerOption = Annotated[
    int,
    typer.Option(
        "--max-answer-mb",
        min=1,
        metavar="MIB",
        help="The largest answer accepted from the master; a longer one is cut off (exit 3).",
    ),
]
OnlySchemaOption = Annotated[
    str | None,
    typer.Option("--only", help="The schema, when the configuration names several."),
]
OptionalMasterOption = Annotated[
    str | None,
    typer.Option("--master", help="The ROS master's URI, e.g. http://127.0.0.1:11311/."),
]
Ros2Option = Annotated[
    bool, typer.Option("--ros2", help="Read a ROS 2 graph from DDS discovery (rosreconf[ros2]).")
]
DomainOption = Annotated[
    int,
    typer.Option("--domain", envvar="ROS_DOMAIN_ID", help="The ROS 2 domain id (ROS_DOMAIN_ID)."),
]
DistroOption = Annotated[
    str | None,
    typer.Option(
        "--distro", help="The ROS 2 distribution (humble, jazzy, ...); default: read both layouts."
    ),
]
CurrentOption = Annotated[
    Path | None,
    typer.Option(
        "--current",
        metavar="FILE",
        help="What runs now (a configuration file, or the JSON of enumerate/plan). Default: "
        "each schema's declared nominal configuration, else its best by --objective, else its "
        "first valid one.",
        show_default=False,
    ),
]


WorkersOption = Annotated[
    int | None,
    typer.Option(min=1, help="Worker processes. Default: one per core.", show_default=False),
]


def _cluster(work: str) -> Any:
    """Return the ``--cluster`` option, saying what the scheduler's workers do."""
    return typer.Option(help=f"{work} on a Dask scheduler at tcp://HOST:PORT.", show_default=False)


SimulateClusterOption = Annotated[str | None, _cluster("Simulate")]
SolveClusterOption = Annotated[str | None, _cluster("Solve")]


def _search_limit(spent: str) -> Any:
    """Return the ``--search-limit`` option, saying what happens when it is spent."""
    return typer.Option(
        "--search-limit",
        min=1,
        max=10_000_000,
        help="When the fewest-change configuration fails the performance requirements: the "
        f"most configurations simulated to find one that meets them (then {spent}). Memory "
        "grows with it, not with the number of valid configurations.",
    )


def _search_time(spent: str) -> Any:
    """Return the ``--search-time`` option, saying what happens when it is spent."""
    return typer.Option(
        "--search-time",
        min=1,
        max=7 * 24 * 3600.0,
        callback=finite,
        help=f"The most seconds spent on that search (then {spent}).",
    )


_PLAN_SPENT = "exit 3, saying what was tried"
_WATCH_SPENT = "log no-configuration, saying what was tried, and keep watching"
SearchLimitOption = Annotated[int, _search_limit(_PLAN_SPENT)]
SearchTimeOption = Annotated[float, _search_time(_PLAN_SPENT)]
WatchSearchLimitOption = Annotated[int, _search_limit(_WATCH_SPENT)]
"""``watch`` goes on watching when a search is spent: a later failure may have an answer."""
WatchSearchTimeOption = Annotated[float, _search_time(_WATCH_SPENT)]
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


def weights_of(
    objective: Sequence[str] | None, library: ComponentLibrary, flag: str = "--objective"
) -> dict[str, float]:
    """Parse ``metric=weight`` options into the weights of an objective on ``library``.

    A metric no component carries is refused, as ``simulate --pareto`` refuses one: it
    would weigh 0 everywhere, and a misspelt ``--objective cots=1`` would silently choose
    by the other rules alone.

    Raises:
        UsageError: an item is not ``metric=weight`` with a number, or names no metric of
            the library.
    """
    weights: dict[str, float] = {}
    for item in objective or []:
        written, sep, value = item.partition("=")
        name = written.strip()
        try:
            weights[name] = float(value)
        except ValueError:
            sep = ""
        if not sep or not name:
            raise UsageError(f"{flag} {item}: write metric=weight, e.g. cost=1")
        if name not in library.metrics:
            known = ", ".join(sorted(library.metrics)) or "none: no component has metrics"
            raise UsageError(f"{flag} {item}: unknown metric '{name}' (the library's: {known})")
    return weights
