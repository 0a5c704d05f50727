"""Turn validity into small tables over few roles, and eliminate roles from them one by one.

Counting (``rosreconf.solve.counting``, sum-product) and optimisation (``rosreconf.solve.optimum``,
min-plus) run the same algorithm on the same tables; only how two values combine and how a
role is summed out differ. Keeping both here means they cannot drift apart: a rule of
validity added once is counted and optimised alike.

Every rule of validity becomes a table over the few roles it mentions, holding only the
rows (candidate combinations) it allows:

* edge u -> v realised:                 scope {u, v}
* requirements of u's component met:    scope {u} + the providers that can meet them
* "C needs D":                          scope {u} + the roles D can fill
* "C excludes D", one type per label, one component per role (injectivity): scope {u, w}

Generated system graphs have small treewidth, so eliminating the role with the fewest
neighbours first keeps every intermediate table to a few candidates^3 rows.
"""

from __future__ import annotations

import contextlib
import functools
import gc
import itertools
import operator
from collections import defaultdict
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from rosreconf.errors import RosreconfError
from rosreconf.solve.instance import Instance

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


def constraint_factors(
    inst: Instance, alive: list[list[str]], one: int, max_rows: int = MAX_FACTOR_ROWS
) -> list[Factor]:
    """Build one table per rule of validity, each allowed row valued ``one``.

    Raises:
        TooHard: a table would exceed ``max_rows`` rows.
    """
    table = functools.partial(_table, alive=alive, one=one, max_rows=max_rows)
    lib = inst.library
    out: list[Factor] = []
    for (u, v), ok in zip(inst.edges, inst.edge_ok, strict=True):
        out.append(table((u, v), keep=ok.__contains__, rule="edge-realised"))
    for u in range(len(inst.roles)):
        out.extend(_requirement_factors(inst, u, alive, one, max_rows))
    holders: dict[str, list[int]] = defaultdict(list)
    for v, names in enumerate(alive):
        for n in names:
            holders[n].append(v)
    # One table per scope, not per component: at 10,000 candidates of one role, a table per
    # excluding candidate was 10,000 x K rows each, quadratic in all; grouped, each pair of
    # roles gets one table holding every banned pair (the same function: all are 0/1 filters).
    needs: dict[tuple[int, ...], dict[str, list[str]]] = defaultdict(dict)
    banned: dict[tuple[str, tuple[int, int]], dict[str, set[str]]] = defaultdict(dict)
    for u in range(len(inst.roles)):
        for cu in alive[u]:
            comp = lib[cu]
            for need in sorted(comp.needs):
                where = tuple(w for w in holders.get(need, []) if w != u)
                needs[(u, *where)].setdefault(cu, []).append(need)
            for ex in sorted(comp.excludes):
                for w in holders.get(ex, []):
                    if w != u:
                        banned[("excludes", (u, w))].setdefault(cu, set()).add(ex)
            for other in sorted(inst.clashes.get(cu, ())):
                for w in holders.get(other, []):
                    if w > u:  # clashes are symmetric: one table per pair of roles
                        banned[("one-type-per-label", (u, w))].setdefault(cu, set()).add(other)
    for scope, wanted in needs.items():
        keep = functools.partial(_needs_met, needs=wanted)
        out.append(table(scope, keep=keep, rule="needs"))
    for (rule, pair), bans in banned.items():
        out.append(table(pair, keep=functools.partial(_not_banned, bans=bans), rule=rule))
    shared_pairs = {
        pair for shared in holders.values() for pair in itertools.combinations(shared, 2)
    }
    for pair in sorted(shared_pairs):  # one table per pair of roles, however many they share
        out.append(table(pair, keep=_distinct, rule="one-role-each"))
    return out


def _table(
    scope: tuple[int, ...],
    alive: list[list[str]],
    keep: Callable[[tuple[str, ...]], bool],
    one: int,
    max_rows: int,
    rule: str,
) -> Factor:
    size = 1
    for v in scope:
        size *= len(alive[v])
    if size > max_rows:
        raise TooHard(
            f"exact elimination needs a table of {size} rows over {len(scope)} roles; "
            "the system graph is too densely connected"
        )
    rows = {combo: one for combo in itertools.product(*(alive[v] for v in scope)) if keep(combo)}
    return Factor(scope, rows, unit=True, rule=rule)


def _distinct(s: tuple[str, ...]) -> bool:
    return s[0] != s[1]


def _needs_met(s: tuple[str, ...], needs: dict[str, list[str]]) -> bool:
    wanted = needs.get(s[0])
    return not wanted or all(need in s[1:] for need in wanted)


def _not_banned(s: tuple[str, ...], bans: dict[str, set[str]]) -> bool:
    banned = bans.get(s[0])
    return not banned or s[1] not in banned


def _requirement_factors(
    inst: Instance, u: int, alive: list[list[str]], one: int, max_rows: int
) -> list[Factor]:
    """Build "every requirement of u's component is met" as one table per provider set.

    A requirement of candidate ``cu`` is met by one of the provider roles in its ``meets``
    table. Grouping the requirements by that set of roles gives the same function as one
    table over all of u's providers, but each table is only as wide as one group (usually
    u and one provider: K^2 rows, not K^4).
    """
    groups: dict[tuple[int, ...], dict[str, list[set[tuple[int, str]]]]] = defaultdict(dict)
    made: dict[int, tuple[tuple[int, ...], set[tuple[int, str]]]] = {}
    for cu in alive[u]:
        for i in range(len(inst.library[cu].requires)):
            pairs = inst.meets[(u, cu, i)]
            found = made.get(id(pairs))  # candidates with one requirement share its pairs
            if found is None:
                found = made[id(pairs)] = (tuple(sorted({v for v, _ in pairs})), set(pairs))
            roles, allowed = found
            groups[roles].setdefault(cu, []).append(allowed)
    out = []
    for roles, needs in groups.items():
        scope = (u, *roles)
        if len(roles) == 1:  # the usual case: allowed provider candidates, per candidate
            (v,) = roles
            rows: dict[tuple[str, ...], int] = {}
            for cu in alive[u]:
                reqs = needs.get(cu)
                both = set.intersection(*reqs) if reqs else None  # providers meeting all
                for cv in alive[v]:
                    if both is None or (v, cv) in both:
                        rows[(cu, cv)] = one
            out.append(Factor(scope, rows, unit=True, rule="requirement-met"))
            continue

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

        out.append(_table(scope, alive, met, one, max_rows, "requirement-met"))
    return out


def elimination_order(scopes: list[tuple[int, ...]], n: int) -> list[int]:
    """Return the roles in the order to eliminate them: fewest neighbours first.

    Decided from the scopes alone (which roles share a table), so counting and
    optimisation eliminate in the very same order. Ties go to the lower role index.
    """
    adjacent: list[set[int]] = [set() for _ in range(n)]
    for scope in scopes:
        for v in scope:
            adjacent[v].update(scope)
    for v in range(n):
        adjacent[v].discard(v)
    order: list[int] = []
    left = set(range(n))
    buckets: dict[int, set[int]] = defaultdict(set)
    for v in range(n):
        buckets[len(adjacent[v])].add(v)
    while left:
        degree = min(d for d, b in buckets.items() if b)
        var = min(buckets[degree])
        buckets[degree].discard(var)
        left.discard(var)
        order.append(var)
        near = adjacent[var]
        for a in near:  # eliminating var joins its neighbours into one table: a clique
            before = len(adjacent[a])
            adjacent[a].discard(var)
            adjacent[a].update(near - {a})
            if len(adjacent[a]) != before:
                buckets[before].discard(a)
                buckets[len(adjacent[a])].add(a)
    return order


def eliminate(
    factors: list[Factor],
    order: list[int],
    times: Times,
    marginal: Marginal,
    max_rows: int,
    one: int = 1,
    join_out: JoinOut | None = None,
) -> tuple[list[int], list[int]] | None:
    """Eliminate the roles in ``order``; return the leftover scalars and the free roles.

    A free role is in no table (any candidate will do). None means some table lost its last
    row: there is no valid configuration. ``factors`` is emptied: the tables move into the
    elimination's pool, so each is freed as soon as it is joined instead of living (in the
    caller's list) until the end; at 10,000 roles they are about 180 MiB. ``one`` is the
    neutral value of ``times`` (1 to count, 0 for costs): combining with it is skipped.
    Costs of single roles are the marginal's business (``optimum`` adds them while
    minimising a role out), so a role in no table is free here too. ``join_out``, when
    given, does the last join of each role's tables and its marginal in one pass: the
    joined table is the widest of each step, and is otherwise built only to be walked once.

    Raises:
        TooHard: a joined table would exceed ``max_rows`` rows.
    """
    by_var: dict[int, set[int]] = defaultdict(set)
    pool: dict[int, Factor] = dict(enumerate(factors))
    next_id = len(factors)
    factors.clear()  # the pool owns the tables now: each is freed once joined
    for k, f in pool.items():
        if not f.rows:
            return None
        for v in f.scope:
            by_var[v].add(k)
    scalars: list[int] = []
    free: list[int] = []
    for var in order:
        ids = sorted(by_var.pop(var, ()))
        mine = [pool.pop(k) for k in ids]
        if not mine:
            free.append(var)
            continue
        merged, last = _join_all_but_last(mine, times, max_rows, one)
        if last is None:
            reduced = marginal(merged, var)
        elif join_out is not None:
            reduced = join_out(merged, last, var, max_rows)
        else:
            reduced = marginal(_join(merged, last, times, max_rows, one), var)
        if not reduced.rows:
            return None
        for v in {v for f in mine for v in f.scope} - {var}:
            by_var[v].difference_update(ids)
        if not reduced.scope:
            scalars.append(reduced.rows[()])
            continue
        pool[next_id] = reduced
        for v in reduced.scope:
            by_var[v].add(next_id)
        next_id += 1
    scalars.extend(v for f in pool.values() for v in f.rows.values())  # pragma: no cover
    return scalars, free


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
        pick = min(range(len(rest)), key=lambda i: (len(set(rest[i].scope) - have), i))
        if len(rest) == 1:
            return merged, rest[pick]
        merged = _join(merged, rest.pop(pick), times, max_rows, one)
    return merged, None


def _join_all(factors: list[Factor], times: Times, max_rows: int, one: int = 1) -> Factor:
    """Join tables in ``_join_all_but_last``'s order, the last one too."""
    merged, last = _join_all_but_last(factors, times, max_rows, one)
    return merged if last is None else _join(merged, last, times, max_rows, one)


def join_sum_out(a: Factor, b: Factor, var: int, max_rows: int) -> Factor:
    """Join two count tables and sum ``var`` out of the result, in one pass.

    The same table as ``_sum_out(_join(a, b, operator.mul, max_rows), var)`` (counting's
    tests hold the two alike), without building the joined table: at 1000 roles x 10
    candidates, that table is most of the rows of the whole count, each built only to be
    added into its sub-row. The row budget still counts the joined rows, so a schema too
    densely connected to count exactly is refused exactly where it was before.
    """
    if a.unit and not b.unit:  # keep the valued table on the left: only b may be a filter
        a, b = b, a
    extra = [v for v in b.scope if v not in a.scope]
    shared = [v for v in a.scope if v in b.scope]
    key_a = key_of([a.scope.index(v) for v in shared])
    key_b = key_of([b.scope.index(v) for v in shared])
    pos = a.scope.index(var)
    head = key_of([i for i in range(len(a.scope)) if i != pos])
    tail_b = key_of([b.scope.index(v) for v in extra])
    grouped: dict[tuple[str, ...], list[tuple[tuple[str, ...], int]]] = defaultdict(list)
    for row, w in b.rows.items():
        grouped[key_b(row)].append((tail_b(row), w))
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
            raise TooHard(
                f"exact elimination needs over {max_rows} rows; the system graph is too "
                "densely connected"
            )
    return Factor((*a.scope[:pos], *a.scope[pos + 1 :], *extra), dict(rows))


def key_of(positions: list[int]) -> Callable[[tuple[str, ...]], tuple[str, ...]]:
    """Return a fast row -> sub-row function (itemgetter, always returning a tuple)."""
    if not positions:
        return lambda row: ()
    if len(positions) == 1:
        p = positions[0]
        return lambda row: (row[p],)
    return operator.itemgetter(*positions)


@contextlib.contextmanager
def paused_gc() -> Iterator[None]:
    """Pause the cyclic garbage collector while millions of acyclic rows are built.

    Tables hold only tuples of strings and integers, which reference counting frees; but
    every collection would still walk the whole loaded library, and at 1000 roles those
    walks cost more than the elimination itself.
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


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
            raise TooHard(
                f"exact elimination needs over {max_rows} rows; the system graph is too "
                "densely connected"
            )
    return Factor((*a.scope, *extra), rows, a.unit and b.unit)
