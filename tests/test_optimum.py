"""Elimination's optimum equals the brute-force minimum and clingo's, on the same integers."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.validity import is_valid
from rosreconf.solve.factors import TooHard
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.optimum import minimise
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, Objective, optimise, unary_costs
from rosreconf.synthetic import generate, write

PROPS = settings(max_examples=examples(150))


def _with_metrics(library: ComponentLibrary, data: st.DataObject) -> ComponentLibrary:
    """Give every component a small random cost and latency (ties included)."""
    comps = []
    for c in library:
        cost = data.draw(st.sampled_from([0.0, 0.5, 1.0, 2.25]))
        latency = data.draw(st.sampled_from([0.0, 0.001, 3.0]))
        comps.append(replace(c, metrics={"cost": cost, "latency": latency}))
    return ComponentLibrary(library.name, tuple(comps))


@PROPS
@given(problem=problems(), data=st.data())
def test_elimination_optimum_is_brute_force_minimum_and_clingos(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    library = _with_metrics(library, data)
    names = [c.name for c in library]
    failed = frozenset(data.draw(st.sets(st.sampled_from(names), max_size=1)))
    configs = brute_force(library, schema, failed)
    current = dict(data.draw(st.sampled_from(configs)).assignment) if configs else {}
    weights = data.draw(st.sampled_from([{}, {"cost": 1.0}, {"cost": 1.0, "latency": -0.5}]))
    objective = Objective(current=current, weights=weights)
    inst = compile_instance(library, schema, failed)
    best = EliminationEngine().best(inst, objective)
    reference = ClingoEngine().best(inst, objective)
    tiny = optimise(inst, objective, max_rows=0)  # any table is too big: clingo answers
    if not configs:
        assert best is None and reference is None and tiny.configuration is None
        return
    assert best is not None and reference is not None and tiny.configuration is not None
    assert is_valid(best, library, schema, failed)
    least = min(objective.cost(inst, c) for c in configs)
    assert objective.cost(inst, best) == least == objective.cost(inst, reference)
    assert objective.cost(inst, tiny.configuration) == least
    assert EliminationEngine().best(inst, objective) == best  # deterministic
    found = minimise(inst, unary_costs(inst, objective))
    assert found is not None and found[1] == least


def _load(
    tmp: Path, roles: int, candidates: int
) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    write(generate(roles, candidates, 0.2, seed=roles), tmp)
    loaded = load_paths([tmp / "libraries", tmp / "schemas"])
    return loaded.library, loaded.schemas[0]


def test_too_hard_is_raised_for_a_tiny_row_budget(tmp_path: Path) -> None:
    library, schema = _load(tmp_path, 6, 3)
    inst = compile_instance(library, schema)
    with pytest.raises(TooHard):
        EliminationEngine(max_rows=2).best(inst, Objective())
    assert optimise(inst, Objective(), max_rows=2).engine == "clingo"
    assert optimise(inst, Objective()).engine == "elimination"


@pytest.mark.parametrize(("roles", "candidates"), [(20, 3), (50, 5), (60, 10)])
def test_generated_instances_elimination_equals_clingo(
    tmp_path: Path, roles: int, candidates: int
) -> None:
    library, schema = _load(tmp_path, roles, candidates)
    inst = compile_instance(library, schema)
    for current in ({}, dict(schema.nominal or {})):
        objective = Objective(current=current, weights={"cost": 1})
        fast = optimise(inst, objective)
        reference = ClingoEngine().best(inst, objective)
        assert fast.engine == "elimination"
        assert fast.configuration is not None and reference is not None
        assert is_valid(fast.configuration, library, schema)
        assert objective.cost(inst, fast.configuration) == objective.cost(inst, reference)
