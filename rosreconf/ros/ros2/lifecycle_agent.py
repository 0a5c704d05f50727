#!/usr/bin/env python3
"""Perform lifecycle transitions for rosreconf: one rclpy node answering JSON lines on stdin.

It ships inside rosreconf, run by ``rosreconf.ros.ros2.lifecycle`` under a Python with rclpy;
it is never imported by rosreconf. Each request is one JSON line on stdin, each answer one on
stdout (same ``id``)::

    {"id": 1, "op": "watch", "nodes": ["/NDC1"]}        clients made now, so later calls are
                                                         not slowed by discovery -> {"ok": true}
    {"id": 2, "op": "transition", "node": "/NDC1", "transition": "activate", "timeout": 5}
        -> {"ok": true, "state": "active", "seconds": 0.004}   (change_state, then get_state)
    {"id": 3, "op": "state", "node": "/NDC1", "timeout": 5}  -> {"ok": true, "state": "inactive"}
    {"id": 4, "op": "ready", "nodes": ["/NDC1", "/NDC2"]}   -> {"ok": true, "ready": ["/NDC2"]}
                                                         (whose services are matched now)
    {"id": 5, "op": "batch", "items": [{"node": "/NDC1", "transition": "activate"}, ...]}
        -> {"ok": true, "results": [{"node", "transition", "ok", "state", "seconds", "error"}]}
                                    (all calls in flight at once, then all states read back)

``appear`` (seconds, default ``timeout``) bounds the wait for a service to appear, separately
from ``timeout``, which bounds each call: a node just started needs seconds to come up.

A failure is {"ok": false, "error": "..."}: the service did not appear, the call timed out,
the node refused the transition, or the state read back is not the one the transition leads
to. The node is not left half-way by the agent: it either did the transition or not.
"""

from __future__ import annotations

import json
import sys
import time
from typing import Any

import rclpy
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState, GetState

IDS = {
    "configure": Transition.TRANSITION_CONFIGURE,
    "cleanup": Transition.TRANSITION_CLEANUP,
    "activate": Transition.TRANSITION_ACTIVATE,
    "deactivate": Transition.TRANSITION_DEACTIVATE,
    "shutdown": Transition.TRANSITION_UNCONFIGURED_SHUTDOWN,
}
GOAL = {
    "configure": "inactive",
    "cleanup": "unconfigured",
    "activate": "active",
    "deactivate": "inactive",
    "shutdown": "finalized",
}


class Agent:
    """One node holding a change_state and a get_state client per managed node."""

    def __init__(self) -> None:
        self.node = rclpy.create_node("_rosreconf_lifecycle")  # hidden: not an extra node
        self.clients: dict[str, tuple[Any, Any]] = {}

    def _clients(self, node: str) -> tuple[Any, Any]:
        if node not in self.clients:
            self.clients[node] = (
                self.node.create_client(ChangeState, f"{node}/change_state"),
                self.node.create_client(GetState, f"{node}/get_state"),
            )
        return self.clients[node]

    def _call(self, client: Any, request: Any, deadline: float, what: str, appear: float) -> Any:
        if not client.wait_for_service(timeout_sec=max(0.0, appear)):
            raise TimeoutError(f"{client.srv_name} did not appear within {appear:g} s ({what})")
        deadline = max(deadline, time.monotonic() + 0.5)
        future = client.call_async(request)
        rclpy.spin_until_future_complete(
            self.node, future, timeout_sec=max(0.0, deadline - time.monotonic())
        )
        if not future.done():
            client.remove_pending_request(future)
            raise TimeoutError(f"{client.srv_name} did not answer within the timeout ({what})")
        return future.result()

    def state(self, node: str, timeout: float, appear: float) -> str:
        """Return the node's current state label (its get_state service)."""
        _, get = self._clients(node)
        deadline = time.monotonic() + timeout
        answer = self._call(get, GetState.Request(), deadline, "get_state", appear)
        return str(answer.current_state.label)

    def transition(self, node: str, name: str, timeout: float, appear: float) -> dict[str, Any]:
        """Ask for one transition, then read the state back."""
        change, get = self._clients(node)
        start = time.monotonic()
        request = ChangeState.Request()
        request.transition.id = IDS[name]
        answer = self._call(change, request, time.monotonic() + timeout, name, appear)
        deadline = time.monotonic() + timeout
        got = self._call(get, GetState.Request(), deadline, "get_state", appear)
        state = str(got.current_state.label)
        took = round(time.monotonic() - start, 4)
        done = {"state": state, "seconds": took}
        if not answer.success:
            return {"ok": False, **done, "error": f"{node} refused {name} (it is {state})"}
        if state != GOAL[name]:
            why = f"after {name}, {node} is {state}, not {GOAL[name]}"
            return {"ok": False, **done, "error": why}
        return {"ok": True, **done}

    def batch(self, items: list[dict[str, str]], timeout: float, appear: float) -> list[Any]:
        """Ask for several transitions at once, then read every state back."""
        start = time.monotonic()
        calls: list[tuple[dict[str, str], Any, str | None]] = []
        for item in items:
            change, _ = self._clients(item["node"])
            if not change.wait_for_service(timeout_sec=appear):
                calls.append((item, None, f"{change.srv_name} did not appear within {appear:g} s"))
                continue
            request = ChangeState.Request()
            request.transition.id = IDS[item["transition"]]
            calls.append((item, change.call_async(request), None))
        self._spin([f for _, f, _ in calls if f is not None], time.monotonic() + timeout)
        reads = [
            self._clients(item["node"])[1].call_async(GetState.Request()) if f else None
            for item, f, _ in calls
        ]
        self._spin([r for r in reads if r is not None], time.monotonic() + timeout)
        results = []
        for (item, future, error), read in zip(calls, reads, strict=True):
            node, name = item["node"], item["transition"]
            state = read.result().current_state.label if read and read.done() else None
            if error is None and (future is None or not future.done()):
                error = f"{node}/change_state did not answer within {timeout:g} s ({name})"
            elif error is None and not future.result().success:
                error = f"{node} refused {name} (it is {state})"
            elif error is None and state != GOAL[name]:
                error = f"after {name}, {node} is {state}, not {GOAL[name]}"
            took = round(time.monotonic() - start, 4)
            results.append({"node": node, "transition": name, "ok": error is None,
                            "state": state, "seconds": took, "error": error})  # fmt: skip
        return results

    def _spin(self, futures: list[Any], deadline: float) -> None:
        while futures and not all(f.done() for f in futures) and time.monotonic() < deadline:
            rclpy.spin_once(self.node, timeout_sec=max(0.0, min(0.05, deadline - time.monotonic())))

    def handle(self, request: dict[str, Any]) -> dict[str, Any]:
        op = request.get("op")
        timeout = float(request.get("timeout", 5.0))
        appear = float(request.get("appear", timeout))
        try:
            if op == "watch":
                for node in request.get("nodes", []):
                    self._clients(node)
                return {"ok": True}
            if op == "ready":
                ready = [
                    n
                    for n in request.get("nodes", [])
                    if all(c.service_is_ready() for c in self._clients(n))
                ]
                return {"ok": True, "ready": ready}
            if op == "state":
                return {"ok": True, "state": self.state(request["node"], timeout, appear)}
            if op == "batch":
                return {"ok": True, "results": self.batch(request["items"], timeout, appear)}
            if op == "transition":
                node, name = request["node"], request["transition"]
                return self.transition(node, name, timeout, appear)
            return {"ok": False, "error": f"unknown op {op!r}"}
        except TimeoutError as exc:
            return {"ok": False, "error": str(exc)}


def main() -> int:
    """Answer requests until stdin closes (rosreconf ended) or a signal stops it."""
    rclpy.init(args=sys.argv)
    agent = Agent()
    print(json.dumps({"ready": agent.node.get_fully_qualified_name()}), flush=True)
    try:
        for line in sys.stdin:
            if not line.strip():
                continue
            request = json.loads(line)
            answer = agent.handle(request)
            print(json.dumps({"id": request.get("id"), **answer}), flush=True)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
