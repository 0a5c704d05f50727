"""Perform ROS 2 lifecycle transitions: ``change_state``, confirmed with ``get_state``.

A managed node (``ros.lifecycle: true``) is taken into service by ``configure`` then
``activate`` and out of it by ``deactivate`` then ``cleanup``; each is a call of the node's
``/<node>/change_state`` service (``lifecycle_msgs/srv/ChangeState``), what ``ros2 lifecycle
set`` does. rosreconf reads DDS without rclpy, so the calls go through one helper process it
owns, ``scripts/lifecycle_agent.py`` under the ROS 2 Python (``rosreconf.ros.ros2.helper``),
which answers JSON lines and stays up, so its service clients are matched before they are needed:
a transition then takes milliseconds, not a new process and a discovery round (seconds).
Each transition has a timeout and is confirmed by reading the state back; any failure is a
``LifecycleError`` with the node, the transition and why. Nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.ros.ros2.helper import Helper
from rosreconf.ros.ros2.runtime import ros2_python

AGENT_SCRIPT = Path(__file__).parent / "scripts" / "lifecycle_agent.py"
TIMEOUT = 5.0
"""Seconds one lifecycle service call may take."""
APPEAR = 30.0
"""Seconds a node just started may take until its lifecycle services appear."""
OUT_OF_SERVICE = ("deactivate", "cleanup")
HUNG_SECONDS = 2.0
"""Seconds without a word from the agent (it beats every 0.25 s, even during a long request)
after which it is hung and replaced, as a hung node is within 2 s."""


class LifecycleError(ExternalToolError):
    """A transition was refused, timed out, or did not lead to the state it should."""


@dataclass(frozen=True)
class Outcome:
    """One transition performed: the node, the transition, the state read back, how long.

    ``timed_out``: it failed for want of an answer in time (a service that did not appear, a
    call unanswered, the agent itself silent), so the node may yet get there: it is asked
    again later (``rosreconf.ros.ros2.retrying``), where a refusal is final.
    """

    node: str
    transition: str
    ok: bool
    state: str | None
    seconds: float
    error: str | None = None
    timed_out: bool = False


AGENT_NODE = "/_rosreconf_lifecycle"
"""The agent's node name (hidden: a leading underscore), given to the script as it starts."""


class LifecycleAgent(Helper):
    """Own the helper process that calls lifecycle services (see the module docstring)."""

    error = LifecycleError
    hung_after = HUNG_SECONDS

    def __init__(self, env: Mapping[str, str], log: Path, timeout: float = TIMEOUT) -> None:
        self.timeout = timeout
        self._next = 0
        python = ros2_python(env)
        name = f"the lifecycle agent ({python} {AGENT_SCRIPT.name})"
        super().__init__([python, str(AGENT_SCRIPT), AGENT_NODE], env, log, name)

    def _ask(self, request: dict[str, Any], timeout: float) -> dict[str, Any]:
        self._next += 1
        self.send([{"id": self._next, **request}])
        return self.answer(self._next, timeout + 2.0, str(request.get("op")))

    def watch(self, nodes: Collection[str]) -> None:
        """Make the clients for these nodes now, so that their transitions are fast later."""
        if nodes:
            self._ask({"op": "watch", "nodes": sorted(nodes)}, self.timeout)

    def forget(self, nodes: Collection[str]) -> None:
        """Drop the clients of nodes whose process was stopped, to be made anew on next use.

        A node restarted under the same name is then matched by fresh clients, not through
        endpoints that were matched with its predecessor.
        """
        if nodes:
            self._ask({"op": "forget", "nodes": sorted(nodes)}, self.timeout)

    def ready(self, nodes: Collection[str]) -> set[str]:
        """Return the nodes whose lifecycle services are matched now (no waiting)."""
        answer = self._ask({"op": "ready", "nodes": sorted(nodes)}, self.timeout)
        return set(answer.get("ready", []))

    def transitions(
        self,
        items: list[tuple[str, str]],
        appear: float | None = None,
        timeout: float | None = None,
    ) -> list[Outcome]:
        """Perform several (node, transition) at once, each confirmed with ``get_state``.

        ``timeout`` bounds each transition (default: the agent's); a caller on the watch
        loop's path passes a short one, so that a slow node never holds detection up.
        """
        if not items:
            return []
        each = self.timeout if timeout is None else timeout
        wait = each if appear is None else appear
        start = time.monotonic()
        request = {
            "op": "batch",
            "timeout": each,
            "appear": wait,
            "items": [{"node": n, "transition": t} for n, t in items],
        }
        try:
            answer = self._ask(request, 2 * each + wait * len(items))
        except LifecycleError as exc:
            took = time.monotonic() - start
            return [Outcome(n, t, False, None, took, str(exc), timed_out=True) for n, t in items]
        return [
            Outcome(
                r["node"],
                r["transition"],
                bool(r["ok"]),
                r.get("state"),
                float(r["seconds"]),
                r.get("error"),
                bool(r.get("timed_out", False)),
            )
            for r in answer.get("results", [])
        ]
