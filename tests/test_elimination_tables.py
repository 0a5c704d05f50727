"""The solver's compact tables and shortcuts answer exactly as the plain ones do.

Min-plus elimination (``rosreconf.solve.optimum``) minimises a role out by cost level first
and adds a candidate's cost once per kept row when every row value is below the gap
between two candidates' costs, instead of adding every row's cost; the traceback keeps
its choices in a grid of bytes when it is dense enough, else in a dictionary; joining
skips combining with the neutral value. Each is held to the plain way on every input
here; the end-to-end equivalence (brute force, clingo) is in test_first.py and
test_optimum.py.
"""

from __future__ import annotations

import itertools
import operator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.solve.counting import _sum_out
from rosreconf.solve.minout import Choices, join_minimise_out, minimise_out
from rosreconf.solve.tables import Factor, TooHard, _join, join_sum_out

NAMES = [f"c{i}" for i in range(6)]


def _widens(a: Factor, b: Factor) -> bool:
    """Say whether joining adds roles to the valued table (the one a join keeps left)."""
    left, right = (b, a) if a.unit and not b.unit else (a, b)
    return not set(right.scope) <= set(left.scope)


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


def _plain_min_out(
    f: Factor, cost: dict[str, int], rank: dict[str, int]
) -> tuple[dict[tuple[str, ...], int], dict[tuple[str, ...], str]]:
    """Minimise role 0 out the plain way: add every row's cost, keep the least, then rank."""
    best: dict[tuple[str, ...], int] = {}
    arg: dict[tuple[str, ...], str] = {}
    for row, w in f.rows.items():
        c, k, v = row[0], row[1:], w + cost[row[0]]
        if k not in best or v < best[k] or (v == best[k] and rank[c] < rank[arg[k]]):
            best[k], arg[k] = v, c
    return best, arg


@settings(max_examples=400, deadline=None)
@given(drawn=tables(), data=st.data())
def test_minimising_out_equals_adding_every_cost(
    drawn: tuple[Factor, list[list[str]], int], data: st.DataObject
) -> None:
    f, alive, cap = drawn
    scale = data.draw(st.sampled_from([1, cap, 2 * cap, 3**50]))  # cap: costs dominate values
    levels = st.integers(0, 3).map(lambda n: n * scale) | st.integers(0, 3 * cap)
    cost = {c: data.draw(levels) for c in alive[0]}
    rank = {c: i for i, c in enumerate(reversed(NAMES))}  # ties: not alphabetical
    want, want_arg = _plain_min_out(f, cost, rank)
    trace: list[Choices] = []
    offsets: list[int] = []
    got = minimise_out(f, 0, cost, rank, trace, offsets, alive)
    low = min(want.values(), default=0)
    assert got.scope == f.scope[1:]
    assert got.rows == {k: v - low for k, v in want.items()}
    assert offsets == ([low] if low else [])
    where = [{c: j for j, c in enumerate(names)} for names in alive]
    for k, c in want_arg.items():
        assert trace[-1].pick(dict(zip(got.scope, k, strict=True)), where) == c


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


@settings(max_examples=300, deadline=None)
@given(
    a=tables(),
    b=tables(),
    unit=st.sampled_from(["neither", "a", "b", "both"]),
    ones=st.booleans(),
    shift=st.integers(0, 1),
)
def test_join_and_sum_out_in_one_pass_equals_joining_then_summing(
    a: tuple[Factor, list[list[str]], int],
    b: tuple[Factor, list[list[str]], int],
    unit: str,
    ones: bool,
    shift: int,
) -> None:
    """Counting's fused step builds the same table as the join it skips, then the sum."""
    values = enumerate(a[0].rows.items())
    fa = Factor(a[0].scope, {k: 1 if ones and i % 2 else w + 1 for i, (k, w) in values})
    # b's roles: role 0 (summed out: it is in every table of its step) and a's other roles
    # or (shift) partly new ones, so that both a filter and a widening join are drawn
    scope_b = (0, *(v + shift for v in b[0].scope[1:]))
    fb = Factor(scope_b, {k: w + 1 for k, w in b[0].rows.items()})
    if unit in ("a", "both"):
        fa = Factor(fa.scope, dict.fromkeys(fa.rows, 1), unit=True)
    if unit in ("b", "both"):
        fb = Factor(fb.scope, dict.fromkeys(fb.rows, 1), unit=True)
    joined = _join(fa, fb, operator.mul, 10**9)
    plain = _sum_out(joined, 0)
    fused = join_sum_out(fa, fb, 0, 10**9)
    assert (fused.scope, fused.rows) == (plain.scope, plain.rows)
    if joined.rows and _widens(fa, fb):  # the budget counts the joined rows
        with pytest.raises(TooHard):
            join_sum_out(fa, fb, 0, len(joined.rows) - 1)
        assert join_sum_out(fa, fb, 0, len(joined.rows)).rows == plain.rows


@settings(max_examples=300, deadline=None)
@given(
    a=tables(),
    b=tables(),
    unit=st.sampled_from(["neither", "a", "b", "both"]),
    shift=st.integers(0, 1),
    data=st.data(),
)
def test_join_and_minimise_out_in_one_pass_equals_joining_then_minimising(
    a: tuple[Factor, list[list[str]], int],
    b: tuple[Factor, list[list[str]], int],
    unit: str,
    shift: int,
    data: st.DataObject,
) -> None:
    """The optimum's fused step: same table, offsets and traceback as join then minimise."""
    fa, alive, cap = a
    scope_b = (0, *(v + shift for v in b[0].scope[1:]))
    fb = Factor(scope_b, dict(b[0].rows))
    if unit in ("a", "both"):
        fa = Factor(fa.scope, dict.fromkeys(fa.rows, 0), unit=True)
    if unit in ("b", "both"):
        fb = Factor(fb.scope, dict.fromkeys(fb.rows, 0), unit=True)
    roles = max((*fa.scope, *fb.scope)) + 1
    alive = [list(NAMES) for _ in range(roles)]  # every name any row may hold, per role
    scale = data.draw(st.sampled_from([1, cap, 2 * cap, 3**50]))  # large: the dominated path
    levels = st.integers(0, 3).map(lambda n: n * scale) | st.integers(0, 3 * cap)
    cost = {c: data.draw(levels) for c in NAMES}
    rank = {c: i for i, c in enumerate(reversed(NAMES))}
    plain_trace: list[Choices] = []
    plain_offsets: list[int] = []
    joined = _join(fa, fb, operator.add, 10**9, 0)
    want = minimise_out(joined, 0, cost, rank, plain_trace, plain_offsets, alive)
    trace: list[Choices] = []
    offsets: list[int] = []
    got = join_minimise_out(fa, fb, 0, cost, rank, trace, offsets, alive, 10**9)
    assert (got.scope, got.rows, offsets) == (want.scope, want.rows, plain_offsets)
    where = [{c: j for j, c in enumerate(names)} for names in alive]
    for k in want.rows:
        chosen = dict(zip(want.scope, k, strict=True))
        assert trace[-1].pick(chosen, where) == plain_trace[-1].pick(chosen, where)
    if joined.rows and _widens(fa, fb):  # the budget counts the joined rows
        with pytest.raises(TooHard):
            join_minimise_out(fa, fb, 0, cost, rank, [], [], alive, len(joined.rows) - 1)
