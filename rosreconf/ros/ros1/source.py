"""A ROS 1 system as a ``LiveSource``: read from its master, acted on with roslaunch."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosreconf.procs import Background
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
from rosreconf.ros.ros1.standins import start_roslaunch, write_standin_package


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
        self, launch: Path, env: Mapping[str, str], stand_ins: Path | None
    ) -> Background | None:
        """Start ``roslaunch --wait`` on the file (the stand-in package made in ``stand_ins``)."""
        package = None if stand_ins is None else write_standin_package(stand_ins / "pkg")
        return start_roslaunch(launch, env, package_path=package)

    def launch_command(self, launch: Path) -> list[str]:
        """Return the roslaunch command line."""
        return ["roslaunch", "--wait", str(launch)]

    def actuator(self, acting: Acting) -> Actuator:
        """Return roslaunch's actuator (nodes stopped through their API's ``shutdown``)."""
        return LaunchActuator(self, acting)

    def close(self) -> None:
        """Hold nothing: each read is its own XML-RPC calls."""
