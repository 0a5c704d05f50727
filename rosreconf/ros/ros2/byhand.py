"""What ``watch`` does about the nodes it did not start: stop them when allowed, else name them.

ROS 2 has no remote "kill node" (ros2/ros2cli#535). A replaced node that rosreconf did not
start and that is not managed can only be taken down by signalling its process, which takes
down every node of that process. So, for such a node:

    ``--stop-outside`` and its process confirmed    SIGINT, SIGTERM, SIGKILL after a grace
    (``outside.OutsideNodes``), running only it     (``stopproc``): event ``stop``, how ``signal``
    its process runs other nodes too                never signalled: ``stop-by-hand`` names
                                                    the nodes it would take down
    no ``--stop-outside``, or no process known      ``stop-by-hand`` (why, when it is known)

A hung node (its process stopped) is failed and replaced; with ``--stop-outside`` its
process is stopped then too (``stopproc`` resumes it after each signal so it can act on it).
A kept node that must be rewired cannot be restarted from here: ``restart-by-hand`` names
it with the ``-r`` rules to start it with. Until the system conforms again, ``left_running``
says what is left for a person; nothing here prints.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.launchfiles import ros2_rules, wiring
from rosreconf.ros.livenames import Finding
from rosreconf.ros.ros2.outside import OutsideNodes
from rosreconf.ros.ros2.stopproc import Stopped, StopResult

Say = Callable[..., None]


@dataclass
class ByHand:
    """The outside nodes one watcher retires or rewires (see the module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        say: receives every event.
        node_of: a component's live node name.
        outside: the outside nodes' confirmed processes (None: the domain is not known).
        stop_outside: signal a replaced outside node's process (``--stop-outside``).
        nodes: live node name -> component, for nodes a person must stop or restart.
        restarting: components a person was asked to restart, rewired (until conformant).
        left: the nodes last said to be left for a person.
        findings: what kept the system from conforming then: said again when it changes (a
            node a person restarted with the wrong rules is named with what is still wrong).
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    say: Say
    node_of: Callable[[str], str]
    outside: OutsideNodes | None = None
    stop_outside: bool = False
    nodes: dict[str, str] = field(default_factory=dict)
    restarting: set[str] = field(default_factory=set)
    left: tuple[str, ...] = ()
    findings: tuple[str, ...] = ()

    def retire(self, leaving: list[tuple[str, str, str, bool]]) -> None:
        """Take outside nodes out of service: stop their processes (all at once), or name them.

        ``leaving`` holds (component, role, replacement, alive in the graph).
        """
        outside = self.outside
        results = {}
        if self.stop_outside and outside is not None:
            results = outside.stop([self.node_of(c) for c, _, _, _ in leaving])
        for component, role, replacement, alive in leaving:
            self._retired(component, role, replacement, alive, results.get(self.node_of(component)))

    def _retired(
        self, component: str, role: str, replacement: str, alive: bool, result: StopResult | None
    ) -> None:
        """Say how one outside node left service: stopped, or named for a person, and why."""
        node = self.node_of(component)
        outside = self.outside
        known = outside.process_of(node) if outside is not None else None
        if result is not None:
            if result.outcome in (Stopped.STOPPED, Stopped.GONE):
                self.say(
                    "stop",
                    f"stopped {component} ({role}): replaced by {replacement}; {result.message}",
                    component=component,
                    node=node,
                    how="signal",
                    pid=result.proc.pid,
                    outside=True,
                )
                return
            why = result.message
        elif self.stop_outside:
            lease = self.outside.lease_only.get(node) if self.outside is not None else None
            why = f"its process is not known ({lease or 'not found on this host'})"
        elif known is not None and len(known[1]) > 1:
            why = (
                f"its process {known[0].pid} also runs {', '.join(sorted(set(known[1]) - {node}))}"
            )
        else:
            why = "ROS 2 has no remote kill" + (
                f"; --stop-outside would stop its process {known[0].pid}" if known else ""
            )
        if not alive and known is None:
            return  # gone already, and nothing of it left to stop
        self.nodes[node] = component
        launch = self.library[component].launch
        kind = (  # a managed one is here when its replacement takes its node name
            f"{replacement} starts under its node name once it is gone"
            if launch is not None and launch.lifecycle
            else "it is not a managed node"
        )
        self.say(
            "stop-by-hand",
            f"stop this by hand: {node} ({component}, {role}) is replaced by {replacement}, "
            f"but rosreconf did not start it and {kind} ({why})",
            component=component,
            node=node,
        )

    def restart(self, component: str, role: str, configuration: Configuration) -> None:
        """Name a node rosreconf did not start that must restart to be rewired, and how."""
        node = self.node_of(component)
        self.nodes[node] = component
        self.restarting.add(component)
        rules = ros2_rules(wiring(self.library, self.schema, configuration).get(component, []))
        self.say(
            "restart-by-hand",
            f"restart this by hand: {node} ({component}, {role}) must be rewired for the new "
            "configuration (its remappings are fixed at start), but rosreconf did not start it; "
            f"start it with --ros-args {' '.join(f'-r {r}' for r in rules)}",
            component=component,
            node=node,
            remappings=rules,
        )

    def settled(self) -> None:
        """Forget what a person was asked to do: the system conforms."""
        self.left, self.findings = (), ()
        self.nodes.clear()
        self.restarting.clear()

    def left_running(self, check: Conformance) -> bool:
        """Say what is left when only nodes for a person keep ``check`` from conforming, and
        again whenever what is wrong changes; True in that case.
        """
        for node in set(self.nodes) - set(check.live.names):  # stopped by a person
            if self.nodes[node] not in self.restarting:  # one to restart is half done: gone
                del self.nodes[node]

        def for_a_person(f: Finding) -> bool:  # a node to stop, or to restart rewired
            if f.code == "extra-node":
                return f.live_name in self.nodes
            return f.component is not None and self.node_of(f.component) in self.nodes

        if not check.findings or not all(for_a_person(f) for f in check.findings):
            return False
        left = tuple(
            sorted(
                {
                    f.live_name if f.code == "extra-node" else self.node_of(str(f.component))
                    for f in check.findings
                }
            )
        )
        findings = tuple(sorted(f.message for f in check.findings))
        if (left, findings) != (self.left, self.findings):
            self.left, self.findings = left, findings
            rewire = [n for n in left if self.nodes.get(n) in self.restarting]
            stop = [n for n in left if n not in rewire]
            todo = [f"to stop by hand: {', '.join(stop)}"] if stop else []
            todo += [f"to restart rewired by hand: {', '.join(rewire)}"] if rewire else []
            self.say(
                "left-running",
                f"the configuration runs; left {'; '.join(todo)} (conformant is logged once "
                f"that is done); still: {'; '.join(findings[:3])}"
                + (f" and {len(findings) - 3} more" if len(findings) > 3 else ""),
                nodes=list(left),
                findings=list(findings),
            )
        return True
