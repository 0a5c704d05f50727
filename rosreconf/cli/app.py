"""The command line: parse options, build objects, call the library, map errors to exit codes.

Each verb lives in ``rosreconf/cli/<verb>.py`` as a plain function with typer annotations.
``COMMANDS`` names them, with their one-line summaries, and nothing imports a verb's module
until that verb runs (or shows its own ``--help``): ``rosreconf --help`` and ``validate`` then
never load clingo, networkx, Jinja, the planners or a ROS client (whole-process time; the test
``tests/test_cli_imports.py`` holds this, and that each summary is its docstring's first line).

Library code raises ``RosreconfError``; ``guard`` turns it into one line on stderr and the
documented exit code (see ``rosreconf.errors.ExitCode``), so the user never sees a traceback.
"""

from __future__ import annotations

import contextlib
import functools
import importlib
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterator, MutableMapping
from typing import Any, NamedTuple, NoReturn, ParamSpec, TypeVar

import typer
import typer.core
import typer.main
from typer._click import Command, Context  # typer vendors click: its types are what it builds

from rosreconf import __version__, jsonout
from rosreconf.cli import capped
from rosreconf.cli.capped import OUT_OF_MEMORY
from rosreconf.cli.console import stderr, write_stdout
from rosreconf.errors import ExitCode, InvalidInputError, RosreconfError
from rosreconf.procs.signals import Terminated

P = ParamSpec("P")
R = TypeVar("R")


class Verb(NamedTuple):
    """Where a verb's function lives and what ``rosreconf --help`` says about it.

    Attributes:
        target: ``module:function``, imported only when the verb runs.
        summary: the first line of the function's docstring (a test keeps them equal).
    """

    target: str
    summary: str


COMMANDS: dict[str, Verb] = {
    "validate": Verb(
        "rosreconf.cli.validate:validate",
        "Check component libraries and interoperability schemas; exit 0 valid, 1 invalid, 2 usage.",
    ),
    "enumerate": Verb(
        "rosreconf.cli.enumerate:enumerate_command",
        "List every valid configuration of each schema (or count them), with why-not reasons.",
    ),
    "analyse": Verb(
        "rosreconf.cli.analyse:analyse_command",
        "Analyse orthogonality, redundancy, failure points and reliability of each schema.",
    ),
    "redundancy": Verb(
        "rosreconf.cli.redundancy:redundancy_command",
        "Compute the redundancy r with (1 - p^r)^N >= q (Theorem 10), beside the approximation.",
    ),
    "graph": Verb(
        "rosreconf.cli.graph:graph_command",
        "Draw the schemas' system graphs, a configuration's ROS-graph, or the library.",
    ),
    "launch": Verb(
        "rosreconf.cli.launch:launch_command",
        "Write a launch file starting exactly one schema's configuration, wired by remappings.",
    ),
    "snapshot": Verb(
        "rosreconf.cli.live:snapshot_command",
        "Save the live graph (nodes, topics, services, types; pids or QoS) as JSON.",
    ),
    "import": Verb(
        "rosreconf.cli.live:import_command",
        "Draft a component library (one component per live node) with TODOs to fill in.",
    ),
    "inspect": Verb(
        "rosreconf.cli.live:inspect_command",
        "Compare the live ROS-graph with the configuration's; exit 0 if it conforms, else 1.",
    ),
    "watch": Verb(
        "rosreconf.cli.watch:watch_command",
        "Watch the live system; when a node fails, replan with the fewest changes (and apply).",
    ),
    "task": Verb(
        "rosreconf.cli.task:task_command",
        "Ask a running watch --ros2 to switch task; exit 0 taken, 1 refused (why), 3 no answer.",
    ),
    "render-pddl": Verb(
        "rosreconf.cli.render_pddl:render_pddl",
        "Write the PDDL task of each schema (pre-grounded STRIPS with action costs; docs/pddl.md).",
    ),
    "plan": Verb(
        "rosreconf.cli.plan:plan_command",
        "Re-plan each schema after --fail with a PDDL planner: steps, new configuration, why.",
    ),
    "generate": Verb(
        "rosreconf.cli.generate:generate_command",
        "Generate a layered library and schema shaped like the paper's Figure 2.",
    ),
    "whatif": Verb(
        "rosreconf.cli.whatif:whatif_command",
        "Show which schemas survive each set of up to K failures: critical parts and pairs.",
    ),
    "simulate": Verb(
        "rosreconf.cli.simulate:simulate_command",
        "Simulate every valid configuration's control loops; rank by settling time and error.",
    ),
}
"""Every verb, in the order ``rosreconf --help`` lists them."""


def guard(command: Callable[P, R]) -> Callable[P, R]:
    """Run a command body, turning rosreconf errors, memory, Ctrl-C and SIGTERM into exit codes."""

    @functools.wraps(command)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return command(*args, **kwargs)
        except InvalidInputError as exc:
            _over()
            for problem in exc.problems:
                stderr.print(str(problem), markup=False)
            raise typer.Exit(exc.exit_code) from None
        except RosreconfError as exc:
            _over()
            stderr.print(f"rosreconf: error: {exc}", markup=False)
            raise typer.Exit(exc.exit_code) from None
        except MemoryError:
            # Raised where an allocation failed, anywhere in rosreconf or numpy; by now the
            # frames that held the memory are gone, so the message can be printed.
            out_of_memory()
        except KeyboardInterrupt:
            _over()
            stderr.print("rosreconf: interrupted", markup=False)
            raise typer.Exit(ExitCode.INTERRUPTED) from None
        except Terminated:
            _over()
            stderr.print("rosreconf: terminated", markup=False)
            raise typer.Exit(ExitCode.TERMINATED) from None

    return wrapper


def _over() -> None:
    """Note that the run is over: a Ctrl-C from here on ends the process quietly.

    It gets the signal's default action (the process ends at once, by SIGINT) instead of a
    KeyboardInterrupt, which during the interpreter's teardown is printed as a traceback
    ("Exception ignored in threading._shutdown"; seen when a test stopped a watch that had
    just said its error).
    """
    with contextlib.suppress(ValueError):  # signals are set from the main thread only
        signal.signal(signal.SIGINT, signal.SIG_DFL)


def out_of_memory(*_: object) -> NoReturn:
    """Say ``OUT_OF_MEMORY`` and end with exit 3 at once, from any thread.

    Without memory, the interpreter's own shutdown (thread joins, exit hooks) can fail in turn
    and print its own traceback with exit 1; ending here skips it. The children rosreconf
    started die with it (a parent-death signal), and its temp folders are removed by a later
    run (their marker files). No half document is left in a file (``take_back_stdout``).
    """
    capped.take_back_stdout()
    try:
        sys.stderr.write(OUT_OF_MEMORY + "\n")
        sys.stderr.flush()
    finally:
        os._exit(ExitCode.PLANNER)


def _stop_dropped(args: Any) -> None:
    """End the run when Python drops a Ctrl-C or SIGTERM ("Exception ignored in ...").

    A signal's exception raised inside a finalizer or a weakref callback (an import's module
    lock has one; the garbage collector runs them at any allocation) cannot propagate: Python
    prints it and the run goes on as if no signal came (once, a capped
    ``enumerate --limit 1000000`` was still running 60 s after SIGINT). Here it ends the run as
    ``guard`` would, at once: one line, 130 or 143, no half document left in a file; the
    children die with rosreconf (parent-death signal) and its temp folders go with a later run.
    Any other dropped exception is printed as Python prints it.
    """
    if not issubclass(args.exc_type, (KeyboardInterrupt, Terminated)):
        sys.__unraisablehook__(args)
        return
    capped.take_back_stdout()
    interrupted = issubclass(args.exc_type, KeyboardInterrupt)
    try:
        sys.stderr.write(f"rosreconf: {'interrupted' if interrupted else 'terminated'}\n")
        sys.stderr.flush()
    finally:
        os._exit(ExitCode.INTERRUPTED if interrupted else ExitCode.TERMINATED)


def _thread_failed(args: threading.ExceptHookArgs) -> None:
    """End as ``out_of_memory`` when a thread ran out of memory; else Python's own hook."""
    if args.exc_type is MemoryError:
        out_of_memory()
    threading.__excepthook__(args)


def verb_function(name: str) -> Callable[..., object]:
    """Import and return the function behind verb ``name`` (only now: imports cost time)."""
    module, _, function = COMMANDS[name].target.partition(":")
    found: Callable[..., object] = getattr(importlib.import_module(module), function)
    return found


def _load(name: str) -> Command:
    """Build verb ``name``'s command, as ``app.command(name)`` would have."""
    one = typer.Typer(add_completion=False, pretty_exceptions_enable=False, rich_markup_mode=None)
    one.command(name)(guard(verb_function(name)))
    command = typer.main.get_command(one)
    command.name = name
    return command


class _Verbs(MutableMapping[str, Command]):
    """The group's commands: every name of ``COMMANDS``, each built on first lookup.

    typer's group reads its ``commands`` mapping for a command and for its "did you mean"
    suggestions; this mapping knows every verb name without importing any verb.
    """

    def __init__(self) -> None:
        self._built: dict[str, Command] = {}

    def __getitem__(self, name: str) -> Command:
        if name not in self._built:
            if name not in COMMANDS:
                raise KeyError(name)
            self._built[name] = _load(name)
        return self._built[name]

    def __setitem__(self, name: str, command: Command) -> None:
        self._built[name] = command

    def __delitem__(self, name: str) -> None:
        del self._built[name]

    def __iter__(self) -> Iterator[str]:
        return iter(dict.fromkeys([*COMMANDS, *self._built]))

    def __len__(self) -> int:
        return len(set(COMMANDS) | set(self._built))


class LazyGroup(typer.core.TyperGroup):
    """The verbs of ``COMMANDS``, each imported when it is run or asked for its ``--help``."""

    def __init__(self, **attrs: Any) -> None:
        super().__init__(**attrs)
        self.commands = _Verbs()

    def list_commands(self, ctx: Context) -> list[str]:
        """Return every verb name, in ``COMMANDS`` order, without importing any."""
        return list(self.commands)

    def format_commands(self, ctx: Context, formatter: Any) -> None:
        """List the verbs with their summaries from ``COMMANDS`` (no verb is imported)."""
        limit = formatter.width - 6 - max(len(name) for name in COMMANDS)
        rows = [
            (name, typer.core.TyperCommand(name, help=verb.summary).get_short_help_str(limit))
            for name, verb in COMMANDS.items()
        ]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


app = typer.Typer(
    name="rosreconf",
    cls=LazyGroup,
    help="Configure and reconfigure ROS systems from a component library "
    "(Aitken, Veres and Judge, IFAC 2014).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


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
    jsonout.allow_big_ints()  # counts of any size print in full, in text and JSON


def main() -> None:
    """Run the CLI (the console script and ``python -m rosreconf``).

    Under a memory cap it runs in a forked child, so that an abort in C++ (clingo) for want of
    memory still ends in exit 3 with ``OUT_OF_MEMORY`` (``rosreconf.cli.capped``).
    """
    threading.excepthook = _thread_failed  # a thread out of memory ends the run as the main would
    sys.unraisablehook = _stop_dropped
    try:
        capped.run(app)
    finally:
        _over()
