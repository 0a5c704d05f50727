"""Make the dense grids of one schema's rules of validity (``rosreconf.solve.dense``).

The same tables as ``rosreconf.solve.factors.constraint_factors``, one integer per cell of
their roles' candidate grid; the pair tables (edges realised, requirements met across one
provider role), most of them, are laid out straight from ``compile_instance``'s indexes
(tests/test_dense.py holds both ways alike).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import repeat

from rosreconf.solve.dense import Grid, cells_of, gather
from rosreconf.solve.factors import (
    MAX_FACTOR_ROWS,
    Factor,
    _Met,
    coupling_factors,
    providers_meeting_all,
    requirement_groups,
    requirement_table,
)
from rosreconf.solve.instance import Instance

__all__ = ["constraint_grids", "grids"]


def grids(
    factors: Sequence[Factor],
    alive: Sequence[Sequence[str]],
    present: int,
    absent: int,
    combine: Callable[[int, int], int],
    cap: int,
    into: dict[frozenset[int], Grid] | None = None,
) -> list[Grid]:
    """Turn constraint tables into grids: ``present`` for an allowed row, ``absent`` elsewhere.

    Tables over the same roles are combined into one as they are made (an edge realised and
    the requirement met across it are both tables over the same two roles): each step then
    gathers fewer grids. ``into`` holds grids already made (by roles), to combine with.

    Raises:
        TooWide: a table's grid would pass ``cap`` cells (``cap_for``).
    """
    sizes = [len(a) for a in alive]
    pos = [{c: i for i, c in enumerate(names)} for names in alive]
    out: dict[frozenset[int], Grid] = {} if into is None else into
    for f in factors:
        scope = f.scope
        data = [absent] * cells_of(scope, sizes, cap)
        for row in f.rows:
            code = 0
            for v, c in zip(scope, row, strict=True):
                code = code * sizes[v] + pos[v][c]
            data[code] = present
        _merge(out, Grid(scope, data), combine, sizes)
    return list(out.values())


def _merge(
    out: dict[frozenset[int], Grid],
    g: Grid,
    combine: Callable[[int, int], int],
    sizes: Sequence[int],
) -> None:
    """Add ``g`` to ``out``, combined cell by cell with a grid already over the same roles."""
    key = frozenset(g.scope)
    earlier = out.get(key)
    if earlier is None:
        out[key] = g
    else:
        moved = gather(g, earlier.scope, sizes)
        out[key] = Grid(earlier.scope, list(map(combine, earlier.data, moved)))


def constraint_grids(
    inst: Instance,
    alive: list[list[str]],
    present: int,
    absent: int,
    combine: Callable[[int, int], int],
    cap: int,
) -> list[Grid]:
    """Build ``grids(constraint_factors(...))`` with the pair tables made as grids directly.

    The edges realised and the requirements met across one provider role are most of the
    tables: their rows come straight from ``compile_instance``'s indexes (partners, meets),
    one row of cells per distinct set of allowed providers, without a dictionary of name
    pairs in between. The other rules' tables are made as ``constraint_factors`` makes them.

    Raises:
        TooWide: a table's grid would pass ``cap`` cells (``cap_for``).
    """
    sizes = [len(a) for a in alive]
    out: dict[frozenset[int], Grid] = {}
    for (u, v), partners in zip(inst.edges, inst.partners, strict=True):
        cells_of((u, v), sizes, cap)
        data = _rows(alive[u], alive[v], partners.get, present, absent)
        _merge(out, Grid((u, v), data), combine, sizes)
    rest: list[Factor] = []
    everyone = set[str]()  # stands for "any provider" (no requirement): never read
    for u in range(len(inst.roles)):
        for roles, needs in requirement_groups(inst, u, alive).items():
            scope = (u, *roles)
            if len(roles) != 1:
                rest.append(requirement_table(scope, needs, alive, 1, MAX_FACTOR_ROWS))
                continue
            cells_of(scope, sizes, cap)
            meeting: dict[tuple[int, ...], set[str]] = {}

            def allowed(
                cu: str,
                needs: dict[str, list[_Met]] = needs,
                meeting: dict[tuple[int, ...], set[str]] = meeting,
            ) -> set[str] | None:
                reqs = needs.get(cu)
                if not reqs:
                    return everyone
                key = tuple(map(id, reqs))
                found = meeting.get(key)
                if found is None:
                    found = meeting[key] = providers_meeting_all(reqs) or set()
                return found

            data = _rows(alive[u], alive[roles[0]], allowed, present, absent, everyone)
            _merge(out, Grid(scope, data), combine, sizes)
    rest.extend(coupling_factors(inst, alive, 1, MAX_FACTOR_ROWS))
    return grids(rest, alive, present, absent, combine, cap, out)


def _rows(
    consumers: Sequence[str],
    providers: Sequence[str],
    allowed: Callable[[str], set[str] | None],
    present: int,
    absent: int,
    everyone: set[str] | None = None,
) -> list[int]:
    """Lay out a pair table: per consumer, a row of cells over the providers it allows.

    ``allowed(consumer)`` is None (none allowed) or a set of providers (``everyone``: all);
    consumers sharing one set share its row, made once.
    """
    k = len(providers)
    made: dict[int, list[int]] = {}
    data: list[int] = []
    for cu in consumers:
        mates = allowed(cu)
        if mates is None:
            data.extend(repeat(absent, k))
        elif mates is everyone:
            data.extend(repeat(present, k))
        else:
            row = made.get(id(mates))
            if row is None:
                row = made[id(mates)] = [present if cv in mates else absent for cv in providers]
            data.extend(row)
    return data
