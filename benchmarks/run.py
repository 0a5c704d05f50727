"""Measure rosreconf at scale: count, first, optimal, clingo's optimal, whatif, clingo alone,
and simulate (the M-solution sweep, whole process, 1 and 2 workers).

Every measurement runs in a fresh subprocess (this script with ``--child``), which reports
its wall time and its own peak RSS; the parent keeps the median of n runs per cell, prints
a rich table and writes benchmarks/results.json. ``--quick`` runs a tiny grid for CI.
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
FULL = [(r, k) for r in (10, 50, 200, 1000) for k in (2, 5, 10)]
QUICK = [(8, 2), (12, 3)]


OBJECTIVE_WEIGHTS = {"cost": 1.0}
"""What "optimal" minimises in the benchmark: the generated components' cost metric."""


def child(kind: str, folder: str) -> dict[str, Any]:
    """Run one measurement in this process and return seconds and peak RSS (KiB)."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.solve.counting import count
    from rosreconf.solve.factors import paused_gc
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import ClingoEngine, Objective, _control, optimise

    objective = Objective(weights=OBJECTIVE_WEIGHTS)
    d = Path(folder)
    loaded = load_paths([d / "libraries", d / "schemas"])
    lib, schema = loaded.library, loaded.schemas[0]
    t = time.perf_counter()
    extra: dict[str, Any] = {}
    if kind == "count":
        extra["digits"] = len(str(count(compile_instance(lib, schema))))
    elif kind == "first":
        extra["found"] = ClingoEngine().first(compile_instance(lib, schema)) is not None
    elif kind == "optimal":  # what best_configuration does: compile, elimination or clingo
        with paused_gc():
            inst = compile_instance(lib, schema)
        best = optimise(inst, objective)
        extra["found"] = best.configuration is not None
        extra["engine"] = best.engine
    elif kind == "clingo_optimal":  # the reference: clingo's proven optimum (usc)
        inst = compile_instance(lib, schema)
        extra["found"] = ClingoEngine().best(inst, objective) is not None
    elif kind == "clingo":  # the reference: clingo's own ground + solve, our compile excluded
        inst = compile_instance(lib, schema)
        t = time.perf_counter()
        ctl = _control(inst, None, ["--models=1"])
        extra["found"] = bool(ctl.solve().satisfiable)
    elif kind == "whatif":
        from concurrent.futures import ProcessPoolExecutor

        from rosreconf.analysis.whatif import analyse

        with ProcessPoolExecutor(2) as pool:
            report = analyse(lib, schema, 2, pool)
        extra["solver_calls"] = report.solver_calls
    elif kind.startswith("fd-"):  # Fast Downward on the rendered task: the plan must be valid
        extra.update(fast_downward(kind[3:], lib, schema))
    elif kind.startswith("list"):
        n = int(kind[4:])
        extra["listed"] = sum(
            1 for _ in ClingoEngine().configurations(compile_instance(lib, schema), n)
        )
    seconds = time.perf_counter() - t
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return {"seconds": seconds, "rss_kib": rss, **extra}


FD_TIMEOUT = 60.0
"""Fast Downward's own time limit per cell (the anytime search uses all of it)."""


def fast_downward(search: str, lib: Any, schema: Any) -> dict[str, Any]:
    """Render the schema, plan with ``search`` and say whether the plan's configuration is valid."""
    from rosreconf.model import Configuration
    from rosreconf.model.validity import is_valid
    from rosreconf.planning.pddl import render
    from rosreconf.planning.planners import FastDownward, solve
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import Objective

    first = search in ("ff-first", "lama-first")  # first-plan searches ignore costs
    objective = None if first else Objective(dict(schema.nominal), {"cost": 1})
    task = render(compile_instance(lib, schema), objective)
    run = solve(
        FastDownward(search), task.domain, task.problem, timeout=FD_TIMEOUT, memory_limit_mb=2048
    )
    if not run.solved:
        return {"planned": run.status.value, "valid": False}
    steps = [task.names.step(name) for name, _ in run.actions]
    picks = {st.role: st.component for st in steps if st is not None and st.kind == "choose"}
    config = Configuration.of(schema.name, picks, schema.graph.roles)
    return {"planned": "solved", "cost": run.cost, "valid": is_valid(config, lib, schema)}


def measure(kind: str, folder: Path, runs: int, timeout: float) -> dict[str, Any]:
    """Return the median of ``runs`` child runs of ``kind`` (or why it did not finish)."""
    results = []
    for _ in range(runs):
        cmd = [sys.executable, str(Path(__file__)), "--child", kind, str(folder)]
        try:
            out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=True)
        except subprocess.TimeoutExpired:
            return {"status": f"timeout {timeout:.0f} s"}
        except subprocess.CalledProcessError as exc:
            return {"status": "error: " + exc.stderr.strip().splitlines()[-1][:80]}
        results.append(json.loads(out.stdout))
    best = dict(results[0])
    best["seconds"] = statistics.median(r["seconds"] for r in results)
    best["rss_kib"] = max(r["rss_kib"] for r in results)
    best["status"] = "ok"
    return best


def import_floor(runs: int) -> dict[str, float]:
    """Time ``python -c pass`` against ``python -c 'import rosreconf'``."""

    def wall(code: str) -> float:
        times = []
        for _ in range(runs):
            t = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True)
            times.append(time.perf_counter() - t)
        return statistics.median(times)

    bare, ours = wall("pass"), wall("import rosreconf")
    return {"python": bare, "import_rosreconf": ours, "ratio": ours / bare}


def main() -> None:
    """Run the grid and write the table and JSON."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--child", nargs=2)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument(
        "--clingo-timeout", type=float, default=60.0, help="per-cell limit of clingo_optimal"
    )
    ap.add_argument("--json", type=Path, default=HERE / "results.json")
    ap.add_argument(
        "--simulate-only",
        action="store_true",
        help="measure only the simulate sweep and update its entry in the JSON",
    )
    args = ap.parse_args()
    if args.child:
        print(json.dumps(child(*args.child)))
        return
    if args.simulate_only:
        update_simulate(args.json, args.timeout)
        return
    from rich.console import Console
    from rich.table import Table

    from rosreconf.formats.generate import generate, write

    grid = QUICK if args.quick else FULL
    rows = []
    kinds = ["count", "first", "optimal", "clingo_optimal", "clingo", "whatif"]
    with tempfile.TemporaryDirectory() as tmp:
        for r, k in grid:
            folder = Path(tmp) / f"{r}x{k}"
            write(generate(r, k, 0.2, seed=1), folder)
            runs = 1 if args.quick or r * k >= 2000 else 3
            row: dict[str, Any] = {"roles": r, "candidates": k}
            for kind in kinds:
                if kind == "whatif" and r > 50:
                    row[kind] = {"status": "skipped (R > 50)"}
                    continue
                limit = args.clingo_timeout if kind == "clingo_optimal" else args.timeout
                row[kind] = measure(kind, folder, runs, limit)
            fd_runs = {"first": "fd-ff-first", "anytime": "fd-seq-sat-lama-2011"}
            row["fast_downward"] = {
                key: measure(kind, folder, 1, FD_TIMEOUT + 30)
                if key == "first" or r <= 50
                else {"status": "skipped (R > 50)"}
                for key, kind in fd_runs.items()
            }
            rows.append(row)
        # Streaming: peak RSS after listing few vs many configurations of one instance must be
        # (nearly) the same. 50x5 has millions of configurations of 50 components each.
        where = (50, 5) if (50, 5) in grid else grid[-1]
        stream = Path(tmp) / f"{where[0]}x{where[1]}"
        counts = (10, 1000) if args.quick else (1000, 100_000)
        flat = {n: measure(f"list{n}", stream, 1, args.timeout) for n in counts}
        r, k = (8, 2) if args.quick else SIMULATE_SIZE
        sim_folder = Path(tmp) / f"sim{r}x{k}"
        write(generate(r, k, 0.2, seed=1, dynamics=True), sim_folder)
        simulate = simulate_sweep(sim_folder, 1 if args.quick else 3, args.timeout)
        simulate["instance"] = f"{r}x{k}"
    floor = import_floor(3 if args.quick else 5)
    doc = {
        "machine": machine(),
        "grid": rows,
        "streaming_rss_kib": {str(n): v.get("rss_kib") for n, v in flat.items()},
        "streaming_instance": f"{where[0]}x{where[1]}",
        "import_floor": floor,
        "simulate": simulate,
    }
    args.json.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    table = Table(title="rosreconf benchmark (median seconds / peak RSS MiB)")
    for col in ["R x K", *kinds, "overhead", "FD first", "FD anytime"]:
        table.add_column(col)
    for row in rows:
        cells = [f"{row['roles']}x{row['candidates']}"]
        for kind in kinds:
            m = row[kind]
            ok = m.get("status") == "ok"
            cells.append(f"{m['seconds']:.2f} / {m['rss_kib'] / 1024:.0f}" if ok else m["status"])
        f, c = row["first"], row["clingo"]
        ok = f.get("status") == c.get("status") == "ok"
        cells.append(f"{f['seconds'] / c['seconds']:.1f}x" if ok else "n/a")
        cells += [fd_cell(row["fast_downward"][key], f) for key in ("first", "anytime")]
        table.add_row(*cells)
    console = Console(width=200)  # a file or pipe gets the whole table, not 80 columns
    console.print(table)
    console.print(f"import floor: {floor}; streaming RSS KiB: {doc['streaming_rss_kib']}")
    if simulate["status"] == "ok":
        console.print(
            f"simulate {simulate['instance']} (whole process): {simulate['configurations']} "
            f"configurations, {simulate['loops_simulated']} distinct loops simulated; "
            f"1 worker {simulate['seconds_1_worker']:.1f} s, 2 workers "
            f"{simulate['seconds_2_workers']:.1f} s ({simulate['speedup_2_workers']:.2f}x)"
        )
    else:
        console.print(f"simulate: {simulate['status']}")


def fd_cell(m: dict[str, Any], first: dict[str, Any]) -> str:
    """Show a Fast Downward cell: seconds, whether the plan is valid, ratio to our first."""
    if m.get("status") != "ok":
        return str(m["status"])
    if m["planned"] != "solved":
        return f"{m['planned']} {m['seconds']:.1f} s"
    ratio = f", {m['seconds'] / first['seconds']:.0f}x" if first.get("status") == "ok" else ""
    return f"{m['seconds']:.2f} ({'valid' if m['valid'] else 'INVALID'}{ratio})"


SIMULATE_SIZE = (8, 4)
"""The simulate benchmark's generated instance (seed 1): 14,096 valid configurations."""


def simulate_sweep(folder: Path, runs: int, timeout: float) -> dict[str, Any]:
    """Time ``rosreconf simulate --json`` whole-process with 1 and 2 workers, interleaved.

    Each run is a fresh ``python -m rosreconf`` (imports, loading, enumeration, simulation,
    ranking, JSON), alternating 1 and 2 workers so that load on the machine hits both alike.
    """
    times: dict[int, list[float]] = {1: [], 2: []}
    doc: dict[str, Any] = {}
    for _ in range(runs):
        for workers in (1, 2):
            argv = [sys.executable, "-m", "rosreconf", "simulate", "--workers", str(workers)]
            start = time.perf_counter()
            done = subprocess.run(
                [*argv, "--json"], cwd=folder, capture_output=True, text=True, timeout=timeout
            )
            times[workers].append(time.perf_counter() - start)
            if done.returncode not in (0, 1):
                return {"status": f"exit {done.returncode}: {done.stderr.strip()[-200:]}"}
            doc = json.loads(done.stdout)["schemas"][0]
    one, two = statistics.median(times[1]), statistics.median(times[2])
    return {
        "status": "ok",
        "configurations": doc["configurations_simulated"],
        "distinct_loops": doc["distinct_loops"],
        "loops_simulated": doc["loops_simulated"],
        "meeting_requirements": sum(c["meets_requirements"] for c in doc["configurations"]),
        "unstable": sum(not c["stable"] for c in doc["configurations"]),
        "seconds_1_worker": one,
        "seconds_2_workers": two,
        "speedup_2_workers": one / two,
        "runs": runs,
    }


def update_simulate(path: Path, timeout: float) -> None:
    """Measure only the simulate sweep and replace its entry in the results at ``path``."""
    from rosreconf.formats.generate import generate, write

    r, k = SIMULATE_SIZE
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / f"sim{r}x{k}"
        write(generate(r, k, 0.2, seed=1, dynamics=True), folder)
        result = simulate_sweep(folder, 3, timeout)
    result["instance"] = f"{r}x{k}"
    result["machine"] = machine()
    doc = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    doc["simulate"] = result
    path.write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    print(json.dumps(result, indent=2))


def machine() -> dict[str, Any]:
    """Describe the machine: cores, CPU model, Python."""
    import os

    model = ""
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return {"cores": os.cpu_count(), "cpu": model, "python": platform.python_version()}


if __name__ == "__main__":
    main()
