"""Keep a running ROS system in a valid configuration when its nodes die (the paper's use case).

"An operating autonomous system needs to self-reconfigure due to changes in own hardware":
each ``Watcher.step`` reads the live graph, decides which components have failed, replans
with the fewest changes (``rosreconf.ros.replanning``, current configuration first), and
with ``apply`` has its ``Actuator`` retire the components that must go and start the new
ones, then confirms with ``rosreconf.ros.conformance.compare``.

When a component counts as failed: it was given as failed, or its node is registered but
does not answer (ROS 1: SIGKILLed nodes linger in the master; its actuator purges them), or its
process was seen to exit or hang (ROS 2: no DDS lease to wait for), or it was seen alive by
this watcher and is gone now. A component never seen is only *missing*: with ``apply`` it is
started (so a watcher can also bring a configuration up); without, it is only reported. A
restarted ROS 1 master (new pid or ``/run_id``; ``LiveSource.restarted``) is said, not
counted as failures, and checked again (with ``apply``, what the actuator started is stopped
and the configuration restarted).

The watcher decides; an ``Actuator`` (``rosreconf.ros.actuator``), made by the source, acts:
roslaunch on ROS 1; on ROS 2 each node's own process (a process of its own that exits is a
failure at once, with no DDS lease to wait for; managed nodes get lifecycle transitions;
nodes it cannot stop are named; ``standby`` prepares managed alternatives), or ``ros2
launch``. Nodes an actuator holds out of service on purpose are not extra nodes.

A repair is confirmed however it is made: after a replan the watcher keeps comparing, and
logs ``conformant`` (with the seconds since the failure was seen) once the live graph
matches, with ``apply`` or after a person repaired it by hand. ``rosreconf.ros.polling``
runs the steps (``stop_requested`` is polled between them and in every wait, so a signal
stops the watcher within one poll slice). A failed component is restarted in place or held
(``rosreconf.ros.restarts``); with ``prefer_after`` the configuration a failure left is
returned to once it is whole again (``rosreconf.ros.preference``), and with ``prefer`` the
best configuration by those metrics once failures and context allow it.

Context read live (``rosreconf.ros.livecontext``, ``context``) rules components out after
its dwell: a chosen one that is ruled out is replanned away as a failed one is, with the
fewest changes, but never restarted in place; the reason is its unmet condition.

A switch of task (``rosreconf.ros.tasks``) is asked from any thread and taken at the start
of a step: the fewest changes to the new schema's configuration, applied as a replan's are.
Its faces (``tasks.Face``) are shown every decision and the state after each read.

Launch errors are handed on (``rosreconf.ros.launcher``); a component that was launched
and never came up is not launched again on every poll. Every decision is an ``Event``
(``rosreconf.ros.events``) handed to the ``log`` callback; nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosreconf.errors import UnsettledGraphError
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.clashes import NameClashes
from rosreconf.ros.conformance import Conformance, compare
from rosreconf.ros.events import Event
from rosreconf.ros.lifecycle_faults import LifecycleFaults, checked
from rosreconf.ros.livecontext import LiveContext
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.options import WatchOptions
from rosreconf.ros.outsiders import Outsiders
from rosreconf.ros.preference import Preference
from rosreconf.ros.replanning import Change, replan
from rosreconf.ros.restarts import Restarts
from rosreconf.ros.sources import LiveSource
from rosreconf.ros.tasks import Tasks
from rosreconf.ros.verdicts import Missing, judge

__all__ = ["Event", "Watcher"]


@dataclass
class Watcher:
    """Watch one schema's configuration on one master, and repair it when asked to.

    Attributes:
        source: the running system: a ROS 1 master (with its call deadline and answer cap)
            or a ROS 2 DDS domain (``rosreconf.ros.sources``).
        library, schema: what the configuration is made of.
        current: the configuration that should run now (changes on replanning).
        workdir: a private directory for the stand-in package (removed by the caller).
        env: the environment roslaunch runs in.
        log: receives every ``Event``.
        options: how it watches and acts (``options.WatchOptions``; its actuator gets them
            whole).
        failed: components known to have failed, until restarted in place or released.
        stop_requested: polled between steps and while waiting; True ends ``run``.
        tasks: the tasks it may be switched to, the requests waiting, its faces.
        context: context read live, which rules components out (None: none read).
    """

    source: LiveSource
    library: ComponentLibrary
    schema: InteroperabilitySchema
    current: Configuration
    workdir: Path
    env: Mapping[str, str]
    log: Callable[[Event], None]
    options: WatchOptions = field(default_factory=WatchOptions)
    failed: set[str] = field(default_factory=set)
    stop_requested: Callable[[], bool] = lambda: False
    tasks: Tasks = field(default_factory=Tasks)
    context: LiveContext | None = None
    _ruled: dict[str, str] = field(default_factory=dict)
    _seen: set[str] = field(default_factory=set)
    _hopeless: frozenset[str] | None = None
    _missing: Missing = field(default_factory=Missing)
    _running: bool = False
    _actuator: Actuator = field(init=False, repr=False)
    _pending: float | None = None
    _graph: LiveGraph | None = None
    _lifecycle: LifecycleFaults = field(init=False, repr=False)
    _clashes: NameClashes = field(init=False, repr=False)
    _restarts: Restarts = field(init=False, repr=False)
    _outsiders: Outsiders = field(init=False, repr=False)
    _prefer: Preference = field(init=False, repr=False)

    def __post_init__(self) -> None:
        o = self.options
        acting = Acting(self.library, self.schema, self.workdir, self.env, self._say, o)
        self._actuator = self.source.actuator(acting)
        self._lifecycle = LifecycleFaults(self._say, self._actuator.reactivate)
        self._clashes = NameClashes(self._say, self._role, self._actuator.squatter)
        self._restarts = Restarts(self._say, self._role, o.restart_limit, o.restart_window, o.hold)
        parts = self._actuator, self._clashes, self._restarts
        self._outsiders = Outsiders(self.library, self.schema, self._say, self._role, *parts)
        self._prefer = Preference(self._say, o.prefer_after if o.apply else 0.0, weights=o.prefer)

    @property
    def unusable(self) -> set[str]:
        """The components no configuration may use now: failed, or ruled out by context."""
        return self.failed | set(self._ruled)

    def _assess(self) -> None:
        """Take what context rules out now (said as it changes, ``LiveContext.assess``)."""
        if self.context is not None:
            self._ruled = self.context.assess(self._say)

    def _read(self) -> LiveGraph:
        """Read the live graph; who announced a newly failed node is noted before and after."""
        if self._graph is not None:
            self._outsiders.note(self.failed)
        self._graph = self._actuator.visible(self.source.read())
        self._outsiders.note(self.failed)
        self._show()
        return self._graph

    def _live(self, fresh: bool) -> LiveGraph:
        """Return the live graph: read now with ``fresh``, else the one last read if any."""
        return self._graph if not fresh and self._graph is not None else self._read()

    def _compare(self, graph: LiveGraph) -> Conformance:
        """Compare, leaving out the nodes the actuator holds out of service on purpose."""
        check = compare(self.current, self.library, self.schema, graph)
        return self._clashes.excused(self._actuator.filtered(check))

    def _own_exits(self, tend: bool = True) -> bool:
        """Count a node whose process rosreconf started and saw exit as failed, at once.

        With ``tend``, standby nodes that came up are configured (not while confirming).
        """
        now = self._actuator.exits(self.current, self.failed, tend=tend)
        self.failed |= now
        return bool(now)

    def step(self) -> Conformance:
        """Observe once, replan and apply if needed; return how the system conforms now."""
        self._check_restart()
        self._assess()
        if self._retask():
            return self._confirm()
        if self._release():
            return self._confirm()
        if self._own_exits() and self._graph is not None and self._replan():
            return self._confirm()  # no graph to read first: the process exit says it all
        graph = self._read()
        check = self._compare(graph)
        clashing = self._clashes.clashing(check, self._actuator.started())
        back, news = self._outsiders.check(check, clashing, self.current, self.failed)
        self._seen -= back  # seen again if it runs; if its name is free, started
        self._hopeless = None if back else self._hopeless
        self._pending = time.monotonic() if news and self._pending is None else self._pending
        awaited = self._actuator.awaited()  # an unwired node a person is asked to restart
        verdicts = judge(check, self.current.components, self._seen, {*awaited, *clashing})
        for comp, why in verdicts.failed.items():
            if comp not in self.failed:
                role = self._role(comp)
                self._say(
                    "failed", f"{comp} ({role}) is {why}: failed", component=comp, how="graph"
                )
                self.failed.add(comp)
        missing = verdicts.missing
        self._seen |= verdicts.seen
        if not self._running and self._seen >= set(self.current.components):
            self._running = True
            self._say(
                "running",
                f"all {len(self.current.components)} components of the configuration run",
                components=list(self.current.components),
            )
        dead = [n.name for n in graph.nodes if not n.answered]
        if dead:
            self._actuator.forget(graph, dead)
        self.failed |= self._clashes.failed(check, self._actuator.started(), self.failed)
        # a managed node out of 'active' is a fault, re-activated with apply (lifecycle_faults)
        if self._lifecycle.check(check, self.failed, self._role) and self._pending is None:
            self._pending = time.monotonic()
        if self.unusable & set(self.current.components):
            if self._replan():
                return self._confirm()
        elif missing:
            fresh = self._missing.report(missing, self._actuator, self.options.apply, self._say)
            if fresh and self._start(fresh, "not running yet"):
                return self._confirm()
        if dead:
            check = self._compare(self._read())
        self._follow(check)
        if self._pending is None and check.ok and self._return():
            return self._confirm()
        return check

    def _return(self) -> bool:
        """Go back to the configuration a failure left, when ``preference`` says it is time."""
        unavailable = self.unusable | set(self._restarts.held)
        args = self.library, self.schema, self.current, unavailable
        found = self._prefer.returning(*args) or self._prefer.better(*args)
        if found is None:
            return False
        self._pending = time.monotonic()
        return self._switch(*found)

    def _follow(self, check: Conformance) -> None:
        """Confirm a repair made since the last replan, by rosreconf or by a person."""
        if self._pending is None:
            return
        if check.ok:
            self._conformant(check, time.monotonic() - self._pending, "since the failure")
        else:
            self._actuator.left_running(check)

    def _conformant(self, check: Conformance, took: float, since: str) -> None:
        self._seen |= set(self.current.components)
        self._running = True  # "conformant" says it
        self._pending = None
        self._lifecycle.said.clear()
        self._say(
            "conformant",
            f"the live system conforms to the configuration ({took:.1f} s {since})",
            seconds=round(took, 3),
            configuration=self.current.shown,
            task=self.schema.name,
            **checked(check),
        )
        self._actuator.settled(self.current, self.failed)

    def _check_restart(self) -> None:
        """Notice a restarted master, and start over from what the new one lists."""
        said = self.source.restarted()
        if said is None:
            return
        self._say("master-restarted", said[0], **said[1])
        self._actuator.restart(stop=self.options.apply)
        self._seen.clear()
        self._missing = Missing()
        self._running = False

    def _role(self, comp: str) -> str:
        return next(r for r, c in self.current.assignment if c == comp)

    def _say(self, kind: str, message: str, **data: Any) -> None:
        event = Event(kind, message, data)
        self.log(event)
        self._show(event)

    def _show(self, event: Event | None = None) -> None:
        """Show the faces ``event`` and the state now (``tasks.Tasks.show``)."""
        args = self.library, self.schema, self.current, self.unusable, self._seen
        states = self.context.states() if self.context is not None else []
        self.tasks.show(*args, event, context=states)

    def _retask(self) -> bool:
        """Switch task when asked (``rosreconf.ros.tasks``): decided, said, then applied as
        a replan is. True if something changed (to be confirmed)."""
        task = self.tasks.take(self._say)
        if task is None:
            return False
        args = self.library, task, self.current, self.schema, self.unusable, self._say
        found = self.tasks.decide(*args, self.options.apply)
        if found is None:
            return False
        self.schema, new, changes = found
        self._actuator.retask(self.schema)
        self._outsiders.schema = self.schema
        self._hopeless, self._prefer.preferred = None, None
        self._pending = time.monotonic()
        return self._switch(new, changes) or self.options.apply

    def _release(self) -> bool:
        """Restart the components whose backoff is over (``Restarts.last_resort``); make held
        components whose hold is over candidates again, and start those in service when no
        configuration was left without them. True if something was started.
        """
        inside = set(self.current.components)
        due = self._restarts.due() & self.failed & inside
        back = self._restarts.released() & self.failed
        self.failed -= back
        if self.options.apply and not (self.failed - due) & inside:
            due |= back & inside  # no configuration was left without them: tried again
        return self._restart(due, "restarted in place after its backoff or hold")

    def _restart(self, components: Collection[str], why: str) -> bool:
        """Start failed ``components`` of the configuration again, in place."""
        if not components:
            return False
        self.failed -= set(components)
        self._seen -= set(components)
        self._pending = self._pending or time.monotonic()
        return self._start(sorted(components), why)

    def _replan(self) -> bool:
        """Restart failed components in place where allowed (``restarts``); else find the
        minimal-change configuration without the failed and ruled-out components, and apply
        it. With none left, restart the failed ones in place all the same, backing off
        (``Restarts.last_resort``); ruled-out ones keep running (nothing better is left).
        """
        inside = set(self.current.components)
        failing = self.failed & inside
        apply = self.options.apply
        again = self._restarts.restartable(failing, apply)
        started = self._restart(again, "restarted in place")
        if not failing - again and not set(self._ruled) & inside:
            return started
        failed = frozenset(self.unusable)
        found = None
        if failed != self._hopeless:  # the same failures: the same answer, said already
            budget = self.options.budget
            args = self.library, self.schema, self.current, failed, self._say
            found = replan(*args, budget, self._ruled)
        if found is None:
            self._hopeless = failed
            now = self._restarts.last_resort(failing - again, apply, self._actuator.theirs())
            return (
                self._restart(now, "restarted in place: no configuration is left without it")
                or started
            )
        self._restarts.hold_failed(failing - again, apply)
        new, changes = found
        self._prefer.leaving(self.current)
        if self._pending is None:
            self._pending = time.monotonic()
        return self._switch(new, changes)

    def _switch(self, new: Configuration, changes: list[Change]) -> bool:
        """Make ``new`` the configuration; with ``apply``, start and retire as ``changes`` say."""
        if not self.options.apply:
            self.current = new
            return False
        started = self._actuator.replace(changes, new, self.failed, self._live)
        self.current = new
        self._seen -= {a for _, a, _ in changes}
        return started

    def _start(self, components: Collection[str], why: str) -> bool:
        """Start ``components`` (or say what would run); True if something was done."""
        return self._actuator.start(self.current, components, why)

    def _confirm(self) -> Conformance:
        """Wait until the live graph conforms or ``settle`` passes; log which.

        A read caught half-announced (``UnsettledGraphError``) is no answer yet: the nodes
        just started are announcing themselves, slowly on a loaded host. The wait goes on; the
        error is raised only when the settle ends on one (``polling`` says it if it lasts).
        """
        start = time.monotonic()
        while True:
            self._own_exits(tend=False)
            ended = self._actuator.ended()
            try:
                check = self._compare(self._read())
            except UnsettledGraphError:
                if self.stop_requested() and self._graph is not None:
                    return self._compare(self._graph)  # the last whole read
                if time.monotonic() - start > self.options.settle or ended:
                    raise
                time.sleep(0.1)
                continue
            self.failed |= self._clashes.failed(check, self._actuator.started(), self.failed)
            took = time.monotonic() - start
            if check.ok:
                self._conformant(check, took, "after the change")
                return check
            if (
                self.stop_requested()
                or self.failed & set(self.current.components)
                or self._clashes.freed  # a squatter stopped: its component starts next poll
                or self._actuator.left_running(check)
            ):
                return check
            if took > self.options.settle or ended:
                first = "; ".join(f.message for f in check.findings[:3])
                why = "roslaunch has exited" if ended else f"after {took:.0f} s"
                self._say(
                    "not-conformant",
                    f"still not conformant ({why}): {first}",
                    findings=[f.message for f in check.findings],
                )
                return check
            time.sleep(0.1)

    def close(self) -> None:
        """Stop every roslaunch and node process this watcher started, and what they run."""
        self._actuator.close()
        self.source.close()

    def has_read(self) -> bool:
        """Tell whether a read of the live graph has succeeded (``polling`` retries after it)."""
        return self._graph is not None

    def replan_due(self) -> bool:
        """Tell whether a failure waits for a replan, or a freed component to start: poll now.

        Not one held, or waiting out a restart's backoff: its time is ``due_at``.
        """
        waiting = {*self._restarts.held, *self._restarts.backoff}
        failing = (self.failed & set(self.current.components)) - waiting
        return bool(failing or self._clashes.freed)

    def exited(self) -> bool:
        """Tell whether a watched process ended or hung, or a task switch waits: step now."""
        return self._actuator.exited() or self.tasks.waiting()

    def due_at(self) -> float | None:
        """Return when a restart waiting out its backoff is due, or a context dwell ends or a
        topic falls silent (monotonic seconds), if ever."""
        dues = [self._restarts.next_due(), self.context.next_due() if self.context else None]
        return min((d for d in dues if d is not None), default=None)
