"""Measure rosreconf: whole processes against references, and the solvers in-process.

Seven parts, all written to benchmarks/results.json and printed as tables:

* ``whole_process`` (``whole.py``): the commands a user runs against the references of
  issue 12, in interleaved pairs, CPU seconds of each whole process.
* ``loading`` (``loading.py``): where reading and checking a 1000 x 10 library goes.
* ``largest`` (``largest.py``): whole process, peak RSS and CPU of ``validate``,
  ``enumerate`` and ``plan`` beside the largest library file rosreconf reads (64 MiB).
* ``growth`` and ``grid``: in-process solver times (YAML loading excluded), each in a fresh
  child (``children.py``: this script with ``--child KIND WHERE``) reporting seconds and its
  own peak RSS.
* ``watch``: in-process, what the watcher does between detecting a failure and having the
  new configuration, against Fast Downward's own time on the same task.
* ``recovery`` (``recovery.py``): whole process, real nodes: ``kill -9`` to ``conformant``.
* ``switching`` (``switching.py``): whole process, real nodes: a task switch, request to
  ``conformant``, and the parameter's answer.
* ``context`` (``context_change.py``): whole process, real nodes: a context reading that rules
  the chosen component out, to ``conformant`` without it (cold and with standbys).
* ``simulate`` (``sweep.py``): the M-solution sweep with 1 and 2 workers.
* ``soak`` (``soak.py``): whole process, real nodes: watch's RSS over 40 repairs.

``--quick`` runs a tiny version of each; ``benchmarks/selfcheck.py`` (first in ``make bench``)
runs it and checks that every table and JSON entry comes out.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import tempfile
from pathlib import Path
from typing import Any

# This folder is the script's sys.path[0]: its modules import each other by name.
from children import FD_TIMEOUT, child_main, measure, run_child, write_in_child
from context_change import context, context_table
from docsections import markdown
from largest import largest
from largest import table as largest_table
from loading import loading
from recovery import recovery
from recovery import table as recovery_table
from rows import OK, GridRow, GrowthRow, Measured, machine
from soak import soak
from sweep import SIMULATE_SIZE, simulate_sweep, update_simulate
from switching import switching
from switching import table as switching_table
from tables import grid_table, growth_table, whole_table
from whole import import_floor, whole_process

HERE = Path(__file__).resolve().parent
FULL = [(r, k) for r in (10, 50, 200, 1000) for k in (2, 10)]
QUICK = [(8, 2), (12, 3)]
GROWTH = [10, 100, 1000, 10_000]
"""Roles (x 10 candidates) for the growth fit; libraries over 1000 roles are split in files."""
QUICK_GROWTH = [8, 16]
KINDS = ["count", "first", "optimal", "clingo_optimal", "clingo", "whatif"]
"""The grid's columns: the solver kinds of ``children.SOLVER_KINDS`` timed per cell."""
FD_SEARCHES = {"first": "fd:ff-first", "anytime": "fd:seq-sat-lama-2011"}


def fit_exponent(xs: list[float], ys: list[float]) -> float | None:
    """Return the slope of log(y) over log(x) by least squares (time ~ roles ** slope)."""
    if len(xs) < 2 or any(y <= 0 for y in ys):
        return None
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = statistics.fmean(lx), statistics.fmean(ly)
    den = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly, strict=True)) / den if den else None


def growth(tmp: Path, quick: bool, timeout: float) -> dict[str, Any]:
    """Time count, first and optimal in-process from 10 to 10,000 roles (x 10), fit exponents."""
    rows = []
    for roles in QUICK_GROWTH if quick else GROWTH:
        folder = tmp / f"growth{roles}"
        write_in_child(roles, 10, folder)
        try:
            rows.append(GrowthRow(**{**run_child("growth", folder, timeout), "roles": roles}))
        except subprocess.TimeoutExpired:
            rows.append(GrowthRow(roles, f"timeout {timeout:.0f} s"))
        except subprocess.CalledProcessError as exc:
            rows.append(GrowthRow(roles, "error: " + exc.stderr.strip()[-80:]))
    ok = [r for r in rows if r.status == OK]
    series = {
        "count": [r.count or 0.0 for r in ok],
        "first": [r.first or 0.0 for r in ok],
        "optimal": [r.optimal or 0.0 for r in ok],
    }
    roles_ok: list[float] = [r.roles for r in ok]
    return {
        "scope": "in-process (YAML loading excluded)",
        "candidates": 10,
        "rows": [r.to_json() for r in rows],
        "exponent": {kind: fit_exponent(roles_ok, ys) for kind, ys in series.items()},
    }


def grid(tmp: Path, quick: bool, timeout: float, clingo_timeout: float) -> list[GridRow]:
    """Time every solver kind in a fresh child per cell, R x K over the grid, and Fast Downward."""
    rows = []
    for r, k in QUICK if quick else FULL:
        folder = tmp / f"{r}x{k}"
        write_in_child(r, k, folder)
        runs = 1 if quick or r * k >= 2000 else 3
        row = GridRow(r, k)
        for kind in KINDS:
            if kind == "whatif" and r > 50:
                row.kinds[kind] = Measured(status="skipped (R > 50)")
                continue
            limit = clingo_timeout if kind == "clingo_optimal" else timeout
            row.kinds[kind] = measure(kind, folder, runs, limit)
        for key, kind in FD_SEARCHES.items():
            skip = key != "first" and r > 50
            row.fast_downward[key] = (
                Measured(status="skipped (R > 50)")
                if skip
                else measure(kind, folder, 1, FD_TIMEOUT + 30)
            )
        rows.append(row)
    return rows


def streaming(tmp: Path, quick: bool, timeout: float) -> tuple[str, dict[str, Any]]:
    """Peak RSS after listing few vs many configurations of one instance: (nearly) the same.

    50 x 10 has millions of configurations of 50 components each (1000 x 10 took over 120 s
    to list 100,000 configurations of 1000 components).
    """
    grid_sizes = QUICK if quick else FULL
    r, k = (50, 10) if (50, 10) in grid_sizes else grid_sizes[-1]
    counts = (10, 1000) if quick else (1000, 100_000)
    flat = {n: measure(f"list:{n}", tmp / f"{r}x{k}", 1, timeout) for n in counts}
    return f"{r}x{k}", {str(n): m.rss_kib for n, m in flat.items()}


def main() -> None:
    """Run every part and write the tables and the JSON (or one child, or the Markdown)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--child", nargs=2, metavar=("KIND", "WHERE"), help="internal: one child")
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument(
        "--clingo-timeout", type=float, default=30.0, help="per-cell limit of clingo_optimal"
    )
    ap.add_argument("--json", type=Path, default=HERE / "results.json")
    ap.add_argument(
        "--markdown", action="store_true", help="print the tables of --json for docs/PERFORMANCE.md"
    )
    ap.add_argument(
        "--reading-rows",
        action="store_true",
        help="measure only issue 44's reading rows (whole process) into the JSON's "
        "reading_rows (benchmarks/largest.py measures the largest library)",
    )
    ap.add_argument(
        "--simulate-only",
        action="store_true",
        help="measure only the simulate sweep and update its entry in the JSON",
    )
    args = ap.parse_args()
    if args.markdown:
        print(markdown(json.loads(args.json.read_text(encoding="utf-8"))))
    elif args.child:
        child_main(*args.child)
    elif args.reading_rows:
        reading_rows(args.json)
    elif args.simulate_only:
        update_simulate(args.json, args.timeout)
    else:
        measure_all(args.quick, args.json, args.timeout, args.clingo_timeout)


def reading_rows(out: Path) -> None:
    """Measure the rows issue 44 asks of reading and update their entries in ``out``.

    The pairs of ``whole.py`` (``plan --fail NSM3``, ``validate`` with each mistake, the
    1000 x 10 solver rows) go to ``reading_rows``, apart from a full run's ``whole_process``
    (``benchmarks/largest.py`` alone updates ``largest``).
    """
    load_start = os.getloadavg()
    with tempfile.TemporaryDirectory() as temporary:
        rows = whole_process(Path(temporary), quick=False, reading=True)
    doc = json.loads(out.read_text(encoding="utf-8")) if out.exists() else {}
    doc["reading_rows"] = {
        "scope": "whole-process (CPU seconds of each child, interleaved pairs as whole.py)",
        "load_average": {"start": load_start, "end": os.getloadavg()},
        "rows": [r.to_json() for r in rows],
    }
    out.write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    from rich.console import Console

    Console(width=200).print(whole_table(rows))


def measure_all(quick: bool, out: Path, timeout: float, clingo_timeout: float) -> None:
    """Measure every part, write ``out`` (results.json) and print the tables."""
    from rich.console import Console

    load_start = os.getloadavg()  # the machine is shared: say how busy it was
    with tempfile.TemporaryDirectory() as temporary:
        tmp = Path(temporary)
        wholes = whole_process(tmp, quick)
        size = (12, 3) if quick else (1000, 10)  # whole_process's generated library
        stages = loading(tmp / f"whole{size[0]}x{size[1]}", 1 if quick else 3)
        stages["instance"] = f"{size[0]} x {size[1]}"
        biggest = largest(1, 1_000_000) if quick else largest(3)
        grown = growth(tmp, quick, 600.0)
        watched = run_child("watch", "1" if quick else "5")
        recovered = (
            {"status": "skipped in --quick (real nodes, minutes: make bench)"}
            if quick
            else recovery(5)
        )
        switched = (
            {"status": "skipped in --quick (real nodes, minutes: make bench)"}
            if quick
            else switching(3)
        )
        contexted = (
            {"status": "skipped in --quick (real nodes, minutes: make bench)"}
            if quick
            else context(3)
        )
        soaked = (
            {"status": "skipped in --quick (real nodes, minutes: make bench)"}
            if quick
            else soak(40, tmp)
        )
        rows = grid(tmp, quick, timeout, clingo_timeout)
        where, flat = streaming(tmp, quick, timeout)
        r, k = (8, 2) if quick else SIMULATE_SIZE
        sim_folder = tmp / f"sim{r}x{k}"
        from rosreconf.synthetic import generate, write

        write(generate(r, k, 0.2, seed=1, dynamics=True), sim_folder)
        simulate = simulate_sweep(sim_folder, 1 if quick else 3, timeout)
        simulate.instance = f"{r}x{k}"
    floor = import_floor(3 if quick else 5)
    doc = {
        "machine": {**machine(), "load_average": {"start": load_start, "end": os.getloadavg()}},
        "loading": stages,
        "largest": biggest,
        "whole_process": [w.to_json() for w in wholes],
        "growth": grown,
        "watch": watched,
        "recovery": recovered,
        "switching": switched,
        "context": contexted,
        "soak": soaked,
        "grid_scope": "in-process (YAML loading excluded), fresh child per cell",
        "grid": [row.to_json() for row in rows],
        "streaming_rss_kib": flat,
        "streaming_instance": where,
        "import_floor": floor.to_json(),
        "simulate": simulate.to_json(),
    }
    out.write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    console = Console(width=200)  # a file or pipe gets the whole table, not 80 columns
    console.print(whole_table(wholes))
    console.print(growth_table(grown))
    console.print(largest_table(biggest), markup=False)
    console.print(f"watch (in-process): {watched}")
    console.print("recovery (whole process, real nodes, median seconds):")
    console.print(recovery_table(recovered), markup=False)
    console.print("task switch (whole process, real nodes, median seconds from the request):")
    console.print(switching_table(switched), markup=False)
    console.print("context change (whole process, real nodes, median seconds from the reading):")
    console.print(context_table(contexted), markup=False)
    shown = {k: v for k, v in soaked.items() if k != "samples_kib"}
    console.print(f"soak (whole process, real nodes): {shown}", markup=False)
    console.print(grid_table(rows, KINDS))
    console.print(
        f"import rosreconf vs python -c pass (whole-process CPU): {floor.ratio or 0.0:.2f}x; "
        f"streaming RSS KiB (in-process): {flat}"
    )
    if simulate.status == OK:
        console.print(
            f"simulate {simulate.instance} (whole process): {simulate.configurations} "
            f"configurations, {simulate.loops_simulated} distinct loops simulated; "
            f"1 worker {simulate.seconds_1_worker:.1f} s "
            f"({simulate.cpu_seconds_1_worker:.1f} s CPU), 2 workers "
            f"{simulate.seconds_2_workers:.1f} s ({simulate.cpu_seconds_2_workers:.1f} s "
            f"CPU, {simulate.speedup_2_workers:.2f}x); goal < {simulate.goal_seconds:g} s: "
            f"{'met' if simulate.met else 'not met'}"
        )
    else:
        console.print(f"simulate: {simulate.status}")


if __name__ == "__main__":
    main()
