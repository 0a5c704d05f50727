"""``rosreconf watch``'s loop: it keeps watching through failed reads, and fails fast at start.

The loop (``rosreconf.ros.polling.poll``) is driven with ``ScriptedWatcher``, a stand-in
watcher whose reads succeed or fail as scripted (a fake, named as such: a master that is lost
for exactly three reads, or a ROS 2 graph that stays half-announced for exactly 3.5 s, cannot
be made to order). A failing start runs the real command against an address where nothing
listens. tests/test_live_ros.py runs watch against a real roscore through a real master
restart; tests/test_live_ros2.py a real half-announced ROS 2 graph.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import ExternalToolError, UnsettledGraphError
from rosreconf.ros.events import Event
from rosreconf.ros.polling import UNSETTLED_SAID_AFTER, poll

ARGS = ["watch", "--master", "http://127.0.0.1:9/", "--only", "object_repositioning"]
ARGS += ["--interval", "0.05"]
LOST = ExternalToolError("http://127.0.0.1:9/: the ROS master does not answer")


@dataclass
class ScriptedWatcher:
    """A fake watcher: each step takes the next outcome of ``script`` (a function of the
    seconds since the first step, returning an exception to raise or None for a good read);
    it asks to stop once ``until`` seconds have passed."""

    script: Callable[[float], Exception | None]
    until: float
    events: list[Event] = field(default_factory=list)
    schema: Any = field(default_factory=lambda: SimpleNamespace(simulation=None))
    steps: int = 0
    _t0: float | None = None
    _read: bool = False

    def _now(self) -> float:
        if self._t0 is None:
            self._t0 = time.monotonic()
        return time.monotonic() - self._t0

    @property
    def log(self) -> Callable[[Event], None]:
        return self.events.append

    @property
    def stop_requested(self) -> Callable[[], bool]:
        return lambda: self._now() >= self.until

    def step(self) -> Any:
        self.steps += 1
        failure = self.script(self._now())
        if failure is not None:
            raise failure
        self._read = True
        return SimpleNamespace(ok=True, steps=self.steps)

    def has_read(self) -> bool:
        return self._read

    def replan_due(self) -> bool:
        return False

    def exited(self) -> bool:
        return False

    def due_at(self) -> float | None:
        return None


def _kinds(watcher: ScriptedWatcher) -> list[str]:
    return [e.kind for e in watcher.events]


def test_a_restarting_master_is_said_once_lost_and_once_back() -> None:
    watcher = ScriptedWatcher(lambda t: LOST if 0.1 <= t < 0.4 else None, until=0.7)
    last = poll(watcher, 0.05)
    assert _kinds(watcher) == ["master-lost", "master-back"], watcher.events
    lost, back = watcher.events
    assert "does not answer" in lost.message and "retrying every 0.05 s" in lost.message
    assert "the master answers again after" in back.message
    assert last.steps == watcher.steps  # the last good read is what it returns


def test_a_graph_half_announced_for_a_moment_is_not_said() -> None:
    """A failover's nodes starting make reads partial for a moment: nobody's fault."""
    partial = UnsettledGraphError("1 ROS 2 participant(s) announce endpoints ...")
    short = UNSETTLED_SAID_AFTER / 3
    watcher = ScriptedWatcher(lambda t: partial if 0.1 <= t < 0.1 + short else None, 2 * short)
    poll(watcher, 0.05)
    assert _kinds(watcher) == [] and watcher.steps > 5


def test_a_graph_half_announced_for_longer_is_said_once_with_its_end() -> None:
    partial = UnsettledGraphError("1 ROS 2 participant(s) announce endpoints ...")
    end = 0.1 + UNSETTLED_SAID_AFTER + 1.0  # a margin for a slow step on a busy host
    watcher = ScriptedWatcher(lambda t: partial if 0.1 <= t < end else None, end + 0.3)
    poll(watcher, 0.05)
    assert _kinds(watcher) == ["graph-unsettled", "graph-settled"], watcher.events
    unsettled, settled = watcher.events
    assert "announce endpoints" in unsettled.message
    assert "the graph reads whole again after" in settled.message


def test_an_unreachable_master_at_start_is_an_error(runner: CliRunner) -> None:
    result = runner.invoke(app, ARGS)
    assert result.exit_code == 3, result.stderr
    assert "http://127.0.0.1:9/" in result.stderr and "Traceback" not in result.stderr


def test_apply_leaves_no_launch_directory_when_nothing_was_launched(
    runner: CliRunner, monkeypatch: Any, tmp_path: Path
) -> None:
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "log"))
    result = runner.invoke(app, [*ARGS, "--apply"])
    assert result.exit_code == 3, result.stderr
    made = str(tmp_path / "log" / "rosreconf-watch-")
    assert made in result.stderr  # said at the start
    assert list((tmp_path / "log").iterdir()) == []
