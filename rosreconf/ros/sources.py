"""Where a live graph comes from, and how nodes there are stopped and started.

Every live command reads one ``LiveGraph`` document, whatever the middleware, so that
comparing, importing, and re-planning are shared. What differs is here::

                  ROS 1 (``--master URI``)             ROS 2 (``--ros2 --domain N``)
    ------------  -----------------------------------  ------------------------------------------
    read          master XML-RPC + each node's getPid  DDS discovery + ros_discovery_info
    dead nodes    stay registered: purged like         leave by themselves when their
                  ``rosnode cleanup``                  participant's lease expires
    stop a node   its API's ``shutdown``               no remote kill in ROS 2: managed nodes get
                                                       lifecycle transitions (listed), processes
                                                       rosreconf started are ended by it
    start nodes   ``roslaunch --wait FILE``            ``ros2 launch FILE`` where a ``ros2``
                                                       command exists; otherwise the file is
                                                       written and the command said
"""

from __future__ import annotations

import shutil
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.procs import Background, start_program
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros1.rosmaster import (
    DEFAULT_MAX_BYTES,
    DEFAULT_TIMEOUT,
    master_identity,
    purge_dead,
    read_live,
    read_live_graph,
    shutdown_node,
)
from rosreconf.ros.ros1.standins import start_roslaunch
from rosreconf.ros.ros2.discovery import Ros2Discovery, check_domain, gid_sizes
from rosreconf.ros.ros2.graph import graph_uri
from rosreconf.ros.ros2.lifecycle_state import StateReader, with_states


class LiveSource(Protocol):
    """A running system rosreconf can read, and act on as far as its middleware allows."""

    @property
    def uri(self) -> str:
        """Return where the graph is read (a master URI, or ``ros2://domain/<id>``)."""
        ...

    @property
    def ros_version(self) -> RosVersion:
        """Return which launch files this system runs."""
        ...

    def read(self) -> LiveGraph:
        """Return the live graph now (the one read of every live command, ``watch``'s too).

        Raises:
            ExternalToolError: the graph cannot be read, or only in part (``watch`` stops
                at a first read's, and waits out a later one's).
        """
        ...

    def identity(self) -> tuple[int | None, str | None] | None:
        """Return the master's pid and ``/run_id``, which change when it restarts (None: none)."""
        ...

    def purge(self, graph: LiveGraph, dead: list[str]) -> tuple[str, ...]:
        """Forget dead nodes the middleware keeps listing; return the ones forgotten."""
        ...

    def stop(self, graph: LiveGraph, node: str, reason: str) -> bool:
        """Ask node ``node`` to shut down; return whether that was possible."""
        ...

    def start(
        self, launch: Path, env: Mapping[str, str], package_path: Path | None
    ) -> Background | None:
        """Run ``launch`` as a process rosreconf owns; None when there is no launcher here."""
        ...

    def launch_command(self, launch: Path) -> list[str]:
        """Return the command ``start`` runs for ``launch``."""
        ...

    def close(self) -> None:
        """Release what reading holds (a DDS participant)."""
        ...


@dataclass
class MasterSource:
    """A ROS 1 system, read from its master (each call with a deadline and an answer cap)."""

    master_uri: str
    timeout: float = DEFAULT_TIMEOUT
    max_bytes: int = DEFAULT_MAX_BYTES
    ros_version: RosVersion = RosVersion.ROS1

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

    def purge(self, graph: LiveGraph, dead: list[str]) -> tuple[str, ...]:
        """Unregister dead nodes (SIGKILLed nodes linger in the master)."""
        return purge_dead(
            self.master_uri, graph, only=dead, timeout=self.timeout, max_bytes=self.max_bytes
        )

    def stop(self, graph: LiveGraph, node: str, reason: str) -> bool:
        """Call the node API's ``shutdown`` (what ``rosnode kill`` does)."""
        uri = next((n.uri for n in graph.nodes if n.name == node), None)
        return uri is not None and shutdown_node(uri, reason, timeout=self.timeout)

    def start(
        self, launch: Path, env: Mapping[str, str], package_path: Path | None
    ) -> Background | None:
        """Start ``roslaunch --wait`` on the file."""
        return start_roslaunch(launch, env, package_path=package_path)

    def launch_command(self, launch: Path) -> list[str]:
        """Return the roslaunch command line."""
        return ["roslaunch", "--wait", str(launch)]

    def close(self) -> None:
        """Hold nothing: each read is its own XML-RPC calls."""


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
    """

    domain: int
    distro: str | None = None
    ros_version: RosVersion = RosVersion.ROS2
    empty_ok: bool = False
    on_note: Callable[[str], None] | None = None
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
                no node name could be read (a wrong ``--distro``, a broken writer), or a
                participant's newest node list never arrived (``stale``: a partial answer).
        """
        first = self._session is None
        if self._session is None:
            self._session = Ros2Discovery(self.domain, self.distro)
        session = self._session
        graph = session.read()
        if first:
            self._refuse_empty(graph, session)
        deadline = time.monotonic() + STALE_GRACE
        while session.stale and not first and time.monotonic() < deadline:
            time.sleep(0.02)
            graph = session.read()
        if session.stale:
            raise ExternalToolError(
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

    def identity(self) -> tuple[int | None, str | None] | None:
        """Return None: a ROS 2 graph has no master to restart."""
        return None

    def purge(self, graph: LiveGraph, dead: list[str]) -> tuple[str, ...]:
        """Forget nothing: DDS drops a participant whose lease expired by itself."""
        return ()

    def stop(self, graph: LiveGraph, node: str, reason: str) -> bool:
        """Refuse: ROS 2 has no remote kill (ros2/ros2cli#535); see ``lifecycle_steps``."""
        return False

    def start(
        self, launch: Path, env: Mapping[str, str], package_path: Path | None
    ) -> Background | None:
        """Start ``ros2 launch FILE`` if a ``ros2`` command exists here, else None."""
        if shutil.which("ros2", path=env.get("PATH")) is None:
            return None
        return start_program(self.launch_command(launch), log=launch.with_suffix(".log"), env=env)

    def launch_command(self, launch: Path) -> list[str]:
        """Return the ``ros2 launch`` command line."""
        return ["ros2", "launch", str(launch)]

    def close(self) -> None:
        """Leave the DDS domain."""
        if self._session is not None:
            self._session.close()
            self._session = None
            self._states = StateReader()


def lifecycle_steps(node: str, *, stop: bool) -> list[str]:
    """Return the lifecycle transitions that take managed node ``node`` out of or into service.

    Out: deactivate (active -> inactive), cleanup (inactive -> unconfigured); in: configure
    (unconfigured -> inactive), activate (inactive -> active). Each is a call of the node's
    ``change_state`` service (``lifecycle_msgs/srv/ChangeState``), what
    ``ros2 lifecycle set NODE TRANSITION`` does.
    """
    transitions = ("deactivate", "cleanup") if stop else ("configure", "activate")
    return [f"ros2 lifecycle set {node} {t}" for t in transitions]


def open_source(
    master: str | None,
    ros2: bool,
    domain: int,
    distro: str | None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
) -> MasterSource | Ros2Source:
    """Return the source the options name: ``--master URI`` or ``--ros2 [--domain N]``.

    Raises:
        UsageError: both or neither are given, or ``--distro`` without ``--ros2``.
    """
    if ros2 == (master is not None):
        raise UsageError("give exactly one of --master URI and --ros2 [--domain N]")
    if master is not None:
        if distro is not None:
            raise UsageError("--distro is for --ros2 (ROS 2 over DDS) only")
        return MasterSource(master, timeout, max_bytes)
    check_domain(domain)
    gid_sizes(distro)  # refuse an unknown distribution before joining the domain
    return Ros2Source(domain, distro)


def read_any(
    master: str | None,
    snapshot: Path | None,
    ros2: bool = False,
    domain: int = 0,
    distro: str | None = None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    on_note: Callable[[str], None] | None = None,
) -> LiveGraph:
    """Read the live graph from exactly one of a master, ROS 2 discovery and a snapshot.

    A ROS 2 read also asks every managed node its lifecycle state, and says through
    ``on_note`` what it had to leave out (undecodable or forged discovery samples).

    Raises:
        UsageError: not exactly one is given, or the snapshot cannot be read.
        ExternalToolError: the master does not answer, DDS cannot be used, or nothing ROS 2
            was seen on the domain.
    """
    if sum((master is not None, snapshot is not None, ros2)) != 1:
        raise UsageError("give exactly one of --master URI, --ros2 and --snapshot FILE")
    if snapshot is not None:
        return read_live(None, snapshot)
    source = open_source(master, ros2, domain, distro, timeout=timeout, max_bytes=max_bytes)
    if isinstance(source, Ros2Source):
        source.on_note = on_note
    try:
        return source.read()
    finally:
        source.close()
