"""Property: a planned task switch makes exactly the brute-force fewest changes (issue 46).

Small random libraries (``randomlib.problems``): S1 and S2 are two schemas over one library
that share some roles (S1's may be renamed, so that components pair by abstraction), each
with its own edges; one of them may lack a role the other has. S1 runs a random valid
configuration, a component may fail, and Fast Downward with an optimal search plans the
switch. The reference tries every assignment of S2 (``randomlib.brute_force``) and counts
each one's changes by the simple rule of docs/pddl.md ("Task switches"), with a wiring
written here: the interfaces a consumer uses along its edges (these components have no
launch data, so each is served at ``/label``).
"""

from __future__ import annotations

from collections.abc import Mapping

import pytest
from conftest import examples
from hypothesis import assume, event, given, settings
from hypothesis import strategies as st
from randomlib import IFACES, brute_force, problems

from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Edge,
    InteroperabilitySchema,
    Requirement,
    Role,
    RosLaunch,
    SystemGraph,
)
from rosreconf.model.switching import count_changes, switch_changes
from rosreconf.model.validity import is_valid
from rosreconf.planning.planners import FastDownward, PlanStatus
from rosreconf.planning.switch import switch

pytestmark = pytest.mark.planner

Wires = set[tuple[str, str, str]]


def wires(
    library: ComponentLibrary, schema: InteroperabilitySchema, mapping: Mapping[str, str]
) -> dict[str, Wires]:
    """Return role -> (label, type, served name) of each interface it uses along its edges."""
    out: dict[str, Wires] = {}
    for edge in schema.graph.edges:
        c, p = mapping.get(edge.consumer, EMPTY), mapping.get(edge.provider, EMPTY)
        if EMPTY in (c, p):
            continue
        consumer, provider = library[c], library[p]
        for req in consumer.requires:
            for o in req.options:
                if o in provider.provides and edge.allows(o):
                    out.setdefault(edge.consumer, set()).add(
                        (o.label, o.type, served(provider, o.label))
                    )
    return out


def served(component: Component, label: str) -> str:
    """Return the name ``component`` serves ``label`` at: its absolute remapping, else /label."""
    launch = component.launch
    return launch.remappings.get(label, "/" + label) if launch is not None else "/" + label


@st.composite
def wired_problems(draw: st.DrawFn) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Draw a connected library: 2-4 roles, 2-3 candidates each, dense edges, no couplings.

    Some providers serve a label under a name of their own (an absolute remapping), so
    choosing another provider may rewire a kept consumer: restarts happen.
    """
    n_roles = draw(st.integers(2, 4))
    roles = tuple(
        Role(f"r{i}", f"l{i}", optional=draw(st.booleans()) and draw(st.booleans()))
        for i in range(n_roles)
    )
    edges = [
        Edge(f"r{u}", f"r{v}")
        for u in range(n_roles)
        for v in range(n_roles)
        if u != v and draw(st.booleans())
    ]
    comps = []
    for i in range(n_roles):
        for k in range(draw(st.integers(2, 3))):
            provides = frozenset(draw(st.sets(st.sampled_from(IFACES[:3]), min_size=1, max_size=2)))
            requires = tuple(
                Requirement(
                    tuple(
                        draw(
                            st.lists(
                                st.sampled_from(IFACES[:3]), min_size=1, max_size=2, unique=True
                            )
                        )
                    )
                )
                for _ in range(draw(st.integers(0, 1)))
            )
            own = {i.label: f"/c{i}_{k}/{i.label}" for i in provides if draw(st.booleans())}
            launch = RosLaunch("p", "x", remappings=own) if own else None
            comps.append(Component(f"C{i}_{k}", f"l{i}", provides, requires, launch=launch))
    library = ComponentLibrary("random", tuple(comps))
    return library, InteroperabilitySchema("s", SystemGraph(roles, tuple(edges)), "skill", "env")


def brute_count(
    library: ComponentLibrary,
    s1: InteroperabilitySchema,
    before: Mapping[str, str],
    s2: InteroperabilitySchema,
    after: Mapping[str, str],
) -> int:
    """Count a switch's changes per S2 role; roles pair by abstraction (one role each here)."""
    r1 = {r.abstraction: r.name for r in s1.graph.roles}
    w1, w2 = wires(library, s1, before), wires(library, s2, after)
    n = 0
    for role in s2.graph.roles:
        new = after.get(role.name, EMPTY)
        if role.abstraction not in r1:
            n += new != EMPTY  # nothing stood there: a start, if anything
            continue
        old = before.get(r1[role.abstraction], EMPTY)
        if new != old:
            n += 1  # a start, a stop, or a replacement (once)
        elif new != EMPTY:
            n += w1.get(r1[role.abstraction], set()) != w2.get(role.name, set())
    shared = {r.abstraction for r in s2.graph.roles}
    n += sum(1 for r in s1.graph.roles if r.abstraction not in shared and before.get(r.name))
    return n


def variant(
    schema: InteroperabilitySchema, keep: list[Role], prefix: str, edges: list[bool]
) -> InteroperabilitySchema:
    """Return a schema with the roles ``keep`` (renamed with ``prefix``) and some of the edges."""
    names = {r.name for r in keep}
    rename = {r.name: prefix + r.name[1:] for r in keep}
    chosen = [
        Edge(rename[e.consumer], rename[e.provider], optional=e.optional)
        for e, on in zip(schema.graph.edges, edges, strict=True)
        if on and e.consumer in names and e.provider in names
    ]
    roles = tuple(Role(rename[r.name], r.abstraction, optional=r.optional) for r in keep)
    return InteroperabilitySchema(prefix + "task", SystemGraph(roles, tuple(chosen)), "s", "e")


@settings(max_examples=examples(30), deadline=None)
@given(problem=st.one_of(problems(optional_roles=True), wired_problems()), data=st.data())
def test_the_planned_switch_makes_the_brute_force_fewest_changes(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, full = problem
    roles = list(full.graph.roles)
    n_edges = len(full.graph.edges)
    drop = data.draw(st.sampled_from(["none", "from-s1", "from-s2"]))
    gone = data.draw(st.integers(0, len(roles) - 1))
    without = [r for i, r in enumerate(roles) if i != gone]
    s1_prefix = data.draw(st.sampled_from(["r", "q"]))  # q: renamed, paired by abstraction
    s1 = variant(
        full,
        without if drop == "from-s1" else roles,
        s1_prefix,
        data.draw(st.lists(st.booleans(), min_size=n_edges, max_size=n_edges)),
    )
    s2 = variant(
        full,
        without if drop == "from-s2" else roles,
        "r",
        data.draw(st.lists(st.booleans(), min_size=n_edges, max_size=n_edges)),
    )
    running = brute_force(library, s1)
    assume(running)
    before = data.draw(st.sampled_from(running)).mapping
    ran = sorted(c for c in before.values() if c != EMPTY)  # a failure that matters: S1's
    failed = frozenset(data.draw(st.sets(st.sampled_from(ran), max_size=1))) if ran else frozenset()
    every = brute_force(library, s2, failed)
    answer = switch(library, s1, before, s2, failed, FastDownward("astar(lmcut())"), timeout=60)
    event(f"a running component failed: {bool(failed)}")
    event(f"switch possible: {bool(every)}")
    if not every:
        assert answer.result.status is PlanStatus.UNSOLVABLE_PROVEN
        assert answer.result.why_not and answer.count is None
        return
    fewest = min(brute_count(library, s1, before, s2, c.mapping) for c in every)
    assert answer.result.status is PlanStatus.SOLVED, answer.result.message
    config = answer.result.configuration
    assert config is not None and is_valid(config, library, s2, failed)
    assert brute_count(library, s1, before, s2, config.mapping) == fewest
    assert answer.count == answer.result.fewest_changes == fewest
    again = switch_changes(library, s1, before, s2, config.mapping, failed)
    event(f"fewest changes: {min(fewest, 3)}{'+' if fewest >= 3 else ''}")
    event(f"kinds: {', '.join(sorted({c.kind for c in again}))}")
    assert count_changes(again) == fewest
    kept = {c.component for c in again if c.kind in ("keep", "restart")}
    started = {c.component for c in again if c.kind == "start"}
    stopped = {c.component for c in again if c.kind == "stop"}
    assert kept | started == {c for c in config.mapping.values() if c != EMPTY}
    assert kept | stopped == {c for c in before.values() if c != EMPTY}
