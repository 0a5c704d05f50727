"""The watcher's ROS 2 actuator for ``--ros2-launch``: ``ros2 launch``, transitions listed.

``Ros2Launch`` runs ``ros2 launch`` on launch files as ROS 1 runs roslaunch, and lists the
lifecycle transitions a swap needs for a person to run: ROS 2 has no remote kill
(ros2/ros2cli#535). With ``--apply`` alone, rosreconf starts each node's process itself
instead (``rosreconf.ros.ros2.actuator``).
"""

from __future__ import annotations

import shutil
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.model import Configuration
from rosreconf.model.wiring import node_live_name
from rosreconf.procs import Background, start_program
from rosreconf.ros.launcher import LaunchActuator
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.replanning import Change
from rosreconf.ros.ros2.onename import OneName


@dataclass(frozen=True)
class Ros2LaunchPort:
    """``ros2 launch`` as the ``launcher.LaunchPort`` of ROS 2, where a ``ros2`` command exists."""

    ros_version: RosVersion = RosVersion.ROS2

    def start(
        self, launch: Path, env: Mapping[str, str], stand_ins: Path | None
    ) -> Background | None:
        """Start ``ros2 launch FILE`` if a ``ros2`` command exists here, else None."""
        if shutil.which("ros2", path=env.get("PATH")) is None:
            return None
        return start_program(self.command(launch), log=launch.with_suffix(".log"), env=env)

    def command(self, launch: Path) -> list[str]:
        """Return the ``ros2 launch`` command line."""
        return ["ros2", "launch", str(launch)]


@dataclass
class Ros2Launch(LaunchActuator):
    """Start ROS 2 nodes with ``ros2 launch``; list each swap's lifecycle transitions.

    A newcomer whose node name a live node still has is not launched beside it (``onename``):
    it waits until a person has ended that node's process, as the transitions listed say.
    ``participants`` finds that node (``Ros2Source.participants``).
    """

    participants: Callable[[], Mapping[bytes, tuple[str, ...]]] = dict
    names: OneName = field(init=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        a = self.acting
        self.names = OneName(a.library, None, self.participants, lambda: None, a.say)

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Launch those of ``components`` whose node name is free; the others wait."""
        if not self.acting.options.apply:  # only says what would run
            return super().start(current, components, why)
        free = self.names.admit(components, current.components, ())
        return super().start(current, free, why) if free else not components

    def exits(self, current: Configuration, failed: Collection[str], *, tend: bool) -> set[str]:
        """Read the launch processes; while confirming, launch the newcomers whose node name
        is free now (a poll starts them as missing components, and confirms).
        """
        now = super().exits(current, failed, tend=tend)
        due = [] if tend else self.names.due(current.components)  # a poll: missing ones
        if due:
            self.start(current, due, "its node name is free now")
        return now

    def replace(
        self,
        changes: list[Change],
        new: Configuration,
        failed: Collection[str],
        graph: Callable[[bool], LiveGraph],
    ) -> bool:
        """List the transitions swapping managed nodes, then launch the new components."""
        for role, old_comp, new_comp in changes:
            self.listed_transitions(old_comp, new_comp, role)
        return super().replace(changes, new, failed, graph)

    def listed_transitions(self, old_comp: str, new_comp: str, role: str) -> None:
        """Say the lifecycle transitions swapping managed nodes, for a person to run."""
        library = self.acting.library
        steps: list[str] = []
        for comp, stop in ((old_comp, True), (new_comp, False)):
            if not comp:  # an optional role left empty
                continue
            launch = library[comp].launch
            if launch is not None and launch.lifecycle:
                steps += lifecycle_steps(node_live_name(library[comp]), stop=stop)
        if steps:
            self.acting.say(
                "lifecycle",
                f"{role}: lifecycle transitions {old_comp} -> {new_comp}: {'; '.join(steps)}",
                role=role,
                transitions=steps,
            )


def lifecycle_steps(node: str, *, stop: bool) -> list[str]:
    """Return the lifecycle transitions that take managed node ``node`` out of or into service.

    Out: deactivate (active -> inactive), cleanup (inactive -> unconfigured); in: configure
    (unconfigured -> inactive), activate (inactive -> active). Each is a call of the node's
    ``change_state`` service (``lifecycle_msgs/srv/ChangeState``), what
    ``ros2 lifecycle set NODE TRANSITION`` does.
    """
    transitions = ("deactivate", "cleanup") if stop else ("configure", "activate")
    return [f"ros2 lifecycle set {node} {t}" for t in transitions]
