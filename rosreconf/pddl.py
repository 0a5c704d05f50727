"""Render one compiled schema as a pre-grounded STRIPS task with action costs.

Why pre-grounded: lifted ADL with two component variables inside a quantified condition makes
Fast Downward's translator build an axiom per component pair (50 roles x 10 candidates: 39 s,
950 MB); one parameter-free action per (role, candidate) with the compatibility tables of
``rosreconf.instance`` compiled into its precondition plans 200 x 10 in under 2 s
(see docs/pddl.md). The task, for every role ``r`` and candidate ``c`` of the instance::

    choose-r-c       (filled previous role), not (filled r), not (chosen c),
                     not (uses v c') for every candidate c' of a neighbouring role v that
                     cannot share an edge with c, not (chosen x) for every x that excludes
                     c or that c excludes
                     -> (filled r) (uses r c) (chosen c); cost: the objective's price
    connect-r-q-v-p  (filled last role), (done previous role), not (met r q), (uses v p),
                     where p meets requirement q along an edge r -> v  -> (met r q); cost 0
    finish-r-c       (filled last role), (done previous role), (uses r c), (met r q) for
                     every requirement q of c, (chosen d) for every d that c needs
                     -> (done r); cost 0
    goal             (done r) for every role

Roles are chosen, then connected and finished, in schema order: without that, every
reordering of a plan is another plan and optimal searches drown in the symmetry
(astar(lmcut()) on the paper's example: over 30 s unordered, 7 s ordered; seq-sat-lama-2011
proves the optimum in 0.4 s ordered).

Names map one way through ``PddlNames`` (model -> PDDL) and back (PDDL -> model). Model names
are ``[A-Za-z][A-Za-z0-9_]*``, so ``-`` separates the parts of an action name unambiguously.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import jinja2

from rosreconf.instance import Instance
from rosreconf.model import Configuration, Requirement
from rosreconf.pddl_names import PddlNameError, PddlNames, Step, label
from rosreconf.resources import Bundle, bundled
from rosreconf.solver import Objective

METRIC_SCALE = 100
"""Metric weights are real numbers; PDDL costs are integers: weights count in hundredths."""

COST_LIMIT = 2**30
"""Fast Downward adds costs in 32-bit integers: keep the worst plan's cost below this."""


@dataclass
class Action:
    """One ground action for the template: name, comment, literals and cost."""

    name: str
    comment: str
    pre: list[str]
    eff: list[str]
    cost: int


@dataclass
class PddlTask:
    """A rendered task: the two texts and the names to read its plans back with.

    Attributes:
        domain: the domain text.
        problem: the problem text.
        names: the two-way name map.
        schema: the schema's name.
    """

    domain: str
    problem: str
    names: PddlNames
    schema: str


@dataclass
class _Costs:
    change: int
    metric: dict[str, int] = field(default_factory=dict)


def _costs(inst: Instance, objective: Objective) -> _Costs:
    """Price each choice: metrics in hundredths, a change above any metric sum (lexicographic)."""
    metric: dict[str, int] = {}
    for dom in inst.domains:
        for c in dom:
            w = sum(wt * c.metrics.get(m, 0.0) for m, wt in objective.weights.items())
            metric[c.name] = round(w * METRIC_SCALE)
    low = min(metric.values(), default=0)
    metric = {k: v - low for k, v in metric.items()}  # PDDL costs must not be negative
    worst = sum(max((metric[c.name] for c in dom), default=0) for dom in inst.domains)
    change = worst + 1 if objective.current else 0
    if change * (len(inst.roles) + 1) + worst >= COST_LIMIT:
        raise PddlNameError("the objective's weights are too large for PDDL's integer costs")
    return _Costs(change, metric)


def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
    )
    return env


def _template(env: jinja2.Environment, name: str) -> jinja2.Template:
    return env.from_string(bundled(Bundle.TEMPLATES, name).read_text(encoding="utf-8"))


def render(
    inst: Instance,
    objective: Objective | None = None,
    forbid: Sequence[Configuration] = (),
) -> PddlTask:
    """Render ``inst`` as a domain and a problem whose plans are exactly its valid configurations.

    Args:
        inst: the compiled schema.
        objective: what choices cost (keep the current component: 0; change: more than every
            metric together; metrics: weighted, in hundredths). None: every plan costs 0.
        forbid: configurations the plan must not produce (used to enumerate by planning):
            for each, the goal needs ``(avoided-K)``, which only an ``avoid-K-ROLE`` action
            achieves, where ROLE holds another component than in the forbidden one. A
            negated conjunction in the goal would do, but Fast Downward multiplies such
            disjunctions out (13 roles, 4 configurations: 13^4 axiom rules).
    """
    objective = objective or Objective()
    names = PddlNames()
    schema = inst.schema
    roles = [names.role(r.name) for r in inst.roles]
    candidates = {c.name for dom in inst.domains for c in dom}
    extra = {n for u in range(len(inst.roles)) for n in inst.excluded[u]}
    comps = {n: names.component(n) for n in sorted(candidates | extra | set(inst.failed))}
    reqs = _requirement_names(inst, names)
    costs = _costs(inst, objective)
    actions = _choose_actions(inst, names, comps, roles, objective, costs)
    actions += _connect_actions(inst, names, comps, roles, reqs)
    actions += _finish_actions(inst, names, comps, roles, reqs)
    env = _environment()
    current = {r: c for r, c in objective.current.items() if r in inst.role_index}
    avoided = _avoid_actions(inst, names, comps, roles, forbid)
    actions += avoided
    forbidden = sorted({a.eff[0] for a in avoided})
    context = {
        "schema": schema,
        "domain_name": f"rosreconf-{schema.name.lower()}",
        "roles": list(zip(roles, inst.roles, strict=True)),
        "components": sorted(comps.values()),
        "requirements": sorted(reqs.values()),
        "actions": actions,
        "failed": sorted(comps[n] for n in inst.failed if n in comps),
        "current": [(names.role(r), c) for r, c in current.items()],
        "weights": dict(objective.weights),
        "forbid": [f[1:-1] for f in forbidden],
    }
    return PddlTask(
        _template(env, "domain.pddl.j2").render(context),
        _template(env, "problem.pddl.j2").render(context),
        names,
        schema.name,
    )


def _requirement_names(inst: Instance, names: PddlNames) -> dict[Requirement, str]:
    distinct = {req for dom in inst.domains for c in dom for req in c.requires}
    base: dict[str, set[tuple[object, ...]]] = {}
    for req in distinct:
        base.setdefault("-or-".join(label(o.label) for o in req.options), set()).add(req.options)
    return {
        req: names.requirement(
            req, qualified=len(base["-or-".join(label(o.label) for o in req.options)]) > 1
        )
        for req in sorted(distinct, key=lambda r: r.options)
    }


def _choose_actions(
    inst: Instance,
    names: PddlNames,
    comps: dict[str, str],
    roles: list[str],
    objective: Objective,
    costs: _Costs,
) -> list[Action]:
    out = []
    chosen_names = {c.name for dom in inst.domains for c in dom}
    for u, dom in enumerate(inst.domains):
        role = inst.roles[u]
        for c in dom:
            pre = [f"(not (filled {roles[u]}))", f"(not (chosen {comps[c.name]}))"]
            if u:  # roles are filled in schema order: no plan is a reordering of another
                pre.append(f"(filled {roles[u - 1]})")
            possible = True
            for k, (eu, ev) in enumerate(inst.edges):
                if eu != u and ev != u:
                    continue
                ok = inst.edge_ok[k]
                if eu == ev:  # a self-loop: c must realise it with itself
                    possible &= (c.name, c.name) in ok
                    continue
                other = ev if eu == u else eu
                for d in inst.domains[other]:
                    pair = (c.name, d.name) if eu == u else (d.name, c.name)
                    if pair not in ok:
                        pre.append(f"(not (uses {roles[other]} {comps[d.name]}))")
            if not possible:
                continue
            if c.name in c.excludes:
                continue  # excludes itself: never valid
            foes = {x for x in c.excludes if x in chosen_names} | {
                x.name for dom2 in inst.domains for x in dom2 if c.name in x.excludes
            }
            pre += [f"(not (chosen {comps[x]}))" for x in sorted(foes)]
            keep = objective.current.get(role.name)
            cost = costs.metric[c.name] + (costs.change if keep and keep != c.name else 0)
            name = names.action(
                f"choose-{roles[u]}-{comps[c.name]}", Step("choose", role.name, c.name)
            )
            verb = "keep" if keep == c.name else "start"
            out.append(
                Action(
                    name,
                    f"{verb} {c.name} as {role.name}",
                    list(dict.fromkeys(pre)),
                    [
                        f"(filled {roles[u]})",
                        f"(uses {roles[u]} {comps[c.name]})",
                        f"(chosen {comps[c.name]})",
                    ],
                    cost,
                )
            )
    return out


def _connect_actions(
    inst: Instance,
    names: PddlNames,
    comps: dict[str, str],
    roles: list[str],
    reqs: dict[Requirement, str],
) -> list[Action]:
    out = []
    done: set[tuple[int, Requirement]] = set()
    for (u, cu, i), pairs in inst.meets.items():
        req = inst.library[cu].requires[i]
        if (u, req) in done:
            continue  # the providers meeting a requirement do not depend on who requires it
        done.add((u, req))
        for v, cv in pairs:
            step = Step("connect", inst.roles[u].name, cv, req, inst.roles[v].name)
            name = names.action(f"connect-{roles[u]}-{reqs[req]}-{roles[v]}-{comps[cv]}", step)
            out.append(
                Action(
                    name,
                    f"{cv} ({inst.roles[v].name}) meets {inst.roles[u].name}'s need for {req}",
                    [
                        f"(filled {roles[-1]})",
                        *([f"(done {roles[u - 1]})"] if u else []),
                        f"(not (met {roles[u]} {reqs[req]}))",
                        f"(uses {roles[v]} {comps[cv]})",
                    ],
                    [f"(met {roles[u]} {reqs[req]})"],
                    0,
                )
            )
    return out


def _finish_actions(
    inst: Instance,
    names: PddlNames,
    comps: dict[str, str],
    roles: list[str],
    reqs: dict[Requirement, str],
) -> list[Action]:
    out = []
    for u, dom in enumerate(inst.domains):
        role = inst.roles[u]
        for c in dom:
            missing = [d for d in c.needs if d not in comps or d in inst.failed]
            if missing:
                continue  # a needed component that cannot be chosen: c can never finish
            pre = [f"(uses {roles[u]} {comps[c.name]})", f"(filled {roles[-1]})"]
            if u:
                pre.append(f"(done {roles[u - 1]})")
            pre += [f"(met {roles[u]} {reqs[r]})" for r in dict.fromkeys(c.requires)]
            pre += [f"(chosen {comps[d]})" for d in sorted(c.needs)]
            name = names.action(
                f"finish-{roles[u]}-{comps[c.name]}", Step("finish", role.name, c.name)
            )
            out.append(
                Action(
                    name, f"{c.name} has all it requires and needs", pre, [f"(done {roles[u]})"], 0
                )
            )
    return out


def _avoid_actions(
    inst: Instance,
    names: PddlNames,
    comps: dict[str, str],
    roles: list[str],
    forbid: Sequence[Configuration],
) -> list[Action]:
    out = []
    usable = [  # a configuration using a non-candidate cannot come out anyway
        f
        for f in forbid
        if f.assignment and all(c in comps and r in inst.role_index for r, c in f.assignment)
    ]
    index = inst.role_index
    for k, f in enumerate(usable, start=1):
        for r, c in f.assignment:
            role = roles[index[r]]
            pre = [f"(done {roles[-1]})", f"(not (avoided-{k}))", f"(not (uses {role} {comps[c]}))"]
            if k > 1:
                pre.append(f"(avoided-{k - 1})")
            name = names.action(f"avoid-{k}-{role}", Step("avoid", r, c))
            out.append(
                Action(
                    name,
                    f"not forbidden configuration {k}: {r} is not {c}",
                    pre,
                    [f"(avoided-{k})"],
                    0,
                )
            )
    return out
