"""The engines agree with the one definition of validity on random libraries."""

from __future__ import annotations

import itertools
import math

from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.analysis import library as library_analysis
from rosreconf.analysis.library import analyse, exact_probability
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import ClingoEngine, Objective

PROPS = settings(max_examples=120, deadline=None)


@PROPS
@given(problem=problems(), data=st.data())
def test_enumeration_count_and_brute_force_agree(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    names = [c.name for c in library]
    failed = frozenset(data.draw(st.sets(st.sampled_from(names), max_size=2)))
    inst = compile_instance(library, schema, failed)
    listed = list(ClingoEngine().configurations(inst))
    expected = brute_force(library, schema, failed)
    # Same set, and the stream comes in the brute force's (role, library) order.
    assert [c.assignment for c in listed] == [c.assignment for c in expected]
    assert count(inst) == len(expected)


@PROPS
@given(problem=problems())
def test_best_is_optimal(problem: tuple[ComponentLibrary, InteroperabilitySchema]) -> None:
    library, schema = problem
    configs = brute_force(library, schema)
    current = dict(configs[-1].assignment) if configs else {}
    objective = Objective(current=current)
    inst = compile_instance(library, schema)
    best = ClingoEngine().best(inst, objective)
    if not configs:
        assert best is None
        return
    assert best is not None
    assert objective.score(inst, best)[0] == min(objective.score(inst, c)[0] for c in configs)


@settings(max_examples=60, deadline=None)
@given(problem=problems())
def test_probability_equals_brute_force_over_failure_states(
    problem: tuple[ComponentLibrary, InteroperabilitySchema],
) -> None:
    library, schema = problem
    configs = [frozenset(c.components) for c in brute_force(library, schema)]
    p = {c.name: c.failure_probability or 0.0 for c in library}
    names = sorted(p)
    total = 0.0
    for state in itertools.product([False, True], repeat=len(names)):
        dead = {n for n, f in zip(names, state, strict=True) if f}
        weight = math.prod(p[n] if n in dead else 1 - p[n] for n in names)
        if any(not (cfg & dead) for cfg in configs):
            total += weight
    assert math.isclose(exact_probability(configs, p), total, abs_tol=1e-12)
    result = analyse(library, schema)
    if configs:
        assert result.reliability is not None
        assert math.isclose(result.reliability.probability, total, abs_tol=1e-12)


@PROPS
@given(problem=problems())
def test_orthogonality_counterexamples_are_sound_and_complete_when_they_say_so(
    problem: tuple[ComponentLibrary, InteroperabilitySchema],
) -> None:
    """Every listed counterexample is one; when called complete, they explain every failure."""
    library, schema = problem
    result = analyse(library, schema)
    pairs = {frozenset((p.first, p.second)) for p in result.incompatible}
    alone = {u.component for u in result.unusable}
    valid = {frozenset(c.components) for c in brute_force(library, schema)}
    for config in valid:
        assert not alone & config
        assert not any(pair <= config for pair in pairs)
    roles = schema.graph.roles
    doms = [[c.name for c in library.candidates(r.abstraction)] for r in roles]
    for combo in itertools.product(*doms):
        chosen = frozenset(combo)
        explained = bool(alone & chosen) or any(pair <= chosen for pair in pairs)
        if result.counterexamples_complete:
            assert explained == (chosen not in valid), combo


@PROPS
@given(problem=problems(), listed=st.booleans())
def test_single_points_of_failure_are_exactly_the_parts_of_every_configuration(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], listed: bool
) -> None:
    """Both paths: configurations listed, or (EXACT_LIMIT 0, as for a huge library) counted."""
    library, schema = problem
    valid = [frozenset(c.components) for c in brute_force(library, schema)]
    limit = library_analysis.EXACT_LIMIT
    try:
        library_analysis.EXACT_LIMIT = limit if listed else 0
        result = analyse(library, schema, samples=200)
    finally:
        library_analysis.EXACT_LIMIT = limit
    expected = sorted(frozenset.intersection(*valid)) if valid else []
    assert result.single_points_of_failure == expected
