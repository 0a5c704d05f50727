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

import functools
import heapq
import itertools
from collections import defaultdict
from collections.abc import Callable

from rosreconf.gcpause import paused_gc
from rosreconf.solve.instance import Instance
from rosreconf.solve.tables import (
    MAX_FACTOR_ROWS,
    Factor,
    JoinOut,
    Marginal,
    Times,
    TooHard,
    _join,
    _join_all_but_last,
    join_sum_out,
    key_of,
)

__all__ = [
    "MAX_FACTOR_ROWS",
    "Factor",
    "JoinOut",
    "Marginal",
    "Times",
    "TooHard",
    "constraint_factors",
    "eliminate",
    "elimination_order",
    "join_sum_out",
    "key_of",
    "paused_gc",
]


def constraint_factors(
    inst: Instance, alive: list[list[str]], one: int, max_rows: int = MAX_FACTOR_ROWS
) -> list[Factor]:
    """Build one table per rule of validity, each allowed row valued ``one``.

    Raises:
        TooHard: a table would exceed ``max_rows`` rows.
    """
    out: list[Factor] = []
    for (u, v), partners in zip(inst.edges, inst.partners, strict=True):
        # edge_ok by consumer: only the allowed pairs are made, never every pair to test it
        _check_size((u, v), alive, max_rows)
        rows: dict[tuple[str, ...], int] = {
            (a, b): one for a in alive[u] if a in partners for b in alive[v] if b in partners[a]
        }
        out.append(Factor((u, v), rows, unit=True, rule="edge-realised"))
    for u in range(len(inst.roles)):
        out.extend(_requirement_factors(inst, u, alive, one, max_rows))
    out.extend(coupling_factors(inst, alive, one, max_rows))
    return out


def coupling_factors(
    inst: Instance, alive: list[list[str]], one: int, max_rows: int = MAX_FACTOR_ROWS
) -> list[Factor]:
    """Build the tables of the rules that name components (the rest of ``constraint_factors``).

    Needs, excludes, one type per label and one role each.

    Raises:
        TooHard: a table would exceed ``max_rows`` rows.
    """
    table = functools.partial(_table, alive=alive, one=one, max_rows=max_rows)
    lib = inst.library
    out: list[Factor] = []
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
    _check_size(scope, alive, max_rows)
    rows = {combo: one for combo in itertools.product(*(alive[v] for v in scope)) if keep(combo)}
    return Factor(scope, rows, unit=True, rule=rule)


def _check_size(scope: tuple[int, ...], alive: list[list[str]], max_rows: int) -> None:
    """Refuse a table over ``scope`` whose every combination would exceed ``max_rows`` rows."""
    size = 1
    for v in scope:
        size *= len(alive[v])
    if size > max_rows:
        raise TooHard(
            f"exact elimination needs a table of {size} rows over {len(scope)} roles; "
            "the system graph is too densely connected"
        )


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
    out = []
    for roles, needs in requirement_groups(inst, u, alive).items():
        scope = (u, *roles)
        if len(roles) == 1:  # the usual case: allowed provider candidates, per candidate
            (v,) = roles
            rows: dict[tuple[str, ...], int] = {}
            for cu in alive[u]:
                both = providers_meeting_all(needs.get(cu))
                if both is None:
                    rows.update(((cu, cv), one) for cv in alive[v])
                    continue
                rows.update(((cu, cv), one) for cv in alive[v] if cv in both)
            out.append(Factor(scope, rows, unit=True, rule="requirement-met"))
            continue
        out.append(requirement_table(scope, needs, alive, one, max_rows))
    return out


def requirement_groups(
    inst: Instance, u: int, alive: list[list[str]]
) -> dict[tuple[int, ...], dict[str, list[_Met]]]:
    """Group role u's candidates' requirements by the provider roles that can meet them.

    Returns provider roles -> candidate -> its requirements met across exactly those roles
    (one table each: ``_requirement_factors``, and the dense grids of
    ``rosreconf.solve.dense``).
    """
    groups: dict[tuple[int, ...], dict[str, list[_Met]]] = defaultdict(dict)
    made: dict[int, _Met] = {}
    for cu in alive[u]:
        for i in range(len(inst.interfaces[cu][1])):  # cu's requirements
            pairs = inst.meets[(u, cu, i)]
            found = made.get(id(pairs))  # candidates with one requirement share its pairs
            if found is None:
                found = made[id(pairs)] = _Met(pairs)
            groups[found.roles].setdefault(cu, []).append(found)
    return groups


def providers_meeting_all(reqs: list[_Met] | None) -> set[str] | None:
    """Return the candidates of the one provider role meeting every requirement (None: any)."""
    if not reqs:
        return None
    return set.intersection(*(r.names for r in reqs))


def requirement_table(
    scope: tuple[int, ...],
    needs: dict[str, list[_Met]],
    alive: list[list[str]],
    one: int,
    max_rows: int,
) -> Factor:
    """Build the table of one group of requirements met across several provider roles."""

    def met(s: tuple[str, ...]) -> bool:
        reqs = needs.get(s[0])
        if not reqs:
            return True
        have = set(zip(scope[1:], s[1:], strict=True))
        return all(not have.isdisjoint(r.pairs) for r in reqs)

    return _table(scope, alive, met, one, max_rows, "requirement-met")


class _Met:
    """One ``meets`` list as sets: its provider roles, its (role, candidate) pairs, its names.

    Made once per shared list; ``names`` (the candidates alone) is what a requirement met
    across a single provider role is tested against, without making a pair per test.
    """

    def __init__(self, pairs: list[tuple[int, str]]) -> None:
        self.roles = tuple(sorted({v for v, _ in pairs}))
        self.pairs = set(pairs)
        self.names = {cv for _, cv in pairs}


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
    done = [False] * n
    # a heap of (degree, role) with stale entries skipped: scanning every degree and every
    # role of the least one was quadratic in a hub's 10,000 consumers
    heap = [(len(adjacent[v]), v) for v in range(n)]
    heapq.heapify(heap)
    while heap:
        degree, var = heapq.heappop(heap)
        if done[var] or degree != len(adjacent[var]):
            continue
        done[var] = True
        order.append(var)
        near = adjacent[var]
        for a in near:  # eliminating var joins its neighbours into one table: a clique
            before = len(adjacent[a])
            adjacent[a].discard(var)
            adjacent[a].update(near - {a})
            if len(adjacent[a]) != before:
                heapq.heappush(heap, (len(adjacent[a]), a))
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
