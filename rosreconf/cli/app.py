"""The command line: parse options, build objects, call the library, map errors to exit codes.

Each verb lives in ``rosreconf/cli/<verb>.py`` as a plain function with typer
annotations; ``_register`` below registers them. Library code raises ``RosreconfError``;
``guard`` turns it into one line on stderr and the documented exit code (see
``rosreconf.errors.ExitCode``), so the user never sees a traceback.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import ParamSpec, TypeVar

import typer

from rosreconf import __version__
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.errors import ExitCode, InvalidInputError, RosreconfError

P = ParamSpec("P")
R = TypeVar("R")

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
    from rosreconf.cli import (
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
    from rosreconf.cli import enumerate as enumerate_

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
