"""The watcher's two ROS 2 actuators: each node's own process, or ``ros2 launch``.

``Ros2Actuator`` (``watch --ros2 --apply``) acts through ``rosreconf.ros.ros2.control``:
rosreconf starts each node's process, retires managed nodes with lifecycle transitions and
its own processes with signals, makes before it breaks (but breaks first where a newcomer
takes a node name still live: ``onename``), and names what a person must stop.
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
from rosreconf.ros.ros2.onename import OneName
from rosreconf.ros.ros2.retrying import Retries
from rosreconf.ros.ros2.shmdebris import diagnose
from rosreconf.ros.ros2.squatting import Squatting


@dataclass
class Ros2Actuator(Actuator):
    """Start and retire ROS 2 nodes one process at a time (``Ros2Control``), make before break.

    Break before make where a newcomer takes a replaced node's name (``onename``).

    Attributes:
        acting: the watcher's options.
        participants: the source's participants -> their nodes, as last read: the nodes
            rosreconf did not start are watched by their processes (``Ros2Control.track``).
        hide: leaves participants out of the source's later reads: those of processes seen
            to end, so that a node restarted under its name is only its new process.
        control: what ROS 2 lets rosreconf do to each node.
        launched: the components started (not started again on every poll).
        names: the newcomers waiting for their node name to be free (``onename``).
    """

    acting: Acting
    participants: Callable[[], dict[bytes, tuple[str, ...]]] = dict
    hide: Callable[[Collection[bytes]], None] = lambda _: None
    control: Ros2Control = field(init=False)
    launched: set[str] = field(default_factory=set)
    retries: Retries = field(init=False)
    names: OneName = field(init=False)
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
        self.retries = Retries(a.library, self.control.lifecycle, a.say)
        self.names = OneName(
            a.library, self.control.nodes, self.participants, lambda: self.control.outside, a.say
        )
        self.squatting = Squatting(self.control, self.participants, self.hide)

    def _hide_stopping(self, stopping: list[OwnNode]) -> None:
        """Leave out of later reads the participants of processes rosreconf is stopping.

        A process stopped without a DDS goodbye (SIGKILLed, or its goodbye lost) is announced
        until its lease ends, and a node started anew under its name would then be two: the
        dead one's state query, unanswered, read as the new one's "hung".
        Taken from the last read, before any restart: each participant naming a stopped node
        whose Fast DDS GUID carries that process's pid (another vendor's carries none, and
        its node name is then what tells). The lifecycle state read back from a stopped
        process is forgotten too: a process started anew for the component is unconfigured,
        and must be configured and activated (a replaced managed node released after its
        hold was started and left unconfigured until the lifecycle check after ``--settle``).
        """
        for own in stopping:
            self.control.states.pop(own.component, None)
        pids = {own.node: own.pid for own in stopping}
        self.hide(
            {
                g
                for g, nodes in self.participants().items()
                if any(n in pids and may_be_of(g, pids[n]) for n in nodes)
            }
        )

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Start ``components``' processes (managed ones configured and activated).

        One whose node name another process holds waits until it is free (``onename``).
        """
        return self._start(current, components, why, ())

    def _start(
        self,
        current: Configuration,
        components: Collection[str],
        why: str,
        leaving: Collection[str],
    ) -> bool:
        """Start those of ``components`` whose name is free; ``leaving`` are retired next."""
        free = self.names.admit(components, current.components, leaving)
        self.launched |= set(free)
        if free:
            self.control.start(current, free, why)
        return bool(free) or not components

    def _admit_waiting(self, current: Configuration) -> bool:
        """Start the newcomers whose node name has come free since they were held back."""
        due = self.names.due(current.components)
        return bool(due) and self._start(current, due, "its node name is free now", ())

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
        leaving = {a for _, a, _ in changes if a and a not in restarts}
        # a replaced component whose node name a newcomer takes must be gone first, never
        # parked: its process is stopped (or named for a person), and the newcomer waits
        taken = {self.names.node_of(b) for b in fresh}
        going = {a for a in leaving if self.names.node_of(a) in taken}
        started = self._start(new, fresh, "new in the configuration", leaving)
        library = self.acting.library
        self.control.retire(
            [
                (a, r, b, a not in failed and node_live_name(library[a]) in alive)
                for r, a, b in changes
                if a and a not in restarts  # empty role: none; failed: its process, if left
            ],
            {*failed, *going},
        )
        for comp, role in by_hand.items():
            self.control.restart_by_hand(comp, role, new)
        admitted = self._admit_waiting(new)  # their names are free once the replaced are gone
        return started or admitted or bool(self.names.waiting)

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
        rosreconf did not start are watched by their processes from the last read on. A
        transition that timed out is tried again (``retrying``), while confirming too.
        Without ``tend`` (while a change is confirmed), a newcomer held back for its node
        name is started once the name is free; on a poll it is started as a missing
        component is, which the watcher then confirms.
        """
        participants = self.participants()
        self.control.track(participants, current)
        now = self.control.exits(current, failed)
        # their participants linger until their lease ends (those that died in a start too)
        newly, self.control.newly_dead = self.control.newly_dead, set()
        ended = self.control.ended_participants()  # outside processes: exactly theirs
        ended |= self.control.lifecycle.ghosts(participants)  # a dead agent's
        self.hide({g for g, nodes in participants.items() if newly & set(nodes)} | ended)
        if not now:  # a failure's repair first: neither retries nor standby upkeep delay it
            self.retries.tend(current, self.control.parked)
        if not now and not tend:  # while confirming; a poll starts them as missing ones
            self._admit_waiting(current)
        if tend and not now:
            self.control.tend()
        return now

    def exited(self) -> bool:
        """Return whether a watched node process (own or outside) ended or hung, not yet said."""
        return self.control.any_exited()

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes whose process rosreconf saw exit."""
        shown = self.control.visible(graph)
        self.retries.saw(self.control.read_states)  # what a timed-out transition is judged on
        return shown

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

    def theirs(self) -> frozenset[str]:
        """Return the components whose node was found in a process rosreconf did not start."""
        outside = self.control.outside
        if outside is None or not outside.theirs:
            return frozenset()
        library = self.acting.library
        return frozenset(c.name for c in library.components if node_live_name(c) in outside.theirs)

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
        True when its process was stopped.
        """
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
    """Start ROS 2 nodes with ``ros2 launch``; list each swap's lifecycle transitions.

    A newcomer whose node name a live node still has is not launched beside it (``onename``):
    it waits until a person has ended that node's process, as the transitions listed say.
    """

    names: OneName = field(init=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        participants = getattr(self.source, "participants", dict)
        self.names = OneName(self.acting.library, None, participants, lambda: None, self.acting.say)

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Launch those of ``components`` whose node name is free; the others wait."""
        if not self.acting.apply:  # only says what would run
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
