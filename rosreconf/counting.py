"""Count configurations exactly without listing them.

The number of configurations can be astronomically large (Theorem 9: with orthogonality
it is a product over the roles), so it is computed, not enumerated: every rule of validity
becomes a 0/1 factor over the few roles it mentions, and variable elimination sums the roles
out one at a time, cheapest first. Independent parts of the system graph never share a
factor, so their counts multiply, which is Theorem 9's product; chains and trees cost
O(roles x candidates^2). Python integers keep the result exact at any size.

Factors:

* edge u -> v realised:                 scope {u, v}
* requirements of u's component met:    scope {u} + the providers that can meet them
* "C needs D":                          scope {u} + the roles D can fill
* "C excludes D", one component per role (injectivity): scope {u, w}
"""

from __future__ import annotations

import itertools
from collections import defaultdict
from dataclasses import dataclass

from rosreconf.errors import RosreconfError
from rosreconf.instance import Instance, prune

MAX_FACTOR_ROWS = 2_000_000
"""Largest intermediate table the counter builds before giving up on exactness."""


class CountTooHard(RosreconfError):
    """The system graph is too densely connected to count exactly within the memory budget."""


@dataclass
class Factor:
    """A non-negative table over a few roles; only non-zero rows are stored."""

    scope: tuple[int, ...]
    rows: dict[tuple[str, ...], int]


def count(inst: Instance) -> int:
    """Return the exact number of valid configurations of ``inst``.

    Raises:
        CountTooHard: an intermediate table would exceed ``MAX_FACTOR_ROWS`` rows.
    """
    alive, _, _ = prune(inst)
    if any(not a for a in alive):
        return 0
    factors = _factors(inst, alive)
    return _eliminate(factors, len(inst.roles), alive)


def _table(scope: tuple[int, ...], alive: list[list[str]], keep: object) -> Factor:
    size = 1
    for v in scope:
        size *= len(alive[v])
    if size > MAX_FACTOR_ROWS:
        raise CountTooHard(
            f"counting needs a table of {size} rows over {len(scope)} roles; "
            "the system graph is too densely connected to count exactly"
        )
    rows = {}
    for combo in itertools.product(*(alive[v] for v in scope)):
        if keep(dict(zip(scope, combo, strict=True))):  # type: ignore[operator]
            rows[combo] = 1
    return Factor(scope, rows)


def _factors(inst: Instance, alive: list[list[str]]) -> list[Factor]:
    lib = inst.library
    out: list[Factor] = []
    for (u, v), ok in zip(inst.edges, inst.edge_ok, strict=True):
        pairs = {(a, b) for a, b in ok}
        out.append(_table((u, v), alive, lambda s, u=u, v=v, p=pairs: (s[u], s[v]) in p))
    for u in range(len(inst.roles)):
        scope_set: set[int] = set()
        for cu in alive[u]:
            for i in range(len(lib[cu].requires)):
                scope_set.update(v for v, _ in inst.meets[(u, cu, i)])
        if any(lib[cu].requires for cu in alive[u]):
            scope = (u, *sorted(scope_set - {u}))

            def met(s: dict[int, str], u: int = u) -> bool:
                cu = s[u]
                return all(
                    any(s.get(v) == cv for v, cv in inst.meets[(u, cu, i)])
                    for i in range(len(lib[cu].requires))
                )

            out.append(_table(scope, alive, met))
    holders: dict[str, list[int]] = defaultdict(list)
    for v, names in enumerate(alive):
        for n in names:
            holders[n].append(v)
    for u in range(len(inst.roles)):
        for cu in alive[u]:
            comp = lib[cu]
            for need in sorted(comp.needs):
                where = tuple(w for w in holders.get(need, []) if w != u)
                out.append(
                    _table(
                        (u, *where),
                        alive,
                        lambda s, u=u, cu=cu, need=need, where=where: (
                            s[u] != cu or any(s[w] == need for w in where)
                        ),
                    )
                )
            for ex in sorted(comp.excludes):
                for w in holders.get(ex, []):
                    if w != u:
                        out.append(
                            _table(
                                (u, w),
                                alive,
                                lambda s, u=u, w=w, cu=cu, ex=ex: not (s[u] == cu and s[w] == ex),
                            )
                        )
    for shared in holders.values():
        for u, w in itertools.combinations(shared, 2):
            out.append(_table((u, w), alive, lambda s, u=u, w=w: s[u] != s[w]))
    return out


def _eliminate(factors: list[Factor], n: int, alive: list[list[str]]) -> int:
    by_var: dict[int, list[int]] = defaultdict(list)
    pool: dict[int, Factor] = dict(enumerate(factors))
    for k, f in pool.items():
        for v in f.scope:
            by_var[v].append(k)
    total = 1
    next_id = len(factors)
    remaining = set(range(n))
    while remaining:
        var = min(remaining, key=lambda v: (_neighbours(v, by_var, pool), v))
        remaining.discard(var)
        ids = [k for k in by_var.pop(var, []) if k in pool]
        if not ids:
            total *= len(alive[var])
            continue
        mine = [pool.pop(k) for k in ids]
        merged = mine[0]
        for f in mine[1:]:
            merged = _join(merged, f)
        summed = _sum_out(merged, var)
        if not summed.rows:
            return 0
        if not summed.scope:
            total *= summed.rows[()]
            continue
        pool[next_id] = summed
        for v in summed.scope:
            by_var[v] = [k for k in by_var[v] if k in pool]
            by_var[v].append(next_id)
        next_id += 1
    for f in pool.values():  # pragma: no cover - every factor has its variables eliminated
        total *= sum(f.rows.values())
    return total


def _neighbours(v: int, by_var: dict[int, list[int]], pool: dict[int, Factor]) -> int:
    seen: set[int] = set()
    for k in by_var.get(v, []):
        if k in pool:
            seen.update(pool[k].scope)
    return len(seen)


def _join(a: Factor, b: Factor) -> Factor:
    shared = [v for v in a.scope if v in b.scope]
    extra = [v for v in b.scope if v not in a.scope]
    scope = (*a.scope, *extra)
    ia = [a.scope.index(v) for v in shared]
    ib = [b.scope.index(v) for v in shared]
    ie = [b.scope.index(v) for v in extra]
    index: dict[tuple[str, ...], list[tuple[tuple[str, ...], int]]] = defaultdict(list)
    for row, w in b.rows.items():
        index[tuple(row[i] for i in ib)].append((tuple(row[i] for i in ie), w))
    rows: dict[tuple[str, ...], int] = {}
    for row, w in a.rows.items():
        for tail, w2 in index.get(tuple(row[i] for i in ia), ()):
            rows[row + tail] = w * w2
            if len(rows) > MAX_FACTOR_ROWS:
                raise CountTooHard(
                    f"counting needs over {MAX_FACTOR_ROWS} rows; the system graph is too "
                    "densely connected to count exactly"
                )
    return Factor(scope, rows)


def _sum_out(f: Factor, var: int) -> Factor:
    pos = f.scope.index(var)
    scope = f.scope[:pos] + f.scope[pos + 1 :]
    rows: dict[tuple[str, ...], int] = defaultdict(int)
    for row, w in f.rows.items():
        rows[row[:pos] + row[pos + 1 :]] += w
    return Factor(scope, dict(rows))
