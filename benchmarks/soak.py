"""Measure ``watch``'s memory over many repairs: does it grow with each one?

Whole process, real nodes: ``rosreconf watch --ros2 --apply --stand-ins`` on the bundled
example (``--only object_repositioning``, Jazzy rclpy stand-ins, ``--hold 1``). Once it is
``conformant``, the process of the component that fills ``elbow_joint`` is SIGKILLed, and again
after each repair: NSM3 dies, the arm moves to the DC joints (10 changes, 10 new processes);
NDC3 dies once NSM3's hold is over, and it moves back; and so on. After each repair's
``conformant`` watch's resident set (``VmRSS`` of ``/proc/PID/status``) is sampled; its peak
(``VmHWM``) at the end.

The rows: RSS after the first ``conformant``, after the last repair, the least-squares slopes
from the first repair on and over the last half of the repairs (KiB per repair, ``slope``),
the open file descriptors after the first ``conformant`` and after the last repair,
and the repairs done. Issue 44 measured 84 -> 100 MiB over
5 minutes with 9 repairs.

``python benchmarks/soak.py --repairs N [--json benchmarks/results.json]`` runs it alone
(it replaces the ``soak`` entry of the results).
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
from pathlib import Path
from typing import Any

# This folder is the script's sys.path[0]; recovery puts the test harnesses on it too.
from recovery import JAZZY, REPAIR_TIMEOUT, UP_TIMEOUT, _events, stop_watch


def _status(pid: int, field: str) -> int:
    """Return a ``/proc/PID/status`` field in KiB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1])
    raise RuntimeError(f"no {field} for {pid}")


def _wait_conformant(
    log: Path, proc: subprocess.Popen[bytes], after: int, timeout: float
) -> dict[str, Any]:
    deadline = time.monotonic() + timeout
    while True:
        done = [e for e in _events(log)[after:] if e["event"] == "conformant"]
        if done:
            return done[-1]
        if proc.poll() is not None or time.monotonic() > deadline:
            tail = [e["message"] for e in _events(log)[-5:]]
            raise RuntimeError(f"watch did not conform ({proc.poll()}): {tail}")
        time.sleep(0.1)


def slope(samples: list[int], start: int) -> float:
    """Return the least-squares slope of ``samples[start:]`` (KiB per repair).

    From the first repair on (``start`` 1: the first loads the replanning's modules, once),
    and over the last half: a growth that settles shows there as about 0.
    """
    ys = samples[start:]
    if len(ys) < 3:
        return 0.0
    return round(statistics.linear_regression(range(len(ys)), ys).slope, 1)


def soak(repairs: int, tmp: Path) -> dict[str, Any]:
    """Run one watcher through ``repairs`` kills; return its RSS samples and their slope."""
    import ros2_harness

    log = tmp / "watch.jsonl"
    env = ros2_harness.dds_env()
    env.pop("CYCLONEDDS_URI", None)  # Fast DDS announces by multicast: Cyclone's defaults hear it
    env.update(ROSRECONF_ROS2_PYTHON=str(JAZZY), HOME=str(tmp), ROS_LOG_DIR=str(tmp))
    domain = ros2_harness.free_domain()
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(domain),
            "--apply", "--stand-ins", "--interval", "0.5", "--hold", "1", "--json-log", str(log),
            "--only", "object_repositioning"]  # fmt: skip
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL,
                            stderr=(tmp / "watch.err").open("wb"))  # fmt: skip
    samples: list[int] = []
    fds: list[int] = []
    started = time.monotonic()
    try:
        done = _wait_conformant(log, proc, 0, UP_TIMEOUT)
        samples.append(_status(proc.pid, "VmRSS"))
        fds.append(len(os.listdir(f"/proc/{proc.pid}/fd")))
        for _ in range(repairs):
            time.sleep(1.5)  # the last hold is over: the other arm is a candidate again
            elbow = done["configuration"]["elbow_joint"]
            pids = {c: p for e in _events(log) if e["event"] in ("launch", "restart")
                    for c, p in e.get("pids", {}).items()}  # fmt: skip
            before = len(_events(log))
            os.kill(int(pids[elbow]), signal.SIGKILL)
            done = _wait_conformant(log, proc, before, REPAIR_TIMEOUT)
            samples.append(_status(proc.pid, "VmRSS"))
            fds.append(len(os.listdir(f"/proc/{proc.pid}/fd")))
        peak = _status(proc.pid, "VmHWM")
    finally:
        stop_watch(proc, 15.0)
    return {
        "repairs": repairs,
        "seconds": round(time.monotonic() - started, 1),
        "rss_first_kib": samples[0],
        "rss_last_kib": samples[-1],
        "rss_peak_kib": peak,
        "slope_kib_per_repair": slope(samples, 1),
        "slope_last_half_kib_per_repair": slope(samples, len(samples) // 2),
        "fds_first": fds[0],
        "fds_last": fds[-1],
        "samples_kib": samples,
    }


def main() -> int:
    """Run the soak and print (or store) its figures."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repairs", type=int, default=20)
    parser.add_argument("--json", type=Path, help="results.json whose 'soak' entry to replace")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="rosreconf-soak-") as tmp:
        row = soak(args.repairs, Path(tmp))
    row["scope"] = "whole process (watch's /proc status), real Jazzy stand-ins"
    print(json.dumps({k: v for k, v in row.items() if k != "samples_kib"}))
    print("RSS after each repair (MiB):", " ".join(f"{s / 1024:.1f}" for s in row["samples_kib"]))
    if args.json is not None:
        results = json.loads(args.json.read_text()) if args.json.exists() else {}
        results["soak"] = row
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
