"""Nodes that hold a component's name and are not rosreconf's: squatters.

ROS 2 lets two nodes take one name, and then service calls, parameters and lifecycle requests
reach either one. ``watch`` never starts a component whose node name a live node holds already
(``onename``; event ``name-taken``): that node is judged as it runs (the component restarted
by hand, wired or not; or another node, a name clash). A participant is rosreconf's own when
its Fast DDS GUID carries the pid of a process rosreconf started (another vendor's carries
none: then its node names tell).

A squatter (a node of the component's name that is not the component, ``clashes``) is named
for a person (``stop-by-hand``, with its process when /proc confirmed it), or with
``--stop-outside`` its process is stopped (``stopproc``: SIGINT, SIGTERM, SIGKILL; event
``stop``), only when /proc confirmed that process, the kernel proved it sends the squatting
participant's datagrams (``provenance``), and it runs that node alone, never by a guess.
Beside a running component that rosreconf did not start either, which of the two is the
squatter is not known (a participant's endpoints are not kept per node): it is named, not
stopped. Nothing here prints.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from dataclasses import dataclass

from rosreconf.ros.ros2.fastdds_ids import fastdds_fields, may_be_of
from rosreconf.ros.ros2.hostprocs import locate_participants, nodes_by_process
from rosreconf.ros.ros2.nodes import NodeProcesses
from rosreconf.ros.ros2.stopproc import Stopped
from rosreconf.ros.ros2.supervisor import OutsideSupervisor

Participants = Callable[[], dict[bytes, tuple[str, ...]]]


@dataclass
class Squatting:
    """Keep rosreconf from starting a name twice; name or stop squatters (module docstring).

    Attributes:
        nodes: the node processes rosreconf started (its own participants).
        supervisor: the nodes rosreconf did not start: their confirmed processes, and those
            named for a person to stop.
        participants: each alive participant's GUID -> its nodes (the last read).
        hide: leaves participants out of later reads (a squatter stopped here).
    """

    nodes: NodeProcesses
    supervisor: OutsideSupervisor
    participants: Participants
    hide: Callable[[Collection[bytes]], None]

    def _own(self, guid: bytes, nodes: Collection[str]) -> bool:
        """Tell whether participant ``guid`` (with ``nodes``) is a process rosreconf started."""
        own = self.nodes.nodes.values()
        if fastdds_fields(guid) is None:  # another vendor's GUID carries no pid: names tell
            return set(nodes) <= {o.node for o in own}
        return any(may_be_of(guid, o.pid) for o in own)

    def holders(self, node: str) -> dict[bytes, tuple[str, ...]]:
        """Return the participants not rosreconf's own that announce ``node``, with their nodes."""
        return {
            g: ns for g, ns in self.participants().items() if node in ns and not self._own(g, ns)
        }

    def incarnations(self, node: str) -> frozenset[str]:
        """Return the participants (hex GUIDs) announcing ``node`` now: one per process."""
        return frozenset(g.hex() for g, ns in self.participants().items() if node in ns)

    def squatter(self, component: str, role: str, node: str, beside: bool) -> bool:
        """Name the node holding ``component``'s name that is not it, or stop its process;
        True when every process of it was stopped (the name is free).

        ``beside``: the component runs too; the squatter is then the participant that is not
        its process (known only when rosreconf started the component).
        """
        supervisor = self.supervisor
        what = f"has {component}'s name ({role}) but none of its endpoints: a name clash"
        if beside and component not in self.nodes.nodes:  # which one is which is not known
            which = "which of the nodes of that name it is cannot be told: stop the one that is not"
            supervisor.stop_by_hand(component, node, f"a node named {node} {what} ({which})")
            return False
        held = self.holders(node)
        if not held:
            return False  # every node of that name is rosreconf's own: nothing to hand on
        outside = supervisor.outside
        located = locate_participants(
            self.participants(),
            outside.domain if outside is not None else -1,
            seen_at=outside.seen_at if outside is not None else None,
        )
        procs = nodes_by_process(located)
        stopped = 0
        for guid in sorted(held):
            proc = located[guid].proc
            if proc is not None and outside is not None:
                outside.drop(proc)  # not the component's process: never failed by its exit
            if supervisor.stop_outside and proc is not None and outside is not None:
                result = outside.stop_proven(proc, guid, node, procs.get(proc, (node,)))
                if result.outcome in (Stopped.STOPPED, Stopped.GONE):
                    self.hide({guid})
                    supervisor.say(
                        "stop",
                        f"stopped {node}: it {what}; {result.message}",
                        component=component,
                        node=node,
                        how="signal",
                        pid=proc.pid,
                        outside=True,
                    )
                    stopped += 1
                    continue
                why = result.message
            elif supervisor.stop_outside:
                why = f"its process is not known: {located[guid].detail}"
            else:
                why = "ROS 2 has no remote kill" + (
                    f"; --stop-outside would stop its process {proc.pid}" if proc else ""
                )
            supervisor.stop_by_hand(component, node, f"{node} {what} ({why})")
        return stopped == len(held)
