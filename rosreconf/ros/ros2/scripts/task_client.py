"""Ask a running watch's ROS 2 face to switch task (``rosreconf task``, under ROS 2's Python).

``task_client.py FACE TASK TIMEOUT`` sets the face's ``task`` parameter with one
``rcl_interfaces/srv/SetParameters`` call, what ``ros2 param set FACE task TASK`` does, and
prints one JSON line: ``{"successful": bool, "reason": str}``, or ``{"error": str}`` when
the face did not appear or answer within TIMEOUT seconds. Its node is hidden (a leading
underscore): it is no extra node of the robot. Never imported by rosreconf.
"""

from __future__ import annotations

import json
import os
import sys

import rclpy
from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import SetParameters


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
        future = client.call_async(request)
        rclpy.spin_until_future_complete(node, future, timeout_sec=timeout)
        if not future.done():
            print(json.dumps({"error": f"{face} did not answer within {timeout:g} s"}))
            return 0
        (result,) = future.result().results
        print(json.dumps({"successful": bool(result.successful), "reason": result.reason}))
        return 0
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
