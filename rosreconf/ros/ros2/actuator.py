"""Act on a live ROS 2 system for ``rosreconf watch --apply``: start, stop, transitions, standby.

ROS 2 has no master that can stop a node (ros2/ros2cli#535). So the watcher acts only where
it can, and says so where it cannot::

    component to take out of service       what is done
    -------------------------------------  ---------------------------------------------------
    managed (ros.lifecycle: true)          deactivate, cleanup (each confirmed with get_state;
                                           with standby deactivate only: an inactive node is a
                                           ready standby); the node stays ("parked")
    a process rosreconf started            SIGINT, then SIGTERM, then SIGKILL
    any other node                         ``byhand``: its process stopped with
                                           ``--stop-outside``, else named "stop this by hand"

    component to put into service          what is done
    -------------------------------------  ---------------------------------------------------
    not running                            its process started (``rosreconf.ros.ros2.nodes``);
                                           managed: then configure and activate
    managed and in standby (configured)    activate: one service call

New components start before the replaced ones leave (make before break), but a newcomer that
takes a replaced node's name waits until it is gone (break before make: ``onename``). With
``standby``, the managed alternatives of the schema's roles are started and configured in
advance (they show in the graph as parked, not as extra nodes), so a failover is one
``activate``. A node process rosreconf started that exits is known dead at once: ``exits``
says so, and ``visible`` hides its node from the live graph until DDS notices (a lease;
``exits.OwnExits``), as it hides the participants of every process known dead: the source
only reads, the filter is the actuator's.

``Ros2Actuator`` is the one class that implements ``rosreconf.ros.actuator.Actuator`` this
way, as a ros2_control hardware interface implements its one interface: it owns its parts,
and each part owns its state, which the others ask for through its methods (none holds
another's set)::

    part                               what it owns
    ---------------------------------  -------------------------------------------------------------
    ``nodes.NodeProcesses``            the processes rosreconf started
    ``exits.OwnExits``                 those seen to end, left out of the graph until DDS notices
    ``transitions.Transitions``        the lifecycle agent and the states it read back
    ``bringup.Bringup``                nodes on their way into service (rewired, started, activated)
    ``standby.Standbys``               the standbys, and every node held out of service (parked)
    ``supervisor.OutsideSupervisor``   the nodes rosreconf did not start: watched, stopped, named
    ``retrying.Retries``               the timed-out transitions to try again
    ``onename.OneName``                the newcomers waiting for their node name
    ``squatting.Squatting``            who else holds a component's name (it asks the supervisor)

Every step is an event handed to ``say``; nothing here prints.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Collection
from dataclasses import dataclass, field

from rosreconf.model import Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.replanning import Change
from rosreconf.ros.ros2.bringup import Bringup
from rosreconf.ros.ros2.exits import OwnExits
from rosreconf.ros.ros2.nodes import NodeProcesses, OwnNode
from rosreconf.ros.ros2.onename import OneName
from rosreconf.ros.ros2.retrying import Retries
from rosreconf.ros.ros2.shmdebris import diagnose
from rosreconf.ros.ros2.squatting import Squatting
from rosreconf.ros.ros2.standby import Standbys
from rosreconf.ros.ros2.supervisor import OutsideSupervisor
from rosreconf.ros.ros2.transitions import Transitions

Participants = Callable[[], dict[bytes, tuple[str, ...]]]


@dataclass
class Ros2Actuator(Actuator):
    """Start, stop and switch one watcher's ROS 2 nodes, make before break (module docstring).

    Attributes:
        acting: the watcher's options.
        participants: the source's participants -> their nodes, as last read: the nodes
            rosreconf did not start are watched by their processes (``supervisor``). Its
            parts see them without those of processes known dead (``own_exits.alive``).
        launched: the components started (not started again on every poll).
        read_states: node -> the lifecycle state of the graph last read (``visible``).
        nodes, lifecycle, own_exits, bringup, standbys, supervisor, retries, names, squatting:
            its parts (module docstring).
    """

    acting: Acting
    participants: Participants = dict
    launched: set[str] = field(default_factory=set)
    read_states: dict[str, str | None] = field(default_factory=dict)
    nodes: NodeProcesses = field(init=False)
    lifecycle: Transitions = field(init=False)
    own_exits: OwnExits = field(init=False)
    bringup: Bringup = field(init=False)
    standbys: Standbys = field(init=False)
    supervisor: OutsideSupervisor = field(init=False)
    retries: Retries = field(init=False)
    names: OneName = field(init=False)
    squatting: Squatting = field(init=False)

    def __post_init__(self) -> None:
        a = self.acting
        self.nodes = NodeProcesses(a.env, a.directory, stand_ins=a.options.stand_ins)
        self.supervisor = OutsideSupervisor(
            a.library, a.schema, a.env, a.say, stop_outside=a.options.ros2.stop_outside
        )
        self.lifecycle = Transitions(a.env, a.directory, a.say, self._node)
        forget = self.lifecycle.forget
        self.own_exits = exits = OwnExits(self.nodes, self.participants, forget, a.say)
        self.nodes.stopping = self.own_exits.stopping
        self.standbys = Standbys(a.library, a.schema, self.nodes, self.lifecycle, a.say)
        self.bringup = Bringup(
            a.library,
            a.schema,
            self.nodes,
            self.lifecycle,
            self.standbys,
            self._ended,
            self.own_exits.started,
            a.say,
        )
        self.retries = Retries(a.library, self.lifecycle, a.say)
        self.names = OneName(
            a.library, self.nodes, exits.alive, lambda: self.supervisor.outside, a.say
        )
        self.squatting = Squatting(self.nodes, self.supervisor, exits.alive, exits.hide)

    def _node(self, component: str) -> str:
        return node_live_name(self.acting.library[component])

    def _managed(self, component: str) -> bool:
        launch = self.acting.library[component].launch
        return launch is not None and launch.lifecycle

    def _ended(self, only: Collection[str] | None = None) -> list[tuple[OwnNode, int]]:
        """Return each own process (of ``only``'s components) that ended since last asked."""
        gone = self.own_exits.ended(only)
        for own, _ in gone:
            self.standbys.ended(own.node)  # a standby gone: started again
        return gone

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
            self.bringup.start(current, free, why, self.read_states)
        return bool(free) or not components

    def retask(self, schema: InteroperabilitySchema) -> None:
        """Wire, prepare and name what starts for ``schema`` from now on (a task switch)."""
        self.acting = dataclasses.replace(self.acting, schema=schema)
        for part in (self.supervisor, self.supervisor.by_hand, self.standbys, self.bringup):
            part.schema = schema

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
        by_hand = {c: r for c, r in restarts.items() if c not in self.nodes.nodes}
        fresh = [b for _, _, b in changes if b and b not in by_hand]
        leaving = {a for _, a, _ in changes if a and a not in restarts}
        # a replaced component whose node name a newcomer takes must be gone first, never
        # parked: its process is stopped (or named for a person), and the newcomer waits
        taken = {self.names.node_of(b) for b in fresh}
        going = {a for a in leaving if self.names.node_of(a) in taken}
        started = self._start(new, fresh, "new in the configuration", leaving)
        self._retire(
            [
                (a, r, b, a not in failed and self._node(a) in alive)
                for r, a, b in changes
                if a and a not in restarts  # empty role: none; failed: its process, if left
            ],
            {*failed, *going},
        )
        for comp, role in by_hand.items():
            self.supervisor.restart_by_hand(comp, role, new)
        admitted = self._admit_waiting(new)  # their names are free once the replaced are gone
        return started or admitted or bool(self.names.waiting)

    def _retire(self, leaving: list[tuple[str, str, str, bool]], failed: Collection[str]) -> None:
        """Take components out of service, each the way its kind allows (module docstring).

        ``leaving`` holds (component, role, replacement, alive in the graph). Own processes
        are stopped together, so their grace periods overlap. A ``failed`` one whose process
        is still there (hung) is stopped too, never driven through lifecycle transitions it
        cannot answer: a hung process is not left behind.
        """
        say = self.acting.say
        processes, managed, outside = [], [], []
        for component, role, replacement, alive in leaving:
            own = component in self.nodes.nodes
            if self._managed(component) and (own or alive) and component not in failed:
                managed.append((component, role, replacement))
            elif own:
                processes.append((component, role, replacement))
            else:
                outside.append((component, role, replacement, alive))
        self.supervisor.retire(outside)  # their processes stopped together, graces overlapping
        self.standbys.retire(managed, standby=self.acting.options.ros2.standby)  # parked: they stay
        stopped = {n.component: n for n in self.nodes.stop([c for c, _, _ in processes])}
        for component, role, replacement in processes:
            ended = stopped[component]
            code = ended.program.process.returncode
            say(
                "stop",
                f"stopped {component} ({role}): replaced by {replacement} "
                f"(pid {ended.pid}, exit {code})",
                component=component,
                how="process",
                returncode=code,
            )

    def not_running(self, missing: list[str]) -> tuple[list[str], str]:
        """Return the started ones of ``missing``; point at their output, or at what they wait on.

        A process stuck on a broken Fast DDS shared-memory port never shows up; the file is
        named, with what to do (``shmdebris``).
        """
        where = self.acting.directory
        stuck = [c for c in missing if c in self.launched]
        own = self.nodes.nodes
        debris = diagnose((c, own[c].pid) for c in stuck if c in own)
        why = debris or f"launched but not running (see the launch output in {where})"
        return stuck, why

    def exits(self, current: Configuration, failed: Collection[str], *, tend: bool) -> set[str]:
        """Say which own processes exited; return the components of ``current`` now failed.

        The nodes of ``current`` rosreconf did not start are watched by their processes from
        the last read on, and count too (``supervisor``). With ``tend``, standby nodes that
        came up are configured. A transition that timed out is tried again (``retrying``),
        while confirming too. Without ``tend`` (while a change is confirmed), a newcomer held
        back for its node name is started once the name is free; on a poll it is started as
        a missing component is, which the watcher then confirms.
        """
        participants = self.own_exits.alive()
        own = {self._node(c) for c in self.nodes.nodes}
        wanted = {self._node(c) for c in current.components}
        # an own node whose process was seen to end is hidden by name until a new participant
        # (a new process) announces it: a team restarting it by hand brings it back (an
        # outside node's ended process hides only its participant: ``take_ended``)
        self.own_exits.revived(self.supervisor.track(participants, own, wanted))
        now = self.supervisor.gone(current, failed) | self.bringup.take_failed()
        for news in [*self.nodes.take_helpers(), *self.lifecycle.take_helpers()]:
            self.acting.say("helper", news)
        now |= self.own_exits.said(current, failed, self._ended())
        # their participants linger until their lease ends (those that died in a start too)
        ended = self.own_exits.take_newly(participants)
        ended |= self.supervisor.take_ended()  # outside processes: exactly theirs
        ended |= self.lifecycle.ghosts(participants)  # a dead agent's
        self.own_exits.hide(ended)
        if not now:  # a failure's repair first: neither retries nor standby upkeep delay it
            self.retries.tend(current, self.standbys.held())
        if not now and not tend:  # while confirming; a poll starts them as missing ones
            self._admit_waiting(current)
        if tend and not now:
            if self.acting.options.ros2.standby:
                self.standbys.replace_hung(self.read_states)
            self.standbys.tend()  # configure those whose services have come up (no waiting)
        return now

    def exited(self) -> bool:
        """Return whether a watched node process (own or outside) ended or hung, not yet said."""
        return self.supervisor.poll() or self.nodes.any_exited()

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes of processes known dead (``exits.OwnExits``).

        The lifecycle states and names read, those of dead participants left out, are kept
        for ``exits``: parked standbys' too, and what a timed-out transition is judged on
        (``retrying``).
        """
        graph = self.own_exits.unhidden(graph)
        self.read_states = {n.name: n.lifecycle_state for n in graph.nodes}
        self.standbys.saw(self.read_states)
        self.bringup.saw(self.read_states)
        self.retries.saw(self.read_states)
        return self.own_exits.visible(graph)

    def filtered(self, check: Conformance) -> Conformance:
        """Return ``check`` without the nodes rosreconf holds out of service on purpose."""
        kept = tuple(
            f
            for f in check.findings
            if f.code != "extra-node" or not self.standbys.is_parked(f.live_name)
        )
        return check if kept == check.findings else dataclasses.replace(check, findings=kept)

    def left_running(self, check: Conformance) -> bool:
        """Say once what is left for a person to stop; True when only that is left."""
        return self.supervisor.left_running(check)

    def settled(self, current: Configuration, failed: Collection[str]) -> None:
        """Forget what a person was asked to stop; prepare the standbys for ``current``.

        After the confirmation, not before it: choosing each standby's wiring replans.
        """
        self.supervisor.settled()
        if self.acting.options.ros2.standby:
            self.standbys.prepare(current, failed)

    def started(self) -> frozenset[str]:
        """Return the components whose node process rosreconf started and that still runs."""
        return frozenset(self.nodes.nodes)

    def theirs(self) -> frozenset[str]:
        """Return the components whose node was found in a process rosreconf did not start."""
        return self.supervisor.theirs()

    def awaited(self) -> frozenset[str]:
        """Return the components named "restart this by hand", until the system conforms."""
        return self.supervisor.awaited()

    def restart(self, *, stop: bool) -> None:
        """Forget what was started (a ROS 2 graph has no master to restart)."""
        self.launched.clear()

    @property
    def reactivate(self) -> Callable[[str, str], bool] | None:
        """Return how a managed node is made ``active`` again (lifecycle transitions)."""
        return self._reactivate

    def _reactivate(self, component: str, state: str) -> bool:
        """Bring a managed node of the configuration back to ``active``; True when it holds.

        ``state`` is the one the live graph shows. A node rosreconf did not start is driven
        the same way (lifecycle services answer whoever calls them). Configure first when it
        is ``unconfigured``; a node ``finalized`` cannot come back.
        """
        if state == "finalized":
            return False
        steps = ["configure", "activate"] if state == "unconfigured" else ["activate"]
        return all(self.lifecycle.perform([(component, t)]).get(component, False) for t in steps)

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
        self.supervisor.restart_by_hand(component, role, configuration)

    def close(self) -> None:
        """Stop every node process started here, the lifecycle agent and the outside watch."""
        stopped = [own.component for own in self.nodes.close()]
        self.lifecycle.close()
        self.supervisor.close()
        if stopped:
            self.acting.say(
                "stopped",
                f"stopped the {len(stopped)} node process(es) started: {', '.join(stopped)}",
                components=stopped,
            )
