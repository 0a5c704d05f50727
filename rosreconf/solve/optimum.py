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

import logging
import operator
from collections.abc import Callable, Mapping, Sequence

from rosreconf.model import Configuration
from rosreconf.solve.dense import MinOut, TooWide, cap_for, run
from rosreconf.solve.emptyroles import as_chosen
from rosreconf.solve.factors import (
    MAX_FACTOR_ROWS,
    Factor,
    TooHard,
    constraint_factors,
    eliminate,
    elimination_order,
    paused_gc,
)
from rosreconf.solve.gridtables import constraint_grids
from rosreconf.solve.instance import Instance, interchangeable, prune
from rosreconf.solve.minout import Trace, join_minimise_out, minimise_out

LOG = logging.getLogger(__name__)

__all__ = ["MAX_FACTOR_ROWS", "TooHard", "first", "minimise"]


def minimise(
    inst: Instance,
    costs: Sequence[Mapping[str, tuple[int, ...]]],
    max_rows: int = MAX_FACTOR_ROWS,
    *,
    earliest: bool = False,
) -> tuple[Configuration, tuple[int, ...]] | None:
    """Return a valid configuration of least total cost and that cost, or None if none exists.

    ``costs[r][c]`` is the cost tuple (most important level first) of candidate ``c`` in
    role ``r``; a configuration costs the element-wise sum over its roles, compared
    lexicographically. Among equal costs, earlier candidates in library order win at every
    elimination step, so the answer is deterministic.

    With ``earliest``, a tie is settled by the last rule of
    ``rosreconf.solve.objective.PREFERENCE``: the first of the tied configurations in
    enumeration order, by a last cost level that is each candidate's position weighted as
    ``first`` weighs it. Every configuration then has a cost of its own, so the optimum is
    one configuration whichever order the roles are eliminated in (the costs are then too
    wide for the dense grids: the sparse tables answer).

    Raises:
        TooHard: an intermediate table would exceed ``max_rows`` rows.
    """
    with paused_gc():
        alive, _, _ = prune(inst)
        if any(not a for a in alive):
            return None
        packed, unpacked = _pack(alive, costs)
        unpack: Callable[[int], tuple[int, ...]] = unpacked
        if earliest:
            packed, unpack = _earliest(inst, alive, packed, unpacked)
        costs_of = packed.__getitem__
        # a class's cheapest member; the earliest (least rank: alive keeps library order) on ties
        found = _minimise(
            inst,
            alive,
            costs_of,
            max_rows,
            lambda r, ms: min(ms, key=costs_of(r).__getitem__),
            small=True,
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
    *,
    small: bool = False,
) -> tuple[Configuration, int] | None:
    """Minimise the packed unary costs over the constraint tables; the answer and its total.

    ``packed(r)`` gives role r's candidates' costs; it is asked once, when r is eliminated,
    and added to the rows while r is minimised out rather than joined as a table of its
    own: that join copied the largest table of every step once more.

    Only one candidate of each class of interchangeable ones is kept (``interchangeable``):
    ``prefer(r, members)``, the one of least cost, the earliest on ties. Its rows are the
    others' rows, so every step picks what it would have picked among all of them.

    With ``small`` costs (the optimum's, not the first configuration's thousand-digit ones)
    the dense grids (``rosreconf.solve.dense``) eliminate first; the sparse tables answer
    when a grid would be too wide. Both pick the same configuration: the least cost, then
    the earliest candidate, at every step of the same order.
    """
    rank = {c.name: i for i, c in enumerate(inst.library.components)}
    alive = [
        sorted((prefer(r, members) for members in role), key=rank.__getitem__)
        for r, role in enumerate(interchangeable(inst, alive))
    ]
    if small:
        try:
            return _dense_minimise(inst, alive, packed, cap_for(max_rows))
        except TooWide as exc:
            LOG.info("sparse elimination: %s", exc)
    factors = constraint_factors(inst, alive, 0, max_rows)
    order = elimination_order([f.scope for f in factors], len(inst.roles))
    trace: Trace = []
    offsets: list[int] = []

    def min_out(f: Factor, var: int) -> Factor:
        return minimise_out(f, var, packed(var), rank, trace, offsets, alive)

    def join_out(a: Factor, b: Factor, var: int, budget: int) -> Factor:
        return join_minimise_out(a, b, var, packed(var), rank, trace, offsets, alive, budget)

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
    mapping = {inst.roles[r].name: as_chosen(chosen[r]) for r in range(len(inst.roles))}
    config = Configuration.of(inst.schema.name, mapping, inst.roles)
    return config, sum(scalars) + sum(offsets)


def _dense_minimise(
    inst: Instance,
    alive: list[list[str]],
    packed: Callable[[int], Mapping[str, int]],
    cap: int,
) -> tuple[Configuration, int] | None:
    """Minimise over dense grids (``_minimise``'s answer; ``alive`` in library order).

    The elimination order is the sparse path's: it is decided by which roles share a table,
    and the grids are the same tables.

    Raises:
        TooWide: a grid would pass ``cap`` cells, or the costs are too large for small integers.
    """
    costs = [[packed(r)[c] for c in names] for r, names in enumerate(alive)]
    step = MinOut(costs)
    sizes = [len(a) for a in alive]
    tables = constraint_grids(inst, alive, 0, step.inf, operator.add, cap)
    order = elimination_order([g.scope for g in tables], len(inst.roles))
    done = run(tables, order, sizes, step, cap)
    if done is None:
        return None
    _, free = done
    chosen: dict[int, int] = {}
    extra = 0
    for var in free:  # in no table: its cheapest candidate, the earlier one on ties
        pick = min(range(sizes[var]), key=lambda j: (costs[var][j], j))
        chosen[var] = pick
        extra += costs[var][pick]
    step.traceback(chosen, sizes)
    mapping = {inst.roles[r].name: as_chosen(alive[r][chosen[r]]) for r in range(len(inst.roles))}
    config = Configuration.of(inst.schema.name, mapping, inst.roles)
    return config, step.total() + extra


def _pack(
    alive: list[list[str]], costs: Sequence[Mapping[str, tuple[int, ...]]]
) -> tuple[list[dict[str, int]], _Unpack]:
    """Pack each candidate's cost tuple into one non-negative integer, order preserved."""
    levels = max((len(t) for m in costs for t in m.values()), default=0)
    pad = (0,) * levels
    # per role, its candidates' cost tuples padded to every level (a missing level costs 0)
    table = [[(costs[r].get(c, ()) + pad)[:levels] for c in names] for r, names in enumerate(alive)]
    lows = [list(map(min, zip(*rows, strict=True))) if rows else list(pad) for rows in table]
    highs = [list(map(max, zip(*rows, strict=True))) if rows else list(pad) for rows in table]
    spans = [sum(h[i] - lo[i] for h, lo in zip(highs, lows, strict=True)) for i in range(levels)]
    bases = [1] * levels
    for i in range(levels - 2, -1, -1):
        bases[i] = bases[i + 1] * (spans[i + 1] + 1)
    packed = [
        {
            c: sum((x - low) * base for x, low, base in zip(t, lo, bases, strict=True))
            for c, t in zip(names, rows, strict=True)
        }
        for names, rows, lo in zip(alive, table, lows, strict=True)
    ]
    offsets = [sum(low[i] for low in lows) for i in range(levels)]
    return packed, _Unpack(bases, offsets)


def _earliest(
    inst: Instance, alive: list[list[str]], packed: list[dict[str, int]], unpack: _Unpack
) -> tuple[list[dict[str, int]], Callable[[int], tuple[int, ...]]]:
    """Add a last level to packed costs: each candidate's position, the earlier role heavier.

    Role ``r``'s candidate at position ``j`` of its domain adds ``j * B ** (R - 1 - r)``
    (``B`` larger than any domain): the sum over the roles is below ``B ** R`` and tells every
    configuration apart, the first in enumeration order least (``first``'s weights).
    """
    base = max(len(d) for d in inst.domains) + 1 if inst.domains else 1
    last = len(alive) - 1
    top = base ** len(alive)
    out = []
    for r, costs in enumerate(packed):
        weight = base ** (last - r)
        position = {c.name: j for j, c in enumerate(inst.domains[r])}
        out.append({c: cost * top + position[c] * weight for c, cost in costs.items()})
    return out, lambda total: unpack(total // top)


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
