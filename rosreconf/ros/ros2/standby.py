"""Keep managed alternatives configured and wired, so that a failover is one ``activate``.

With ``watch --standby``, for every running component the watcher's own replan says which
configuration would replace it were it to fail; the managed alternatives that configuration
starts are started now, wired for it (its remappings, and a stand-in's options), held
``inactive`` and out of the graph's judgement (``parked``). The likeliest failure (by
failure probability) decides when two would wire one alternative differently; one running
with other wiring is started again. Configuring them happens on the watch loop's path, so
each ``configure`` waits at most ``TEND_TIMEOUT`` and is tried again on a later tick.

The managed nodes a change retires are held here too (``retire``: deactivated, and cleaned up
but with ``--standby``, an inactive node being a ready standby): one set of parked nodes,
which the actuator's other parts ask about and never hold.

A hung standby (its process stopped, or its state query unanswered: ``hung``) could answer
no ``activate``: on each tick it is stopped and started anew for the configuration it joins
(event ``standby-hung``), and one found hung at a failover is started cold instead of
activated, so a hung standby never delays a failover by a transition's timeout.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.ros.ros2.lifecycle import OUT_OF_SERVICE
from rosreconf.ros.ros2.lifecycle_state import UNANSWERED
from rosreconf.ros.ros2.nodes import NodeProcesses, OwnNode
from rosreconf.ros.ros2.pidwatch import STOPPED_STATES, proc_state
from rosreconf.ros.ros2.transitions import Transitions

TEND_TIMEOUT = 0.5
"""Seconds a standby's configure may take on the watch loop's path (tried again later)."""
STANDBY_TRIES = 5
"""Configure attempts for one standby node before it is left unconfigured (and said so)."""


@dataclass
class Standbys:
    """The standby nodes of one watcher (see the module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        nodes: the watcher's node processes (standbys are among them).
        lifecycle: the lifecycle agent's transitions.
        say: receives every event.
        parked: live names of the managed nodes held out of service, standbys and retired
            ones alike (kept here alone: the actuator parks and unparks through ``retire``,
            ``unpark`` and ``ended``, and asks ``is_parked`` and ``held``).
        unready: standby components started and not yet configured (``tend`` does it).
        tries: standby component -> configure attempts that failed (``STANDBY_TRIES`` at most).
        last: the configuration and failures the standbys were last prepared for.
        lost: a standby's process exited: the set is prepared again on the next tick.
        seen: node names of the graph last read, less the standbys started since (``tend``).
        refused: alternative -> the node whose name it shares, said once (``_unshared``).
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    nodes: NodeProcesses
    lifecycle: Transitions
    say: Callable[..., None]
    parked: set[str] = field(default_factory=set)
    unready: list[str] = field(default_factory=list)
    tries: dict[str, int] = field(default_factory=dict)
    last: tuple[Configuration, frozenset[str]] | None = None
    lost: bool = False
    seen: set[str] = field(default_factory=set)
    refused: dict[str, str] = field(default_factory=dict)

    def retire(self, managed: list[tuple[str, str, str]], *, standby: bool) -> None:
        """Take managed nodes out of service with lifecycle transitions, and hold them there.

        ``managed`` holds (component, role, replacement). Each stays, parked: not an extra
        node to the graph's judgement. With ``standby``, deactivate is enough: an inactive
        node is a ready standby.
        """
        steps = OUT_OF_SERVICE[:1] if standby else OUT_OF_SERVICE
        out = {c: True for c, _, _ in managed}
        for transition in steps:
            todo = [(c, transition) for c, _, _ in managed if out[c]]
            out.update(self.lifecycle.perform(todo))
        for component, role, replacement in managed:
            self.parked.add(self.node_of(component))
            self.say(
                "stop",
                f"took {component} ({role}) out of service: replaced by {replacement}",
                component=component,
                how="lifecycle",
            )

    def unpark(self, nodes: Collection[str]) -> None:
        """Take ``nodes`` back into service, or note their processes stopped."""
        self.parked -= set(nodes)

    def ended(self, node: str) -> None:
        """Note that ``node``'s process exited: a standby lost is started again (``lost``)."""
        self.lost |= node in self.parked
        self.parked.discard(node)

    def is_parked(self, node: str) -> bool:
        """Tell whether ``node`` is held out of service on purpose."""
        return node in self.parked

    def held(self) -> frozenset[str]:
        """Return the nodes held out of service now (a copy: they change only here)."""
        return frozenset(self.parked)

    def claim(self, components: Collection[str], states: Mapping[str, str | None]) -> None:
        """Take ``components`` into service: a hung standby among them is stopped, to be
        started cold (``hung``; ``states`` as there), and none is configured as a standby.
        """
        standing = [c for c in components if c in self.nodes.nodes]
        self.drop(self.hung(standing, states), "started cold instead of activated")
        self.unready = [c for c in self.unready if c not in components]

    def node_of(self, component: str) -> str:
        """Return the live node name of ``component``."""
        return node_live_name(self.library[component])

    def _managed(self, component: str) -> bool:
        launch = self.library[component].launch
        return launch is not None and launch.lifecycle

    def prepare(self, configuration: Configuration, failed: Collection[str]) -> None:
        """Start and configure managed alternatives, each wired for the configuration it joins.

        For every running component, the configuration that would replace it were it to fail
        (``rosreconf.solve.running.nearest_valid``, the watcher's own replan) names the
        alternatives that would start; each is started wired for that configuration (the
        likeliest failure first, by failure probability), so activating it at a failover
        leaves nothing dangling. A standby running with other wiring is started again.
        """
        self.last = (configuration, frozenset(failed))
        running = set(configuration.components)
        joins = self._joins(configuration, set(failed))
        stale = [
            c
            for c, cfg in joins.items()
            if c in self.nodes.nodes and self.nodes.miswired(self.library, self.schema, cfg, [c])
        ]
        for own in self.nodes.stop(stale):
            self.parked.discard(own.node)
            self.lifecycle.forget(own.component)
        wanted = self._unshared(
            [c for c in joins if c not in self.nodes.nodes and c not in running], running
        )
        if not wanted:
            return
        pids: dict[str, int] = {}
        try:
            for cfg in dict.fromkeys(joins[c] for c in wanted):
                group = [c for c in wanted if joins[c] == cfg]
                started = self.nodes.start(self.library, self.schema, cfg, group)
                pids.update((own.component, own.pid) for own in started)
        except ExternalToolError as exc:
            self.say("launch-error", f"cannot start standby {', '.join(wanted)}: {exc}")
            return
        finally:
            for problem in self.nodes.take_problems():  # a broken zygote: started alone
                self.say("launch-error", problem)
        names = [self.node_of(c) for c in wanted]
        self.parked |= set(names)
        self.seen -= set(names)  # up only once a later read shows the new processes
        self.lifecycle.call(lambda agent: agent.watch(names))
        self.say(
            "launch",
            f"started standby {', '.join(wanted)} (each is configured as soon "
            "as it is up, so a failover is one activate)",
            components=wanted,
            pids=pids,
            standby=True,
        )
        # each started process is configured afresh: listed once, with attempts of its own
        self.unready += [c for c in wanted if c not in self.unready]
        for c in wanted:
            self.tries.pop(c, None)

    def _unshared(self, wanted: list[str], running: Collection[str]) -> list[str]:
        """Return those of ``wanted`` whose node name no running node, nor standby, has.

        A standby under a running node's name would be a second node of that name, and two
        nodes of one name answer each other's lifecycle calls: it is not parked, and said
        once (event ``no-standby``); a failover to it starts it cold, once the node of its
        name is gone (``onename``).
        """
        taken = {self.node_of(c): c for c in running}
        for c, own in self.nodes.nodes.items():
            taken.setdefault(own.node, c)
        out = []
        for c in wanted:
            name = self.node_of(c)
            holder = taken.setdefault(name, c)
            if holder == c:
                out.append(c)
            elif self.refused.get(c) != holder:
                self.refused[c] = holder
                self.say(
                    "no-standby",
                    f"{c} cannot wait as a standby: it runs as {name}, the node name of "
                    f"{holder}, and two nodes of one name would answer each other's lifecycle "
                    f"calls; a failover to it starts it once {holder}'s process is gone",
                    component=c,
                    node=name,
                    holder=holder,
                )
        return out

    def hung(self, components: Collection[str], states: Mapping[str, str | None]) -> list[str]:
        """Return those of ``components`` whose own process is stopped or whose node is hung.

        ``states`` is node -> the lifecycle state last read (``UNANSWERED``: hung). Reading a
        process's state letter is one small /proc read: cheap enough for a failover's path.
        """
        out = []
        for c in components:
            own = self.nodes.nodes.get(c)
            if own is None:
                continue
            letter = proc_state(own.pid)
            if (letter is not None and letter in STOPPED_STATES) or states.get(
                own.node
            ) == UNANSWERED:
                out.append(c)
        return out

    def stop(self, components: Collection[str]) -> list[OwnNode]:
        """Stop these components' own processes (a hung standby, one wired otherwise); return
        those stopped. None of them stays parked, and the agent's clients, matched to the old
        processes, are made anew for the processes started next.
        """
        stopped = self.nodes.stop(components)
        if stopped:
            self.lifecycle.call(lambda agent: agent.forget([own.node for own in stopped]))
        for own in stopped:
            self.parked.discard(own.node)
            self.lifecycle.forget(own.component)
        return stopped

    def drop(self, components: Collection[str], why: str) -> None:
        """Stop hung standbys' processes and say so; they start again on ``replace_hung``."""
        for own in self.stop(components):
            self.say(
                "standby-hung",
                f"standby {own.component} ({own.node}) is hung (its process is stopped, or it "
                f"answers no state query): stopped (pid {own.pid}); {why}",
                component=own.component,
                node=own.node,
                pid=own.pid,
            )

    def replace_hung(self, states: Mapping[str, str | None]) -> None:
        """Stop each hung standby and start it anew for the configuration it would join;
        start again any that exited (``lost``).
        """
        standing = [c for c in self.nodes.nodes if self.node_of(c) in self.parked]
        hung = self.hung(standing, states)
        if not hung and not self.lost:
            return
        self.drop(hung, "started anew")
        self.lost = False
        if self.last is not None:  # the hung ones, and any that exited, start again
            self.prepare(*self.last)

    def _joins(self, configuration: Configuration, failed: set[str]) -> dict[str, Configuration]:
        """Return managed alternative -> the configuration it would join after one failure."""
        from rosreconf.solve.running import nearest_valid

        joins: dict[str, Configuration] = {}
        likely = sorted(
            (c for c in configuration.components if c not in failed),
            key=lambda c: -(self.library[c].failure_probability or 0.0),
        )
        for comp in likely:
            new = nearest_valid(self.library, self.schema, failed | {comp}, configuration)
            if new is None:
                continue
            for c in new.components:
                if c not in configuration.components and self._managed(c):
                    joins.setdefault(c, new)
        return joins

    def saw(self, names: Collection[str]) -> None:
        """Take the node names of the graph just read (``tend`` configures only those)."""
        self.seen = set(names)

    def tend(self) -> None:
        """Configure the standby nodes that have come up (never waits for one).

        Up means both: the lifecycle agent's client has matched the node's services, and the
        node is in a graph rosreconf read after starting it (``seen``). The agent alone is not
        enough: it also matches a dead predecessor's services while DDS still announces them,
        and rosreconf's own reads leave those out (``exits.OwnExits.stopping``). A
        configure sent before the node itself is up goes unanswered and uses up its tries.
        """
        self.unready = [c for c in self.unready if c in self.nodes.nodes]
        if not self.unready:
            return
        nodes = [self.node_of(c) for c in self.unready if self.node_of(c) in self.seen]
        if not nodes:
            return
        ready = self.lifecycle.call(lambda agent: agent.ready(nodes)) or set()
        up = [c for c in self.unready if self.node_of(c) in ready]
        self.unready = [c for c in self.unready if c not in up]
        # short: tend runs on the watch loop's path, and a slow configure must never hold
        # detection up; a configure that did not finish in time is tried on a later tick
        configured = self.lifecycle.perform([(c, "configure") for c in up], 0.0, TEND_TIMEOUT)
        # A configure that timed out on a busy machine (or whose answer was lost while the
        # node's service was still being matched) is tried again on a later tick, a few times.
        for component in (c for c, ok in configured.items() if not ok):
            self.tries[component] = self.tries.get(component, 0) + 1
            if self.tries[component] < STANDBY_TRIES:
                self.unready.append(component)
            else:
                self.say(
                    "lifecycle",
                    f"{self.node_of(component)}: not a ready standby after "
                    f"{STANDBY_TRIES} configure attempts; left unconfigured",
                    component=component,
                    node=self.node_of(component),
                )
