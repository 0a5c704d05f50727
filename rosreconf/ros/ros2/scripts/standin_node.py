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
stand-in poses (``standin_posing.py``, this script's sibling, says how): it goes over DDS
under the declared name, with String's wire format (Trigger's for services), so two
stand-ins posing as one type talk to each other and a real node with the real type would
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

import faulthandler
import json
import os
import signal
import sys
from pathlib import Path
from typing import Any

import rclpy
import std_msgs.msg
from rclpy.action import ActionClient, ActionServer
from rclpy.executors import ExternalShutdownException

# The sibling comes from this script's folder however it is run: as a program, forked by the
# zygote, or through runpy from a wrapper (the tests' fault injectors) whose folder is another.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from standin_posing import (
    POSING,
    CannotPose,
    action_class,
    load_bases,
    message_class,
    service_class,
)

SHUTDOWN_BOUND_SECONDS = 4.0  # a healthy teardown takes milliseconds; ros2 launch waits 5 s


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

    load_bases()


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
