"""Find configurations: enumerate, first, best, behind one small interface.

The optimum comes from min-plus variable elimination (``rosreconf.solve.optimum``) when the system
graph is sparse enough to eliminate exactly, else from clingo; both minimise the very same
integers (``unary_costs``). Everything else is clingo (Potassco's ASP solver, PyPI
``clingo``): configuration is a finite-domain problem and clingo is a kept, well-made solver
for exactly that. The program below is fixed; everything specific to a library and schema
arrives as ground facts from ``rosreconf.solve.instance``, so grounding stays linear in the size
of the compatibility tables.

Enumeration order is deterministic and reads like the paper's lists: a domain heuristic makes
clingo decide roles in schema order and candidates in library order, and backtracking
enumeration then yields configurations in that lexicographic order, one at a time (flat
memory, ``limit`` stops early).
"""

from __future__ import annotations

import logging
from collections.abc import Collection, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.solve.emptyroles import as_candidate, as_chosen
from rosreconf.solve.factors import MAX_FACTOR_ROWS, TooHard, paused_gc
from rosreconf.solve.instance import Instance, compile_instance
from rosreconf.solve.objective import METRIC_SCALE, Objective, scaled_metric, unary_costs
from rosreconf.solve.optimum import first, minimise
from rosreconf.solve.unfillable import explain

if TYPE_CHECKING:
    # clingo is imported where it runs: a first configuration or an optimum that elimination
    # finds never loads it (whole-process time)
    import clingo

LOG = logging.getLogger(__name__)

# Objective and its integers live in objective.py (free of clingo); re-exported for solver users.
__all__ = [
    "METRIC_SCALE",
    "Best",
    "ClingoEngine",
    "EliminationEngine",
    "Objective",
    "asp_program",
    "best_configuration",
    "configurations",
    "optimise",
    "scaled_metric",
    "unary_costs",
    "why_not",
]

PROGRAM = """
1 { x(R,C) : cand(R,C) } 1 :- role(R).                      % rule: complete
:- edge(E,U,V), x(U,CU), x(V,CV), not ok(E,CU,CV).          % rule: edge-realised
sat(U,I) :- x(U,CU), meets(U,CU,I,V,CV), x(V,CV).           % rule: requirement-met any-of
:- x(U,CU), req(U,CU,I), not sat(U,I).                      % rule: requirement-met
chosen(C) :- x(_,C).                           % rule: needs excludes one-type-per-label
:- x(_,C), needs(C,D), not chosen(D).                       % rule: needs
:- x(_,C), excludes(C,D), chosen(D).                        % rule: excludes
:- x(_,C), clash(C,D), chosen(D).                           % rule: one-type-per-label
:- x(R1,C), x(R2,C), R1 < R2.                               % rule: one-role-each
#show x/2.
"""
"""The fixed ASP program; each line names the rules of ``validity.RULES`` it encodes."""

RESTARTS = """
wire(U,W) :- current(U,C), x(U,C), offer(U,V,D,W), x(V,D).
restart(U) :- current(U,C), x(U,C), wire(U,W), not wired(U,W).
restart(U) :- current(U,C), x(U,C), wired(U,W), not wire(U,W).
"""
"""A kept component restarts when what it is wired to changes (``Objective.restarts``)."""

OPTIMISE = (
    RESTARTS
    + """
#minimize { 1@3,R : x(R,C), current(R,D), C != D }.
#minimize { 1@3,U,restart : restart(U) }.
#minimize { 1@2,R : x(R,C), current(R,D), C != D }.
#minimize { W@1,R,C : x(R,C), weight(C,W) }.
#minimize { J@-R-1,R : x(R,C), position(R,C,J) }.
"""
)
"""The objective, ``objective.PREFERENCE`` level by level: fewest changes, a kept component
restarted to rewire it counting as one (the wiring model); then fewest replaced; then the
weighted metric sum; then, one level per role below those, in schema order, the position of
its candidate in library order (``position(R,C,J)``, J > 0): the first configuration in
enumeration order among the tied ones (core-guided optimisation, ``usc``, proves these
levels one after the other: 0.08 s at 60 roles x 10, where branch and bound ran out of 60 s)."""


def _facts(inst: Instance, objective: Objective | None = None) -> str:
    """Render the instance as ASP facts (integers for roles and components: fast to ground)."""
    ids = {c.name: i for i, c in enumerate(inst.library.components)}
    out: list[str] = []
    width = max((len(d) for d in inst.domains), default=1) + 1
    n = len(inst.roles)
    for r, dom in enumerate(inst.domains):
        out.append(f"role({r}).")
        for j, c in enumerate(dom):
            out.append(f"cand({r},{ids[c.name]}).")
            level = (n - r) * width + (width - j)
            out.append(f"#heuristic x({r},{ids[c.name]}). [{level},true]")
    for e, ((u, v), ok) in enumerate(zip(inst.edges, inst.edge_ok, strict=True)):
        out.append(f"edge({e},{u},{v}).")
        out.extend(f"ok({e},{ids[a]},{ids[b]})." for a, b in ok)
    for (u, cu, i), pairs in inst.meets.items():
        out.append(f"req({u},{ids[cu]},{i}).")
        out.extend(f"meets({u},{ids[cu]},{i},{v},{ids[cv]})." for v, cv in pairs)
    for c in inst.library.components:
        out.extend(f"needs({ids[c.name]},{ids[d]})." for d in c.needs if d in ids)
        out.extend(f"excludes({ids[c.name]},{ids[d]})." for d in c.excludes if d in ids)
    for name, others in sorted(inst.clashes.items()):
        out.extend(f"clash({ids[name]},{ids[d]})." for d in sorted(others))
    if objective is not None:
        index = inst.role_index
        for role, comp in objective.current.items():
            comp = as_candidate(role, comp)  # an empty optional role: its empty choice
            if role in index and comp in ids:
                out.append(f"current({index[role]},{ids[comp]}).")
        for c in inst.library.components:
            out.append(f"weight({ids[c.name]},{scaled_metric(objective, c)}).")
        for r, dom in enumerate(inst.domains if objective.settles_ties else ()):
            out.extend(  # the first candidate costs nothing
                f"position({r},{ids[c.name]},{j})." for j, c in enumerate(dom) if j
            )
        out += _restart_facts(inst, objective, ids)
    return "\n".join(out)


def _restart_facts(inst: Instance, objective: Objective, ids: dict[str, int]) -> list[str]:
    """Render ``Objective.restarts`` as ``wired(U,W)`` and ``offer(U,V,D,W)`` facts.

    W numbers each (interface, served name) pair; U and V are role indices, D a candidate.
    """
    index = inst.role_index
    table = objective.restarts
    wires: dict[object, int] = {}
    out = []
    for u, was in sorted(table.wired.items()):
        if u in index:
            out += [f"wired({index[u]},{wires.setdefault(w, len(wires))})." for w in sorted(was)]
    for (u, v), offer in sorted(table.offers.items()):
        if u not in index or v not in index:
            continue
        for name, pairs in sorted(offer.items()):
            d = ids.get(as_candidate(v, name))
            if d is not None:
                out += [
                    f"offer({index[u]},{index[v]},{d},{wires.setdefault(w, len(wires))})."
                    for w in sorted(pairs)
                ]
    return out


def asp_program(inst: Instance, objective: Objective | None = None) -> str:
    """Return the whole ASP program clingo solves for ``inst``: the rules, then its facts.

    Public so that clingo can be run on it alone (``python -m clingo``), as the benchmarks'
    reference does.
    """
    return PROGRAM + (OPTIMISE if objective is not None else "") + _facts(inst, objective)


def _control(inst: Instance, objective: Objective | None, args: list[str]) -> clingo.Control:
    import clingo

    ctl = clingo.Control(["--warn=none", *args])
    ctl.add("base", [], asp_program(inst, objective))
    ctl.ground([("base", [])])
    return ctl


def _configuration(inst: Instance, model: clingo.Model) -> Configuration:
    return _Reader(inst)(model)


class _Reader:
    """Turn clingo models into configurations through one table built per enumeration.

    Looking a shown atom up by its symbol is one call into clingo; reading its arguments
    and their numbers was five, and made up most of enumerating ten thousand models. Each
    (role, component) pair is made once here and shared by every configuration that holds
    it: a configuration then costs one pointer per role, not a new pair (10,000
    configurations of 1,000 roles held 640 MB of identical pairs).
    """

    def __init__(self, inst: Instance) -> None:
        import clingo

        ids = {c.name: i for i, c in enumerate(inst.library.components)}
        self.schema = inst.schema.name
        self.table = {
            clingo.Function("x", [clingo.Number(r), clingo.Number(ids[c.name])]): (
                r,
                (inst.roles[r].name, as_chosen(c.name)),
            )
            for r, dom in enumerate(inst.domains)
            for c in dom
        }

    def __call__(self, model: clingo.Model) -> Configuration:
        chosen = sorted(self.table[sym] for sym in model.symbols(shown=True))
        return Configuration(self.schema, tuple(pair for _, pair in chosen))


class ClingoEngine:
    """Enumerate and optimise configurations with clingo."""

    name = "clingo"

    def configurations(self, inst: Instance, limit: int | None = None) -> Iterator[Configuration]:
        """Yield valid configurations in role/library order, at most ``limit`` of them."""
        if any(not d for d in inst.domains):
            return
        models = "0" if limit is None else str(limit)
        ctl = _control(inst, None, [f"--models={models}", "--heuristic=Domain", "--enum-mode=bt"])
        read = _Reader(inst)
        with ctl.solve(yield_=True) as handle:
            for model in handle:
                yield read(model)

    def first(self, inst: Instance) -> Configuration | None:
        """Return one valid configuration, or None when there is none."""
        return next(self.configurations(inst, limit=1), None)

    def best(self, inst: Instance, objective: Objective) -> Configuration | None:
        """Return the configuration optimal for ``objective`` (proven), or None.

        Optimal at every level of ``OPTIMISE``, the last ones included: a tie is settled by
        the last rule of ``objective.PREFERENCE``, as elimination settles it.
        """
        if any(not d for d in inst.domains):
            return None
        ctl = _control(inst, objective, ["--opt-mode=opt", "--opt-strategy=usc"])
        best: Configuration | None = None
        with ctl.solve(yield_=True) as handle:
            for model in handle:  # each model improves on the last; the final one is optimal
                best = _configuration(inst, model)
        return best


class EliminationEngine:
    """Optimise configurations exactly by min-plus variable elimination (no enumeration)."""

    name = "elimination"

    def __init__(self, max_rows: int = MAX_FACTOR_ROWS) -> None:
        self.max_rows = max_rows

    def best(self, inst: Instance, objective: Objective) -> Configuration | None:
        """Return a configuration optimal for ``objective`` (proven), or None.

        Restarts (``Objective.restarts``) are not a cost of one role alone: the unary
        optimum is returned when it restarts nothing, since its change count is then a lower
        bound that it reaches; else clingo decides (``TooHard``), with restarts in its sum.
        Without restarts every change replaces a component, so the unary optimum of (changes,
        metric sum, position) is ``objective.PREFERENCE``'s (``minimise(earliest=True)``).

        Raises:
            TooHard: the system graph is too dense for tables of ``max_rows`` rows, or the
                optimum without restarts restarts a kept component.
        """
        found = minimise(
            inst, unary_costs(inst, objective), self.max_rows, earliest=objective.settles_ties
        )
        if found is not None and objective.restarted(found[0].mapping):
            raise TooHard("the fewest-change configuration restarts a kept component to rewire it")
        return found[0] if found else None


ENGINES = {"clingo": ClingoEngine}
"""The engines that enumerate (one today); the CLI does not care which one answers."""


@dataclass(frozen=True)
class Best:
    """An optimum and who proved it.

    Attributes:
        configuration: an optimal configuration, or None when there is none.
        engine: the name of the engine that answered ("elimination" or "clingo").
    """

    configuration: Configuration | None
    engine: str


def optimise(inst: Instance, objective: Objective, max_rows: int = MAX_FACTOR_ROWS) -> Best:
    """Return an optimum for ``objective``: by elimination, by clingo when that is too hard."""
    try:
        return Best(EliminationEngine(max_rows).best(inst, objective), EliminationEngine.name)
    except TooHard as exc:
        LOG.info("optimum by clingo: %s", exc)
        return Best(ClingoEngine().best(inst, objective), ClingoEngine.name)


def first_configuration(inst: Instance, max_rows: int = MAX_FACTOR_ROWS) -> Configuration | None:
    """Return the first configuration in enumeration order, without clingo where possible.

    Counting's tables give it by elimination (``optimum.first``) in a fraction of clingo's
    grounding time on large libraries; clingo answers only when a table would be too big.
    Both return the same configuration (tests/test_first.py).
    """
    try:
        return first(inst, max_rows)
    except TooHard as exc:
        LOG.info("first configuration by clingo: %s", exc)
        return ClingoEngine().first(inst)


def configurations(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str] = (),
    limit: int | None = None,
) -> Iterator[Configuration]:
    """Yield the valid configurations of ``schema`` (streaming, deterministic order)."""
    return ClingoEngine().configurations(compile_instance(library, schema, failed), limit)


def best_configuration(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    objective: Objective,
    failed: Collection[str] = (),
) -> Configuration | None:
    """Return a configuration optimal for ``objective``, or None when there is none."""
    with paused_gc():  # compiling allocates many small tuples too
        inst = compile_instance(library, schema, failed)
    return optimise(inst, objective).configuration


def why_not(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: Collection[str] = ()
) -> str:
    """Say in plain words why ``schema`` has no configuration."""
    return explain(compile_instance(library, schema, failed))
