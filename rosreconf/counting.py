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

import functools
import heapq
import itertools
import operator
from collections import defaultdict
from collections.abc import Callable
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


def _table(
    scope: tuple[int, ...], alive: list[list[str]], keep: Callable[[tuple[str, ...]], bool]
) -> Factor:
    size = 1
    for v in scope:
        size *= len(alive[v])
    if size > MAX_FACTOR_ROWS:
        raise CountTooHard(
            f"counting needs a table of {size} rows over {len(scope)} roles; "
            "the system graph is too densely connected to count exactly"
        )
    rows = {combo: 1 for combo in itertools.product(*(alive[v] for v in scope)) if keep(combo)}
    return Factor(scope, rows)


def _factors(inst: Instance, alive: list[list[str]]) -> list[Factor]:
    lib = inst.library
    out: list[Factor] = []
    for (u, v), ok in zip(inst.edges, inst.edge_ok, strict=True):
        out.append(_table((u, v), alive, ok.__contains__))
    for u in range(len(inst.roles)):
        out.extend(_requirement_factors(inst, u, alive))
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
                        functools.partial(_needs_met, cu=cu, need=need),
                    )
                )
            for ex in sorted(comp.excludes):
                for w in holders.get(ex, []):
                    if w != u:
                        out.append(_table((u, w), alive, (cu, ex).__ne__))
    for shared in holders.values():
        for u, w in itertools.combinations(shared, 2):
            out.append(_table((u, w), alive, lambda s: s[0] != s[1]))
    return out


def _needs_met(s: tuple[str, ...], cu: str, need: str) -> bool:
    return s[0] != cu or need in s[1:]


def _requirement_factors(inst: Instance, u: int, alive: list[list[str]]) -> list[Factor]:
    """Build "every requirement of u's component is met" as one factor per provider set.

    A requirement of candidate ``cu`` is met by one of the provider roles in its ``meets``
    table. Grouping the requirements by that set of roles and multiplying one factor per
    group gives the same function as one factor over all of u's providers, but each table
    is only as wide as one group (usually u and one provider: K^2 rows, not K^4).
    """
    groups: dict[tuple[int, ...], dict[str, list[set[tuple[int, str]]]]] = defaultdict(dict)
    for cu in alive[u]:
        for i in range(len(inst.library[cu].requires)):
            pairs = inst.meets[(u, cu, i)]
            roles = tuple(sorted({v for v, _ in pairs}))
            groups[roles].setdefault(cu, []).append(set(pairs))
    out = []
    for roles, needs in groups.items():
        scope = (u, *roles)

        def met(
            s: tuple[str, ...],
            scope: tuple[int, ...] = scope,
            needs: dict[str, list[set[tuple[int, str]]]] = needs,
        ) -> bool:
            reqs = needs.get(s[0])
            if not reqs:
                return True
            have = set(zip(scope[1:], s[1:], strict=True))
            return all(not have.isdisjoint(r) for r in reqs)

        out.append(_table(scope, alive, met))
    return out


def _eliminate(factors: list[Factor], n: int, alive: list[list[str]]) -> int:
    by_var: dict[int, set[int]] = defaultdict(set)
    pool: dict[int, Factor] = dict(enumerate(factors))
    for k, f in pool.items():
        for v in f.scope:
            by_var[v].add(k)
    total = 1
    next_id = len(factors)
    heap = [(_neighbours(v, by_var, pool), v) for v in range(n)]
    heapq.heapify(heap)
    done: set[int] = set()
    while heap:
        score, var = heapq.heappop(heap)
        if var in done:
            continue
        now = _neighbours(var, by_var, pool)
        if now != score:  # stale entry: its neighbourhood changed since it was pushed
            heapq.heappush(heap, (now, var))
            continue
        done.add(var)
        ids = sorted(by_var.pop(var, ()))
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
        touched = {v for f in mine for v in f.scope} - {var}
        for v in touched:
            by_var[v].difference_update(ids)
        if not summed.scope:
            total *= summed.rows[()]
        else:
            pool[next_id] = summed
            for v in summed.scope:
                by_var[v].add(next_id)
            next_id += 1
        for v in touched:
            heapq.heappush(heap, (_neighbours(v, by_var, pool), v))
    for f in pool.values():  # pragma: no cover - every factor has its variables eliminated
        total *= sum(f.rows.values())
    return total


def _neighbours(v: int, by_var: dict[int, set[int]], pool: dict[int, Factor]) -> int:
    seen: set[int] = set()
    for k in by_var.get(v, ()):
        seen.update(pool[k].scope)
    return len(seen)


def _key(positions: list[int]) -> Callable[[tuple[str, ...]], tuple[str, ...]]:
    """Return a fast row -> sub-row function (itemgetter, always returning a tuple)."""
    if not positions:
        return lambda row: ()
    if len(positions) == 1:
        p = positions[0]
        return lambda row: (row[p],)
    return operator.itemgetter(*positions)


def _join(a: Factor, b: Factor) -> Factor:
    shared = [v for v in a.scope if v in b.scope]
    extra = [v for v in b.scope if v not in a.scope]
    scope = (*a.scope, *extra)
    key_a = _key([a.scope.index(v) for v in shared])
    key_b = _key([b.scope.index(v) for v in shared])
    tail_b = _key([b.scope.index(v) for v in extra])
    index: dict[tuple[str, ...], list[tuple[tuple[str, ...], int]]] = defaultdict(list)
    for row, w in b.rows.items():
        index[key_b(row)].append((tail_b(row), w))
    rows: dict[tuple[str, ...], int] = {}
    for row, w in a.rows.items():
        for tail, w2 in index.get(key_a(row), ()):
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
    rest = _key([i for i in range(len(f.scope)) if i != pos])
    rows: dict[tuple[str, ...], int] = defaultdict(int)
    for row, w in f.rows.items():
        rows[rest(row)] += w
    return Factor(scope, dict(rows))
