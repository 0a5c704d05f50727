"""rosreconf's face on a ROS 2 graph: a node that shows a running watch and takes task requests.

Run by rosreconf (``rosreconf.ros.ros2.face``) under the ROS 2 Python, as the lifecycle
agent is: ``face_node.py /rosreconf``. It speaks JSON lines on its own channel
(``helper_channel``). rosreconf pushes, one line each, never answered::

    {"op": "state", "state": {"task", "configuration", "failed", "switching", "tasks",
                              "diagnostics"}}          (rosreconf.ros.facestate.snapshot)
    {"op": "log", "level": "error", "text": "..."}     one decision of the JSON log

and the node says, unasked::

    {"event": "switch", "task": "disc_loading"}        the task parameter was set: switch
    {"event": "refused", "task": "...", "reason": "..."}   a request it refused

The node ``/rosreconf`` (its argument) has:

- parameter ``task`` (string): the task running now. Setting it asks for a switch. The
  callback only decides, from the feasibility table rosreconf pushed (fast, no side effects):
  it refuses (``successful: false``, the reason in words) a task that is not one of the
  watch's, has no configuration now, or comes while a switch is under way. The switch
  request is said only after the answer is sent (the next turn of the loop), and the
  switch runs in rosreconf. The descriptor's ``additional_constraints`` lists the tasks.
- read-only parameters ``configuration`` (``role=component`` strings) and ``failed``.
- ``/diagnostics`` (``diagnostic_msgs/msg/DiagnosticArray``): every second, and at once
  when the state changes; header.stamp set; levels as ``DiagnosticStatus``'s byte constants.
- ``/rosout``: every decision as a log line of its level (rclpy's logger).
"""

from __future__ import annotations

import faulthandler
import json
import queue
import sys
import threading
from typing import Any

import rclpy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from helper_channel import Channel, take_channel
from rcl_interfaces.msg import ParameterDescriptor, ParameterType, SetParametersResult
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter

LEVELS = {0: DiagnosticStatus.OK, 1: DiagnosticStatus.WARN, 2: DiagnosticStatus.ERROR}
PERIOD = 1.0
"""Seconds between two ``/diagnostics`` messages when nothing changes (Foxglove marks a
status stale after 5 s without one)."""


def split(name: str) -> tuple[str, str]:
    """Return (namespace, base name) of an absolute node name."""
    namespace, _, base = name.rpartition("/")
    return namespace or "/", base


class Face:
    """The node, its parameters, its publisher and what it last heard from rosreconf."""

    def __init__(self, name: str, answers: Channel) -> None:
        namespace, base = split(name)
        self.node = rclpy.create_node(base, namespace=namespace)
        self.answers = answers
        self.state: dict[str, Any] = {}
        self.outbox: list[dict[str, Any]] = []
        self.declared = False
        self.internal = False
        self.publisher = self.node.create_publisher(DiagnosticArray, "/diagnostics", 10)
        self.node.add_on_set_parameters_callback(self.asked)
        self.node.create_timer(PERIOD, self.publish)

    def descriptors(self) -> dict[str, ParameterDescriptor]:
        tasks = ", ".join(t["task"] for t in self.state.get("tasks", []))
        return {
            "task": ParameterDescriptor(
                name="task",
                type=ParameterType.PARAMETER_STRING,
                description="The task (interoperability schema) watch runs; set it to switch.",
                additional_constraints=f"one of: {tasks}",
            ),
            "configuration": ParameterDescriptor(
                name="configuration",
                type=ParameterType.PARAMETER_STRING_ARRAY,
                description="The configuration that should run now, as role=component.",
                read_only=True,
            ),
            "failed": ParameterDescriptor(
                name="failed",
                type=ParameterType.PARAMETER_STRING_ARRAY,
                description="The components known to have failed.",
                read_only=True,
            ),
        }

    def values(self) -> list[Parameter]:
        config = [f"{r}={c or ''}" for r, c in self.state["configuration"].items()]
        return [
            Parameter("task", Parameter.Type.STRING, self.state["task"]),
            Parameter("configuration", Parameter.Type.STRING_ARRAY, config or ["(none)"]),
            Parameter("failed", Parameter.Type.STRING_ARRAY, self.state["failed"] or ["(none)"]),
        ]

    def take(self, state: dict[str, Any]) -> None:
        """Take a state line: parameters follow it; a change is published at once."""
        changed = state != self.state
        self.state = state
        descriptors, values = self.descriptors(), self.values()
        self.internal = True
        try:
            if not self.declared:
                for p in values:
                    self.node.declare_parameter(p.name, p.value, descriptors[p.name])
                self.declared = True
            else:  # new descriptors skip the read-only check: only this node sets them
                self.node._set_parameters_atomically_common(values, descriptors)
        finally:
            self.internal = False
        if changed:
            self.publish()

    def verdict(self, task: str) -> str | None:
        """Return why a switch to ``task`` is refused now, or None when it may go ahead."""
        switching = self.state.get("switching")
        if switching:
            return f"a switch to {switching} is under way; ask again once it is conformant"
        table = {t["task"]: t for t in self.state.get("tasks", [])}
        if task not in table:
            return f"no task {task!r}: the tasks are {', '.join(sorted(table))}"
        if not table[task]["ok"]:
            return str(table[task]["reason"])
        return None

    def asked(self, params: list[Parameter]) -> SetParametersResult:
        """Decide a parameter set from the table pushed last; say the switch after answering.

        A set of the task a switch is under way to is answered as taken and not said again:
        a client resends when its answer was lost (the service had not matched it both ways)."""
        if self.internal:
            return SetParametersResult(successful=True)
        for p in params:
            if p.name != "task":
                return SetParametersResult(successful=False, reason=f"{p.name} is read-only")
            if p.value == self.state.get("task") and not self.state.get("switching"):
                return SetParametersResult(successful=True)  # the task running now: no change
            if p.value == self.state.get("switching"):  # a repeat (a client's resend whose
                return SetParametersResult(successful=True)  # first answer was lost): taken
            why = self.verdict(str(p.value))
            if why is not None:
                self.outbox.append({"event": "refused", "task": str(p.value), "reason": why})
                return SetParametersResult(successful=False, reason=why)
            self.outbox.append({"event": "switch", "task": str(p.value)})
            self.state = {**self.state, "switching": str(p.value)}  # a second set is refused
        return SetParametersResult(successful=True)

    def publish(self) -> None:
        rows = self.state.get("diagnostics")
        if rows is None:
            return
        msg = DiagnosticArray()
        msg.header.stamp = self.node.get_clock().now().to_msg()
        for row in rows:
            status = DiagnosticStatus()
            status.level = LEVELS[int(row["level"])]
            status.name = str(row["name"])
            status.message = str(row["message"])
            status.hardware_id = str(row["hardware_id"])
            status.values = [KeyValue(key=str(k), value=str(v)) for k, v in row["values"]]
            msg.status.append(status)
        self.publisher.publish(msg)

    def log(self, level: str, text: str) -> None:
        """Say ``text`` on /rosout. One call site per level: rclpy refuses a call site whose
        severity changes between calls."""
        logger = self.node.get_logger()
        if level == "error":
            logger.error(text)
        elif level == "warn":
            logger.warning(text)
        elif level == "debug":
            logger.debug(text)
        else:
            logger.info(text)

    def flush(self) -> None:
        """Say what was asked, now that the answers have gone out."""
        while self.outbox:
            self.answers.say(self.outbox.pop(0))


def read_lines(into: queue.Queue[dict[str, Any] | None]) -> None:
    """Hand every line of stdin to the loop; None when it closes (rosreconf ended)."""
    for line in sys.stdin:
        if line.strip():
            into.put(json.loads(line))
    into.put(None)


def main() -> int:
    """Show the watch until stdin closes (rosreconf ended) or a signal stops it."""
    faulthandler.enable()
    answers = take_channel()  # before rclpy.init: Fast DDS prints on fd 1
    rclpy.init(args=sys.argv)
    face = Face(sys.argv[1], answers)
    executor = SingleThreadedExecutor()
    executor.add_node(face.node)
    inbox: queue.Queue[dict[str, Any] | None] = queue.Queue()
    threading.Thread(target=read_lines, args=(inbox,), daemon=True).start()
    answers.say({"ready": face.node.get_fully_qualified_name()})
    try:
        while True:
            executor.spin_once(timeout_sec=0.02)
            face.flush()
            try:
                while True:
                    line = inbox.get_nowait()
                    if line is None:
                        return 0
                    if line.get("op") == "state":
                        face.take(line["state"])
                    elif line.get("op") == "log":
                        face.log(str(line.get("level")), str(line.get("text")))
            except queue.Empty:
                pass
    except KeyboardInterrupt:
        return 0
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
