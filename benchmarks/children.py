"""What ``run.py --child KIND WHERE`` measures in a fresh process: a registry of child kinds.

Each measurement runs in a child of its own, so that its peak RSS is its own (Linux keeps a
parent's high-water mark across fork) and nothing one cell imports or caches helps the next.
A kind is written ``name`` or ``name:argument`` (``fd:ff-first``, ``list:1000``,
``split:1000x10``); ``KINDS`` maps each name to the function that runs it, and the parent
reads the child's one line of JSON back into its row type (``run_child``).
"""

from __future__ import annotations

import json
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rows import OK, GrowthRow, Measured, Watched

RUN = Path(__file__).resolve().parent / "run.py"
OBJECTIVE_WEIGHTS = {"cost": 1.0}
"""What "optimal" minimises in the benchmark: the generated components' cost metric."""
FD_TIMEOUT = 60.0
"""Fast Downward's own time limit per cell (the anytime search uses all of it)."""


@dataclass
class Loaded:
    """The library and the first schema of a generated folder, loaded before the clock starts."""

    library: Any
    schema: Any


def _load(folder: str) -> Loaded:
    from rosreconf.formats.loader import load_paths

    sys.set_int_max_str_digits(0)  # a 10,000-role count has about 10,000 digits
    d = Path(folder)
    loaded = load_paths([d / "libraries", d / "schemas"])
    return Loaded(loaded.library, loaded.schemas[0])


def _instance(x: Loaded) -> Any:
    from rosreconf.solve.instance import compile_instance

    return compile_instance(x.library, x.schema)


# --- the solver kinds: each times its own work (YAML loading excluded) ---------------------


def _count(x: Loaded, _: str) -> Measured:
    from rosreconf.solve.counting import count

    t = time.perf_counter()
    digits = len(str(count(_instance(x))))
    return Measured(seconds=time.perf_counter() - t, digits=digits)


def _first(x: Loaded, _: str) -> Measured:
    """What ``enumerate --limit 1`` does: elimination, clingo if too hard."""
    from rosreconf.solve.solver import first_configuration

    t = time.perf_counter()
    found = first_configuration(_instance(x)) is not None
    return Measured(seconds=time.perf_counter() - t, found=found)


def _clingo_first(x: Loaded, _: str) -> Measured:
    from rosreconf.solve.solver import ClingoEngine

    t = time.perf_counter()
    found = ClingoEngine().first(_instance(x)) is not None
    return Measured(seconds=time.perf_counter() - t, found=found)


def _optimal(x: Loaded, _: str) -> Measured:
    """What ``best_configuration`` does: compile, then elimination or clingo."""
    from rosreconf.solve.factors import paused_gc
    from rosreconf.solve.solver import Objective, optimise

    t = time.perf_counter()
    with paused_gc():
        inst = _instance(x)
    best = optimise(inst, Objective(weights=OBJECTIVE_WEIGHTS))
    seconds = time.perf_counter() - t
    return Measured(seconds=seconds, found=best.configuration is not None, engine=best.engine)


def _clingo_optimal(x: Loaded, _: str) -> Measured:
    """The reference: clingo's proven optimum (usc)."""
    from rosreconf.solve.solver import ClingoEngine, Objective

    t = time.perf_counter()
    found = ClingoEngine().best(_instance(x), Objective(weights=OBJECTIVE_WEIGHTS)) is not None
    return Measured(seconds=time.perf_counter() - t, found=found)


def _clingo(x: Loaded, _: str) -> Measured:
    """The reference: clingo's own ground and solve of rosreconf's program, compiling excluded."""
    import clingo

    from rosreconf.solve.solver import asp_program

    inst = _instance(x)
    t = time.perf_counter()
    ctl = clingo.Control(["--warn=none", "--models=1"])
    ctl.add("base", [], asp_program(inst))
    ctl.ground([("base", [])])
    found = bool(ctl.solve().satisfiable)
    return Measured(seconds=time.perf_counter() - t, found=found)


def _whatif(x: Loaded, _: str) -> Measured:
    from concurrent.futures import ProcessPoolExecutor

    from rosreconf.analysis.whatif import analyse

    t = time.perf_counter()
    with ProcessPoolExecutor(2) as pool:
        report = analyse(x.library, x.schema, 2, pool)
    return Measured(seconds=time.perf_counter() - t, solver_calls=report.solver_calls)


def _fast_downward(x: Loaded, search: str) -> Measured:
    """Render the schema, plan with ``search``; say whether the plan's configuration is valid."""
    from rosreconf.model import Configuration
    from rosreconf.model.validity import is_valid
    from rosreconf.planning.pddl import render
    from rosreconf.planning.planners import FastDownward, solve
    from rosreconf.solve.solver import Objective

    t = time.perf_counter()
    first = search in ("ff-first", "lama-first")  # first-plan searches ignore costs
    objective = None if first else Objective(dict(x.schema.nominal), {"cost": 1})
    task = render(_instance(x), objective)
    planner = FastDownward(search)
    run = solve(planner, task.domain, task.problem, timeout=FD_TIMEOUT, memory_limit_mb=2048)
    if not run.solved:
        return Measured(seconds=time.perf_counter() - t, planned=run.status.value, valid=False)
    steps = [task.names.step(name) for name, _ in run.actions]
    picks = {st.role: st.component for st in steps if st is not None and st.kind == "choose"}
    config = Configuration.of(x.schema.name, picks, x.schema.graph.roles)
    valid = is_valid(config, x.library, x.schema)
    seconds = time.perf_counter() - t
    return Measured(seconds=seconds, planned="solved", cost=run.cost, valid=valid)


def _listing(x: Loaded, n: str) -> Measured:
    """List ``n`` configurations (the streaming check: peak RSS must not grow with ``n``)."""
    from rosreconf.solve.solver import ClingoEngine

    t = time.perf_counter()
    listed = sum(1 for _ in ClingoEngine().configurations(_instance(x), int(n)))
    return Measured(seconds=time.perf_counter() - t, listed=listed)


SolverKind = Callable[[Loaded, str], Measured]
SOLVER_KINDS: dict[str, SolverKind] = {
    "count": _count,
    "first": _first,
    "clingo_first": _clingo_first,
    "optimal": _optimal,
    "clingo_optimal": _clingo_optimal,
    "clingo": _clingo,
    "whatif": _whatif,
    "fd": _fast_downward,
    "list": _listing,
}
"""The kinds timed on a loaded generated folder, each in a fresh child (``measure``)."""


def _solver_child(kind: SolverKind) -> Callable[[str, str], dict[str, Any]]:
    def run(folder: str, argument: str) -> dict[str, Any]:
        measured = kind(_load(folder), argument)
        measured.rss_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return measured.to_json()

    return run


# --- the other kinds -----------------------------------------------------------------------


def _growth(folder: str, _: str) -> dict[str, Any]:
    """Time count, first and optimal one after the other on one loaded library (in-process)."""
    from rosreconf.solve.counting import count
    from rosreconf.solve.factors import paused_gc
    from rosreconf.solve.solver import Objective, first_configuration, optimise

    x = _load(folder)
    row = GrowthRow(roles=len(x.schema.graph.roles))
    for kind in ("count", "first", "optimal"):
        t = time.perf_counter()
        with paused_gc():
            inst = _instance(x)
        if kind == "count":
            row.digits = len(str(count(inst)))
            row.count = time.perf_counter() - t
        elif kind == "first":
            row.first_found = first_configuration(inst) is not None
            row.first = time.perf_counter() - t
        else:
            best = optimise(inst, Objective(weights=OBJECTIVE_WEIGHTS))
            row.optimal_found = best.configuration is not None
            row.optimal = time.perf_counter() - t
    row.rss_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return row.to_json()


def _facts(folder: str, _: str) -> dict[str, Any]:
    """Write ``folder/first.lp``: clingo's whole program for the folder's schema."""
    from rosreconf.solve.solver import asp_program

    text = asp_program(_instance(_load(folder)))
    (Path(folder) / "first.lp").write_text(text, encoding="utf-8")
    return {"bytes": len(text)}


def _watch(runs: str, _argument: str) -> dict[str, Any]:
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
    planner = FastDownward(DEFAULT_SEARCH)
    fd = [
        solve(planner, task.domain, task.problem, timeout=60.0, memory_limit_mb=2048).elapsed
        for _ in range(int(runs))
    ]
    replan, own = statistics.median(times), statistics.median(fd)
    goal = "replan <= Fast Downward's own time + 0.05 s"
    return Watched(replan, own, DEFAULT_SEARCH, goal, replan <= own + 0.05).to_json()


def _split(folder: str, size: str) -> dict[str, Any]:
    """Write a generated library of ``size`` (``RxK``) in files of 1000 components."""
    roles, candidates = (int(v) for v in size.split("x"))
    split_write(roles, candidates, Path(folder))
    return {}


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


KINDS: dict[str, Callable[[str, str], dict[str, Any]]] = {
    **{name: _solver_child(kind) for name, kind in SOLVER_KINDS.items()},
    "growth": _growth,
    "facts": _facts,
    "watch": _watch,
    "split": _split,
}
"""Every child kind by name; ``WHERE`` is a folder, or the run count for ``watch``."""


def child_main(kind: str, where: str) -> None:
    """Run one child kind in this process and print its result as one line of JSON."""
    name, _, argument = kind.partition(":")
    print(json.dumps(KINDS[name](where, argument)))


def run_child(kind: str, where: str | Path, timeout: float | None = None) -> dict[str, Any]:
    """Run ``kind`` in a fresh child and return its JSON (raises as ``subprocess.run`` does)."""
    cmd = [sys.executable, str(RUN), "--child", kind, str(where)]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=True)
    found: dict[str, Any] = json.loads(out.stdout)
    return found


def write_in_child(roles: int, candidates: int, folder: Path) -> None:
    """Write a generated library in a child, so that the parent's peak RSS stays small."""
    run_child(f"split:{roles}x{candidates}", folder)


def measure(kind: str, folder: Path, runs: int, timeout: float) -> Measured:
    """Return the median of ``runs`` child runs of ``kind`` (or why it did not finish)."""
    results = []
    for _ in range(runs):
        try:
            results.append(Measured(**run_child(kind, folder, timeout)))
        except subprocess.TimeoutExpired:
            return Measured(status=f"timeout {timeout:.0f} s")
        except subprocess.CalledProcessError as exc:
            return Measured(status="error: " + exc.stderr.strip().splitlines()[-1][:80])
    best = results[0]
    best.seconds = statistics.median(r.seconds or 0.0 for r in results)
    best.rss_kib = max(r.rss_kib or 0 for r in results)
    best.status = OK
    return best
