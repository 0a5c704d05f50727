"""``rosreconf graph``: draw a system graph, a ROS-graph or the library as DOT, SVG or PNG."""

from __future__ import annotations

from typing import Annotated

import typer

from rosreconf.cli.common import (
    ConfigurationOption,
    FailOption,
    LibraryOption,
    OnlyOption,
    OutputOption,
    SchemaOption,
    select,
)
from rosreconf.cli.console import stderr, write_output
from rosreconf.errors import ExitCode
from rosreconf.outfiles import output_target
from rosreconf.render.pictures import (
    RosPicture,
    View,
    library_dot,
    picture,
    ros_dot,
    system_dot,
)
from rosreconf.solve.running import targets


def graph_command(
    output: OutputOption,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    configuration: ConfigurationOption = None,
    fail: FailOption = None,
    view: Annotated[
        View, typer.Option(help="system: system graphs; ros: ROS-graphs; library: candidates.")
    ] = View.ROS,
    fmt: Annotated[
        str | None,
        typer.Option(
            "--format", help="dot, svg or png. Default: from the file suffix.", show_default=False
        ),
    ] = None,
) -> None:
    """Draw the schemas' system graphs, a configuration's ROS-graph, or the library.

    Exit 0 when the picture is written, 1 when a schema has no configuration to draw,
    3 when Graphviz's dot is missing or fails.
    """

    target = output_target(output)
    sel = select(library, schema, fail, only)
    if view is View.SYSTEM:
        text = system_dot(sel.schemas)
    elif view is View.LIBRARY:
        text = library_dot(sel.library, sel.schemas, sel.failed)
    else:
        pictures = [
            RosPicture(t.schema, t.configuration, t.before) for t in targets(sel, configuration)
        ]
        text = ros_dot(sel.library, pictures, sel.failed)
    data, written = picture(target.shown, text, fmt)
    where = write_output(target, data)
    stderr.print(f"rosreconf: wrote {where} ({view.value} view, {written})", markup=False)
    raise typer.Exit(ExitCode.OK)
