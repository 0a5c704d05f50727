"""``rosreconf snapshot``, ``import`` and ``inspect``: read a running ROS 1 or ROS 2 system."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from rosreconf.cli.common import (
    ConfigurationOption,
    JsonOption,
    LibraryOption,
    SchemaOption,
    select,
)
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.cli.target import checked
from rosreconf.errors import ExitCode, UsageError
from rosreconf.formats.configfile import read_configurations
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.outfiles import write_atomic
from rosreconf.ros.conformance import compare
from rosreconf.ros.importer import draft_library
from rosreconf.ros.livegraph import LiveGraph, from_json, to_json, without_plumbing
from rosreconf.ros.sources import open_source

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


def target(
    libraries: list[Path] | None,
    schemas: list[Path] | None,
    configuration: Path | None,
    only: str | None,
) -> tuple[ComponentLibrary, InteroperabilitySchema, Configuration]:
    """Return the library, the one schema and the (valid) configuration a live command checks.

    Raises:
        UsageError: no single schema is named, or it has no configuration to use.
        RosreconfError: the configuration leaves a role empty or is not valid (exit 1).
        InvalidInputError: the files are invalid.
    """
    sel = select(libraries, schemas, None, [only] if only else None)
    configs = read_configurations(configuration) if configuration else {}
    names = [s.name for s in sel.schemas if not configs or s.name in configs]
    if len(names) != 1:
        choices = ", ".join(names) or "none"
        raise UsageError(f"name one schema with --only (schemas to choose from: {choices})")
    schema = next(s for s in sel.schemas if s.name == names[0])
    mapping = configs.get(schema.name) or dict(schema.nominal)
    if not mapping:
        raise UsageError(f"{schema.name} has no nominal configuration: give --configuration")
    source = configuration if schema.name in configs else Path(f"nominal of {schema.source}")
    config = checked(sel, schema, mapping, source)
    return sel.library, schema, config


def snapshot_command(
    master: OptionalMasterOption = None,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Write here (default: stdout).")
    ] = None,
    ros2: Ros2Option = False,
    domain: DomainOption = 0,
    distro: DistroOption = None,
) -> None:
    """Save the live graph (nodes, topics, services, types; pids or QoS) as JSON."""

    text = to_json(_live(master, None, ros2, domain, distro))
    if output is None:
        write_stdout(text)
    else:
        write_atomic(output, text)


def import_command(
    output: Annotated[Path, typer.Option("--output", "-o", help="The library file to write.")],
    master: Annotated[
        str | None, typer.Option("--master", help="Read this ROS master's URI.")
    ] = None,
    snapshot: Annotated[
        Path | None, typer.Option("--snapshot", help="Read a saved 'rosreconf snapshot'.")
    ] = None,
    name: Annotated[str, typer.Option(help="The library's name.")] = "imported",
    ros2: Ros2Option = False,
    domain: DomainOption = 0,
    distro: DistroOption = None,
) -> None:
    """Draft a component library (one component per live node) with TODOs to fill in."""

    graph = _live(master, snapshot, ros2, domain, distro)
    text = draft_library(graph, name)
    write_atomic(output, text)
    todo, nodes = text.count("# TODO"), len(without_plumbing(graph).nodes)
    stderr.print(
        f"rosreconf: wrote {output}: {nodes} node(s) read, {todo} TODO(s) to fill in",
        markup=False,
    )


def _live(
    master: str | None,
    snapshot: Path | None,
    ros2: bool = False,
    domain: int = 0,
    distro: str | None = None,
) -> LiveGraph:
    """Read the live graph from exactly one of a master, ROS 2 discovery and a snapshot."""
    if sum((master is not None, snapshot is not None, ros2)) != 1:
        raise UsageError("give exactly one of --master URI, --ros2 and --snapshot FILE")
    if snapshot is not None:
        try:
            return from_json(snapshot.read_text(encoding="utf-8"), str(snapshot))
        except OSError as exc:
            raise UsageError(f"{snapshot}: cannot read: {exc.strerror}") from None
    source = open_source(master, ros2, domain, distro)
    try:
        return source.read()
    finally:
        source.close()


def inspect_command(
    master: OptionalMasterOption = None,
    snapshot: Annotated[
        Path | None,
        typer.Option("--snapshot", help="Inspect a saved 'rosreconf snapshot' instead."),
    ] = None,
    configuration: ConfigurationOption = None,
    only: OnlySchemaOption = None,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    as_json: JsonOption = False,
    ros2: Ros2Option = False,
    domain: DomainOption = 0,
    distro: DistroOption = None,
) -> None:
    """Compare the live ROS-graph with the configuration's; exit 0 if it conforms, else 1."""

    lib, sch, config = target(library, schema, configuration, only)
    graph = _live(master, snapshot, ros2, domain, distro)
    result = compare(config, lib, sch, graph)
    if as_json:
        write_stdout(json.dumps(result.to_dict(), indent=2) + "\n")
    else:
        head = "conforms to" if result.ok else "does NOT conform to"
        where = graph.master_uri
        write_stdout(f"{where}: the live system {head} the {sch.display_name} configuration\n")
        for f in result.findings:
            write_stdout(f"  {f.code}: {f.message}\n")
    raise typer.Exit(ExitCode.OK if result.ok else ExitCode.FAILED)
