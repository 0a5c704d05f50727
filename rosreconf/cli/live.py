"""``rosreconf snapshot``, ``import`` and ``inspect``: read a running ROS 1 or ROS 2 system."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import typer

from rosreconf.cli.common import (
    ConfigurationOption,
    DistroOption,
    DomainOption,
    JsonOption,
    LibraryOption,
    MasterTimeoutOption,
    MaxAnswerOption,
    OnlySchemaOption,
    OptionalMasterOption,
    Ros2Option,
    SchemaOption,
    finite,
    select,
)
from rosreconf.cli.console import stderr, write_output, write_stdout
from rosreconf.errors import ExitCode
from rosreconf.outfiles import output_target
from rosreconf.render.reports import Output
from rosreconf.render.reports.inspect import REPORTERS
from rosreconf.ros.conformance import compare
from rosreconf.ros.connect import DEFAULT_MAX_BYTES, DEFAULT_SPIN_TIME, DEFAULT_TIMEOUT, read_any
from rosreconf.ros.importer import draft_library, is_anonymous
from rosreconf.ros.livegraph import LiveGraph, to_json, without_plumbing
from rosreconf.solve.running import one_target

SpinTimeOption = Annotated[
    float | None,
    typer.Option(
        "--spin-time",
        min=0.0,
        max=600.0,
        callback=finite,
        metavar="SECONDS",
        help=f"ROS 2: listen at least this long for discovery before the read may settle "
        f"(as ros2cli's --spin-time; default {DEFAULT_SPIN_TIME:g}: Fast DDS announces every "
        "3 s). Longer on a loaded host, where a participant can answer late and be left out.",
        show_default=False,
    ),
]


def _note(text: str) -> None:
    """Say what a ROS 2 read had to leave out (on stderr; the output stays clean)."""
    stderr.print(text, markup=False)


@dataclass(frozen=True)
class LiveRead:
    """How a command reads a live graph: the options of every command that reads one."""

    timeout: float
    max_bytes: int
    ros2: bool
    domain: int
    distro: str | None
    spin_time: float | None

    def graph(self, master: str | None, snapshot: Path | None) -> LiveGraph:
        """Read the graph from ``master``, a saved ``snapshot`` or ROS 2 discovery."""
        return read_any(
            master,
            snapshot,
            self.ros2,
            self.domain,
            self.distro,
            timeout=self.timeout,
            max_bytes=self.max_bytes,
            on_note=_note,
            spin_time=self.spin_time,
        )


def _live_read(
    master_timeout: MasterTimeoutOption = DEFAULT_TIMEOUT,
    max_answer_mb: MaxAnswerOption = DEFAULT_MAX_BYTES >> 20,
    ros2: Ros2Option = False,
    domain: DomainOption = 0,
    distro: DistroOption = None,
    spin_time: SpinTimeOption = None,
) -> LiveRead:
    """Declare the live-read options once; ``reads_live`` gives them to each command."""
    return LiveRead(master_timeout, max_answer_mb << 20, ros2, domain, distro, spin_time)


def reads_live(command: Callable[..., None]) -> Callable[..., None]:
    """Give ``command`` the live-read options, passed to it as one ``read: LiveRead``.

    Typer reads a command's options from its signature, so the returned command's signature
    is ``command``'s own without ``read``, followed by ``_live_read``'s parameters: the
    options keep their place at the end of ``--help``, and a new one is added in one place.
    """
    own = inspect.signature(command, eval_str=True)
    options = inspect.signature(_live_read, eval_str=True).parameters

    @functools.wraps(command)
    def with_options(**given: Any) -> None:
        read = _live_read(**{name: given.pop(name) for name in options})
        command(**given, read=read)

    params = [p for p in own.parameters.values() if p.name != "read"]
    params += options.values()
    with_options.__signature__ = own.replace(parameters=params)  # type: ignore[attr-defined]
    with_options.__annotations__ = {p.name: p.annotation for p in params}
    return with_options


@reads_live
def snapshot_command(
    master: OptionalMasterOption = None,
    output: Annotated[
        str, typer.Option("--output", "-o", help="Write here (- or default: stdout).")
    ] = "-",
    *,
    read: LiveRead,
) -> None:
    """Save the live graph (nodes, topics, services, types; pids or QoS) as JSON."""

    target = output_target(output)
    text = to_json(read.graph(master, None))
    write_output(target, text)


@reads_live
def import_command(
    output: Annotated[
        str, typer.Option("--output", "-o", help="The library file to write (- for stdout).")
    ],
    master: Annotated[
        str | None, typer.Option("--master", help="Read this ROS master's URI.")
    ] = None,
    snapshot: Annotated[
        Path | None, typer.Option("--snapshot", help="Read a saved 'rosreconf snapshot'.")
    ] = None,
    name: Annotated[str, typer.Option(help="The library's name.")] = "imported",
    *,
    read: LiveRead,
) -> None:
    """Draft a component library (one component per live node) with TODOs to fill in."""

    target = output_target(output)
    graph = read.graph(master, snapshot)
    text = draft_library(graph, name)
    where = write_output(target, text)
    live = without_plumbing(graph).nodes
    todo, nodes = text.count("# TODO"), len(live)
    stderr.print(
        f"rosreconf: wrote {where}: {nodes} node(s) read, {todo} TODO(s) to fill in",
        markup=False,
    )
    anonymous = [n.name for n in live if is_anonymous(n.name)]
    if anonymous:
        stderr.print(
            f"rosreconf: warning: {', '.join(anonymous)} "
            f"{'has an anonymous name' if len(anonymous) == 1 else 'have anonymous names'}"
            " that change on every restart; inspect and watch will not find them again"
            " (start them under fixed names and set ros.node)",
            markup=False,
        )


@reads_live
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
    *,
    read: LiveRead,
) -> None:
    """Compare the live ROS-graph with the configuration's; exit 0 if it conforms, else 1.

    Exit 3 when the live graph cannot be read: no master answering, or nothing ROS 2
    readable on the domain.
    """

    sel = select(library, schema, None, [only] if only else None)
    target = one_target(sel, configuration)
    graph = read.graph(master, snapshot)
    result = compare(target.configuration, sel.library, target.schema, graph)
    write_stdout(REPORTERS[Output.of(as_json)].render(result, target.schema))
    raise typer.Exit(ExitCode.OK if result.ok else ExitCode.FAILED)
