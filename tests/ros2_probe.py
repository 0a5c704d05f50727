#!/usr/bin/env python3
"""Read a ROS 2 graph with rclpy itself, the tests' independent reference (run under rclpy).

Usage: ros2_probe.py SECONDS [NODE ...]. After SECONDS of discovery, prints one JSON document:
{"nodes": [full names], "topics": {name: [types]}, "services": {name: [types]},
 "states": {node: lifecycle state label, via its get_state service}}.
"""

from __future__ import annotations

import json
import sys
import time

import rclpy
from lifecycle_msgs.srv import GetState


def main() -> int:
    """Print what rclpy's graph API and the nodes' get_state services say."""
    seconds, nodes = float(sys.argv[1]), sys.argv[2:]
    rclpy.init()
    node = rclpy.create_node("_rosreconf_probe")
    time.sleep(seconds)
    names = sorted((ns.rstrip("/") + "/" + n) for n, ns in node.get_node_names_and_namespaces())
    states = {}
    for name in nodes:
        client = node.create_client(GetState, f"{name}/get_state")
        if not client.wait_for_service(timeout_sec=10.0):
            states[name] = None
            continue
        future = client.call_async(GetState.Request())
        rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
        states[name] = future.result().current_state.label if future.done() else None
    print(
        json.dumps(
            {
                "nodes": names,
                "topics": dict(node.get_topic_names_and_types()),
                "services": dict(node.get_service_names_and_types()),
                "states": states,
            }
        )
    )
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
