"""Ask a running watch's ROS 2 face to switch task (``rosreconf task``, under ROS 2's Python).

``task_client.py FACE TASK TIMEOUT`` sets the face's ``task`` parameter with a
``rcl_interfaces/srv/SetParameters`` call, what ``ros2 param set FACE task TASK`` does, and
prints one JSON line: ``{"successful": bool, "reason": str}``, or ``{"error": str}`` when
the face did not appear or answer within TIMEOUT seconds. Its node is hidden (a leading
underscore): it is no extra node of the robot. Never imported by rosreconf.

A request unanswered after ``RESEND`` seconds is sent again (the first answer to any of them
counts): a service can take a request from a client it has not yet matched both ways and
drop the answer (rmw_fastrtps waits 100 ms for the client's reader, then rclpy warns
"failed to send response (timeout)"), and ``wait_for_service`` only says the client matched
the service, not the reverse. The face answers a repeat of the switch it took as taken.
"""

from __future__ import annotations

import json
import os
import sys
import time
from typing import Any

import rclpy
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters

RESEND = 1.5
"""Seconds without an answer before the request is sent again."""


def call(node: Any, client: Any, request: Any, timeout: float) -> Any:
    """Send ``request``, again every ``RESEND`` s unanswered; return the first answer, or None
    after ``timeout`` s."""
    deadline = time.monotonic() + timeout
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
                return done[0].result()
    for f in futures:
        client.remove_pending_request(f)
    return None


def main() -> int:
    face, task, timeout = sys.argv[1], sys.argv[2], float(sys.argv[3])
    rclpy.init()
    node = rclpy.create_node(f"_rosreconf_task_{os.getpid()}")
    try:
        client = node.create_client(SetParameters, f"{face.rstrip('/')}/set_parameters")
        if not client.wait_for_service(timeout_sec=timeout):
            print(json.dumps({"error": f"no face {face} answers on this domain"}))
            return 0
        request = SetParameters.Request()
        value = ParameterValue(type=ParameterType.PARAMETER_STRING, string_value=task)
        request.parameters = [Parameter(name="task", value=value)]
        answer = call(node, client, request, timeout)
        if answer is None:
            print(json.dumps({"error": f"{face} did not answer within {timeout:g} s"}))
            return 0
        (result,) = answer.results
        print(json.dumps({"successful": bool(result.successful), "reason": result.reason}))
        return 0
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
