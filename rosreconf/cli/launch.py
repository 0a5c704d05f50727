"""``rosreconf launch``: write a ROS 1 or ROS 2 launch file that starts one configuration."""

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
from rosreconf.errors import ExitCode, UsageError
from rosreconf.outfiles import output_target
from rosreconf.ros.launchfiles import RosVersion, launch_file
from rosreconf.solve.running import targets


def launch_command(
    output: OutputOption,
    library: LibraryOption = None,
    schema: SchemaOption = None,
    only: OnlyOption = None,
    configuration: ConfigurationOption = None,
    fail: FailOption = None,
    ros1: Annotated[bool, typer.Option("--ros1", help="Write roslaunch XML (ROS 1).")] = False,
    ros2: Annotated[bool, typer.Option("--ros2", help="Write ROS 2 launch XML.")] = False,
) -> None:
    """Write a launch file starting exactly one schema's configuration, wired by remappings.

    Exit 0 when written, 1 when a component has no 'ros:' entry or there is no
    configuration, 2 when the options do not pick exactly one schema and one ROS version.
    """

    if ros1 == ros2:
        raise UsageError("give exactly one of --ros1 and --ros2")
    out = output_target(output)
    sel = select(library, schema, fail, only)
    found = targets(sel, configuration)
    if len(found) != 1:
        names = ", ".join(t.schema.name for t in found)
        raise UsageError(f"a launch file starts one schema; choose one with --only ({names})")
    (target,) = found
    version = RosVersion.ROS1 if ros1 else RosVersion.ROS2
    result = launch_file(sel.library, target.schema, target.configuration, version)
    where = write_output(out, result.text)
    for note in result.notes:
        stderr.print(f"rosreconf: note: {note}", markup=False)
    stderr.print(
        f"rosreconf: wrote {where} ({version.value}, {len(result.nodes)} nodes: "
        f"{', '.join(result.nodes)})",
        markup=False,
    )
    raise typer.Exit(ExitCode.OK)
