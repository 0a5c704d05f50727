"""The command line: parse options, build objects, call the library, map errors to exit codes.

Each verb lives in ``rosreconf/commands/<verb>.py`` and registers itself on ``app``; this
module only owns the app, the shared console and ``main``.
"""

from __future__ import annotations

import typer

app = typer.Typer(
    name="rosreconf",
    help="Configure and reconfigure ROS systems from a component library (Aitken et al. 2014).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def main() -> None:
    """Run the CLI (the console script and ``python -m rosreconf``)."""
    app()
