"""Try again, while the watcher waits for conformance, a lifecycle transition that timed out.

A managed node put into service is configured, then activated, each call with a 5 s timeout
(``rosreconf.ros.ros2.lifecycle``). Under load a call can time out and still come right: the
node's ``on_configure`` takes longer than that (a camera driver opening its device), or the
request was lost because the node had not yet matched the agent's request writer (a fresh
process: the client sees the service before the server sees the client). Before, nothing
asked again until ``--settle`` had passed (``not-conformant``) and the next poll's lifecycle
check found the node ``inactive``: 3 of 10 camera switches with standbys ended so. Now, for a
component of the configuration whose transition timed out, each tick of the watcher (while
it confirms a change too) looks at the node's state read with the graph and sends the next
transition towards ``active``: ``configure`` from ``unconfigured``, ``activate`` from
``inactive``. Each is said (event ``lifecycle``).

Never twice at once: a node is asked again only ``RETRY_AFTER`` s after a call of its timed
out (a request DDS is still repairing arrives within Fast DDS's 3 s heartbeat), only from a
primary state the graph read shows (a node still in ``on_configure`` answers no
``get_state``: nothing is sent), and the agent reads the state again before sending
(rclpy's ``LifecycleNode`` ends its process on a transition from a state it does not leave).
Each retry waits at most ``RETRY_TIMEOUT`` s: it runs on the watch loop's path. Retries go on
for ``RETRY_FOR`` s after the first timeout, then are said given up; the lifecycle checks
(``rosreconf.ros.lifecycle_faults``) take over. A refused transition is not retried.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from rosreconf.model import ComponentLibrary, Configuration
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.ros2.transitions import Transitions

RETRY_AFTER = 3.5
"""Seconds after a call timed out before its node is asked again."""
RETRY_TIMEOUT = 1.0
"""Seconds one retried transition may take (it runs on the watch loop's path)."""
RETRY_FOR = 30.0
"""Seconds after a first timeout that a component is retried (``watch``'s default
``--settle``): then it is left to the lifecycle checks."""
NEXT = {"unconfigured": "configure", "inactive": "activate"}
"""The transition towards ``active`` from each primary state that has one."""


@dataclass
class Retry:
    """A component whose node is not yet where its timed-out transitions were to take it.

    Attributes:
        since: when its first transition timed out (``time.monotonic``).
        last: when its last one timed out.
    """

    since: float
    last: float


@dataclass
class Retries:
    """The timed-out transitions of one watcher's components, tried again (module docstring).

    Attributes:
        library: what the configuration is made of.
        lifecycle: the watcher's lifecycle agent (its ``timeouts`` say what timed out).
        say: receives every event.
        pending: component -> its retry.
        states: node -> the lifecycle state of the graph last read (``saw``).
        read_at: when that graph was read (``time.monotonic``).
    """

    library: ComponentLibrary
    lifecycle: Transitions
    say: Callable[..., None]
    pending: dict[str, Retry] = field(default_factory=dict)
    states: Mapping[str, str | None] = field(default_factory=dict)
    read_at: float = float("-inf")

    def saw(self, states: Mapping[str, str | None]) -> None:
        """Take the lifecycle states of a graph read just now (node -> state)."""
        self.states, self.read_at = dict(states), time.monotonic()

    def tend(self, current: Configuration, parked: Collection[str]) -> None:
        """Send the next transition towards ``active`` to each component due for one.

        Judged on the graph read last, and only if it was read after the component's last
        timeout: a state read before (the process a restart replaced was ``active``) says
        nothing of the node now. ``parked``: the nodes held out of service, which are not
        taken back into it here.
        """
        for comp, at in self.lifecycle.timeouts.items():
            known = self.pending.get(comp)
            self.pending[comp] = Retry(at if known is None else known.since, at)
        self.lifecycle.timeouts.clear()
        now = time.monotonic()
        for comp, retry in list(self.pending.items()):
            node = node_live_name(self.library[comp])
            state = self.states.get(node) if self.read_at > retry.last else None
            if comp not in current.components or node in parked or state == "active":
                del self.pending[comp]  # no longer to be put into service, or there
            elif now - retry.since > RETRY_FOR:
                del self.pending[comp]
                self.say(
                    "lifecycle",
                    f"{node}: not active {now - retry.since:.0f} s after a transition timed "
                    f"out (it is {state}): not tried again here",
                    component=comp,
                    node=node,
                    ok=False,
                )
            elif now - retry.last >= RETRY_AFTER and state in NEXT:
                step = [(comp, NEXT[state])]
                ok = self.lifecycle.perform(step, RETRY_TIMEOUT, RETRY_TIMEOUT).get(comp, False)
                if not ok and comp not in self.lifecycle.timeouts:
                    del self.pending[comp]  # refused, or in a state it does not leave: final
