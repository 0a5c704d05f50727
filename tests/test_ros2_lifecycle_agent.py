"""The lifecycle agent performs transitions on a real rclpy ``LifecycleNode`` (issue 23).

The node runs under the Jazzy venv (``tests/ros2_node.py``); the agent is rosreconf's own
(``rosreconf.ros.ros2.lifecycle``). The reference is what ROS 2's lifecycle state machine
allows: ``configure`` leads unconfigured to inactive, ``activate`` inactive to active, and
``activate`` of an unconfigured node is refused. A transition to the state the node is already
in (a retried ``configure`` whose first answer was lost) counts as done.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
import ros2_real

from rosreconf.ros.ros2.lifecycle import LifecycleAgent


@pytest.fixture
def agent(ros2_domain: int, tmp_path: Path) -> Iterator[LifecycleAgent]:
    """Start two unconfigured lifecycle nodes and the agent on one private domain."""
    system = ros2_real.Ros2System("jazzy", ros2_domain, tmp_path, [])
    env = ros2_real.node_env(ros2_domain, tmp_path / "agent-home")
    env["ROSRECONF_ROS2_PYTHON"] = str(ros2_real.python_of("jazzy"))
    try:
        system.start({"name": "left", "lifecycle": "unconfigured"})
        system.start({"name": "right", "lifecycle": "unconfigured"})
        agent = LifecycleAgent(env, tmp_path / "agent.log", timeout=10.0)
        try:
            yield agent
        finally:
            agent.close()
    finally:
        system.stop()


def _results(agent: LifecycleAgent, *items: tuple[str, str]) -> dict[str, tuple[bool, str | None]]:
    outcomes = agent.transitions(list(items), appear=60.0)
    assert [(o.node, o.transition) for o in outcomes] == list(items)
    return {o.node: (o.ok, o.state) for o in outcomes}


def test_configure_twice_is_done_and_an_activate_out_of_order_is_refused(
    agent: LifecycleAgent,
) -> None:
    assert _results(agent, ("/left", "configure")) == {"/left": (True, "inactive")}
    # configure again: it is inactive, where configure leads (rclpy would raise if asked)
    assert _results(agent, ("/left", "configure")) == {"/left": (True, "inactive")}
    assert _results(agent, ("/left", "activate"), ("/right", "activate")) == {
        "/left": (True, "active"),
        "/right": (False, "unconfigured"),
    }
    refused = agent.transitions([("/right", "activate")], appear=60.0)[0]
    assert refused.error == "/right is unconfigured: activate is not a transition from it"
