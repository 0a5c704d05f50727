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


def test_a_node_asked_twice_in_one_batch_is_asked_once_and_lives(
    agent: LifecycleAgent, tmp_path: Path
) -> None:
    """Two configures of one node in one batch: rclpy would end the node at the second (it is
    inactive by then, and rclpy raises "Transition is not registered" out of its executor)."""
    outcomes = agent.transitions([("/left", "configure"), ("/left", "configure")], appear=60.0)
    assert [(o.ok, o.state) for o in outcomes[:1]] == [(True, "inactive")]
    assert not outcomes[1].ok and "already" in (outcomes[1].error or ""), outcomes[1]
    # the node lives: it takes the next transition
    assert _results(agent, ("/left", "activate")) == {"/left": (True, "active")}


def test_a_configure_slower_than_its_timeout_is_not_asked_again_while_it_runs(
    ros2_domain: int, tmp_path: Path
) -> None:
    """watch's standbys are configured with a 0.5 s timeout and tried again on a later tick; a
    node whose ``on_configure`` takes 2 s must be configured once, and never ended by a retry."""
    system = ros2_real.Ros2System("jazzy", ros2_domain, tmp_path, [])
    env = ros2_real.node_env(ros2_domain, tmp_path / "agent-home")
    env["ROSRECONF_ROS2_PYTHON"] = str(ros2_real.python_of("jazzy"))
    try:
        slow = system.start({"name": "slow", "lifecycle": "unconfigured", "configure_seconds": 2})
        agent = LifecycleAgent(env, tmp_path / "agent.log", timeout=10.0)
        try:
            (first,) = agent.transitions([("/slow", "configure")], appear=60.0, timeout=0.5)
            assert not first.ok and "did not answer" in (first.error or ""), first
            (again,) = agent.transitions([("/slow", "configure")], timeout=0.5)  # while it runs
            assert not again.ok, again
            (done,) = agent.transitions([("/slow", "configure")], timeout=10.0)
            assert (done.ok, done.state) == (True, "inactive"), done
            assert slow.process.poll() is None, slow.process.returncode  # not ended
            assert _results(agent, ("/slow", "activate")) == {"/slow": (True, "active")}
        finally:
            agent.close()
    finally:
        system.stop()
