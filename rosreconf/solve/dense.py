"""Eliminate roles over dense tables: one integer per cell of a few roles' candidate grid.

On generated libraries (1000 roles x 10 candidates, about 6 kept per role) a table over two
or three roles allows 70-100% of its grid's cells, so storing every cell costs little and
lets each elimination step run as a few C-level ``map`` calls over flat lists (gather, add or
multiply, ``min`` or sum across the role's candidates) instead of a Python loop per row over
a dictionary of name tuples. Each step is the same function as the sparse one of
``rosreconf.solve.factors`` (tests/test_dense.py holds them alike). A cell is numbered by its
candidates' positions in their roles' lists, mixed-radix in the scope's order (last fastest).

Min-plus cells hold ``cost * W`` (``W`` larger than any role's candidates); adding a
candidate's ``cost * W + position`` before ``min`` orders by cost, then by position: the
argmin and its tie-break ride in the same integer. Cells a rule of validity rules out hold
``MinOut.inf``, far above any real total, and stay above ``MinOut.feasible`` whatever is
added or taken out. When costs are too large for that (the first configuration's costs are
integers of thousands of digits) or a grid would be too large, ``TooWide`` sends the caller
back to the sparse tables. The grids themselves are made in ``rosreconf.solve.gridtables``.
"""

from __future__ import annotations

import operator
from array import array
from collections.abc import Callable, Sequence
from itertools import chain, repeat
from typing import NamedTuple, Protocol

DENSE_CELLS = 1 << 18
"""Largest grid (cells of the joined table of one step) eliminated densely."""

SMALL_COST_BITS = 60
"""Largest total cost, in bits, that the dense min-plus cells carry (small integers stay fast)."""


class TooWide(Exception):
    """A grid would pass its cap (``cap_for``) or costs are too large: use the sparse tables."""


class Grid(NamedTuple):
    """A dense table: one value per cell of its roles' candidate grid (row-major, last fastest).

    Attributes:
        scope: the role indices, in axis order.
        data: the cells' values (a count, or an encoded cost).
    """

    scope: tuple[int, ...]
    data: list[int]


def cap_for(max_rows: int) -> int:
    """Return the largest grid to make: ``DENSE_CELLS``, or the row budget if smaller.

    A grid holds at least the rows of the sparse table it stands for, so within the row
    budget everywhere, the sparse tables would have been within it too: the dense path
    never answers where the sparse one would refuse (``TooHard``).
    """
    return min(DENSE_CELLS, max_rows)


def cells_of(scope: Sequence[int], sizes: Sequence[int], cap: int) -> int:
    """Return how many cells a grid over ``scope`` has.

    Raises:
        TooWide: more than ``cap``.
    """
    cells = 1
    for v in scope:
        cells *= sizes[v]
    if cells > cap:
        raise TooWide(f"a grid of {cells} cells")
    return cells


def gather(
    g: Grid,
    axes: Sequence[int],
    sizes: Sequence[int],
    cache: dict[tuple[tuple[int, int], ...], list[int]] | None = None,
) -> list[int]:
    """Return ``g``'s values laid out over ``axes`` (a superset of its scope), broadcast.

    The cell index list depends only on each axis's size and stride in ``g``; ``cache``
    keeps it across the steps of one elimination (a few hundred shapes for a thousand roles).
    """
    if g.scope == tuple(axes):
        return g.data
    stride: dict[int, int] = {}
    step = 1
    for v in reversed(g.scope):
        stride[v] = step
        step *= sizes[v]
    shape = tuple((sizes[a], stride.get(a, 0)) for a in axes)
    idx = None if cache is None else cache.get(shape)
    if idx is None:
        idx = [0]
        for size, s in shape:  # C-level: each cell so far becomes ``size`` cells
            if s:  # x, x + s, ..., x + (size - 1) * s
                ends = map(operator.add, idx, repeat(size * s))
                idx = list(chain.from_iterable(map(range, idx, ends, repeat(s))))
            else:  # broadcast: x repeated
                idx = list(chain.from_iterable(map(repeat, idx, repeat(size))))
        if cache is not None:
            cache[shape] = idx
    return list(map(g.data.__getitem__, idx))


class Step(Protocol):
    """How a role leaves its grids (counting's ``SumOut``, min-plus's ``MinOut``)."""

    def dense(
        self, var: int, rest: tuple[int, ...], parts: list[list[int]], leading: bool
    ) -> list[int] | None:
        """Take ``var`` out of ``parts``, all laid over (var, *rest) or (*rest, var)."""

    def fold(self, parts: list[list[int]]) -> list[int]:
        """Combine grids laid over the same axes, cell by cell."""

    def outer(
        self, var: int, rest: tuple[int, ...], joined: list[int], last: list[int], size: int
    ) -> list[int] | None:
        """Take ``var`` out of ``joined`` (over var, *rest[1:]) and ``last`` (over var, rest[0]).

        ``last`` is the one grid over ``rest[0]`` (of ``size`` candidates): per candidate
        of that role, each of var's slices of ``joined`` gets one number added (or multiplied),
        so the widest grid of the step is never laid out cell by cell.
        """


def run(
    tables: list[Grid], order: Sequence[int], sizes: Sequence[int], step: Step, cap: int
) -> tuple[list[int], list[int]] | None:
    """Eliminate the roles in ``order``; return the scalars left and the free roles.

    The same walk as ``factors.eliminate``: the grids over a role are joined over the role
    and its neighbours (the role first or last, so its candidates are slices) and ``step``
    takes it out. None when a grid or a step leaves nothing allowed (``step``
    says so by returning None).

    Raises:
        TooWide: a step's joined grid would pass ``cap`` cells (``cap_for``).
    """
    by_var: dict[int, set[int]] = {}
    pool: dict[int, Grid] = dict(enumerate(tables))
    for k, g in pool.items():
        for v in g.scope:
            by_var.setdefault(v, set()).add(k)
    next_id = len(pool)
    cache: dict[tuple[tuple[int, int], ...], list[int]] = {}
    scalars: list[int] = []
    free: list[int] = []
    for var in order:
        ids = by_var.pop(var, None)
        if not ids:
            free.append(var)
            continue
        mine = sorted((pool.pop(k) for k in ids), key=lambda g: -len(g.scope))
        # the widest grid's own order when the role is its first or last axis (its cells
        # need no gathering, and the role's candidates are slices); else the role first
        first = mine[0].scope
        order_rest = [v for v in first if v != var]
        for g in mine:
            for v in g.scope:
                if v != var and v not in order_rest:
                    order_rest.append(v)
        for v in order_rest:
            by_var[v].difference_update(ids)
        lone = _lone(var, mine)
        if lone is not None:  # (var, z) with z in no other grid: the outer step
            last = mine.pop(lone)
            z = last.scope[0] if last.scope[1] == var else last.scope[1]
            order_rest.remove(z)
            axes = (var, *order_rest)
            rest: tuple[int, ...] = (z, *order_rest)
            cells_of((*axes, z), sizes, cap)
            parts = [gather(g, axes, sizes, cache) for g in mine]
            joined = step.fold(parts)
            data = step.outer(var, rest, joined, gather(last, (var, z), sizes), sizes[z])
        else:
            rest = tuple(order_rest)
            leading = first[0] == var or first[-1] != var
            axes = (var, *rest) if leading else (*rest, var)
            cells_of(axes, sizes, cap)
            parts = [gather(g, axes, sizes, cache) for g in mine]
            data = step.dense(var, rest, parts, leading)
        if data is None:
            return None
        if not rest:
            scalars.append(data[0])
            continue
        pool[next_id] = Grid(rest, data)
        for v in rest:
            by_var[v].add(next_id)
        next_id += 1
    return scalars, free


def _lone(var: int, mine: list[Grid]) -> int | None:
    """Return the index of a grid over (var, z) whose z is in no other grid, if any."""
    if len(mine) < 2:
        return None
    for n in range(len(mine) - 1, -1, -1):
        scope = mine[n].scope
        if len(scope) == 2:
            z = scope[0] if scope[1] == var else scope[1]
            if all(z not in g.scope for k, g in enumerate(mine) if k != n):
                return n
    return None


def _slices(data: list[int], k: int, leading: bool) -> list[list[int]]:
    """Split ``data`` by the role's candidates: contiguous when it leads, else strided."""
    if not leading:
        return [data[i::k] for i in range(k)]
    m = len(data) // k
    return [data[i * m : (i + 1) * m] for i in range(k)]


def _folded(parts: list[list[int]], op: Callable[[int, int], int]) -> list[int]:
    if len(parts) == 1:
        return parts[0]
    it = map(op, parts[0], parts[1])
    for p in parts[2:]:
        it = map(op, it, p)
    return list(it)


class SumOut:
    """Counting's step: multiply the grids, weigh each candidate, sum the role out."""

    def __init__(self, weights: Sequence[Sequence[int]]) -> None:
        self.weights = weights

    def fold(self, parts: list[list[int]]) -> list[int]:
        """Multiply grids laid over the same axes, cell by cell."""
        return _folded(parts, operator.mul)

    def outer(
        self, var: int, rest: tuple[int, ...], joined: list[int], last: list[int], size: int
    ) -> list[int] | None:
        """Return the role summed out of ``joined`` times ``last`` (see ``Step.outer``)."""
        weights = self.weights[var]
        slices = _slices(joined, len(weights), True)
        out: list[int] = []
        for z in range(size):
            cols = [
                map(operator.mul, piece, repeat(w * last[i * size + z]))
                for i, (piece, w) in enumerate(zip(slices, weights, strict=True))
                if last[i * size + z]
            ]
            if not cols:
                out.extend(repeat(0, len(slices[0])))
            else:
                out.extend(cols[0] if len(cols) == 1 else map(sum, zip(*cols, strict=True)))
        return out if any(out) else None

    def dense(
        self, var: int, rest: tuple[int, ...], parts: list[list[int]], leading: bool
    ) -> list[int] | None:
        """Return the role's grid summed out, or None when no cell is left."""
        joined = self.fold(parts)
        weights = self.weights[var]
        slices = [
            s if w == 1 else list(map(operator.mul, s, repeat(w)))
            for s, w in zip(_slices(joined, len(weights), leading), weights, strict=True)
        ]
        out = slices[0] if len(slices) == 1 else list(map(sum, zip(*slices, strict=True)))
        return out if any(out) else None


class MinOut:
    """Min-plus's step: add the grids and the role's costs, keep the least and its argmin.

    Attributes:
        trace: per eliminated role, in order: (role, its neighbours, argmin per their cell).
        offsets: the least value taken out of each step's grid (encoded; sum / W is the cost).
    """

    def __init__(self, costs: Sequence[Sequence[int]]) -> None:
        self.width = max((len(c) for c in costs), default=1) + 1
        bound = sum(max(c, default=0) for c in costs) + 1
        if bound.bit_length() > SMALL_COST_BITS:
            raise TooWide("costs too large for small integers")
        self.feasible = 2 * bound * self.width  # every real encoded value is below
        self.inf = 4 * bound * self.width  # ruled-out cells, a multiple of the width
        w = self.width
        self.adds = [[x * w + i for i, x in enumerate(c)] for c in costs]
        self.trace: list[tuple[int, tuple[int, ...], array[int]]] = []
        self.offsets: list[int] = []

    def fold(self, parts: list[list[int]]) -> list[int]:
        """Add grids laid over the same axes, cell by cell."""
        return _folded(parts, operator.add)

    def outer(
        self, var: int, rest: tuple[int, ...], joined: list[int], last: list[int], size: int
    ) -> list[int] | None:
        """Return the role minimised out of ``joined`` plus ``last`` (see ``Step.outer``)."""
        adds = self.adds[var]
        feasible = self.feasible
        slices = _slices(joined, len(adds), True)
        best: list[int] = []
        for z in range(size):
            cols = [
                map(operator.add, piece, repeat(a + last[i * size + z]))
                for i, (piece, a) in enumerate(zip(slices, adds, strict=True))
                if last[i * size + z] < feasible
            ]
            if not cols:
                best.extend(repeat(self.inf, len(slices[0])))
            else:
                best.extend(cols[0] if len(cols) == 1 else map(min, *cols))
        return self._finish(var, rest, best)

    def dense(
        self, var: int, rest: tuple[int, ...], parts: list[list[int]], leading: bool
    ) -> list[int] | None:
        """Return the role's grid minimised out (least value taken out), or None if none left."""
        joined = self.fold(parts)
        adds = self.adds[var]
        cols = [
            map(operator.add, s, repeat(a))
            for s, a in zip(_slices(joined, len(adds), leading), adds, strict=True)
        ]
        return self._finish(var, rest, list(cols[0]) if len(cols) == 1 else list(map(min, *cols)))

    def _finish(self, var: int, rest: tuple[int, ...], best: list[int]) -> list[int] | None:
        """Keep the argmin per cell for the traceback; take the least value out."""
        feasible, w = self.feasible, self.width
        low = min(best)
        if low >= feasible:
            return None
        if max(best) >= feasible:
            inf = self.inf
            best = [x if x < feasible else inf for x in best]
        args = list(map(operator.mod, best, repeat(w)))
        low -= low % w
        self.trace.append((var, rest, array("B" if w <= 256 else "I", args)))
        if low:
            self.offsets.append(low)
            return list(map(operator.sub, best, map(operator.add, args, repeat(low))))
        return list(map(operator.sub, best, args))

    def traceback(self, chosen: dict[int, int], sizes: Sequence[int]) -> None:
        """Fill ``chosen`` (role -> position) for every traced role, last eliminated first."""
        for var, rest, args in reversed(self.trace):
            index = 0
            for v in rest:
                index = index * sizes[v] + chosen[v]
            chosen[var] = args[index]

    def total(self) -> int:
        """Return the sum of the costs taken out (the optimum, less the free roles' costs)."""
        return sum(self.offsets) // self.width
