"""Small random libraries and schemas for property tests (hypothesis strategies)."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

from hypothesis import strategies as st

from rosreconf.model import (
    EMPTY,
    Component,
    ComponentLibrary,
    Configuration,
    Edge,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    Requirement,
    Role,
    SystemGraph,
)
from rosreconf.model.validity import is_valid

IFACES = [
    Interface(InterfaceKind.TOPIC, "a", "m/A"),
    Interface(InterfaceKind.TOPIC, "b", "m/B"),
    Interface(InterfaceKind.SERVICE, "c", "m/C"),
    Interface(InterfaceKind.TOPIC, "a", "m/A2"),  # one label, two types (rule one-type-per-label)
]


@st.composite
def problems(
    draw: st.DrawFn, optional_roles: bool = False
) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    """Draw a library of up to ~9 components and a schema of 2-4 roles (some edges optional).

    With ``optional_roles`` some roles are optional too (issue 22); without, the draws are
    what they always were.
    """
    n_roles = draw(st.integers(2, 4))
    labels = [f"l{i}" for i in range(n_roles)]
    roles = tuple(
        Role(f"r{i}", labels[i], optional=optional_roles and draw(st.booleans()))
        for i in range(n_roles)
    )
    edges = []
    for u, v in itertools.permutations(range(n_roles), 2):
        if draw(st.booleans()) and draw(st.booleans()):
            edges.append(Edge(f"r{u}", f"r{v}", optional=draw(st.booleans())))
    comps: list[Component] = []
    for i in range(n_roles):
        for k in range(draw(st.integers(1, 3))):
            provides = frozenset(draw(st.sets(st.sampled_from(IFACES), max_size=2)))
            reqs = []
            for _ in range(draw(st.integers(0, 2))):
                opts = draw(st.lists(st.sampled_from(IFACES), min_size=1, max_size=2, unique=True))
                reqs.append(Requirement(tuple(opts)))
            comps.append(
                Component(
                    name=f"C{i}_{k}",
                    abstraction=labels[i],
                    provides=provides,
                    requires=tuple(reqs),
                    failure_probability=draw(st.sampled_from([0.0, 0.1, 0.3, 0.5])),
                )
            )
    names = [c.name for c in comps]
    final = []
    for c in comps:
        others = [n for n in names if n != c.name]
        needs = frozenset(draw(st.sets(st.sampled_from(others), max_size=1)))
        excludes = frozenset(draw(st.sets(st.sampled_from(others), max_size=1))) - needs
        final.append(replace(c, needs=needs, excludes=excludes))
    library = ComponentLibrary("random", tuple(final))
    schema = InteroperabilitySchema("s", SystemGraph(roles, tuple(edges)), "skill", "env")
    return library, schema


def brute_force(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: frozenset[str] = frozenset()
) -> list[Configuration]:
    """Return every valid configuration by trying every label-respecting assignment.

    An optional role is also tried empty, after its candidates (the solvers' order).
    """
    roles = schema.graph.roles
    doms = [
        [c.name for c in library.candidates(r.abstraction)] + ([EMPTY] if r.optional else [])
        for r in roles
    ]
    out = []
    for combo in itertools.product(*doms):
        config = Configuration.of(
            schema.name, dict(zip([r.name for r in roles], combo, strict=True)), roles
        )
        if is_valid(config, library, schema, failed):
            out.append(config)
    return out


def brute_force_probability(configs: list[frozenset[str]], p: dict[str, float]) -> float:
    """Return the probability that some configuration survives, over every failure state.

    The reference for the exact reliability (``analyse``): each component fails on its own
    with probability ``p``; a state is counted when one configuration has no failed part.
    """
    names = sorted(p)
    total = 0.0
    for state in itertools.product([False, True], repeat=len(names)):
        dead = {n for n, f in zip(names, state, strict=True) if f}
        weight = math.prod(p[n] if n in dead else 1 - p[n] for n in names)
        if any(not (cfg & dead) for cfg in configs):
            total += weight
    return total
