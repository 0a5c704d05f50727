"""Cross-check the PDDL encoding against clingo on generated libraries (rosreconf.synthetic).

Two checks: enumerating by planning (forbid each configuration found) yields exactly
clingo's set; and every Fast Downward plan on a random small instance, with random failures,
maps back to a configuration that ``validity.is_valid`` accepts (or FD proves what clingo
proves: no configuration).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from pddlcheck import chosen, plan_all

from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.validity import is_valid
from rosreconf.planning.pddl import PddlTask, render
from rosreconf.planning.planners import FastDownward, PlanResult, PlanStatus, solve
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import Objective, configurations
from rosreconf.synthetic import generate, write

pytestmark = pytest.mark.planner


@cache
def generated(
    roles: int, candidates: int, coupling: float, seed: int
) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Write one generated instance to a temp dir and load it back (cached per arguments)."""
    import tempfile

    folder = Path(tempfile.mkdtemp(prefix="rosreconf-gen-"))
    write(generate(roles, candidates, coupling, seed), folder)
    loaded = load_paths([folder / "libraries", folder / "schemas"])
    return loaded.library, loaded.schemas[0]


def run(task: PddlTask) -> PlanResult:
    """Plan with the default first-plan search (ff-first; lama-first is tested in test_pddl)."""
    return solve(FastDownward(), task.domain, task.problem, timeout=30, memory_limit_mb=1024)


CASES = [  # (roles, candidates, coupling, seed, failed): at most ~15 configurations each
    (4, 2, 1.0, 1, ()),
    (5, 2, 1.0, 2, ()),
    (6, 2, 1.0, 1, ()),
    (8, 2, 1.0, 1, ()),
    (4, 3, 1.0, 2, ("SEN0_C1", "PER0_C2")),
    (5, 3, 0.5, 0, ("SEN0_C0", "CTL0_C1", "PER0_C1", "SEN1_C2")),
]


@pytest.mark.parametrize(("r", "k", "coupling", "seed", "failed"), CASES)
def test_planning_enumerates_exactly_clingos_configurations(
    r: int, k: int, coupling: float, seed: int, failed: tuple[str, ...]
) -> None:
    library, s = generated(r, k, coupling, seed)
    expected = set(configurations(library, s, failed))
    assert 0 < len(expected) <= 30
    assert plan_all(library, s, failed, most=30) == expected


@settings(max_examples=examples(15))
@given(
    r=st.integers(4, 8),
    k=st.integers(2, 3),
    seed=st.integers(0, 5),
    data=st.data(),
)
def test_every_plan_maps_back_to_a_valid_configuration(
    r: int, k: int, seed: int, data: st.DataObject
) -> None:
    library, s = generated(r, k, 0.5, seed)
    names = sorted(c.name for c in library.components)
    failed = tuple(data.draw(st.lists(st.sampled_from(names), max_size=3, unique=True)))
    task = render(compile_instance(library, s, failed), Objective(dict(s.nominal)))
    result = run(task)
    if result.solved:
        assert is_valid(chosen(task, result, s), library, s, failed)
    else:
        assert result.status is PlanStatus.UNSOLVABLE_PROVEN, result.message
        assert next(configurations(library, s, failed), None) is None


@pytest.mark.parametrize(
    ("roles", "candidates", "seed", "failures"),
    [(5, 2, 1, 1), (6, 3, 2, 1), (8, 2, 3, 2), (6, 3, 4, 0)],
)
def test_optimal_planner_and_solver_agree_on_the_objective(
    roles: int, candidates: int, seed: int, failures: int
) -> None:
    """Issue 7: with an optimal search, Fast Downward's objective equals the solver's optimum.

    The running configuration is the nominal one; a few of its components fail, and both the
    planner (astar with lmcut: optimal for action costs) and the elimination optimum must
    reach the same (changes, metric) value, each with a valid configuration.
    """
    from rosreconf.planning.replan import plan
    from rosreconf.solve.running import change_objective
    from rosreconf.solve.solver import optimise

    library, schema = generated(roles, candidates, 0.2, seed)
    current = dict(schema.nominal)
    failed = sorted(current.values())[:failures]
    weights = {"cost": 1.0}
    result = plan(
        library,
        schema,
        failed,
        current,
        FastDownward("astar(lmcut())"),
        weights=weights,
        timeout=60,
    )
    inst = compile_instance(library, schema, failed)
    objective = change_objective(library, schema, current, weights)  # restarts counted too
    best = optimise(inst, objective).configuration
    if best is None:
        assert result.status is PlanStatus.UNSOLVABLE_PROVEN
        return
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.configuration is not None
    assert is_valid(result.configuration, library, schema, failed)
    assert objective.cost(inst, result.configuration) == objective.cost(inst, best)


@pytest.mark.parametrize(("failed", "fewest"), [("NSM3", 10), ("NCA1", 8), ("NFB21", 10)])
def test_optimal_planner_counts_restarts_as_the_solver_does(failed: str, fewest: int) -> None:
    """An optimal plan restarts the kept consumers a failover rewires, and costs what the
    solver proves (and tests/test_watcher_fewest.py checks by brute force): 9 role changes
    and NREA's restart after NSM3, 3 and five restarts after NCA1."""
    from rosreconf.formats.loader import load_bundled
    from rosreconf.planning.replan import plan

    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
    result = plan(
        bundle.library, schema, [failed], dict(schema.nominal), FastDownward("astar(lmcut())")
    )
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.fewest_changes == fewest
    assert sum(c.counted for c in result.changes) == fewest
    assert any(step.startswith("restart NREA") for step in result.steps)
