"""Resolve ROS names with rcl itself, through real rclpy nodes (run by a ROS 2 venv's python).

Reads one JSON list on stdin, ``[[name, node, namespace, [[from, to], ...]], ...]``, and
prints one JSON list of the names rcl resolves (``rcl_node_resolve_name``: expansion, then
the node's remap rules), one per case, in order: each case is a node of that name and
namespace started with exactly those ``-r`` rules (``--ros-args``, local to the node), and
``Node.resolve_topic_name`` asks rcl. A case rcl refuses gives ``{"error": ...}``.
tests/test_rosnames.py compares rosreconf's resolver with it.
"""

from __future__ import annotations

import json
import sys

import rclpy


def main() -> None:
    """Print rcl's resolution of every case on stdin."""
    cases = json.load(sys.stdin)
    rclpy.init(args=[])
    out: list[object] = []
    for name, node_name, namespace, rules in cases:
        args = ["--ros-args", *(a for f, t in rules for a in ("-r", f"{f}:={t}"))]
        node = rclpy.create_node(
            node_name, namespace=namespace, cli_args=args, use_global_arguments=False
        )
        try:
            out.append(node.resolve_topic_name(name))
        except Exception as exc:  # rcl refused the name: say so, as the case's answer
            out.append({"error": f"{type(exc).__name__}: {exc}"})
        node.destroy_node()
    print(json.dumps(out))
    rclpy.shutdown()


if __name__ == "__main__":
    main()
