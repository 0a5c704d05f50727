"""What "best" means when choosing a configuration: the objective every engine minimises.

Its own small module, free of clingo, so that the PDDL renderer (``rosreconf.planning.pddl``)
and the choice of the running configuration can name an objective without loading a solver:
clingo, the elimination optimum and the planner's action costs all read the same integers
from ``unary_costs``.
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
