"""Count configurations exactly without listing them.

The number of configurations can be astronomically large (Theorem 9: with orthogonality
it is a product over the roles), so it is computed, not enumerated: every rule of validity
becomes a 0/1 table over the few roles it mentions (``rosreconf.solve.factors``), and variable
elimination sums the roles out one at a time, cheapest first. Independent parts of the
system graph never share a table, so their counts multiply, which is Theorem 9's product;
chains and trees cost O(roles x candidates^2). Python integers keep the result exact at
any size. ``rosreconf.solve.optimum`` minimises over the very same tables in the same order.
"""

from __future__ import annotations

import math
import operator
from collections import defaultdict

from rosreconf.solve.dense import SumOut, TooWide, cap_for, run
from rosreconf.solve.factors import (
    MAX_FACTOR_ROWS,
    Factor,
    TooHard,
    constraint_factors,
    eliminate,
    elimination_order,
    join_sum_out,
    key_of,
    paused_gc,
)
from rosreconf.solve.gridtables import constraint_grids
from rosreconf.solve.instance import Instance, interchangeable, prune

CountTooHard = TooHard
"""The name callers of ``count`` know for "too densely connected to count exactly"."""

__all__ = ["MAX_FACTOR_ROWS", "CountTooHard", "count"]


def count(inst: Instance, max_rows: int = MAX_FACTOR_ROWS) -> int:
    """Return the exact number of valid configurations of ``inst``.

    Raises:
        CountTooHard: an intermediate table would exceed ``max_rows`` rows.
    """
    with paused_gc():
        alive, _, _ = prune(inst)
        if any(not a for a in alive):
            return 0
        classes = interchangeable(inst, alive)
        kept = [[members[0] for members in role] for role in classes]
        sizes = [len(k) for k in kept]
        try:  # dense grids first (``rosreconf.solve.dense``); the sparse tables if too wide
            cap = cap_for(max_rows)
            tables = constraint_grids(inst, kept, 1, 0, operator.mul, cap)
            order = elimination_order([g.scope for g in tables], len(inst.roles))
            weights = [[len(members) for members in role] for role in classes]
            done = run(tables, order, sizes, SumOut(weights), cap)
        except TooWide:
            factors = constraint_factors(inst, kept, 1, max_rows)
            _weigh(factors, classes)
            order = elimination_order([f.scope for f in factors], len(inst.roles))
            done = eliminate(factors, order, operator.mul, _sum_out, max_rows, 1, join_sum_out)
    if done is None:
        return 0
    scalars, free = done
    return math.prod(scalars) * math.prod(len(alive[v]) for v in free)


def _weigh(factors: list[Factor], classes: list[list[list[str]]]) -> None:
    """Count each kept candidate as many times as its class has members.

    The tables hold one candidate per class of interchangeable ones (``interchangeable``):
    every configuration through a kept candidate stands for one per member. Each role's
    sizes go into the first table over it, once; a role in no table is free, and counted
    by all its candidates at the end.
    """
    weighed: set[int] = set()
    for f in factors:
        for pos, v in enumerate(f.scope):
            if v in weighed:
                continue
            weighed.add(v)
            size = {members[0]: len(members) for members in classes[v] if len(members) > 1}
            if size:
                f.rows = {row: w * size.get(row[pos], 1) for row, w in f.rows.items()}
                f.unit = False


def _sum_out(f: Factor, var: int) -> Factor:
    pos = f.scope.index(var)
    rest = key_of([i for i in range(len(f.scope)) if i != pos])
    rows: dict[tuple[str, ...], int] = defaultdict(int)
    for row, w in f.rows.items():
        rows[rest(row)] += w
    return Factor(f.scope[:pos] + f.scope[pos + 1 :], dict(rows))
