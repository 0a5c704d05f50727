"""The semantic checks decide a clean library on an index: the same problems as walking it.

``checks.check`` first asks small questions of an index built in one walk (are the names
unique, do the distinct interfaces agree, is every requirement option provided, is every
named schema and abstraction used?) and walks the components only when the answer is no.
These tests draw libraries and schemas with every kind of semantic problem and compare the
problems found with those found when every answer is forced to "no" (every walk taken).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.errors import Problem
from rosreconf.formats import checks, interfacechecks
from rosreconf.formats.loader import load_paths
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    Requirement,
    Role,
    SystemGraph,
)

REPO = Path(__file__).resolve().parent.parent

INTERFACES = [
    Interface(InterfaceKind.TOPIC, "a", "m/A"),
    Interface(InterfaceKind.TOPIC, "b", "m/B"),
    Interface(InterfaceKind.SERVICE, "c", "m/C"),
    Interface(InterfaceKind.TOPIC, "a", "m/A2"),  # one label, two types
    Interface(InterfaceKind.SERVICE, "b", "m/B"),  # one label, two kinds
    Interface(InterfaceKind.TOPIC, "z", "m/Z"),  # provided by nobody unless drawn
]
NAMES = ["C0", "C1", "C2", "c1", "C3"]  # c1: C1 in another letter case
LABELS = ["l0", "l1", "l2", "unused"]
SCHEMA_NAMES = ["s", "t", "nowhere"]


@st.composite
def _component(draw: st.DrawFn) -> Component:
    requires = tuple(
        Requirement(tuple(draw(st.lists(st.sampled_from(INTERFACES), min_size=1, max_size=2))))
        for _ in range(draw(st.integers(0, 2)))
    )
    return Component(
        name=draw(st.sampled_from(NAMES)),
        abstraction=draw(st.sampled_from(LABELS)),
        provides=frozenset(draw(st.sets(st.sampled_from(INTERFACES), max_size=2))),
        requires=requires,
        needs=frozenset(draw(st.sets(st.sampled_from([*NAMES, "NOPE"]), max_size=1))),
        excludes=frozenset(draw(st.sets(st.sampled_from(NAMES), max_size=1))),
        schemas=frozenset(draw(st.sets(st.sampled_from(SCHEMA_NAMES), max_size=2))),
    )


@st.composite
def _schema(draw: st.DrawFn) -> InteroperabilitySchema:
    roles = tuple(
        Role(f"r{i}", draw(st.sampled_from([*LABELS[:3], "nolabel"])))
        for i in range(draw(st.integers(1, 3)))
    )
    edges = tuple(
        Edge(
            draw(st.sampled_from(["r0", "r1", "r9"])),
            draw(st.sampled_from(["r0", "r1"])),
            frozenset(draw(st.sets(st.sampled_from(["a", "b", "c", "z", "q"]), max_size=2))),
        )
        for _ in range(draw(st.integers(0, 2)))
    )
    nominal = draw(
        st.dictionaries(st.sampled_from(["r0", "r1", "r7"]), st.sampled_from(NAMES), max_size=2)
    )
    name = draw(st.sampled_from(SCHEMA_NAMES[:2]))
    return InteroperabilitySchema(name, SystemGraph(roles, edges), "k", "e", nominal=nominal)


@st.composite
def _inputs(draw: st.DrawFn) -> tuple[list[ComponentLibrary], list[InteroperabilitySchema]]:
    libraries = [
        ComponentLibrary(f"lib{i}", tuple(draw(st.lists(_component(), min_size=1, max_size=4))))
        for i in range(draw(st.integers(1, 2)))
    ]
    return libraries, draw(st.lists(_schema(), max_size=2))


DECISIONS = [
    (checks, "_unique_names"),
    (checks, "_all_used"),
    (interfacechecks.InterfaceIndex, "agree"),
    (interfacechecks.InterfaceIndex, "all_met"),
]
"""Every question a clean library is decided on."""


def _walked(
    libraries: list[ComponentLibrary],
    schemas: list[InteroperabilitySchema],
    complete: bool,
) -> list[Problem]:
    """Return ``check``'s problems with every decision answered "no" (every walk taken)."""
    with pytest.MonkeyPatch.context() as mp:
        for owner, name in DECISIONS:
            mp.setattr(owner, name, lambda *_: False)
        return checks.check(libraries, schemas, library_complete=complete)


@settings(max_examples=examples(400))
@given(inputs=_inputs(), complete=st.booleans())
def test_deciding_on_the_index_finds_what_the_walks_find(
    inputs: tuple[list[ComponentLibrary], list[InteroperabilitySchema]], complete: bool
) -> None:
    libraries, schemas = inputs
    found = checks.check(libraries, schemas, library_complete=complete)
    assert found == _walked(libraries, schemas, complete)


def _broken() -> Iterator[tuple[str, list[ComponentLibrary], list[InteroperabilitySchema]]]:
    """Yield one library per decision, each with exactly the problem that decision sees."""
    a, a2 = INTERFACES[0], INTERFACES[3]
    good = Component("P", "l0", provides=frozenset({a}))
    user = Component("U", "l1", requires=(Requirement((a,)),))
    roles = (Role("r0", "l0"), Role("r1", "l1"))
    schema = InteroperabilitySchema("s", SystemGraph(roles, ()), "k", "e")
    lib = ComponentLibrary("l", (good, user))
    yield "clean", [lib], [schema]
    yield "case-collision", [replace(lib, components=(good, replace(user, name="p")))], [schema]
    yield "type-conflict", [replace(lib, components=(good, replace(user, provides={a2})))], [schema]
    elsewhere = replace(good, provides=frozenset({INTERFACES[1]}))
    yield "unmet-requirement", [replace(lib, components=(elsewhere, user))], [schema]
    yield (
        "unknown-schema",
        [replace(lib, components=(good, replace(user, schemas={"x"})))],
        [schema],
    )


@pytest.mark.parametrize(("code", "libraries", "schemas"), list(_broken()), ids=lambda x: x)
def test_each_decision_sees_its_problem(
    code: str, libraries: list[ComponentLibrary], schemas: list[InteroperabilitySchema]
) -> None:
    found = checks.check(libraries, schemas)
    assert [p.code for p in found] == ([] if code == "clean" else [code])
    assert found == _walked(libraries, schemas, True)


def test_the_bundled_and_test_libraries_give_the_walks_answers() -> None:
    folders = [REPO / "libraries", REPO / "schemas"]
    folders += sorted(p for p in (REPO / "tests" / "cases" / "invalid").iterdir())
    for folder in folders:
        loaded = load_paths([folder])
        if not loaded.libraries and not loaded.schemas:
            continue
        args = (loaded.libraries, loaded.schemas)
        found = checks.check(*args, library_complete=loaded.library_complete)
        assert found == _walked(*args, loaded.library_complete), folder
