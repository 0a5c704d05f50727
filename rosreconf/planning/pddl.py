"""Render one compiled schema as a pre-grounded STRIPS task with action costs (Def. 11).

How it differs from the paper's Def. 11, on purpose: the paper's domain D = {Req, Ty, Pred, A}
is lifted (typed objects for ROS nodes and schemas, predicates on nodes and message types,
actions with node parameters). Here every action is parameter-free, one per (role, candidate)
choice, with the compatibility joins computed in Python and compiled in as preconditions, and
the objective (keep the running components, then weighted metrics) is the action costs, so
the planner minimises the change. docs/architecture.md and docs/pddl.md give the numbers.

Why pre-grounded: lifted joins make Fast Downward's translator build an axiom per component
pair (50 x 10: 39 s); one parameter-free action per (role, candidate), with the tables of
``rosreconf.solve.instance`` compiled in, avoids every join (see docs/pddl.md). Roles are chosen,
then checked, in schema order; a token (``choosing r``, ``checking r``, ``finished``) walks
along it. The task, for roles ``r_0 .. r_n`` and a candidate ``c`` of ``r_i``::

    choose-r-c     (choosing r_i), not (uses v d) for every EARLIER role v holding a d that
                   cannot share an edge with c, that c excludes or that excludes c (or whose
                   provisions clash with c's: one label, two types), or that is
                   c itself -> (uses r c), (serves r u q) for every requirement q of a
                   consumer role u that c meets, (chosen c) if some candidate needs c,
                   token to the next role; cost: the objective's price
    connect-u-q-v  (checking u), not (met u q), (serves v u q) -> (met u q); cost 0
    finish-r-c     (checking r), (uses r c), (met r q) for every requirement q of c,
                   (chosen d) for every d that c needs -> token to the next role; cost 0;
                   for the running component c of r: also not (rewired r), and
                   (wire-r-k) for each thing k it is wired to now
    restart-r-c    for the running component c of r: as finish-r-c without those; cost:
                   one change. A choose action of a provider candidate adds (wire-r-k) for
                   each thing k it wires c to as now, (rewired r) for anything else
                   (``Objective.restarts``; the wiring model, ``rosreconf.model.wiring``)
    goal           (finished)

Only earlier roles are checked: when ``r_i`` is chosen exactly ``r_0 .. r_(i-1)`` are
filled, and every later neighbour checks against ``r_i`` when its turn comes. Which provider
meets which requirement is decided by the provider's own choose action (``serves``), so there
is one connect action per (role, requirement, provider role), not one per provider candidate.
Without the fixed order every reordering of a plan is another plan (optimal searches drown).

``PddlNames`` maps names both ways; model names are ``[A-Za-z][A-Za-z0-9_]*``, so ``-``
separates the parts of an action name. A connect step names the provider role; the choose
step for that role names the provider component (``planning`` fills it in).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import jinja2

from rosreconf.model import Configuration, Requirement
from rosreconf.planning.pddl_names import PddlNameError, PddlNames, Step, label
from rosreconf.planning.pddl_rewiring import rewiring
from rosreconf.resources import Bundle, bundled
from rosreconf.solve.emptyroles import as_candidate, as_chosen
from rosreconf.solve.instance import Instance
from rosreconf.solve.objective import Objective

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


def _template(name: str) -> jinja2.Template:
    env = jinja2.Environment(
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
    )
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
    t = _Tables(inst, roles, comps, _requirement_names(inst, names))
    wires = rewiring(inst, t.roles, objective)
    actions = _choose_actions(inst, names, t, objective, _costs(inst, objective))
    actions += _connect_actions(inst, names, t)
    actions += _finish_actions(inst, names, t, objective, _costs(inst, objective).change)
    avoided = _avoid_actions(inst, names, t, forbid)
    actions += avoided
    current = {r: c for r, c in objective.current.items() if r in inst.role_index}
    forbidden = sorted({a.eff[0] for a in avoided})
    context = {
        "schema": schema,
        "domain_name": f"rosreconf-{schema.name.lower()}",
        "roles": list(zip(roles, inst.roles, strict=True)),
        "components": sorted(comps.values()),
        "requirements": sorted(t.reqs.values()),
        "actions": actions,
        "start": f"(choosing {roles[0]})" if roles else "(finished)",
        "failed": sorted(comps[n] for n in inst.failed if n in comps),
        "current": [(names.role(r), c or "(empty)") for r, c in current.items()],
        "weights": dict(objective.weights),
        "forbid": [f[1:-1] for f in forbidden],
        "rewired": bool(wires.needs),
        "flags": wires.flags,
    }
    return PddlTask(
        _template("domain.pddl.j2").render(context),
        _template("problem.pddl.j2").render(context),
        names,
        schema.name,
    )


class _Tables:
    """Index the instance the way the actions need it: holders, requirements, who serves whom.

    Attributes:
        roles: PDDL role names, in schema order.
        comps: component name -> PDDL name.
        reqs: requirement -> PDDL name.
        holders: component name -> the roles whose domain holds it, ascending.
        needed: the components some candidate needs.
        foes: component name -> the components it excludes, that exclude it, or that
            provide one of its labels with another type (``Instance.clashes``).
        incident: per role, the indices of its edges.
        served: (requirement's role, requirement) -> its provider roles, ascending.
        serves: (provider role, provider) -> the (role, requirement) pairs it meets.
    """

    def __init__(
        self,
        inst: Instance,
        roles: list[str],
        comps: dict[str, str],
        reqs: dict[Requirement, str],
    ) -> None:
        self.roles, self.comps, self.reqs = roles, comps, reqs
        self.holders: dict[str, list[int]] = {}
        for u, dom in enumerate(inst.domains):
            for c in dom:
                self.holders.setdefault(c.name, []).append(u)
        self.needed = {d for dom in inst.domains for c in dom for d in c.needs}
        self.foes: dict[str, set[str]] = {}
        for dom in inst.domains:
            for c in dom:
                for x in c.excludes | inst.clashes.get(c.name, set()):
                    self.foes.setdefault(c.name, set()).add(x)
                    self.foes.setdefault(x, set()).add(c.name)
        self.incident: list[list[int]] = [[] for _ in roles]
        for k, (eu, ev) in enumerate(inst.edges):
            self.incident[eu].append(k)
            if ev != eu:
                self.incident[ev].append(k)
        self.served: dict[tuple[int, Requirement], list[int]] = {}
        self.serves: dict[tuple[int, str], list[tuple[int, Requirement]]] = {}
        for (u, cu, i), pairs in inst.meets.items():
            req = inst.library[cu].requires[i]
            if (u, req) in self.served:
                continue  # the providers meeting a requirement do not depend on who requires it
            self.served[(u, req)] = sorted({v for v, _ in pairs})
            for v, cv in dict.fromkeys(pairs):
                self.serves.setdefault((v, cv), []).append((u, req))

    def earlier(self, name: str, u: int) -> list[str]:
        """Return ``not (uses v name)`` for every role v before ``u`` that could hold it."""
        return [
            f"(not (uses {self.roles[v]} {self.comps[name]}))"
            for v in self.holders.get(name, ())
            if v < u
        ]

    def after(self, kind: str, u: int) -> list[str]:
        """Move the token from role ``u`` of phase ``kind`` to the next role or phase."""
        roles = self.roles
        if u + 1 < len(roles):
            following = f"({kind} {roles[u + 1]})"
        else:
            following = f"(checking {roles[0]})" if kind == "choosing" else "(finished)"
        return [f"(not ({kind} {roles[u]}))", following]


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
    inst: Instance, names: PddlNames, t: _Tables, objective: Objective, costs: _Costs
) -> list[Action]:
    out = []
    roles, comps = t.roles, t.comps
    rewires = rewiring(inst, t.roles, objective).adds
    for u, dom in enumerate(inst.domains):
        role = inst.roles[u]
        for c in dom:
            if c.name in c.excludes:
                continue  # excludes itself: never valid
            pre = [f"(choosing {roles[u]})", *t.earlier(c.name, u)]
            possible = True
            for k in t.incident[u]:
                eu, ev = inst.edges[k]
                ok = inst.edge_ok[k]
                if eu == ev:  # a self-loop: c must realise it with itself
                    possible &= (c.name, c.name) in ok
                    continue
                other = ev if eu == u else eu
                if other > u:
                    continue  # checked when the later role is chosen
                for d in inst.domains[other]:
                    pair = (c.name, d.name) if eu == u else (d.name, c.name)
                    if pair not in ok:
                        pre.append(f"(not (uses {roles[other]} {comps[d.name]}))")
            if not possible:
                continue
            for x in sorted(t.foes.get(c.name, ())):
                pre += t.earlier(x, u)
            eff = [*t.after("choosing", u), f"(uses {roles[u]} {comps[c.name]})"]
            if c.name in t.needed:
                eff.append(f"(chosen {comps[c.name]})")
            eff += [
                f"(serves {roles[u]} {roles[w]} {t.reqs[q]})"
                for w, q in t.serves.get((u, c.name), ())
            ]
            eff += rewires.get((u, c.name), [])
            keep = objective.current.get(role.name)
            keep = None if keep is None else as_candidate(role.name, keep)
            cost = costs.metric[c.name] + (costs.change if keep and keep != c.name else 0)
            chosen = as_chosen(c.name)  # rule optional-role: the empty choice is EMPTY
            name = names.action(
                f"choose-{roles[u]}-{comps[c.name]}", Step("choose", role.name, chosen)
            )
            verb = "keep" if keep == c.name else "start" if chosen else "leave"
            comment = f"{verb} {c.name} as {role.name}" if chosen else f"{verb} {role.name} empty"
            out.append(Action(name, comment, list(dict.fromkeys(pre)), eff, cost))
    return out


def _connect_actions(inst: Instance, names: PddlNames, t: _Tables) -> list[Action]:
    out, roles = [], t.roles
    for (u, req), providers in t.served.items():
        for v in providers:
            step = Step("connect", inst.roles[u].name, "", req, inst.roles[v].name)
            name = names.action(f"connect-{roles[u]}-{t.reqs[req]}-{roles[v]}", step)
            out.append(
                Action(
                    name,
                    f"{inst.roles[v].name} meets {inst.roles[u].name}'s need for {req}",
                    [
                        f"(checking {roles[u]})",
                        f"(not (met {roles[u]} {t.reqs[req]}))",
                        f"(serves {roles[v]} {roles[u]} {t.reqs[req]})",
                    ],
                    [f"(met {roles[u]} {t.reqs[req]})"],
                    0,
                )
            )
    return out


def _finish_actions(
    inst: Instance, names: PddlNames, t: _Tables, objective: Objective, change: int
) -> list[Action]:
    """Check each role's requirements and couplings; a kept component rewired must restart.

    Where a choice of a provider rewires the kept component of role ``u`` (``(rewired u)``),
    its plain finish needs ``not (rewired u)``, and ``restart-u-c`` finishes it instead at
    the price of one change.
    """
    out = []
    roles, comps = t.roles, t.comps
    needs = rewiring(inst, t.roles, objective).needs
    for u, dom in enumerate(inst.domains):
        role = inst.roles[u]
        kept = objective.current.get(role.name)
        for c in dom:
            if any(d in inst.failed or not t.holders.get(d) for d in c.needs):
                continue  # a needed component that cannot be chosen: c can never finish
            pre = [f"(checking {roles[u]})", f"(uses {roles[u]} {comps[c.name]})"]
            pre += [f"(met {roles[u]} {t.reqs[r]})" for r in dict.fromkeys(c.requires)]
            pre += [f"(chosen {comps[d]})" for d in sorted(c.needs)]
            name = names.action(
                f"finish-{roles[u]}-{comps[c.name]}", Step("finish", role.name, as_chosen(c.name))
            )
            comment = f"{c.name} has all it requires and needs"
            if u in needs and c.name == kept:
                step = Step("restart", role.name, c.name)
                restart = names.action(f"restart-{roles[u]}-{comps[c.name]}", step)
                why = f"restart {c.name} to rewire it: a provider it is wired to changed"
                out.append(Action(restart, why, pre, t.after("checking", u), change))
                pre = [*pre, f"(not (rewired {roles[u]}))", *needs[u]]
            out.append(Action(name, comment, pre, t.after("checking", u), 0))
    return out


def _avoid_actions(
    inst: Instance, names: PddlNames, t: _Tables, forbid: Sequence[Configuration]
) -> list[Action]:
    out = []
    index = inst.role_index
    usable = [  # a configuration using a non-candidate cannot come out anyway
        f
        for f in forbid
        if f.assignment
        and all(as_candidate(r, c) in t.comps and r in index for r, c in f.assignment)
    ]
    for k, f in enumerate(usable, start=1):
        for r, given in f.assignment:
            c = as_candidate(r, given)  # rule optional-role: an empty role's empty choice
            role = t.roles[index[r]]
            pre = ["(finished)", f"(not (avoided-{k}))", f"(not (uses {role} {t.comps[c]}))"]
            if k > 1:
                pre.append(f"(avoided-{k - 1})")
            name = names.action(f"avoid-{k}-{role}", Step("avoid", r, c))
            comment = f"not forbidden configuration {k}: {r} is not {c}"
            out.append(Action(name, comment, pre, [f"(avoided-{k})"], 0))
    return out
