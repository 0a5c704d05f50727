"""Run a real rclpy action server and client (test_msgs/action/Fibonacci) until killed.

Run with a real ROS 2 venv's Python (``.venv-ros2-jazzy/bin/python``), with ROS_DOMAIN_ID
and ROS_LOG_DIR set. Arguments: the action name, then ``server`` and/or ``client`` node
names as ``server=NAME`` / ``client=NAME``. Prints ``ready`` once both exist; the test then
reads the graph with ``rosreconf snapshot --ros2``.
"""

from __future__ import annotations

import sys

import rclpy
from rclpy.action import ActionClient, ActionServer
from rclpy.executors import SingleThreadedExecutor
from test_msgs.action import Fibonacci


def execute(goal_handle: object) -> object:
    """Succeed at once: the tests look at the graph, not at goals."""
    goal_handle.succeed()  # type: ignore[attr-defined]
    return Fibonacci.Result()


def main() -> None:
    """Start the nodes the arguments ask for and spin them."""
    action, *roles = sys.argv[1:]
    rclpy.init()
    executor = SingleThreadedExecutor()
    keep = []
    for role in roles:
        kind, _, name = role.partition("=")
        node = rclpy.create_node(name)
        if kind == "server":
            keep.append(ActionServer(node, Fibonacci, action, execute))
        else:
            keep.append(ActionClient(node, Fibonacci, action))
        executor.add_node(node)
    print("ready", flush=True)
    executor.spin()


if __name__ == "__main__":
    main()
