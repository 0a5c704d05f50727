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
from rosreconf.procs import Background, stop_all
from rosreconf.ros.conformance import Conformance, compare, node_live_name
from rosreconf.ros.launchfiles import RosVersion, launch_file
from rosreconf.ros.rosmaster import purge_dead, read_live_graph, shutdown_node
from rosreconf.ros.standins import start_roslaunch, write_standin_package
from rosreconf.solve.running import nearest_valid
from rosreconf.solve.solver import why_not


@dataclass(frozen=True)
class Event:
    """One decision or observation, for people (``message``) and programs (``data``).

    Attributes:
        kind: ``started``, ``stopped``, ``failed``, ``purged``, ``replanned``, ``no-configuration``,
            ``stop``, ``launch``, ``conformant``, ``not-conformant``, ``missing``,
            ``master-lost``, ``master-back``.
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
        master_uri: the ROS master.
        library, schema: what the configuration is made of.
        current: the configuration that should run now (changes on replanning).
        workdir: a private directory for launch files, the stand-in package and logs.
        env: the environment roslaunch runs in.
        log: receives every ``Event``.
        apply: stop and start components, rather than only say what should change.
        stand_ins: launch stand-in nodes instead of the components' real executables.
        settle: seconds to wait for the live graph to conform after applying a change.
        failed: components known to have failed (sticky).
        launches: the roslaunch processes started, stopped by ``close``.
    """

    master_uri: str
    library: ComponentLibrary
    schema: InteroperabilitySchema
    current: Configuration
    workdir: Path
    env: Mapping[str, str]
    log: Callable[[Event], None]
    apply: bool = False
    stand_ins: bool = False
    settle: float = 30.0
    failed: set[str] = field(default_factory=set)
    launches: list[Background] = field(default_factory=list)
    _seen: set[str] = field(default_factory=set)
    _hopeless: frozenset[str] | None = None
    _missing: tuple[str, ...] = ()

    def step(self) -> Conformance:
        """Observe once, replan and apply if needed; return how the system conforms now."""
        graph = read_live_graph(self.master_uri)
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
        dead = [n.name for n in graph.nodes if not n.answered]
        if dead:
            purged = purge_dead(self.master_uri, graph, only=dead)
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
            if not self.apply and tuple(missing) != self._missing:
                self._missing = tuple(missing)
                self._say(
                    "missing",
                    f"not running: {', '.join(missing)} (use --apply to start)",
                    components=missing,
                )
            elif self.apply:
                self._start(missing, "not running yet")
                return self._confirm()
        return (
            check
            if not dead
            else compare(self.current, self.library, self.schema, read_live_graph(self.master_uri))
        )

    def _role(self, comp: str) -> str:
        return next(r for r, c in self.current.assignment if c == comp)

    def _say(self, kind: str, message: str, **data: Any) -> None:
        self.log(Event(kind, message, data))

    def _replan(self) -> bool:
        """Find the minimal-change configuration without the failed components; apply it."""
        failed = frozenset(self.failed)
        if failed == self._hopeless:
            return False
        new = nearest_valid(self.library, self.schema, failed, self.current)
        if new is None:
            why = why_not(self.library, self.schema, failed)
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
            f"{len(changes)} change(s), the fewest possible: {text}",
            failed=sorted(failed),
            configuration=new.mapping,
            changes=[{"role": r, "from": a, "to": b} for r, a, b in changes],
        )
        for line in explain_replan(
            self.library, self.schema, failed, old, new, fewest_changes=len(changes)
        ):
            self._say("why", line)
        if not self.apply:
            self.current = new
            return False
        graph = read_live_graph(self.master_uri)
        for role, old_comp, new_comp in changes:
            node = self.library[old_comp]
            uri = next((n.uri for n in graph.nodes if n.name == node_live_name(node)), None)
            if uri is not None and old_comp not in self.failed:
                shutdown_node(uri, f"rosreconf: {role} is now {new_comp}")
                self._say(
                    "stop",
                    f"stopped {old_comp} ({role}): replaced by {new_comp}",
                    component=old_comp,
                )
        self.current = new
        self._seen -= {a for _, a, _ in changes}
        self._start([b for _, _, b in changes], "new in the configuration")
        return True

    def _start(self, components: Collection[str], why: str) -> None:
        """Start ``components`` with one roslaunch process."""
        n = len(self.launches) + 1
        launch = self.workdir / f"step{n}.launch"
        text = launch_file(
            self.library,
            self.schema,
            self.current,
            RosVersion.ROS1,
            only=components,
            stand_ins=self.stand_ins,
        ).text
        launch.write_text(text, encoding="utf-8")
        pkg = write_standin_package(self.workdir / "pkg") if self.stand_ins else None
        self.launches.append(start_roslaunch(launch, self.env, package_path=pkg))
        how = "stand-ins of " if self.stand_ins else ""
        self._say(
            "launch",
            f"roslaunch started {how}{', '.join(components)} ({why})",
            components=list(components),
            launch_file=str(launch),
        )

    def _confirm(self) -> Conformance:
        """Wait until the live graph conforms or ``settle`` passes; log which."""
        start = time.monotonic()
        while True:
            check = compare(
                self.current, self.library, self.schema, read_live_graph(self.master_uri)
            )
            took = time.monotonic() - start
            if check.ok:
                self._seen |= set(self.current.components)
                self._say(
                    "conformant",
                    f"the live system conforms to the configuration "
                    f"({took:.1f} s after the change)",
                    seconds=round(took, 3),
                    configuration=self.current.mapping,
                )
                return check
            if took > self.settle:
                first = "; ".join(f.message for f in check.findings[:3])
                self._say(
                    "not-conformant",
                    f"still not conformant after {took:.0f} s: {first}",
                    findings=[f.message for f in check.findings],
                )
                return check
            time.sleep(0.2)

    def close(self) -> None:
        """Stop every roslaunch this watcher started, and the nodes they run."""
        if self.launches:
            stop_all(self.launches)
            self._say("stopped", f"stopped the {len(self.launches)} roslaunch process(es) started")
        self.launches.clear()

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
