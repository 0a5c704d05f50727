"""The indexes compile_instance makes once are the plain tables, regrouped (issue 12).

``compile_instance`` indexes each required edge's allowed pairs by consumer (``partners``)
and by provider (``users``) while it makes them, and ``edge_ok`` is made from ``partners``
only when read; the constraint tables are built from those indexes and from each shared
``meets`` list's sets. These tests hold every one of them to the plain way: the pairs
``validity.edge_interfaces`` allows, and each table's every combination tested one by one.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import problems

from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.validity import edge_interfaces
from rosreconf.solve.factors import constraint_factors
from rosreconf.solve.instance import Instance, compile_instance, interchangeable, prune
from rosreconf.synthetic import generate, write


def _instance(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], fail: list[bool]
) -> Instance:
    library, schema = problem
    failed = [c.name for c, dead in zip(library, fail, strict=False) if dead]
    return compile_instance(library, schema, failed)


def _generated(tmp: Path, roles: int, k: int, seed: int, fail: list[bool]) -> Instance:
    """Compile a generated library (bench-like: requirements across one provider role)."""
    write(generate(roles, k, 0.5, seed), tmp)
    loaded = load_paths([tmp / "libraries", tmp / "schemas"])
    return _instance((loaded.library, loaded.schemas[0]), fail)


@settings(max_examples=examples(200), deadline=None)
@given(problem=problems(), fail=st.lists(st.booleans(), max_size=9))
def test_partners_users_and_edge_ok_are_the_allowed_pairs(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], fail: list[bool]
) -> None:
    _check_pairs(_instance(problem, fail))


@settings(max_examples=examples(200), deadline=None)
@given(problem=problems(), fail=st.lists(st.booleans(), max_size=9))
def test_tables_hold_exactly_the_allowed_combinations(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], fail: list[bool]
) -> None:
    _check_tables(_instance(problem, fail))


@settings(max_examples=examples(25), deadline=None)
@given(
    roles=st.integers(2, 24),
    k=st.integers(2, 5),
    seed=st.integers(0, 10_000),
    fail=st.lists(st.booleans(), max_size=40),
)
def test_generated_pairs_and_tables(
    tmp_path_factory: pytest.TempPathFactory, roles: int, k: int, seed: int, fail: list[bool]
) -> None:
    """Generated libraries: most requirements are met across one provider role."""
    inst = _generated(tmp_path_factory.mktemp("gen"), roles, k, seed, fail)
    _check_pairs(inst)
    _check_tables(inst)


def test_generated_tables_filter_by_requirement(tmp_path: Path) -> None:
    """The checks above are not vacuous: requirement tables over one provider role filter."""
    inst = _generated(tmp_path, 16, 4, 3, [])
    _check_pairs(inst)
    assert _check_tables(inst) > 0


def _check_pairs(inst: Instance) -> None:
    """Hold ``partners``, ``users`` and ``edge_ok`` to ``validity.edge_interfaces``."""
    required = [e for e in inst.schema.graph.edges if not e.optional]
    assert len(required) == len(inst.edges) == len(inst.partners) == len(inst.users)
    for k, e in enumerate(required):
        u, v = inst.edges[k]
        plain = {
            (cu.name, cv.name)
            for cu in inst.domains[u]
            for cv in inst.domains[v]
            if edge_interfaces(cu, cv, e)
        }
        assert inst.edge_ok[k] == plain
        by_consumer: dict[str, set[str]] = {}
        by_provider: dict[str, set[str]] = {}
        for a, b in plain:
            by_consumer.setdefault(a, set()).add(b)
            by_provider.setdefault(b, set()).add(a)
        assert inst.partners[k] == by_consumer
        assert inst.users[k] == by_provider


def _check_tables(inst: Instance) -> int:
    """Hold each edge and requirement table to its rule tested on every combination.

    Returns how many requirement tables over one provider role had a row filtered out.
    """
    alive, _, _ = prune(inst)
    if any(not a for a in alive):
        return 0
    filtered = 0
    alive = [[members[0] for members in role] for role in interchangeable(inst, alive)]
    tables = constraint_factors(inst, alive, 1)
    edge_tables = [f for f in tables if f.rule == "edge-realised"]  # one per edge, in order
    assert [f.scope for f in edge_tables] == inst.edges
    for f, ok in zip(edge_tables, inst.edge_ok, strict=True):
        every = itertools.product(*(alive[v] for v in f.scope))
        assert set(f.rows) == {row for row in every if row in ok}
    for f in tables:
        every = itertools.product(*(alive[v] for v in f.scope))
        if f.rule == "requirement-met":
            scope = f.scope

            def met(row: tuple[str, ...], scope: tuple[int, ...] = scope) -> bool:
                """Every requirement whose providers are this table's roles is met here."""
                u, providers = scope[0], set(scope[1:])
                have = set(zip(scope[1:], row[1:], strict=True))
                for i in range(len(inst.library[row[0]].requires)):
                    pairs = inst.meets[(u, row[0], i)]
                    if {v for v, _ in pairs} == providers and have.isdisjoint(pairs):
                        return False
                return True

            kept = {row for row in every if met(row)}
            assert set(f.rows) == kept
            total = len(alive[f.scope[0]]) * len(alive[f.scope[1]])
            filtered += len(f.scope) == 2 and len(kept) < total
    return filtered
