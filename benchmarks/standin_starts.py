"""Start rclpy stand-ins over and over as ``watch`` starts them; count the crashes, time them.

It acts out the bundled example's elbow failover again and again, through rosreconf's own
``NodeProcesses`` (the stand-ins forked by the stand-in zygote; with ``--alone`` each a
process of its own, as ``ROSRECONF_STANDIN_ZYGOTE=0`` starts them): the nominal
configuration of ``object_repositioning`` (13 stand-ins) is started, then each round
switches to the other arm as a repair does: the reasoner NREA is stopped, the 10 stand-ins
of the other arm (and NREA, rewired) are asked for at once, and right after, the 9 of the
arm left are stopped with SIGINT while the new ones start (the camera, gripper sensor and
perception run on throughout). So every start meets what a real repair's meets: peers
running, peers leaving, peers joining. Rounds alternate between the two arms.

A stand-in that ends before it says it is ready (its ``{"ready": ...}`` line in its log), is
ended by a signal other than the SIGKILL of a stop past its grace, or leaves
``Fatal Python error`` in its log is a crash; its log is kept (``--keep``). Per stand-in,
from the request to its ready line: wall seconds, and the CPU seconds its process had spent
by then (utime + stime of ``/proc/<pid>/stat``, read when its ready line is seen: 10 ms
ticks; a forked stand-in's count starts at the fork, an exec'd one's at its exec). The first
round's times are left out: they include the zygote's own start.

    python benchmarks/standin_starts.py --distro kilted --starts 2000
    python benchmarks/standin_starts.py --distro jazzy --starts 200 --alone

Runs on a DDS domain of its own (the tests' host-wide domain locks), with the environment
``watch`` gives its stand-ins (short-lease profile, UDP only). Prints a summary (JSON) on
stdout, one line per round on stderr with ``--verbose``; exit 1 if any stand-in crashed.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))  # the test harness's domain locks
READY_TIMEOUT = 120.0
"""Seconds a stand-in may take to say it is ready (ten at once on a loaded 2-core host)."""
TICK = os.sysconf("SC_CLK_TCK")
OTHER_ARM = {"NSM1": "NDC1", "NSM2": "NDC2", "NSM3": "NDC3", "NSM4": "NDC4", "NSM5": "NDC5",
             "NFB21": "NFB11", "NFB22": "NFB12", "NFB23": "NFB13", "NFB24": "NFB14"}  # fmt: skip
"""The elbow failover's switch (``watch`` re-plans NSM3's loss onto the DC arm so)."""
OK_EXITS = (0, -signal.SIGKILL)
"""How a stopped stand-in may end: said goodbye, or killed past its grace (Fast-DDS #6513)."""
REWIRED = "NREA"
"""The kept consumer a switch restarts, wired to the other arm's services."""


def _cpu(pid: int) -> float | None:
    """Return the CPU seconds (user + system) process ``pid`` has used, or None if gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="utf-8") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / TICK


def _since(log: Path, start: int) -> bytes:
    try:
        with log.open("rb") as f:
            f.seek(start)
            return f.read()
    except OSError:
        return b""


class Failovers:
    """The two arms' configurations and the nodes of the one running now."""

    def __init__(self, nodes: Any, keep: Path) -> None:
        from rosreconf.formats.loader import load_bundled
        from rosreconf.model import Configuration

        bundle = load_bundled()
        self.library = bundle.library
        self.schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
        roles = self.schema.graph.roles
        nominal = dict(self.schema.nominal)
        other = {r: OTHER_ARM.get(c, c) for r, c in nominal.items()}
        self.configs = [Configuration.of(self.schema.name, m, roles) for m in (nominal, other)]
        self.nodes = nodes
        self.keep = keep
        self.now = 0
        self.crashed: set[int] = set()
        """The pids of the stand-ins said to have crashed as they started (said once)."""

    def start(self, names: list[str]) -> tuple[list[Any], float]:
        """Ask for ``names`` of the configuration now, all at once; return them and when."""
        begun = time.monotonic()
        config = self.configs[self.now]
        return self.nodes.start(self.library, self.schema, config, names), begun

    def first(self) -> dict[str, Any]:
        """Start the nominal configuration whole."""
        started, begun = self.start(sorted(c for c in self.configs[0].mapping.values() if c))
        return self.settle(started, begun, [])

    def switch(self) -> dict[str, Any]:
        """Switch arms as a repair does: stop NREA, start the new ones, stop the old arm."""
        old = self.configs[self.now].mapping
        self.now = 1 - self.now
        new = self.configs[self.now].mapping
        leaving = sorted(c for r, c in old.items() if c and new[r] != c)
        coming = sorted(c for r, c in new.items() if c and old[r] != c)
        self.nodes.stop([REWIRED])
        started, begun = self.start([*coming, REWIRED])
        return self.settle(started, begun, leaving)

    def settle(self, started: list[Any], begun: float, leaving: list[str]) -> dict[str, Any]:
        """Stop ``leaving`` while ``started`` come up; wait for each ready line; say all."""
        stopped = self.nodes.stop(leaving)
        walls: dict[str, float] = {}
        cpus: dict[str, float] = {}
        early: dict[str, int] = {}
        deadline = begun + READY_TIMEOUT
        while len(walls) + len(early) < len(started) and time.monotonic() < deadline:
            for own in started:
                name = own.component
                if name in walls or name in early:
                    continue
                if b'{"ready"' in _since(own.log, own.log_from):
                    walls[name] = time.monotonic() - begun
                    cpu = _cpu(own.pid)
                    if cpu is not None:
                        cpus[name] = cpu
                elif (code := own.program.process.poll()) is not None:
                    early[name] = code
            time.sleep(0.005)
        crashed: dict[str, int | None] = dict(early)
        unready = [o.component for o in started if o.component not in walls | early.keys()]
        crashed.update({name: None for name in unready})  # still not ready: said as a crash
        codes = {o.component: o.program.process.poll() for o in stopped}
        at_stop: dict[str, int | None] = {}
        stopped = [o for o in stopped if o.pid not in self.crashed]
        for own, where in [*((o, crashed) for o in started), *((o, at_stop) for o in stopped)]:
            text = _since(own.log, own.log_from)
            code = codes.get(own.component) if where is at_stop else early.get(own.component)
            if b"Fatal Python error" in text or (where is at_stop and code not in OK_EXITS):
                where[own.component] = code
            if own.component in where:
                (self.keep / f"{own.component}-{own.pid}.log").write_bytes(text)
        self.crashed.update(o.pid for o in started if o.component in crashed)
        return {
            "walls": walls,
            "cpus": cpus,
            "crashed": crashed,
            "crashed_at_stop": at_stop,
            "killed_at_stop": [n for n, c in codes.items() if c == -signal.SIGKILL],
        }


def _follow(domain: int, stop: threading.Event) -> None:
    """Read the domain's graph every 0.5 s, as ``watch`` does, until ``stop`` is set.

    rosreconf's reader is a Cyclone DDS participant: every stand-in discovers it (and, on
    Kilted, its XTypes type information) while it starts, as under ``watch``.
    """
    from rosreconf.errors import RosreconfError
    from rosreconf.ros.ros2.source import Ros2Source

    source = Ros2Source(domain, empty_ok=True)
    try:
        while not stop.wait(0.5):
            try:
                source.read()
            except RosreconfError:
                continue  # a graph in the middle of a switch: read again
    finally:
        source.close()


def _quantiles(values: list[float]) -> dict[str, float]:
    if not values:
        return {}
    values = sorted(values)
    return {
        "n": len(values),
        "median": round(statistics.median(values), 3),
        "p90": round(values[min(len(values) - 1, int(0.9 * len(values)))], 3),
        "max": round(values[-1], 3),
    }


def main() -> int:
    """Run the rounds and print the summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--distro", choices=("jazzy", "kilted"), required=True)
    parser.add_argument("--starts", type=int, default=2000, help="stand-ins to start in all")
    parser.add_argument("--alone", action="store_true", help="no zygote: each stand-in alone")
    parser.add_argument("--no-reader", action="store_true", help="no graph reader on the domain")
    parser.add_argument("--keep", type=Path, help="folder for crashed stand-ins' logs")
    parser.add_argument("--verbose", action="store_true")
    args = parser.parse_args()

    import ros2_harness

    from rosreconf.ros.ros2.nodes import NodeProcesses

    python = ROOT / f".venv-ros2-{args.distro}" / "bin" / "python"
    if not python.exists():
        print(f"{python} is missing: run make ros2-venvs", file=sys.stderr)
        return 2
    tmp = Path(tempfile.mkdtemp(prefix="standin-starts-"))
    keep = args.keep or tmp / "crashed"
    keep.mkdir(parents=True, exist_ok=True)
    domain = ros2_harness.free_domain()
    env = ros2_harness.dds_env()
    env.pop("CYCLONEDDS_URI", None)
    env.update(
        ROSRECONF_ROS2_PYTHON=str(python),
        HOME=str(tmp),
        ROS_LOG_DIR=str(tmp),
        ROS_DOMAIN_ID=str(domain),
        ROSRECONF_STANDIN_ZYGOTE="0" if args.alone else "1",
    )
    nodes = NodeProcesses(env, tmp / "run", stand_ins=True)
    arms = Failovers(nodes, keep)
    walls: list[float] = []
    cpus: list[float] = []
    crashes: dict[str, Any] = {}
    at_stop: dict[str, Any] = {}
    killed = 0
    starts = 0
    began = time.monotonic()
    load = os.getloadavg()[0]
    stop = threading.Event()
    reader = threading.Thread(target=_follow, args=(domain, stop), daemon=True)
    if not args.no_reader:
        reader.start()
    try:
        row = arms.first()
        while True:
            if starts:  # the first round's times include the zygote's own start
                walls += row["walls"].values()
                cpus += row["cpus"].values()
            starts += len(row["walls"]) + len(row["crashed"])
            crashes.update({f"{n}@{starts}": c for n, c in row["crashed"].items()})
            at_stop.update({f"{n}@{starts}": c for n, c in row["crashed_at_stop"].items()})
            killed += len(row["killed_at_stop"])
            if args.verbose:
                print(json.dumps({"starts": starts, **row}), file=sys.stderr, flush=True)
            for said in nodes.take_problems() + nodes.take_helpers():
                print(said, file=sys.stderr, flush=True)
            if starts >= args.starts:
                break
            row = arms.switch()
    finally:
        stop.set()
        if reader.is_alive():
            reader.join(30)
        nodes.close()
        ros2_harness.release(domain)
    commit = subprocess.run(
        ["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
        capture_output=True, text=True, check=False,
    ).stdout.strip()  # fmt: skip
    summary = {
        "commit": commit,
        "distro": args.distro,
        "zygote": not args.alone,
        "reader": not args.no_reader,
        "starts": starts,
        "crashes": len(crashes),
        "crashed": crashes,
        "crashed_at_stop": at_stop,
        "killed_at_stop": killed,
        "ready_wall_s": _quantiles(walls),
        "ready_cpu_s": _quantiles(cpus),
        "seconds": round(time.monotonic() - began, 1),
        "load": [round(load, 1), round(os.getloadavg()[0], 1)],
        "logs": str(keep),
    }
    print(json.dumps(summary, indent=1))
    return 1 if crashes else 0


if __name__ == "__main__":
    sys.exit(main())
