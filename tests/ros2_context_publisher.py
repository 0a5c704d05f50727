"""The tests' own publisher of a context topic (tests/test_watch_context.py, benchmarks).

Run by a ROS 2 venv's python, written with rclpy alone, never with rosreconf's code:

    ros2_context_publisher.py TOPIC [HZ]

publishes ``std_msgs/msg/Float64`` on TOPIC at HZ (default 10) once a value is given. Each
line of stdin is a command: a number sets the value published from now on (printed back as
``{"value": V, "at": wall time}``, the time taken just before the first message with it is
sent), ``silent`` stops
publishing, ``end`` exits.
"""

from __future__ import annotations

import json
import queue
import sys
import threading
import time

import rclpy
from std_msgs.msg import Float64


def _read(into: queue.Queue[str]) -> None:
    for line in sys.stdin:
        into.put(line.strip())
    into.put("end")


def main() -> int:
    topic = sys.argv[1]
    period = 1.0 / float(sys.argv[2]) if len(sys.argv) > 2 else 0.1
    rclpy.init()
    node = rclpy.create_node("context_publisher")
    pub = node.create_publisher(Float64, topic, 10)
    commands: queue.Queue[str] = queue.Queue()
    threading.Thread(target=_read, args=(commands,), daemon=True).start()
    value: float | None = None
    fresh = False
    print(json.dumps({"ready": topic}), flush=True)
    try:
        while True:
            try:
                command = commands.get(timeout=period)
            except queue.Empty:
                command = ""
            if command == "end":
                return 0
            if command == "silent":
                value = None
            elif command:
                value, fresh = float(command), True
            if value is not None:
                at = time.time()  # before the message goes out: no reader has it earlier
                pub.publish(Float64(data=value))
                if fresh:
                    print(json.dumps({"value": value, "at": at}), flush=True)
                    fresh = False
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
