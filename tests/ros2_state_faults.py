"""Run rosreconf's stand-in with lifecycle services of its own that misbehave on a signal.

A fault injector for the tests, named as such. A real managed node (rclpy's or rclcpp's
``LifecycleNode``) makes its state services with the node and never drops them, and it stays
in the state it was taken to; what the tests must provoke is how rosreconf reads such a node
when a read misses its ``get_state`` server (a loaded host's discovery) and when the node
keeps leaving ``active``. So the stand-in runs as a plain rclpy node (its spec's
``lifecycle`` set false) and this wrapper gives it the ``<node>/get_state`` and
``<node>/change_state`` services of ``lifecycle_msgs`` itself, answering the lifecycle state
machine as rclpy does (a transition from a state it does not leave is refused)::

    python tests/ros2_state_faults.py rosreconf/ros/ros2/scripts/standin_node.py SPEC ...

SIGUSR2 destroys the ``get_state`` server: it leaves DDS discovery; with ``STATE_GAP_SECONDS``
in the environment it is made again that many seconds later, else never. SIGUSR1 makes the
node fall back to ``inactive`` 0.3 s after every activation from then on (its own error
handling, say), and at once when it is active.
"""

from __future__ import annotations

import json
import os
import runpy
import signal
import sys
from typing import Any

import rclpy
from lifecycle_msgs.msg import State, Transition
from lifecycle_msgs.srv import ChangeState, GetState

IDS = {"unconfigured": 1, "inactive": 2, "active": 3, "finalized": 4}
MOVES = {
    Transition.TRANSITION_CONFIGURE: ("unconfigured", "inactive"),
    Transition.TRANSITION_CLEANUP: ("inactive", "unconfigured"),
    Transition.TRANSITION_ACTIVATE: ("inactive", "active"),
    Transition.TRANSITION_DEACTIVATE: ("active", "inactive"),
}


class Lifecycle:
    """The state services of one plain node, and the faults they act out."""

    def __init__(self, node: Any) -> None:
        self.node = node
        self.state = "unconfigured"
        self.falls_back = False
        self.gap = float(os.environ.get("STATE_GAP_SECONDS", "0") or 0)
        self.pending: list[str] = []
        """What signals asked since the last tick (a handler only takes note)."""
        self._due: list[tuple[float, str]] = []
        self.get_state: Any = self._make_get_state()
        name = node.get_fully_qualified_name()
        node.create_service(ChangeState, f"{name}/change_state", self._change)
        node.create_timer(0.05, self._tick)

    def _make_get_state(self) -> Any:
        name = self.node.get_fully_qualified_name()
        return self.node.create_service(GetState, f"{name}/get_state", self._get)

    def _now(self) -> float:
        return float(self.node.get_clock().now().nanoseconds) / 1e9

    def _get(self, _request: Any, response: Any) -> Any:
        response.current_state = State(id=IDS[self.state], label=self.state)
        return response

    def _change(self, request: Any, response: Any) -> Any:
        move = MOVES.get(request.transition.id)
        response.success = move is not None and move[0] == self.state
        if response.success:
            self.state = move[1]
            if self.state == "active" and self.falls_back:
                self._due.append((self._now() + 0.3, "fall"))
        return response

    def _tick(self) -> None:
        """Carry out what a signal asked (signal handlers only take note) and what is due."""
        for what in self.pending:
            if what == "drop" and self.get_state is not None:
                self.node.destroy_service(self.get_state)
                self.get_state = None
                if self.gap > 0:
                    self._due.append((self._now() + self.gap, "make"))
            elif what == "fall":
                self.falls_back = True
                self._due.append((self._now(), "fall"))
        self.pending.clear()
        now, due = self._now(), self._due
        self._due = [(t, w) for t, w in due if t > now]
        for _, what in (d for d in due if d[0] <= now):
            if what == "make" and self.get_state is None:
                self.get_state = self._make_get_state()
            elif what == "fall" and self.state == "active":
                self.state = "inactive"


def main() -> None:
    """Run the stand-in script given, plain, with these state services on its node."""
    script, spec_arg, *rest = sys.argv[1:]
    with open(spec_arg) if not spec_arg.lstrip().startswith("{") else open(os.devnull) as f:
        text = spec_arg if spec_arg.lstrip().startswith("{") else f.read()
    spec = {**json.loads(text), "lifecycle": False}
    made: list[Lifecycle] = []
    create = rclpy.create_node

    def create_node(*args: Any, **kwargs: Any) -> Any:
        node = create(*args, **kwargs)
        made.append(Lifecycle(node))
        return node

    rclpy.create_node = create_node  # the stand-in's plain node, made through rclpy's own call
    signal.signal(signal.SIGUSR2, lambda *_: [m.pending.append("drop") for m in made])
    signal.signal(signal.SIGUSR1, lambda *_: [m.pending.append("fall") for m in made])
    sys.argv = [script, json.dumps(spec), *rest]
    runpy.run_path(script, run_name="__main__")


if __name__ == "__main__":
    main()
