"""Shared pytest fixtures only; the helpers behind them live in plain modules (ros_harness)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
import ros_harness


@pytest.fixture
def ros_master(tmp_path: Path) -> Iterator[ros_harness.Master]:
    """Run a private roscore on a free loopback port; kill it and everything it started after."""
    if not ros_harness.ros_installed():
        pytest.skip("ROS 1 is not installed: run scripts/system-deps.sh (as root)")
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
