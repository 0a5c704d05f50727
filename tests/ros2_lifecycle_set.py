#!/usr/bin/env python3
"""Change a managed node's lifecycle state as a person would, with rclpy (run under rclpy).

Usage: ros2_lifecycle_set.py NODE TRANSITION (configure, activate, deactivate, cleanup).
Prints one JSON line: {"ok": bool, "state": the label get_state reads back}. What ``ros2
lifecycle set`` does, for a machine with no ros2 command.
"""

from __future__ import annotations

import json
import sys

import rclpy
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState

IDS = {
    "configure": Transition.TRANSITION_CONFIGURE,
    "activate": Transition.TRANSITION_ACTIVATE,
    "deactivate": Transition.TRANSITION_DEACTIVATE,
    "cleanup": Transition.TRANSITION_CLEANUP,
}


def main() -> int:
    """Perform the transition and read the state back."""
    node_name, transition = sys.argv[1], sys.argv[2]
    rclpy.init()
    node = rclpy.create_node("_rosreconf_lifecycle_set")
    change = node.create_client(ChangeState, f"{node_name}/change_state")
    get = node.create_client(GetState, f"{node_name}/get_state")
    if not change.wait_for_service(timeout_sec=30.0) or not get.wait_for_service(timeout_sec=30.0):
        print(json.dumps({"ok": False, "state": None}))
        return 1
    request = ChangeState.Request()
    request.transition.id = IDS[transition]
    future = change.call_async(request)
    rclpy.spin_until_future_complete(node, future, timeout_sec=30.0)
    ok = bool(future.done() and future.result().success)
    read = get.call_async(GetState.Request())
    rclpy.spin_until_future_complete(node, read, timeout_sec=30.0)
    state = read.result().current_state.label if read.done() else None
    print(json.dumps({"ok": ok, "state": state}))
    rclpy.shutdown()
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
