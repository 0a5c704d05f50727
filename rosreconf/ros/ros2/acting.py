"""The watcher's two ROS 2 actuators: each node's own process, or ``ros2 launch``.

``Ros2Actuator`` (``watch --ros2 --apply``) acts through ``rosreconf.ros.ros2.control``:
rosreconf starts each node's process, retires managed nodes with lifecycle transitions and
its own processes with signals, makes before it breaks, and names what a person must stop.
``Ros2Launch`` (``--ros2-launch``) runs ``ros2 launch`` on launch files as ROS 1 runs
roslaunch, and lists the lifecycle transitions a swap needs for a person to run: ROS 2 has
no remote kill (ros2/ros2cli#535).
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from dataclasses import dataclass, field

from rosreconf.model import Configuration
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.launcher import LaunchActuator
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.replanning import Change
from rosreconf.ros.ros2.control import Ros2Control
from rosreconf.ros.ros2.fastdds_ids import may_be_of
from rosreconf.ros.ros2.nodes import OwnNode
from rosreconf.ros.ros2.shmdebris import diagnose
from rosreconf.ros.ros2.squatting import Squatting


@dataclass
class Ros2Actuator(Actuator):
    """Start and retire ROS 2 nodes one process at a time (``Ros2Control``), make before break.

    Attributes:
        acting: the watcher's options.
        participants: the source's participants -> their nodes, as last read: the nodes
            rosreconf did not start are watched by their processes (``Ros2Control.track``).
        hide: leaves participants out of the source's later reads: those of processes seen
            to end, so that a node restarted under its name is only its new process.
        control: what ROS 2 lets rosreconf do to each node.
        launched: the components started (not started again on every poll).
    """

    acting: Acting
    participants: Callable[[], dict[bytes, tuple[str, ...]]] = dict
    hide: Callable[[Collection[bytes]], None] = lambda _: None
    control: Ros2Control = field(init=False)
    launched: set[str] = field(default_factory=set)
    squatting: Squatting = field(init=False)

    def __post_init__(self) -> None:
        a = self.acting
        self.control = Ros2Control(
            a.library,
            a.schema,
            a.env,
            a.directory,
            a.say,
            stand_ins=a.stand_ins,
            standby=a.standby,
            stop_outside=a.stop_outside,
        )
        self.control.nodes.stopping = self._hide_stopping
        self.squatting = Squatting(self.control, self.participants, self.hide)

    def _hide_stopping(self, stopping: list[OwnNode]) -> None:
        """Leave out of later reads the participants of processes rosreconf is stopping.

        A process stopped without a DDS goodbye (SIGKILLed, or its goodbye lost) is announced
        until its lease ends, and a node started anew under its name would then be two: the
        dead one's state query, unanswered, read as the new one's "hung" (fresh clone fc177).
        Taken from the last read, before any restart: each participant naming a stopped node
        whose Fast DDS GUID carries that process's pid (another vendor's carries none, and
        its node name is then what tells).
        """
        pids = {own.node: own.pid for own in stopping}
        self.hide(
            {
                g
                for g, nodes in self.participants().items()
                if any(n in pids and may_be_of(g, pids[n]) for n in nodes)
            }
        )

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Start ``components``' processes (managed ones configured and activated); never one
        whose node name a node rosreconf did not start holds (``squatting``)."""
        free = self.squatting.free(components)
        self.launched |= set(free)
        self.control.start(current, free, why)
        return bool(free) or not components

    def replace(
        self,
        changes: list[Change],
        new: Configuration,
        failed: Collection[str],
        graph: Callable[[bool], LiveGraph],
    ) -> bool:
        """Start the new ones first, then retire the replaced; name restarts for a person.

        A failed component's process that is still there (hung) is stopped as well.

        A kept component rewired is restarted if rosreconf started it, else named
        ("restart this by hand"): its remappings are fixed at start.
        """
        alive = {n.name for n in graph(False).nodes}
        restarts = {b: r for r, a, b in changes if a == b}  # kept, to be rewired
        by_hand = {c: r for c, r in restarts.items() if not self.control.owns(c)}
        fresh = [b for _, _, b in changes if b and b not in by_hand]
        started = self.start(new, fresh, "new in the configuration")
        library = self.acting.library
        self.control.retire(
            [
                (a, r, b, a not in failed and node_live_name(library[a]) in alive)
                for r, a, b in changes
                if a and a not in restarts  # empty role: none; failed: its process, if left
            ],
            failed,
        )
        for comp, role in by_hand.items():
            self.control.restart_by_hand(comp, role, new)
        return started

    def not_running(self, missing: list[str]) -> tuple[list[str], str]:
        """Return the started ones of ``missing``; point at their output, or at what they wait on.

        A process stuck on a broken Fast DDS shared-memory port never shows up; the file is
        named, with what to do (``shmdebris``).
        """
        where = self.acting.directory
        stuck = [c for c in missing if c in self.launched]
        own = self.control.nodes.nodes
        debris = diagnose((c, own[c].pid) for c in stuck if c in own)
        why = debris or f"launched but not running (see the launch output in {where})"
        return stuck, why

    def exits(self, current: Configuration, failed: Collection[str], *, tend: bool) -> set[str]:
        """Say which own processes exited; return the components of ``current`` now failed.

        With ``tend``, standby nodes that came up are configured. The nodes of ``current``
        rosreconf did not start are watched by their processes from the last read on.
        """
        participants = self.participants()
        self.control.track(participants, current)
        dead = set(self.control.dead)
        now = self.control.exits(current, failed)
        newly = self.control.dead - dead  # their participants linger until their lease ends
        ended = self.control.ended_participants()  # outside processes: exactly theirs
        self.hide({g for g, nodes in participants.items() if newly & set(nodes)} | ended)
        if tend and not now:  # a failure's repair first: standby upkeep never delays it
            self.control.tend()
        return now

    def exited(self) -> bool:
        """Return whether a watched node process (own or outside) ended or hung, not yet said."""
        return self.control.any_exited()

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes whose process rosreconf saw exit."""
        return self.control.visible(graph)

    def filtered(self, check: Conformance) -> Conformance:
        """Return ``check`` without the nodes parked out of service on purpose."""
        return self.control.filtered(check)

    def left_running(self, check: Conformance) -> bool:
        """Say once what is left for a person to stop; True when only that is left."""
        return self.control.left_running(check)

    def settled(self, current: Configuration, failed: Collection[str]) -> None:
        """Forget what a person was asked to stop; prepare the standbys for ``current``.

        After the confirmation, not before it: choosing each standby's wiring replans.
        """
        self.control.by_hand.settled()
        self.control.prepare_standby(current, failed)

    def started(self) -> frozenset[str]:
        """Return the components whose node process rosreconf started and that still runs."""
        return frozenset(self.control.nodes.nodes)

    def awaited(self) -> frozenset[str]:
        """Return the components named "restart this by hand", until the system conforms."""
        return frozenset(self.control.by_hand.restarting)

    def restart(self, *, stop: bool) -> None:
        """Forget what was started (a ROS 2 graph has no master to restart)."""
        self.launched.clear()

    @property
    def reactivate(self) -> Callable[[str, str], bool] | None:
        """Return how a managed node is made ``active`` again (lifecycle transitions)."""
        return self.control.reactivate

    def incarnations(self, node: str) -> frozenset[str] | None:
        """Return the participants announcing ``node`` now: a new one is a new process."""
        return self.squatting.incarnations(node)

    def squatter(self, component: str, role: str, node: str, beside: bool) -> bool:
        """Name, or stop (``--stop-outside``), a node squatting on ``component``'s name;
        True when its process was stopped."""
        return self.squatting.squatter(component, role, node, beside)

    def await_rewire(self, component: str, role: str, configuration: Configuration) -> None:
        """Name a node rosreconf did not start to restart by hand, with its ``-r`` rules."""
        self.control.restart_by_hand(component, role, configuration)

    def close(self) -> None:
        """Stop every node process started here, and the lifecycle agent."""
        stopped = self.control.close()
        if stopped:
            self.acting.say(
                "stopped",
                f"stopped the {len(stopped)} node process(es) started: {', '.join(stopped)}",
                components=stopped,
            )


@dataclass
class Ros2Launch(LaunchActuator):
    """Start ROS 2 nodes with ``ros2 launch``; list each swap's lifecycle transitions."""

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
