"""Treat a managed node of the configuration that leaves ``active`` as a fault (ROS 2).

A managed (lifecycle) node does its work only while ``active``; one deactivated by a person
or by its own error handling is as good as gone, though its process runs and DDS shows it.
``watch`` reads every managed node's state with the graph (``inspect``'s ``not-active``
finding); ``LifecycleFaults`` says each such node once per state it is found in and, with
``--apply``, brings it back (configure if unconfigured, then activate). When that does not
hold, the component is failed and the watcher replaces it by the fewest change. A node whose
state query goes unanswered (``unanswered``: it answered before, then not for 1.5 s) is hung:
it could not answer a transition either, so it is failed at once, never driven.

``checked`` names what a conformance check found met, for the ``conformant`` event.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from rosreconf.ros.conformance import Conformance

HUNG = "unanswered"
"""The state label a ROS 2 reader gives a managed node that stopped answering its state
query (``ros2.lifecycle_state.UNANSWERED``; the core does not import a middleware)."""


@dataclass
class LifecycleFaults:
    """Say and repair managed nodes of the configuration found out of ``active``.

    Attributes:
        say: receives the events (``not-active``, and ``failed`` when it cannot come back).
        reactivate: (component, state shown) -> whether it is ``active`` again; None: only
            say it (``watch`` without ``--apply``).
        said: component -> the state last said: a stale read must not act twice.
    """

    say: Callable[..., None]
    reactivate: Callable[[str, str], bool] | None = None
    said: dict[str, str] = field(default_factory=dict)

    def check(self, check: Conformance, failed: set[str], role_of: Callable[[str], str]) -> bool:
        """Act on ``check``'s ``not-active`` findings; True when one was new (a fault seen).

        A component that cannot be made active again is added to ``failed``.
        """
        states = {n.name: n.lifecycle_state for n in check.live.nodes}
        new = False
        for f in check.findings:
            comp = f.component
            if f.code != "not-active" or comp is None or comp in failed:
                continue
            state = states.get(f.live_name) or "unknown"
            if self.said.get(comp) == state:
                continue
            self.said[comp], new, role = state, True, role_of(comp)
            if state == HUNG:
                self.say(
                    "failed",
                    f"{comp} ({role}): managed node {f.live_name} has stopped answering its "
                    "state query (get_state): hung, failed",
                    component=comp,
                    node=f.live_name,
                    how="unanswered",
                )
                failed.add(comp)
                continue
            self.say(
                "not-active",
                f"{comp} ({role}): managed node {f.live_name} is {state}, not active: a fault",
                component=comp,
                node=f.live_name,
                state=state,
            )
            if self.reactivate is not None and not self.reactivate(comp, state):
                self.say(
                    "failed",
                    f"{comp} ({role}) cannot be made active again: failed",
                    component=comp,
                    how="lifecycle",
                )
                failed.add(comp)
        return new


def checked(check: Conformance) -> dict[str, Any]:
    """Return what a conformance check judged (``Conformance.checked``), for ``conformant``.

    Nodes, the ROS-graph edges, every call, subscription and action of the configuration's
    nodes and the managed nodes' states: the event says what the confirmation stands on.
    """
    return {"checked": check.checked.to_dict()}
