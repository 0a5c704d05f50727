"""Shared pytest fixtures; the helpers behind the ROS ones live in tests/ros_harness.py."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
import ros_harness
from typer.testing import CliRunner

FAKES = Path(__file__).parent / "fakes"
FAKE_START_SECONDS = 5.0
"""Time limit for a fake that reports, then hangs: long enough for Python to start it and write
its report on a loaded machine (0.5 s was not), so the kill is tested after the report."""
LOADED_MACHINE_SLACK = 20.0
"""Seconds a time bound allows beyond the limit under test: the fakes hang forever, so any bound
proves the limit worked, and 2 cores shared with other jobs must never make a test flip."""
DATA = Path(__file__).parent / "data"


@pytest.fixture
def runner() -> CliRunner:
    """Return a CLI runner; stdout and stderr are kept apart so JSON can be parsed."""
    return CliRunner(env={"COLUMNS": "200", "NO_COLOR": "1"})


def live_members(pgid: int) -> list[int]:
    """Return the pids of the group's processes that are still alive (zombies do not count).

    ``os.killpg(pgid, 0)`` would also count zombies, which a container's PID 1 may never reap.
    """
    alive = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue  # the process ended while we looked
        state, group = fields[0], int(fields[2])
        if group == pgid and state not in ("Z", "X"):
            alive.append(int(stat.parent.name))
    return alive


def wait_until_gone(pgid: int, seconds: float = 2.0) -> list[int]:
    """Wait for a group's processes to die (SIGKILL is asynchronous); return the survivors."""
    deadline = time.monotonic() + seconds
    while (alive := live_members(pgid)) and time.monotonic() < deadline:
        time.sleep(0.02)
    return alive


@pytest.fixture
def report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Make fakes write which processes they started (see tests/fakes/_report.py) here."""
    path = tmp_path / "fake-report.json"
    monkeypatch.setenv("ROSRECONF_FAKE_REPORT", str(path))
    return path


def read_report(path: Path) -> dict[str, Any]:
    """Read what a fake reported about itself."""
    data: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
    return data


@pytest.fixture
def signal_when_started(report: Path) -> Iterator[Any]:
    """Send a real signal to this test process once the fake has reported that it runs.

    Python raises KeyboardInterrupt (SIGINT) or calls rosreconf's SIGTERM handler in the main
    thread, wherever it is blocked: exactly what a user's Ctrl-C or ``kill`` does.
    """
    threads: list[threading.Thread] = []

    def arm(sig: signal.Signals) -> None:
        def fire() -> None:
            deadline = time.monotonic() + 10
            while not report.exists() and time.monotonic() < deadline:
                time.sleep(0.01)
            os.kill(os.getpid(), sig)

        thread = threading.Thread(target=fire, daemon=True)
        thread.start()
        threads.append(thread)

    yield arm
    for thread in threads:
        thread.join(timeout=15)


@pytest.fixture
def ros_master(tmp_path: Path) -> Iterator[ros_harness.Master]:
    """Run a private roscore on a free loopback port; kill it and everything it started after."""
    if not ros_harness.ros_installed():
        # In CI `make test` installs ROS first, so a missing ROS is a failure there, never a skip.
        message = "ROS 1 is not installed: run scripts/system-deps.sh (as root)"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    with ros_harness.running_master(tmp_path / "ros") as master:
        yield master


@pytest.fixture
def ros_master_uri(ros_master: ros_harness.Master) -> str:
    """Return the URI of the private master (``http://127.0.0.1:PORT/``)."""
    return ros_master.uri


StartStandIn = Callable[[dict[str, Any]], ros_harness.StandIn]


@pytest.fixture
def standin(ros_master: ros_harness.Master) -> Iterator[StartStandIn]:
    """Start stand-in nodes from JSON specs on the private master; stop them all after."""
    started: list[ros_harness.StandIn] = []

    def start(spec: dict[str, Any]) -> ros_harness.StandIn:
        node = ros_harness.start_standin(ros_master, spec)
        started.append(node)
        return node

    yield start
    ros_harness.stop(*(node.process for node in started))
