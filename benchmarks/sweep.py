"""The ``simulate`` row of ``run.py``: the M-solution sweep, whole process, 1 and 2 workers.

``run.py --simulate-only`` measures only this and replaces its entry in the results.
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from rows import OK, Sweep, machine

SIMULATE_SIZE = (8, 4)
"""The simulate benchmark's generated instance (seed 1): 14,096 valid configurations."""


SIMULATE_GOAL_SECONDS = 30.0
"""Issue 13's goal for the sweep: under 30 s whole process (wall clock) on this machine."""


def simulate_sweep(folder: Path, runs: int, timeout: float) -> Sweep:
    """Time ``rosreconf simulate --json`` whole-process with 1 and 2 workers, interleaved.

    Each run is a fresh ``python -m rosreconf`` (imports, loading, enumeration, simulation,
    ranking, JSON), alternating 1 and 2 workers so that load on the machine hits both alike.
    Wall-clock seconds are the goal's measure; CPU seconds (the child and its workers) say
    how much of the wall clock was waiting for a shared machine.
    """
    times: dict[int, list[float]] = {1: [], 2: []}
    cpu: dict[int, list[float]] = {1: [], 2: []}
    doc: dict[str, Any] = {}  # the last run's JSON output (its first schema)
    for _ in range(runs):
        for workers in (1, 2):
            argv = [sys.executable, "-m", "rosreconf", "simulate", "--workers", str(workers)]
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            done = subprocess.run(
                [*argv, "--json"], cwd=folder, capture_output=True, text=True, timeout=timeout
            )
            times[workers].append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            used = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
            cpu[workers].append(used)
            if done.returncode not in (0, 1):
                return Sweep(f"exit {done.returncode}: {done.stderr.strip()[-200:]}")
            doc = json.loads(done.stdout)["schemas"][0]
    one, two = statistics.median(times[1]), statistics.median(times[2])
    return Sweep(
        OK,
        configurations=doc["configurations_simulated"],
        distinct_loops=doc["distinct_loops"],
        loops_simulated=doc["loops_simulated"],
        meeting_requirements=sum(c["meets_requirements"] for c in doc["configurations"]),
        unstable=sum(not c["stable"] for c in doc["configurations"]),
        seconds_1_worker=one,
        seconds_2_workers=two,
        cpu_seconds_1_worker=statistics.median(cpu[1]),
        cpu_seconds_2_workers=statistics.median(cpu[2]),
        speedup_2_workers=one / two,
        goal_seconds=SIMULATE_GOAL_SECONDS,
        met=max(one, two) < SIMULATE_GOAL_SECONDS,
        load_average=list(os.getloadavg()),
        runs=runs,
    )


def update_simulate(path: Path, timeout: float) -> None:
    """Measure only the simulate sweep and replace its entry in the results at ``path``."""
    from rosreconf.synthetic import generate, write

    r, k = SIMULATE_SIZE
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / f"sim{r}x{k}"
        write(generate(r, k, 0.2, seed=1, dynamics=True), folder)
        result = simulate_sweep(folder, 3, timeout)
    result.instance = f"{r}x{k}"
    result.machine = machine()
    doc = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    doc["simulate"] = result.to_json()
    path.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(json.dumps(doc["simulate"], indent=2))
