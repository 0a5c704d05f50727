"""Measure a live task switch (issue 46): Object Repositioning on the DC arm to Disc Loading.

Whole process, real nodes: ``rosreconf watch --ros2 --apply --stand-ins`` runs Object
Repositioning on the DC arm (``--configuration``), rclpy stand-ins under the Jazzy venv.
Once it is ``conformant`` (and, with standby, every servo-arm alternative is configured),
the tests' own rclpy client (tests/ros2_face_client.py) sets the face's ``task`` parameter
to ``disc_loading``. Times, from the request (the client's call, by its own clock):

    answer      the parameter's answer (the client sends the request again after 1.5 s
                unanswered: a service may drop its answer to a client it has not matched
                both ways yet; ``sent`` in each run says how many went)
    decide      request -> the ``task`` event (the next step of the watcher)
    conformant  request -> ``conformant`` for disc_loading (goal: <= 2 s standby, <= 4 s cold)

Rows: ``switch-cold`` (plain stand-ins: the servo arm started cold), ``switch-standby``
(every component managed, ``--standby``: the servo arm parked configured, the switch is
``activate``), and ``refusal`` (``--fail NSM3``: refused; only the answer, goal <= 50 ms).
``python benchmarks/switching.py --switches N`` runs it alone.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from recovery import JAZZY, ROOT, UP_TIMEOUT, _at, _events, _wait, stop_watch

CLIENT = ROOT / "tests" / "ros2_face_client.py"
COLUMNS = ("answer", "decide", "conformant")
GOALS = {"switch-standby": ("conformant", 2.0), "switch-cold": ("conformant", 4.0),
         "refusal": ("answer", 0.05)}  # fmt: skip
KINDS = tuple(GOALS)
DC_ARM = {"base_joint": "NDC1", "shoulder_joint": "NDC2", "elbow_joint": "NDC3",
          "wrist_joint": "NDC4", "gripper_joint": "NDC5", "camera": "NCA1",
          "gripper_sensor": "NCO1", "perception": "NVP1", "positioning": "NFB11",
          "grasping": "NFB12", "carrying": "NFB13", "placing": "NFB14",
          "reasoner": "NREA"}  # fmt: skip
SERVO = {"NSM1", "NSM2", "NSM3", "NSM4", "NSM5", "NFB21", "NFB22", "NFB23", "NFB24"}


def one_switch(kind: str, tmp: Path) -> dict[str, float]:
    """Start a watch on the DC arm, ask for disc_loading once, return the columns."""
    import ros2_harness

    log = tmp / "watch.jsonl"
    env = ros2_harness.dds_env()
    env.pop("CYCLONEDDS_URI", None)
    # UDP, as the tests' processes (tests/conftest.py) and the face: no shared-memory port
    # file of another process's to wait on in rcl_node_init (docs/live.md)
    env.setdefault("FASTDDS_BUILTIN_TRANSPORTS", "UDPv4")
    # TMPDIR: the watch's work dir (its face.log) under tmp, read when the client fails
    env.update(ROSRECONF_ROS2_PYTHON=str(JAZZY), HOME=str(tmp), ROS_LOG_DIR=str(tmp),
               TMPDIR=str(tmp))  # fmt: skip
    config = tmp / "dc_arm.json"
    config.write_text(json.dumps({"format": "rosreconf/configuration", "version": 1,
                                  "configurations": {"object_repositioning": DC_ARM}}))  # fmt: skip
    args = ["--only", "object_repositioning", "--configuration", str(config)]
    if kind == "refusal":
        args += ["--fail", "NSM3"]
    if kind == "switch-standby":
        text = (ROOT / "libraries" / "robot_arms.yaml").read_text()
        library = tmp / "robot_arms_managed.yaml"
        library.write_text(text.replace("\n    ros:\n", "\n    ros:\n      lifecycle: true\n"))
        args += ["--library", str(library), "--standby"]
        args += ["--schema", str(ROOT / "schemas" / "object_repositioning.yaml")]
        args += ["--schema", str(ROOT / "schemas" / "disc_loading.yaml")]
    domain = ros2_harness.free_domain()
    env["ROS_DOMAIN_ID"] = str(domain)
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(domain),
            "--apply", "--stand-ins", "--interval", "0.5", "--json-log", str(log),
            *args]  # fmt: skip
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                            stderr=(tmp / "watch.err").open("wb"))  # fmt: skip
    try:
        _wait(log, proc, lambda ev: any(e["event"] == "conformant" for e in ev), UP_TIMEOUT)
        if kind == "switch-standby":
            _wait(log, proc, _servo_parked, UP_TIMEOUT)
        before = len(_events(log))
        ask = [str(JAZZY), str(CLIENT), "set", "/rosreconf", "disc_loading"]
        try:
            out = subprocess.run(ask, env=env, capture_output=True, text=True, timeout=120,
                                 check=True)  # fmt: skip
        except subprocess.SubprocessError as exc:  # what the client and the face said
            raise RuntimeError(f"{exc}; client: {_tail(getattr(exc, 'stderr', None))}; "
                               f"face: {_tail(_face_log(tmp))}") from exc  # fmt: skip
        said = json.loads(out.stdout.splitlines()[-1])
        asked = said["answered_at"] - said["seconds"]
        if kind == "refusal":
            if said["successful"]:
                raise RuntimeError("the switch was taken with NSM3 failed")
            return {"answer": said["seconds"], "decide": 0.0, "conformant": 0.0,
                    "sent": said["sent"]}  # fmt: skip
        _wait(log, proc, lambda ev: any(e["event"] == "conformant" and e.get("task") ==
                                        "disc_loading" for e in ev[before:]), 120.0)  # fmt: skip
        after = _events(log)[before:]
        task = next(_at(e) for e in after if e["event"] == "task")
        done = next(_at(e) for e in after if e["event"] == "conformant")
        return {"answer": said["seconds"], "decide": task - asked, "conformant": done - asked,
                "sent": said["sent"]}  # fmt: skip
    finally:
        stop_watch(proc, 10.0)


def _tail(text: str | bytes | None) -> str:
    if isinstance(text, bytes):
        text = text.decode(errors="replace")
    return (text or "").strip()[-300:]


def _face_log(tmp: Path) -> str:
    """Return what the face printed besides its decisions (rclpy's warnings, a traceback)."""
    logs = sorted(tmp.glob("rosreconf-*/face.log"))
    text = logs[-1].read_text(errors="replace") if logs else ""
    return "\n".join(x for x in text.splitlines() if not x.startswith("["))


def _servo_parked(events: list[dict[str, Any]]) -> bool:
    return {e["component"] for e in events if e.get("transition") == "configure"} >= SERVO


def repeated(
    kinds: tuple[str, ...],
    runs: int,
    one: Callable[[str, Path], dict[str, float]],
    columns: tuple[str, ...],
    goals: dict[str, tuple[str, float]],
) -> dict[str, Any]:
    """Run ``one(kind, tmp)`` ``runs`` times per kind, each in a fresh temporary directory;
    return per kind every run's columns (or its error), their medians and the goal's verdict."""
    rows: dict[str, Any] = {}
    for kind in kinds:
        done = []
        for _ in range(runs):
            with tempfile.TemporaryDirectory(prefix="rosreconf-bench-") as tmp:
                try:
                    done.append(one(kind, Path(tmp)))
                except (RuntimeError, subprocess.SubprocessError) as exc:
                    done.append({"error": str(exc)[:1000]})
        good = [r for r in done if "error" not in r]
        medians = {c: statistics.median(r[c] for r in good) for c in columns} if good else {}
        column, goal = goals[kind]
        met = None if not good else medians[column] <= goal
        rows[kind] = {"runs": done, "median": medians, "goal": [column, goal], "met": met}
    return rows


def switching(runs: int, kinds: tuple[str, ...] = KINDS) -> dict[str, Any]:
    """Return, per row, every run's columns and their medians (seconds)."""
    if not JAZZY.exists():
        return {"status": "skipped: no .venv-ros2-jazzy (make ros2-venvs)"}
    rows = repeated(kinds, runs, one_switch, COLUMNS, GOALS)
    return {"status": "ok", "scope": "whole process, real nodes, from the request", "rows": rows}


def table(doc: dict[str, Any], columns: tuple[str, ...] = COLUMNS) -> str:
    """Return the rows as a Markdown table (median seconds)."""
    if doc.get("status") != "ok":
        return f"rows: {doc.get('status')}"
    lines = [
        f"| path | runs | {' | '.join(columns)} | goal |",
        "| --- | --- | " + "--- | " * len(columns) + "--- |",
    ]
    for kind, row in doc["rows"].items():
        m = row["median"]
        ok = len([r for r in row["runs"] if "error" not in r])
        cells = [f"{m[c]:.3f}" if m else "n/a" for c in columns]
        column, goal = row["goal"]
        verdict = f"{column} <= {goal:g} s: {'met' if row['met'] else 'not met'}"
        lines.append(f"| {kind} | {ok}/{len(row['runs'])} | {' | '.join(cells)} | {verdict} |")
    return "\n".join(lines)


def main() -> None:
    """Run the rows alone and print them (and the JSON with --json)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--switches", type=int, default=3)
    ap.add_argument("--kinds", default=",".join(KINDS))
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    doc = switching(args.switches, tuple(args.kinds.split(",")))
    if args.json is not None:
        args.json.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(table(doc))


if __name__ == "__main__":
    main()
