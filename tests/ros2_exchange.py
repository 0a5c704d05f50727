"""Subscribe to a topic and call a service as a plain rclpy node does; print what came back.

Usage (under a ROS 2 venv's python): ``ros2_exchange.py TOPIC SERVICE SECONDS``. The node,
with Fast DDS's defaults (on Kilted: XTypes type information in its discovery and a type
lookup service), subscribes to TOPIC (``std_msgs/msg/String``) and calls SERVICE
(``std_srvs/srv/Trigger``) once it is served, for at most SECONDS in all, and prints one JSON
object: ``{"message": the first message's data or null, "answer": [success, message] or
null, "threads": the names of this process's threads}`` (Fast DDS names its own threads:
``dds.tls.request`` and ``dds.tls.replies`` are its type lookup service's).
"""

from __future__ import annotations

import json
import os
import sys
import time
from typing import Any

import rclpy
from std_msgs.msg import String
from std_srvs.srv import Trigger


def _threads() -> list[str]:
    tasks = os.listdir("/proc/self/task")
    return sorted(open(f"/proc/self/task/{t}/comm", encoding="utf-8").read().strip() for t in tasks)


def main() -> int:
    """Exchange once with TOPIC and SERVICE; print the JSON object."""
    topic, service, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
    rclpy.init()
    node = rclpy.create_node("_rosreconf_test_exchange")
    got: dict[str, Any] = {"message": None, "answer": None}
    node.create_subscription(
        String, topic, lambda m: got.update(message=got["message"] or m.data), 10
    )
    client = node.create_client(Trigger, service)
    deadline = time.monotonic() + seconds
    future = None
    while time.monotonic() < deadline and (got["message"] is None or got["answer"] is None):
        rclpy.spin_once(node, timeout_sec=0.1)
        if future is None and client.service_is_ready():
            future = client.call_async(Trigger.Request())
        if future is not None and future.done() and future.result() is not None:
            got["answer"] = [future.result().success, future.result().message]
    print(json.dumps({**got, "threads": _threads()}), flush=True)
    node.destroy_node()
    rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
