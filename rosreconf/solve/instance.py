"""Compile one schema over the library into the static facts every solver works on.

Which components can fill which role, which candidate pairs realise which edge, and which
providers meet which requirement are all decided here, once, in Python; the solvers (clingo,
the counter, the PDDL renderer) only see the resulting tables. Computing these joins ahead
is what keeps grounding linear (docs/pddl.md, "The encoding": lifted joins explode).

It also explains emptiness: ``explain`` prunes candidates by local reasoning and turns the
first role left without candidates into a plain-language reason.
"""

from __future__ import annotations

import functools
from collections.abc import Collection
from dataclasses import dataclass, field

from rosreconf.model import (
    Component,
    ComponentLibrary,
    Edge,
    Interface,
    InteroperabilitySchema,
    Role,
)
from rosreconf.solve.emptyroles import with_empty_choices


@dataclass
class Instance:
    """The finite-domain problem of one schema.

    Attributes:
        schema: the interoperability schema.
        library: the component library L, with each optional role's empty choice appended
            (a component that provides and requires nothing), so every solver looks it up
            like any other candidate.
        failed: names of components that are unavailable.
        roles: the schema's roles, in order (variable i is roles[i]).
        domains: per role, the candidate components (available, label and schema match),
            in library order; an optional role's empty choice (``empty_choice``) last.
        excluded: per role, candidate name -> why it was ruled out before solving.
        edges: the (consumer, provider) role indices of the schema's *required* edges, the
            ones every configuration must realise; optional edges are left out (rule
            ``optional-edge`` of ``rosreconf.model.validity.RULES``) and only feed ``meets``.
        meets: per (role index, candidate, requirement index), the (provider role index,
            provider candidate) pairs meeting that requirement along the role's edges
            (required and optional); candidates of one role with the same requirement share
            one list (read it, never change it).
        clashes: candidate -> the candidates providing one of its labels with another type
            (symmetric; rule ``one-type-per-label``: never chosen together).
        partners: per required edge index, consumer candidate -> the provider candidates
            it may be paired with, the pairs of which make ``edge_ok`` (candidates with none
            are absent; candidates with the same requirements share one set: read it, never
            change it).
        interfaces: candidate -> (the numbers of the interfaces it provides, per requirement
            the numbers of its options): equal numbers are equal interfaces, so comparing
            these compares what the candidates provide and require.
    """

    schema: InteroperabilitySchema
    library: ComponentLibrary
    failed: frozenset[str]
    roles: tuple[Role, ...]
    domains: list[list[Component]]
    excluded: list[dict[str, str]]
    edges: list[tuple[int, int]] = field(default_factory=list)
    meets: dict[tuple[int, str, int], list[tuple[int, str]]] = field(default_factory=dict)
    clashes: dict[str, set[str]] = field(default_factory=dict)
    partners: list[dict[str, set[str]]] = field(default_factory=list)
    interfaces: dict[str, tuple[frozenset[int], tuple[tuple[int, ...], ...]]] = field(
        default_factory=dict
    )

    @functools.cached_property
    def edge_ok(self) -> list[set[tuple[str, str]]]:
        """Return per required edge index, the allowed (consumer, provider) candidate pairs.

        Made from ``partners`` when first asked: clingo's facts, the PDDL and the library
        analysis read pairs; elimination and pruning read ``partners`` and ``users`` and never
        pay for a set of every pair (read it, never change it).
        """
        return [
            {(cu, cv) for cu, mates in partners.items() for cv in mates}
            for partners in self.partners
        ]

    @functools.cached_property
    def users(self) -> list[dict[str, set[str]]]:
        """Return per required edge index, provider candidate -> the consumers that may use it.

        ``partners`` by provider, made when first asked (the library analysis reads it);
        pruning asks instead whether a provider is among the surviving consumers' partners,
        and never pays for it.
        """
        out: list[dict[str, set[str]]] = []
        for partners in self.partners:
            by_provider: dict[str, set[str]] = {}
            for cu, mates in partners.items():
                for cv in mates:
                    by_provider.setdefault(cv, set()).add(cu)
            out.append(by_provider)
        return out

    @property
    def role_index(self) -> dict[str, int]:
        """Return role name -> variable index."""
        return {r.name: i for i, r in enumerate(self.roles)}


def compile_instance(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: Collection[str] = ()
) -> Instance:
    """Compute candidates, edge tables and requirement tables of ``schema`` over ``library``.

    Interfaces are numbered once and every join is a set intersection over those numbers,
    so compiling stays linear in the size of the tables (1000 roles x 10 candidates in a
    fraction of a second); the tables are exactly what ``validity.edge_interfaces`` and
    ``validity.requirement_met`` decide.
    """
    dead = frozenset(failed)
    roles = schema.graph.roles
    index = {r.name: i for i, r in enumerate(roles)}
    by_label: dict[str, list[Component]] = {}
    for c in library.components:
        by_label.setdefault(c.abstraction, []).append(c)
    domains: list[list[Component]] = []
    excluded: list[dict[str, str]] = []
    for role in roles:
        dom, why = [], {}
        for c in by_label.get(role.abstraction, ()):
            if c.name in dead:
                why[c.name] = f"{c.name} has failed"
            elif not c.may_serve_in(schema.name):
                why[c.name] = f"{c.name} may only serve in {', '.join(sorted(c.schemas))}"
            else:
                dom.append(c)
        domains.append(dom)
        excluded.append(why)
    library = with_empty_choices(library, roles, domains)  # rule optional-role
    inst = Instance(schema, library, dead, roles, domains, excluded)
    ids: dict[Interface, int] = {}
    provides: dict[str, frozenset[int]] = {}
    options: dict[str, tuple[tuple[int, ...], ...]] = {}
    for dom in domains:
        for c in dom:
            if c.name not in provides:
                provides[c.name] = frozenset(ids.setdefault(i, len(ids)) for i in c.provides)
                options[c.name] = tuple(
                    tuple(ids.setdefault(o, len(ids)) for o in r.options) for r in c.requires
                )
                inst.interfaces[c.name] = (provides[c.name], options[c.name])
    _clashes(inst)
    labels = {i: iface.label for iface, i in ids.items()}
    out_edges: dict[int, list[tuple[Edge, int]]] = {}
    # wanted options over an edge allowing every interface: once per requirement list
    wanted_all: dict[tuple[tuple[int, ...], ...], frozenset[int]] = {}
    for e in schema.graph.edges:
        u, v = index[e.consumer], index[e.provider]
        out_edges.setdefault(u, []).append((e, v))
        if e.optional:
            continue  # requirements may be met across it (meets, below); it need not be realised
        inst.edges.append((u, v))
        partners: dict[str, set[str]] = {}
        offered = [(cv.name, provides[cv.name]) for cv in domains[v]]
        # rule optional-role: an edge touching an empty role is realised whatever the other
        # end holds (its requirements are still met elsewhere: ``meets``)
        empty_v = {domains[v][-1].name} if roles[v].optional else set()
        # the mates depend only on the consumer's requirements: candidates with the same
        # ones share one (read-only) set
        by_opts: dict[tuple[tuple[int, ...], ...], set[str]] = {}
        for cu in domains[u]:
            if roles[u].optional and cu is domains[u][-1]:
                partners[cu.name] = {cv.name for cv in domains[v]}
                continue
            reqs = options[cu.name]
            mates = by_opts.get(reqs)
            if mates is None:
                wanted: frozenset[int] | set[int]
                if e.interfaces:
                    wanted = {o for group in reqs for o in group if _allows(e, labels[o])}
                else:
                    if reqs not in wanted_all:
                        wanted_all[reqs] = frozenset(o for g in reqs for o in g)
                    wanted = wanted_all[reqs]
                mates = by_opts[reqs] = empty_v | (
                    {name for name, p in offered if not p.isdisjoint(wanted)} if wanted else set()
                )
            if mates:
                partners[cu.name] = mates
        inst.partners.append(partners)
    for u in range(len(roles)):
        mine = out_edges.get(u, [])
        # the edges to a role offering each interface (a fan-in scanned all, per requirement)
        offering: dict[int, set[int]] = {}
        for j, (_, v) in enumerate(mine):
            for o in {o for cv in domains[v] for o in provides[cv.name]}:
                offering.setdefault(o, set()).add(j)
        # the pairs depend only on the requirement's options: a role's candidates share a
        # few requirements, and one (read-only) list is made for each
        made: dict[tuple[int, ...], list[tuple[int, str]]] = {}
        for cu in domains[u]:
            for i, opts in enumerate(options[cu.name]):
                pairs = made.get(opts)
                if pairs is None:
                    pairs = made[opts] = []
                    near = sorted(set().union(*(offering.get(o, ()) for o in opts)))
                    for e, v in (mine[j] for j in near):
                        allowed = {o for o in opts if _allows(e, labels[o])}
                        pairs.extend(
                            (v, cv.name)
                            for cv in domains[v]
                            if not provides[cv.name].isdisjoint(allowed)
                        )
                inst.meets[(u, cu.name, i)] = pairs
    return inst


def _clashes(inst: Instance) -> None:
    """Fill ``inst.clashes``: candidates providing one label with different types."""
    typed: dict[tuple[str, str], dict[str, set[str]]] = {}
    for dom in inst.domains:
        for c in dom:
            for i in c.provides:
                typed.setdefault((i.kind, i.label), {}).setdefault(i.type, set()).add(c.name)
    for by_type in typed.values():
        if len(by_type) < 2:
            continue
        for t, names in by_type.items():
            others = {n for t2, ns in by_type.items() if t2 != t for n in ns}
            for n in names:
                inst.clashes.setdefault(n, set()).update(others - {n})


def _allows(edge: Edge, label: str) -> bool:
    return not edge.interfaces or label in edge.interfaces


def prune(inst: Instance) -> tuple[list[list[str]], list[dict[str, str]], list[int]]:
    """Remove candidates that cannot be in any configuration by local reasoning.

    Returns the surviving candidate names per role, per role candidate -> reason, and the
    roles in the order they lost their last candidate (the first is nearest the cause).
    Local reasoning: a requirement with no surviving provider, an edge with no surviving
    partner, a needed component that cannot be chosen. It is sound (never removes a
    candidate of a valid configuration) but not complete.
    """
    alive = [[c.name for c in dom] for dom in inst.domains]
    why: list[dict[str, str]] = [dict(x) for x in inst.excluded]
    emptied = [u for u, a in enumerate(alive) if not a]
    support = _Support(inst)
    changed = True
    while changed:
        changed = False
        alive_sets = [set(a) for a in alive]
        anywhere = set().union(*alive_sets) if alive_sets else set()
        support.met.clear()  # what a shared list or set says holds for one pass only
        support.provided.clear()
        for u in range(len(inst.roles)):
            kept = []
            for name in alive[u]:
                reason = _dead_reason(inst, support, u, name, alive_sets, anywhere)
                if reason:
                    why[u][name] = reason
                    changed = True
                else:
                    kept.append(name)
            if len(kept) != len(alive[u]):  # rebuilt, not list.remove: K removals cost K^2
                alive[u] = kept
                if not kept:
                    emptied.append(u)
    return alive, why, emptied


def interchangeable(inst: Instance, alive: list[list[str]]) -> list[list[list[str]]]:
    """Group each role's candidates into classes that no rule of validity tells apart.

    Two candidates of one role that provide the same interfaces and have the same
    requirements sit in exactly the same rows of every table of edges realised and
    requirements met (those see only interfaces); the other rules name components
    (needs, excludes, one type per label, one role each), so a candidate that names
    another, is named, clashes or could fill two roles stays alone. A solver may then keep
    one candidate per class: counting weighs it by its class's size, minimising keeps the
    member it prefers. A generated library of 1000 roles x 10 candidates has about 6 classes
    per role, and each elimination step's table is cubic in that. Classes and their members
    keep ``alive``'s order.
    """
    lib = inst.library.by_name
    roles_of: dict[str, int] = {}
    named: set[str] = set(inst.clashes)
    # an empty choice is never interchangeable with a component that provides and requires
    # nothing: it realises every edge, that component none
    roles_domains = zip(inst.roles, inst.domains, strict=True)
    named.update(dom[-1].name for r, dom in roles_domains if r.optional)
    for names in alive:
        for n in names:
            roles_of[n] = roles_of.get(n, 0) + 1
            c = lib[n]
            if c.needs or c.excludes:
                named.update(c.needs, c.excludes)
                named.add(n)
    out: list[list[list[str]]] = []
    for names in alive:
        by_key: dict[object, list[str]] = {}
        for n in names:
            # compile_instance's interface numbers stand for the interfaces themselves
            key = n if n in named or roles_of[n] > 1 else inst.interfaces[n]
            by_key.setdefault(key, []).append(n)
        out.append(list(by_key.values()))
    return out


class _Support:
    """Index the edge tables by role and by candidate, so pruning never scans every edge.

    The candidate index is ``compile_instance``'s own (``partners``), made while the tables
    were joined; only the edges touching each role are listed here.
    """

    def __init__(self, inst: Instance) -> None:
        self.incident: list[list[int]] = [[] for _ in inst.roles]
        for k, (eu, ev) in enumerate(inst.edges):
            self.incident[eu].append(k)
            if ev != eu:
                self.incident[ev].append(k)
        self.partners = inst.partners
        self.provided: dict[int, set[str]] = {}
        """per required edge index, the providers some surviving consumer may use, this pass."""
        self.met: dict[int, bool] = {}
        """id of a ``meets`` list or ``partners`` set -> whether a survivor is in it, this
        pass (candidates with the same requirements share them: each is read once)."""

    def provided_along(self, k: int, consumers: set[str]) -> set[str]:
        """Return the providers of edge k that one of ``consumers`` may use (once a pass)."""
        found = self.provided.get(k)
        if found is None:
            partners = self.partners[k]
            sets = {id(m): m for cu in consumers if (m := partners.get(cu)) is not None}
            found = self.provided[k] = set().union(*sets.values())
        return found


def _dead_reason(
    inst: Instance,
    support: _Support,
    u: int,
    name: str,
    alive: list[set[str]],
    anywhere: set[str],
) -> str:
    c = inst.library[name]
    met = support.met
    for i, req in enumerate(c.requires):
        pairs = inst.meets[(u, name, i)]
        ok = met.get(id(pairs))
        if ok is None:
            ok = met[id(pairs)] = any(cv in alive[v] for v, cv in pairs)
        if not ok:
            return f"{name} requires {req}, and no surviving provider along its edges offers it"
    for k in support.incident[u]:
        eu, ev = inst.edges[k]
        if eu == u:
            mates = support.partners[k].get(name)
            if mates is None:
                ok = False
            else:
                ok = met.get(id(mates))
                if ok is None:
                    ok = met[id(mates)] = not alive[ev].isdisjoint(mates)
            if not ok:
                provider = inst.roles[ev]
                return (
                    f"{name} uses nothing the surviving {provider.abstraction} candidates "
                    f"({', '.join(sorted(alive[ev])) or 'none'}) provide"
                )
        if ev == u and name not in support.provided_along(k, alive[eu]):
            consumer = inst.roles[eu]
            return (
                f"no surviving {consumer.abstraction} candidate "
                f"({', '.join(sorted(alive[eu])) or 'none'}) uses what {name} provides"
            )
    for need in sorted(c.needs):
        if need not in anywhere:
            return f"{name} needs {need}, which cannot be chosen"
    return ""
