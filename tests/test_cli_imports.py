"""The CLI imports only what the command runs (issue 12): ``--help`` and ``validate`` stay light.

Each check runs ``python -X importtime -m rosreconf ...`` in a fresh process and reads the
modules it imported from ``-X importtime``'s report, so a module-level import of clingo,
networkx or a ROS client anywhere on the way fails here by name.
"""

from __future__ import annotations

import inspect
import re
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import COMMANDS, app, verb_function

HEAVY = (
    "clingo",  # the solver
    "networkx",  # ROS-graphs and system graphs as graphs
    "jinja2",  # the PDDL templates
    "jsonschema",  # python-jsonschema: the tests' reference only (formats use jsonschema-rs)
    "rosreconf.solve",
    "rosreconf.planning",  # PDDL and the planners
    "rosreconf.ros",  # the ROS client: xmlrpc, http, ssl
    "xmlrpc",
    "http.client",
    "urllib.request",
    "ssl",
)
"""Modules that ``rosreconf --help`` and ``rosreconf validate`` must never import."""
LIGHT = (
    "rosreconf.solve",
    "rosreconf.solve.instance",
    "rosreconf.solve.emptyroles",
    "rosreconf.solve.unfillable",
)
"""Exceptions: the stage's docstring-only package and its pure-Python pruning (with optional
roles' empty choices), which ``validate`` uses to warn about a schema without any
configuration (issue 22)."""


def imported(args: list[str], cwd: Path) -> tuple[set[str], subprocess.CompletedProcess[str]]:
    """Run ``python -X importtime -m rosreconf ARGS`` and return the modules it imported."""
    done = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "rosreconf", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    names = set(re.findall(r"^import time:\s+\d+ \|\s+\d+ \|\s+(\S+)$", done.stderr, re.M))
    assert "rosreconf.cli.app" in names, done.stderr[-2000:]  # the report was read at all
    return names, done


def heavy_in(names: set[str]) -> list[str]:
    """Return the HEAVY modules (or their submodules) among ``names``."""
    return sorted(
        n for n in names for h in HEAVY if (n == h or n.startswith(h + ".")) and n not in LIGHT
    )


def test_help_imports_no_heavy_module(tmp_path: Path) -> None:
    names, done = imported(["--help"], tmp_path)
    assert done.returncode == 0
    assert heavy_in(names) == []
    verbs = {n for n in names if n.startswith("rosreconf.cli.")}
    # no verb module loaded (capped: the memory-cap wrapper every run goes through)
    assert verbs <= {"rosreconf.cli.app", "rosreconf.cli.capped", "rosreconf.cli.console"}
    for verb in COMMANDS:
        assert verb in done.stdout


def test_validate_imports_no_heavy_module(tmp_path: Path) -> None:
    names, done = imported(["validate"], tmp_path)  # the bundled example: valid
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.formats.loader" in names
    assert heavy_in(names) == []


def test_parsing_options_imports_no_pydantic(tmp_path: Path) -> None:
    """A command with options parses them without pydantic (why typer stays below 0.29).

    typer 0.29 builds a pydantic ``TypeAdapter`` for every option that is not a plain flag,
    given or not: importing pydantic cost ``plan`` and every other command 0.06-0.1 CPU s.
    """
    args = ["plan", "--fail", "NSM3", "--only", "object_repositioning", "--timeout", "60"]
    names, done = imported(args, tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.planning.replan" in names  # the options were parsed and plan ran
    assert sorted(n for n in names if n.split(".")[0] == "pydantic") == []


def test_the_check_sees_a_heavy_import(tmp_path: Path) -> None:
    """Listing every configuration needs clingo: the same reading of the report must find it."""
    names, done = imported(["enumerate", "--only", "disc_loading"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "clingo" in heavy_in(names)


@pytest.mark.parametrize(
    "args", [["--limit", "1"], ["--best", "--objective", "cost=1"], ["--count"]]
)
def test_elimination_answers_without_clingo(tmp_path: Path, args: list[str]) -> None:
    """The first configuration, the optimum and the count come from elimination: no clingo.

    clingo is imported where it runs (``rosreconf.solve.solver``), so these commands do not
    pay for loading it when elimination answers (issue 12: whole-process time).
    """
    names, done = imported(["enumerate", *args], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.solve.listing" in names  # the command ran
    assert "clingo" not in names


@pytest.mark.parametrize("verb", list(COMMANDS))
def test_summary_is_the_first_docstring_line(verb: str) -> None:
    doc = inspect.getdoc(verb_function(verb)) or ""
    assert COMMANDS[verb].summary == doc.splitlines()[0]


def test_a_typo_is_answered_with_the_nearest_verb() -> None:
    result = CliRunner().invoke(app, ["valdate"])
    assert result.exit_code == 2
    assert "Did you mean 'validate'?" in result.output


def test_enumerate_imports_no_graph_library(tmp_path: Path) -> None:
    """enumerate lists configurations: networkx comes only with a picture (0.2 s of each run)."""
    names, done = imported(["enumerate"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.solve.listing" in names
    assert [n for n in heavy_in(names) if n.split(".")[0] in ("networkx", "jinja2")] == []


def test_plan_imports_no_drawing_and_no_process_pool(tmp_path: Path) -> None:
    """plan simulates in process and draws only with --graph: neither import is paid for.

    ``render.pictures`` (with ``render.dot``) comes with ``--graph``; the process pool
    (``concurrent.futures.process``, multiprocessing) only with more than one worker.
    """
    names, done = imported(["plan", "--fail", "NSM3"], tmp_path)
    assert done.returncode in (0, 1), done.stdout + done.stderr
    assert "rosreconf.analysis.simulate" in names and "rosreconf.planning.replan" in names
    unneeded = ("rosreconf.render.pictures", "rosreconf.render.dot", "multiprocessing")
    assert sorted(names & set(unneeded)) == []
    assert "concurrent.futures.process" not in names


def test_plan_with_graph_does_import_the_drawing(tmp_path: Path) -> None:
    """The same reading sees render.pictures when --graph asks for it."""
    names, done = imported(["plan", "--fail", "NSM3", "--graph", str(tmp_path / "g.svg")], tmp_path)
    assert done.returncode in (0, 1), done.stdout + done.stderr
    assert "rosreconf.render.pictures" in names
    assert (tmp_path / "g.svg").stat().st_size > 0


def test_piped_enumerate_imports_no_picture_or_progress_module(tmp_path: Path) -> None:
    """Piped, enumerate shows no live counter and draws nothing: neither module is loaded."""
    names, done = imported(["enumerate"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.render.pictures" not in names
    assert "rich.progress" not in names
    assert "rich._emoji_codes" not in names  # the consoles never turn ':name:' into emoji


def test_enumerate_graph_still_draws(tmp_path: Path) -> None:
    """--graph imports the picture module where it is needed and writes the picture."""
    names, done = imported(["enumerate", "--only", "disc_loading", "--graph", "g.dot"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "rosreconf.render.pictures" in names
    assert (tmp_path / "g.dot").read_text().startswith("digraph")
