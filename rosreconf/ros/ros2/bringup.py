"""Bring ROS 2 nodes into service, the started ones as each comes up; say each early exit.

``Bringup.start`` puts components into service the one way ROS 2 allows: a process of
rosreconf's wired otherwise is stopped first (ROS names are fixed when a process starts), a
standby of one is activated (a hung one is started cold instead: ``standby``), what does not
run is started (``nodes``), and a managed node is then configured and activated.

A managed node just started takes a while until its lifecycle services appear, and one may
never come: a stand-in that cannot act out its actions (an action type not installed and none
to pose as), a real executable that refuses a parameter, exit at once. Handing them all to the
lifecycle agent in one batch made it wait for each missing service in turn (``APPEAR``, 30 s
each): ``watch`` said nothing for minutes, and the nodes that did start stayed unconfigured.
So the started nodes are watched together, every ``POLL`` seconds:

- a node whose lifecycle services have appeared (the agent's ``ready``: no waiting in the
  agent) is configured and activated at once, without waiting for the others;
- a node whose process ends first is said at once, event ``failed`` (``how``:
  ``exited-before-ready``) with its exit status and the last lines its run wrote to its log,
  which say why; its component is failed, for the watcher to repair (restart in place, with
  backoff, or replace: ``rosreconf.ros.restarts``);
- only a node that neither comes up nor exits is waited for, up to ``APPEAR`` seconds.

The same event says every exit of a node process rosreconf started (``exit_news``): before it
was ready (seen in the graph, or it answered a lifecycle call), or later (``process-exit``: a
crash); its data carries the end of that run's log either way. Nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.printable import printable
from rosreconf.ros.ros2.lifecycle import APPEAR
from rosreconf.ros.ros2.nodes import NodeProcesses, OwnNode
from rosreconf.ros.ros2.standby import Standbys
from rosreconf.ros.ros2.transitions import Transitions

Say = Callable[..., None]
POLL = 0.05
"""Seconds between looks at the started nodes' services and processes."""
TAIL_LINES = 5
"""How many of its last log lines a node process that exited is said with."""
TAIL_BYTES = 16384
"""How much of the end of a log is read for them (a crash's stacks can be long)."""


def log_tail(own: OwnNode, lines: int = TAIL_LINES) -> list[str]:
    """Return the last non-empty lines this run of ``own`` wrote to its log, made printable.

    Only this run's: the log is appended to by every start of the component.
    """
    if own.log is None:
        return []
    try:
        with own.log.open("rb") as f:
            size = f.seek(0, 2)
            f.seek(max(own.log_from, size - TAIL_BYTES))
            text = f.read().decode(errors="replace")
    except OSError:
        return []
    return [printable(line, 300) for line in text.splitlines() if line.strip()][-lines:]


def exit_news(own: OwnNode, code: int, role: str) -> tuple[str, dict[str, Any]]:
    """Return the message and data of event ``failed`` for ``own``'s process that exited."""
    tail = log_tail(own)
    message = f"{own.component} ({role}) is gone: its process exited ({code}): failed"
    how = "process-exit"
    if not own.ready:  # no one has seen it run: its log is all there is to say why
        how = "exited-before-ready"
        ends = f"ends: {' | '.join(tail)}" if tail else "is empty"
        message = (
            f"{own.component} ({role}) exited ({code}) before it was ready: failed; its log "
            f"({own.log}) {ends}"
        )
    data = {
        "component": own.component,
        "node": own.node,
        "returncode": code,
        "how": how,
        "log": tail,
        "log_file": str(own.log),
    }
    return message, data


@dataclass
class Bringup:
    """Take nodes into service; the started ones as each comes up (module docstring).

    Attributes:
        library, schema: what the configuration is made of.
        nodes: the node processes rosreconf started.
        lifecycle: the lifecycle agent and the states it read back.
        standbys: the standbys (one is activated, not started) and the nodes held out of
            service (one taken into service is no longer).
        ended: component names -> those whose process has ended, with the exit status
            (the actuator's ``_ended``: it keeps its own books on a dead node).
        started: told of the processes just started (their node names are theirs again).
        say: receives every event.
        appear: seconds a started node may take until its lifecycle services appear.
        failed: components said failed here (their process exited before ready), until
            taken (``take_failed``) by the watcher's next look at the exits.
    """

    library: ComponentLibrary
    schema: InteroperabilitySchema
    nodes: NodeProcesses
    lifecycle: Transitions
    standbys: Standbys
    ended: Callable[[Collection[str]], list[tuple[OwnNode, int]]]
    started: Callable[[Collection[OwnNode]], None]
    say: Say
    appear: float = APPEAR
    failed: set[str] = field(default_factory=set)

    def _managed(self, component: str) -> bool:
        launch = self.library[component].launch
        return launch is not None and launch.lifecycle

    def start(
        self,
        configuration: Configuration,
        components: Collection[str],
        why: str,
        states: Mapping[str, str | None],
    ) -> bool:
        """Put ``components`` into service: start what does not run; configure, activate.

        ``states``: node -> the lifecycle state of the graph last read (a standby that does
        not answer is hung). Returns whether everything asked for was done.
        """
        self._rewire(configuration, components)
        self.standbys.claim(components, states)
        fresh = [c for c in components if c not in self.nodes.nodes]
        ok = True
        if fresh:
            try:
                started = self.nodes.start(self.library, self.schema, configuration, fresh)
            except ExternalToolError as exc:
                self._say_problems()
                self.say("launch-error", f"cannot start {', '.join(fresh)}: {exc}")
                return False
            self._say_problems()
            self.started(started)
            how = "stand-ins of " if self.nodes.stand_ins else ""
            pids = {own.component: own.pid for own in started}
            self.say(
                "launch",
                f"started {how}{', '.join(fresh)} ({why}): "
                + ", ".join(f"{c} pid {p}" for c, p in pids.items()),
                components=fresh,
                pids=pids,
                output=str(self.nodes.directory),
            )
        managed = [c for c in components if self._managed(c)]
        if managed:
            names = [self.lifecycle.node_of(c) for c in managed]
            self.lifecycle.call(lambda agent: agent.watch(names))
        # the ready standbys first (one activate each), then what had to start, each as its
        # services appear: a fresh node takes a while, and one may never come
        ok = self.into_service([c for c in managed if c not in fresh]) and ok
        ok = self.as_they_come(configuration, [c for c in managed if c in fresh]) and ok
        self.standbys.unpark([self.lifecycle.node_of(c) for c in managed])
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
        for own in self.standbys.stop(stale):
            self.say(
                "stop",
                f"stopped {own.component} to restart it wired for the new "
                f"configuration (pid {own.pid})",
                component=own.component,
                how="rewire",
            )

    def into_service(self, components: Sequence[str], appear: float | None = None) -> bool:
        """Configure (those unconfigured) and activate ``components``; True if all are active."""
        state = self.lifecycle.state
        todo = [c for c in components if state(c) in (None, "unconfigured")]
        configured = self.lifecycle.perform([(c, "configure") for c in todo], appear)
        ready = [c for c in components if c not in todo or configured.get(c)]
        steps = [(c, "activate") for c in ready if state(c) != "active"]
        activated = self.lifecycle.perform(steps, appear)
        return len(ready) == len(components) and all(activated.values())

    def as_they_come(self, configuration: Configuration, started: Sequence[str]) -> bool:
        """Take the just started managed ``started`` into service, each as it comes up.

        Returns whether all of them are active. A node whose process exits first is said
        (``failed``) and its component kept in ``failed``.
        """
        ok, pending = True, list(started)
        deadline = time.monotonic() + self.appear
        while pending:
            for own, code in self.ended(pending):
                ok = False
                self._exited(configuration, own, code)
            pending = [c for c in pending if c in self.nodes.nodes]
            ready = self._ready(pending)
            if ready is None:  # no agent to ask: the transitions say why, one by one
                return self.into_service(pending, max(0.0, deadline - time.monotonic())) and ok
            if ready:
                ok = self.into_service(ready) and ok
                pending = [c for c in pending if c not in ready]
                for comp in ready:  # it answered: an exit from now on is a crash
                    if comp in self.nodes.nodes and self.lifecycle.state(comp) is not None:
                        self.nodes.nodes[comp].ready = True
            elif pending and time.monotonic() >= deadline:
                for comp in pending:
                    self.lifecycle.failed(
                        comp,
                        "configure",
                        f"its lifecycle services did not appear within {self.appear:g} s of "
                        "its start (its process runs)",
                    )
                return False
            elif pending:
                time.sleep(POLL)
        return ok

    def _ready(self, components: Sequence[str]) -> list[str] | None:
        """Return those of ``components`` whose lifecycle services are matched now.

        None when the lifecycle agent cannot be asked (said by ``Transitions.call``).
        """
        if not components:
            return []
        nodes = {self.lifecycle.node_of(c): c for c in components}
        answer = self.lifecycle.call(lambda agent: agent.ready(nodes))
        return None if answer is None else [c for n, c in nodes.items() if n in answer]

    def _exited(self, configuration: Configuration, own: OwnNode, code: int) -> None:
        """Say that ``own``'s process exited before it was taken into service; fail it."""
        role = next((r for r, c in configuration.assignment if c == own.component), "spare")
        message, data = exit_news(own, code, role)
        self.say("failed", message, **data)
        self.failed.add(own.component)

    def saw(self, names: Collection[str]) -> None:
        """Note the started nodes seen in the graph as ready: an exit is then a crash."""
        for own in self.nodes.nodes.values():
            own.ready |= own.node in names

    def take_failed(self) -> set[str]:
        """Return the components said failed here since the last call."""
        failed, self.failed = self.failed, set()
        return failed
