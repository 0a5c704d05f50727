"""Tables over a few roles (``Factor``) and the ways two are joined.

A rule of validity, a count or a cost over a few roles is one table holding only its
allowed rows; elimination (``rosreconf.solve.factors``) joins the tables around a role and
takes the role out. The joins live here, apart from the rules that make the tables: how two
tables combine is the same for counting (values multiply) and optimising (costs add), and
a role's last join can take the role out in the same pass (``join_sum_out``, and
``rosreconf.solve.minout`` for costs) instead of building the widest table of the step.
"""

from __future__ import annotations

import operator
from collections import defaultdict
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

from rosreconf.errors import RosreconfError

MAX_FACTOR_ROWS = 2_000_000
"""Largest table built before giving up on exact elimination."""


class TooHard(RosreconfError):
    """The system graph is too densely connected to eliminate exactly within the row budget."""


@dataclass
class Factor:
    """A table over a few roles; only allowed rows are stored.

    Attributes:
        scope: the role indices the table ranges over, in column order.
        rows: candidate names (one per scope role) -> value (a count, or an encoded cost).
        unit: every value is the neutral one (1 to count, 0 for costs), so joining with this
            table only filters rows and never needs to combine values.
        rule: the rule of ``rosreconf.model.validity.RULES`` a constraint table encodes
            (empty for tables made while eliminating and for cost tables).
    """

    scope: tuple[int, ...]
    rows: dict[tuple[str, ...], int]
    unit: bool = False
    rule: str = ""


Times = Callable[[int, int], int]
"""How two values of one row combine: ``operator.mul`` to count, ``operator.add`` for costs."""

Marginal = Callable[[Factor, int], Factor]
"""How a role leaves a table: summed out to count, minimised out (with argmin) to optimise."""

JoinOut = Callable[[Factor, Factor, int, int], Factor]
"""Join two tables and take a role out in the same pass, never building the joined table
(``join_sum_out``; its arguments are the two tables, the role and the row budget)."""


def _join_all_but_last(
    factors: list[Factor], times: Times, max_rows: int, one: int = 1
) -> tuple[Factor, Factor | None]:
    """Join tables over the same roles first, then widest first, then the fewest new roles.

    The last table is returned unjoined (None when there is only one table), so the caller
    may join it and take the eliminated role out in one pass (``eliminate``'s ``join_out``).

    Several rules often constrain the same roles (an edge realised and the consumer's
    requirement met across it are both tables over the two roles): joined while they are
    small, each only filters the other, instead of each filtering in turn the wide table
    the other roles' tables make (at 1000 roles x 10 candidates counting's filters walked
    648k rows that way, 248k this way).
    """
    same: dict[frozenset[int], Factor] = {}
    for f in factors:
        roles = frozenset(f.scope)
        earlier = same.get(roles)
        same[roles] = f if earlier is None else _join(earlier, f, times, max_rows, one)
    rest = sorted(same.values(), key=lambda f: -len(f.scope))
    merged = rest.pop(0)
    while rest:
        have = set(merged.scope)
        # Tables adding no role are taken first, in order, all in one sweep: picking them
        # one by one rescanned the rest each time, quadratic in a hub's 10,000 tables.
        covered = [f for f in rest if have.issuperset(f.scope)]
        if covered:
            rest = [f for f in rest if not have.issuperset(f.scope)]
            last = covered.pop() if not rest else None
            for f in covered:
                merged = _join(merged, f, times, max_rows, one)
            if last is not None:
                return merged, last
            continue
        pick = min(range(len(rest)), key=lambda i: (len(set(rest[i].scope) - have), i))
        if len(rest) == 1:
            return merged, rest[pick]
        merged = _join(merged, rest.pop(pick), times, max_rows, one)
    return merged, None


def _join_all(factors: list[Factor], times: Times, max_rows: int, one: int = 1) -> Factor:
    """Join tables in ``_join_all_but_last``'s order, the last one too."""
    merged, last = _join_all_but_last(factors, times, max_rows, one)
    return merged if last is None else _join(merged, last, times, max_rows, one)


Row = tuple[str, ...]
"""One row of a table: a candidate name per role of its scope."""


class OnePass(NamedTuple):
    """How a join that takes a role out in the same pass walks its two tables.

    ``join_sum_out`` and ``minout.join_minimise_out`` both walk every row of ``a`` once and
    only the rows of ``b`` agreeing with it on their shared roles (``grouped`` by those
    roles' candidates); each result row is ``head(row)`` (``a``'s row without the role
    taken out, at ``pos``) followed by the tail of the matching ``b`` row (its ``extra``
    roles, which ``a`` lacks).
    """

    a: Factor
    b: Factor
    pos: int
    extra: list[int]
    key_a: Callable[[Row], Row]
    head: Callable[[Row], Row]
    grouped: dict[Row, list[tuple[Row, int]]]


def one_pass(a: Factor, b: Factor, var: int) -> OnePass:
    """Lay out a one-pass join of ``a`` and ``b`` taking ``var`` (in ``a``'s scope) out.

    A table of neutral values goes on the right, as in ``_join``: only ``b`` may be a filter.
    """
    if a.unit and not b.unit:
        a, b = b, a
    extra = [v for v in b.scope if v not in a.scope]
    shared = [v for v in a.scope if v in b.scope]
    key_b = key_of([b.scope.index(v) for v in shared])
    tail_b = key_of([b.scope.index(v) for v in extra])
    grouped: dict[Row, list[tuple[Row, int]]] = defaultdict(list)
    for row, w in b.rows.items():
        grouped[key_b(row)].append((tail_b(row), w))
    pos = a.scope.index(var)
    head = key_of([i for i in range(len(a.scope)) if i != pos])
    return OnePass(a, b, pos, extra, key_of([a.scope.index(v) for v in shared]), head, grouped)


def over_budget(max_rows: int) -> TooHard:
    """Return the error for a join that would pass ``max_rows`` rows (the row budget)."""
    return TooHard(
        f"exact elimination needs over {max_rows} rows; the system graph is too densely connected"
    )


def join_sum_out(a: Factor, b: Factor, var: int, max_rows: int) -> Factor:
    """Join two count tables and sum ``var`` out of the result, in one pass.

    The same table as ``_sum_out(_join(a, b, operator.mul, max_rows), var)`` (counting's
    tests hold the two alike), without building the joined table: at 1000 roles x 10
    candidates, that table is most of the rows of the whole count, each built only to be
    added into its sub-row. The row budget still counts the joined rows, so a schema too
    densely connected to count exactly is refused exactly where it was before.
    """
    a, b, pos, extra, key_a, head, grouped = one_pass(a, b, var)
    rows: dict[tuple[str, ...], int] = defaultdict(int)
    joined = 0
    for row, w in a.rows.items():
        matches = grouped.get(key_a(row), ())
        start = head(row)
        if b.unit:
            for tail, _ in matches:
                rows[start + tail] += w
        else:
            for tail, w2 in matches:
                rows[start + tail] += w2 if w == 1 else w if w2 == 1 else w * w2
        joined += len(matches)
        if joined > max_rows and extra:  # as ``_join``: a filter never grows its table
            raise over_budget(max_rows)
    return Factor((*a.scope[:pos], *a.scope[pos + 1 :], *extra), dict(rows))


def key_of(positions: list[int]) -> Callable[[tuple[str, ...]], tuple[str, ...]]:
    """Return a fast row -> sub-row function (itemgetter, always returning a tuple)."""
    if not positions:
        return lambda row: ()
    if len(positions) == 1:
        p = positions[0]
        return lambda row: (row[p],)
    return operator.itemgetter(*positions)


def _join(a: Factor, b: Factor, times: Times, max_rows: int, one: int = 1) -> Factor:
    """Join two tables; a value equal to ``one`` (the neutral one) is never combined.

    Counts and the first configuration's costs are integers of thousands of digits at
    10,000 roles, and combining such an integer with the neutral value still copies it;
    skipping those combinations is most of what joining them costs.
    """
    if a.unit and not b.unit:  # keep the valued table on the left: only b may be a filter
        a, b = b, a
    shared = [v for v in a.scope if v in b.scope]
    extra = [v for v in b.scope if v not in a.scope]
    key_a = key_of([a.scope.index(v) for v in shared])
    key_b = key_of([b.scope.index(v) for v in shared])
    rows: dict[tuple[str, ...], int] = {}
    if not extra:  # b only filters a's rows
        index = {key_b(row): w for row, w in b.rows.items()}
        for row, w in a.rows.items():
            w2 = index.get(key_a(row))
            if w2 is not None:
                if b.unit or w2 == one:
                    rows[row] = w
                else:
                    rows[row] = w2 if w == one else times(w, w2)
        return Factor(a.scope, rows, a.unit and b.unit)
    tail_b = key_of([b.scope.index(v) for v in extra])
    grouped: dict[tuple[str, ...], list[tuple[tuple[str, ...], int]]] = defaultdict(list)
    for row, w in b.rows.items():
        grouped[key_b(row)].append((tail_b(row), w))
    for row, w in a.rows.items():
        if b.unit:
            for tail, _ in grouped.get(key_a(row), ()):
                rows[row + tail] = w
        elif w == one:
            for tail, w2 in grouped.get(key_a(row), ()):
                rows[row + tail] = w2
        else:
            for tail, w2 in grouped.get(key_a(row), ()):
                rows[row + tail] = w if w2 == one else times(w, w2)
        if len(rows) > max_rows:
            raise over_budget(max_rows)
    return Factor((*a.scope, *extra), rows, a.unit and b.unit)
