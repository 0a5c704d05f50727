"""Measure the largest library rosreconf accepts: peak memory and CPU of whole processes.

The input is the bundled example (the paper's robot arm and the mobile robot: its libraries
and schemas) with a generated library beside it, as large as rosreconf reads: one file just
under ``resources.MAX_YAML_BYTES`` (64 MiB) of layered components with dynamics
(``synthetic.generate``), none of them of an abstraction a role uses. So the solvers' work is
the example's and what is measured is reading: every command reads, checks and builds all of
it (``validate`` also warns once per unused component, looking each one's position up).

Each command (``validate``, ``enumerate --count``, ``enumerate``, ``plan --fail NSM3``) runs as
a fresh child; its peak RSS and CPU seconds come from ``os.wait4`` on that child (its own
and its waited-for children's: Fast Downward's for ``plan``), whole process. The issue's
goal: peak RSS at most 20 times the file's size.

``python benchmarks/largest.py --json benchmarks/results.json`` measures and replaces the
``largest`` entry of the results; ``run.py`` calls ``largest`` in a full run.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

COMMANDS = [
    ("validate", ["validate"]),
    ("enumerate --count", ["enumerate", "--count"]),
    ("enumerate", ["enumerate"]),
    ("plan --fail NSM3", ["plan", "--fail", "NSM3"]),
]
GOAL_RATIO = 20.0
"""Peak RSS of each command at most this many times the library file's size."""
CANDIDATES = 10


def write_largest(folder: Path, limit: int) -> int:
    """Write the example and a generated library of at most ``limit`` bytes; return its bytes.

    The library's size grows with its roles almost linearly: sized from a small one, then
    shrunk until it fits (names grow a digit on the way).
    """
    from rosreconf.resources import Bundle, bundled
    from rosreconf.synthetic import MAX_COMPONENTS, generate

    for kind in (Bundle.LIBRARIES, Bundle.SCHEMAS):
        (folder / kind.value).mkdir(parents=True, exist_ok=True)
        for f in bundled(kind).iterdir():
            if f.name.endswith((".yaml", ".yml")):
                shutil.copyfile(f, folder / kind.value / f.name)
    sample = 100
    per_role = len(generate(sample, CANDIDATES, seed=1, dynamics=True).library.encode()) / sample
    roles = min(int(limit / per_role), MAX_COMPONENTS // CANDIDATES)
    while True:
        text = generate(roles, CANDIDATES, seed=1, dynamics=True).library.encode()
        if len(text) <= limit:
            break
        roles -= int((len(text) - limit) / per_role) + 1
    (folder / "libraries" / "largest.yaml").write_bytes(text)
    return len(text)


def run_one(cmd: list[str], cwd: Path) -> tuple[int, float, float, int]:
    """Run ``cmd``; return its peak RSS (KiB), CPU seconds, wall seconds and exit code."""
    t = time.perf_counter()
    child = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t
    return usage.ru_maxrss, usage.ru_utime + usage.ru_stime, wall, child.returncode


def largest(runs: int, limit: int | None = None) -> dict[str, Any]:
    """Return each command's median CPU and wall seconds and highest peak RSS on the input.

    ``limit`` is the library's largest size (``resources.MAX_YAML_BYTES`` unless given: a
    smaller one checks the machinery only, as ``run.py --quick`` does).
    """
    from rosreconf.resources import MAX_YAML_BYTES

    limit = limit or MAX_YAML_BYTES
    script = Path(sys.executable).parent / "rosreconf"
    cli = [str(script)] if script.exists() else [sys.executable, "-m", "rosreconf"]
    load_start = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        size = _write_in_child(folder, limit)
        for what, args in COMMANDS:
            results = [run_one([*cli, *args], folder) for _ in range(runs)]
            codes = {r[3] for r in results}
            rss = max(r[0] for r in results) * 1024
            rows.append(
                {
                    "command": f"rosreconf {what}",
                    "exit": sorted(codes),
                    "peak_rss_bytes": rss,
                    "rss_ratio": rss / size,
                    "cpu_seconds": statistics.median(r[1] for r in results),
                    "wall_seconds": statistics.median(r[2] for r in results),
                    "met": codes <= {0, 1} and rss <= GOAL_RATIO * size,
                }
            )
    return {
        "scope": "whole process (os.wait4 of each command's process: peak RSS, user + system CPU)",
        "input": f"the bundled example + a generated library of one file of at most {limit:,} "
        f"bytes ({CANDIDATES} candidates per role, dynamics; no role uses its abstractions)",
        "largest_accepted": limit == MAX_YAML_BYTES,
        "library_bytes": size,
        "runs": runs,
        "goal": f"peak RSS <= {GOAL_RATIO:g} x the library file's size",
        "rows": rows,
        "met": all(r["met"] for r in rows),
        "load_average": {"start": list(load_start), "end": list(os.getloadavg())},
    }


def _write_in_child(folder: Path, limit: int) -> int:
    """Write the input in a child: generating it must not count in any measured process."""
    cmd = [sys.executable, str(Path(__file__)), "--write", str(folder), "--limit", str(limit)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=1800)
    return int(out.stdout)


def table(doc: dict[str, Any]) -> str:
    """Render a ``largest`` entry as a Markdown table."""
    rows = [
        f"| command ({doc['library_bytes'] / 2**20:.1f} MiB library, whole process) "
        "| peak RSS | x file size | CPU s | wall s |",
        "| --- | --- | --- | --- | --- |",
    ]
    for r in doc["rows"]:
        rows.append(
            f"| {r['command']} | {r['peak_rss_bytes'] / 2**20:.0f} MiB | {r['rss_ratio']:.1f} "
            f"| {r['cpu_seconds']:.1f} | {r['wall_seconds']:.1f} |"
        )
    return "\n".join(rows)


def main() -> None:
    """Measure the largest library and update the results' ``largest`` entry."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--write", type=Path, help="internal: write the input there")
    ap.add_argument("--json", type=Path, default=Path(__file__).resolve().parent / "results.json")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--limit", type=int, help="the library's size (default: the largest read)")
    args = ap.parse_args()
    if args.write:
        print(write_largest(args.write, args.limit))
        return
    result = largest(args.runs, args.limit)
    doc = json.loads(args.json.read_text(encoding="utf-8")) if args.json.exists() else {}
    doc["largest"] = result
    args.json.write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    print(table(result))


if __name__ == "__main__":
    main()
