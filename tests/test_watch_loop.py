"""``rosreconf watch`` keeps watching while the master restarts, and fails fast at start.

The master is scripted here (``Watcher.step`` replaced) because the behaviour under test is
the command's loop; tests/test_live_ros.py runs watch against a real roscore.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from types import SimpleNamespace

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import ExternalToolError
from rosreconf.ros.watcher import Watcher

ARGS = ["watch", "--master", "http://127.0.0.1:9/", "--only", "object_repositioning"]
ARGS += ["--interval", "0.05"]


def _script(monkeypatch: pytest.MonkeyPatch, outcomes: list[object]) -> None:
    steps: Iterator[object] = iter(outcomes)

    def step(self: Watcher) -> object:
        outcome = next(steps)
        if isinstance(outcome, BaseException):
            raise outcome
        return outcome

    monkeypatch.setattr(Watcher, "step", step)


def test_a_restarting_master_is_waited_for(
    runner: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    ok = SimpleNamespace(ok=True)
    gone = ExternalToolError("http://127.0.0.1:9/: the ROS master does not answer")
    _script(monkeypatch, [ok, gone, gone, gone, ok, KeyboardInterrupt()])
    result = runner.invoke(app, ARGS)
    assert result.exit_code == 130  # stopped by the (scripted) Ctrl-C, not by the lost master
    lost = [line for line in result.stderr.splitlines() if "retrying every 0.05 s" in line]
    assert len(lost) == 1 and "does not answer" in lost[0]
    assert "the master answers again after" in result.stderr


def test_an_unreachable_master_at_start_is_an_error(
    runner: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    _script(monkeypatch, [ExternalToolError("http://127.0.0.1:9/: connection refused")])
    result = runner.invoke(app, ARGS)
    assert result.exit_code == 3
    assert "connection refused" in result.stderr


def test_apply_leaves_no_launch_directory_when_nothing_was_launched(
    runner: CliRunner, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "log"))
    _script(monkeypatch, [ExternalToolError("http://127.0.0.1:9/: connection refused")])
    result = runner.invoke(app, [*ARGS, "--apply"])
    assert result.exit_code == 3
    made = str(tmp_path / "log" / "rosreconf-watch-")
    assert made in result.stderr  # said at the start
    assert list((tmp_path / "log").iterdir()) == []
