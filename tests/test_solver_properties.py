"""The engines agree with the one definition of validity on random libraries."""

from __future__ import annotations

import itertools
import math

from conftest import examples
from hypothesis import example, given, settings
from hypothesis import strategies as st
from randomlib import IFACES, brute_force, brute_force_probability, problems

from rosreconf.analysis import library as library_analysis
from rosreconf.analysis.library import analyse, exact_probability
from rosreconf.analysis.marginals import marginals
from rosreconf.analysis.reliability import grouped_exact
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Interface,
    InteroperabilitySchema,
    Role,
    SystemGraph,
)
from rosreconf.model.validity import type_clash
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import ClingoEngine, Objective

PROPS = settings(max_examples=examples(120))

A, _, _, A2 = IFACES  # topic "a" with type m/A, and topic "a" with type m/A2


def _problem(
    provides: list[frozenset[Interface]],
) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Return one component per role (role i, label li) providing ``provides[i]``, no edges."""
    roles = tuple(Role(f"r{i}", f"l{i}") for i in range(len(provides)))
    comps = tuple(
        Component(f"C{i}_0", f"l{i}", provides=p, failure_probability=0.0)
        for i, p in enumerate(provides)
    )
    schema = InteroperabilitySchema("s", SystemGraph(roles, ()), "skill", "env")
    return ComponentLibrary("random", comps), schema


SELF_CLASH = _problem([frozenset(), frozenset({A2, IFACES[1]}), frozenset({A, A2})])
"""Found by ``make explore``: C2_0 provides topic a with two types, C1_0 provides a as m/A2.

The definition (``validity.type_clash``) kept one provision per label of C2_0, so whether it
saw the clash with C1_0 depended on set order (the hash seed): the brute force then found a
configuration that the solvers, which see every provision, rightly refuse.
"""


def test_a_type_clash_is_seen_whichever_type_the_other_also_provides() -> None:
    """Both types of a two-typed provider clash with the other's; neither order hides it."""
    both = Component("both", "l", provides=frozenset({A, A2}))
    for one in (A, A2):
        single = Component("single", "l", provides=frozenset({one}))
        assert type_clash(single, both) is not None
        assert type_clash(both, single) is not None


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


@settings(max_examples=examples(60))
@given(problem=problems())
@example(problem=SELF_CLASH)
def test_probability_equals_brute_force_over_failure_states(
    problem: tuple[ComponentLibrary, InteroperabilitySchema],
) -> None:
    library, schema = problem
    configs = [frozenset(c.components) for c in brute_force(library, schema)]
    p = {c.name: c.failure_probability or 0.0 for c in library}
    total = brute_force_probability(configs, p)
    assert math.isclose(exact_probability(configs, p), total, abs_tol=1e-12)
    result = analyse(library, schema)
    if configs:
        assert result.reliability is not None
        assert math.isclose(result.reliability.probability, total, abs_tol=1e-12)
        grouped = grouped_exact(library, schema, frozenset(), p, 10**6)
        assert grouped is not None
        assert math.isclose(grouped[0], total, abs_tol=1e-12)


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


@PROPS
@given(problem=problems(), data=st.data())
def test_marginals_are_brute_force_counts_per_role_and_candidate(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    """The two-pass elimination counts, per role and candidate, what listing counts."""
    library, schema = problem
    failed = frozenset(data.draw(st.sets(st.sampled_from([c.name for c in library]), max_size=2)))
    inst = compile_instance(library, schema, failed)
    expected = [dict.fromkeys((c.name for c in dom), 0) for dom in inst.domains]
    configs = brute_force(library, schema, failed)
    for config in configs:
        for u, (_, comp) in enumerate(config.assignment):
            expected[u][comp] += 1
    marg = marginals(inst)
    assert marg.total == len(configs)
    assert marg.per_role == expected
