"""A ROS 1 system as a ``LiveSource``: read from its master, acted on with roslaunch.

``MasterSource`` only reads; what acts is its actuator, ``MasterActuator``: roslaunch starts
nodes (``standins.Roslaunch``), the node API's ``shutdown`` stops them, and dead nodes the
master keeps listing are unregistered.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.launcher import LaunchActuator
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros1.rosmaster import (
    DEFAULT_MAX_BYTES,
    DEFAULT_TIMEOUT,
    known_identity,
    master_identity,
    purge_dead,
    read_live_graph,
    restart_event,
    shutdown_node,
)
from rosreconf.ros.ros1.standins import Roslaunch


@dataclass
class MasterSource:
    """A ROS 1 system, read from its master (each call with a deadline and an answer cap)."""

    master_uri: str
    timeout: float = DEFAULT_TIMEOUT
    max_bytes: int = DEFAULT_MAX_BYTES
    ros_version: RosVersion = RosVersion.ROS1
    _known: tuple[int | None, str | None] | None = field(default=None, repr=False)

    @property
    def uri(self) -> str:
        """Return the master URI."""
        return self.master_uri

    def read(self) -> LiveGraph:
        """Return what the master lists, with each node's pid."""
        return read_live_graph(self.master_uri, timeout=self.timeout, max_bytes=self.max_bytes)

    def identity(self) -> tuple[int | None, str | None] | None:
        """Return the master's pid and ``/run_id`` (they change when it restarts)."""
        return master_identity(self.master_uri, timeout=self.timeout, max_bytes=self.max_bytes)

    def restarted(self) -> tuple[str, dict[str, Any]] | None:
        """Return what to say when the master restarted since the last call (new pid or run id)."""
        now = self.identity()
        before, self._known = self._known, known_identity(self._known, now)
        return restart_event(before, now)

    def actuator(self, acting: Acting) -> Actuator:
        """Return roslaunch's actuator (nodes stopped through their API's ``shutdown``)."""
        return MasterActuator(Roslaunch(), acting, master=self)

    def close(self) -> None:
        """Hold nothing: each read is its own XML-RPC calls."""


@dataclass
class MasterActuator(LaunchActuator):
    """The ``Actuator`` of ROS 1: roslaunch, nodes stopped through their API, dead ones
    unregistered from ``master`` (each call with its deadline and answer cap)."""

    master: MasterSource = field(kw_only=True)

    def stop_node(self, graph: LiveGraph, node: str, reason: str) -> bool:
        """Call the node API's ``shutdown`` (what ``rosnode kill`` does)."""
        uri = next((n.uri for n in graph.nodes if n.name == node), None)
        return uri is not None and shutdown_node(uri, reason, timeout=self.master.timeout)

    def forget(self, graph: LiveGraph, dead: list[str]) -> None:
        """Unregister dead nodes (SIGKILLed nodes linger in the master), saying which."""
        m = self.master
        purged = purge_dead(
            m.master_uri, graph, only=dead, timeout=m.timeout, max_bytes=m.max_bytes
        )
        if purged:
            self.acting.say(
                "purged",
                f"unregistered dead node(s) {', '.join(purged)} from the master",
                nodes=list(purged),
            )
