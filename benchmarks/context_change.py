"""Measure a live context change: the water's visibility drops below spiral_high's bound.

Whole process, real nodes: ``rosreconf watch --ros2 --apply --stand-ins`` runs the SUAVE-like
example (docs/examples/suave) with the default dwell (2 s), rclpy stand-ins under the Jazzy
venv; the tests' own rclpy publisher (tests/ros2_context_publisher.py) sends
``/water_visibility`` at 10 Hz. Once watch is ``conformant`` on spiral_high (visibility 4.0;
with standby, once every alternative is configured), the publisher sends 3.0. Times, from the
first message with 3.0 (the publisher's own clock):

    decide      the reading -> the ``context`` event ruling spiral_high out (the dwell, then
                the watcher's next step)
    conformant  the reading -> ``conformant`` on spiral_medium (goal: <= the dwell + 1 s)

Rows: ``context-cold`` (plain stand-ins: spiral_medium started cold) and ``context-standby``
(every component managed, ``--standby``: spiral_medium parked configured, the change is
``activate``). ``python benchmarks/context_change.py --runs N`` runs it alone.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

from recovery import JAZZY, ROOT, UP_TIMEOUT, _at, _events, _wait, stop_watch
from switching import repeated, table

EXAMPLE = ROOT / "docs" / "examples" / "suave"
PUBLISHER = ROOT / "tests" / "ros2_context_publisher.py"
DWELL = 2.0
COLUMNS = ("decide", "conformant")
GOALS = {"context-cold": ("conformant", DWELL + 1.0),
         "context-standby": ("conformant", DWELL + 1.0)}  # fmt: skip
KINDS = tuple(GOALS)
ALTERNATIVE = "spiral_medium"
"""What replaces spiral_high (the fewest changes, then the library's order): with standby,
the row waits until it is parked configured."""


def one_change(kind: str, tmp: Path) -> dict[str, float]:
    """Start a watch on spiral_high, drop the visibility once, return the columns."""
    import ros2_harness

    log = tmp / "watch.jsonl"
    env = ros2_harness.dds_env()
    env.pop("CYCLONEDDS_URI", None)
    env.setdefault("FASTDDS_BUILTIN_TRANSPORTS", "UDPv4")  # as the tests' processes and the face
    env.update(ROSRECONF_ROS2_PYTHON=str(JAZZY), HOME=str(tmp), ROS_LOG_DIR=str(tmp))
    library = EXAMPLE / "library.yaml"
    args = ["--schema", str(EXAMPLE / "schema.yaml"), "--dwell", f"{DWELL:g}"]
    if kind == "context-standby":
        text = library.read_text()
        library = tmp / "suave_managed.yaml"
        managed = "    ros: {package: suave_mini, executable: node, lifecycle: true}\n"
        library.write_text(text.replace("    abstraction:", managed + "    abstraction:"))
        args.append("--standby")
    domain = ros2_harness.free_domain()
    env["ROS_DOMAIN_ID"] = str(domain)
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(domain),
            "--apply", "--stand-ins", "--interval", "0.5", "--json-log", str(log),
            "--library", str(library), *args]  # fmt: skip
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                            stderr=(tmp / "watch.err").open("wb"))  # fmt: skip
    pub = subprocess.Popen([str(JAZZY), str(PUBLISHER), "/water_visibility"], env=env,
                           stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, text=True)  # fmt: skip
    try:
        assert pub.stdin is not None and pub.stdout is not None
        pub.stdout.readline()  # ready
        pub.stdin.write("4.0\n")
        pub.stdin.flush()
        pub.stdout.readline()
        _wait(log, proc, lambda ev: any(e["event"] == "conformant" for e in ev), UP_TIMEOUT)
        if kind == "context-standby":
            _wait(log, proc, _parked, UP_TIMEOUT)
        before = len(_events(log))
        pub.stdin.write("3.0\n")
        pub.stdin.flush()
        sent = float(json.loads(pub.stdout.readline())["at"])
        _wait(log, proc, lambda ev: any(e["event"] == "conformant" for e in ev[before:]), 60.0)
        after = _events(log)[before:]
        ruled = next(_at(e) for e in after if e["event"] == "context")
        done = next(e for e in after if e["event"] == "conformant")
        if done["configuration"]["search"] != "spiral_medium":
            raise RuntimeError(f"conformant on {done['configuration']}, not spiral_medium")
        return {"decide": ruled - sent, "conformant": _at(done) - sent}
    finally:
        pub.kill()
        stop_watch(proc, 10.0)


def _parked(events: list[dict[str, Any]]) -> bool:
    configured = {e["component"] for e in events if e.get("transition") == "configure"}
    return ALTERNATIVE in configured


def context(runs: int, kinds: tuple[str, ...] = KINDS) -> dict[str, Any]:
    """Return, per row, every run's columns and their medians (seconds)."""
    if not JAZZY.exists():
        return {"status": "skipped: no .venv-ros2-jazzy (make ros2-venvs)"}
    rows = repeated(kinds, runs, one_change, COLUMNS, GOALS)
    scope = "whole process, real nodes, from the reading's first message (dwell 2 s)"
    return {"status": "ok", "scope": scope, "rows": rows}


def context_table(doc: dict[str, Any]) -> str:
    """Return the rows as a Markdown table (median seconds)."""
    return table(doc, COLUMNS)


def main() -> None:
    """Run the rows alone and print them (and the JSON with --json)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--kinds", default=",".join(KINDS))
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    doc = context(args.runs, tuple(args.kinds.split(",")))
    if args.json is not None:
        args.json.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(context_table(doc))


if __name__ == "__main__":
    main()
