"""Measure recovery: ``kill -9`` NSM3 under ``watch --apply --stand-ins``, to ``conformant``.

Whole process, real nodes: ``rosreconf watch`` runs as a subprocess on the bundled example
(``--only object_repositioning``, ``--interval 0.5``); every node is a real process (ROS 2:
rclpy stand-ins under the Jazzy venv; ROS 1: rospy stand-ins under roslaunch and a private
roscore). Once the watcher has logged ``conformant`` (and, with standby, configured every
alternative), NSM3's process is SIGKILLed and the times are read from the JSON log
(``--json-log``), against the wall clock of the kill:

    detect     kill -> ``failed``
    replan     ``failed`` -> ``replanned``
    start      ``replanned`` -> the last ``launch`` or ``activate`` of the repair
    stop       ``replanned`` -> the last ``stop`` of the repair
    conformant kill -> ``conformant`` (the goal: median <= 2 s standby, <= 4 s cold)

Each kill gets a fresh watcher and fresh nodes. Rows: ROS 2 standby (the bundled library
with every component managed, ``--standby``: the switch is ``activate``), ROS 2 cold starts,
ROS 1 (roslaunch), and three of supervision (issue 31), in the same run:

    outside-kill    NSM3 started outside rosreconf, as the team's launch file would (its -r
                    rules, Fast DDS's own 20 s lease); watch ``--stop-outside`` starts the
                    other twelve; ``kill -9`` NSM3: detect is by its process, not the lease
    outside-sigstop the same, NSM3 stopped with SIGSTOP (hung): detect after 1 s stopped;
                    the hung process is stopped by watch in the repair
    restart-in-place  cold stand-ins, ``--restarts 1``: NSM3 restarted in place, one change
                    (re-plan: ``failed`` -> ``restart``)

``python benchmarks/recovery.py --kills N`` runs it alone; ``benchmarks/run.py`` runs it with
5 kills per row.
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
import time
from datetime import datetime
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))  # the test harnesses: loopback DDS, a private roscore
JAZZY = ROOT / ".venv-ros2-jazzy" / "bin" / "python"
UP_TIMEOUT = 240.0
REPAIR_TIMEOUT = 120.0
COLUMNS = ("detect", "replan", "start", "stop", "conformant")
GOALS = {"ros2-standby": 2.0, "ros2-cold": 4.0, "outside-kill": 4.0, "restart-in-place": 4.0}
KINDS = ("ros2-standby", "ros2-cold", "ros1", "outside-kill", "outside-sigstop", "restart-in-place")
OUTSIDE = ("outside-kill", "outside-sigstop")


def _events(log: Path) -> list[dict[str, Any]]:
    if not log.exists():
        return []
    return [json.loads(x) for x in log.read_text().splitlines() if x.endswith("}")]


def stop_watch(proc: subprocess.Popen[bytes], grace: float) -> None:
    """Stop a watch as a person does (SIGTERM), and kill it if it is still there after ``grace``."""
    proc.send_signal(signal.SIGTERM)
    try:
        proc.wait(grace)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def _at(event: dict[str, Any]) -> float:
    return datetime.fromisoformat(event["time"]).timestamp()


def _wait(log: Path, proc: subprocess.Popen[bytes], ready: Any, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while not ready(_events(log)):
        if proc.poll() is not None or time.monotonic() > deadline:
            tail = [e["message"] for e in _events(log)[-5:]]
            raise RuntimeError(f"watch did not get ready ({proc.poll()}): {tail}")
        time.sleep(0.1)


def _nsm3_pid(events: list[dict[str, Any]]) -> int:
    """Return NSM3's pid: from the launch event (ROS 2), else from /proc (roslaunch's node)."""
    for e in events:
        if e["event"] == "launch" and "NSM3" in e.get("pids", {}):
            return int(e["pids"]["NSM3"])
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                argv = (entry / "cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if b"__name:=NSM3" in argv:
                return int(entry.name)
    raise RuntimeError("NSM3's process was not found")


def columns(events: list[dict[str, Any]], killed: float) -> dict[str, float]:
    """Return the five columns (seconds) from the events logged after the kill."""
    after = [e for e in events if _at(e) >= killed - 0.01]
    first = {e["event"]: _at(e) for e in reversed(after)}
    failed = first["failed"]
    replanned = first.get("replanned", first.get("restart", failed))
    starts = [_at(e) for e in after if e["event"] == "launch" or e.get("transition") == "activate"]
    stops = [_at(e) for e in after if e["event"] == "stop"]
    ends = [_at(e) for e in after if e["event"] == "conformant"]
    return {
        "detect": failed - killed,
        "replan": replanned - failed,
        "start": max(starts) - replanned if starts else 0.0,
        "stop": max(stops) - replanned if stops else 0.0,
        "conformant": min(ends) - killed,
    }


def one_kill(kind: str, tmp: Path) -> dict[str, float]:
    """Start a watcher and its nodes, kill NSM3 once, return the columns."""
    import ros2_harness
    import ros_harness

    log = tmp / "watch.jsonl"
    env = ros2_harness.dds_env()
    env.pop("CYCLONEDDS_URI", None)  # Fast DDS announces by multicast: Cyclone's defaults hear it
    env.update(ROSRECONF_ROS2_PYTHON=str(JAZZY), HOME=str(tmp), ROS_LOG_DIR=str(tmp))
    args = ["--only", "object_repositioning"]
    if kind in OUTSIDE:
        args += ["--stop-outside"]
    if kind == "restart-in-place":
        args += ["--restarts", "1"]
    if kind == "ros2-standby":
        managed = (ROOT / "libraries" / "robot_arms.yaml").read_text()
        library = tmp / "robot_arms_managed.yaml"
        library.write_text(managed.replace("\n    ros:\n", "\n    ros:\n      lifecycle: true\n"))
        schema = ROOT / "schemas" / "object_repositioning.yaml"
        args = ["--library", str(library), "--schema", str(schema), "--standby"]
    with ros_harness.running_master(tmp / "ros") if kind == "ros1" else _nothing() as master:
        if master is not None:
            env = {**master.env(), "HOME": str(tmp)}
            where = ["--master", master.uri]
        else:
            domain = ros2_harness.free_domain()
            where = ["--ros2", "--domain", str(domain)]
        team = _team_nsm3(env, domain, tmp) if kind in OUTSIDE else None
        argv = [sys.executable, "-m", "rosreconf", "watch", *where, "--apply", "--stand-ins",
                "--interval", "0.5", "--json-log", str(log), *args]  # fmt: skip
        proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                                stderr=(tmp / "watch.err").open("wb"))  # fmt: skip
        try:
            _wait(log, proc, lambda ev: any(e["event"] == "conformant" for e in ev), UP_TIMEOUT)
            if kind == "ros2-standby":  # every alternative configured: a failover is activate
                _wait(log, proc, _standby_ready, UP_TIMEOUT)
            if team is not None:  # its process found and watched, or the row is not this one
                _wait(log, proc, _nsm3_watched, UP_TIMEOUT)
            time.sleep(1.0)
            before = len(_events(log))
            pid = team.pid if team is not None else _nsm3_pid(_events(log))
            killed = time.time()
            os.kill(pid, signal.SIGSTOP if kind == "outside-sigstop" else signal.SIGKILL)
            _wait(
                log,
                proc,
                lambda ev: any(e["event"] == "conformant" for e in ev[before:]),
                REPAIR_TIMEOUT,
            )
            return columns(_events(log), killed)
        finally:
            stop_watch(proc, 10.0)
            if team is not None and team.poll() is None:
                os.kill(team.pid, signal.SIGCONT)
                team.kill()
                team.wait()


def _team_nsm3(env: dict[str, str], domain: int, tmp: Path) -> subprocess.Popen[bytes]:
    """Start NSM3 as the team's launch file would: its own process, wired by -r rules."""
    from rosreconf.formats.loader import load_bundled
    from rosreconf.model import Configuration
    from rosreconf.ros.launchfiles import ros2_node_arguments, wiring
    from rosreconf.ros.standin_spec import ros2_standin_spec

    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    spec = json.dumps(ros2_standin_spec(bundle.library["NSM3"]))
    script = ROOT / "rosreconf" / "ros" / "ros2" / "scripts" / "standin_node.py"
    argv = [str(JAZZY), str(script), spec]
    argv += ros2_node_arguments(bundle.library, "NSM3", wiring(bundle.library, schema, nominal))
    team = subprocess.Popen(argv, env={**env, "ROS_DOMAIN_ID": str(domain)},
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    assert team.stdout is not None
    if b'"ready"' not in team.stdout.readline():
        raise RuntimeError("the team's NSM3 did not start")
    return team


def _nsm3_watched(events: list[dict[str, Any]]) -> bool:
    return any(e["event"] == "watched" and e.get("how") == "process" and "/NSM3" in e["nodes"]
               for e in events)  # fmt: skip


def _standby_ready(events: list[dict[str, Any]]) -> bool:
    configured = {e["component"] for e in events if e.get("transition") == "configure"}
    return {"NDC1", "NDC2", "NDC3", "NDC4", "NDC5", "NFB11", "NFB12", "NFB13", "NFB14"} <= (
        configured
    )


class _nothing:
    def __enter__(self) -> None:
        return None

    def __exit__(self, *exc: object) -> None:
        return None


def recovery(kills: int, kinds: tuple[str, ...] = KINDS) -> dict[str, Any]:
    """Return, per kind, every kill's columns and their medians (whole process, seconds)."""
    if not JAZZY.exists():
        return {"status": "skipped: no .venv-ros2-jazzy (make ros2-venvs)"}
    rows: dict[str, Any] = {}
    load_start = os.getloadavg()
    for kind in kinds:
        runs = []
        for _ in range(kills):
            with tempfile.TemporaryDirectory(prefix="rosreconf-bench-") as tmp:
                try:
                    runs.append(one_kill(kind, Path(tmp)))
                except RuntimeError as exc:
                    runs.append({"error": str(exc)[:300]})
        good = [r for r in runs if "error" not in r]
        medians = {c: statistics.median(r[c] for r in good) for c in COLUMNS} if good else {}
        goal = GOALS.get(kind)
        rows[kind] = {
            "kills": runs,
            "median": medians,
            "goal_conformant_seconds": goal,
            "met": None if goal is None or not good else medians["conformant"] <= goal,
        }
    return {
        "status": "ok",
        "scope": "whole process, real nodes, wall clock from the kill, times from --json-log",
        "load_average": {"start": load_start, "end": os.getloadavg()},
        "rows": rows,
    }


def table(doc: dict[str, Any]) -> str:
    """Return the recovery rows as a Markdown table (median seconds)."""
    if doc.get("status") != "ok":
        return f"recovery: {doc.get('status')}"
    lines = [
        "| path | kills | detect | re-plan | start | stop | conformant | goal |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for kind, row in doc["rows"].items():
        m = row["median"]
        ok = len([r for r in row["kills"] if "error" not in r])
        cells = [f"{m[c]:.2f}" if m else "n/a" for c in COLUMNS]
        goal = row["goal_conformant_seconds"]
        verdict = "" if goal is None else f"<= {goal:g} s: {'met' if row['met'] else 'not met'}"
        lines.append(f"| {kind} | {ok}/{len(row['kills'])} | {' | '.join(cells)} | {verdict} |")
    return "\n".join(lines)


def main() -> None:
    """Run the recovery rows alone and print them (and the JSON with --json)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--kills", type=int, default=5)
    ap.add_argument("--kinds", default=",".join(KINDS))
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    doc = recovery(args.kills, tuple(args.kinds.split(",")))
    if args.json is not None:
        args.json.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(table(doc))


if __name__ == "__main__":
    main()
