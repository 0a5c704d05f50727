"""Tell a parked standby from an extra node: a library's managed node held out of service (ROS 2).

A managed (lifecycle) node that is not active does no work: its lifecycle publishers are
silent and nothing of the configuration is wired to it. ``watch --standby`` keeps the managed
alternatives of the schema's roles so, configured and ``inactive``, so that a failover is one
``activate``; without ``--standby`` a replaced managed node is parked ``unconfigured``
(deactivate, then cleanup). Either is where rosreconf leaves it on purpose, not a node that
runs beside the configuration. So a node of the live graph that is not in the configuration,
whose name is the live name of a managed component of the library, and whose state was read
``inactive`` or ``unconfigured``, is a **standby**: listed, not an ``extra-node`` finding.
``inspect`` and ``watch`` judge it alike (``watch`` also excuses the nodes it parked itself
whatever their state reads). An active one, one in another state (``finalized``, ``unknown``:
no answer, ``unanswered``: hung) or a managed node the library does not know is an extra node
as before: nothing says it is out of service, or ready to come back.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass
from typing import Any

from rosreconf.model import ComponentLibrary
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.livegraph import LiveNode

PARKED_STATES = ("inactive", "unconfigured")
"""The lifecycle states of a managed node held out of service: a ready standby (inactive,
one ``activate`` from service) or a parked one (unconfigured: configure, then activate)."""


@dataclass(frozen=True)
class Standby:
    """A managed node of the library held out of service.

    Attributes:
        node: its live name.
        components: the library's managed components that have this live name.
        state: its lifecycle state read (one of ``PARKED_STATES``).
    """

    node: str
    components: tuple[str, ...]
    state: str

    def to_dict(self) -> dict[str, Any]:
        """Return the JSON shape of one ``standby`` entry of ``inspect --json``."""
        return {"node": self.node, "components": list(self.components), "state": self.state}


def standbys(
    library: ComponentLibrary, expected: Collection[str], answering: Mapping[str, LiveNode]
) -> tuple[Standby, ...]:
    """Return the live nodes not in ``expected`` that are the library's parked managed nodes.

    ``expected`` holds the configuration's live node names, ``answering`` the live nodes
    found alive by name.
    """
    managed: dict[str, list[str]] = {}
    for comp in library.components:
        if comp.launch is not None and comp.launch.lifecycle:
            managed.setdefault(node_live_name(comp), []).append(comp.name)
    return tuple(
        Standby(name, tuple(sorted(managed[name])), str(node.lifecycle_state))
        for name, node in sorted(answering.items())
        if name not in expected and name in managed and node.lifecycle_state in PARKED_STATES
    )
