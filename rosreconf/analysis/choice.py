"""Choose the configuration that plan and watch move to: the best one that also performs.

The plain optimum (fewest changes, then the weighted library metrics) stands when it meets
the schema's performance requirements. Otherwise the valid configurations are walked in the
objective's order, lazily (``rosreconf.solve.search``): the optimum is simulated, each loop of
it that fails is forbidden as an assignment of its roles, and the next optimum is asked for,
until one performs or none is left. Each distinct loop is simulated once (the shared cache).
With a failing loop, the assignments of its roles one swap away are simulated too (a loop
is judged alone) and the failing ones forbidden in the same round (``_Walk.forbid_near``):
on 1000 roles x 10 candidates a round is a clingo optimum of seconds, a loop milliseconds.
When an objective weights a simulated figure (settling time, ...), which is no sum over
roles, the configurations with the fewest changes among those that perform are then listed
one by one and judged.

Memory and time are bounded (``Budget``): peak memory grows with the configurations tried,
never with how many valid ones exist (once: 24 GB and a kill on 1000 roles x 10
candidates with 40 failures). When the budget runs out, ``SearchExhausted`` says what was
tried and the best found (exit 3).
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Collection, Mapping
from dataclasses import dataclass

from rosreconf.analysis.performance import meets, rank_key, simulate_all
from rosreconf.analysis.ranking import Performance
from rosreconf.analysis.simulate import Cache, loop_spec, performance_of, simulation_of
from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, Configuration, ControlLoop, InteroperabilitySchema
from rosreconf.model.dynamics import METRICS
from rosreconf.solve.emptyroles import is_empty_choice
from rosreconf.solve.factors import paused_gc
from rosreconf.solve.instance import Instance, compile_instance
from rosreconf.solve.objective import Objective
from rosreconf.solve.search import Budget, OutOfTime, Search

__all__ = ["Budget", "Choice", "SearchExhausted", "choose", "shortfall"]


SHOWN = 5
"""Most shortfalls of the closest configuration named when the budget runs out."""


class SearchExhausted(ExternalToolError):
    """The budget ran out before a performing configuration was found or ruled out (exit 3)."""


@dataclass(frozen=True)
class Choice:
    """A configuration chosen with the schema's performance requirements honoured.

    Attributes:
        configuration: the chosen configuration, or None when no valid one performs.
        performance: how it performs (None when no simulation block or nothing chosen).
        passed_over: the fewest-change configuration when it was passed over because it
            fails the requirements (None otherwise).
        passed_over_performance: how that one performs.
        tried: how many configurations were simulated to decide (None: only the first).
    """

    configuration: Configuration | None
    performance: Performance | None = None
    passed_over: Configuration | None = None
    passed_over_performance: Performance | None = None
    tried: int | None = None


class _Walk:
    """The state of one search: budget, cache, what was tried and the best so far."""

    def __init__(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        cache: Cache,
        budget: Budget,
    ) -> None:
        self.library, self.schema, self.cache, self.budget = library, schema, cache, budget
        self.start = time.monotonic()
        self.deadline = None if budget.seconds is None else self.start + budget.seconds
        self.tried = 0
        self.near = 0  # loops simulated one swap from a failing loop's assignment
        self.forbidden = 0  # loop assignments forbidden
        self._banned: set[tuple[tuple[str, str], ...]] = set()
        self.closest: Performance | None = None

    def judge(self, config: Configuration) -> Performance:
        """Simulate ``config`` (through the cache), count it, and check the budget.

        Raises:
            SearchExhausted: the budget is spent.
        """
        if self.tried >= self.budget.configurations or self._late():
            raise self.exhausted()
        self.tried += 1
        perf = performance_of(self.library, self.schema, config, self.cache)
        failing = sum(not o.meets_requirements for o in perf.loops)
        if self.closest is None or failing < sum(
            not o.meets_requirements for o in self.closest.loops
        ):
            self.closest = perf
        return perf

    def forbid_near(
        self, search: Search, inst: Instance, loop: ControlLoop, mapping: Mapping[str, str]
    ) -> None:
        """Forbid the assignments one swap away from a failing loop's that fail it too.

        A loop's result depends only on the components in its roles, so each assignment of
        its roles that differs from ``mapping`` in one role is simulated alone (a few dozen
        loops, cached), and those that fail are forbidden at once; when every one of them
        fails, those two swaps away too (a few hundred). Each is a nogood the walk would
        otherwise learn from one clingo optimum of the whole schema (seconds at 1000 roles),
        so the walk reaches a performing configuration in fewer rounds; only loops that were
        simulated and failed are forbidden, so the answer is the same.
        """
        index = inst.role_index
        mine = {r: mapping[r] for r in loop.roles}  # a loop reads its own roles only
        other = {  # the candidates each role could swap to (an empty choice is no loop block)
            r: [c.name for c in inst.domains[index[r]] if c.name != mine[r]] for r in mine
        }
        other = {r: [c for c in cs if not is_empty_choice(c)] for r, cs in other.items()}
        one = [{**mine, r: c} for r, cs in other.items() for c in cs]
        if self._judge(search, loop, one):
            return
        pairs = itertools.combinations(other, 2)
        self._judge(
            search,
            loop,
            [{**mine, r: c, q: d} for r, q in pairs for c in other[r] for d in other[q]],
        )

    def _judge(self, search: Search, loop: ControlLoop, near: list[dict[str, str]]) -> bool:
        """Simulate the loop under each mapping, forbid those that fail; tell if one performs."""
        sim = simulation_of(self.schema)
        specs = [loop_spec(self.library, sim, loop, m)[0] for m in near]
        if self._late():
            raise OutOfTime
        simulate_all(specs, self.cache)
        self.near += len(specs)
        performs = False
        for m, spec in zip(near, specs, strict=True):
            if meets(sim.requirements, self.cache[spec]):
                performs = True
            else:
                self.ban(search, tuple((r, m[r]) for r in loop.roles))
        return performs

    def ban(self, search: Search, assignment: tuple[tuple[str, str], ...]) -> None:
        """Forbid a failing assignment of a loop's roles (once: later rounds meet it again)."""
        if assignment not in self._banned:
            self._banned.add(assignment)
            search.forbid(assignment)
            self.forbidden += 1

    def _late(self) -> bool:
        return self.deadline is not None and time.monotonic() >= self.deadline

    def exhausted(self) -> SearchExhausted:
        """Return the error that says what was tried and the closest configuration found."""
        spent = time.monotonic() - self.start
        which = (
            f"--search-limit {self.budget.configurations}"
            if self.tried >= self.budget.configurations
            else f"--search-time {self.budget.seconds:g}"
        )
        text = (
            f"schema '{self.schema.name}': no configuration that meets the performance "
            f"requirements was found within the search budget ({which}): {self.tried} "
            f"configuration(s) simulated, {len(self.cache)} distinct loop(s), {spent:.1f} s; "
            f"{self.forbidden} failing assignment(s) of a loop's roles forbidden, "
            f"{self.near} loop(s) judged one or two swaps from a failing one's assignment"
        )
        if self.closest is not None:
            wrong = shortfall(self.schema, self.closest).split("; ")
            more = f" and {len(wrong) - SHOWN} more" if len(wrong) > SHOWN else ""
            text += f"; the closest found fails {'; '.join(wrong[:SHOWN])}{more}"
        return SearchExhausted(text + " (raise --search-limit or --search-time)")


def choose(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    fewest: Configuration,
    current: Mapping[str, str],
    weights: Mapping[str, float],
    failed: Collection[str] = (),
    cache: Cache | None = None,
    budget: Budget | None = None,
) -> Choice:
    """Return the best configuration that meets ``schema``'s performance requirements.

    ``fewest`` is the optimum of the plain objective (fewest changes, then weighted library
    metrics). When it performs and no weight names a simulated metric, it stands. Otherwise
    the walk of the module docstring finds the best that performs by (changes, weighted
    metrics with simulated figures), or proves that none does.

    Raises:
        SearchExhausted: ``budget`` ran out first (exit 3), saying what was tried.
    """
    if schema.simulation is None:
        return Choice(fewest)
    cache = {} if cache is None else cache
    walk = _Walk(library, schema, cache, budget or Budget())
    first = walk.judge(fewest)
    simulated = {m: w for m, w in weights.items() if m in METRICS and w}
    if first.meets_requirements and not simulated:
        return Choice(fewest, first)
    plain = {m: w for m, w in weights.items() if m not in METRICS}
    objective = Objective(current=dict(current), weights=plain)
    with paused_gc():
        inst = compile_instance(library, schema, failed)
    search = Search(inst, objective, walk.deadline)
    sim = simulation_of(schema)
    best: Performance | None = first if first.meets_requirements else None
    try:
        config: Configuration | None = fewest
        perf = first
        while best is None and config is not None:
            for loop, outcome in zip(sim.loops, perf.loops, strict=True):
                if not outcome.meets_requirements:
                    walk.ban(search, tuple((r, config.mapping[r]) for r in loop.roles))
                    walk.forbid_near(search, inst, loop, config.mapping)
            config = search.best()
            if config is not None:
                perf = walk.judge(config)
                best = perf if perf.meets_requirements else None
        if best is not None and simulated:
            best = _best_at_level(walk, search, objective, inst_changes(objective, best), weights)
    except OutOfTime:
        raise walk.exhausted() from None
    passed = None if first.meets_requirements else first
    return Choice(
        best.configuration if best else None,
        best,
        passed.configuration if passed else None,
        passed,
        walk.tried,
    )


def inst_changes(objective: Objective, perf: Performance) -> int:
    """Return how many roles ``perf``'s configuration changes against the running one."""
    cur = objective.current
    return sum(1 for r, c in perf.configuration.assignment if r in cur and cur[r] != c)


def _best_at_level(
    walk: _Walk,
    search: Search,
    objective: Objective,
    changes: int,
    weights: Mapping[str, float],
) -> Performance | None:
    """Return the performing configuration with ``changes`` changes that scores best.

    The score is the weighted sum of the figures (simulated ones and library sums), then
    the rank (settling time, error, overshoot), then listing order.
    """

    def score(p: Performance) -> tuple[float, tuple[bool, float, float, float]]:
        metric = sum(w * p.figures.get(m, 0.0) for m, w in weights.items() if w)
        return (metric if math.isfinite(metric) else math.inf), rank_key(True, p.figures)

    best: Performance | None = None
    for config in search.at_level(changes):
        perf = walk.judge(config)
        if perf.meets_requirements and (best is None or score(perf) < score(best)):
            best = perf
    return best


def shortfall(schema: InteroperabilitySchema, performance: Performance) -> str:
    """Say which loop misses which requirement, e.g. "gripper_force: overshoot 29.9 > 25"."""
    sim = simulation_of(schema)
    parts = []
    for o in performance.loops:
        if not o.result.stable:
            parts.append(f"{o.loop}: unstable")
            continue
        for metric, limit in sim.requirements.limits().items():
            value = o.result.figure(metric)
            if value > limit:
                shown = "not settled" if math.isinf(value) else f"{value:.3g}"
                parts.append(f"{o.loop}: {metric} {shown} > {limit:g}")
    return "; ".join(parts) or "none"
