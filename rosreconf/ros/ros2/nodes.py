"""Run a configuration's ROS 2 nodes as processes rosreconf owns, without ``ros2 launch``.

Each component is one process, started as ``ros2 run`` would start it: its executable found
through the ament index (``rosreconf.ros.ros2.runtime.ament_executable``) with ``--ros-args``
naming the node, its namespace, its remappings and parameters
(``rosreconf.ros.launchfiles.ros2_node_arguments``); or, with stand-ins, rosreconf's rclpy
stand-in (``standin_node.py`` next to this module) under the ROS 2 Python. Every process is a
``rosreconf.procs.Background`` (a new session; on Linux a parent-death signal and a group
watchdog, so it dies with rosreconf even when rosreconf is SIGKILLed), with a short-lease
Fast DDS profile and its output in ``<directory>/<component>.log``.

Stand-ins are forked by one warm process that has imported rclpy already
(``rosreconf.ros.ros2.zygote``), which saves each about 0.5 s of CPU; ``ROSRECONF_STANDIN_ZYGOTE=0``
starts each as a process of its own instead, and so does a zygote that cannot start or dies: the
stand-ins of that very start still start (each alone), and the reason is kept in ``problems``
for the caller to say (a helper that hangs or talks garbage is named, not hidden).

Because rosreconf (or its zygote) is the parent, it sees a node's process exit at once
(``exited``; ``wait`` returns as soon as one does), long before DDS would. Stopping is SIGINT
(rclpy says goodbye and exits), then SIGTERM, then SIGKILL, each after ``grace`` seconds.
Nothing here prints.
"""

from __future__ import annotations

import json
import signal
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, Interface, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name, used_interfaces
from rosreconf.procs import start_program
from rosreconf.procs.ladder import climb, wait_all
from rosreconf.procs.signals import signal_group
from rosreconf.ros.launchfiles import Remap, ros2_node_arguments, wiring
from rosreconf.ros.ros2.runtime import (
    LEASE_SECONDS,
    ament_executable,
    lease_profile,
    node_env,
    own_participant_env,
    own_profile,
    ros2_python,
)
from rosreconf.ros.ros2.zygote import DISABLE_ENV, Zygote
from rosreconf.ros.standin_spec import ros2_standin_spec

STANDIN_SCRIPT = Path(__file__).parent / "scripts" / "standin_node.py"
GRACE_SECONDS = 1.0
"""Seconds between SIGINT, SIGTERM and SIGKILL when rosreconf stops a node's process."""


class Process(Protocol):
    """What is asked of a node's process: ``subprocess.Popen`` or a forked stand-in."""

    @property
    def pid(self) -> int:
        """The process id."""

    @property
    def returncode(self) -> int | None:
        """The exit status once known."""

    def poll(self) -> int | None:
        """Return the exit status, or None while it runs."""

    def wait(self, timeout: float | None = None) -> int:
        """Wait until it has ended (``subprocess.TimeoutExpired`` after ``timeout``)."""


class Program(Protocol):
    """A node's program: ``rosreconf.procs.Background`` or ``zygote.ForkedProgram``."""

    @property
    def process(self) -> Process:
        """The process."""

    def remember(self) -> None:
        """Record what it forked, for ``stop``."""

    def stop(self, grace: float = ..., sig: signal.Signals = ...) -> int:
        """Signal it, wait ``grace`` s, kill what is left; return the exit status."""


@dataclass
class OwnNode:
    """One node process rosreconf started.

    Attributes:
        component: the library component it runs.
        node: its global node name.
        program: the process (and what it forks).
        managed: a lifecycle node (taken in and out of service by transitions).
        argv: the command line, for the log.
        log: where its output goes (``<component>.log``, appended to by every run).
        log_from: the log's size when this run started: where its own output begins.
        ready: its node has been seen in the graph, or answered a lifecycle call; a
            process that exits before is said with the end of its log (``bringup``).
    """

    component: str
    node: str
    program: Program
    managed: bool
    argv: tuple[str, ...]
    log: Path | None = None
    log_from: int = 0
    ready: bool = False

    @property
    def pid(self) -> int:
        """Return the process id."""
        return self.program.process.pid


@dataclass
class NodeProcesses:
    """Own the node processes of one watcher, from the first start to ``close``.

    Attributes:
        env: the environment nodes run in (ROS_DOMAIN_ID set).
        directory: where each node's output goes (``<component>.log``) and the lease profile.
        stand_ins: run rosreconf's rclpy stand-in instead of each component's executable.
        lease: the participant lease, seconds, of the processes started here.
        nodes: component -> its running process.
        problems: what went wrong without stopping a start (the stand-in zygote failed, so
            stand-ins start on their own), each once, for the caller to say and clear.
        helpers: helper deaths seen (the stand-in zygote killed or crashed), each once, for
            the caller to say: never a component's failure (its stand-ins run on).
        stopping: told of the nodes ``stop`` is about to stop, before any signal: their
            processes' participants are still the graph's last read, and none started
            after (a node started anew under the same name) is among them.
    """

    env: Mapping[str, str]
    directory: Path
    stand_ins: bool = False
    lease: float = LEASE_SECONDS
    nodes: dict[str, OwnNode] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    helpers: list[str] = field(default_factory=list)
    stopping: Callable[[list[OwnNode]], None] = lambda _: None
    _profile: Path | None = None
    _zygote: Zygote | None = None
    _zygote_failed: bool = False

    def _node_env(self) -> dict[str, str]:
        if self._profile is None and self.stand_ins:  # rosreconf's own participants
            self._profile = own_profile(self.directory, self.lease)
        elif self._profile is None:
            self.directory.mkdir(parents=True, exist_ok=True)
            self._profile = self.directory / "fastdds-short-lease.xml"
            self._profile.write_text(lease_profile(self.lease), encoding="utf-8")
        env = node_env(self.env, self._profile)
        return own_participant_env(env) if self.stand_ins else env

    def command(
        self,
        library: ComponentLibrary,
        component: str,
        remaps: dict[str, list[Remap]],
        uses: Mapping[str, frozenset[Interface]],
    ) -> list[str]:
        """Return the command line that runs ``component``'s node, wired for a configuration.

        ``remaps`` (``launchfiles.wiring``) and ``uses`` (``model.wiring.used_interfaces``)
        are the configuration's: a stand-in acts out only the options it is wired to.

        Raises:
            ExternalToolError: no ROS 2 Python (stand-ins), or no such executable (exit 3).
        """
        args = ros2_node_arguments(library, component, remaps)
        comp = library[component]
        if self.stand_ins:
            spec = json.dumps(ros2_standin_spec(comp, uses.get(component, frozenset())))
            return [ros2_python(self.env), str(STANDIN_SCRIPT), spec, *args]
        launch = comp.launch
        assert launch is not None  # the watcher refuses components without a ros: entry
        program = ament_executable(launch.package, launch.executable, self.env)
        return [str(program), *launch.args, *args]

    def start(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        configuration: Configuration,
        components: Collection[str],
    ) -> list[OwnNode]:
        """Start one process per component (all before any is waited for); return them.

        Raises:
            ExternalToolError: a program is missing or cannot be run (those started stay).
        """
        env = self._node_env()
        runs = [
            (argv, self.directory / f"{name}.log")
            for name, argv in self.commands(library, schema, configuration, components).items()
        ]
        sizes = [log.stat().st_size if log.exists() else 0 for _, log in runs]
        started = []
        for name, (argv, log), size, program in zip(
            components, runs, sizes, self._start(runs, env), strict=True
        ):
            comp = library[name]
            managed = bool(comp.launch is not None and comp.launch.lifecycle)
            own = OwnNode(name, node_live_name(comp), program, managed, tuple(argv), log, size)
            self.nodes[name] = own
            started.append(own)
        return started

    def commands(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        configuration: Configuration,
        components: Collection[str],
    ) -> dict[str, list[str]]:
        """Return per component the command line that runs it wired for ``configuration``.

        Raises:
            ExternalToolError: as ``command``.
        """
        remaps = wiring(library, schema, configuration)
        uses = used_interfaces(library, schema, configuration.mapping)
        return {c: self.command(library, c, remaps, uses) for c in components}

    def miswired(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        configuration: Configuration,
        components: Collection[str],
    ) -> list[str]:
        """Return the components whose running process was started with other wiring.

        ROS names are fixed when a process starts: such a node must restart to be wired for
        ``configuration`` (a kept consumer whose providers changed, a standby started for
        another failure).
        """
        own = [c for c in components if c in self.nodes]
        wanted = self.commands(library, schema, configuration, own)
        return [c for c in own if tuple(wanted[c]) != self.nodes[c].argv]

    def _start(self, runs: list[tuple[list[str], Path]], env: Mapping[str, str]) -> list[Program]:
        """Start one process per (argv, log): forked by the zygote (stand-ins), else each alone."""
        zygote = self._warm(env) if self.stand_ins else None
        if zygote is not None:
            try:
                return list(zygote.spawn(runs))
            except ExternalToolError as exc:  # it died: from now on each stand-in starts alone
                self._zygote_broke(exc)
                for orphan in zygote.orphans:
                    orphan.stop(grace=0.0, sig=signal.SIGKILL)
        return [start_program(argv, log=log, env=env) for argv, log in runs]

    def _warm(self, env: Mapping[str, str]) -> Zygote | None:
        """Return the stand-in zygote, started on first use; None when it cannot be had.

        The zygote only saves CPU: one that fails to start must not keep the stand-ins it
        was to fork from starting (the robot would be left worse, and nothing retries them),
        so its reason goes to ``problems`` and they start on their own, now and from then on.
        """
        if self._zygote_failed or env.get(DISABLE_ENV) == "0":
            return None
        self._zygote_died()
        if self._zygote is None:
            try:
                self._zygote = Zygote(env, self.directory / "standin-zygote.log")
            except ExternalToolError as exc:
                self._zygote_broke(exc)
                return None
        return self._zygote

    def take_problems(self) -> list[str]:
        """Return what went wrong in the starts since the last call (each said once)."""
        problems, self.problems = self.problems, []
        return problems

    def _zygote_broke(self, exc: ExternalToolError) -> None:
        """Give up the zygote for good and keep, once, why (its message names the helper)."""
        self._zygote_failed = True
        self._zygote = None
        self.problems.append(f"{exc}; each stand-in starts on its own from now on")

    def _zygote_died(self) -> None:
        """Note a zygote that ended on its own; the next stand-in is forked by a new one."""
        zygote = self._zygote
        if zygote is None or zygote.died() is None:
            return
        self._zygote = None
        code = zygote.process.returncode
        zygote.close()  # its own watchdog; its children are in sessions of their own
        self.helpers.append(
            f"{zygote.name} (pid {zygote.process.pid}) exited ({code}): its stand-ins run on, "
            "and the next one is forked by a new zygote (a helper's death is no component's "
            "failure)"
        )

    def take_helpers(self) -> list[str]:
        """Return the helper deaths seen since the last call (each said once)."""
        self._zygote_died()
        helpers, self.helpers = self.helpers, []
        return helpers

    def exited(self, only: Collection[str] | None = None) -> list[tuple[OwnNode, int]]:
        """Return the nodes whose process has ended since the last call, with the exit status.

        ``only``: look at these components' processes alone (the others are told later).
        """
        ended = [
            (n, n.program.process.poll())
            for c, n in self.nodes.items()
            if only is None or c in only
        ]
        gone = [(n, code) for n, code in ended if code is not None]
        for own, _ in gone:
            del self.nodes[own.component]
            self._reap(own)
        return gone

    def any_exited(self) -> bool:
        """Tell whether a node's process has ended and ``exited`` has not said so yet."""
        return any(n.program.process.poll() is not None for n in self.nodes.values())

    def stop(self, components: Collection[str], grace: float = GRACE_SECONDS) -> list[OwnNode]:
        """Stop these components' processes: SIGINT, SIGTERM, SIGKILL, ``grace`` s apart.

        SIGINT and SIGTERM go to each running node's group; SIGKILL then goes to every
        group, ended or not (``_reap``), so nothing a node forked outlives it.
        """
        own = [self.nodes.pop(c) for c in components if c in self.nodes]
        if own:
            self.stopping(own)
        alive: list[OwnNode] = []

        def send(sig: signal.Signals) -> bool:
            alive[:] = [n for n in own if n.program.process.poll() is None]
            for n in alive:
                n.program.remember()
                signal_group(n.pid, sig)
                signal_group(n.pid, signal.SIGCONT)  # a stopped (hung) process acts on it
            return bool(alive)

        def gone(wait: float) -> bool:
            return wait_all([n.program.process for n in alive], wait)

        climb(send, gone, grace, (signal.SIGINT, signal.SIGTERM))
        for n in own:
            self._reap(n)
        return own

    @staticmethod
    def _reap(own: OwnNode) -> None:
        """Kill what is left of the node's group (SIGKILL) and release its watchdog."""
        own.program.stop(grace=0.0, sig=signal.SIGKILL)

    def close(self) -> list[OwnNode]:
        """Stop every node process started here, then the zygote; return the nodes."""
        stopped = self.stop(list(self.nodes))
        if self._zygote is not None:
            self._zygote.close()
            self._zygote = None
        return stopped
