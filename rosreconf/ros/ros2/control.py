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

With ``standby``, the managed alternatives of the schema's roles are started and configured
in advance (they show in the graph as parked, not as extra nodes), so a failover is one
``activate``. A node process rosreconf started that exits is known dead at once: ``exited``
says so, and ``visible`` hides its node from the live graph until DDS notices (a lease).
Every step is an event handed to ``say``; nothing here prints.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.bringup import Bringup, exit_news
from rosreconf.ros.ros2.byhand import ByHand
from rosreconf.ros.ros2.lifecycle import OUT_OF_SERVICE, TIMEOUT, LifecycleAgent
from rosreconf.ros.ros2.nodes import NodeProcesses, OwnNode
from rosreconf.ros.ros2.outside import OutsideNodes
from rosreconf.ros.ros2.standby import Standbys
from rosreconf.ros.ros2.transitions import Transitions

Say = Callable[..., None]
"""Receives one event: its kind, its message, and its data as keyword arguments."""


@dataclass
class Ros2Control:
    """Start, stop and switch one watcher's ROS 2 nodes (see the module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        env: the environment nodes run in (ROS_DOMAIN_ID set).
        directory: where node output, the lease profile and the agent's log go.
        say: receives every event.
        stand_ins: run rclpy stand-ins instead of the components' executables.
        standby: start and configure the managed alternatives in advance.
        timeout: seconds each lifecycle transition may take.
        stop_outside: stop a replaced outside node's process (``byhand``).
        parked: live names of managed nodes rosreconf holds out of service.
        dead: live names of nodes whose process rosreconf saw exit.
        newly_dead: those of ``dead`` not yet taken by the actuator's ``exits``: their
            processes' participants are to be left out of later reads.
        states: component -> the lifecycle state last read back.
        by_hand: the outside nodes to stop or restart, or named for a person (``byhand``).
        standbys: the standby nodes (``rosreconf.ros.ros2.standby``).
        bringup: takes managed nodes into service, the started ones as each comes up.
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    env: Mapping[str, str]
    directory: Path
    say: Say
    stand_ins: bool = False
    standby: bool = False
    stop_outside: bool = False
    timeout: float = TIMEOUT
    parked: set[str] = field(default_factory=set)
    dead: set[str] = field(default_factory=set)
    newly_dead: set[str] = field(default_factory=set)
    outside: OutsideNodes | None = field(init=False, default=None)
    states: dict[str, str] = field(init=False)
    read_states: dict[str, str | None] = field(init=False, default_factory=dict)
    by_hand: ByHand = field(init=False)
    standbys: Standbys = field(init=False)
    nodes: NodeProcesses = field(init=False)
    lifecycle: Transitions = field(init=False)
    bringup: Bringup = field(init=False)

    def __post_init__(self) -> None:
        self.nodes = NodeProcesses(self.env, self.directory, stand_ins=self.stand_ins)
        domain = self.env.get("ROS_DOMAIN_ID", "0")  # the nodes' domain: their ports prove pids
        if domain.isdigit():
            self.outside = OutsideNodes(int(domain), self.say, prove=self.stop_outside)
        self.lifecycle = Transitions(self.env, self.directory, self.say, self._node, self.timeout)
        self.by_hand = ByHand(
            self.library, self.schema, self.say, self._node, self.outside, self.stop_outside
        )
        self.states = self.lifecycle.states
        self.standbys = Standbys(
            self.library, self.schema, self.nodes, self.lifecycle, self.parked, self.say
        )
        self.bringup = Bringup(self.nodes, self.lifecycle, self.exited, self.say)

    def _managed(self, component: str) -> bool:
        launch = self.library[component].launch
        return launch is not None and launch.lifecycle

    def _node(self, component: str) -> str:
        return node_live_name(self.library[component])

    def _agent_call(self, call: Callable[[LifecycleAgent], Any]) -> Any:
        return self.lifecycle.call(call)

    def _transitions(
        self, steps: list[tuple[str, str]], appear: float | None = None
    ) -> dict[str, bool]:
        return self.lifecycle.perform(steps, appear)

    def _transition(self, component: str, transition: str) -> bool:
        return self.lifecycle.perform([(component, transition)]).get(component, False)

    def exited(self, only: Collection[str] | None = None) -> list[tuple[OwnNode, int]]:
        """Return each own process (of ``only``'s components) that ended since last asked."""
        gone = self.nodes.exited(only)
        for own, _ in gone:
            self.dead.add(own.node)
            self.newly_dead.add(own.node)
            self.standbys.lost |= own.node in self.parked  # a standby gone: started again
            self.parked.discard(own.node)
            self.states.pop(own.component, None)
        return gone

    def track(self, participants: Mapping[bytes, tuple[str, ...]], current: Configuration) -> None:
        """Watch the processes of ``current``'s nodes that rosreconf did not start."""
        if self.outside is not None:
            # an own node whose process was seen to end is hidden by name until a new
            # participant (a new process) announces it: a team restarting it by hand brings it
            # back (an outside node's ended process hides only its participant: exits)
            self.dead -= {
                n for g, ns in participants.items() if g not in self.outside.seen_at for n in ns
            }
            own = {self._node(c) for c in self.nodes.nodes}
            self.outside.forget(own)
            wanted = {self._node(c) for c in current.components} - own
            self.outside.track(participants, wanted)

    def ended_participants(self) -> set[bytes]:
        """Return the participants of outside processes found exited or hung since last asked:
        DDS announces them until their lease ends, so the graph must leave them out.
        """
        return self.outside.take_ended() if self.outside is not None else set()

    def any_exited(self) -> bool:
        """Tell whether a watched process (own or outside) ended or hung, not yet said."""
        outside = self.outside is not None and self.outside.poll()
        return outside or self.nodes.any_exited()

    def _outside_gone(self, current: Configuration, failed: Collection[str]) -> set[str]:
        """Say which outside nodes' processes exited or hung; return the failed components."""
        if self.outside is None:
            return set()
        comps = {self._node(c): (r, c) for r, c in current.assignment if c}
        now = set()
        for node, how in sorted(self.outside.take().items()):
            # its participant is hidden from the graph (``ended_participants``), not its name
            if node not in comps or comps[node][1] in {*failed, *self.by_hand.restarting}:
                continue  # a person restarting it (rewired) stops it first: not a failure
            role, comp = comps[node]
            why = "its process exited" if how == "exited" else "its process is stopped (hung)"
            self.say(
                "failed",
                f"{comp} ({role}) is gone: {why}, seen by watching it: failed",
                component=comp,
                node=node,
                how=f"process-{how}",
                outside=True,
            )
            now.add(comp)
        return now

    def exits(self, current: Configuration, failed: Collection[str]) -> set[str]:
        """Say which own processes exited; return the components of ``current`` now failed.

        The outside nodes whose processes are watched (``track``) count too.
        """
        now = self._outside_gone(current, failed) | self.bringup.take_failed()
        for news in [*self.nodes.take_helpers(), *self.lifecycle.take_helpers()]:
            self.say("helper", news)
        for own, code in self.exited():
            comp, node = own.component, own.node
            if comp in current.components and comp not in failed:
                role = next(r for r, c in current.assignment if c == comp)
                message, data = exit_news(own, code, role)  # before ready: why, from its log
                self.say("failed", message, **data)
                now.add(comp)
            else:
                self.say(
                    "exited",
                    f"{node} ({comp}, not in service) exited ({code})",
                    component=comp,
                    returncode=code,
                )
        return now

    def left_running(self, check: Conformance) -> bool:
        """Say once what is left when only nodes to stop by hand keep it from conforming."""
        return self.by_hand.left_running(check)

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes whose process rosreconf saw exit.

        The lifecycle states and names read are kept for ``tend``: parked standbys' too.
        """
        self.read_states = {n.name: n.lifecycle_state for n in graph.nodes}
        self.standbys.saw(self.read_states)
        self.bringup.saw(self.read_states)
        if not self.dead & set(graph.names):
            return graph
        return dataclasses.replace(
            graph, nodes=tuple(n for n in graph.nodes if n.name not in self.dead)
        )

    def filtered(self, check: Conformance) -> Conformance:
        """Return ``check`` without the nodes rosreconf holds out of service on purpose."""
        kept = tuple(
            f for f in check.findings if f.code != "extra-node" or f.live_name not in self.parked
        )
        return check if kept == check.findings else dataclasses.replace(check, findings=kept)

    def start(self, configuration: Configuration, components: Collection[str], why: str) -> bool:
        """Put ``components`` into service: start what does not run; configure, activate.

        Returns whether everything asked for was done.
        """
        self._rewire(configuration, components)
        standing = [c for c in components if c in self.nodes.nodes]
        self.standbys.drop(
            self.standbys.hung(standing, self.read_states), "started cold instead of activated"
        )
        fresh = [c for c in components if c not in self.nodes.nodes]
        self.standbys.unready = [c for c in self.standbys.unready if c not in components]
        ok = True
        if fresh:
            try:
                started = self.nodes.start(self.library, self.schema, configuration, fresh)
            except ExternalToolError as exc:
                self._say_problems()
                self.say("launch-error", f"cannot start {', '.join(fresh)}: {exc}")
                return False
            self._say_problems()
            for own in started:
                self.dead.discard(own.node)
            how = "stand-ins of " if self.stand_ins else ""
            pids = {own.component: own.pid for own in started}
            self.say(
                "launch",
                f"started {how}{', '.join(fresh)} ({why}): "
                + ", ".join(f"{c} pid {p}" for c, p in pids.items()),
                components=fresh,
                pids=pids,
                output=str(self.directory),
            )
        managed = [c for c in components if self._managed(c)]
        if managed:
            self._agent_call(lambda agent: agent.watch([self._node(c) for c in managed]))
        # the ready standbys first (one activate each), then what had to start, each as its
        # services appear (``bringup``): a fresh node takes a while, and one may never come
        ok = self.bringup.into_service([c for c in managed if c not in fresh]) and ok
        ok = self.bringup.as_they_come(configuration, [c for c in managed if c in fresh]) and ok
        self.parked -= {self._node(c) for c in managed}
        return ok

    def _say_problems(self) -> None:
        """Say what went wrong in a start that still started (a broken stand-in zygote), once."""
        for problem in self.nodes.take_problems():
            self.say("launch-error", problem)

    def _rewire(self, configuration: Configuration, components: Collection[str]) -> None:
        """Stop the processes of ``components`` that were started wired otherwise.

        ROS names are fixed when a process starts, so a kept consumer whose providers
        changed, or a standby prepared for another failure, is stopped here and started
        again by ``start``, wired for ``configuration``. A node rosreconf did not start
        cannot be restarted: it is named, with the remappings it needs. Each is stopped
        with SIGINT first, so that it says goodbye on DDS at once: a lifecycle request to
        the new process would otherwise go to the old one's lingering endpoints and be lost.
        """
        try:
            stale = self.nodes.miswired(self.library, self.schema, configuration, components)
        except ExternalToolError:
            stale = []  # said by start, which fails the same way
        stopped = self.nodes.stop(stale)
        if stopped:  # the agent's clients matched the old processes: made anew for the new
            self._agent_call(lambda agent: agent.forget([own.node for own in stopped]))
        for own in stopped:
            self.parked.discard(own.node)
            self.states.pop(own.component, None)
            self.say(
                "stop",
                f"stopped {own.component} to restart it wired for the new "
                f"configuration (pid {own.pid})",
                component=own.component,
                how="rewire",
            )

    def retire(
        self, leaving: list[tuple[str, str, str, bool]], failed: Collection[str] = ()
    ) -> None:
        """Take components out of service, each the way its kind allows (module docstring).

        ``leaving`` holds (component, role, replacement, alive in the graph). Own processes
        are stopped together, so their grace periods overlap. A ``failed`` one whose process
        is still there (hung) is stopped too, never driven through lifecycle transitions it
        cannot answer: a hung process is not left behind.
        """
        processes, managed, outside = [], [], []
        for component, role, replacement, alive in leaving:
            own = component in self.nodes.nodes
            if self._managed(component) and (own or alive) and component not in failed:
                managed.append((component, role, replacement))
            elif own:
                processes.append((component, role, replacement))
            else:
                outside.append((component, role, replacement, alive))
        self.by_hand.retire(outside)  # their processes stopped together, graces overlapping
        # With standby, an inactive node is a ready standby: deactivate is enough.
        steps = OUT_OF_SERVICE[:1] if self.standby else OUT_OF_SERVICE
        out = {c: True for c, _, _ in managed}
        for transition in steps:
            todo = [(c, transition) for c, _, _ in managed if out[c]]
            out.update(self._transitions(todo))
        for component, role, replacement in managed:
            self.parked.add(self._node(component))
            self.say(
                "stop",
                f"took {component} ({role}) out of service: replaced by {replacement}",
                component=component,
                how="lifecycle",
            )
        stopped = {n.component: n for n in self.nodes.stop([c for c, _, _ in processes])}
        for component, role, replacement in processes:
            ended = stopped[component]
            code = ended.program.process.returncode
            self.say(
                "stop",
                f"stopped {component} ({role}): replaced by {replacement} "
                f"(pid {ended.pid}, exit {code})",
                component=component,
                how="process",
                returncode=code,
            )

    def reactivate(self, component: str, state: str) -> bool:
        """Bring a managed node of the configuration back to ``active``; True when it holds.

        ``state`` is the one the live graph shows. A node rosreconf did not start is driven
        the same way (lifecycle services answer whoever calls them). Configure first when it
        is ``unconfigured``; a node ``finalized`` cannot come back.
        """
        if state == "finalized":
            return False
        steps = ["configure", "activate"] if state == "unconfigured" else ["activate"]
        return all(self._transition(component, t) for t in steps)

    def owns(self, component: str) -> bool:
        """Tell whether the node of ``component`` runs in a process rosreconf started."""
        return component in self.nodes.nodes

    def restart_by_hand(self, component: str, role: str, configuration: Configuration) -> None:
        """Name a node rosreconf did not start that must restart to be rewired, and how."""
        self.by_hand.restart(component, role, configuration)

    def prepare_standby(self, configuration: Configuration, failed: Collection[str]) -> None:
        """Start managed alternatives wired for the configuration each would join (standby)."""
        if self.standby:
            self.standbys.prepare(configuration, failed)

    def tend(self) -> None:
        """Replace hung standbys; configure those whose services have come up (no waiting)."""
        if self.standby:
            self.standbys.replace_hung(self.read_states)
        self.standbys.tend()

    def close(self) -> list[str]:
        """Stop every process started here and the lifecycle agent; return the components."""
        stopped = [own.component for own in self.nodes.close()]
        self.lifecycle.close()
        if self.outside is not None:
            self.outside.close()
        return stopped
