"""Find a provably optimal configuration by min-plus variable elimination.

The tables and the elimination order are counting's (``rosreconf.solve.factors``); only the
algebra changes. Each allowed row costs 0, each role adds a unary table with its
candidates' costs, joining adds costs, and eliminating a role keeps, per row of its
neighbours, the cheapest candidate and remembers which one it was. After the last role the
single value left is the optimum; walking the remembered choices back (traceback) gives a
configuration that reaches it. On the small treewidth of real and generated system graphs
this is exact and takes about as long as counting.

Costs are lexicographic tuples of integers (fewest changes first, then the scaled metric
sum, ``rosreconf.solve.solver``). They are packed into one Python integer per row so that joins
add plain integers: level ``l`` is multiplied by one more than the largest total the lower
levels can reach, which keeps the order lexicographic and the arithmetic exact.
"""

from __future__ import annotations

import operator
from array import array
from collections import defaultdict
from collections.abc import Callable, Mapping, Sequence
from itertools import pairwise, product

from rosreconf.model import Configuration
from rosreconf.solve.factors import (
    MAX_FACTOR_ROWS,
    Factor,
    TooHard,
    constraint_factors,
    eliminate,
    elimination_order,
    key_of,
    paused_gc,
)
from rosreconf.solve.instance import Instance, interchangeable, prune

__all__ = ["MAX_FACTOR_ROWS", "TooHard", "first", "minimise"]


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


def minimise(
    inst: Instance,
    costs: Sequence[Mapping[str, tuple[int, ...]]],
    max_rows: int = MAX_FACTOR_ROWS,
) -> tuple[Configuration, tuple[int, ...]] | None:
    """Return a valid configuration of least total cost and that cost, or None if none exists.

    ``costs[r][c]`` is the cost tuple (most important level first) of candidate ``c`` in
    role ``r``; a configuration costs the element-wise sum over its roles, compared
    lexicographically. Among equal costs, earlier candidates in library order win at every
    elimination step, so the answer is deterministic.

    Raises:
        TooHard: an intermediate table would exceed ``max_rows`` rows.
    """
    with paused_gc():
        alive, _, _ = prune(inst)
        if any(not a for a in alive):
            return None
        packed, unpack = _pack(alive, costs)
        costs_of = packed.__getitem__
        # a class's cheapest member; the earliest (least rank: alive keeps library order) on ties
        found = _minimise(
            inst, alive, costs_of, max_rows, lambda r, ms: min(ms, key=costs_of(r).__getitem__)
        )
    return None if found is None else (found[0], unpack(found[1]))


def first(inst: Instance, max_rows: int = MAX_FACTOR_ROWS) -> Configuration | None:
    """Return the first valid configuration in enumeration order, or None if none exists.

    Enumeration order is lexicographic: roles in schema order, candidates in library order
    (``ClingoEngine.configurations``). That first configuration is the one of least cost when
    a candidate's cost is its position in its role's domain scaled by ``B ** (R - 1 - r)``
    (``B`` larger than any domain, ``R`` roles): an earlier role then outweighs every later one
    together. Min-plus elimination over counting's tables finds it without grounding
    anything in clingo, which is most of clingo's time on large libraries.

    Raises:
        TooHard: an intermediate table would exceed ``max_rows`` rows.
    """
    with paused_gc():
        alive, _, _ = prune(inst)
        if any(not a for a in alive):
            return None
        base = max(len(d) for d in inst.domains) + 1 if inst.domains else 1
        last = len(alive) - 1

        def packed(r: int) -> dict[str, int]:
            """Weigh role r's candidates: the last role 1, each earlier one base times more."""
            weight = base ** (last - r)
            position = {c.name: j for j, c in enumerate(inst.domains[r])}
            return {c: position[c] * weight for c in alive[r]}

        found = _minimise(inst, alive, packed, max_rows, lambda r, ms: ms[0])  # the earliest
    return None if found is None else found[0]


def _minimise(
    inst: Instance,
    alive: list[list[str]],
    packed: Callable[[int], Mapping[str, int]],
    max_rows: int,
    prefer: Callable[[int, list[str]], str],
) -> tuple[Configuration, int] | None:
    """Minimise the packed unary costs over the constraint tables; the answer and its total.

    ``packed(r)`` gives role r's candidates' costs; it is asked once, when r is eliminated,
    and added to the rows while r is minimised out rather than joined as a table of its
    own: that join copied the largest table of every step once more.

    Only one candidate of each class of interchangeable ones is kept (``interchangeable``):
    ``prefer(r, members)``, the one of least cost, the earliest on ties. Its rows are the
    others' rows, so every step picks what it would have picked among all of them.
    """
    alive = [
        [prefer(r, members) for members in role]
        for r, role in enumerate(interchangeable(inst, alive))
    ]
    factors = constraint_factors(inst, alive, 0, max_rows)
    order = elimination_order([f.scope for f in factors], len(inst.roles))
    rank = {c.name: i for i, c in enumerate(inst.library.components)}
    trace: Trace = []
    offsets: list[int] = []

    def min_out(f: Factor, var: int) -> Factor:
        return _min_out(f, var, packed(var), rank, trace, offsets, alive)

    def join_out(a: Factor, b: Factor, var: int, budget: int) -> Factor:
        return _join_min_out(a, b, var, packed(var), rank, trace, offsets, alive, budget)

    done = eliminate(factors, order, operator.add, min_out, max_rows, 0, join_out)
    if done is None:
        return None
    scalars, free = done
    chosen: dict[int, str] = {}
    for var in free:  # in no table: its cheapest candidate, the earlier one on ties
        costs = packed(var)
        pick = min(alive[var], key=lambda c: (costs[c], rank[c]))
        chosen[var] = pick
        offsets.append(costs[pick])
    where = [{c: j for j, c in enumerate(names)} for names in alive]
    for choices in reversed(trace):
        chosen[choices.var] = choices.pick(chosen, where)
    mapping = {inst.roles[r].name: chosen[r] for r in range(len(inst.roles))}
    config = Configuration.of(inst.schema.name, mapping, inst.roles)
    return config, sum(scalars) + sum(offsets)


def _min_out(
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
    levels = sorted(set(cost.values()))
    gap = min((b - a for a, b in pairwise(levels)), default=0)
    if not gap or max(f.rows.values(), default=0) < gap:
        best, arg = _min_out_dominated(f, pos, rest, cost, levels, rank)
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


def _join_min_out(
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
    """Join two cost tables and minimise ``var`` out, in one pass: ``_min_out(_join(a, b))``.

    The joined table is the widest of each elimination step and was built only to be
    walked once; here each row of ``a`` (which holds ``var``: every table of the step does)
    looks up its candidate's cost, rank and sub-row once, and only the rows of ``b`` it
    matches are walked. The dominated path (see ``_min_out_dominated``) is taken when the
    largest joined value, at most ``a``'s largest plus ``b``'s, stays below the costs' gap;
    both paths give the same minimum and argmin, so the choice changes only the time.
    tests/test_elimination_tables.py holds this to joining then minimising.
    """
    if a.unit and not b.unit:  # as ``_join``: the valued table on the left
        a, b = b, a
    extra = [v for v in b.scope if v not in a.scope]
    shared = [v for v in a.scope if v in b.scope]
    key_a = key_of([a.scope.index(v) for v in shared])
    key_b = key_of([b.scope.index(v) for v in shared])
    pos = a.scope.index(var)
    head = key_of([i for i in range(len(a.scope)) if i != pos])
    tail_b = key_of([b.scope.index(v) for v in extra])
    grouped: dict[Row, list[tuple[Row, int]]] = defaultdict(list)
    for row, w in b.rows.items():
        grouped[key_b(row)].append((tail_b(row), w))
    levels = sorted(set(cost.values()))
    gap = min((y - x for x, y in pairwise(levels)), default=0)
    top = max(a.rows.values(), default=0) + max(b.rows.values(), default=0)
    level = {c: levels.index(u) for c, u in cost.items()}
    dominated = not gap or top < gap
    best_level: dict[Row, int] = {}
    best: dict[Row, int] = {}
    arg: dict[Row, str] = {}
    joined = 0
    for row, w in a.rows.items():
        matches = grouped.get(key_a(row), ())
        joined += len(matches)
        if joined > max_rows and extra:  # the budget of the join it replaces
            raise TooHard(
                f"exact elimination needs over {max_rows} rows; the system graph is too "
                "densely connected"
            )
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


Row = tuple[str, ...]


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


def _min_out_dominated(
    f: Factor,
    pos: int,
    rest: Callable[[Row], Row],
    cost: Mapping[str, int],
    levels: list[int],
    rank: Mapping[str, int],
) -> tuple[dict[Row, int], dict[Row, str]]:
    """Minimise when the candidate's cost decides: every row value is below the costs' gap.

    Rows hold values >= 0 (offsets are taken out), so when they all stay below the least
    difference between two candidates' costs, ``cost + value`` orders rows exactly as
    (cost, value) does; comparing a candidate's cost level (a small integer) first and adding
    only once per remaining row is what makes the first configuration's thousand-digit
    costs cheap: they are added once per kept row, not once per row joined.
    """
    level = {c: levels.index(u) for c, u in cost.items()}
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


def _pack(
    alive: list[list[str]], costs: Sequence[Mapping[str, tuple[int, ...]]]
) -> tuple[list[dict[str, int]], _Unpack]:
    """Pack each candidate's cost tuple into one non-negative integer, order preserved."""
    levels = max((len(t) for m in costs for t in m.values()), default=0)

    def level(r: int, c: str, i: int) -> int:
        t = costs[r].get(c, ())
        return t[i] if i < len(t) else 0

    lows = [
        [min(level(r, c, i) for c in names) for i in range(levels)] for r, names in enumerate(alive)
    ]
    spans = [
        sum(max(level(r, c, i) for c in names) - lows[r][i] for r, names in enumerate(alive))
        for i in range(levels)
    ]
    bases = [1] * levels
    for i in range(levels - 2, -1, -1):
        bases[i] = bases[i + 1] * (spans[i + 1] + 1)
    packed = [
        {c: sum((level(r, c, i) - lows[r][i]) * bases[i] for i in range(levels)) for c in names}
        for r, names in enumerate(alive)
    ]
    offsets = [sum(low[i] for low in lows) for i in range(levels)]
    return packed, _Unpack(bases, offsets)


class _Unpack:
    """Turn a packed total back into its cost tuple."""

    def __init__(self, bases: list[int], offsets: list[int]) -> None:
        self.bases = bases
        self.offsets = offsets

    def __call__(self, total: int) -> tuple[int, ...]:
        out = []
        for base, offset in zip(self.bases, self.offsets, strict=True):
            q, total = divmod(total, base)
            out.append(q + offset)
        return tuple(out)
