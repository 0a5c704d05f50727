"""Tests for planning.planners: real Fast Downward, fake planners, and what they leave behind."""

from __future__ import annotations

import signal
import sys
from pathlib import Path
from typing import Any

import pytest
from conftest import (
    DATA,
    FAKE_START_SECONDS,
    FAKES,
    LOADED_MACHINE_SLACK,
    read_report,
    wait_until_gone,
)

from rosreconf.planning.planners import (
    FF,
    PLANNERS,
    FastDownward,
    Planner,
    PlanResult,
    PlanStatus,
    TaskFiles,
    fast_downward_root,
    solve,
)
from rosreconf.planning.planners import fast_downward as fd_module
from rosreconf.planning.planners.fast_downward import parse_plan
from rosreconf.procs import Terminated

PDDL = DATA / "pddl"
DOMAIN = (PDDL / "pick-domain.pddl").read_text()
OPTIMAL = (
    ("pick", ("sensor", "cam_b", "power", "image")),
    ("pick", ("planner", "nav_b", "image", "path")),
    ("pick", ("driver", "base_a", "path", "motion")),
)


def problem(name: str) -> str:
    return (PDDL / f"{name}.pddl").read_text()


@pytest.fixture
def parent(tmp_path: Path) -> Path:
    """Hold the private workdirs of a test, so it can check that none is left."""
    path = tmp_path / "workdirs"
    path.mkdir()
    return path


def run(
    planner: Planner,
    parent: Path,
    domain: str = DOMAIN,
    task: str = "pick-solvable",
    timeout: float = 30,
) -> PlanResult:
    result = solve(
        planner, domain, problem(task), timeout=timeout, memory_limit_mb=1024, workdir_parent=parent
    )
    assert list(parent.iterdir()) == [], "the private workdir was left behind"
    return result


# --- real Fast Downward ----------------------------------------------------------------------


def test_fast_downward_is_found_without_importing_it() -> None:
    root = fast_downward_root()
    assert root is not None and (root / "downward" / "fast-downward.py").is_file()
    assert "up_fast_downward" not in sys.modules


@pytest.mark.planner
def test_lama_first_finds_a_plan_that_fills_every_role(parent: Path) -> None:
    result = run(FastDownward("lama-first"), parent)
    assert result.status is PlanStatus.SOLVED and result.returncode == 0
    assert [(name, args[0]) for name, args in result.actions] == [
        ("pick", "sensor"),
        ("pick", "planner"),
        ("pick", "driver"),
    ]
    assert result.cost is not None and result.cost >= 6  # lama-first ignores costs
    assert result.planner == "fd (lama-first)"
    assert result.command[result.command.index("--alias") + 1] == "lama-first"


@pytest.mark.planner
def test_ff_first_is_the_default_and_runs_its_named_search_string(parent: Path) -> None:
    result = run(FastDownward(), parent)
    assert result.status is PlanStatus.SOLVED and result.returncode == 0
    assert sorted(args[0] for _, args in result.actions) == ["driver", "planner", "sensor"]
    assert result.planner == "fd (ff-first)"
    search = result.command[result.command.index("--search") + 1]
    assert search == fd_module.FF_FIRST and "landmark" not in search
    assert "--skip-variable-reordering" in result.command
    assert "--alias" not in result.command


@pytest.mark.planner
@pytest.mark.parametrize("task", ["pick-dead-end", "pick-no-provider"])
def test_ff_first_proves_unsolvability_like_lama_first(parent: Path, task: str) -> None:
    result = run(FastDownward("ff-first"), parent, task=task)
    assert (result.status, result.returncode) == (PlanStatus.UNSOLVABLE_PROVEN, 11)


@pytest.mark.planner
@pytest.mark.parametrize("search", ["astar(lmcut())", "seq-sat-lama-2011"])
def test_cost_aware_searches_find_the_optimum(parent: Path, search: str) -> None:
    result = run(FastDownward(search), parent)
    assert (result.status, result.cost, result.actions) == (PlanStatus.SOLVED, 6, OPTIMAL)


@pytest.mark.planner
@pytest.mark.parametrize("task", ["pick-dead-end", "pick-no-provider"])
def test_an_exhausted_complete_search_proves_unsolvability(parent: Path, task: str) -> None:
    result = run(FastDownward("lama-first"), parent, task=task)
    assert (result.status, result.returncode, result.actions) == (
        PlanStatus.UNSOLVABLE_PROVEN,
        11,
        (),
    )


@pytest.mark.planner
def test_hill_climbing_into_a_dead_end_is_not_a_proof(parent: Path) -> None:
    result = run(FastDownward("ehc(ff())"), parent, task="pick-dead-end")
    assert (result.status, result.returncode) == (PlanStatus.UNSOLVABLE_INCOMPLETE, 12)
    assert "a plan may still exist" in result.message


@pytest.mark.planner
def test_a_pddl_error_is_reported_with_the_translators_words(parent: Path) -> None:
    result = run(FastDownward(), parent, domain=(PDDL / "broken-domain.pddl").read_text())
    assert (result.status, result.returncode) == (PlanStatus.PLANNER_ERROR, 31)
    assert "rejected the PDDL" in result.message
    assert "Undefined predicate" in result.message and "chosen" in result.message


@pytest.mark.planner
def test_a_malformed_search_string_is_a_planner_error(parent: Path) -> None:
    result = run(FastDownward("astar(no_such_heuristic())"), parent)
    assert (result.status, result.returncode) == (PlanStatus.PLANNER_ERROR, 33)
    assert "no_such_heuristic" in result.message


@pytest.mark.planner
def test_a_tiny_timeout_stops_fast_downward(parent: Path) -> None:
    result = run(FastDownward(), parent, timeout=0.05)
    assert result.status is PlanStatus.TIMEOUT and result.actions == ()
    assert result.elapsed < 0.05 + LOADED_MACHINE_SLACK and "time limit" in result.message


@pytest.mark.planner
def test_a_one_second_budget_does_not_starve_the_translator(parent: Path) -> None:
    # The driver rounds each component's remaining CPU time down to whole seconds: given
    # --overall-time-limit 1 its translator gets 0 s and dies of SIGXCPU (exit code 232).
    # On a quiet machine the tiny task is solved; on a loaded one our own 1 s wall clock may
    # stop it first, which is a timeout, never the translator's death.
    result = run(FastDownward(), parent, timeout=1.0)
    assert result.status in {PlanStatus.SOLVED, PlanStatus.TIMEOUT}, result.message
    assert result.returncode != 232, result.message
    assert result.command[result.command.index("--overall-time-limit") + 1] == "2"


def test_missing_fast_downward_says_how_to_install_it(
    parent: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(fd_module, "fast_downward_root", lambda: None)
    result = run(FastDownward(), parent)
    assert result.status is PlanStatus.PLANNER_MISSING and result.command == ()
    assert "pip install 'up-fast-downward" in result.message


# --- fake planners behind the Fast Downward adapter ----------------------------------------


class FakeFastDownward(FastDownward):
    """Run a fake script with Fast Downward's command-line shape; read it like Fast Downward."""

    def __init__(self, script: str, *args: str) -> None:
        super().__init__("fake")
        self.argv = [str(FAKES / script), *args]

    def command(self, files: TaskFiles, *, timeout: float, memory_limit_mb: int) -> list[str]:
        task = [str(files.domain), str(files.problem)]
        return [*self.argv, "--plan-file", str(files.plan), *task]


@pytest.mark.parametrize(
    ("code", "status"),
    [
        (10, PlanStatus.UNSOLVABLE_PROVEN),
        (13, PlanStatus.UNSOLVABLE_INCOMPLETE),
        (20, PlanStatus.MEMOUT),
        (21, PlanStatus.TIMEOUT),
        (22, PlanStatus.MEMOUT),
        (23, PlanStatus.TIMEOUT),
        (24, PlanStatus.MEMOUT),
        (30, PlanStatus.PLANNER_ERROR),
        (34, PlanStatus.PLANNER_ERROR),
        (36, PlanStatus.PLANNER_ERROR),
        (232, PlanStatus.TIMEOUT),  # the driver's exit code for a component killed by SIGXCPU
        (245, PlanStatus.PLANNER_ERROR),  # ... and by SIGSEGV
        (139, PlanStatus.PLANNER_ERROR),  # a shell's "segfault": unknown to the driver
        (0, PlanStatus.PLANNER_ERROR),  # success, but no plan file
        (2, PlanStatus.PLANNER_ERROR),  # "plan found, then out of time", but no plan file
    ],
)
def test_exit_codes_map_onto_statuses(parent: Path, code: int, status: PlanStatus) -> None:
    result = run(FakeFastDownward("exit_with.py", str(code)), parent)
    assert (result.status, result.returncode, result.actions) == (status, code, ())
    assert result.message
    if status is PlanStatus.PLANNER_ERROR and code not in (0, 2):
        assert "the last words of an error" in result.message


def test_a_crash_is_a_planner_error(parent: Path, report: Path) -> None:
    result = run(FakeFastDownward("crash.py"), parent)
    assert (result.status, result.returncode) == (PlanStatus.PLANNER_ERROR, -signal.SIGSEGV)
    assert "SIGSEGV" in result.message
    assert read_report(report)["cwd"].startswith(str(parent))


def test_half_a_plan_is_not_a_plan_even_with_exit_0(parent: Path) -> None:
    result = run(FakeFastDownward("half_plan.py"), parent)
    assert (result.status, result.returncode, result.actions) == (PlanStatus.PLANNER_ERROR, 0, ())
    assert "incomplete plan" in result.message


def test_unknown_action_names_are_returned_faithfully(parent: Path) -> None:
    result = run(FakeFastDownward("unknown_actions.py"), parent)
    assert result.status is PlanStatus.SOLVED and result.cost == 7
    assert result.actions == (
        ("teleport", ("robot_1", "nowhere")),
        ("hover", ()),
        ("pick", ("r2", "c-9")),
    )


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("(a x)\n(b)\n; cost = 2 (unit cost)\n", ((("a", ("x",)), ("b", ())), 2)),
        ("; cost = 0 (unit cost)\n", ((), 0)),
        ("(a x)\n; cost = 2 (unit cost)", None),  # killed before the newline: FD's rule
        ("(a x)\n; cost = 1 (unit cost)\n(b)\n", None),  # a step after the cost line
        ("(a x)\n; cost = 1 (unit cost)\n\n", None),  # the cost line is not the last line
        ("(a x)\n; cost = N (unit cost)\n", None),
        ("a x\n; cost = 1 (unit cost)\n", None),  # not a step
        ("", None),
    ],
)
def test_a_plan_is_complete_only_if_it_ends_with_the_cost_line(text: str, expected: Any) -> None:
    assert parse_plan(text) == expected


def test_a_hanging_planner_times_out_and_its_group_is_gone(parent: Path, report: Path) -> None:
    result = run(FakeFastDownward("hang.py"), parent, timeout=FAKE_START_SECONDS)
    assert result.status is PlanStatus.TIMEOUT
    assert result.elapsed < FAKE_START_SECONDS + LOADED_MACHINE_SLACK
    assert wait_until_gone(read_report(report)["pgid"]) == []


def test_a_child_ignoring_sigterm_does_not_survive_the_timeout(parent: Path, report: Path) -> None:
    result = run(FakeFastDownward("fork_ignore_term.py"), parent, timeout=FAKE_START_SECONDS)
    assert result.status is PlanStatus.TIMEOUT
    facts = read_report(report)
    assert len(facts["pids"]) == 2 and wait_until_gone(facts["pgid"]) == []


def test_an_anytime_planner_stopped_by_the_timeout_keeps_its_best_complete_plan(
    parent: Path,
) -> None:
    result = run(FakeFastDownward("anytime.py"), parent, timeout=FAKE_START_SECONDS)
    assert (result.status, result.cost) == (PlanStatus.SOLVED, 1)
    assert result.actions == (("pick", ("sensor", "cam_b", "power", "image")),)
    assert "time limit" in result.message


@pytest.mark.parametrize(
    ("sig", "raised"), [(signal.SIGINT, KeyboardInterrupt), (signal.SIGTERM, Terminated)]
)
def test_an_interrupted_solve_kills_the_planner_and_removes_the_workdir(
    parent: Path, report: Path, signal_when_started: Any, sig: signal.Signals, raised: type
) -> None:
    signal_when_started(sig)
    with pytest.raises(raised):
        solve(
            FakeFastDownward("fork_ignore_term.py"),
            DOMAIN,
            problem("pick-solvable"),
            timeout=30,
            memory_limit_mb=1024,
            workdir_parent=parent,
        )
    facts = read_report(report)
    assert facts["cwd"].startswith(str(parent))
    assert wait_until_gone(facts["pgid"]) == []
    assert list(parent.iterdir()) == []


# --- FF, faked on PATH ---------------------------------------------------------------------


@pytest.fixture
def fake_ff(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Any:
    """Put a fake ``ff`` on PATH that prints the transcript ``name`` and exits ``code``."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "ff").symlink_to(FAKES / "ff.py")
    monkeypatch.setenv("PATH", f"{bin_dir}:{Path(sys.executable).parent}:/usr/bin:/bin")

    def use(name: str, code: int = 0) -> None:
        monkeypatch.setenv("FAKE_FF_TRANSCRIPT", str(DATA / "ff" / f"{name}.txt"))
        monkeypatch.setenv("FAKE_FF_EXIT", str(code))

    return use


@pytest.mark.parametrize(
    ("transcript", "code", "status", "cost", "steps"),
    [
        ("plan", 0, PlanStatus.SOLVED, None, 3),
        ("metric_plan", 0, PlanStatus.SOLVED, 6, 3),
        ("goal_true", 1, PlanStatus.SOLVED, 0, 0),
        ("goal_false", 1, PlanStatus.UNSOLVABLE_PROVEN, None, 0),
        ("proven_unsolvable", 0, PlanStatus.UNSOLVABLE_PROVEN, None, 0),
        ("syntax_error", 1, PlanStatus.PLANNER_ERROR, None, 0),
    ],
)
def test_ff_output_is_read_faithfully(
    parent: Path,
    fake_ff: Any,
    transcript: str,
    code: int,
    status: PlanStatus,
    cost: int | None,
    steps: int,
) -> None:
    fake_ff(transcript, code)
    result = run(FF(), parent)
    assert (result.status, result.cost, len(result.actions)) == (status, cost, steps)
    names = [Path(arg).name for arg in result.command]
    assert names == ["ff", "-o", "domain.pddl", "-f", "problem.pddl"]
    if transcript == "metric_plan":
        assert result.actions == OPTIMAL
    if transcript == "syntax_error":
        assert "syntax error in line 7" in result.message


def test_ff_runs_with_the_rlimits_it_lacks() -> None:
    assert FF().limits(2.5, 512) == (512, 3)
    assert FastDownward().limits(2.5, 512) == (None, None)


def test_missing_ff_is_reported_clearly(
    parent: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))
    result = run(FF(), parent)
    assert result.status is PlanStatus.PLANNER_MISSING and result.command == ()
    assert "no 'ff' on PATH" in result.message and "--planner fd" in result.message


def test_the_registry_builds_every_planner_without_arguments() -> None:
    assert {name: type(cls()).__name__ for name, cls in PLANNERS.items()} == {
        "fd": "FastDownward",
        "ff": "FF",
    }
