"""Treat a managed node of the configuration that leaves ``active`` as a fault (ROS 2).

A managed (lifecycle) node does its work only while ``active``; one deactivated by a person
or by its own error handling is as good as gone, though its process runs and DDS shows it.
``watch`` reads every managed node's state with the graph (``inspect``'s ``not-active``
finding); ``LifecycleFaults`` says each such node once per state it is found in and, with
``--apply``, brings it back (configure if unconfigured, then activate). When that does not
hold, the component is failed and the watcher replaces it by the fewest change. A node whose
state query goes unanswered (``unanswered``: it answered before, then not for 1.5 s) is hung:
it could not answer a transition either, so it is failed at once, never driven.

A finding that persists is never left standing: a node still read in the same state
``LASTS`` s after it was brought back (the transitions said it held, the graph says
otherwise) is failed (``how``: ``lifecycle``), and so is a component whose node has been read
as a plain node (``not-managed``: it serves no ``get_state``) for ``LASTS`` s (``how``:
``not-managed``): either way the watcher restarts or replaces it, as any failure. A node just
started shows itself before its lifecycle services are discovered, hence the wait; a node
once seen managed stays managed in the ROS 2 reader while it runs, so one unanswered or
unseen read never makes it plain. A state read ``unknown`` (no answer yet, or a server not
asked: rmw_cyclonedds) is said and brought back, but never failed for lasting.

``checked`` names what a conformance check found met, for the ``conformant`` event.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from rosreconf.ros.conformance import Conformance, Finding

HUNG = "unanswered"
"""The state label a ROS 2 reader gives a managed node that stopped answering its state
query (``ros2.lifecycle_state.UNANSWERED``; the core does not import a middleware)."""
UNKNOWN = "unknown"
"""The state label of a managed node whose state was not read (``ros2.lifecycle_state``)."""
LASTS = 5.0
"""Seconds a lifecycle finding may outlast its repair (or, ``not-managed``, last) before the
component is failed: a read after a transition that held shows it within a poll or two."""


@dataclass
class LifecycleFaults:
    """Say and repair managed nodes of the configuration found out of ``active``.

    Attributes:
        say: receives the events (``not-active``, and ``failed`` when it cannot come back).
        reactivate: (component, state shown) -> whether it is ``active`` again; None: only
            say it (``watch`` without ``--apply``).
        said: component -> the state last said: a stale read must not act twice.
        since: component -> when its state was said (``not-active``) or its node first read
            plain (``not-managed``), in monotonic seconds: what ``LASTS`` counts from.
    """

    say: Callable[..., None]
    reactivate: Callable[[str, str], bool] | None = None
    said: dict[str, str] = field(default_factory=dict)
    since: dict[str, float] = field(default_factory=dict)

    def check(self, check: Conformance, failed: set[str], role_of: Callable[[str], str]) -> bool:
        """Act on ``check``'s ``not-active`` and ``not-managed`` findings; True when one was
        new (a fault seen).

        A component that cannot be made active again, or whose finding persists (``LASTS``),
        is added to ``failed``.
        """
        states = {n.name: n.lifecycle_state for n in check.live.nodes}
        now, new = time.monotonic(), False
        codes = {(f.component, f.code) for f in check.findings}
        for ended in [c for c in self.since if (c, "not-active") not in codes]:
            if (ended, "not-managed") not in codes:  # read active (or gone): a fault ended
                del self.since[ended]
                self.said.pop(ended, None)
        for f in check.findings:
            comp = f.component
            if comp is None or comp in failed:
                continue
            if f.code == "not-managed":
                self._plain(f, comp, failed, role_of, now)
                continue
            if f.code != "not-active":
                continue
            state = states.get(f.live_name) or UNKNOWN
            if self.said.get(comp) == state:
                self._lasting(comp, state, failed, role_of, now)
                continue
            self.said[comp], self.since[comp], new, role = state, now, True, role_of(comp)
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
            self.since[comp] = time.monotonic()  # brought back now: LASTS counts from here
        return new

    def _lasting(
        self, comp: str, state: str, failed: set[str], role_of: Callable[[str], str], now: float
    ) -> None:
        """Fail a component still read in a state it was brought back from, ``LASTS`` s on."""
        if self.reactivate is None or state == UNKNOWN or now - self.since[comp] < LASTS:
            return
        self.say(
            "failed",
            f"{comp} ({role_of(comp)}) is still {state} {now - self.since[comp]:.0f} s after it "
            "was brought back: it does not stay active, failed",
            component=comp,
            how="lifecycle",
        )
        failed.add(comp)

    def _plain(
        self,
        finding: Finding,
        comp: str,
        failed: set[str],
        role_of: Callable[[str], str],
        now: float,
    ) -> None:
        """Fail a component whose node has been read as a plain node for ``LASTS`` s.

        Without ``--apply`` (no ``reactivate``) nothing is failed: ``watch`` only reports.
        """
        if self.reactivate is None or now - self.since.setdefault(comp, now) < LASTS:
            return
        self.say(
            "failed",
            f"{comp} ({role_of(comp)}): {finding.message}; still so after "
            f"{now - self.since[comp]:.0f} s: failed",
            component=comp,
            node=finding.live_name,
            how="not-managed",
        )
        failed.add(comp)


def checked(check: Conformance) -> dict[str, Any]:
    """Return what a conformance check judged (``Conformance.checked``), for ``conformant``.

    Nodes, the ROS-graph edges, every call, subscription and action of the configuration's
    nodes and the managed nodes' states: the event says what the confirmation stands on.
    """
    return {"checked": check.checked.to_dict()}
