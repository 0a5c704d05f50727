"""The tests' own rclpy client of rosreconf's ROS 2 face (tests/test_watch_tasks.py).

Run by a ROS 2 venv's python, written with rclpy alone, never with rosreconf's code:

    ros2_face_client.py set NODE TASK [again]
                                          SetParameters task=TASK; prints {"successful",
                                           "reason", "seconds", "sent"}; with ``again``, the
                                           same request once more right after the answer,
                                           its answer as "again": {"successful", "reason"}
    ros2_face_client.py get NODE          prints the parameters' values and descriptors
    ros2_face_client.py listen OUT        writes every /diagnostics and /rosout message to OUT,
                                           one JSON line each with the wall time it came, until
                                           killed

A request unanswered after ``RESEND`` s is sent again, the first answer to any counting
("sent": how many went): a service may take a request from a client it has not matched both
ways yet and drop its answer (rclpy warns "failed to send response (timeout)"), though
``wait_for_service`` passed. ``seconds`` runs from the first request.
"""

from __future__ import annotations

import faulthandler
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
RESEND = 1.5


def _ask(node: Any, client: Any, request: Any) -> tuple[Any, int]:
    """Return the first answer to ``request`` and how many times it was sent."""
    deadline = time.monotonic() + WAIT
    futures = []
    while time.monotonic() < deadline:
        futures.append(client.call_async(request))
        resend = min(deadline, time.monotonic() + RESEND)
        while time.monotonic() < resend:
            rclpy.spin_once(node, timeout_sec=max(0.0, min(0.05, resend - time.monotonic())))
            done = [f for f in futures if f.done()]
            if done:
                for f in futures:
                    client.remove_pending_request(f)
                return done[0].result(), len(futures)
    raise SystemExit(f"{client.srv_name} did not answer ({len(futures)} requests)")


def _call(node: Any, kind: Any, name: str, request: Any) -> Any:
    client = node.create_client(kind, name)
    if not client.wait_for_service(timeout_sec=WAIT):
        raise SystemExit(f"{name} did not appear")
    return _ask(node, client, request)[0]


def set_task(node: Any, face: str, task: str, again: bool = False) -> None:
    request = SetParameters.Request()
    value = ParameterValue(type=ParameterType.PARAMETER_STRING, string_value=task)
    request.parameters = [Parameter(name="task", value=value)]
    client = node.create_client(SetParameters, f"{face}/set_parameters")
    found = time.monotonic()
    if not client.wait_for_service(timeout_sec=WAIT):
        raise SystemExit("set_parameters did not appear")
    print(f"set_parameters found in {time.monotonic() - found:.2f} s", file=sys.stderr)
    start = time.monotonic()
    answer, sent = _ask(node, client, request)
    took = time.monotonic() - start
    answered_at = time.time()
    (result,) = answer.results
    out = {"successful": result.successful, "reason": result.reason, "seconds": took,
           "sent": sent, "answered_at": answered_at}  # fmt: skip
    if again:
        (repeat,) = _ask(node, client, request)[0].results
        out["again"] = {"successful": repeat.successful, "reason": repeat.reason}
    print(json.dumps(out))


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
    what, arg = sys.argv[1], sys.argv[2]
    if what != "listen":  # a call still here after 100 s says where it is, on stderr
        faulthandler.dump_traceback_later(100.0)
    rclpy.init()
    node = rclpy.create_node(f"_face_client_{os.getpid()}")  # hidden: no extra node
    if what == "set":
        set_task(node, arg, sys.argv[3], sys.argv[4:] == ["again"])
    elif what == "get":
        get(node, arg)
    else:
        listen(node, arg)
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
