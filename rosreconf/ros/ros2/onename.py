"""Never two nodes of one name from rosreconf: a newcomer whose name is taken waits for it.

Alternatives may share a node name. Nav2's global planners are one executable, nav2_planner's
``planner_server``, started with another plugin: NavFn and Smac Hybrid-A* both run as
``/planner_server``. ROS 2 does not refuse a second node of a name (ROS 1's master shuts the
older one down), and two nodes of one name answer each other's calls: a lifecycle
``configure`` meant for the new one reaches the old one ("/planner_server is active"),
``get_state`` answers for either, and conformance sees a duplicate node for good. So a
component whose node name another process still holds is started only once that process is
gone: break before make. Every other newcomer still starts before the replaced components
leave (make before break), so a switch that renames nothing keeps its speed.

Who holds a name, besides the component's own process (a standby of it is activated, and a
kept one restarted to be rewired is stopped first by ``bringup``):

    holder                                          what is done
    ----------------------------------------------  ------------------------------------------
    another process rosreconf started (a replaced    stopped, never parked: the caller retires
    managed node, a standby of another component)    a replaced one as a process, and ``admit``
                                                     stops any other out of service
    a process rosreconf did not start, confirmed     waited for (``--stop-outside`` stops a
    (``outside``; a hung one too, which DDS may no   replaced one; else "stop this by hand")
    longer show)
    any other participant naming it (a node known    waited for
    by its DDS lease only)

A newcomer held back is said once (event ``name-taken``, naming the holders) and started as
soon as its name is free: the actuator asks on every poll and every look while confirming.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from rosreconf.model import ComponentLibrary
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.ros2.fastdds_ids import may_be_of
from rosreconf.ros.ros2.hostprocs import read_proc_id
from rosreconf.ros.ros2.nodes import NodeProcesses
from rosreconf.ros.ros2.outside import OutsideNodes

Say = Callable[..., None]


@dataclass
class OneName:
    """The newcomers waiting for their node name to be free (see the module docstring).

    Attributes:
        library: what the components are.
        nodes: the node processes rosreconf started (None: it starts none itself, as with
            ``ros2 launch``).
        participants: the last read's participants -> their nodes (processes known dead
            already left out).
        outside: the confirmed processes of nodes rosreconf did not start (None: unknown).
        say: receives every event.
        waiting: components held back, until their name is free (or they leave the
            configuration).
        said: component -> the holders last said, so each wait is said once.
    """

    library: ComponentLibrary
    nodes: NodeProcesses | None
    participants: Callable[[], Mapping[bytes, tuple[str, ...]]]
    outside: Callable[[], OutsideNodes | None]
    say: Say
    waiting: set[str] = field(default_factory=set)
    said: dict[str, tuple[str, ...]] = field(default_factory=dict)

    def node_of(self, component: str) -> str:
        """Return ``component``'s live node name."""
        return node_live_name(self.library[component])

    def own_holders(self, component: str) -> list[str]:
        """Return the other components whose process, started by rosreconf, runs its name."""
        name = self.node_of(component)
        own = self.nodes.nodes if self.nodes is not None else {}
        return [d for d, o in own.items() if d != component and o.node == name]

    def holders(self, component: str) -> list[str]:
        """Return who else holds ``component``'s node name now, as said to a person."""
        name = self.node_of(component)
        processes = self.nodes.nodes if self.nodes is not None else {}
        own = {d: processes[d].pid for d in self.own_holders(component)}
        mine = processes.get(component)
        pids = [*own.values(), *([mine.pid] if mine is not None else [])]
        said = [f"{d} (pid {p}, started by rosreconf)" for d, p in own.items()]
        outside = self.outside()
        known = outside.process_of(name) if outside is not None else None
        if known is not None and read_proc_id(known[0].pid) == known[0]:
            said.append(f"pid {known[0].pid}, a process rosreconf did not start")
            pids.append(known[0].pid)
        others = [
            g
            for g, names in self.participants().items()
            if name in names and not any(may_be_of(g, p) for p in pids)
        ]
        if others:
            said.append(f"{len(others)} participant(s) rosreconf did not start")
        return said

    def admit(
        self, components: Collection[str], configuration: Collection[str], leaving: Collection[str]
    ) -> list[str]:
        """Return those of ``components`` free to start now; hold the others back (said).

        A process rosreconf started under a newcomer's name that is neither in
        ``configuration`` nor ``leaving`` (the caller retires those as processes) is out of
        service, rosreconf's own: it is stopped here first.
        """
        idle = [
            d
            for c in components
            for d in self.own_holders(c)
            if d not in configuration and d not in leaving
        ]
        stopped = self.nodes.stop(list(dict.fromkeys(idle))) if self.nodes is not None else []
        for own in stopped:
            taker = next(c for c in components if self.node_of(c) == own.node)
            self.say(
                "stop",
                f"stopped {own.component} (out of service, pid {own.pid}): {taker} starts "
                f"under the same node name {own.node}",
                component=own.component,
                node=own.node,
                how="name",
            )
        free = []
        for c in components:
            held = self.holders(c)
            if not held:
                free.append(c)
                self.waiting.discard(c)
                self.said.pop(c, None)
                continue
            self.waiting.add(c)
            if self.said.get(c) != tuple(held):
                self.said[c] = tuple(held)
                self.say(
                    "name-taken",
                    f"{c} waits to start: its node name {self.node_of(c)} is still taken by "
                    f"{'; '.join(held)} (two nodes of one name would answer each other's "
                    "lifecycle calls); it starts once that is gone",
                    component=c,
                    node=self.node_of(c),
                    holders=held,
                )
        return free

    def due(self, configuration: Collection[str]) -> list[str]:
        """Return the waiting components of ``configuration`` whose name is free now."""
        self.waiting &= set(configuration)
        return [c for c in sorted(self.waiting) if not self.holders(c)]
