"""Compute the reconfigurability probability: exactly over listed configurations, else sampled.

Each component fails independently with its own ``failure_probability``; the probability
asked for is that at least one valid configuration has every component working. Exactly,
by factoring (Shannon expansion over the components of the configurations, memoised, with
supersets absorbed) when the configurations can be listed; else by Monte Carlo with a 95 %
Wilson interval, where witnesses and groups of interchangeable components (``Twins``) keep
solver calls few and small. The method is always named in the result.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Collection, Iterable
from dataclasses import dataclass

import numpy

from rosreconf.model import Component, ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.counting import count
from rosreconf.solve.factors import TooHard, paused_gc
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.optimum import minimise
from rosreconf.solve.solver import ClingoEngine

EXACT_CELLS = 2_000_000
"""Most (configuration, role) cells the exact analysis lists: 5,000 configurations of 400
roles, or 3 of 600,000. Past it the configurations are not listed, whatever their number,
so that their length alone cannot exhaust memory."""

MC_BLOCK = 1_000
"""Failure states drawn as one array (1,000 x 10,000 components is 10 MB)."""


@dataclass(frozen=True)
class Reliability:
    """The reconfigurability probability of a schema.

    Attributes:
        probability: P(at least one valid configuration has every component working).
        method: ``exact (factoring over N configurations)`` or ``Monte Carlo (N samples)``.
        low: lower end of the 95 % interval (equal to ``probability`` when exact).
        high: upper end of the 95 % interval.
        assumed_reliable: components without a failure probability (taken as never failing).
    """

    probability: float
    method: str
    low: float
    high: float
    assumed_reliable: tuple[str, ...] = ()


State = frozenset[frozenset[str]]
"""A set of configurations, each the set of its components' names."""


def _absorb(configs: Iterable[frozenset[str]]) -> frozenset[frozenset[str]]:
    """Drop configurations that are supersets of others (they never add to survival)."""
    ordered = sorted(set(configs), key=len)
    kept: list[frozenset[str]] = []
    for c in ordered:
        if not any(k <= c for k in kept):
            kept.append(c)
    return frozenset(kept)


def exact_probability(configs: Iterable[frozenset[str]], p: dict[str, float]) -> float:
    """Return P(some configuration has all its components working), exactly.

    Shannon expansion on the most frequent component: P = p_x * P(x failed) +
    (1 - p_x) * P(x works), where "x failed" drops every configuration using x and "x works"
    removes x from them; memoised on the (absorbed) set of configurations. A single
    configuration is the product of its components' chances. The expansion runs on an
    explicit stack: it is as deep as a configuration is long, and a chain of 500 roles
    overflowed Python's recursion limit.

    The configurations are first reduced by ``_merge_alike``: without it the memo held one
    state per component of a long configuration, each as long as the configuration, and a
    hub of 3 candidates with 10,000 consumers ran out of 6 GB.
    """
    memo: dict[State, float] = {}
    splits: dict[State, tuple[str, State, State]] = {}
    merged, p = _merge_alike(configs, p)
    root = _absorb(merged)
    stack = [root]
    while stack:
        state = stack[-1]
        if state in memo:
            stack.pop()
            continue
        leaf = _leaf(state, p)
        if leaf is not None:
            memo[state] = leaf
            stack.pop()
            continue
        if state not in splits:
            splits[state] = _split(state)
        x, if_failed, if_works = splits[state]
        todo = [s for s in (if_failed, if_works) if s not in memo]
        if todo:
            stack.extend(todo)
            continue
        memo[state] = p[x] * memo[if_failed] + (1 - p[x]) * memo[if_works]
        del splits[state]
        stack.pop()
    return memo[root]


def _merge_alike(
    configs: Iterable[frozenset[str]], p: dict[str, float]
) -> tuple[list[frozenset[str]], dict[str, float]]:
    """Return the configurations with alike components merged, and the merged probabilities.

    A component that never fails (p = 0) cannot decide whether a configuration survives, so
    it is dropped. Components in exactly the same configurations are always all needed
    together, and fail independently: they act as one component that works when all of them
    work. Each such class becomes its first member's name, failing with 1 - prod(1 - p). The
    answer is unchanged, and a configuration is left with at most as many parts as there are
    distinct sets of configurations its parts belong to: its length (a long chain of
    single-candidate roles) no longer matters. Linear in the total size of the input.
    """
    listed = list(dict.fromkeys(configs))
    where: dict[str, list[int]] = {}
    for i, cfg in enumerate(listed):
        for c in cfg:
            if p[c] > 0:
                where.setdefault(c, []).append(i)
    classes: dict[tuple[int, ...], list[str]] = {}
    for c in sorted(where):
        classes.setdefault(tuple(where.pop(c)), []).append(c)
    parts: list[list[str]] = [[] for _ in listed]
    q: dict[str, float] = {}
    for found_in, members in classes.items():
        q[members[0]] = 1 - math.prod(1 - p[c] for c in members)
        for i in found_in:
            parts[i].append(members[0])
    return [frozenset(part) for part in parts], q


def _leaf(state: State, p: dict[str, float]) -> float | None:
    """Return the probability of a state that needs no expansion, else None."""
    if not state:
        return 0.0
    if frozenset() in state:
        return 1.0
    if len(state) == 1:
        return math.prod(1 - p[c] for c in next(iter(state)))
    return None


def _split(
    state: State,
) -> tuple[str, State, State]:
    """Return the most frequent component and the states where it failed and where it works."""
    freq: dict[str, int] = {}
    for cfg in state:
        for c in cfg:
            freq[c] = freq.get(c, 0) + 1
    x = max(sorted(freq), key=lambda c: freq[c])
    return (
        x,
        _absorb(cfg for cfg in state if x not in cfg),
        _absorb(cfg - {x} for cfg in state),
    )


def monte_carlo(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    dead: frozenset[str],
    p: dict[str, float],
    samples: int,
    seed: int,
    assumed: tuple[str, ...],
    *,
    relevant: Collection[str] | None = None,
) -> Reliability:
    """Estimate the probability by sampling failure states (seeded, so reproducible).

    Only ``relevant`` components (those in some configuration) with a failure probability
    above 0 are drawn: no other failure changes the answer. States are drawn in blocks as
    one array; a state that misses every part of a known surviving configuration (a
    witness) survives with it, decided for the whole block at once. Only the rest go to the
    solver, which returns the most reliable configuration that survives them, so that one
    witness covers as many later states as it can.
    """
    twins = Twins(library, schema)
    names = sorted(n for n in (p if relevant is None else relevant) if p[n] > 0 and n not in dead)
    index = {n: i for i, n in enumerate(names)}
    probs = numpy.array([p[n] for n in names], dtype=float)
    rng = numpy.random.default_rng(seed)
    witnesses: list[numpy.ndarray] = []
    seen: dict[bytes, bool] = {}
    hits = 0
    for start in range(0, samples, MC_BLOCK):
        failed = rng.random((min(MC_BLOCK, samples - start), len(names))) < probs
        alive = numpy.zeros(len(failed), dtype=bool)
        for w in witnesses:
            alive |= ~failed[:, w].any(axis=1)
        for row in numpy.flatnonzero(~alive):
            if alive[row]:  # covered by a witness found for an earlier row of this block
                continue
            key = numpy.packbits(failed[row]).tobytes()
            if key not in seen:
                state = dead | {names[i] for i in numpy.flatnonzero(failed[row])}
                found = most_reliable(twins.survivors(state, p), schema, state, p)
                seen[key] = found is not None
                if found is not None:
                    w = numpy.array([index[c] for c in found if c in index], dtype=numpy.intp)
                    witnesses.append(w)
                    alive |= ~failed[:, w].any(axis=1)
            alive[row] = seen[key]
        hits += int(alive.sum())
    est = hits / samples
    low, high = wilson(hits, samples)
    return Reliability(est, f"Monte Carlo ({samples} samples, seed {seed})", low, high, assumed)


class Twins:
    """Group components that validity cannot tell apart, to solve over one of each.

    Validity reads a component's label, provisions, requirements, needs, excludes and
    schemas, never its name, unless another component names it in ``needs`` or
    ``excludes``. Components alike in all of these can swap places in any configuration,
    so a failure state leaves a configuration exactly when it leaves one over the library
    cut down to the most reliable working members of each group (as many as the schema has
    roles with their label, since one component fills one role): 10,000 candidates for a
    role are a handful of groups, and the solver sees only those.
    """

    def __init__(self, library: ComponentLibrary, schema: InteroperabilitySchema) -> None:
        named = {n for c in library for n in c.needs | c.excludes}
        self.library = library
        self.room = Counter(r.abstraction for r in schema.graph.roles)
        groups: dict[object, list[Component]] = {}
        for c in library:
            key: object = c.name if c.name in named else _behaviour(c)
            groups.setdefault(key, []).append(c)
        self.groups = list(groups.values())

    def survivors(self, failed: frozenset[str], p: dict[str, float]) -> ComponentLibrary:
        """Return the library cut to the most reliable working members of every group."""
        keep: set[str] = set()
        for members in self.groups:
            working = [c.name for c in members if c.name not in failed]
            working.sort(key=lambda n: p[n])  # stable: library order among equals
            keep.update(working[: max(1, self.room[members[0].abstraction])])
        kept = tuple(c for c in self.library if c.name in keep)
        return ComponentLibrary(self.library.name, kept)

    def grouped(
        self, failed: frozenset[str], p: dict[str, float]
    ) -> tuple[ComponentLibrary, dict[str, float]]:
        """Return one component per group, failing only when all its working members do.

        Independent failures make "some member works" a single event of probability
        1 - prod(p); a group whose label has more than one role in the schema keeps its
        members (two of them may be needed at once).
        """
        keep: list[Component] = []
        q: dict[str, float] = {}
        for members in self.groups:
            working = [c for c in members if c.name not in failed]
            if not working:
                continue
            if self.room[members[0].abstraction] > 1:
                keep.extend(working)
                q.update((c.name, p[c.name]) for c in working)
                continue
            keep.append(working[0])
            q[working[0].name] = math.prod(p[c.name] for c in working)
        order = {c.name: i for i, c in enumerate(self.library)}
        keep.sort(key=lambda c: order[c.name])
        return ComponentLibrary(self.library.name, tuple(keep)), q


def grouped_exact(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    dead: frozenset[str],
    p: dict[str, float],
    limit: int,
) -> tuple[float, int, int] | None:
    """Return the exact probability over groups of interchangeable components, if few enough.

    With one component per group (``Twins.grouped``) the configurations are those of the
    groups; when at most ``limit`` of them remain, factoring over them is exact. Returns the
    probability, the number of group configurations and of groups; None when there are
    more than ``limit``, more than ``EXACT_CELLS`` cells to list, or the system graph is
    too dense to count them.
    """
    small, q = Twins(library, schema).grouped(dead, p)
    with paused_gc():
        inst = compile_instance(small, schema, dead)
    try:
        n = count(inst)
        if n > limit or n * len(inst.roles) > EXACT_CELLS:
            return None
    except TooHard:
        return None
    configs = [frozenset(c.components) for c in ClingoEngine().configurations(inst)]
    return exact_probability(configs, q), len(configs), len(small)


def _behaviour(c: Component) -> tuple[object, ...]:
    """Return everything validity reads from a component, except its name."""
    return (c.abstraction, c.provides, c.requires, c.needs, c.excludes, c.schemas)


def most_reliable(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: frozenset[str],
    p: dict[str, float],
) -> frozenset[str] | None:
    """Return the components of the configuration most likely to keep working, or None.

    Each candidate costs -log(1 - p) (scaled to integers), so the least total cost is the
    greatest probability that all parts work: min-plus elimination over counting's tables,
    clingo's first configuration when the tables would be too large.
    """
    with paused_gc():
        inst = compile_instance(library, schema, failed)
    # an optional role's empty choice is not in p: it never fails
    costs = [{c.name: (_log_cost(p.get(c.name, 0.0)),) for c in dom} for dom in inst.domains]
    try:
        found = minimise(inst, costs)
        config = found[0] if found is not None else None
    except TooHard:
        config = ClingoEngine().first(inst)
    return None if config is None else frozenset(config.components)


def _log_cost(p: float) -> int:
    """Return -log(1 - p) in millionths (a certain failure costs more than any sum of others)."""
    return 10**12 if p >= 1 else round(-math.log1p(-p) * 1e6)


def wilson(hits: int, n: int, z: float = 1.959964) -> tuple[float, float]:
    """Return the 95 % Wilson score interval of a binomial proportion."""
    if n == 0:
        return 0.0, 1.0
    phat = hits / n
    denom = 1 + z * z / n
    centre = (phat + z * z / (2 * n)) / denom
    half = z * math.sqrt(phat * (1 - phat) / n + z * z / (4 * n * n)) / denom
    return max(0.0, centre - half), min(1.0, centre + half)
