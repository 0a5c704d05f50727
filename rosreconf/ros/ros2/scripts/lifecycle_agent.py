#!/usr/bin/env python3
"""Perform lifecycle transitions for rosreconf: one rclpy node answering JSON lines on stdin.

It ships inside rosreconf, run by ``rosreconf.ros.ros2.lifecycle`` under a Python with rclpy;
it is never imported by rosreconf. Each request is one JSON line on stdin, each answer one on
the pipe rosreconf gave it as stdout (same ``id``), which the agent keeps for its answers
alone: fd 1 itself goes to its log before rclpy starts, with whatever Fast DDS prints
(``helper_channel``)::

    {"id": 1, "op": "watch", "nodes": ["/NDC1"]}        clients made now, so later calls are
                                                         not slowed by discovery -> {"ok": true}
    {"id": 2, "op": "ready", "nodes": ["/NDC1", "/NDC2"]}   -> {"ok": true, "ready": ["/NDC2"]}
                                                         (whose services are matched now)
    {"id": 3, "op": "batch", "items": [{"node": "/NDC1", "transition": "activate"}, ...],
     "timeout": 5}
        -> {"ok": true, "results": [{"node", "transition", "ok", "state", "seconds", "error",
                                     "timed_out"}]}
           (every state read, the transitions asked for at once, every state read back)

``appear`` (seconds, default ``timeout``) bounds the wait for a service to appear, separately
from ``timeout``, which bounds each call: a node just started needs seconds to come up.

Each result fails ("ok": false, "error": "...") when a service did not appear, a call timed
out, the node is in a state the transition does not leave, the node refused, the state read
back is not the one the transition leads to, or the node was already asked in this batch (only
its first item is sent: rclpy ends a node asked for a transition it has just left). The first
two also say ``"timed_out": true``: the node may yet get there (a slow ``on_configure``, a
request lost while the service was being matched), so rosreconf asks again later. The node
is not left half-way by the agent: it either did the transition or not. A node already in the
state the transition leads to counts as done: a retried ``configure`` whose first answer was
lost on a busy machine must not fail.
"""

from __future__ import annotations

import faulthandler
import json
import sys
import time
from typing import Any

import rclpy
from helper_channel import take_channel
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState

HEARTBEAT = 0.25
"""Seconds between the agent's signs of life (``{"alive": ...}``), which it says while it runs
even in the middle of a long request: rosreconf replaces an agent silent for 2 s."""
IDS = {
    "configure": Transition.TRANSITION_CONFIGURE,
    "cleanup": Transition.TRANSITION_CLEANUP,
    "activate": Transition.TRANSITION_ACTIVATE,
    "deactivate": Transition.TRANSITION_DEACTIVATE,
    "shutdown": Transition.TRANSITION_UNCONFIGURED_SHUTDOWN,
}
FROM = {
    "configure": ("unconfigured",),
    "cleanup": ("inactive",),
    "activate": ("inactive",),
    "deactivate": ("active",),
    "shutdown": ("unconfigured", "inactive", "active"),
}
"""The primary states each transition leaves (ROS 2's lifecycle state machine)."""
GOAL = {
    "configure": "inactive",
    "cleanup": "unconfigured",
    "activate": "active",
    "deactivate": "inactive",
    "shutdown": "finalized",
}


RESEND = 0.5
"""Seconds before an unanswered ``get_state`` is asked again (``Agent._states``)."""


class Agent:
    """One node holding a change_state and a get_state client per managed node."""

    def __init__(self, name: str) -> None:
        self.node = rclpy.create_node(name)  # hidden (a leading _): not an extra node
        self.clients: dict[str, tuple[Any, Any]] = {}

    def _clients(self, node: str) -> tuple[Any, Any]:
        if node not in self.clients:
            self.clients[node] = (
                self.node.create_client(ChangeState, f"{node}/change_state"),
                self.node.create_client(GetState, f"{node}/get_state"),
            )
        return self.clients[node]

    def _states(
        self, items: list[dict[str, str]], which: list[int], timeout: float
    ) -> dict[int, Any]:
        """Read several items' node states at once (None: no answer within the timeout).

        A read is asked again every ``RESEND`` s until answered: a node restarted under the
        same name can be matched late (its predecessor's endpoints linger a moment), and a
        request sent before it matched is lost, not queued. ``get_state`` changes nothing,
        so asking twice is harmless.
        """
        deadline = time.monotonic() + timeout
        reads: dict[int, Any] = {}
        while True:
            for i in which:
                if i not in reads or not reads[i].done():
                    reads[i] = self._clients(items[i]["node"])[1].call_async(GetState.Request())
            self._spin(list(reads.values()), min(deadline, time.monotonic() + RESEND))
            if all(r.done() for r in reads.values()) or time.monotonic() >= deadline:
                break
        return {
            i: str(r.result().current_state.label) if r.done() else None for i, r in reads.items()
        }

    def batch(self, items: list[dict[str, str]], timeout: float, appear: float) -> list[Any]:
        """Perform several transitions at once: read each state, ask, read each state back.

        A transition is asked for only from a state it leaves: rclpy's ``LifecycleNode``
        (Jazzy, Kilted) raises out of its executor on any other, which ends the node's
        process, where rclcpp answers ``success: false``. A node already in the state the
        transition leads to counts as done. So one node is asked once per batch: a second
        ``configure`` sent beside the first reaches it inactive, and ends it (seen: a standby
        listed twice for configuring exited 1 on every start).
        """
        start = time.monotonic()
        errors: dict[int, str] = {}
        late: set[int] = set()  # timed out: the node may yet answer, or get there
        for i, item in enumerate(items):
            change, get = self._clients(item["node"])
            for client in (change, get):
                if i not in errors and not client.wait_for_service(timeout_sec=appear):
                    errors[i] = f"{client.srv_name} did not appear within {appear:g} s"
                    late.add(i)
        asking = [i for i in range(len(items)) if i not in errors]
        before = self._states(items, asking, timeout)
        calls: dict[int, Any] = {}
        first: dict[str, int] = {}
        for i in asking:
            node, name = items[i]["node"], items[i]["transition"]
            if first.setdefault(node, i) != i:
                asked = items[first[node]]["transition"]
                errors[i] = f"{node} was asked for {asked} in this batch already: {name} not sent"
            elif before[i] is None:
                errors[i] = f"{node}/get_state did not answer within {timeout:g} s ({name})"
                late.add(i)
            elif before[i] != GOAL[name] and before[i] not in FROM[name]:
                errors[i] = f"{node} is {before[i]}: {name} is not a transition from it"
            elif before[i] != GOAL[name]:
                request = ChangeState.Request()
                request.transition.id = IDS[name]
                calls[i] = self._clients(node)[0].call_async(request)
        self._spin(list(calls.values()), time.monotonic() + timeout)
        after = self._states(items, list(calls), timeout)
        results = []
        for i, item in enumerate(items):
            node, name = item["node"], item["transition"]
            state, future, error = after.get(i, before.get(i)), calls.get(i), errors.get(i)
            if error is None and future is not None and not future.done():
                error = f"{node}/change_state did not answer within {timeout:g} s ({name})"
                late.add(i)
            elif error is None and future is not None and not future.result().success:
                error = f"{node} refused {name} (it is {state})"
            elif error is None and state != GOAL[name]:
                error = f"after {name}, {node} is {state}, not {GOAL[name]}"
            took = round(time.monotonic() - start, 4)
            results.append(
                {
                    "node": node,
                    "transition": name,
                    "ok": error is None,
                    "state": state,
                    "seconds": took,
                    "error": error,
                    "timed_out": i in late and error is not None,
                }
            )
        return results

    def _spin(self, futures: list[Any], deadline: float) -> None:
        while futures and not all(f.done() for f in futures) and time.monotonic() < deadline:
            rclpy.spin_once(self.node, timeout_sec=max(0.0, min(0.05, deadline - time.monotonic())))

    def handle(self, request: dict[str, Any]) -> dict[str, Any]:
        """Answer one request (see the module docstring)."""
        op = request.get("op")
        timeout = float(request.get("timeout", 5.0))
        appear = float(request.get("appear", timeout))
        if op == "watch":
            for node in request.get("nodes", []):
                self._clients(node)
            return {"ok": True}
        if op == "forget":  # a node restarted under its name: new clients match it afresh
            for node in request.get("nodes", []):
                for client in self.clients.pop(node, ()):
                    self.node.destroy_client(client)
            return {"ok": True}
        if op == "ready":
            nodes = request.get("nodes", [])
            ready = [n for n in nodes if all(c.service_is_ready() for c in self._clients(n))]
            return {"ok": True, "ready": ready}
        if op == "batch":
            return {"ok": True, "results": self.batch(request["items"], timeout, appear)}
        return {"ok": False, "error": f"unknown op {op!r}"}


def main() -> int:
    """Answer requests until stdin closes (rosreconf ended) or a signal stops it."""
    faulthandler.enable()  # a crash in rclpy or DDS leaves every thread's stack on stderr
    answers = take_channel()  # before rclpy.init: Fast DDS prints on fd 1
    rclpy.init(args=sys.argv)
    agent = Agent(sys.argv[1].lstrip("/"))
    answers.say({"ready": agent.node.get_fully_qualified_name()})
    answers.beat(HEARTBEAT)
    try:
        for line in sys.stdin:
            if not line.strip():
                continue
            request = json.loads(line)
            answer = agent.handle(request)
            answers.say({"id": request.get("id"), **answer})
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
