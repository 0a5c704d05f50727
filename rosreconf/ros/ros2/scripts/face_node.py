"""rosreconf's face on a ROS 2 graph: a node that shows a running watch and takes task requests.

Run by rosreconf (``rosreconf.ros.ros2.face``) under the ROS 2 Python, as the lifecycle
agent is: ``face_node.py /rosreconf [CONTEXT_JSON] [--quiet]``. It speaks JSON lines on its own
channel
(``helper_channel``). rosreconf pushes, one line each, never answered::

    {"op": "state", "state": {"task", "configuration", "failed", "switching", "tasks",
                              "diagnostics"}}          (rosreconf.ros.facestate.snapshot)
    {"op": "log", "level": "error", "text": "..."}     one decision of the JSON log

and the node says, unasked::

    {"event": "switch", "task": "disc_loading"}        the task parameter was set: switch
    {"event": "refused", "task": "...", "reason": "..."}   a request it refused
    {"event": "context", "name": "visibility", "value": 2.0}   one reading of a context topic
    {"event": "context-error", "name": "...", "reason": "..."}  a context topic it cannot read

``CONTEXT_JSON`` lists the library's context variables (``[{"name", "topic", "type",
"field"}]``): the node subscribes to each topic with the sensor-data QoS (best effort, so it
matches reliable and best-effort publishers alike) and says the field's value of every
message (nested fields as ``a.b``). A NaN or infinite reading is no reading
(``sensor_msgs/BatteryState`` says an unmeasured percentage as NaN); a field that is no
number, boolean or string is said once as an error. With ``--quiet`` (``watch --no-face``)
the node only reads context: no parameters, no ``/diagnostics``, no ``/rosout`` lines.

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
import functools
import importlib
import json
import math
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
from rclpy.qos import qos_profile_sensor_data

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

    def __init__(self, name: str, answers: Channel, serve: bool = True) -> None:
        """``serve``: parameters, /diagnostics and /rosout (without: it only reads context)."""
        namespace, base = split(name)
        self.node = rclpy.create_node(base, namespace=namespace)
        self.answers = answers
        self.serve = serve
        self.state: dict[str, Any] = {}
        self.outbox: list[dict[str, Any]] = []
        self.declared = False
        self.internal = False
        if serve:
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
        if not self.serve:
            return
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


def message_class(type_name: str) -> Any:
    """Return the message class of ``pkg/msg/Name`` (or ``pkg/Name``)."""
    parts = type_name.split("/")
    if len(parts) not in (2, 3) or not all(parts):
        raise ValueError(f"not a message type: {type_name}")
    return getattr(importlib.import_module(f"{parts[0]}.msg"), parts[-1])


class Readings:
    """The subscriptions to the context topics; every reading is said on the channel."""

    def __init__(self, node: Any, variables: list[dict[str, str]], answers: Channel) -> None:
        self.answers = answers
        self.subscriptions = []
        self.bad: set[str] = set()
        for v in variables:
            try:
                kind = message_class(v["type"])
            except (ImportError, AttributeError, ValueError) as exc:
                self.error(v["name"], f"cannot subscribe to {v['topic']} as {v['type']}: {exc}")
                continue
            take = functools.partial(self.read, v)
            sub = node.create_subscription(kind, v["topic"], take, qos_profile_sensor_data)
            self.subscriptions.append(sub)

    def error(self, name: str, reason: str) -> None:
        if name not in self.bad:
            self.bad.add(name)
            self.answers.say({"event": "context-error", "name": name, "reason": reason})

    def read(self, v: dict[str, str], msg: Any) -> None:
        value = msg
        try:
            for part in v["field"].split("."):
                value = getattr(value, part)
        except AttributeError:
            self.error(v["name"], f"{v['type']} has no field {v['field']}")
            return
        if isinstance(value, bool | str):
            pass
        elif isinstance(value, int | float):
            value = float(value)
            if not math.isfinite(value):
                return  # no reading (an unmeasured BatteryState percentage is NaN)
        else:
            self.error(v["name"], f"{v['field']} of {v['type']} is no number, boolean or text")
            return
        self.answers.say({"event": "context", "name": v["name"], "value": value})


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
    args = [a for a in sys.argv[1:] if a != "--quiet"]
    quiet = "--quiet" in sys.argv[1:]
    rclpy.init(args=sys.argv)
    face = Face(args[0], answers, serve=not quiet)
    readings = Readings(face.node, json.loads(args[1]) if len(args) > 1 else [], answers)
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
        del readings
        rclpy.try_shutdown()


if __name__ == "__main__":
    sys.exit(main())
