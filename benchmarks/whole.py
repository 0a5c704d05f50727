"""The whole-process rows of ``run.py``: the commands a user runs, against references.

``rosreconf --help``, ``validate``, ``enumerate``, ``plan --fail NSM3`` on the bundled
example; ``enumerate --count``, ``--limit 1`` and ``--best`` on 1000 x 10; ``validate`` on
1000 x 10 with one mistake each (a bad value, a wrong key, a duplicate key, a tab near the
end of a file: issue 24's goal of at most 1 CPU s); ``whatif -k 1`` on a hub of 10^4
consumers. Each against issue 12's reference, run back to back (ours, reference, ours,
reference, ...) so that both see the same load. Time is the child's CPU time (user +
system, ``getrusage(RUSAGE_CHILDREN)`` deltas) and wall time; the ratio is median(ours) /
median(reference) of CPU time.
"""

from __future__ import annotations

import compileall
import resource
import shutil
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

from children import run_child, write_in_child
from rows import Pair

HERE = Path(__file__).resolve().parent
IMPORT_FLOOR = "import typer, rich, networkx, jinja2, yaml"
"""Issue 12's floor: what any typer + rich CLI of this kind imports before doing anything."""


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
) -> Pair:
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
            return Pair(what, f"error: exit {code}")
        mine.append(cpu)
        walls.append(wall)
        total = 0.0
        for cmd in reference:
            cpu, _, code = cpu_run(cmd, cwd, 600)
            if code > 1:
                return Pair(what, f"reference error: exit {code}")
            total += cpu
        theirs.append(total)
    ours_cpu, ref_cpu = statistics.median(mine), statistics.median(theirs)
    ratio = ours_cpu / ref_cpu if ref_cpu > 0 else None
    met = True
    if goal_ratio is not None:
        met &= ratio is not None and ratio <= goal_ratio
    if goal_seconds is not None:
        met &= ours_cpu < goal_seconds
    return Pair(
        what,
        runs=runs,
        cpu_seconds=ours_cpu,
        wall_seconds=statistics.median(walls),
        reference=reference_name,
        reference_cpu_seconds=ref_cpu,
        ratio=ratio,
        goal_ratio=goal_ratio,
        goal_seconds=goal_seconds,
        met=met,
    )


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


def with_mistake(folder: Path, dest: Path, mistake: Callable[[str], str]) -> None:
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


def _setup(tmp: Path) -> tuple[list[str], list[str], Path, list[str]]:
    """Return the CLI, the import floor, the bundled example's folder and Fast Downward alone
    on the example's ``plan --fail NSM3`` task (rendered under ``tmp``)."""
    from rosreconf.planning.planners import DEFAULT_SEARCH
    from rosreconf.planning.planners.fast_downward import fast_downward_root

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
    return cli, floor, example, fd


def whole_process(tmp: Path, quick: bool, reading: bool = False) -> list[Pair]:
    """Measure the user's commands against issue 12's references, in interleaved pairs.

    ``reading``: only the rows issue 44 asks of reading (``run.py --reading-rows``): ``plan
    --fail NSM3``, the four ``validate`` mistakes and the three 1000 x 10 solver rows.
    """
    from rosreconf.planning.planners import DEFAULT_SEARCH

    byte_compiled()
    cli, floor, example, fd = _setup(tmp)
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
    elif reading:
        specs = specs[3:]
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
    run_child("facts", big)
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
    if not quick and not reading:  # issue 22: one solve per failure made this over 300 s
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


def import_floor(runs: int) -> Pair:
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
