"""Start real ROS 2 nodes (rclpy over Fast DDS, tests/ros2_node.py) on a private domain.

Each distribution has its own venv (``make ros2-venvs``: .venv-ros2-jazzy, .venv-ros2-kilted);
a node process runs with that venv's python, never with rosreconf's (the ROS 2 wheels
re-execute their interpreter with their own library path). Every process is one rclpy
context, one DDS participant; the tests start one process per node, except where a test
says otherwise. A missing venv is a failure ("run make ros2-venvs"), never a skip.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
from ros2_harness import free_domain, release, start_ready

ROOT = Path(__file__).resolve().parent.parent
NODE = Path(__file__).with_name("ros2_node.py")
DISTROS = ("jazzy", "kilted")
START_TIMEOUT = 60.0


def python_of(distro: str) -> Path:
    """Return the python of ``distro``'s venv, failing the test when it is not there."""
    python = ROOT / f".venv-ros2-{distro}" / "bin" / "python"
    if not python.exists():
        pytest.fail(f"{python} is missing: run make ros2-venvs (make test does)")
    return python


def node_env(domain: int, home: Path) -> dict[str, str]:
    """Return a ROS 2 node's environment: its domain, a home and log folder of its own."""
    keep = ("PATH", "LANG", "LC_ALL", "TMPDIR", "FASTDDS_BUILTIN_TRANSPORTS")  # conftest.py
    env = {k: v for k, v in os.environ.items() if k in keep}
    home.mkdir(parents=True, exist_ok=True)
    env.update(HOME=str(home), ROS_LOG_DIR=str(home / "log"), ROS_DOMAIN_ID=str(domain))
    return env


@dataclass
class Process:
    """One node process (one rclpy context holding the spec's nodes)."""

    process: subprocess.Popen[bytes]
    nodes: list[dict[str, Any]]


@dataclass
class Ros2System:
    """Real ROS 2 node processes of one distribution on one domain."""

    distro: str
    domain: int
    tmp: Path
    processes: list[Process]
    holds_domain: bool = field(default=False, kw_only=True)
    """True when this system took its domain (``on_a_free_domain``): ``stop`` gives it back."""

    @classmethod
    def on_a_free_domain(cls, distro: str, tmp: Path) -> Ros2System:
        """Return an empty system on a domain it holds until ``stop`` (a module may keep it)."""
        return cls(distro, free_domain(), tmp, [], holds_domain=True)

    def start(self, *nodes: dict[str, Any]) -> Process:
        """Start one process holding ``nodes``; return once it says ``ready``."""
        n = len(self.processes)
        spec = self.tmp / f"node-{n}.json"
        spec.write_text(json.dumps({"nodes": list(nodes)}), encoding="utf-8")
        argv = [str(python_of(self.distro)), str(NODE), str(spec)]
        env = node_env(self.domain, self.tmp / "home")
        proc = start_ready(argv, self.tmp / f"node-{n}.err", env, "ROS 2 node", START_TIMEOUT)
        started = Process(proc, list(nodes))
        self.processes.append(started)
        return started

    def rclpy_graph(self, at_least: int, seconds: float = 60.0) -> dict[str, Any]:
        """Return rclpy's own view of the graph (``ros2_node.py --graph``)."""
        out = subprocess.run(
            [str(python_of(self.distro)), str(NODE), "--graph", str(at_least), str(seconds)],
            capture_output=True,
            env=node_env(self.domain, self.tmp / "home"),
            timeout=seconds + 30,
            check=True,
        )
        return dict(json.loads(out.stdout.decode().strip().splitlines()[-1]))

    def stop(self) -> None:
        """Stop every process (SIGTERM: the participant says goodbye; SIGKILL after 10 s)."""
        stop_all(p.process for p in self.processes)
        self.processes.clear()
        if self.holds_domain:
            release(self.domain)


def stop_all(processes: Iterable[subprocess.Popen[bytes]]) -> None:
    """Stop processes (SIGTERM, then SIGKILL after 10 s) and reap them."""
    live = [p for p in processes if p.poll() is None]
    for p in live:
        p.send_signal(signal.SIGTERM)
    deadline = time.monotonic() + 10
    for p in live:
        try:
            p.wait(max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait(5)
    for p in live:
        if p.stdout is not None:
            p.stdout.close()
