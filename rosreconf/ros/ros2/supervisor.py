"""Supervise the nodes of a configuration that rosreconf did not start: one collaborator.

The ROS 2 actuator (``rosreconf.ros.ros2.actuator``) starts and stops its own processes; the
nodes a team started run beside them. What ``watch`` may do about those is two things that
are one concern, kept together here so that the actuator asks one part:

- see them fail: their processes are watched (``outside.OutsideNodes``), so an exit or a
  hang is a ``failed`` event at once, not after the DDS lease;
- take them out of service or rewire them: their processes stopped with ``--stop-outside``,
  else each named for a person until the system conforms (``byhand.ByHand``).

Nothing of this is ever shared with the actuator's other parts: they ask through the
methods below. Every decision is said through ``say``; nothing here prints.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.ros2.byhand import ByHand
from rosreconf.ros.ros2.outside import OutsideNodes

Say = Callable[..., None]


@dataclass
class OutsideSupervisor:
    """The outside nodes of one watcher: watched, retired or rewired (module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        env: the environment nodes run in: its ROS_DOMAIN_ID is the domain whose ports
            prove which process runs a participant (none known: nothing is watched).
        say: receives every event.
        stop_outside: signal a replaced outside node's process (``--stop-outside``).
        outside: the confirmed processes of the outside nodes (None: the domain is not known).
        by_hand: the outside nodes to stop or restart, or named for a person.
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    env: Mapping[str, str]
    say: Say
    stop_outside: bool = False
    outside: OutsideNodes | None = field(init=False, default=None)
    by_hand: ByHand = field(init=False)

    def __post_init__(self) -> None:
        domain = self.env.get("ROS_DOMAIN_ID", "0")  # the nodes' domain: their ports prove pids
        if domain.isdigit():
            self.outside = OutsideNodes(int(domain), self.say, prove=self.stop_outside)
        self.by_hand = ByHand(
            self.library, self.schema, self.say, self._node, self.outside, self.stop_outside
        )

    def _node(self, component: str) -> str:
        return node_live_name(self.library[component])

    def track(
        self,
        participants: Mapping[bytes, tuple[str, ...]],
        own: Collection[str],
        wanted: Collection[str],
    ) -> set[str]:
        """Watch the processes of the ``wanted`` nodes rosreconf did not start (``own``: the
        nodes of its own processes, no longer watched here); return the nodes announced by a
        participant seen for the first time (a new process).
        """
        if self.outside is None:
            return set()
        fresh = {n for g, ns in participants.items() if g not in self.outside.seen_at for n in ns}
        self.outside.forget(own)
        self.outside.track(participants, set(wanted) - set(own))
        return fresh

    def take_ended(self) -> set[bytes]:
        """Return the participants of outside processes found exited or hung since last asked:
        DDS announces them until their lease ends, so the graph must leave them out.
        """
        return self.outside.take_ended() if self.outside is not None else set()

    def poll(self) -> bool:
        """Tell whether a watched outside process ended or hung, not yet said."""
        return self.outside is not None and self.outside.poll()

    def gone(self, current: Configuration, failed: Collection[str]) -> set[str]:
        """Say which outside nodes' processes exited or hung; return the failed components."""
        if self.outside is None:
            return set()
        comps = {self._node(c): (r, c) for r, c in current.assignment if c}
        now = set()
        for node, how in sorted(self.outside.take().items()):
            # its participant is hidden from the graph (``take_ended``), not its name
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

    def retire(self, leaving: list[tuple[str, str, str, bool]]) -> None:
        """Take outside nodes out of service: stop their processes (all at once), or name them.

        ``leaving`` holds (component, role, replacement, alive in the graph).
        """
        self.by_hand.retire(leaving)

    def restart_by_hand(self, component: str, role: str, configuration: Configuration) -> None:
        """Name a node rosreconf did not start that must restart to be rewired, and how."""
        self.by_hand.restart(component, role, configuration)

    def stop_by_hand(self, component: str, node: str, why: str) -> None:
        """Name a squatter on ``component``'s name for a person to stop; ``left_running`` says
        it again until it is gone.
        """
        self.by_hand.nodes[node] = component
        self.say(
            "stop-by-hand",
            f"stop this by hand: {why}; rosreconf did not start it",
            component=component,
            node=node,
        )

    def left_running(self, check: Conformance) -> bool:
        """Say once what is left when only nodes for a person keep it from conforming."""
        return self.by_hand.left_running(check)

    def settled(self) -> None:
        """Forget what a person was asked to stop or restart: the system conforms."""
        self.by_hand.settled()

    def theirs(self) -> frozenset[str]:
        """Return the components whose node was found in a process rosreconf did not start."""
        outside = self.outside
        if outside is None or not outside.theirs:
            return frozenset()
        return frozenset(
            c.name for c in self.library.components if node_live_name(c) in outside.theirs
        )

    def awaited(self) -> frozenset[str]:
        """Return the components a person was asked to restart, until the system conforms."""
        return frozenset(self.by_hand.restarting)

    def close(self) -> None:
        """Release the watched processes' pidfds and stop listening for evidence."""
        if self.outside is not None:
            self.outside.close()
