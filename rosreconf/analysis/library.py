"""Answer the paper's Section 4 questions about a library L and a schema.

* Orthogonality (Def. 8): does every label-respecting substitution give a valid
  configuration? If not, how many do, and which pairs of components cannot work together.
* Redundancy per role (the paper's r = card(nu^-1(a))), single points of failure, and
  failure pairs that kill a schema although neither failure alone does.
* Reconfigurability probability: the probability that at least one valid configuration has
  every component working, each component failing independently with its own
  ``failure_probability``. Computed exactly by factoring (Shannon expansion over the
  components of the valid configurations, with memoisation and absorption of supersets)
  when the configurations can be listed, else estimated by Monte Carlo with a 95 % Wilson
  interval; the method is always named in the result.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Collection
from dataclasses import dataclass, field

from rosreconf.analysis.marginals import marginals
from rosreconf.analysis.reliability import (
    EXACT_CELLS,
    Reliability,
    exact_probability,
    grouped_exact,
    monte_carlo,
)
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.counting import count
from rosreconf.solve.emptyroles import empty_choice, is_empty_choice
from rosreconf.solve.factors import paused_gc
from rosreconf.solve.instance import Instance, compile_instance
from rosreconf.solve.solver import ClingoEngine

EXACT_LIMIT = 5_000
"""Most configurations the exact probability (and usable-candidate) analysis lists; fewer
when they are long (``EXACT_CELLS``)."""

PAIR_LIMIT = 80
"""Most relevant components for which every failure pair is checked (whatif scales further)."""


@dataclass(frozen=True)
class IncompatiblePair:
    """Two components that can never be in one configuration, and why."""

    first: str
    second: str
    reason: str


@dataclass(frozen=True)
class Unusable:
    """A candidate that no configuration can hold at all, and why (a counterexample of one)."""

    component: str
    reason: str


@dataclass(frozen=True)
class RoleRedundancy:
    """How many components can play a role.

    Attributes:
        role: the role's name.
        abstraction: its label.
        candidates: available components with the label that may serve in the schema (r).
        usable: the candidates that appear in at least one valid configuration (None when
            there were too many configurations to list).
        may_stay_empty: the role is optional and some valid configuration leaves it empty
            (its empty choice is no candidate and no single point of failure).
    """

    role: str
    abstraction: str
    candidates: tuple[str, ...]
    usable: tuple[str, ...] | None
    may_stay_empty: bool = False


@dataclass
class SchemaAnalysis:
    """Everything ``rosreconf analyse`` says about one schema."""

    schema: str
    title: str
    substitutions: int
    valid: int
    orthogonal: bool
    incompatible: list[IncompatiblePair] = field(default_factory=list)
    unusable: list[Unusable] = field(default_factory=list)
    counterexamples_complete: bool = True
    redundancy: list[RoleRedundancy] = field(default_factory=list)
    single_points_of_failure: list[str] = field(default_factory=list)
    critical_pairs: list[tuple[str, str]] | None = None
    reliability: Reliability | None = None


def analyse(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str] = (),
    *,
    samples: int = 20_000,
    seed: int = 0,
) -> SchemaAnalysis:
    """Analyse ``schema`` over ``library`` with ``failed`` components already gone.

    Usable candidates and single points of failure come from counting's marginals (one
    two-pass elimination, ``rosreconf.analysis.marginals``), not one count per component, so
    they scale with the library as counting does.
    """
    with paused_gc():  # compiling allocates many small tuples; collections would find none
        inst = compile_instance(library, schema, failed)
    substitutions = _substitutions(inst)
    marg = marginals(inst)
    valid = marg.total
    result = SchemaAnalysis(
        schema=schema.name,
        title=schema.display_name,
        substitutions=substitutions,
        valid=valid,
        orthogonal=valid == substitutions and valid > 0,
        incompatible=incompatible_pairs(inst),
    )
    unusable, extra, complete = requirement_counterexamples(inst)
    if extra:
        known = {(p.first, p.second) for p in result.incompatible}
        result.incompatible = sorted(
            [*result.incompatible, *(p for p in extra if (p.first, p.second) not in known)],
            key=lambda p: (p.first, p.second),
        )
    result.unusable = unusable
    result.counterexamples_complete = complete
    for u, role in enumerate(inst.roles):
        names = tuple(c.name for c in inst.domains[u])
        candidates = tuple(c for c in names if not is_empty_choice(c))  # rule optional-role
        usable = tuple(c for c in candidates if marg.per_role[u].get(c, 0))
        empty = role.optional and bool(marg.per_role[u].get(empty_choice(role.name), 0))
        result.redundancy.append(
            RoleRedundancy(role.name, role.abstraction, candidates, usable, empty)
        )
    if valid == 0:
        return result
    listable = valid <= EXACT_LIMIT and valid * len(inst.roles) <= EXACT_CELLS
    listed = list(ClingoEngine().configurations(inst, EXACT_LIMIT)) if listable else []
    configs = [frozenset(c.components) for c in listed]
    dead = frozenset(failed)

    def kills(failures: frozenset[str]) -> bool:
        # With every configuration listed, a failure set kills the schema exactly when it hits
        # all of them; otherwise ask the counter.
        if configs:
            return all(cfg & failures for cfg in configs)
        return count(compile_instance(library, schema, dead | failures)) == 0

    relevant = sorted(marg.usable())
    # In every configuration: its marginal count is the total (a component fills one role).
    result.single_points_of_failure = marg.in_every()
    survivors = [c for c in relevant if c not in result.single_points_of_failure]
    if len(survivors) <= PAIR_LIMIT:
        result.critical_pairs = [
            (a, b) for a, b in itertools.combinations(survivors, 2) if kills(frozenset({a, b}))
        ]
    p = {c.name: c.failure_probability or 0.0 for c in library}
    assumed = tuple(sorted(c for c in relevant if library[c].failure_probability is None))
    if configs:
        exact = exact_probability(configs, p)
        result.reliability = Reliability(
            exact, f"exact (factoring over {len(configs)} configurations)", exact, exact, assumed
        )
    elif grouped := grouped_exact(library, schema, dead, p, EXACT_LIMIT):
        exact, n, groups = grouped
        method = (
            f"exact (factoring over {n} configurations of {groups} groups of "
            "interchangeable components)"
        )
        result.reliability = Reliability(exact, method, exact, exact, assumed)
    else:
        result.reliability = monte_carlo(
            library, schema, dead, p, samples, seed, assumed, relevant=relevant
        )
    return result


def _substitutions(inst: Instance) -> int:
    """Count label-respecting substitutions (distinct components, schema limits kept)."""
    roles_of: dict[str, list[int]] = {}
    for u, dom in enumerate(inst.domains):
        for c in dom:
            roles_of.setdefault(c.name, []).append(u)
    if all(len(v) == 1 for v in roles_of.values()):
        return math.prod(len(d) for d in inst.domains)
    names = [[c.name for c in d] for d in inst.domains]
    return sum(1 for combo in itertools.product(*names) if len(set(combo)) == len(combo))


def incompatible_pairs(inst: Instance) -> list[IncompatiblePair]:
    """List pairs of candidates that no configuration can hold together, with the reason."""
    out: dict[tuple[str, str], str] = {}
    for (u, v), ok in zip(inst.edges, inst.edge_ok, strict=True):
        # Name only what the consumer could want from this provider's role.
        offered = {i.label for c in inst.domains[v] for i in c.provides}
        for cu in inst.domains[u]:
            wanted: list[str] | None = None  # made only when some pair is refused
            for cv in inst.domains[v]:
                if (cu.name, cv.name) in ok:
                    continue
                if wanted is None:
                    wanted = [
                        " or ".join(o.label for o in r.options)
                        for r in cu.requires
                        if any(o.label in offered for o in r.options)
                    ]
                needs = ", ".join(wanted) or "nothing " + inst.roles[v].name + " offers"
                has = ", ".join(sorted(i.label for i in cv.provides)) or "nothing"
                out.setdefault(
                    _key(cu.name, cv.name),
                    f"{cu.name} requires {needs}; {cv.name} provides {has}",
                )
    holders = {c.name: u for u, dom in enumerate(inst.domains) for c in dom}
    for u, dom in enumerate(inst.domains):
        for c in dom:
            for need in sorted(c.needs):
                w = holders.get(need)
                if w is None or w == u:
                    continue
                role = inst.roles[w].name
                for other in inst.domains[w]:
                    if other.name != need:
                        took = "would leave" if is_empty_choice(other.name) else "would take"
                        out.setdefault(
                            _key(c.name, other.name),
                            f"{c.name} needs {need}; {other.name} {took} role {role}",
                        )
            for ex in sorted(c.excludes):
                if ex in holders:
                    out.setdefault(_key(c.name, ex), f"{c.name} excludes {ex}")
            for clashing in sorted(inst.clashes.get(c.name, ())):
                out.setdefault(
                    _key(c.name, clashing),
                    f"{c.name} and {clashing} provide one label with two message types",
                )
    return [IncompatiblePair(a, b, why) for (a, b), why in sorted(out.items())]


def requirement_counterexamples(
    inst: Instance,
) -> tuple[list[Unusable], list[IncompatiblePair], bool]:
    """Return the counterexamples that unmet requirements give, and whether all are listed.

    ``incompatible_pairs`` covers the edge, needs and excludes rules, each a pair. A
    requirement left unmet is a pair only when every candidate that could meet it sits in one
    role: then each other candidate of that role is incompatible with the consumer. When no
    candidate can meet it, the consumer alone is a counterexample (``Unusable``). When the
    candidates that meet it sit in two or more roles, a failing substitution needs all of
    them to miss: a counterexample of three or more components, which no pair list shows,
    so the third value is false and the list must be called a sample.
    """
    unusable: dict[str, str] = {}
    pairs: dict[tuple[str, str], str] = {}
    complete = True
    holders = {c.name: u for u, dom in enumerate(inst.domains) for c in dom}
    for u, dom in enumerate(inst.domains):
        for c in dom:
            for need in sorted(c.needs):
                if holders.get(need, u) == u:  # nowhere to be, or only in c's own role
                    unusable.setdefault(
                        c.name, f"{c.name} needs {need}, which can fill no other role"
                    )
    for (_u, name, i), meeting in sorted(inst.meets.items()):
        if name in unusable:
            continue
        component = inst.library[name]  # by name: a scan of the role was K^2 in all
        wanted = " or ".join(o.label for o in component.requires[i].options)
        roles = {v for v, _ in meeting}
        if not roles:
            unusable[name] = (
                f"{name} requires {wanted}, which no candidate of a connected role provides"
            )
        elif len(roles) == 1:
            (v,) = roles
            good = {cv for _, cv in meeting}
            for cv in inst.domains[v]:
                if cv.name not in good:
                    pairs.setdefault(
                        _key(name, cv.name),
                        f"{name} requires {wanted}; {cv.name} does not provide it",
                    )
        else:
            complete = False
    return (
        [Unusable(c, why) for c, why in sorted(unusable.items())],
        [IncompatiblePair(a, b, why) for (a, b), why in sorted(pairs.items())],
        complete,
    )


def _key(a: str, b: str) -> tuple[str, str]:
    return (a, b) if a <= b else (b, a)
