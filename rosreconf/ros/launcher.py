"""Act on a system through launch files: roslaunch (or ``ros2 launch``), and follow what it says.

``Launcher`` writes one launch file per step, runs it through its ``LaunchPort`` (roslaunch,
``ros1.standins.Roslaunch``, or ``ros2 launch``, ``ros2.launching.Ros2LaunchPort``; or says
the command when there is no launcher here), and while the watcher waits it reads each launch
process's output for errors (escaped, with the paths of the launch file and of that output)
and notices when one exits. ``LaunchActuator`` is the watcher's ``Actuator`` over it: the
new components start from a launch file, and the replaced ones are stopped where the
middleware can stop a node (``stop_node``: a ROS 1 node API's ``shutdown``). Launch files
and output are kept in ``launch_dir`` (``launch_log_dir`` makes one next to ROS's own logs).
Every observation goes to the ``say`` callback; nothing here prints.
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import Protocol

from rosreconf.model import Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.printable import printable
from rosreconf.procs import Background, stop_all
from rosreconf.ros.actuator import Acting, Actuator
from rosreconf.ros.launchfiles import RosVersion, launch_file
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.replanning import Change

CLOSE_GRACE_SECONDS = 2.0
"""Seconds the launch processes get to stop their nodes when the watcher ends, before their
groups are killed. With ``stopped`` and ``kept`` said after it, this fits inside the CLI's
bounded stop (``rosreconf.cli.stopping``: the process ends 4 s after SIGTERM or SIGINT), as
ROS 2's SIGINT, SIGTERM, SIGKILL steps of 1 s do. It was ``stop_all``'s 5 s: a roslaunch
slow to stop (a loaded machine) then ended watch by the hard stop, before it said anything."""


class LaunchPort(Protocol):
    """How launch files are run on one middleware: the one thing a ``Launcher`` needs of it."""

    @property
    def ros_version(self) -> RosVersion:
        """Return which launch files this launcher runs."""
        ...

    def start(
        self, launch: Path, env: Mapping[str, str], stand_ins: Path | None
    ) -> Background | None:
        """Run ``launch`` as a process rosreconf owns; None when there is no launcher here.

        ``stand_ins``: a private directory where what stand-in nodes need can be written
        (None: the launch file starts no stand-ins).
        """
        ...

    def command(self, launch: Path) -> list[str]:
        """Return the command ``start`` runs for ``launch``."""
        ...


@dataclass
class Launcher:
    """Own the launch processes one watcher starts, from the first launch file to ``close``.

    Attributes:
        port: how launch files are run (``LaunchPort``).
        acting: what they are written from (the library, the schema, stand-ins or not),
            where they and their output go, what the launch processes run in, and who
            receives every event (``launch``, ``would-launch``, ``launch-error``,
            ``launch-exited``, ``stopped``, ``kept``).
        launches: the launch processes started and not yet stopped.
        launched: the components launched since the master (re)started.
        steps: how many launch files were written.
    """

    port: LaunchPort
    acting: Acting
    launches: list[Background] = field(default_factory=list)
    launched: set[str] = field(default_factory=set)
    steps: int = 0
    _exited: set[int] = field(default_factory=set)

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Start ``components`` of ``current`` with one launch process (or say what would run).

        Returns whether a process was started.
        """
        self.steps += 1
        a = self.acting
        a.directory.mkdir(parents=True, exist_ok=True)
        version = self.port.ros_version
        suffix = ".launch" if version is RosVersion.ROS1 else ".launch.xml"
        launch = a.directory / f"step{self.steps}{suffix}"
        text = launch_file(
            a.library,
            a.schema,
            current,
            version,
            only=components,
            stand_ins=a.options.stand_ins,
        ).text
        launch.write_text(text, encoding="utf-8")
        process = self.port.start(launch, a.env, a.workdir if a.options.stand_ins else None)
        self.launched |= set(components)
        command = " ".join(self.port.command(launch))
        if process is None:
            self.acting.say(
                "would-launch",
                f"no launcher here: would run '{command}' to start {', '.join(components)} "
                f"({why}); wrote {launch}",
                components=list(components),
                launch_file=str(launch),
                command=command,
            )
            return False
        self.launches.append(process)
        how = "stand-ins of " if a.options.stand_ins else ""
        launcher = "roslaunch" if version is RosVersion.ROS1 else "ros2 launch"
        self.acting.say(
            "launch",
            f"{launcher} started {how}{', '.join(components)} ({why})",
            components=list(components),
            launch_file=str(launch),
            output=str(launch.with_suffix(".log")),
        )
        return True

    def check(self) -> bool:
        """Hand on roslaunch's errors and exits; return whether the newest one has exited."""
        for launch in self.launches:
            files = self._files(launch)
            for line in error_lines(launch.new_output()):
                self.acting.say(
                    "launch-error", f"roslaunch: {line} ({files})", **self._paths(launch)
                )
            code = launch.poll()
            if code is not None and launch.process.pid not in self._exited:
                self._exited.add(launch.process.pid)
                self.acting.say(
                    "launch-exited",
                    f"roslaunch exited with code {code} ({files})",
                    returncode=code,
                    **self._paths(launch),
                )
        return bool(self.launches) and self.launches[-1].process.poll() is not None

    def stop(self, grace: float = 5.0) -> int:
        """Stop every launch process started, and the nodes they run; return how many.

        Each gets SIGINT (roslaunch then stops its nodes) and ``grace`` seconds, then its
        group is killed.
        """
        n = len(self.launches)
        if self.launches:
            stop_all(self.launches, grace)
        self.launches.clear()
        return n

    def restart(self, *, stop: bool) -> None:
        """Forget what was launched with a master that restarted (with ``stop``, stop it)."""
        if stop and self.launches:
            n = self.stop()
            self.acting.say(
                "stopped",
                f"stopped the {n} roslaunch process(es) started with the old master, "
                "to start their nodes again with the new one",
            )
        self.launched.clear()

    def close(self) -> None:
        """Stop every launch process, and say where the launch files are kept."""
        n = self.stop(CLOSE_GRACE_SECONDS)
        if n:
            self.acting.say("stopped", f"stopped the {n} roslaunch process(es) started")
        launch_dir = self.acting.options.launch_dir
        if self.steps and launch_dir is not None:
            self.acting.say(
                "kept",
                f"launch files and roslaunch's output are kept in {launch_dir}",
                launch_dir=str(launch_dir),
            )

    @staticmethod
    def _paths(launch: Background) -> dict[str, str]:
        log = launch.log or Path("?")
        return {"launch_file": str(log.with_suffix(".launch")), "output": str(log)}

    def _files(self, launch: Background) -> str:
        paths = self._paths(launch)
        return f"launch file {paths['launch_file']}, its output {paths['output']}"


@dataclass
class LaunchActuator(Actuator):
    """Start components from launch files; stop the replaced ones where a node can be stopped.

    A replan stops each live component it takes out or restarts (``stop_node``: ROS 1's
    actuator, ``ros1.source.MasterActuator``, calls the node API's ``shutdown``, as
    ``rosnode kill`` does), then one launch file starts the new ones, and a kept one that is
    rewired again (ROS names are fixed at start).
    """

    port: LaunchPort
    acting: Acting
    launcher: Launcher = field(init=False)
    _ended: bool = False

    def __post_init__(self) -> None:
        self.launcher = Launcher(self.port, self.acting)

    def retask(self, schema: InteroperabilitySchema) -> None:
        """Write the launch files of ``schema`` from now on (a task switch)."""
        self.acting = self.launcher.acting = replace(self.acting, schema=schema)

    def start(self, current: Configuration, components: Collection[str], why: str) -> bool:
        """Start ``components`` with one launch process (or say what would run)."""
        return self.launcher.start(current, components, why)

    def replace(
        self,
        changes: list[Change],
        new: Configuration,
        failed: Collection[str],
        graph: Callable[[bool], LiveGraph],
    ) -> bool:
        """Stop what ``changes`` takes out or restarts, then launch the new components."""
        self.stop_replaced(graph(True), changes, failed)
        return self.start(new, [b for _, _, b in changes if b], "new in the configuration")

    def stop_replaced(
        self, graph: LiveGraph, changes: list[Change], failed: Collection[str]
    ) -> None:
        """Stop each live component a replan takes out or restarts (``stop_node``).

        A kept component restarted to be rewired is stopped too: its launch file starts it
        again, wired (``stop`` event). Middlewares that cannot stop a node (ROS 2) stop none.
        """
        alive = {n.name for n in graph.nodes}
        for role, old_comp, new_comp in changes:
            if not old_comp or old_comp in failed:  # an empty optional role: nothing to stop
                continue
            name = node_live_name(self.acting.library[old_comp])
            restart = old_comp == new_comp  # to rewire it: ROS names are fixed at start
            reason = "rosreconf: " + (
                f"{role} is rewired" if restart else f"{role} is now {new_comp}"
            )
            if name in alive and self.stop_node(graph, name, reason):
                how = "to restart it rewired" if restart else f"replaced by {new_comp or '(empty)'}"
                self.acting.say("stop", f"stopped {old_comp} ({role}): {how}", component=old_comp)

    def stop_node(self, graph: LiveGraph, node: str, reason: str) -> bool:
        """Ask node ``node`` to shut down; return whether that was possible (here: never)."""
        return False

    def not_running(self, missing: list[str]) -> tuple[list[str], str]:
        """Return the launched ones of ``missing``; point at the launch output or file."""
        where = self.acting.directory
        if self.launcher.launches:
            why = f"launched but not running (see the launch output in {where})"
        else:
            why = f"no launcher here: the launch file is in {where}"
        return [c for c in missing if c in self.launcher.launched], why

    def exits(self, current: Configuration, failed: Collection[str], *, tend: bool) -> set[str]:
        """Hand on the launch processes' errors and exits (no node process is rosreconf's)."""
        self._ended = self.launcher.check()
        return set()

    def started(self) -> frozenset[str]:
        """Return the components launched here (their nodes are roslaunch's, not a clash)."""
        return frozenset(self.launcher.launched)

    def ended(self) -> bool:
        """Return whether the newest launch process has exited."""
        return self._ended

    def restart(self, *, stop: bool) -> None:
        """Forget what was launched with the old master (with ``stop``, stop it)."""
        self.launcher.restart(stop=stop)

    def close(self) -> None:
        """Stop every launch process, and say where the launch files are kept."""
        self.launcher.close()


_ERROR = re.compile(
    r"error|exception|cannot|not found|no such|failed|has died|traceback", re.IGNORECASE
)
_ESCAPES = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)?|\x1b.")
"""Terminal escape sequences (CSI colours, OSC window titles), which roslaunch writes."""


_LEVEL = re.compile(
    r"^(?:\[[^\]]*\]\s*)*?(?:\[\s*(DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\s*\]"
    r"|(DEBUG|INFO|WARN|WARNING|ERROR|FATAL):)"
)
"""A line's log level, as rospy (``[INFO] [t]: ...``), roscpp (``[ INFO] [t]: ...``) and
roslaunch (``ERROR: ...``) write it, after any ``[node-1]`` prefixes."""


def _is_error(line: str) -> bool:
    """Tell an error line: by its level when it has one, else by its words (``has died``)."""
    level = _LEVEL.match(line)
    if level is not None:
        return (level.group(1) or level.group(2)) in ("ERROR", "FATAL")
    return bool(_ERROR.search(line))


def error_lines(output: str, limit: int = 10) -> list[str]:
    """Return roslaunch's error lines from ``output``: escapes removed, the rest made printable.

    A line with a log level is an error only at ERROR or FATAL: an INFO line that mentions
    "error" or "not found" is no ``launch-error``.
    """
    lines = [printable(_ESCAPES.sub("", line).strip()) for line in output.splitlines()]
    return [line for line in lines if line and _is_error(line)][:limit]


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
