"""Keep a running ROS system in a valid configuration when its nodes die (the paper's use case).

"An operating autonomous system needs to self-reconfigure due to changes in own hardware":
each ``Watcher.step`` reads the master, decides which components have failed, replans with
the fewest changes (``rosreconf.solve.running.nearest_valid``, current configuration first),
and with ``apply`` stops the components that must go (their node API's ``shutdown``, as
``rosnode kill`` does) and starts the new ones with roslaunch (``rosreconf.ros.standins``), then
confirms with ``rosreconf.ros.conformance.compare``.

When a component counts as failed: it was given as failed, or its node is registered but
does not answer (SIGKILLed nodes linger in the master; they are then purged), or it was seen
alive by this watcher and is gone now. A component never seen is only *missing*: with
``apply`` it is started (so a watcher can also bring a configuration up); without, it is
only reported.

When the master restarts (its pid or roscore's ``/run_id`` changes), the new master lists
none of the nodes registered with the old one: ROS 1 nodes do not register again. That is
not every component failing: the watcher says the master restarted, forgets which components
it saw, and checks the graph again (with ``apply``, it stops its own roslaunch processes, whose
nodes the new master does not know, and starts the configuration again).

roslaunch's own errors (a package that does not exist, a node that cannot start) are read
from its output while the watcher waits, and handed on, escaped, with the paths of the launch
file and of that output; both are kept in ``launch_dir`` (``rosreconf.ros.launcher`` owns the
launch processes). A component that was launched and never came up is not launched again on
every poll.

Every decision is an ``Event`` handed to the ``log`` callback; nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.planning.narrative import explain_replan
from rosreconf.procs import Background
from rosreconf.ros.conformance import Conformance, compare, node_live_name
from rosreconf.ros.launcher import Launcher
from rosreconf.ros.launchfiles import RosVersion
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.rosmaster import known_identity, restarted
from rosreconf.ros.sources import LiveSource, lifecycle_steps
from rosreconf.solve.running import nearest_valid
from rosreconf.solve.search import Budget
from rosreconf.solve.solver import why_not


@dataclass(frozen=True)
class Event:
    """One decision or observation, for people (``message``) and programs (``data``).

    Attributes:
        kind: ``started``, ``running`` (once: every component seen alive), ``stopped``,
            ``failed``, ``purged``, ``replanned``, ``why``, ``no-configuration``, ``stop``,
            ``launch``, ``would-launch`` (no launcher here), ``lifecycle`` (ROS 2 managed
            nodes), ``launch-error``, ``launch-exited``, ``conformant``, ``not-conformant``,
            ``missing``, ``master-lost``, ``master-back``, ``master-restarted``, ``kept``.
        message: what happened and why, in plain words.
        data: details for the JSON log (component names, configurations, seconds).
        time: when (UTC).
    """

    kind: str
    message: str
    data: Mapping[str, Any] = field(default_factory=dict)
    time: datetime = field(default_factory=lambda: datetime.now(UTC))


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
        apply: stop and start components, rather than only say what should change.
        stand_ins: launch stand-in nodes instead of the components' real executables.
        settle: seconds to wait for the live graph to conform after applying a change.
        launch_dir: where launch files and roslaunch's output go, kept after the watcher
            ends (default: ``workdir``).
        failed: components known to have failed (sticky).
        budget: how far to search for a configuration that meets the performance
            requirements when the fewest-change one does not (``analysis.choice``).
    """

    source: LiveSource
    library: ComponentLibrary
    schema: InteroperabilitySchema
    current: Configuration
    workdir: Path
    env: Mapping[str, str]
    log: Callable[[Event], None]
    apply: bool = False
    stand_ins: bool = False
    settle: float = 30.0
    launch_dir: Path | None = None
    failed: set[str] = field(default_factory=set)
    budget: Budget | None = None
    _seen: set[str] = field(default_factory=set)
    _hopeless: frozenset[str] | None = None
    _missing: tuple[str, ...] = ()
    _master: tuple[int | None, str | None] | None = None
    _running: bool = False
    _launcher: Launcher = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._launcher = Launcher(
            self.source, self.library, self.schema, self.workdir, self.env, self._say,
            stand_ins=self.stand_ins, launch_dir=self.launch_dir,
        )  # fmt: skip

    @property
    def launches(self) -> list[Background]:
        """Return the roslaunch processes started and not yet stopped (``close`` stops them)."""
        return self._launcher.launches

    def _read(self) -> LiveGraph:
        return self.source.read()

    def step(self) -> Conformance:
        """Observe once, replan and apply if needed; return how the system conforms now."""
        self._check_master()
        self._launcher.check()
        graph = self._read()
        check = compare(self.current, self.library, self.schema, graph)
        missing = []
        for comp in self.current.components:
            codes = {f.code for f in check.findings if f.component == comp}
            if "dead-node" in codes or ("missing-node" in codes and comp in self._seen):
                if comp not in self.failed:
                    why = "registered but not answering" if "dead-node" in codes else "gone"
                    self._say(
                        "failed", f"{comp} ({self._role(comp)}) is {why}: failed", component=comp
                    )
                    self.failed.add(comp)
            elif "missing-node" in codes:
                missing.append(comp)
            else:
                self._seen.add(comp)
        if not self._running and self._seen >= set(self.current.components):
            self._running = True
            self._say(
                "running",
                f"all {len(self.current.components)} components of the configuration run",
                components=list(self.current.components),
            )
        dead = [n.name for n in graph.nodes if not n.answered]
        if dead:
            purged = self.source.purge(graph, dead)
            if purged:
                self._say(
                    "purged",
                    f"unregistered dead node(s) {', '.join(purged)} from the master",
                    nodes=list(purged),
                )
        if self.failed & set(self.current.components):
            if self._replan():
                return self._confirm()
        elif missing:
            # What was launched and never came up is not launched again on every poll.
            stuck = [c for c in missing if c in self._launcher.launched] if self.apply else missing
            if stuck and tuple(stuck) != self._missing:
                self._missing = tuple(stuck)
                if not self.apply:
                    why = "use --apply to start"
                elif self.launches:
                    why = f"launched but not running (see the launch output in {self._where})"
                else:
                    why = f"no launcher here: the launch file is in {self._where}"
                self._say("missing", f"not running: {', '.join(stuck)} ({why})", components=stuck)
            fresh = [c for c in missing if c not in stuck]
            if fresh and self._start(fresh, "not running yet"):
                return self._confirm()
        return check if not dead else compare(self.current, self.library, self.schema, self._read())

    def _check_master(self) -> None:
        """Notice a restarted master, and start over from what the new one lists."""
        now = self.source.identity()
        before, self._master = self._master, known_identity(self._master, now)
        if before is None or now is None or not restarted(before, now):
            return
        what = f"pid {before[0]} -> {now[0]}" if before[0] != now[0] else "new /run_id"
        self._say(
            "master-restarted",
            f"the ROS master restarted ({what}): it lists none of the nodes registered with "
            "the old one (ROS 1 nodes do not register again), so nothing is counted as "
            "failed; checking the graph against the configuration again",
            old_pid=before[0],
            new_pid=now[0],
            old_run_id=before[1],
            new_run_id=now[1],
        )
        if self.apply and self.launches:
            n = self._launcher.stop()
            self._say(
                "stopped",
                f"stopped the {n} roslaunch process(es) started with the old master, "
                "to start their nodes again with the new one",
            )
        self._seen.clear()
        self._launcher.launched.clear()
        self._missing = ()
        self._running = False

    @property
    def _where(self) -> Path:
        return self._launcher.directory

    def _role(self, comp: str) -> str:
        return next(r for r, c in self.current.assignment if c == comp)

    def _say(self, kind: str, message: str, **data: Any) -> None:
        self.log(Event(kind, message, data))

    def _performing(
        self, fewest: Configuration, failed: frozenset[str]
    ) -> tuple[Configuration | None, str]:
        """Return the configuration that meets the schema's performance requirements.

        Says so when the fewest-change configuration was passed over for failing them.
        """
        from rosreconf.analysis.choice import SearchExhausted, choose, shortfall  # numpy

        try:
            mapping, budget = self.current.mapping, self.budget
            choice = choose(self.library, self.schema, fewest, mapping, {}, failed, budget=budget)
        except SearchExhausted as exc:
            return None, str(exc)
        if choice.passed_over is not None and choice.passed_over_performance is not None:
            self._say(
                "passed-over",
                "the fewest-change configuration fails the performance requirements "
                f"({shortfall(self.schema, choice.passed_over_performance)}): passed over",
                configuration=choice.passed_over.mapping,
            )
        if choice.configuration is None:
            return None, (
                "every valid configuration fails the schema's performance requirements "
                f"({choice.tried} simulated to prove it)"
            )
        return choice.configuration, ""

    def _replan(self) -> bool:
        """Find the minimal-change configuration without the failed components; apply it."""
        failed = frozenset(self.failed)
        if failed == self._hopeless:
            return False
        new = nearest_valid(self.library, self.schema, failed, self.current)
        why = why_not(self.library, self.schema, failed) if new is None else ""
        fewest = "the fewest possible (exact optimum)"
        if new is not None and self.schema.simulation is not None:
            nearest = new
            new, why = self._performing(new, failed)
            if new is not None and new != nearest:
                fewest = (
                    "the fewest among the configurations that meet the performance requirements"
                )
        if new is None:
            self._say(
                "no-configuration",
                f"no valid configuration without {', '.join(sorted(failed))}: {why}",
                failed=sorted(failed),
            )
            self._hopeless = failed
            return False
        old = self.current.mapping
        changes = [(r, old[r], c) for r, c in new.assignment if old.get(r) != c]
        text = "; ".join(f"{r}: {a} -> {b}" for r, a, b in changes)
        self._say(
            "replanned",
            f"replanned without {', '.join(sorted(failed))}: "
            f"{len(changes)} change(s), {fewest}: {text}",
            failed=sorted(failed),
            configuration=new.mapping,
            changes=[{"role": r, "from": a, "to": b} for r, a, b in changes],
        )
        # best_configuration is the exact optimum of the change count, so it is the fewest by
        # proof; passing len(changes) as "fewest" would only compare a number with itself.
        for line in explain_replan(self.library, self.schema, failed, old, new):
            self._say("why", line)
        if not self.apply:
            self.current = new
            return False
        graph = self._read()
        for role, old_comp, new_comp in changes:
            self._lifecycle(old_comp, new_comp, role)
            name = node_live_name(self.library[old_comp])
            alive = any(n.name == name for n in graph.nodes)
            reason = f"rosreconf: {role} is now {new_comp}"
            if alive and old_comp not in self.failed and self.source.stop(graph, name, reason):
                self._say(
                    "stop",
                    f"stopped {old_comp} ({role}): replaced by {new_comp}",
                    component=old_comp,
                )
        self.current = new
        self._seen -= {a for _, a, _ in changes}
        return self._start([b for _, _, b in changes], "new in the configuration")

    def _lifecycle(self, old_comp: str, new_comp: str, role: str) -> None:
        """List the lifecycle transitions swapping managed nodes (ROS 2 ``ros.lifecycle``)."""
        if self.source.ros_version is not RosVersion.ROS2:
            return
        steps: list[str] = []
        for comp, stop in ((old_comp, True), (new_comp, False)):
            launch = self.library[comp].launch
            if launch is not None and launch.lifecycle:
                steps += lifecycle_steps(node_live_name(self.library[comp]), stop=stop)
        if steps:
            self._say(
                "lifecycle",
                f"{role}: lifecycle transitions {old_comp} -> {new_comp}: {'; '.join(steps)}",
                role=role,
                transitions=steps,
            )

    def _start(self, components: Collection[str], why: str) -> bool:
        """Start ``components`` with one launch process (or say what would run); True if run."""
        return self._launcher.start(self.current, components, why)

    def _confirm(self) -> Conformance:
        """Wait until the live graph conforms or ``settle`` passes; log which."""
        start = time.monotonic()
        while True:
            ended = self._launcher.check()
            check = compare(self.current, self.library, self.schema, self._read())
            took = time.monotonic() - start
            if check.ok:
                self._seen |= set(self.current.components)
                self._running = True  # "conformant" says it
                self._say(
                    "conformant",
                    f"the live system conforms to the configuration "
                    f"({took:.1f} s after the change)",
                    seconds=round(took, 3),
                    configuration=self.current.mapping,
                )
                return check
            if took > self.settle or ended:
                first = "; ".join(f.message for f in check.findings[:3])
                why = "roslaunch has exited" if ended else f"after {took:.0f} s"
                self._say(
                    "not-conformant",
                    f"still not conformant ({why}): {first}",
                    findings=[f.message for f in check.findings],
                )
                return check
            time.sleep(0.2)

    def close(self) -> None:
        """Stop every roslaunch this watcher started, and the nodes they run."""
        self._launcher.close()
        self.source.close()

    def run(self, interval: float, *, once: bool = False) -> Conformance:
        """Poll every ``interval`` seconds until interrupted; with ``once``, poll once and return.

        At the start a master that does not answer is an error (a wrong URI should fail
        fast); later, a restarting master is waited for, with one event when it goes and
        one when it is back.

        Raises:
            ExternalToolError: the master does not answer the first poll (or, with ``once``,
                any poll).
        """
        started = False
        lost_at: float | None = None
        while True:
            try:
                check = self.step()
            except ExternalToolError as exc:
                if not started or once:
                    raise
                if lost_at is None:
                    lost_at = time.monotonic()
                    self._say("master-lost", f"{exc}; retrying every {interval:g} s")
                time.sleep(interval)
                continue
            started = True
            if lost_at is not None:
                gone = time.monotonic() - lost_at
                self._say("master-back", f"the master answers again after {gone:.1f} s")
                lost_at = None
            if once:
                return check
            time.sleep(interval)
