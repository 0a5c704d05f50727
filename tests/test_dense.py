"""Dense grids answer exactly as the sparse tables do: same optimum, same count, same choices.

``rosreconf.solve.dense`` eliminates over one integer per cell (argmin and tie-break encoded
in the value) and falls back to the sparse tables of ``rosreconf.solve.factors`` when a grid
would be too wide. Here the two are run side by side on random libraries (ties in cost
included) and must pick the very same configuration, not only one of equal cost; the
end-to-end equivalence with brute force and clingo is in test_optimum.py and test_first.py.
"""

from __future__ import annotations

import itertools
import operator
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace
from typing import Any

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve import counting, dense, gridtables, optimum
from rosreconf.solve.dense import Grid, MinOut, TooWide, gather
from rosreconf.solve.factors import constraint_factors
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.objective import Objective, unary_costs

PROPS = settings(max_examples=examples(150), deadline=None)


@contextmanager
def _sparse_only() -> Iterator[None]:
    """Make every grid too wide, so the sparse tables answer (the fallback, exercised)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dense, "DENSE_CELLS", 0)
        yield


@contextmanager
def _dense_spy(module: Any, name: str) -> Iterator[list[int]]:
    """Count the calls of ``module.name`` that returned (the dense path really answered)."""
    real: Callable[..., Any] = getattr(module, name)
    answered: list[int] = []

    def spy(*args: Any, **kwargs: Any) -> Any:
        out = real(*args, **kwargs)
        answered.append(1)
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(module, name, spy)
        yield answered


def _with_costs(library: ComponentLibrary, data: st.DataObject) -> ComponentLibrary:
    comps = [
        replace(c, metrics={"cost": data.draw(st.sampled_from([0.0, 0.5, 1.0, 2.25]))})
        for c in library
    ]
    return ComponentLibrary(library.name, tuple(comps))


@PROPS
@given(problem=problems(), data=st.data())
def test_dense_optimum_is_the_sparse_optimum_same_configuration(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    library = _with_costs(library, data)
    failed = frozenset(data.draw(st.sets(st.sampled_from([c.name for c in library]), max_size=1)))
    configs = brute_force(library, schema, failed)
    current = dict(data.draw(st.sampled_from(configs)).assignment) if configs else {}
    objective = Objective(current=current, weights={"cost": 1.0})
    inst = compile_instance(library, schema, failed)
    costs = unary_costs(inst, objective)
    with _dense_spy(optimum, "_dense_minimise") as answered:
        fast = optimum.minimise(inst, costs)
    with _sparse_only():
        slow = optimum.minimise(inst, costs)
    assert fast == slow
    if configs:
        assert answered, "the dense grids did not answer"
        assert fast is not None
        assert objective.cost(inst, fast[0]) == min(objective.cost(inst, c) for c in configs)
    else:
        assert fast is None


@PROPS
@given(problem=problems(), data=st.data())
def test_dense_count_is_the_sparse_count_and_brute_force(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    failed = frozenset(data.draw(st.sets(st.sampled_from([c.name for c in library]), max_size=1)))
    inst = compile_instance(library, schema, failed)
    with _dense_spy(counting, "run") as answered:
        fast = counting.count(inst)
    with _sparse_only():
        slow = counting.count(inst)
    assert fast == slow == len(brute_force(library, schema, failed))
    assert answered or fast == 0  # only an emptied role skips the grids


@settings(max_examples=200, deadline=None)
@given(data=st.data())
def test_gather_lays_a_grid_over_more_roles_as_indexing_does(data: st.DataObject) -> None:
    n = data.draw(st.integers(1, 4))
    sizes = data.draw(st.lists(st.integers(1, 4), min_size=n, max_size=n))
    scope = tuple(data.draw(st.permutations(range(n)))[: data.draw(st.integers(1, n))])
    axes = tuple(data.draw(st.permutations(range(n))))
    cells = list(itertools.product(*(range(sizes[v]) for v in scope)))
    g = Grid(scope, [data.draw(st.integers(0, 99)) for _ in cells])
    value = dict(zip(cells, g.data, strict=True))
    expected = [
        value[tuple(dict(zip(axes, at, strict=True))[v] for v in scope)]
        for at in itertools.product(*(range(sizes[v]) for v in axes))
    ]
    assert gather(g, axes, sizes) == expected


def test_costs_too_large_for_small_integers_go_to_the_sparse_tables() -> None:
    with pytest.raises(TooWide):
        MinOut([[0, 2**70]])
    assert MinOut([[0, 5], [1]]).inf > MinOut([[0, 5], [1]]).feasible


def test_a_grid_wider_than_the_cap_is_refused() -> None:
    step = MinOut([[0, 0], [0, 0]])
    assert dense.run([Grid((0, 1), [0, 0, 0, 0])], [0, 1], [2, 2], step, 4) == ([0], [])
    with pytest.raises(TooWide):
        dense.run([Grid((0, 1), [0, 0, 0, 0])], [0, 1], [2, 2], MinOut([[0, 0], [0, 0]]), 3)
    assert dense.cap_for(7) == 7  # a row budget below the cap is the cap: never more rows


@PROPS
@given(problem=problems(), data=st.data())
def test_grids_made_directly_are_the_constraint_tables(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    failed = frozenset(data.draw(st.sets(st.sampled_from([c.name for c in library]), max_size=1)))
    inst = compile_instance(library, schema, failed)
    alive = [[c.name for c in dom] for dom in inst.domains]
    sizes = [len(a) for a in alive]
    for present, absent, combine in ((0, 99, operator.add), (1, 0, operator.mul)):
        direct = gridtables.constraint_grids(inst, alive, present, absent, combine, 10**6)
        made = gridtables.grids(
            constraint_factors(inst, alive, 1), alive, present, absent, combine, 10**6
        )
        assert len(direct) == len(made)
        by_roles = {frozenset(g.scope): g for g in made}
        for g in direct:
            other = by_roles[frozenset(g.scope)]
            assert g.data == gather(other, g.scope, sizes), g.scope
