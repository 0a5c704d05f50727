"""The README's command table names every flag of each command, and only flags that exist.

The table is what a newcomer reads first; ``rosreconf CMD --help`` is what the program
accepts. Each is read as a user sees it: the table's first column, and the help's options
as printed (a wide terminal, so no option is wrapped).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
ROW = re.compile(r"^\| `rosreconf ([a-z-]+)( [^`]*)?` \|", re.M)
FLAG = re.compile(r"(?<![\w-])(--?[a-z][a-z0-9-]*)")
OPTION = re.compile(r"^  (-[a-zA-Z], )?(--[a-z0-9-]+)(?: / (--[a-z0-9-]+))?", re.M)


def table() -> dict[str, set[str]]:
    """Return each command of the README's table with the flags its first column names."""
    rows: dict[str, set[str]] = {}
    for command, synopsis in ROW.findall(README.read_text(encoding="utf-8")):
        rows.setdefault(command, set()).update(FLAG.findall(synopsis.replace("\\|", "|")))
    return rows


def options(command: str) -> list[set[str]]:
    """Return the options ``rosreconf COMMAND --help`` prints, each as its set of names."""
    env = {**os.environ, "COLUMNS": "250", "TERMINAL_WIDTH": "250"}
    done = subprocess.run(
        [sys.executable, "-m", "rosreconf", command, "--help"],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    found = []
    for short, long, negative in OPTION.findall(done.stdout.split("Options:", 1)[1]):
        names = (
            {long}
            | ({short.rstrip(", ")} if short else set())
            | ({negative} if negative else set())
        )
        if long != "--help":
            found.append(names)
    return found


TABLE = table()


def test_the_table_lists_every_command() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "rosreconf", "--help"], capture_output=True, text=True, check=True
    )
    listed = set(re.findall(r"^  ([a-z-]+) ", done.stdout.split("Commands:", 1)[1], re.M))
    assert listed == set(TABLE)


@pytest.mark.parametrize("command", sorted(TABLE))
def test_every_flag_in_the_table_exists_and_every_option_is_in_the_table(command: str) -> None:
    """A flag the README names must be accepted; an option --help shows must be in the README
    (by its long or its short name)."""
    known = options(command)
    named = TABLE[command]
    accepted = set().union(*known) if known else set()
    assert not named - accepted, f"in the README, not in --help: {sorted(named - accepted)}"
    missing = [sorted(names) for names in known if not names & named]
    assert not missing, f"in --help, not in the README's table: {missing}"


def _help(command: str) -> str:
    env = {**os.environ, "COLUMNS": "250"}
    args = [sys.executable, "-m", "rosreconf", command, "--help"]
    text = subprocess.run(args, capture_output=True, text=True, env=env, check=True).stdout
    return " ".join(text.split())  # unwrapped


def test_help_says_what_a_spent_search_does_in_plan_and_in_watch() -> None:
    """``plan`` exits 3; ``watch`` logs no-configuration and keeps watching (once said exit 3)."""
    plan, watch = _help("plan"), _help("watch")
    assert "(then exit 3, saying what was tried)" in plan
    assert "exit 3, saying" not in watch
    assert watch.count("(then log no-configuration, saying what was tried, and keep watching)") == 2


def test_watch_help_says_how_real_ros2_nodes_run() -> None:
    """Real nodes run as ``ros2 run`` starts them; stand-ins and helpers need rclpy's Python."""
    watch = _help("watch")
    assert "ROS 2 nodes run as ros2 run starts them (<prefix>/lib/<package>/<executable>)" in watch
    assert "ROS 2 nodes and stand-ins run under ROSRECONF_ROS2_PYTHON" not in watch


def test_inspect_help_and_readme_give_exit_3_when_the_graph_cannot_be_read() -> None:
    assert "Exit 3 when the live graph cannot be read" in _help("inspect")
    assert "3 when the live graph cannot be read" in README.read_text(encoding="utf-8")
