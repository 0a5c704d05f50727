"""A ROS 2 system as a ``LiveSource``: read from DDS discovery on one domain."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from rosreconf.errors import ExternalToolError, UnsettledGraphError
from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.actuator import Ros2Actuator
from rosreconf.ros.ros2.discovery import FIRST_READ_AT_LEAST, Ros2Discovery
from rosreconf.ros.ros2.graph import graph_uri
from rosreconf.ros.ros2.launching import Ros2Launch, Ros2LaunchPort
from rosreconf.ros.ros2.lifecycle_state import StateReader, with_states
from rosreconf.ros.ros2.names import gid_sizes

STALE_GRACE = 0.5
"""Seconds a later read passes over discovery again while a participant's node list is stale:
a node that creates an endpoint (a managed node being configured) announces it before its
participant's next ``ros_discovery_info`` arrives, normally within milliseconds."""
FIRST_STATES_TIMEOUT = 3.0
"""Seconds the first read waits for managed nodes' ``get_state`` answers (their endpoints may
still be matching)."""
STATES_TIMEOUT = 0.1
"""Seconds a later read waits for them (an answer takes about 10 ms once matched; a node that
does not answer keeps the state it last answered, so a slow one never holds a poll back)."""


@dataclass
class Ros2Source:
    """A ROS 2 system, read from DDS discovery on one domain (a session kept open).

    ``read`` is the one read of ``inspect``, ``snapshot``, ``import`` and ``watch``: stale
    and empty graphs are refused, managed nodes' lifecycle states are read.

    Attributes:
        domain: the ROS_DOMAIN_ID.
        distro: the ROS 2 distribution, or None to read both Gid layouts.
        empty_ok: an empty domain is not an error on the first read (``watch --apply``
            starts the nodes itself).
        on_note: where to say what a read had to leave out (undecodable or forged samples).
        spin_time: the least seconds the first read listens before it may settle
            (``--spin-time``, as ros2cli's: a loaded host's participants answer late).
    """

    domain: int
    distro: str | None = None
    ros_version: RosVersion = RosVersion.ROS2
    empty_ok: bool = False
    on_note: Callable[[str], None] | None = None
    spin_time: float = FIRST_READ_AT_LEAST
    _session: Ros2Discovery | None = field(default=None, repr=False)
    _states: StateReader = field(default_factory=StateReader, repr=False)

    @property
    def uri(self) -> str:
        """Return ``ros2://domain/<id>``."""
        return graph_uri(self.domain)

    def read(self) -> LiveGraph:
        """Return the graph with managed nodes' states; refuse to call nothing a graph.

        The first read waits for discovery to settle and refuses an empty domain (unless
        ``empty_ok``) and node names it cannot read. Every read refuses a participant whose
        node list stays out of date (``stale``), a later one after passing over discovery
        for at most ``STALE_GRACE`` s. Later reads are one discovery pass each, and wait at
        most ``STATES_TIMEOUT`` s for lifecycle states.

        Raises:
            ExternalToolError: no ROS 2 participant answered on the domain, or some did but
                no node name could be read (a wrong ``--distro``, a broken writer).
            UnsettledGraphError: a participant's newest node list has not arrived
                (``stale``: a partial answer).
        """
        first = self._session is None
        if self._session is None:
            self._session = Ros2Discovery(self.domain, self.distro)
        session = self._session
        graph = session.read(at_least=self.spin_time)
        if first:
            self._refuse_empty(graph, session)
        deadline = time.monotonic() + STALE_GRACE
        while session.stale and not first and time.monotonic() < deadline:
            time.sleep(0.02)
            graph = session.read()
        if session.stale:
            raise UnsettledGraphError(
                f"{self._where}: {len(session.stale)} ROS 2 participant(s) announce endpoints "
                "that no node of their ros_discovery_info names, still after the read's wait: "
                "their newest ros_discovery_info was not received or did not decode, so their "
                "node list would be out of date (run again; see docs/ros2.md)"
            )
        if first:
            self._notes(session)
        timeout = FIRST_STATES_TIMEOUT if first else STATES_TIMEOUT
        return with_states(session, graph, timeout=timeout, reader=self._states)

    @property
    def _where(self) -> str:
        return f"ROS 2 domain {self.domain}"

    def _refuse_empty(self, graph: LiveGraph, session: Ros2Discovery) -> None:
        """Refuse a first read that shows no node (an empty domain only if not ``empty_ok``)."""
        if graph.nodes:
            return
        where = self._where
        layout = "" if self.distro is None else f" (--distro {self.distro} reads that "
        if layout:
            sizes = "/".join(str(s) for s in gid_sizes(self.distro))
            layout += f"distribution's {sizes}-byte Gid layout: try without --distro)"
        if session.ros_participants == 0 and session.endpoints == 0:
            if self.empty_ok:
                return
            others = session.participants - (1 if self.distro else 2)
            raise ExternalToolError(
                f"nothing seen on {where}: no ROS 2 participant answered"
                + (f" ({others} other DDS participant(s) did)" if others > 0 else "")
                + " (check ROS_DOMAIN_ID, the network interface and CYCLONEDDS_URI, and that "
                "the nodes run; ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST hides other hosts)"
            )
        raise ExternalToolError(
            f"{where}: {session.ros_participants} ROS 2 participant(s) with "
            f"{session.endpoints} endpoint(s), but no node names could be read: their "
            "ros_discovery_info was not received or did not decode"
            + (layout or " (see docs/ros2.md)")
        )

    def _notes(self, session: Ros2Discovery) -> None:
        """Say what the first read had to leave out."""
        if self.on_note is None:
            return
        where = self._where
        if session.undecodable:
            self.on_note(
                f"rosreconf: warning: {len(session.undecodable)} ROS 2 participant(s) on {where} "
                "sent ros_discovery_info that could not be decoded: their nodes are not shown"
                + ("" if self.distro is None else f" (is --distro {self.distro} right?)")
            )
        if session.forged:
            self.on_note(
                f"rosreconf: warning: {session.forged} ros_discovery_info sample(s) on {where} "
                "named another participant's GID and were ignored (a participant announces only "
                "its own nodes)"
            )

    def restarted(self) -> tuple[str, dict[str, Any]] | None:
        """Return None: a ROS 2 graph has no master to restart."""
        return None

    def participants(self) -> dict[bytes, tuple[str, ...]]:
        """Return each alive participant's GUID -> its nodes (the last read).

        One participant is one process: what finding a node's process starts from.
        """
        return {} if self._session is None else self._session.participant_nodes

    def actuator(self, acting: Acting) -> Actuator:
        """Return the actuator ``acting`` asks for: each node's own process, or ``ros2 launch``."""
        if acting.options.apply and not acting.options.ros2.launch:
            return Ros2Actuator(acting, self.participants)
        return Ros2Launch(Ros2LaunchPort(), acting, participants=self.participants)

    def close(self) -> None:
        """Leave the DDS domain."""
        if self._session is not None:
            self._session.close()
            self._session = None
            self._states = StateReader()
