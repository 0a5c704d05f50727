"""What "best" means when choosing a configuration: the objective every engine minimises.

Its own small module, free of clingo, so that the PDDL renderer (``rosreconf.planning.pddl``)
and the choice of the running configuration can name an objective without loading a solver:
clingo, the elimination optimum and the planner's action costs all read the same integers
from ``unary_costs``.

The preference, owned here and nowhere else (``PREFERENCE``, ``Objective.key``): fewest
changes; among those, fewest components replaced (a kept node restarted to be rewired
disturbs less than another component in its place: the running one keeps its name, its
parameters and its package); then the weighted metric sum; then, for any tie left, the
first in enumeration order (roles in schema order, each role's candidates in library order:
the order ``rosreconf enumerate`` lists them). The last rule makes a reconfiguration's
optimum one configuration, not one of several, so that ``plan`` and ``watch``, whichever
engine answers, choose the same: elimination by a positional last level
(``optimum.minimise``), clingo by one minimize level per role below the others
(``solver.OPTIMISE``), and ``plan`` by planning again for that configuration when its
planner's plan differs (``rosreconf.planning.preferred``). A plain optimum, with no running
configuration (``enumerate --best``), has no changes to count and keeps the elimination's own
deterministic choice among equals (``Objective.settles_ties``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from rosreconf.model import EMPTY, Component, Configuration
from rosreconf.model.wiring import RestartTable
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import Instance

METRIC_SCALE = 1000
"""Metrics are real numbers; clingo optimises integers, so weights are scaled and rounded."""

PREFERENCE = (
    "fewest changes (a role that changes component, or a kept component restarted to be rewired)",
    "then fewest components replaced (a kept node restarted disturbs less than another in its "
    "place)",
    "then the least weighted metric sum",
    "then the first in enumeration order (roles in schema order, candidates in library order)",
)
"""The one rule choosing a reconfiguration, most important first (``Objective.key``)."""


@dataclass(frozen=True)
class Objective:
    """What "best" means: keep the running components first, then a weighted metric sum.

    Attributes:
        current: role -> component of the running configuration (changes cost 1 each, and
            are minimised before anything else: the paper's minimal reconfiguration).
        weights: metric name -> weight; a component's score is the weighted sum of its
            metrics (missing metrics count 0); lower is better.
        restarts: what the running components are wired to and what each choice would wire
            them to (``rosreconf.model.wiring.RestartTable``): a kept component whose wiring
            changes must restart, which costs 1, as a change does: it is one, counted at the
            same level (the wiring model, docs/architecture.md). Empty: no restarts counted.
    """

    current: Mapping[str, str] = field(default_factory=dict)
    weights: Mapping[str, float] = field(default_factory=dict)
    restarts: RestartTable = field(default_factory=RestartTable)

    @property
    def settles_ties(self) -> bool:
        """Tell whether the last rule of ``PREFERENCE`` applies: to a reconfiguration only.

        ``plan`` and ``watch`` must choose one configuration away from the running one;
        a plain optimum (``enumerate --best``) keeps the elimination's own deterministic
        choice, which leaves the dense grids usable (with the positional level the optimum
        of the generated 1000 x 10 library took 0.52 s instead of 0.20 s, in-process).
        """
        return bool(self.current)

    def restarted(self, mapping: Mapping[str, str]) -> set[str]:
        """Return the roles whose kept running component ``mapping`` restarts to rewire it."""
        return self.restarts.restarted(self.current, mapping)

    def score(self, inst: Instance, config: Configuration) -> tuple[int, float]:
        """Return (changes against current, restarts included; weighted metric sum)."""
        changes = sum(1 for r, c in config.assignment if r in self.current and self.current[r] != c)
        changes += len(self.restarted(config.mapping))
        metric = sum(
            w * inst.library[c].metrics.get(m, 0.0)
            for _, c in config.assignment
            if c != EMPTY  # an empty optional role costs nothing
            for m, w in self.weights.items()
        )
        return changes, metric

    def key(self, inst: Instance, config: Configuration) -> tuple[int, ...]:
        """Return what ``PREFERENCE`` compares, level by level: the least key is the best.

        (changes, components replaced, scaled metric sum, then each role's candidate's
        position in its domain, roles in schema order). Every engine's answer is this key's
        minimum over the valid configurations: the reference the tests hold them to.
        """
        changes, metric = self.cost(inst, config)
        replaced = changes - len(self.restarted(config.mapping))
        mapping = config.mapping
        positions = []
        for role, dom in zip(inst.roles, inst.domains, strict=True):
            chosen = as_candidate(role.name, mapping.get(role.name, EMPTY))
            positions.append(next(j for j, c in enumerate(dom) if c.name == chosen))
        return (changes, replaced, metric, *positions)

    def cost(self, inst: Instance, config: Configuration) -> tuple[int, int]:
        """Return the exact (changes and restarts, scaled metric sum) every engine minimises."""
        costs = unary_costs(inst, self)
        index = inst.role_index
        changes, metric = len(self.restarted(config.mapping)), 0
        for role, comp in config.assignment:
            c, m = costs[index[role]][as_candidate(role, comp)]
            changes, metric = changes + c, metric + m
        return changes, metric


def scaled_metric(objective: Objective, component: Component) -> int:
    """Return the component's weighted metric sum as the integer clingo optimises."""
    return _scaled(list(objective.weights.items()), component)


def _scaled(weights: list[tuple[str, float]], component: Component) -> int:
    """Return ``scaled_metric`` for the objective's weights, listed once by the caller."""
    return round(sum([wt * component.metrics.get(m, 0.0) for m, wt in weights]) * METRIC_SCALE)


def unary_costs(inst: Instance, objective: Objective) -> list[dict[str, tuple[int, int]]]:
    """Return per role, candidate -> (change against current, scaled metric): the objective.

    A change counts when ``current`` names, for that role, another component of the
    library (or leaves that optional role empty, and the candidate fills it); exactly the
    ``current``/``weight`` facts clingo receives.
    """
    known = inst.library.by_name
    weights = list(objective.weights.items())
    out = []
    for role, dom in zip(inst.roles, inst.domains, strict=True):
        now = objective.current.get(role.name)
        now = None if now is None else as_candidate(role.name, now)
        watch = now is not None and now in known
        out.append({c.name: (int(watch and c.name != now), _scaled(weights, c)) for c in dom})
    return out
