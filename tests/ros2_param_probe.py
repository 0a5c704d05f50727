"""A real rclpy node that reports the parameters its command line gave it, with rcl's types.

Run by a ROS 2 venv's python with exactly the ``--ros-args`` rosreconf builds
(tests/test_ros2_parameters.py). Each override is declared with the type rcl parsed it as
(``automatically_declare_parameters_from_overrides``), and the node prints one JSON object,
``{name: [type, value]}`` for every parameter it has (rclpy's own ones too), with rclpy's
``Parameter.Type`` names (``STRING``, ``BOOL``, ``INTEGER``, ``DOUBLE``); a double that is
not finite is printed as its ``repr``.
"""

from __future__ import annotations

import json
import math
import sys

import rclpy
from rclpy.node import Node


def main() -> None:
    """Start one node with this process's arguments and print its parameter overrides."""
    rclpy.init(args=sys.argv)
    node = Node("param_probe", automatically_declare_parameters_from_overrides=True)
    report = {}
    for name in node.list_parameters([], 0).names:
        parameter = node.get_parameter(name)
        value = parameter.value
        if isinstance(value, float) and not math.isfinite(value):
            value = repr(value)
        report[name] = [parameter.type_.name, value]
    print(json.dumps(report))
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
