"""``rosreconf task``: ask a running ``watch --ros2`` to switch task, without ROS 2 tools."""

from __future__ import annotations

import os
from typing import Annotated

import typer

from rosreconf.cli.common import DomainOption
from rosreconf.cli.console import write_stdout
from rosreconf.errors import ExitCode, UsageError
from rosreconf.ros.connect import ask_switch
from rosreconf.ros.livegraph import FACE_NAME, is_own_face


def task_command(
    task: Annotated[str, typer.Argument(help="The task (a schema's name) to switch to.")],
    domain: DomainOption = 0,
    face_name: Annotated[
        str, typer.Option("--face-name", help="The face node of the watch to ask.")
    ] = FACE_NAME,
    timeout: Annotated[
        float,
        typer.Option(min=0.5, max=600, help="Seconds to wait for the face to appear and answer."),
    ] = 10.0,
) -> None:
    """Ask a running watch --ros2 to switch task; exit 0 taken, 1 refused (why), 3 no answer.

    Sets the task parameter of the watch's face (a SetParameters call, what ``ros2 param
    set`` does, through rosreconf's ROS 2 Python; sent again after 1.5 s unanswered, as DDS
    can lose the answer to a client the face has not matched yet). The watch decides at once
    from what it can reach now and answers; the switch runs after the answer, and its JSON
    log says ``task``, then ``conformant``. Refused (exit 1, the reason on stdout): not one
    of the watch's tasks, no configuration of it without the failed components, or a switch
    to another task under way (a switch to this one under way is taken).
    Exit 3: no ROS 2 Python, or no face answered on the domain within --timeout.
    """
    if not is_own_face(face_name):
        raise UsageError(f"--face-name {face_name}: not a name a face of rosreconf has")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["ROS_DOMAIN_ID"] = str(domain)
    taken, reason = ask_switch(face_name, task, env, timeout)
    if not taken:
        write_stdout(f"{face_name} refused the switch to {task}: {reason}\n")
        raise typer.Exit(ExitCode.FAILED)
    write_stdout(f"{face_name} took the switch to {task}: its log says task, then conformant\n")
