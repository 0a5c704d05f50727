#!/usr/bin/env python3
"""Stand in for a library component as a real rclpy node, so a ROS 2 system can be tried bare.

It ships inside rosreconf because ``rosreconf watch --ros2 --stand-ins`` starts it (see
``rosreconf.ros.ros2.nodes``); it is a script, not part of the library, and is never imported
by rosreconf. Run it with a Python that has rclpy (``ROSRECONF_ROS2_PYTHON``; rosreconf's own
venv has none). The one argument is a JSON spec, inline or as a file path
(``rosreconf.ros.standin_spec.ros2_standin_spec`` writes it)::

    {"name": "NSM3", "namespace": "/",
     "publish":   [{"topic": "/a", "type": "std_msgs/msg/String"}],
     "subscribe": [{"topic": "/b", "type": "robot_arm_msgs/msg/DcServoCommand"}],
     "serve":     [{"service": "/s", "type": "robot_arm_msgs/srv/DigitalServoCommand"}],
     "call":      [{"service": "/t", "type": "std_srvs/srv/Trigger"}],
     "action_serve": [{"action": "/follow_path", "type": "nav2_msgs/action/FollowPath"}],
     "action_call": [...], "lifecycle": false, "rate_hz": 1.0, "component": "NCTRL"}

Types: an installed type (``std_msgs/msg/String``) is used as it is. Any other name (the
example library's invented ``robot_arm_msgs/msg/DcServoCommand``) is *posed*, as the ROS 1
stand-in poses: a subclass of ``std_msgs/msg/String`` (services: ``std_srvs/srv/Trigger``)
whose type support is a copy of String's Fast DDS one (``rosidl_typesupport_fastrtps_c``)
with the declared namespace and name, so rmw_fastrtps announces
``robot_arm_msgs::msg::dds_::DcServoCommand_`` over DDS and rclpy's graph API says
``robot_arm_msgs/msg/DcServoCommand``. The wire format and type hash are String's (Trigger's):
two stand-ins posing as one type talk to each other; a real node with the real type would
not match. Only the Fast DDS route is posed (the RMW the ROS 2 wheels ship). Actions are
served and called with rclpy's ``ActionServer`` / ``ActionClient`` (every goal succeeds at
once); one not installed is posed by ``test_msgs`` (or ``example_interfaces``) Fibonacci, its
send_goal, get_result and feedback renamed; without both, exit 3 naming what to install.

A managed component (``lifecycle: true``) is a ``rclpy.lifecycle.LifecycleNode``: unconfigured
at start, endpoints made on ``configure``, published only while active, gone on ``cleanup``.

Stops cleanly on SIGINT/SIGTERM (its participant says goodbye), also one that comes as it
begins to spin, within ``SHUTDOWN_BOUND_SECONDS``; past it (Fast DDS 2.14 can busy-spin for
ever destroying a participant, holding the GIL: Fast-DDS #6513, 1 in about 400 SIGINTs under
load here) it exits 1, each thread's stack in its log, and its peers see it go when its lease
ends. Once its node exists, one JSON line on stdout: {"ready": "/<name>", "pid": ..., ...}.
"""

from __future__ import annotations

import ctypes
import faulthandler
import functools
import importlib
import json
import os
import signal
import sys
from pathlib import Path
from typing import Any

import rclpy
import std_msgs.msg
import std_srvs.srv
from rclpy.action import ActionClient, ActionServer
from rclpy.executors import ExternalShutdownException
from rclpy.type_support import check_for_type_support

SHUTDOWN_BOUND_SECONDS = 4.0  # a healthy teardown takes milliseconds; ros2 launch waits 5 s
POSING: set[str] = set()
_KEEP: list[Any] = []  # every buffer and callback the posed type supports point to
_FAST = b"rosidl_typesupport_fastrtps_c"
_DYNAMIC = b"rosidl_dynamic_typesupport_c"
_P = ctypes.c_void_p
_HANDLE_FN = ctypes.CFUNCTYPE(_P, _P, ctypes.c_char_p)
_API = ctypes.pythonapi
_API.PyCapsule_GetPointer.restype = _P
_API.PyCapsule_GetPointer.argtypes = [ctypes.py_object, ctypes.c_char_p]
_API.PyCapsule_New.restype = ctypes.py_object
_API.PyCapsule_New.argtypes = [_P, ctypes.c_char_p, _P]
_MSG_HANDLE_BYTES = 6 * 8  # rosidl_message_type_support_t (Iron+): identifier, data, func, 3 hooks
_SRV_HANDLE_BYTES = 11 * 8  # rosidl_service_type_support_t: ident., data, func, 3 msgs, 5 hooks
_MSG_CALLBACKS_BYTES = 16 * 8  # more than message_type_support_callbacks_t; 2 fields changed
_ACTION_HANDLE_BYTES = 8 * 8  # rosidl_action_type_support_t (Iron+): 5 type supports, 3 hooks
POSE_ACTIONS_AS = ("test_msgs", "example_interfaces")
"""Packages whose ``action/Fibonacci`` poses as an action type that is not installed."""
_SRV_CALLBACKS_BYTES = 4 * 8  # service_type_support_callbacks_t: namespace, name, req., resp.


class _Handle(ctypes.Structure):
    _fields_ = [("identifier", ctypes.c_char_p), ("data", _P), ("func", _P)]


def _lookup(handle: int, identifier: bytes) -> int:
    """Return the type support ``identifier`` of ``handle`` (rosidl's dispatch)."""
    h = _Handle.from_address(handle)
    if h.identifier == identifier:
        return handle
    return int(_HANDLE_FN(h.func)(handle, identifier) or 0)


def _copy(address: int, size: int) -> Any:
    buf = ctypes.create_string_buffer(size)
    ctypes.memmove(buf, address, size)
    _KEEP.append(buf)
    return buf


def _text(value: str) -> int:
    s = ctypes.c_char_p(value.encode())
    _KEEP.append(s)
    return int(ctypes.cast(s, _P).value or 0)


def _posed_handle(original: int, size: int, names: tuple[str, str], extra: Any = None) -> int:
    """Copy the Fast DDS type support of ``original`` with another namespace and name."""
    fast = _lookup(original, _FAST)
    if not fast:
        raise RuntimeError("no Fast DDS type support (rmw_fastrtps_cpp is the RMW posed)")
    callbacks_size = _MSG_CALLBACKS_BYTES if extra is None else _SRV_CALLBACKS_BYTES
    callbacks = _copy(_Handle.from_address(fast).data, callbacks_size)
    fields = (_P * 4).from_buffer(callbacks)
    fields[0], fields[1] = _text(names[0]), _text(names[1])
    if extra is not None:
        extra(fields)
    handle = _copy(fast, size)

    def dispatch(_me: int, identifier: bytes) -> int:  # no dynamic one (Kilted asks): the
        if identifier == _DYNAMIC:  # base's dispatch would fail and leave an rcutils error set
            return 0
        return ctypes.addressof(handle) if identifier == _FAST else _lookup(original, identifier)

    func = _HANDLE_FN(dispatch)
    _KEEP.append(func)
    view = _Handle.from_buffer(handle)
    view.data = ctypes.addressof(callbacks)
    view.func = ctypes.cast(func, _P).value
    return ctypes.addressof(handle)


def _posed_class(base: Any, name: str, handle: int, attrs: dict[str, Any]) -> Any:
    meta = type(base)
    capsule = _API.PyCapsule_New(handle, None, None)
    posed_meta = type(
        f"Metaclass_{name}",
        (meta,),
        {"_TYPE_SUPPORT": capsule, "__import_type_support__": classmethod(lambda cls: None)},
    )
    return posed_meta(name, (base,), attrs)


def _installed(pkg: str, folder: str, short: str) -> Any:
    """Return the installed class ``pkg.<folder>.<short>``, or None when no package has it."""
    try:
        return getattr(importlib.import_module(f"{pkg}.{folder}"), short)
    except (ImportError, AttributeError):
        return None


def _posing_base(name: str, base: Any) -> tuple[Any, Any]:
    """Note that ``name`` is posed; return ``base`` and its type support's raw pointer."""
    POSING.add(name)
    check_for_type_support(base)
    return base, _API.PyCapsule_GetPointer(type(base)._TYPE_SUPPORT, None)


def message_class(name: str) -> Any:
    """Return the installed class of ``pkg/msg/Name``, or a String posing as it."""
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "msg", short)
    if installed is not None:
        return installed
    base, original = _posing_base(name, std_msgs.msg.String)
    handle = _posed_handle(original, _MSG_HANDLE_BYTES, (f"{pkg}::msg", short))
    return _posed_class(base, short, handle, {"__slots__": ()})


def _posed_service(original: int, ns: str, short: str) -> int:
    """Copy a service's Fast DDS type support, and its two messages', with other names."""

    def messages(fields: Any) -> None:  # request_members_, response_members_
        fields[2] = _posed_handle(fields[2], _MSG_HANDLE_BYTES, (ns, f"{short}_Request"))
        fields[3] = _posed_handle(fields[3], _MSG_HANDLE_BYTES, (ns, f"{short}_Response"))

    return _posed_handle(original, _SRV_HANDLE_BYTES, (ns, short), messages)


def service_class(name: str) -> Any:
    """Return the installed class of ``pkg/srv/Name``, or a Trigger posing as it."""
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "srv", short)
    if installed is not None:
        return installed
    base, original = _posing_base(name, std_srvs.srv.Trigger)
    return _posed_class(base, short, _posed_service(original, f"{pkg}::srv", short), {})


class CannotPose(Exception):
    """An action type is not installed and no installed action type can pose as it."""


@functools.cache
def action_class(name: str) -> Any:
    """Return the installed class of ``pkg/action/Name``, or a Fibonacci posing as it.

    rcl_action builds an action from five parts of ``rosidl_action_type_support_t``: the
    send_goal and get_result services, the feedback message (these three carry the action's
    name, so they are posed: ``pkg::action::dds_::Name_SendGoal_Request_`` ...), and
    action_msgs' cancel service and status message (the same for every action; kept).
    """
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "action", short)
    if installed is not None:
        return installed
    base = next(filter(None, (_installed(p, "action", "Fibonacci") for p in POSE_ACTIONS_AS)), None)
    if base is None:
        raise CannotPose(
            f"action type {name} is not installed, and no action type to pose as is "
            f"({' or '.join(f'{p}/action/Fibonacci' for p in POSE_ACTIONS_AS)}: install "
            "ros-<distro>-test-msgs or ros-<distro>-example-interfaces beside rclpy)"
        )
    base, original = _posing_base(name, base)
    ns = f"{pkg}::action"
    parts = _copy(original, _ACTION_HANDLE_BYTES)
    fields: Any = (_P * 8).from_buffer(parts)
    fields[0] = _posed_service(fields[0], ns, f"{short}_SendGoal")
    fields[1] = _posed_service(fields[1], ns, f"{short}_GetResult")
    fields[3] = _posed_handle(fields[3], _MSG_HANDLE_BYTES, (ns, f"{short}_FeedbackMessage"))
    return _posed_class(base, short, ctypes.addressof(parts), {})


class Endpoints:
    """The spec's publishers, subscriptions, servers and clients on one node."""

    def __init__(self, node: Any, spec: dict[str, Any]) -> None:
        self.node = node
        self.made: list[Any] = []
        self.pubs: list[tuple[Any, Any]] = []
        self.actions: list[Any] = []
        for p in spec.get("publish", []):
            cls = message_class(p["type"])
            pub = node.create_publisher(cls, p["topic"], 10)
            self.pubs.append((pub, cls))
            self.made.append(pub)
        for s in spec.get("subscribe", []):
            cls = message_class(s["type"])
            self.made.append(node.create_subscription(cls, s["topic"], _ignore, 10))
        for s in spec.get("serve", []):
            cls = service_class(s["type"])
            self.made.append(node.create_service(cls, s["service"], _answer(node)))
        for c in spec.get("call", []):
            self.made.append(node.create_client(service_class(c["type"]), c["service"]))
        for a in spec.get("action_serve", []):
            cls = action_class(a["type"])
            self.actions.append(ActionServer(node, cls, a["action"], _succeed(cls)))
        for a in spec.get("action_call", []):
            self.actions.append(ActionClient(node, action_class(a["type"]), a["action"]))

    def publish(self) -> None:
        """Publish one message on every topic (posed types carry the node's name)."""
        for pub, cls in self.pubs:
            msg = cls()
            if isinstance(msg, std_msgs.msg.String):
                msg.data = self.node.get_fully_qualified_name()
            pub.publish(msg)

    def destroy(self) -> None:
        """Destroy every endpoint (a managed node's cleanup)."""
        for entity in self.made:
            for kind in ("publisher", "subscription", "service", "client"):
                destroy = getattr(self.node, f"destroy_{kind}")
                try:
                    destroy(entity)
                    break
                except Exception:  # not this kind
                    continue
        for action in self.actions:
            action.destroy()
        self.made.clear()
        self.pubs.clear()
        self.actions.clear()


def _ignore(_msg: Any) -> None:
    return None


def _succeed(cls: Any) -> Any:
    def execute(goal: Any) -> Any:  # every goal succeeds at once, with an empty result
        goal.succeed()
        return cls.Result()

    return execute


def _answer(node: Any) -> Any:
    def handle(_request: Any, response: Any) -> Any:
        if hasattr(response, "success"):
            response.success = True
            response.message = f"stand-in {node.get_fully_qualified_name()}"
        return response

    return handle


def plain_node(spec: dict[str, Any]) -> Any:
    """Return an unmanaged node with every endpoint, publishing at the spec's rate."""
    node = rclpy.create_node(spec["name"], namespace=spec.get("namespace") or "/")
    ends = Endpoints(node, spec)
    node.create_timer(1.0 / float(spec.get("rate_hz", 1.0)), ends.publish)
    return node


def managed_node(spec: dict[str, Any]) -> Any:
    """Return a lifecycle node whose endpoints exist from configure to cleanup."""
    from rclpy.lifecycle import LifecycleNode, State, TransitionCallbackReturn

    class StandIn(LifecycleNode):  # type: ignore[misc]
        def __init__(self) -> None:
            super().__init__(spec["name"], namespace=spec.get("namespace") or "/")
            self.ends: Endpoints | None = None
            self.active = False
            self.create_timer(1.0 / float(spec.get("rate_hz", 1.0)), self.tick)

        def tick(self) -> None:
            if self.active and self.ends is not None:
                self.ends.publish()

        def on_configure(self, state: State) -> TransitionCallbackReturn:
            self.ends = Endpoints(self, spec)
            return TransitionCallbackReturn.SUCCESS

        def on_activate(self, state: State) -> TransitionCallbackReturn:
            self.active = True
            return TransitionCallbackReturn.SUCCESS

        def on_deactivate(self, state: State) -> TransitionCallbackReturn:
            self.active = False
            return TransitionCallbackReturn.SUCCESS

        def on_cleanup(self, state: State) -> TransitionCallbackReturn:
            if self.ends is not None:
                self.ends.destroy()
            self.ends = None
            return TransitionCallbackReturn.SUCCESS

        def on_shutdown(self, state: State) -> TransitionCallbackReturn:
            return self.on_cleanup(state)

    return StandIn()


def warm() -> None:
    """Import and load now what any stand-in needs (``standin_zygote.py`` forks after this)."""
    import rclpy.lifecycle  # noqa: F401

    for base in (
        std_msgs.msg.String,
        std_srvs.srv.Trigger,
        _installed(POSE_ACTIONS_AS[0], "action", "Fibonacci"),
    ):
        if base is not None:  # what posed types are made of
            check_for_type_support(base)


def main(argv: list[str]) -> int:
    """Create the spec's node and spin until told to stop."""
    faulthandler.enable()  # a crash in rclpy or DDS (Kilted's SIGSEGV) leaves its stacks in the log
    args = rclpy.utilities.remove_ros_args(argv)
    if len(args) != 2:
        print(f"usage: {args[0]} SPEC_JSON_OR_FILE", file=sys.stderr)
        return 2
    text = args[1] if args[1].lstrip().startswith("{") else Path(args[1]).read_text()
    spec = json.loads(text)
    for action in spec.get("action_serve", []) + spec.get("action_call", []):
        try:
            action_class(action["type"])
        except CannotPose as exc:
            who = f"stand-in for {spec.get('component', spec['name'])} ({spec['name']})"
            print(f"{who}: cannot act out action {action['action']}: {exc}", file=sys.stderr)
            return 3
    rclpy.init(args=argv)
    node = None
    try:
        node = managed_node(spec) if spec.get("lifecycle") else plain_node(spec)
        ready = {"ready": node.get_fully_qualified_name(), "pid": os.getpid()}
        print(json.dumps({**ready, "posing_as": sorted(POSING)}), flush=True)
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception:  # stopped as spin began: rclpy's signal thread shut the context (RCLError)
        if rclpy.ok():
            raise
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C still to be raised: stopping now
        faulthandler.dump_traceback_later(SHUTDOWN_BOUND_SECONDS, exit=True)  # a C thread: no GIL
        if node is not None:
            node.destroy_node()  # while the posed type supports it points to still exist
        rclpy.try_shutdown()  # the participant says goodbye
    sys.stdout.flush()
    # No interpreter teardown: it would free the posed type supports in no set order (a
    # segfault at exit was seen), and it is slow; everything that matters is done.
    os._exit(0)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
