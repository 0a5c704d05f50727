"""The tests' own rclpy client of rosreconf's ROS 2 face (tests/test_watch_tasks.py).

Run by a ROS 2 venv's python, written with rclpy alone, never with rosreconf's code:

    ros2_face_client.py set NODE TASK     SetParameters task=TASK; prints {"successful",
                                           "reason", "seconds"}
    ros2_face_client.py get NODE          prints the parameters' values and descriptors
    ros2_face_client.py listen OUT        writes every /diagnostics and /rosout message to OUT,
                                           one JSON line each with the wall time it came, until
                                           killed
"""

from __future__ import annotations

import json
import os
import sys
import time
from typing import Any

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from rcl_interfaces.msg import Log, Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import DescribeParameters, GetParameters, SetParameters
from rclpy.qos import QoSDurabilityPolicy, QoSProfile

WAIT = 60.0


def _call(node: Any, kind: Any, name: str, request: Any) -> Any:
    client = node.create_client(kind, name)
    if not client.wait_for_service(timeout_sec=WAIT):
        raise SystemExit(f"{name} did not appear")
    future = client.call_async(request)
    rclpy.spin_until_future_complete(node, future, timeout_sec=WAIT)
    if not future.done():
        raise SystemExit(f"{name} did not answer")
    return future.result()


def set_task(node: Any, face: str, task: str) -> None:
    request = SetParameters.Request()
    value = ParameterValue(type=ParameterType.PARAMETER_STRING, string_value=task)
    request.parameters = [Parameter(name="task", value=value)]
    client = node.create_client(SetParameters, f"{face}/set_parameters")
    if not client.wait_for_service(timeout_sec=WAIT):
        raise SystemExit("set_parameters did not appear")
    start = time.monotonic()
    future = client.call_async(request)
    rclpy.spin_until_future_complete(node, future, timeout_sec=WAIT)
    took = time.monotonic() - start
    (result,) = future.result().results
    print(json.dumps({"successful": result.successful, "reason": result.reason,
                      "seconds": took, "answered_at": time.time()}))  # fmt: skip


def get(node: Any, face: str) -> None:
    names = ["task", "configuration", "failed"]
    values = _call(
        node, GetParameters, f"{face}/get_parameters", GetParameters.Request(names=names)
    )
    described = _call(node, DescribeParameters, f"{face}/describe_parameters",
                      DescribeParameters.Request(names=names))  # fmt: skip
    out = {}
    for name, value, d in zip(names, values.values, described.descriptors, strict=True):
        shown = value.string_value if value.type == ParameterType.PARAMETER_STRING else list(
            value.string_array_value)  # fmt: skip
        out[name] = {"value": shown, "read_only": d.read_only,
                     "constraints": d.additional_constraints}  # fmt: skip
    print(json.dumps(out))


def listen(node: Any, out: str) -> None:
    with open(out, "a", encoding="utf-8") as sink:

        def diagnostics(msg: Any) -> None:
            statuses = [{"name": s.name, "level": s.level[0] if isinstance(s.level, bytes)
                         else s.level, "level_type": type(s.level).__name__,
                         "message": s.message, "hardware_id": s.hardware_id,
                         "values": {v.key: v.value for v in s.values}}
                        for s in msg.status]  # fmt: skip
            stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
            sink.write(json.dumps({"topic": "/diagnostics", "at": time.time(), "stamp": stamp,
                                   "status": statuses}) + "\n")  # fmt: skip
            sink.flush()

        def rosout(msg: Any) -> None:
            sink.write(json.dumps({"topic": "/rosout", "at": time.time(), "name": msg.name,
                                   "level": msg.level, "msg": msg.msg}) + "\n")  # fmt: skip
            sink.flush()

        node.create_subscription(DiagnosticArray, "/diagnostics", diagnostics, 50)
        qos = QoSProfile(depth=1000, durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)
        node.create_subscription(Log, "/rosout", rosout, qos)
        print(json.dumps({"listening": True}), flush=True)
        rclpy.spin(node)


def main() -> None:
    rclpy.init()
    node = rclpy.create_node(f"_face_client_{os.getpid()}")  # hidden: no extra node
    what, arg = sys.argv[1], sys.argv[2]
    if what == "set":
        set_task(node, arg, sys.argv[3])
    elif what == "get":
        get(node, arg)
    else:
        listen(node, arg)
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
