"""Candidates no rule tells apart are solved once: held to brute force, clingo and validity.

``instance.interchangeable`` groups a role's candidates that provide and require the same
interfaces and name no other component (nor are named); counting keeps one per class and
weighs it by the class's size, minimising keeps the class's cheapest. Random libraries
rarely draw two such candidates, so these problems copy components into twins on purpose.
"""

from __future__ import annotations

from dataclasses import replace
from types import MappingProxyType

from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    InteroperabilitySchema,
    Role,
    SystemGraph,
)
from rosreconf.model.validity import is_valid
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance, interchangeable, prune
from rosreconf.solve.optimum import first
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, Objective


@st.composite
def with_twins(draw: st.DrawFn) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Draw a random problem, then give some components twins (same interfaces, new name).

    A twin names nothing; the original keeps or (sometimes) loses its needs and excludes,
    so both classes of several members and candidates kept alone are drawn.
    """
    library, schema = draw(problems())
    comps = []
    for c in library:
        if draw(st.booleans()):
            c = replace(c, needs=frozenset(), excludes=frozenset())
        comps.append(c)
        for k in range(draw(st.integers(0, 2))):
            comps.append(
                replace(
                    c,
                    name=f"{c.name}_twin{k}",
                    needs=frozenset(),
                    excludes=frozenset(),
                    metrics=MappingProxyType({"cost": float(draw(st.integers(0, 3)))}),
                )
            )
    return ComponentLibrary(library.name, tuple(comps)), schema


@settings(max_examples=examples(150), deadline=None)
@given(problem=with_twins())
def test_members_of_a_class_swap_without_changing_validity(
    problem: tuple[ComponentLibrary, InteroperabilitySchema],
) -> None:
    """Swapping any candidate for another of its class keeps every configuration valid."""
    library, schema = problem
    inst = compile_instance(library, schema)
    alive, _, _ = prune(inst)
    classes = interchangeable(inst, alive)
    assert [sorted(n for cls in role for n in cls) for role in classes] == [
        sorted(a) for a in alive
    ]
    roles = [r.name for r in inst.roles]
    for config in brute_force(library, schema):
        chosen = dict(config.assignment)
        for r, role in enumerate(classes):
            members = next(cls for cls in role if chosen[roles[r]] in cls)
            for other in members:
                swapped = Configuration.of(schema.name, {**chosen, roles[r]: other}, inst.roles)
                assert is_valid(swapped, library, schema), (chosen, roles[r], other)


@settings(max_examples=examples(150), deadline=None)
@given(problem=with_twins())
def test_count_first_and_optimum_over_classes_equal_the_plain_answers(
    problem: tuple[ComponentLibrary, InteroperabilitySchema],
) -> None:
    """Count = brute force; first = clingo's first; optimum's cost = clingo's proven one."""
    library, schema = problem
    inst = compile_instance(library, schema)
    configs = brute_force(library, schema)
    assert count(inst) == len(configs)
    assert first(inst) == ClingoEngine().first(inst)
    objective = Objective(weights={"cost": 1.0})
    ours = EliminationEngine().best(inst, objective)
    theirs = ClingoEngine().best(inst, objective)
    if theirs is None:
        assert ours is None
        return
    assert ours is not None and is_valid(ours, library, schema)
    assert objective.score(inst, ours) == objective.score(inst, theirs)
    # and no valid configuration is cheaper (brute force), whichever twin it uses
    assert objective.score(inst, ours) == min(objective.score(inst, c) for c in configs)


def test_classes_keep_alive_order_and_leave_named_candidates_alone() -> None:
    """A naming (N) or named (B) candidate is its own class; twins share one, in order."""
    comps = (
        Component("A", "l0"),
        Component("N", "l0", needs=frozenset({"B"})),
        Component("A2", "l0"),
        Component("A3", "l0"),
        Component("B", "l1"),
        Component("B2", "l1"),
    )
    roles = (Role("r0", "l0"), Role("r1", "l1"))
    schema = InteroperabilitySchema("s", SystemGraph(roles, ()), "skill", "env")
    inst = compile_instance(ComponentLibrary("fixed", comps), schema)
    alive, _, _ = prune(inst)
    assert interchangeable(inst, alive) == [[["A", "A2", "A3"], ["N"]], [["B"], ["B2"]]]
    assert count(inst) == 7  # A, A2, A3 with B or B2; N needs B
