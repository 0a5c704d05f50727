"""The command line: parse options, build objects, call the library, map errors to exit codes.

Each verb lives in ``rosreconf/commands/<verb>.py`` as a plain function with typer
annotations; ``COMMANDS`` below registers them. Library code raises ``RosreconfError``;
``guard`` turns it into one line on stderr and the documented exit code (see
``rosreconf.errors.ExitCode``), so the user never sees a traceback.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from typing import ParamSpec, TypeVar

import typer
from rich.console import Console

from rosreconf import __version__
from rosreconf.errors import ExitCode, InvalidInputError, RosreconfError

P = ParamSpec("P")
R = TypeVar("R")

stdout = Console(highlight=False, soft_wrap=True)
stderr = Console(stderr=True, highlight=False, soft_wrap=True)

app = typer.Typer(
    name="rosreconf",
    help="Configure and reconfigure ROS systems from a component library "
    "(Aitken, Veres and Judge, IFAC 2014).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


def guard(command: Callable[P, R]) -> Callable[P, R]:
    """Run a command body, turning rosreconf errors and Ctrl-C into exit codes."""

    @functools.wraps(command)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return command(*args, **kwargs)
        except InvalidInputError as exc:
            for problem in exc.problems:
                stderr.print(str(problem), markup=False)
            raise typer.Exit(exc.exit_code) from None
        except RosreconfError as exc:
            stderr.print(f"rosreconf: error: {exc}", markup=False)
            raise typer.Exit(exc.exit_code) from None
        except KeyboardInterrupt:
            stderr.print("rosreconf: interrupted", markup=False)
            raise typer.Exit(130) from None

    return wrapper


def write_stdout(text: str) -> None:
    """Write ``text`` to stdout exactly (JSON documents must not be re-wrapped by rich)."""
    sys.stdout.write(text)
    sys.stdout.flush()


def _version(value: bool) -> None:
    if value:
        write_stdout(f"rosreconf {__version__}\n")
        raise typer.Exit(ExitCode.OK)


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Configure and reconfigure ROS systems from a component library."""


def _register() -> None:
    from rosreconf.commands import (
        analyse,
        generate,
        graph,
        launch,
        live,
        plan,
        redundancy,
        render_pddl,
        validate,
        watch,
        whatif,
    )
    from rosreconf.commands import enumerate as enumerate_

    commands: dict[str, Callable[..., object]] = {
        "validate": validate.validate,
        "enumerate": enumerate_.enumerate_command,
        "analyse": analyse.analyse_command,
        "redundancy": redundancy.redundancy_command,
        "graph": graph.graph_command,
        "launch": launch.launch_command,
        "snapshot": live.snapshot_command,
        "import": live.import_command,
        "inspect": live.inspect_command,
        "watch": watch.watch_command,
        "render-pddl": render_pddl.render_pddl,
        "plan": plan.plan_command,
        "generate": generate.generate_command,
        "whatif": whatif.whatif_command,
    }
    for name, function in commands.items():
        app.command(name)(guard(function))


_register()


def main() -> None:
    """Run the CLI (the console script and ``python -m rosreconf``)."""
    app()
