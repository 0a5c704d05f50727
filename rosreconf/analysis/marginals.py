"""Count, for every role and candidate, the valid configurations that put it there.

``analyse`` and ``whatif`` ask per component: is it in some configuration (usable, relevant)?
Is it in every one (a single point of failure)? Does the schema survive its failure? Asking
the counter once per component costs a whole count per question; with 10,000 candidates
for one role that was most of ``analyse``'s time. Every one of these answers is a
*marginal* of the count, and all marginals come out of one elimination run twice, which
is the junction-tree (sum-product) algorithm on counting's own tables
(``rosreconf.solve.factors``):

* forward: eliminate the roles in counting's order, remembering which tables each role's
  step joined and which later step received its summed-out table (its "message");
* backward: in reverse order, give each step the count of everything outside its
  subtree (its "outside message", over the roles it shares with the rest), join it with
  the step's tables and sum down to the role itself.

Integers stay exact at any size, as in counting. A candidate ``c`` of role ``u`` is in
``marginal[u][c]`` configurations; since a component fills at most one role, the
configurations that hold ``c`` at all are the sum over its roles, so ``c`` is in every
configuration exactly when that sum equals the total, and the schema survives ``c``'s
failure exactly when it is below the total.
"""

from __future__ import annotations

import operator
from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass

from rosreconf.gcpause import paused_gc
from rosreconf.solve.emptyroles import is_empty_choice
from rosreconf.solve.factors import constraint_factors, elimination_order
from rosreconf.solve.instance import Instance, prune
from rosreconf.solve.tables import MAX_FACTOR_ROWS, Factor, _join_all, key_of

__all__ = ["Marginals", "marginals"]


@dataclass(frozen=True)
class Marginals:
    """How many valid configurations put each candidate in each role.

    Attributes:
        total: the number of valid configurations (counting's answer).
        per_role: per role index, candidate name -> configurations with it in that role
            (every candidate of the role's domain is a key; pruned ones have 0).
    """

    total: int
    per_role: list[dict[str, int]]

    def holding(self, component: str) -> int:
        """Return how many configurations hold ``component`` in any role."""
        return sum(m.get(component, 0) for m in self.per_role)

    def usable(self) -> set[str]:
        """Return the components in at least one valid configuration.

        An optional role's empty choice is no component: never listed (so never a single
        point of failure).
        """
        return {c for m in self.per_role for c, k in m.items() if k and not is_empty_choice(c)}

    def in_every(self) -> list[str]:
        """Return the components in every valid configuration (none when there is none)."""
        if not self.total:
            return []
        held: dict[str, int] = defaultdict(int)
        for m in self.per_role:
            for c, k in m.items():
                held[c] += k
        # an optional role's empty choice is no component: never a single point of failure
        return sorted(
            c for c, k in held.items() if k and k == self.total and not is_empty_choice(c)
        )


def marginals(inst: Instance, max_rows: int = MAX_FACTOR_ROWS) -> Marginals:
    """Return the total count and every role's per-candidate count, in two elimination passes.

    Raises:
        TooHard: a table would exceed ``max_rows`` rows (as counting would).
    """
    zero = [dict.fromkeys((c.name for c in dom), 0) for dom in inst.domains]
    with paused_gc():
        alive, _, _ = prune(inst)
        if any(not a for a in alive):
            return Marginals(0, zero)
        factors = constraint_factors(inst, alive, 1, max_rows)
        if any(not f.rows for f in factors):
            return Marginals(0, zero)
        order = elimination_order([f.scope for f in factors], len(alive))
        forward = _forward(factors, order, max_rows)
        if forward is None:
            return Marginals(0, zero)
        return _backward(forward, alive, zero, max_rows)


@dataclass
class _Forward:
    """What the forward pass remembers.

    Attributes:
        order: the roles in elimination order.
        inputs: per eliminated role, the tables its step joined, each with the role whose
            message it is (None for a constraint table).
        roots: role -> count of its connected part, for the last role eliminated in each part.
        free: roles in no table (any candidate will do).
    """

    order: list[int]
    inputs: dict[int, list[tuple[Factor, int | None]]]
    roots: dict[int, int]
    free: list[int]


def _forward(factors: list[Factor], order: list[int], max_rows: int) -> _Forward | None:
    """Eliminate in ``order`` as counting does, keeping each step's inputs; None if no row."""
    pool: dict[int, Factor] = dict(enumerate(factors))
    origin: dict[int, int] = {}
    by_var: dict[int, set[int]] = defaultdict(set)
    for k, f in pool.items():
        for v in f.scope:
            by_var[v].add(k)
    out = _Forward(order, {}, {}, [])
    next_id = len(factors)
    for var in order:
        ids = sorted(by_var.pop(var, ()))
        if not ids:
            out.free.append(var)
            continue
        mine = [(pool.pop(k), origin.get(k)) for k in ids]
        out.inputs[var] = mine
        joined = _join_all([f for f, _ in mine], operator.mul, max_rows)
        scope = tuple(v for v in joined.scope if v != var)
        for v in scope:
            by_var[v].difference_update(ids)
        message = _project(joined, scope)
        if not message.rows:
            return None
        if not scope:
            out.roots[var] = message.rows[()]
            continue
        pool[next_id] = message
        origin[next_id] = var
        for v in scope:
            by_var[v].add(next_id)
        next_id += 1
    return out


def _backward(
    fw: _Forward, alive: list[list[str]], zero: list[dict[str, int]], max_rows: int
) -> Marginals:
    """Pass outside messages from the roots down and read off every role's marginal."""
    free_factor = 1
    for v in fw.free:
        free_factor *= len(alive[v])
    total = free_factor
    for part in fw.roots.values():
        total *= part
    outside: dict[int, Factor] = {}
    for root, part in fw.roots.items():
        others = total // part  # every other part and free role, multiplied in
        outside[root] = Factor((), {(): others})
    per_role = [dict(z) for z in zero]
    for var in reversed(fw.order):
        if var in fw.free:
            for c in alive[var]:
                per_role[var][c] = total // len(alive[var])
            continue
        inputs = fw.inputs[var]
        lam = outside.pop(var)
        joined = _join_all([*(f for f, _ in inputs), lam], operator.mul, max_rows)
        for (c,), k in _project(joined, (var,)).rows.items():
            per_role[var][c] = k
        for message, child, around in _all_but_one(inputs, lam, max_rows):
            keep = tuple(v for v in message.scope if v in around.scope)
            outside[child] = _project(around, keep)
    return Marginals(total, per_role)


SMALL_STEP = 8
"""Most inputs of a step for which each child's "everything else" is joined afresh."""


def _all_but_one(
    inputs: list[tuple[Factor, int | None]], lam: Factor, max_rows: int
) -> Iterator[tuple[Factor, int, Factor]]:
    """Yield per child message (message, child, join of every other input and ``lam``).

    A few inputs are joined afresh for each child. Many (a hub's 10,000 consumers, a
    fan-in's 2,000 providers) would make that quadratic, so the joins of the inputs after
    each one are made once, right to left, and combined with a running join of those before
    it: linear in the inputs.
    """
    tables = [f for f, _ in inputs]
    if len(inputs) <= SMALL_STEP:
        for i, (message, child) in enumerate(inputs):
            if child is None:
                continue
            rest = tables[:i] + tables[i + 1 :]
            around = _join_all([*rest, lam], operator.mul, max_rows) if rest else lam
            yield message, child, around
        return
    after: list[Factor] = [lam] * (len(tables) + 1)
    for i in range(len(tables) - 1, 0, -1):
        after[i] = _join_all([tables[i], after[i + 1]], operator.mul, max_rows)
    before: Factor | None = None
    for i, (message, child) in enumerate(inputs):
        if child is not None:
            around = after[i + 1]
            if before is not None:
                around = _join_all([before, around], operator.mul, max_rows)
            yield message, child, around
        before = message if before is None else _join_all([before, message], operator.mul, max_rows)


def _project(f: Factor, keep: tuple[int, ...]) -> Factor:
    """Sum ``f`` down to the roles in ``keep`` (in that order); unit tables count 1 a row."""
    pick = key_of([f.scope.index(v) for v in keep])
    rows: dict[tuple[str, ...], int] = defaultdict(int)
    for row, w in f.rows.items():
        rows[pick(row)] += w
    return Factor(keep, dict(rows))
