"""Optional roles (issue 22): every solver and analysis agrees with the definition's brute force.

The random libraries of ``randomlib.problems(optional_roles=True)`` make some roles optional;
the brute force tries every optional role empty as well, and the definition
(``rosreconf.model.validity``) decides. Enumeration (clingo), counting, the optimum
(elimination and clingo), the marginals, single points of failure and the probability of
staying reconfigurable must all agree with it.
"""

from __future__ import annotations

import itertools
import math

from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.analysis.library import analyse
from rosreconf.analysis.marginals import marginals
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.counting import count
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.optimum import first
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, Objective

PROPS = settings(max_examples=examples(100))
Problem = tuple[ComponentLibrary, InteroperabilitySchema]


@PROPS
@given(problem=problems(optional_roles=True), data=st.data())
def test_optional_roles_enumeration_count_and_first_agree_with_brute_force(
    problem: Problem, data: st.DataObject
) -> None:
    library, schema = problem
    names = [c.name for c in library]
    failed = frozenset(data.draw(st.sets(st.sampled_from(names), max_size=2)))
    inst = compile_instance(library, schema, failed)
    expected = brute_force(library, schema, failed)
    listed = list(ClingoEngine().configurations(inst))
    assert [c.assignment for c in listed] == [c.assignment for c in expected]
    assert count(inst) == len(expected)
    found = first(inst)
    assert (found.assignment if found else None) == (expected[0].assignment if expected else None)


@PROPS
@given(problem=problems(optional_roles=True), data=st.data())
def test_optional_roles_optimum_is_the_brute_force_least_change(
    problem: Problem, data: st.DataObject
) -> None:
    """From every valid configuration as the running one, with metric weights: one least cost."""
    library, schema = problem
    configs = brute_force(library, schema)
    inst = compile_instance(library, schema)
    if not configs:
        assert EliminationEngine().best(inst, Objective()) is None
        return
    current = data.draw(st.sampled_from(configs)).mapping
    objective = Objective(current=current, weights={"cost": 1.0})
    least = min(objective.cost(inst, c) for c in configs)
    for engine in (EliminationEngine(), ClingoEngine()):
        best = engine.best(inst, objective)
        assert best is not None
        assert best in configs, engine.name
        assert objective.cost(inst, best) == least == (0, least[1]), engine.name


@PROPS
@given(problem=problems(optional_roles=True))
def test_optional_roles_marginals_count_empty_choices(problem: Problem) -> None:
    library, schema = problem
    inst = compile_instance(library, schema)
    expected = [dict.fromkeys((c.name for c in dom), 0) for dom in inst.domains]
    configs = brute_force(library, schema)
    for config in configs:
        for u, (role, comp) in enumerate(config.assignment):
            expected[u][as_candidate(role, comp)] += 1
    marg = marginals(inst)
    assert marg.total == len(configs)
    assert marg.per_role == expected


@settings(max_examples=examples(60))
@given(problem=problems(optional_roles=True))
def test_optional_roles_single_points_of_failure_and_probability(problem: Problem) -> None:
    """An empty optional role is no single point of failure; what fails is what every
    configuration uses; the probability is the brute force over failure states."""
    library, schema = problem
    configs = [frozenset(c.components) for c in brute_force(library, schema)]
    result = analyse(library, schema)
    expected = sorted(frozenset.intersection(*configs)) if configs else []
    assert result.single_points_of_failure == expected
    p = {c.name: c.failure_probability or 0.0 for c in library}
    names = sorted(p)
    total = 0.0
    for state in itertools.product([False, True], repeat=len(names)):
        dead = {n for n, f in zip(names, state, strict=True) if f}
        weight = math.prod(p[n] if n in dead else 1 - p[n] for n in names)
        if any(not (cfg & dead) for cfg in configs):
            total += weight
    if configs:
        assert result.reliability is not None
        assert math.isclose(result.reliability.probability, total, abs_tol=1e-12)
