"""The exits of the node processes rosreconf started: said at once, hidden until DDS notices.

rosreconf is the parent of every node process it starts (``nodes``), so it sees one end at
once, long before DDS would: the node's participant is announced until its lease ends, and a
node started anew under the same name would then be two. So each process that ends, or that
rosreconf stops, is kept here until the graph no longer needs telling. The source only reads
(each node carries its participant, ``LiveNode.participant``): leaving these out is a filter
the actuator owns (``unhidden``, ``visible``, ``alive``) on each graph and participant list:

    what                                        how long it is left out of the graph
    ------------------------------------------  --------------------------------------------
    a process seen to end (``ended``)            its node name, until a new participant (a
                                                 new process) announces it: a team restarting
                                                 it by hand brings it back (``revived``)
    the participants of those processes          from the next read on (``take_newly``)
    the participants of a process being stopped  from the read before any restart
                                                 (``stopping``)
    outside processes ended or hung, squatters   from the next read on (``hide``); each
    stopped: their participants                  participant until no node of it is left

An end is said once: event ``failed`` for a component in service (``bringup.exit_news``: the
last lines of its log when it exited before it was ready), ``exited`` for one out of service.
Nothing here prints.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field, replace

from rosreconf.model import Configuration
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.ros2.bringup import exit_news
from rosreconf.ros.ros2.fastdds_ids import may_be_of
from rosreconf.ros.ros2.nodes import NodeProcesses, OwnNode

Say = Callable[..., None]


@dataclass
class OwnExits:
    """The own node processes that ended or are being stopped (see the module docstring).

    Attributes:
        nodes: the node processes rosreconf started.
        participants: the source's: each alive participant's GUID -> its nodes (last read).
        forget: told of each component whose process ended or is being stopped: a process
            started anew for it is unconfigured (the lifecycle state read back is stale).
        say: receives every event.
        dead: live names of nodes whose process rosreconf saw exit (kept here alone).
        newly_dead: those of ``dead`` not yet taken by ``take_newly``: their processes'
            participants are to be left out of later reads.
        hidden: the participants left out (processes known dead, announced until their
            lease ends): a node restarted under its name is then its new process only.
    """

    nodes: NodeProcesses
    participants: Callable[[], Mapping[bytes, tuple[str, ...]]]
    forget: Callable[[str], None]
    say: Say
    dead: set[str] = field(default_factory=set)
    newly_dead: set[str] = field(default_factory=set)
    hidden: set[bytes] = field(default_factory=set)

    def hide(self, participants: Collection[bytes]) -> None:
        """Leave ``participants`` out of every later graph and participant list."""
        self.hidden |= set(participants)

    def alive(self) -> dict[bytes, tuple[str, ...]]:
        """Return the source's participants -> their nodes, the hidden ones left out."""
        return {g: ns for g, ns in self.participants().items() if g not in self.hidden}

    def stopping(self, stopping: list[OwnNode]) -> None:
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
            self.forget(own.component)
        pids = {own.node: own.pid for own in stopping}
        self.hidden |= {
            g
            for g, nodes in self.alive().items()
            if any(n in pids and may_be_of(g, pids[n]) for n in nodes)
        }

    def ended(self, only: Collection[str] | None = None) -> list[tuple[OwnNode, int]]:
        """Return each own process (of ``only``'s components) that ended since last asked."""
        gone = self.nodes.exited(only)
        for own, _ in gone:
            self.dead.add(own.node)
            self.newly_dead.add(own.node)
            self.forget(own.component)
        return gone

    def said(
        self, current: Configuration, failed: Collection[str], gone: list[tuple[OwnNode, int]]
    ) -> set[str]:
        """Say each of ``gone`` (``ended``); return the components of ``current`` now failed."""
        now = set()
        for own, code in gone:
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

    def started(self, started: Collection[OwnNode]) -> None:
        """Show the nodes of processes just started again (their names are theirs now)."""
        self.dead -= {own.node for own in started}

    def revived(self, nodes: Collection[str]) -> None:
        """Show ``nodes`` again: a new participant announces them (a restart by hand)."""
        self.dead -= set(nodes)

    def take_newly(self, participants: Mapping[bytes, tuple[str, ...]]) -> set[bytes]:
        """Return those of ``participants`` that run a node whose process ended since last
        asked: they linger until their lease ends.
        """
        newly, self.newly_dead = self.newly_dead, set()
        return {g for g, nodes in participants.items() if newly & set(nodes)}

    def unhidden(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes of hidden participants; stop hiding those with no
        node left in it (gone from DDS: nothing left to hide)."""
        shown = {n.participant for n in graph.nodes}
        self.hidden = {g for g in self.hidden if g.hex() in shown}
        hidden = {g.hex() for g in self.hidden}
        return _without(graph, lambda n: n.participant in hidden)

    def visible(self, graph: LiveGraph) -> LiveGraph:
        """Return ``graph`` without the nodes whose process rosreconf saw exit."""
        return _without(graph, lambda n: n.name in self.dead)


def _without(graph: LiveGraph, drop: Callable[[LiveNode], bool]) -> LiveGraph:
    """Return ``graph`` without the nodes ``drop`` tells (the same graph when none is)."""
    kept = tuple(n for n in graph.nodes if not drop(n))
    return graph if len(kept) == len(graph.nodes) else replace(graph, nodes=kept)
