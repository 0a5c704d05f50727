"""Measure rosreconf: whole processes against references, and the solvers in-process.

Three parts, all written to benchmarks/results.json and printed as tables:

* ``whole_process``: the commands a user runs (``rosreconf --help``, ``validate``,
  ``enumerate``, ``plan --fail NSM3`` on the bundled example; ``enumerate --count``,
  ``--limit 1`` and ``--best`` on 1000 x 10; ``validate`` on 1000 x 10 with one mistake
  each: a bad value, a wrong key, a duplicate key, a tab near the end of a file, issue 24's
  goal of at most 1 CPU s) against the references of issue 12, each pair
  run back to back (ours, reference, ours, reference, ...) so that both see the same load.
  Time is the child's CPU time (user + system, ``getrusage(RUSAGE_CHILDREN)`` deltas) and
  wall time; the ratio is median(ours) / median(reference) of CPU time.
* ``growth`` and ``grid``: in-process solver times (YAML loading excluded), each in a fresh
  child (this script with ``--child``) reporting seconds and its own peak RSS.
* ``watch``: in-process, what the watcher does between detecting a failure and having the
  new configuration, against Fast Downward's own time on the same task.
* ``recovery``: whole process, real nodes: ``kill -9`` NSM3 under ``watch --apply
  --stand-ins`` to ``conformant``, ROS 2 standby, ROS 2 cold starts and ROS 1, 5 kills each,
  detect / re-plan / start / stop / conformant read from the JSON log (benchmarks/recovery.py).

``--quick`` runs a tiny version of each; ``benchmarks/selfcheck.py`` (first in ``make bench``)
runs it and checks that every table and JSON entry comes out.
"""

from __future__ import annotations

import argparse
import compileall
import json
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from loading import loading  # benchmarks/loading.py: this folder is the script's sys.path[0]
from loading import markdown as loading_markdown
from recovery import recovery
from recovery import table as recovery_table

HERE = Path(__file__).resolve().parent
FULL = [(r, k) for r in (10, 50, 200, 1000) for k in (2, 10)]
QUICK = [(8, 2), (12, 3)]
GROWTH = [10, 100, 1000, 10_000]
"""Roles (x 10 candidates) for the growth fit; libraries over 1000 roles are split in files."""
QUICK_GROWTH = [8, 16]
IMPORT_FLOOR = "import typer, rich, networkx, jinja2, yaml"
"""Issue 12's floor: what any typer + rich CLI of this kind imports before doing anything."""


OBJECTIVE_WEIGHTS = {"cost": 1.0}
"""What "optimal" minimises in the benchmark: the generated components' cost metric."""


def child(kind: str, folder: str) -> dict[str, Any]:
    """Run one measurement in this process and return seconds and peak RSS (KiB)."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.solve.counting import count
    from rosreconf.solve.factors import paused_gc
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import ClingoEngine, Objective, _control, optimise

    sys.set_int_max_str_digits(0)  # a 10,000-role count has about 10,000 digits
    objective = Objective(weights=OBJECTIVE_WEIGHTS)
    d = Path(folder)
    loaded = load_paths([d / "libraries", d / "schemas"])
    lib, schema = loaded.library, loaded.schemas[0]
    t = time.perf_counter()
    extra: dict[str, Any] = {}
    if kind == "count":
        extra["digits"] = len(str(count(compile_instance(lib, schema))))
    elif kind == "first":  # what enumerate --limit 1 does: elimination, clingo if too hard
        from rosreconf.solve.solver import first_configuration

        extra["found"] = first_configuration(compile_instance(lib, schema)) is not None
    elif kind == "clingo_first":
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


def growth_child(folder: str) -> dict[str, Any]:
    """Time count, first and optimal one after the other on one loaded library (in-process)."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.solve.counting import count
    from rosreconf.solve.factors import paused_gc
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import Objective, first_configuration, optimise

    sys.set_int_max_str_digits(0)
    d = Path(folder)
    loaded = load_paths([d / "libraries", d / "schemas"])
    lib, schema = loaded.library, loaded.schemas[0]
    out: dict[str, Any] = {}
    for kind in ("count", "first", "optimal"):
        t = time.perf_counter()
        with paused_gc():
            inst = compile_instance(lib, schema)
        if kind == "count":
            out["digits"] = len(str(count(inst)))
        elif kind == "first":
            out["first_found"] = first_configuration(inst) is not None
        else:
            out["optimal_found"] = (
                optimise(inst, Objective(weights=OBJECTIVE_WEIGHTS)).configuration is not None
            )
        out[kind] = time.perf_counter() - t
    out["rss_kib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return out


def facts_child(folder: str) -> dict[str, Any]:
    """Write ``folder/first.lp``: clingo's program and the facts of the folder's schema."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import PROGRAM, _facts

    d = Path(folder)
    loaded = load_paths([d / "libraries", d / "schemas"])
    text = PROGRAM + _facts(compile_instance(loaded.library, loaded.schemas[0]))
    (d / "first.lp").write_text(text, encoding="utf-8")
    return {"bytes": len(text)}


def watch_child(runs: str) -> dict[str, Any]:
    """Time the watcher's step from a detected failure to the new configuration (in-process).

    ``Watcher._replan`` calls ``best_configuration`` (minimal change from what runs) and
    ``explain_replan``; Fast Downward's own time (``PlanResult.elapsed``) on the same task with
    ``plan``'s default search is the reference.
    """
    from rosreconf.formats.loader import load_bundled
    from rosreconf.planning.narrative import explain_replan
    from rosreconf.planning.pddl import render
    from rosreconf.planning.planners import DEFAULT_SEARCH, FastDownward, solve
    from rosreconf.solve.instance import compile_instance
    from rosreconf.solve.solver import Objective, best_configuration

    loaded = load_bundled()
    lib = loaded.library
    schema = next(s for s in loaded.schemas if s.name == "object_repositioning")
    failed = frozenset({"NSM3"})
    current = dict(schema.nominal)
    times = []
    for _ in range(int(runs)):
        t = time.perf_counter()
        new = best_configuration(lib, schema, Objective(current=current), failed)
        assert new is not None
        changes = sum(1 for r, c in new.assignment if current.get(r) != c)
        list(explain_replan(lib, schema, failed, current, new, fewest_changes=changes))
        times.append(time.perf_counter() - t)
    task = render(compile_instance(lib, schema, failed), Objective(current=current))
    fd = []
    for _ in range(int(runs)):
        run = solve(
            FastDownward(DEFAULT_SEARCH),
            task.domain,
            task.problem,
            timeout=60.0,
            memory_limit_mb=2048,
        )
        fd.append(run.elapsed)
    replan, own = statistics.median(times), statistics.median(fd)
    return {
        "replan_seconds": replan,
        "fast_downward_seconds": own,
        "search": DEFAULT_SEARCH,
        "goal": "replan <= Fast Downward's own time + 0.05 s",
        "met": replan <= own + 0.05,
    }


def cpu_run(cmd: list[str], cwd: Path, timeout: float) -> tuple[float, float, int]:
    """Run ``cmd`` and return its CPU seconds (user + system, its children too), wall, exit."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    done = subprocess.run(
        cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=timeout
    )
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return cpu, wall, done.returncode


def pair(
    what: str,
    ours: list[str],
    reference: list[list[str]],
    cwd: Path,
    runs: int,
    *,
    goal_ratio: float | None = None,
    goal_seconds: float | None = None,
    reference_name: str = "",
) -> dict[str, Any]:
    """Run ours and the reference (its commands one after the other) back to back, ``runs`` times.

    Exit codes 0 and 1 are answers (1: some schema has no configuration); anything else is
    recorded as an error instead of a time.
    """
    mine: list[float] = []
    theirs: list[float] = []
    walls: list[float] = []
    for _ in range(runs):
        cpu, wall, code = cpu_run(ours, cwd, 600)
        if code > 1:
            return {"what": what, "status": f"error: exit {code}"}
        mine.append(cpu)
        walls.append(wall)
        total = 0.0
        for cmd in reference:
            cpu, _, code = cpu_run(cmd, cwd, 600)
            if code > 1:
                return {"what": what, "status": f"reference error: exit {code}"}
            total += cpu
        theirs.append(total)
    ours_cpu, ref_cpu = statistics.median(mine), statistics.median(theirs)
    ratio = ours_cpu / ref_cpu if ref_cpu > 0 else None
    met = True
    if goal_ratio is not None:
        met &= ratio is not None and ratio <= goal_ratio
    if goal_seconds is not None:
        met &= ours_cpu < goal_seconds
    return {
        "what": what,
        "status": "ok",
        "scope": "whole-process",
        "runs": runs,
        "cpu_seconds": ours_cpu,
        "wall_seconds": statistics.median(walls),
        "reference": reference_name,
        "reference_cpu_seconds": ref_cpu,
        "ratio": ratio,
        "goal_ratio": goal_ratio,
        "goal_seconds": goal_seconds,
        "met": met,
    }


def write_in_child(roles: int, candidates: int, folder: Path) -> None:
    """Run ``split_write`` in a child, so that the parent's peak RSS stays small."""
    cmd = [sys.executable, str(Path(__file__)), "--child", f"split-{roles}x{candidates}"]
    subprocess.run([*cmd, str(folder)], check=True, capture_output=True)


def split_write(roles: int, candidates: int, folder: Path, per: int = 1000) -> None:
    """Write a generated library in files of ``per`` components (each under the 4 MiB limit)."""
    from rosreconf.synthetic import generate

    gen = generate(roles, candidates, 0.2, seed=1)
    lines = gen.library.splitlines(keepends=True)
    at = lines.index("components:\n") + 1
    head, body = lines[:at], lines[at:]
    starts = [i for i, line in enumerate(body) if line.startswith("  - name:")]
    (folder / "libraries").mkdir(parents=True, exist_ok=True)
    (folder / "schemas").mkdir(parents=True, exist_ok=True)
    for n, k in enumerate(range(0, len(starts), per)):
        end = starts[k + per] if k + per < len(starts) else len(body)
        part = folder / "libraries" / f"generated_{n:03d}.yaml"
        part.write_text("".join(head + body[starts[k] : end]), encoding="utf-8")
    (folder / "schemas" / "generated.yaml").write_text(gen.schema, encoding="utf-8")


def _bad_value(text: str) -> str:
    return text.replace("failure_probability: 0.0", "failure_probability: 1.5", 1)


def _wrong_key(text: str) -> str:
    return text.replace("    failure_probability:", "    failure_probabilty:", 1)


def _duplicate_key(text: str) -> str:
    return text.replace("    abstraction: ", "    abstraction: x\n    abstraction: ", 1)


def _tab_near_the_end(text: str) -> str:
    at = text.rindex("\n    abstraction: ")  # the last component
    return text[:at] + "\n\tabstraction: " + text[at + len("\n    abstraction: ") :]


MISTAKES = [
    ("a bad value", _bad_value),
    ("a wrong key", _wrong_key),
    ("a duplicate key", _duplicate_key),
    ("a tab near the end of a file", _tab_near_the_end),
]
"""The one mistake of each ``validate`` row: how it turns the last library file's text."""


def with_mistake(folder: Path, dest: Path, mistake: Any) -> None:
    """Copy a generated ``folder`` to ``dest`` with one ``mistake`` in its last library file."""
    shutil.copytree(folder, dest)
    last = sorted((dest / "libraries").glob("*.yaml"))[-1]
    text = last.read_text(encoding="utf-8")
    changed = mistake(text)
    assert changed != text, mistake
    last.write_text(changed, encoding="utf-8")


def byte_compiled() -> None:
    """Byte-compile rosreconf and Fast Downward's driver and translator before timing them.

    An installed wheel has its .pyc files (pip writes them), and the reference's typer, rich
    and networkx have theirs; an editable checkout under PYTHONDONTWRITEBYTECODE=1 (set on
    this machine) has none, and every timed process would compile the modules again: about
    0.2 CPU s that no user pays, and only on our side of each pair.
    """
    import rosreconf
    from rosreconf.planning.planners.fast_downward import fast_downward_root

    compileall.compile_dir(Path(rosreconf.__file__).parent, quiet=1)
    root = fast_downward_root()
    if root is not None:
        compileall.compile_dir(root, quiet=1)


def whole_process(tmp: Path, quick: bool) -> list[dict[str, Any]]:
    """Measure the user's commands against issue 12's references, in interleaved pairs."""
    from rosreconf.planning.planners import DEFAULT_SEARCH
    from rosreconf.planning.planners.fast_downward import fast_downward_root

    byte_compiled()

    script = Path(sys.executable).parent / "rosreconf"
    cli = [str(script)] if script.exists() else [sys.executable, "-m", "rosreconf"]
    floor = [sys.executable, "-c", IMPORT_FLOOR]
    example = tmp / "example"  # no libraries/ here: the bundled example
    example.mkdir()
    tasks = tmp / "tasks"
    subprocess.run(
        [*cli, "render-pddl", "--fail", "NSM3", "--only", "object_repositioning", "-o", str(tasks)],
        cwd=example,
        check=True,
        capture_output=True,
    )
    root = fast_downward_root()
    assert root is not None, "Fast Downward is not installed"
    task = tasks / "object_repositioning"
    fd = [
        sys.executable,
        str(root / "downward" / "fast-downward.py"),
        "--plan-file",
        str(tmp / "plan"),
        "--overall-time-limit",
        "61",
        "--overall-memory-limit",
        "2048M",
        "--alias",
        DEFAULT_SEARCH,
        str(task / "domain.pddl"),
        str(task / "problem.pddl"),
    ]
    n = 1 if quick else 5
    floor_name = f"python -c '{IMPORT_FLOOR}'"
    fd_name = f"the floor + Fast Downward alone ({DEFAULT_SEARCH}) on the same PDDL"
    specs = [
        ("rosreconf --help", ["--help"], [floor], 1.0, floor_name),
        ("rosreconf validate (example)", ["validate"], [floor], 1.3, floor_name),
        ("rosreconf enumerate (example)", ["enumerate"], [floor], 1.3, floor_name),
        (
            "rosreconf plan --fail NSM3 (example)",
            ["plan", "--fail", "NSM3"],
            [floor, fd],
            1.3,
            fd_name,
        ),
    ]
    if quick:  # CI checks the machinery on two cheap rows
        specs = specs[:1]
    rows = [
        pair(what, [*cli, *args], ref, example, n, goal_ratio=goal, reference_name=name)
        for what, args, ref, goal, name in specs
    ]
    size = (12, 3) if quick else (1000, 10)
    big = tmp / f"whole{size[0]}x{size[1]}"
    write_in_child(*size, big)
    program = big / "first.lp"
    # In a child: a child's peak RSS starts from its parent's (Linux keeps the high-water
    # mark across fork), so the parent never loads a large library itself.
    cmd = [sys.executable, str(Path(__file__)), "--child", "facts", str(big)]
    subprocess.run(cmd, check=True, capture_output=True)
    clingo = [
        sys.executable,
        "-m",
        "clingo",
        "--warn=none",
        "--models=1",
        "--heuristic=Domain",
        "--enum-mode=bt",
        str(program),
    ]
    m = 1 if quick else 3
    label = f"{size[0]} x {size[1]}"
    mistakes = MISTAKES[:1] if quick else MISTAKES
    for what, mistake in mistakes:  # validate is for catching mistakes: time it doing so
        wrong = tmp / f"mistake-{what.replace(' ', '-')}"
        with_mistake(big, wrong, mistake)
        rows.append(
            pair(
                f"rosreconf validate, {what} ({label})",
                [*cli, "validate"],
                [floor],
                wrong,
                m,
                goal_seconds=1.0,
                reference_name=floor_name,
            )
        )
    commands: list[tuple[str, list[str], float | None]] = [
        ("enumerate --count", ["enumerate", "--count"], None),
        ("enumerate --limit 1", ["enumerate", "--limit", "1"], 1.0),
        (
            "enumerate --best --objective cost=1",
            ["enumerate", "--best", "--objective", "cost=1"],
            None,
        ),
    ]
    for what, args, ratio in commands[1:2] if quick else commands:
        rows.append(
            pair(
                f"rosreconf {what} ({label})",
                [*cli, *args],
                [clingo],
                big,
                m,
                goal_ratio=ratio,
                goal_seconds=2.0,
                reference_name="clingo alone, first model (python -m clingo)",
            )
        )
    if not quick:  # issue 22: one solve per failure made this over 300 s
        sys.path.append(str(HERE.parent / "tests"))
        from shapes import write_hub  # tests/shapes.py: the deep and wide schemas

        hub = tmp / "hub10000"
        write_hub(hub, 10_000)
        rows.append(
            pair(
                "rosreconf whatif -k 1 --workers 1 (a hub of 10^4 consumers, 2 candidates each)",
                [*cli, "whatif", "-k", "1", "--workers", "1"],
                [floor],
                hub,
                1,
                goal_seconds=120.0,
                reference_name=floor_name,
            )
        )
    return rows


def fit_exponent(xs: list[float], ys: list[float]) -> float | None:
    """Return the slope of log(y) over log(x) by least squares (time ~ roles ** slope)."""
    import math

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
        cmd = [sys.executable, str(Path(__file__)), "--child", "growth", str(folder)]
        try:
            out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=True)
            rows.append({"roles": roles, "status": "ok", **json.loads(out.stdout)})
        except subprocess.TimeoutExpired:
            rows.append({"roles": roles, "status": f"timeout {timeout:.0f} s"})
        except subprocess.CalledProcessError as exc:
            rows.append({"roles": roles, "status": "error: " + exc.stderr.strip()[-80:]})
    ok = [r for r in rows if r["status"] == "ok"]
    fits = {
        kind: fit_exponent([r["roles"] for r in ok], [r[kind] for r in ok])
        for kind in ("count", "first", "optimal")
    }
    return {
        "scope": "in-process (YAML loading excluded)",
        "candidates": 10,
        "rows": rows,
        "exponent": fits,
    }


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


def import_floor(runs: int) -> dict[str, Any]:
    """Compare ``import rosreconf`` with ``python -c pass``, in interleaved pairs (CPU time)."""
    here = Path.cwd()
    ours = [sys.executable, "-c", "import rosreconf"]
    return pair(
        "import rosreconf",
        ours,
        [[sys.executable, "-c", "pass"]],
        here,
        runs,
        reference_name="python -c pass",
    )


def main() -> None:
    """Run the grid and write the table and JSON."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--child", nargs=2)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument(
        "--clingo-timeout", type=float, default=30.0, help="per-cell limit of clingo_optimal"
    )
    ap.add_argument("--json", type=Path, default=HERE / "results.json")
    ap.add_argument(
        "--markdown", action="store_true", help="print the tables of --json for docs/PERFORMANCE.md"
    )
    ap.add_argument(
        "--simulate-only",
        action="store_true",
        help="measure only the simulate sweep and update its entry in the JSON",
    )
    args = ap.parse_args()
    if args.markdown:
        print(markdown(json.loads(args.json.read_text(encoding="utf-8"))))
        return
    if args.child:
        kind, where = args.child
        if kind == "growth":
            print(json.dumps(growth_child(where)))
        elif kind == "watch":
            print(json.dumps(watch_child(where)))
        elif kind == "facts":
            print(json.dumps(facts_child(where)))
        elif kind.startswith("split-"):  # split-RxK: write the generated files, in a child
            roles, candidates = (int(v) for v in kind[6:].split("x"))
            split_write(roles, candidates, Path(where))
            print("{}")
        else:
            print(json.dumps(child(kind, where)))
        return
    if args.simulate_only:
        update_simulate(args.json, args.timeout)
        return
    from rich.console import Console
    from rich.table import Table

    load_start = os.getloadavg()  # the machine is shared: say how busy it was
    grid = QUICK if args.quick else FULL
    rows = []
    kinds = ["count", "first", "optimal", "clingo_optimal", "clingo", "whatif"]
    with tempfile.TemporaryDirectory() as tmp:
        wholes = whole_process(Path(tmp), args.quick)
        size = (12, 3) if args.quick else (1000, 10)  # whole_process's generated library
        stages = loading(Path(tmp) / f"whole{size[0]}x{size[1]}", 1 if args.quick else 3)
        stages["instance"] = f"{size[0]} x {size[1]}"
        grown = growth(Path(tmp), args.quick, 600.0)
        watch_cmd = [
            sys.executable,
            str(Path(__file__)),
            "--child",
            "watch",
            "1" if args.quick else "5",
        ]
        watched = json.loads(
            subprocess.run(watch_cmd, capture_output=True, text=True, check=True).stdout
        )
        watched["scope"] = "in-process"
        recovered = (
            {"status": "skipped in --quick (real nodes, minutes: make bench)"}
            if args.quick
            else recovery(5)
        )
        for r, k in grid:
            folder = Path(tmp) / f"{r}x{k}"
            write_in_child(r, k, folder)
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
        # (nearly) the same. 50x10 has millions of configurations of 50 components each
        # (1000x10 took over 120 s to list 100,000 configurations of 1000 components).
        where = (50, 10) if (50, 10) in grid else grid[-1]
        stream = Path(tmp) / f"{where[0]}x{where[1]}"
        counts = (10, 1000) if args.quick else (1000, 100_000)
        flat = {n: measure(f"list{n}", stream, 1, args.timeout) for n in counts}
        r, k = (8, 2) if args.quick else SIMULATE_SIZE
        sim_folder = Path(tmp) / f"sim{r}x{k}"
        from rosreconf.synthetic import generate, write

        write(generate(r, k, 0.2, seed=1, dynamics=True), sim_folder)
        simulate = simulate_sweep(sim_folder, 1 if args.quick else 3, args.timeout)
        simulate["instance"] = f"{r}x{k}"
    floor = import_floor(3 if args.quick else 5)
    doc = {
        "machine": {**machine(), "load_average": {"start": load_start, "end": os.getloadavg()}},
        "loading": stages,
        "whole_process": wholes,
        "growth": grown,
        "watch": watched,
        "recovery": recovered,
        "grid_scope": "in-process (YAML loading excluded), fresh child per cell",
        "grid": rows,
        "streaming_rss_kib": {str(n): v.get("rss_kib") for n, v in flat.items()},
        "streaming_instance": f"{where[0]}x{where[1]}",
        "import_floor": floor,
        "simulate": simulate,
    }
    args.json.write_text(json.dumps(doc, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    console = Console(width=200)  # a file or pipe gets the whole table, not 80 columns
    console.print(whole_table(wholes))
    console.print(growth_table(grown))
    console.print(f"watch (in-process): {watched}")
    console.print("recovery (whole process, real nodes, median seconds):")
    console.print(recovery_table(recovered), markup=False)
    table = Table(title="rosreconf benchmark, in-process (median seconds / peak RSS MiB)")
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
    console.print(table)
    console.print(
        f"import rosreconf vs python -c pass (whole-process CPU): {floor['ratio']:.2f}x; "
        f"streaming RSS KiB (in-process): {doc['streaming_rss_kib']}"
    )

    if simulate["status"] == "ok":
        console.print(
            f"simulate {simulate['instance']} (whole process): {simulate['configurations']} "
            f"configurations, {simulate['loops_simulated']} distinct loops simulated; "
            f"1 worker {simulate['seconds_1_worker']:.1f} s "
            f"({simulate['cpu_seconds_1_worker']:.1f} s CPU), 2 workers "
            f"{simulate['seconds_2_workers']:.1f} s ({simulate['cpu_seconds_2_workers']:.1f} s "
            f"CPU, {simulate['speedup_2_workers']:.2f}x); goal < {simulate['goal_seconds']:g} s: "
            f"{'met' if simulate['met'] else 'not met'}"
        )
    else:
        console.print(f"simulate: {simulate['status']}")


def markdown(doc: dict[str, Any]) -> str:
    """Render results.json's whole-process, growth and watch parts as Markdown tables."""
    out = [
        "| what (whole process) | ours, CPU s | reference, CPU s | ratio | goal | met | reference"
        " |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in [*doc["whole_process"], doc["import_floor"]]:
        if r["status"] != "ok":
            out.append(f"| {r['what']} | {r['status']} | | | | | |")
            continue
        goals = []
        if r.get("goal_ratio") is not None:
            goals.append(f"<= {r['goal_ratio']}x")
        if r.get("goal_seconds") is not None:
            goals.append(f"< {r['goal_seconds']} s")
        out.append(
            f"| `{r['what']}` | {r['cpu_seconds']:.2f} | {r['reference_cpu_seconds']:.2f} "
            f"| {r['ratio']:.2f}x | {', '.join(goals) or '-'} "
            f"| {('yes' if r['met'] else 'no') if goals else '-'} | {r['reference']} |"
        )
    grown = doc["growth"]
    out += ["", "| roles (x 10), in-process | count s | first s | optimal s | peak RSS MiB |"]
    out.append("| --- | --- | --- | --- | --- |")
    for r in grown["rows"]:
        if r["status"] != "ok":
            out.append(f"| {r['roles']} | {r['status']} | | | |")
            continue
        out.append(
            f"| {r['roles']:,} | {r['count']:.3f} | {r['first']:.3f} | {r['optimal']:.3f} "
            f"| {r['rss_kib'] / 1024:.0f} |"
        )
    fits = grown["exponent"]
    cells = [
        f"{fits[k]:.2f}" if fits[k] is not None else "n/a" for k in ("count", "first", "optimal")
    ]
    out.append(f"| fitted exponent | {' | '.join(cells)} | |")
    if "loading" in doc:
        out += ["", loading_markdown(doc["loading"])]
    w = doc["watch"]
    out += [
        "",
        f"watch (in-process): replan {w['replan_seconds'] * 1000:.0f} ms, Fast Downward's own "
        f"time ({w['search']}) {w['fast_downward_seconds']:.2f} s; goal met: {w['met']}",
    ]
    if "recovery" in doc:
        out += ["", "recovery (whole process, real nodes, median seconds):", ""]
        out.append(recovery_table(doc["recovery"]))
    return "\n".join(out)


def whole_table(rows: list[dict[str, Any]]) -> Any:
    """Show the whole-process pairs: CPU seconds, the reference's, ratio, goal, met."""
    from rich.table import Table

    table = Table(title="whole process, interleaved pairs (median CPU seconds)")
    for col in ["what", "ours", "reference", "ratio", "goal", "met", "reference is"]:
        table.add_column(col)
    for r in rows:
        if r["status"] != "ok":
            table.add_row(r["what"], r["status"], "", "", "", "", "")
            continue
        goals = []
        if r["goal_ratio"] is not None:
            goals.append(f"<= {r['goal_ratio']}x")
        if r["goal_seconds"] is not None:
            goals.append(f"< {r['goal_seconds']} s")
        table.add_row(
            r["what"],
            f"{r['cpu_seconds']:.2f}",
            f"{r['reference_cpu_seconds']:.2f}",
            f"{r['ratio']:.2f}x" if r["ratio"] is not None else "n/a",
            ", ".join(goals),
            "yes" if r["met"] else "no",
            r["reference"],
        )
    return table


def growth_table(grown: dict[str, Any]) -> Any:
    """Show in-process seconds per roles (x 10 candidates) and the fitted exponents."""
    from rich.table import Table

    table = Table(title="growth, in-process (seconds; peak RSS MiB of the process)")
    for col in ["roles", "count", "first", "optimal", "peak RSS"]:
        table.add_column(col)
    for r in grown["rows"]:
        if r["status"] != "ok":
            table.add_row(str(r["roles"]), r["status"], "", "", "")
            continue
        cells = [f"{r[k]:.2f}" for k in ("count", "first", "optimal")]
        table.add_row(str(r["roles"]), *cells, f"{r['rss_kib'] / 1024:.0f}")
    fits = grown["exponent"]
    table.add_row(
        "exponent",
        *[f"{fits[k]:.2f}" if fits[k] else "n/a" for k in ("count", "first", "optimal")],
        "",
    )
    return table


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


SIMULATE_GOAL_SECONDS = 30.0
"""Issue 13's goal for the sweep: under 30 s whole process (wall clock) on this machine."""


def simulate_sweep(folder: Path, runs: int, timeout: float) -> dict[str, Any]:
    """Time ``rosreconf simulate --json`` whole-process with 1 and 2 workers, interleaved.

    Each run is a fresh ``python -m rosreconf`` (imports, loading, enumeration, simulation,
    ranking, JSON), alternating 1 and 2 workers so that load on the machine hits both alike.
    Wall-clock seconds are the goal's measure; CPU seconds (the child and its workers) say
    how much of the wall clock was waiting for a shared machine.
    """
    times: dict[int, list[float]] = {1: [], 2: []}
    cpu: dict[int, list[float]] = {1: [], 2: []}
    doc: dict[str, Any] = {}
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
                return {"status": f"exit {done.returncode}: {done.stderr.strip()[-200:]}"}
            doc = json.loads(done.stdout)["schemas"][0]
    one, two = statistics.median(times[1]), statistics.median(times[2])
    return {
        "status": "ok",
        "scope": "whole-process",
        "configurations": doc["configurations_simulated"],
        "distinct_loops": doc["distinct_loops"],
        "loops_simulated": doc["loops_simulated"],
        "meeting_requirements": sum(c["meets_requirements"] for c in doc["configurations"]),
        "unstable": sum(not c["stable"] for c in doc["configurations"]),
        "seconds_1_worker": one,
        "seconds_2_workers": two,
        "cpu_seconds_1_worker": statistics.median(cpu[1]),
        "cpu_seconds_2_workers": statistics.median(cpu[2]),
        "speedup_2_workers": one / two,
        "goal_seconds": SIMULATE_GOAL_SECONDS,
        "met": max(one, two) < SIMULATE_GOAL_SECONDS,
        "load_average": list(os.getloadavg()),
        "runs": runs,
    }


def update_simulate(path: Path, timeout: float) -> None:
    """Measure only the simulate sweep and replace its entry in the results at ``path``."""
    from rosreconf.synthetic import generate, write

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
