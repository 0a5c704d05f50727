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
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.procs import Background, start_program
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.discovery import Ros2Discovery, check_domain, gid_sizes
from rosreconf.ros.ros2.graph import graph_uri
from rosreconf.ros.ros2.lifecycle_state import with_states
from rosreconf.ros.rosmaster import (
    DEFAULT_MAX_BYTES,
    DEFAULT_TIMEOUT,
    master_identity,
    purge_dead,
    read_live,
    read_live_graph,
    shutdown_node,
)
from rosreconf.ros.standins import start_roslaunch


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
        """Return the live graph now."""
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


@dataclass
class Ros2Source:
    """A ROS 2 system, read from DDS discovery on one domain (a session kept open)."""

    domain: int
    distro: str | None = None
    ros_version: RosVersion = RosVersion.ROS2
    _session: Ros2Discovery | None = field(default=None, repr=False)

    @property
    def uri(self) -> str:
        """Return ``ros2://domain/<id>``."""
        return graph_uri(self.domain)

    def read(self) -> LiveGraph:
        """Return the graph discovery shows now (the first read waits for it to settle)."""
        if self._session is None:
            self._session = Ros2Discovery(self.domain, self.distro)
        return self._session.read()

    def read_checked(self, on_note: Callable[[str], None] | None = None) -> LiveGraph:
        """Return the graph with managed nodes' states; refuse to call nothing a graph.

        Raises:
            ExternalToolError: no ROS 2 participant answered on the domain, or some did but
                no node name could be read (a wrong ``--distro``, a broken writer), or a
                participant's newest node list never arrived (``stale``: a partial answer).
        """
        graph = self.read()
        session = self._session
        assert session is not None
        where = f"ROS 2 domain {self.domain}"
        if not graph.nodes:
            layout = "" if self.distro is None else f" (--distro {self.distro} reads that "
            if layout:
                sizes = "/".join(str(s) for s in gid_sizes(self.distro))
                layout += f"distribution's {sizes}-byte Gid layout: try without --distro)"
            if session.ros_participants == 0 and session.endpoints == 0:
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
        if session.stale:
            raise ExternalToolError(
                f"{where}: {len(session.stale)} ROS 2 participant(s) announce endpoints that "
                "no node of their ros_discovery_info names, still after the read's wait: their "
                "newest ros_discovery_info was not received or did not decode, so their node "
                "list would be out of date (run again; see docs/ros2.md)"
            )
        if on_note is not None and session.undecodable:
            on_note(
                f"rosreconf: warning: {len(session.undecodable)} ROS 2 participant(s) on {where} "
                "sent ros_discovery_info that could not be decoded: their nodes are not shown"
                + ("" if self.distro is None else f" (is --distro {self.distro} right?)")
            )
        if on_note is not None and session.forged:
            on_note(
                f"rosreconf: warning: {session.forged} ros_discovery_info sample(s) on {where} "
                "named another participant's GID and were ignored (a participant announces only "
                "its own nodes)"
            )
        return with_states(session, graph)

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
    try:
        if isinstance(source, Ros2Source):
            return source.read_checked(on_note)
        return source.read()
    finally:
        source.close()
