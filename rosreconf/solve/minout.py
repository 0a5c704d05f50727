"""Take a role out of cost tables: keep, per row of its neighbours, its cheapest candidate.

Min-plus elimination (``rosreconf.solve.optimum``) ends each step here: the role's
candidates' costs are added while it is minimised out (``minimise_out``), or its last two
tables are joined and it is minimised out in one pass (``join_minimise_out``); either way the
cheapest candidate per neighbour row is remembered (``Choices``) for the traceback, and the
table's least value is taken out into the offsets so that rows stay small integers.
"""

from __future__ import annotations

from array import array
from collections.abc import Callable, Mapping, Sequence
from itertools import pairwise, product

from rosreconf.solve.tables import Factor, Row, key_of, one_pass, over_budget

__all__ = ["Choices", "Trace", "join_minimise_out", "minimise_out"]


class Choices:
    """Remember, per row of an eliminated role's neighbours, its cheapest candidate; compactly.

    The traceback needs one candidate per row of every table minimising a role out: a
    million rows at 10,000 roles, which as dictionaries of name tuples took 100 MiB for
    the whole solve. When the neighbours' candidates make a dense enough grid, the choice
    is one byte (or two) per grid cell, at the cell's mixed-radix index; else the dictionary
    is kept as it is.

    Attributes:
        var: the eliminated role.
        scope: its neighbours when it was eliminated (the rows' roles, in order).
    """

    def __init__(
        self,
        var: int,
        scope: tuple[int, ...],
        arg: dict[tuple[str, ...], str],
        alive: Sequence[Sequence[str]],
    ) -> None:
        self.var = var
        self.scope = scope
        self._names = alive[var]
        self._grid: array[int] | None = None
        self._arg: dict[tuple[str, ...], str] | None = arg
        cells = 1
        for v in scope:
            cells *= len(alive[v])
        if cells > 4 * len(arg) + 64:  # sparse: a grid would be larger than the dictionary
            return
        code: dict[str | None, int] = {c: j + 1 for j, c in enumerate(self._names)}
        code[None] = 0  # no row: never read back
        kind = "B" if len(self._names) < 255 else "I"
        self._grid = array(
            kind, map(code.__getitem__, map(arg.get, product(*(alive[v] for v in scope))))
        )
        self._arg = None

    def pick(self, chosen: Mapping[int, str], where: Sequence[Mapping[str, int]]) -> str:
        """Return the remembered candidate for the neighbours' ``chosen`` candidates.

        ``where[v]`` maps role v's surviving candidates to their positions.
        """
        if self._arg is not None:
            return self._arg[tuple(chosen[v] for v in self.scope)]
        assert self._grid is not None
        index = 0
        for v in self.scope:
            index = index * len(where[v]) + where[v][chosen[v]]
        return self._names[self._grid[index] - 1]


Trace = list[Choices]
"""Per eliminated role, in elimination order: its cheapest candidate per neighbour row."""


def minimise_out(
    f: Factor,
    var: int,
    cost: Mapping[str, int],
    rank: Mapping[str, int],
    trace: Trace,
    offsets: list[int],
    alive: Sequence[Sequence[str]],
) -> Factor:
    """Minimise ``var`` out of ``f`` plus its unary ``cost``, keeping the argmin per row.

    The table's least value is taken out of every row and kept in ``offsets`` (the total is
    their sum plus what is left at the end): rows then hold only how much worse than the
    best they are. The first configuration's costs weigh each role ``base ** (R - 1 - r)``,
    integers of thousands of digits at 10,000 roles; their differences are mostly 0, so the
    tables stay small integers instead of holding thousands of digits per row.
    """
    pos = f.scope.index(var)
    rest = key_of([i for i in range(len(f.scope)) if i != pos])
    level, gap = _cost_levels(cost)
    if not gap or max(f.rows.values(), default=0) < gap:
        best, arg = _min_out_dominated(f, pos, rest, cost, level, rank)
    else:
        best, arg = _min_out_added(f, pos, rest, cost, rank)
    return _reduced(var, f.scope[:pos] + f.scope[pos + 1 :], best, arg, trace, offsets, alive)


def _reduced(
    var: int,
    scope: tuple[int, ...],
    best: dict[Row, int],
    arg: dict[Row, str],
    trace: Trace,
    offsets: list[int],
    alive: Sequence[Sequence[str]],
) -> Factor:
    """Record the argmin for the traceback and take the least value out into ``offsets``."""
    trace.append(Choices(var, scope, arg, alive))
    low = min(best.values(), default=0)
    if low:
        offsets.append(low)
        best = {k: w - low for k, w in best.items()}
    return Factor(scope, best)


def join_minimise_out(
    a: Factor,
    b: Factor,
    var: int,
    cost: Mapping[str, int],
    rank: Mapping[str, int],
    trace: Trace,
    offsets: list[int],
    alive: Sequence[Sequence[str]],
    max_rows: int,
) -> Factor:
    """Join two cost tables and minimise ``var`` out, in one pass: ``minimise_out(_join(a, b))``.

    The joined table is the widest of each elimination step and was built only to be
    walked once; here each row of ``a`` (which holds ``var``: every table of the step does)
    looks up its candidate's cost, rank and sub-row once, and only the rows of ``b`` it
    matches are walked. The dominated path (see ``_min_out_dominated``) is taken when the
    largest joined value, at most ``a``'s largest plus ``b``'s, stays below the costs' gap;
    both paths give the same minimum and argmin, so the choice changes only the time.
    tests/test_elimination_tables.py holds this to joining then minimising.
    """
    a, b, pos, extra, key_a, head, grouped = one_pass(a, b, var)
    level, gap = _cost_levels(cost)
    top = max(a.rows.values(), default=0) + max(b.rows.values(), default=0)
    dominated = not gap or top < gap
    best_level: dict[Row, int] = {}
    best: dict[Row, int] = {}
    arg: dict[Row, str] = {}
    joined = 0
    for row, w in a.rows.items():
        matches = grouped.get(key_a(row), ())
        joined += len(matches)
        if joined > max_rows and extra:  # the budget of the join it replaces
            raise over_budget(max_rows)
        c = row[pos]
        r = rank[c]
        start = head(row)
        if dominated:  # compare cost levels first; the cost is added once per kept row
            lv = level[c]
            for tail, w2 in matches:
                v = w2 if not w else w if not w2 else w + w2
                k = start + tail
                old = best_level.get(k)
                if old is not None:
                    if lv > old:
                        continue
                    if lv == old:
                        w0 = best[k]
                        if v > w0 or (v == w0 and r > rank[arg[k]]):
                            continue
                best_level[k] = lv
                best[k] = v
                arg[k] = c
            continue
        extra_cost = cost[c]
        for tail, w2 in matches:
            v = w2 if not w else w if not w2 else w + w2
            if extra_cost:
                v = extra_cost if not v else v + extra_cost
            k = start + tail
            old = best.get(k)
            if old is None or v < old or (v == old and r < rank[arg[k]]):
                best[k] = v
                arg[k] = c
    if dominated:
        for k, v in best.items():
            add = cost[arg[k]]
            if add:
                best[k] = add if not v else v + add
    scope = (*a.scope[:pos], *a.scope[pos + 1 :], *extra)
    return _reduced(var, scope, best, arg, trace, offsets, alive)


def _min_out_added(
    f: Factor,
    pos: int,
    rest: Callable[[Row], Row],
    cost: Mapping[str, int],
    rank: Mapping[str, int],
) -> tuple[dict[Row, int], dict[Row, str]]:
    """Minimise by adding each row's candidate cost to its value, then comparing."""
    best: dict[Row, int] = {}
    arg: dict[Row, str] = {}
    for row, w in f.rows.items():
        c = row[pos]
        extra = cost[c]
        if extra:  # most candidates' costs are 0 or the row's is: skip copying a big integer
            w = extra if not w else w + extra
        k = rest(row)
        old = best.get(k)
        if old is None or w < old or (w == old and rank[c] < rank[arg[k]]):
            best[k] = w
            arg[k] = c
    return best, arg


def _cost_levels(cost: Mapping[str, int]) -> tuple[dict[str, int], int]:
    """Return each candidate's cost level (0 for the least cost) and the least gap between costs.

    The gap is 0 when all costs are equal. While every row value stays below the gap,
    ``cost + value`` orders rows exactly as (level, value) does: the dominated path's test.
    """
    levels = sorted(set(cost.values()))
    at = {u: i for i, u in enumerate(levels)}
    gap = min((b - a for a, b in pairwise(levels)), default=0)
    return {c: at[u] for c, u in cost.items()}, gap


def _min_out_dominated(
    f: Factor,
    pos: int,
    rest: Callable[[Row], Row],
    cost: Mapping[str, int],
    level: Mapping[str, int],
    rank: Mapping[str, int],
) -> tuple[dict[Row, int], dict[Row, str]]:
    """Minimise when the candidate's cost decides: every row value is below the costs' gap.

    Rows hold values >= 0 (offsets are taken out), so when they all stay below the least
    difference between two candidates' costs, ``cost + value`` orders rows exactly as
    (cost, value) does; comparing a candidate's cost level (a small integer) first and adding
    only once per remaining row is what makes the first configuration's thousand-digit
    costs cheap: they are added once per kept row, not once per row joined.
    """
    best_level: dict[Row, int] = {}
    value: dict[Row, int] = {}
    arg: dict[Row, str] = {}
    for row, w in f.rows.items():
        c = row[pos]
        k = rest(row)
        old = best_level.get(k)
        if old is not None:
            lv = level[c]
            if lv > old:
                continue
            if lv == old:
                w0 = value[k]
                if w > w0 or (w == w0 and rank[c] > rank[arg[k]]):
                    continue
        best_level[k] = level[c]
        value[k] = w
        arg[k] = c
    best = {}
    for k, w in value.items():
        extra = cost[arg[k]]
        best[k] = (extra if not w else w + extra) if extra else w
    return best, arg
