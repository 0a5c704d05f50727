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
file and of that output; both are kept in ``launch_dir``. A component that was launched and
never came up is not launched again on every poll.

Every decision is an ``Event`` handed to the ``log`` callback; nothing here prints.
"""

from __future__ import annotations

import os
import re
import tempfile
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
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.rosmaster import (
    DEFAULT_MAX_BYTES,
    DEFAULT_TIMEOUT,
    master_identity,
    printable,
    purge_dead,
    read_live_graph,
    shutdown_node,
)
from rosreconf.ros.standins import start_roslaunch, write_standin_package
from rosreconf.solve.running import nearest_valid
from rosreconf.solve.solver import why_not


@dataclass(frozen=True)
class Event:
    """One decision or observation, for people (``message``) and programs (``data``).

    Attributes:
        kind: ``started``, ``stopped``, ``failed``, ``purged``, ``replanned``, ``no-configuration``,
            ``stop``, ``launch``, ``launch-error``, ``launch-exited``, ``conformant``,
            ``not-conformant``, ``missing``, ``master-lost``, ``master-back``,
            ``master-restarted``, ``kept``.
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
        workdir: a private directory for the stand-in package (removed by the caller).
        env: the environment roslaunch runs in.
        log: receives every ``Event``.
        apply: stop and start components, rather than only say what should change.
        stand_ins: launch stand-in nodes instead of the components' real executables.
        settle: seconds to wait for the live graph to conform after applying a change.
        timeout: each XML-RPC call's total deadline (seconds).
        max_bytes: the cap on each answer from the master.
        launch_dir: where launch files and roslaunch's output go, kept after the watcher
            ends (default: ``workdir``).
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
    timeout: float = DEFAULT_TIMEOUT
    max_bytes: int = DEFAULT_MAX_BYTES
    launch_dir: Path | None = None
    failed: set[str] = field(default_factory=set)
    launches: list[Background] = field(default_factory=list)
    _seen: set[str] = field(default_factory=set)
    _hopeless: frozenset[str] | None = None
    _missing: tuple[str, ...] = ()
    _master: tuple[int | None, str | None] | None = None
    _launched: set[str] = field(default_factory=set)
    _exited: set[int] = field(default_factory=set)
    _steps: int = 0

    def _read(self) -> LiveGraph:
        return read_live_graph(self.master_uri, timeout=self.timeout, max_bytes=self.max_bytes)

    def step(self) -> Conformance:
        """Observe once, replan and apply if needed; return how the system conforms now."""
        self._check_master()
        self._check_launches()
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
        dead = [n.name for n in graph.nodes if not n.answered]
        if dead:
            purged = purge_dead(
                self.master_uri, graph, only=dead, timeout=self.timeout, max_bytes=self.max_bytes
            )
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
            stuck = [c for c in missing if c in self._launched] if self.apply else missing
            if stuck and tuple(stuck) != self._missing:
                self._missing = tuple(stuck)
                why = (
                    f"launched but not running (see roslaunch's output in {self._dir()})"
                    if self.apply
                    else "use --apply to start"
                )
                self._say("missing", f"not running: {', '.join(stuck)} ({why})", components=stuck)
            fresh = [c for c in missing if c not in stuck]
            if fresh:
                self._start(fresh, "not running yet")
                return self._confirm()
        return check if not dead else compare(self.current, self.library, self.schema, self._read())

    def _check_master(self) -> None:
        """Notice a restarted master, and start over from what the new one lists."""
        now = master_identity(self.master_uri, timeout=self.timeout, max_bytes=self.max_bytes)
        before, self._master = self._master, now
        if before is None or before == now:
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
            n = len(self.launches)
            stop_all(self.launches)
            self.launches.clear()
            self._say(
                "stopped",
                f"stopped the {n} roslaunch process(es) started with the old master, "
                "to start their nodes again with the new one",
            )
        self._seen.clear()
        self._launched.clear()
        self._missing = ()

    def _dir(self) -> Path:
        return self.launch_dir if self.launch_dir is not None else self.workdir

    def _check_launches(self) -> bool:
        """Hand on roslaunch's errors and exits; return whether the newest one has exited."""
        for launch in self.launches:
            files = self._files(launch)
            for line in _error_lines(launch.new_output()):
                self._say("launch-error", f"roslaunch: {line} ({files})", **self._paths(launch))
            code = launch.poll()
            if code is not None and launch.process.pid not in self._exited:
                self._exited.add(launch.process.pid)
                self._say(
                    "launch-exited",
                    f"roslaunch exited with code {code} ({files})",
                    returncode=code,
                    **self._paths(launch),
                )
        return bool(self.launches) and self.launches[-1].process.poll() is not None

    @staticmethod
    def _paths(launch: Background) -> dict[str, str]:
        log = launch.log or Path("?")
        return {"launch_file": str(log.with_suffix(".launch")), "output": str(log)}

    def _files(self, launch: Background) -> str:
        paths = self._paths(launch)
        return f"launch file {paths['launch_file']}, its output {paths['output']}"

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
        from rosreconf.analysis.simulate import choose, shortfall  # imports python-control

        choice = choose(self.library, self.schema, fewest, self.current.mapping, {}, failed)
        if choice.passed_over is not None and choice.passed_over_performance is not None:
            self._say(
                "passed-over",
                "the fewest-change configuration fails the performance requirements "
                f"({shortfall(self.schema, choice.passed_over_performance)}): passed over",
                configuration=choice.passed_over.mapping,
            )
        if choice.configuration is None:
            return None, (
                f"every one of the {choice.valid} valid configuration(s) fails the schema's "
                "performance requirements"
            )
        return choice.configuration, ""

    def _replan(self) -> bool:
        """Find the minimal-change configuration without the failed components; apply it."""
        failed = frozenset(self.failed)
        if failed == self._hopeless:
            return False
        new = nearest_valid(self.library, self.schema, failed, self.current)
        why = why_not(self.library, self.schema, failed) if new is None else ""
        if new is not None and self.schema.simulation is not None:
            new, why = self._performing(new, failed)
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
            f"{len(changes)} change(s), the fewest possible (exact optimum): {text}",
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
            node = self.library[old_comp]
            uri = next((n.uri for n in graph.nodes if n.name == node_live_name(node)), None)
            if uri is not None and old_comp not in self.failed:
                shutdown_node(uri, f"rosreconf: {role} is now {new_comp}", timeout=self.timeout)
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
        self._steps += 1
        self._dir().mkdir(parents=True, exist_ok=True)
        launch = self._dir() / f"step{self._steps}.launch"
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
        self._launched |= set(components)
        how = "stand-ins of " if self.stand_ins else ""
        self._say(
            "launch",
            f"roslaunch started {how}{', '.join(components)} ({why})",
            components=list(components),
            launch_file=str(launch),
            output=str(launch.with_suffix(".log")),
        )

    def _confirm(self) -> Conformance:
        """Wait until the live graph conforms or ``settle`` passes; log which."""
        start = time.monotonic()
        while True:
            ended = self._check_launches()
            check = compare(self.current, self.library, self.schema, self._read())
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
        if self.launches:
            stop_all(self.launches)
            self._say("stopped", f"stopped the {len(self.launches)} roslaunch process(es) started")
        self.launches.clear()
        if self._steps and self.launch_dir is not None:
            self._say(
                "kept",
                f"launch files and roslaunch's output are kept in {self.launch_dir}",
                launch_dir=str(self.launch_dir),
            )

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


_ERROR = re.compile(
    r"error|exception|cannot|not found|no such|failed|has died|traceback", re.IGNORECASE
)
_ESCAPES = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)?|\x1b.")
"""Terminal escape sequences (CSI colours, OSC window titles), which roslaunch writes."""


def _error_lines(output: str, limit: int = 10) -> list[str]:
    """Return roslaunch's error lines from ``output``: escapes removed, the rest made printable."""
    lines = [printable(_ESCAPES.sub("", line).strip()) for line in output.splitlines()]
    return [line for line in lines if line and _ERROR.search(line)][:limit]


def launch_log_dir(env: Mapping[str, str]) -> Path:
    """Make a new directory for launch files and roslaunch's output, next to ROS's own logs.

    ROS keeps its logs in ``$ROS_LOG_DIR``, else ``$ROS_HOME/log``, else ``~/.ros/log``;
    the directory made there (``rosreconf-watch-<UTC time>-<random>``) is never an existing
    one, so nothing of the user's is overwritten.

    Raises:
        OSError: the directory cannot be made.
    """
    if env.get("ROS_LOG_DIR"):
        base = Path(env["ROS_LOG_DIR"])
    elif env.get("ROS_HOME"):
        base = Path(env["ROS_HOME"]) / "log"
    else:
        base = Path(os.path.expanduser("~")) / ".ros" / "log"
    base.mkdir(parents=True, exist_ok=True)
    stamp = datetime.now(UTC).strftime("%Y%m%dT%H%M%SZ")
    return Path(tempfile.mkdtemp(prefix=f"rosreconf-watch-{stamp}-", dir=base))
