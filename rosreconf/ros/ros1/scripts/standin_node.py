#!/usr/bin/python3
"""Stand in for a library component on a real ROS 1 master, so tests need no real robot code.

It ships inside rosreconf because ``rosreconf watch --stand-ins`` starts it through roslaunch
(see ``rosreconf.ros.ros1.standins``); it is a script, not part of the library, and is never
imported by rosreconf. Run it with the system Python (``/usr/bin/python3``), which has rospy
from Debian; the project's venv has none. The one argument is a JSON spec, inline or a path::

    {"name": "talker",
     "publish":   [{"topic": "/a", "type": "std_msgs/String"}],
     "subscribe": [{"topic": "/b", "type": "robot_arm_msgs/DcServoCommand"}],
     "serve":     [{"service": "/s", "type": "std_srvs/Trigger"}],
     "rate_hz": 2.0}

Types: a type whose Python package is installed (``std_msgs/String``, ``std_srvs/Trigger``,
...) is used as it is. For any other name (the example library's invented
``robot_arm_msgs/DcServoCommand``) the node uses a subclass of ``std_msgs/String`` (services:
``std_srvs/Trigger``) whose ``_type`` is the declared name. rospy registers ``_type`` with
the master, so ``getTopicTypes`` reports the declared type; the wire format and md5sum are
String's, so two stand-ins using the same invented type talk to each other, but a real node
with the real type would not connect (md5sum mismatch). Services have no type at the master.

Stops cleanly (unregistering everything) on SIGINT/SIGTERM. Writes one JSON line to stdout
once everything is registered: {"ready": "/<name>", "pid": ..., "posing_as": [types]}.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

import roslib.message
import rospy
import std_msgs.msg
import std_srvs.srv

FALLBACK_MSG = std_msgs.msg.String
FALLBACK_SRV = std_srvs.srv.Trigger
POSING: set[str] = set()
"""The declared types this process could not import and stands in for."""


def message_class(name: str) -> Any:
    """Return the installed class of message type ``name``, or a String posing as it."""
    try:
        cls = roslib.message.get_message_class(name)
    except ValueError:
        cls = None
    if cls is not None:
        return cls
    POSING.add(name)
    return type(name.replace("/", "__"), (FALLBACK_MSG,), {"__slots__": (), "_type": name})


def service_class(name: str) -> Any:
    """Return the installed class of service type ``name``, or a Trigger posing as it."""
    try:
        cls = roslib.message.get_service_class(name)
    except ValueError:
        cls = None
    if cls is not None:
        return cls
    POSING.add(name)
    return type(name.replace("/", "__"), (FALLBACK_SRV,), {"_type": name})


def answer(cls: Any, node: str) -> Any:
    """Return a handler giving the default response, or Trigger's success, for ``cls``."""
    response = cls._response_class

    def handle(_request: Any) -> Any:
        if issubclass(response, std_srvs.srv.TriggerResponse):
            return response(success=True, message=f"stand-in {node}")
        return response()

    return handle


def _die_with_parent() -> None:
    """Stop (SIGTERM) when roslaunch dies: a SIGKILLed watch kills roslaunch, not its nodes."""
    if sys.platform.startswith("linux"):
        import ctypes
        import signal

        ctypes.CDLL(None).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
        if os.getppid() == 1:  # roslaunch died before prctl took effect
            os.kill(os.getpid(), signal.SIGTERM)


def main(argv: list[str]) -> int:
    """Register the spec's topics and services, publish until told to stop."""
    _die_with_parent()
    argv = rospy.myargv(argv)  # drop roslaunch's __name:= and __log:= arguments
    if len(argv) != 2:
        print(f"usage: {argv[0]} SPEC_JSON_OR_FILE", file=sys.stderr)
        return 2
    text = argv[1] if argv[1].lstrip().startswith("{") else Path(argv[1]).read_text()
    spec = json.loads(text)
    rospy.init_node(spec["name"], anonymous=False)
    pubs = []
    for p in spec.get("publish", []):
        cls = message_class(p["type"])
        pubs.append((rospy.Publisher(p["topic"], cls, queue_size=10, latch=True), cls))
    for s in spec.get("subscribe", []):
        cls = message_class(s["type"])
        rospy.Subscriber(s["topic"], cls, lambda _msg: None)
    for s in spec.get("serve", []):
        cls = service_class(s["type"])
        rospy.Service(s["service"], cls, answer(cls, rospy.get_name()))
    ready = {"ready": rospy.get_name(), "pid": os.getpid(), "posing_as": sorted(POSING)}
    print(json.dumps(ready), flush=True)
    rate = rospy.Rate(float(spec.get("rate_hz", 2.0)))
    while not rospy.is_shutdown():
        for pub, cls in pubs:
            msg = cls()
            if isinstance(msg, FALLBACK_MSG):
                msg.data = rospy.get_name()
            pub.publish(msg)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
