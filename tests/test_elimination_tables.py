"""The solver's compact tables and shortcuts answer exactly as the plain ones do.

Min-plus elimination (``rosreconf.solve.optimum``) has two ways to minimise a role out: adding
every row's candidate cost, and, when row values stay below the gap between candidate
costs, comparing cost levels first and adding once per kept row. The traceback keeps its
choices in a grid of bytes when it is dense enough, else in a dictionary. Each pair must
agree on every input; the end-to-end equivalence (brute force, clingo) is in test_first.py
and test_optimum.py.
"""

from __future__ import annotations

import itertools
import operator

from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.solve.factors import Factor, _join, key_of
from rosreconf.solve.optimum import Choices, _min_out_added, _min_out_dominated

NAMES = [f"c{i}" for i in range(6)]


@st.composite
def tables(draw: st.DrawFn) -> tuple[Factor, list[list[str]], int]:
    """Draw a table over 1-3 roles (role 0 to minimise out), its candidates and the row cap."""
    width = draw(st.integers(1, 3))
    alive = [draw(st.lists(st.sampled_from(NAMES), min_size=1, max_size=4, unique=True))]
    alive += [
        draw(st.lists(st.sampled_from(NAMES), min_size=1, max_size=3, unique=True))
        for _ in range(width - 1)
    ]
    cap = draw(st.sampled_from([1, 7, 2**70]))  # 2**70: values of many digits, as at 10k roles
    rows = {}
    for combo in itertools.product(*alive):
        if draw(st.booleans()):
            rows[combo] = draw(st.integers(0, cap - 1))
    return Factor(tuple(range(width)), rows), alive, cap


@settings(max_examples=300, deadline=None)
@given(drawn=tables(), data=st.data())
def test_dominated_minimising_equals_adding(
    drawn: tuple[Factor, list[list[str]], int], data: st.DataObject
) -> None:
    f, alive, cap = drawn
    levels = data.draw(st.lists(st.integers(0, 3), min_size=len(alive[0]), max_size=len(alive[0])))
    cost = {c: level * cap for c, level in zip(alive[0], levels, strict=True)}  # gap >= cap
    rank = {c: i for i, c in enumerate(reversed(NAMES))}  # ties: not alphabetical
    rest = key_of(list(range(1, len(f.scope))))
    distinct = sorted(set(cost.values()))
    assert _min_out_dominated(f, 0, rest, cost, distinct, rank) == _min_out_added(
        f, 0, rest, cost, rank
    )


@settings(max_examples=200, deadline=None)
@given(
    alive=st.lists(
        st.lists(st.sampled_from(NAMES), min_size=1, max_size=6, unique=True),
        min_size=1,
        max_size=4,
    ),
    data=st.data(),
)
def test_choices_grid_and_dictionary_pick_alike(
    alive: list[list[str]], data: st.DataObject
) -> None:
    scope = tuple(range(1, len(alive)))
    grid = list(itertools.product(*(alive[v] for v in scope)))
    keys = data.draw(st.lists(st.sampled_from(grid), unique=True))
    arg = {k: data.draw(st.sampled_from(alive[0])) for k in keys}
    where = [{c: j for j, c in enumerate(names)} for names in alive]
    choices = Choices(0, scope, dict(arg), alive)
    for key, want in arg.items():
        chosen = dict(zip(scope, key, strict=True))
        assert choices.pick(chosen, where) == want


def test_choices_keep_a_sparse_table_as_a_dictionary() -> None:
    alive = [["a", "b"], [f"p{i}" for i in range(100)], [f"q{i}" for i in range(100)]]
    arg: dict[tuple[str, ...], str] = {("p3", "q7"): "b", ("p99", "q0"): "a"}
    choices = Choices(0, (1, 2), arg, alive)
    assert choices._grid is None  # 10,000 cells for 2 rows: the dictionary is smaller
    where = [{c: j for j, c in enumerate(names)} for names in alive]
    assert choices.pick({1: "p3", 2: "q7"}, where) == "b"
    assert choices.pick({1: "p99", 2: "q0"}, where) == "a"
    dense = Choices(0, (1,), {(p,): "a" for p in alive[1]}, alive)
    assert dense._grid is not None and len(dense._grid) == 100


@settings(max_examples=300, deadline=None)
@given(a=tables(), b=tables(), one=st.sampled_from([0, 1]))
def test_join_skipping_the_neutral_value_equals_combining_every_row(
    a: tuple[Factor, list[list[str]], int],
    b: tuple[Factor, list[list[str]], int],
    one: int,
) -> None:
    times = operator.add if one == 0 else operator.mul
    fa, fb = a[0], Factor(tuple(v + 1 for v in b[0].scope), b[0].rows)  # overlapping scopes
    fa.rows = {k: (one if i % 2 else w) for i, (k, w) in enumerate(fa.rows.items())}
    joined = _join(fa, fb, times, 10**9, one)
    plain: dict[tuple[str, ...], int] = {}
    for ra, wa in fa.rows.items():
        for rb, wb in fb.rows.items():
            row = dict(zip(fa.scope, ra, strict=True))
            if all(row.get(v, c) == c for v, c in zip(fb.scope, rb, strict=True)):
                row.update(zip(fb.scope, rb, strict=True))
                plain[tuple(row[v] for v in joined.scope)] = times(wa, wb)
    assert joined.rows == plain
