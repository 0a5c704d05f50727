"""Act on a live ROS 2 system for ``rosreconf watch --apply``: start, stop, transitions, standby.

ROS 2 has no master that can stop a node (ros2/ros2cli#535). So the watcher acts only where
it can, and says so where it cannot::

    component to take out of service       what is done
    -------------------------------------  ---------------------------------------------------
    managed (ros.lifecycle: true)          deactivate, cleanup (each confirmed with get_state;
                                           with standby deactivate only: an inactive node is a
                                           ready standby); the node stays ("parked")
    a process rosreconf started            SIGINT, then SIGTERM, then SIGKILL
    any other node                         named once, as "stop this by hand"

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
from rosreconf.ros.conformance import Conformance, node_live_name
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.lifecycle import APPEAR, OUT_OF_SERVICE, TIMEOUT, LifecycleAgent, Outcome
from rosreconf.ros.ros2.nodes import NodeProcesses

STANDBY_TRIES = 5
"""Configure attempts for one standby node before it is left unconfigured (and said so)."""

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
        parked: live names of managed nodes rosreconf holds out of service.
        by_hand: live node name -> component, for nodes that must be stopped by hand.
        dead: live names of nodes whose process rosreconf saw exit.
        states: component -> the lifecycle state last read back.
        left: the nodes last said to be left for a person to stop.
        unready: standby components started and not yet configured (``tend`` does it).
        tries: standby component -> configure attempts that failed (``STANDBY_TRIES`` at most).
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    env: Mapping[str, str]
    directory: Path
    say: Say
    stand_ins: bool = False
    standby: bool = False
    timeout: float = TIMEOUT
    parked: set[str] = field(default_factory=set)
    by_hand: dict[str, str] = field(default_factory=dict)
    dead: set[str] = field(default_factory=set)
    states: dict[str, str] = field(default_factory=dict)
    left: tuple[str, ...] = ()
    unready: list[str] = field(default_factory=list)
    tries: dict[str, int] = field(default_factory=dict)
    nodes: NodeProcesses = field(init=False)
    _agent: LifecycleAgent | None = None
    _agent_error: str | None = None

    def __post_init__(self) -> None:
        self.nodes = NodeProcesses(self.env, self.directory, stand_ins=self.stand_ins)

    def _managed(self, component: str) -> bool:
        launch = self.library[component].launch
        return launch is not None and launch.lifecycle

    def _node(self, component: str) -> str:
        return node_live_name(self.library[component])

    def agent(self) -> LifecycleAgent:
        """Return the lifecycle agent, started on first use."""
        if self._agent is None:
            if self._agent_error is not None:  # said once; not retried on every call
                raise ExternalToolError(self._agent_error)
            self.directory.mkdir(parents=True, exist_ok=True)
            try:
                self._agent = LifecycleAgent(
                    self.env, self.directory / "lifecycle-agent.log", self.timeout
                )
            except ExternalToolError as exc:
                self._agent_error = str(exc)
                raise
        return self._agent

    def _agent_call(self, call: Callable[[LifecycleAgent], Any]) -> Any:
        """Ask the lifecycle agent something; a failure is said (never raised), None returned."""
        try:
            return call(self.agent())
        except ExternalToolError as exc:
            self.say("lifecycle", f"lifecycle agent: {exc}", ok=False, error=str(exc))
            return None

    def exited(self) -> list[tuple[str, str, int]]:
        """Return (component, node, exit status) of each own process that ended since last asked."""
        gone = []
        for own, code in self.nodes.exited():
            self.dead.add(own.node)
            self.parked.discard(own.node)
            self.states.pop(own.component, None)
            gone.append((own.component, own.node, code))
        return gone

    def exits(self, current: Configuration, failed: Collection[str]) -> set[str]:
        """Say which own processes exited; return the components of ``current`` now failed."""
        now: set[str] = set()
        for comp, node, code in self.exited():
            if comp in current.components and comp not in failed:
                role = next(r for r, c in current.assignment if c == comp)
                self.say(
                    "failed",
                    f"{comp} ({role}) is gone: its process exited ({code}): failed",
                    component=comp, node=node, returncode=code, how="process-exit",
                )  # fmt: skip
                now.add(comp)
            else:
                self.say("exited", f"{node} ({comp}, not in service) exited ({code})",
                         component=comp, returncode=code)  # fmt: skip
        return now

    def left_running(self, check: Conformance) -> bool:
        """Say once what is left when only nodes to stop by hand keep it from conforming."""
        gone = set(self.by_hand) - set(check.live.names)
        for node in gone:  # stopped by a person
            del self.by_hand[node]
        if not check.findings or any(
            f.code != "extra-node" or f.live_name not in self.by_hand for f in check.findings
        ):
            return False
        left = tuple(sorted(f.live_name for f in check.findings))
        if left != self.left:
            self.left = left
            self.say(
                "left-running",
                f"the configuration runs; left to stop by hand: {', '.join(left)} "
                "(conformant is logged once they are gone)",
                nodes=list(left),
            )
        return True

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes whose process rosreconf saw exit."""
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
        fresh = [c for c in components if c not in self.nodes.nodes]
        self.unready = [c for c in self.unready if c not in components]
        ok = True
        if fresh:
            try:
                started = self.nodes.start(self.library, self.schema, configuration, fresh)
            except ExternalToolError as exc:
                self.say("launch-error", f"cannot start {', '.join(fresh)}: {exc}")
                return False
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
        groups = [c for c in managed if c in fresh], [c for c in managed if c not in fresh]
        for group, appear in zip(groups, (APPEAR, None), strict=True):
            todo = [c for c in group if self.states.get(c, "unconfigured") == "unconfigured"]
            configured = self._transitions([(c, "configure") for c in todo], appear)
            ready = [c for c in group if c not in todo or configured.get(c)]
            ok = ok and len(ready) == len(group)
            steps = [(c, "activate") for c in ready if self.states.get(c) != "active"]
            ok = all(self._transitions(steps, appear).values()) and ok
        self.parked -= {self._node(c) for c in managed}
        return ok

    def _transitions(
        self, steps: list[tuple[str, str]], appear: float | None = None
    ) -> dict[str, bool]:
        """Perform several transitions at once; say each (with its result); component -> ok."""
        if not steps:
            return {}
        nodes = {self._node(c): c for c, _ in steps}
        try:
            outcomes = self.agent().transitions([(self._node(c), t) for c, t in steps], appear)
        except ExternalToolError as exc:
            return {c: self._said_failure(c, t, str(exc)) for c, t in steps}
        done = {}
        for outcome in outcomes:
            done[nodes[outcome.node]] = self._said(nodes[outcome.node], outcome)
        return done

    def _said_failure(self, component: str, transition: str, error: str) -> bool:
        node = self._node(component)
        self.say("lifecycle", f"{node}: {transition} failed: {error}", component=component,
                 node=node, transition=transition, ok=False, error=error)  # fmt: skip
        return False

    def _transition(self, component: str, transition: str, appear: float | None = None) -> bool:
        """Perform one transition, confirmed by reading the state back; say how it went."""
        return self._transitions([(component, transition)], appear).get(component, False)

    def _said(self, component: str, outcome: Outcome) -> bool:
        """Say how one transition went (event ``lifecycle``); return whether it held."""
        if outcome.state is not None:
            self.states[component] = outcome.state
        result = (
            f"now {outcome.state} ({outcome.seconds * 1000:.0f} ms)"
            if outcome.ok
            else f"failed: {outcome.error}"
        )
        self.say(
            "lifecycle",
            f"{outcome.node}: {outcome.transition} {result}",
            component=component,
            node=outcome.node,
            transition=outcome.transition,
            ok=outcome.ok,
            state=outcome.state,
            seconds=round(outcome.seconds, 4),
            **({"error": outcome.error} if outcome.error else {}),
        )
        return bool(outcome.ok)

    def retire(self, leaving: list[tuple[str, str, str, bool]]) -> None:
        """Take components out of service, each the way its kind allows (module docstring).

        ``leaving`` holds (component, role, replacement, alive in the graph). Own processes
        are stopped together, so their grace periods overlap.
        """
        processes, managed = [], []
        for component, role, replacement, alive in leaving:
            node = self._node(component)
            own = component in self.nodes.nodes
            if self._managed(component) and (own or alive):
                managed.append((component, role, replacement))
            elif own:
                processes.append((component, role, replacement))
            elif alive:
                self.by_hand[node] = component
                self.say(
                    "stop-by-hand",
                    f"stop this by hand: {node} ({component}, {role}) is replaced by "
                    f"{replacement}, but rosreconf did not start it and it is not a managed "
                    "node (ROS 2 has no remote kill)",
                    component=component,
                    node=node,
                )
        # With standby, an inactive node is a ready standby: deactivate is enough.
        steps = OUT_OF_SERVICE[:1] if self.standby else OUT_OF_SERVICE
        out = {c: True for c, _, _ in managed}
        for transition in steps:
            todo = [(c, transition) for c, _, _ in managed if out[c]]
            out.update(self._transitions(todo))
        for component, role, replacement in managed:
            self.parked.add(self._node(component))
            self.say("stop", f"took {component} ({role}) out of service: replaced by "
                     f"{replacement}", component=component, how="lifecycle")  # fmt: skip
        stopped = {n.component: n for n in self.nodes.stop([c for c, _, _ in processes])}
        for component, role, replacement in processes:
            ended = stopped[component]
            code = ended.program.process.returncode
            self.say("stop", f"stopped {component} ({role}): replaced by {replacement} "
                     f"(pid {ended.pid}, exit {code})", component=component,
                     how="process", returncode=code)  # fmt: skip

    def prepare_standby(self, configuration: Configuration, failed: Collection[str]) -> None:
        """Start and configure the managed alternatives of every role, ready to activate."""
        if not self.standby:
            return
        running = set(configuration.components)
        wanted = [
            c.name
            for role in self.schema.graph.roles
            for c in self.library.candidates(role.abstraction)
            if c.may_serve_in(self.schema.name)
            and c.name not in running
            and c.name not in failed
            and c.name not in self.nodes.nodes
            and self._managed(c.name)
        ]
        wanted = list(dict.fromkeys(wanted))
        if not wanted:
            return
        try:
            self.nodes.start(self.library, self.schema, configuration, wanted)
        except ExternalToolError as exc:
            self.say("launch-error", f"cannot start standby {', '.join(wanted)}: {exc}")
            return
        self.parked |= {self._node(c) for c in wanted}
        self._agent_call(lambda agent: agent.watch([self._node(c) for c in wanted]))
        self.say("launch", f"started standby {', '.join(wanted)} (each is configured as soon "
                 "as it is up, so a failover is one activate)", components=wanted,
                 standby=True)  # fmt: skip
        self.unready += wanted

    def tend(self) -> None:
        """Configure the standby nodes whose services have come up (never waits for one)."""
        self.unready = [c for c in self.unready if c in self.nodes.nodes]
        if not self.unready:
            return
        nodes = [self._node(c) for c in self.unready]
        ready = self._agent_call(lambda agent: agent.ready(nodes)) or set()
        up = [c for c in self.unready if self._node(c) in ready]
        self.unready = [c for c in self.unready if c not in up]
        configured = self._transitions([(c, "configure") for c in up])
        # A configure that timed out on a busy machine (or whose answer was lost while the
        # node's service was still being matched) is tried again on a later tick, a few times.
        for component in (c for c, ok in configured.items() if not ok):
            self.tries[component] = self.tries.get(component, 0) + 1
            if self.tries[component] < STANDBY_TRIES:
                self.unready.append(component)
            else:
                self.say("lifecycle", f"{self._node(component)}: not a ready standby after "
                         f"{STANDBY_TRIES} configure attempts; left unconfigured",
                         component=component, node=self._node(component))  # fmt: skip

    def close(self) -> list[str]:
        """Stop every process started here and the lifecycle agent; return the components."""
        stopped = [own.component for own in self.nodes.close()]
        if self._agent is not None:
            self._agent.close()
            self._agent = None
        return stopped
