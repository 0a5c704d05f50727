"""Judge and rank a schema's configurations from their loops' results, by table lookup.

A configuration's loops are a few distinct loop assignments shared by thousands of
configurations, so a sweep keeps, per loop, the list of its distinct outcomes and, per
configuration, one row of indices into those lists. A configuration's figures (the worst over
its loops, plus the library's metrics summed over its components), whether it meets the
requirements, and the ranking are then whole-array operations (numpy), with no object per
configuration. ``Performance`` objects, which the table, the plots and ``choose`` read, are
built only for the configurations actually looked at (``SchemaSimulation.ranked[i]``).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, overload

from rosreconf.analysis.numeric import np
from rosreconf.analysis.performance import LoopResult, pareto_front
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.dynamics import METRICS

Array = np.ndarray[Any, Any]


@dataclass(frozen=True)
class LoopOutcome:
    """One loop of one configuration, simulated.

    Attributes:
        loop: the loop's name.
        result: its figures.
        unity: the loop's roles whose component has no dynamics (simulated as unity gain).
        meets_requirements: the loop is stable and meets every requirement of the schema.
    """

    loop: str
    result: LoopResult
    unity: tuple[str, ...]
    meets_requirements: bool


@dataclass(frozen=True)
class Performance:
    """How one configuration performs.

    Attributes:
        configuration: the configuration.
        loops: its loops, in the schema's order.
        figures: metric -> the worst figure over its loops (+inf when undefined), plus the
            library's metrics summed over its components.
        meets_requirements: every loop is stable and meets every requirement.
    """

    configuration: Configuration
    loops: tuple[LoopOutcome, ...]
    figures: Mapping[str, float]
    meets_requirements: bool

    @property
    def stable(self) -> bool:
        """Tell whether every loop is stable."""
        return all(o.result.stable for o in self.loops)


@dataclass
class SchemaSimulation:
    """Every valid configuration of one schema, simulated and ranked, held as tables.

    Attributes:
        schema: the schema.
        configurations: the configurations, in enumeration order.
        outcomes: per loop of the schema, its distinct outcomes.
        rows: per configuration (enumeration order), the index of each loop's outcome.
        metrics: the names of the columns of ``figures``: the simulated metrics, then the
            library's.
        figures: per configuration, each metric; NaN for a library metric none of its
            components carries.
        meets: per configuration, whether it meets the requirements.
        order: the configurations' enumeration indices, best first (``rank_key``'s order,
            ties by enumeration order).
        loops_simulated: distinct loops simulated for this schema (the rest came from the
            cache).
        distinct_loops: distinct loops among this schema's configurations.
        pareto: ranks (indices into ``ranked``) of the Pareto front over ``pareto_metrics``.
        pareto_metrics: the metrics of the front (empty when none was asked for).
        limited: the limit stopped the listing: more valid configurations exist than were
            simulated, and the ranking is over those simulated only.
    """

    schema: InteroperabilitySchema
    configurations: list[Configuration] = field(default_factory=list)
    outcomes: list[list[LoopOutcome]] = field(default_factory=list)
    rows: Array = field(default_factory=lambda: np.zeros((0, 0), dtype=np.int64))
    metrics: tuple[str, ...] = METRICS
    figures: Array = field(default_factory=lambda: np.zeros((0, len(METRICS))))
    meets: Array = field(default_factory=lambda: np.zeros(0, dtype=bool))
    order: Array = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    loops_simulated: int = 0
    distinct_loops: int = 0
    pareto: list[int] = field(default_factory=list)
    pareto_metrics: tuple[str, ...] = ()
    limited: bool = False

    @property
    def ranked(self) -> Ranked:
        """Return the configurations' performances, best first (built when read)."""
        return Ranked(self)

    def performance(self, index: int) -> Performance:
        """Return how the configuration at enumeration ``index`` performs."""
        loops = tuple(
            outcomes[j] for outcomes, j in zip(self.outcomes, self.rows[index], strict=True)
        )
        return Performance(
            self.configurations[index],
            loops,
            self.figure_map(index),
            bool(self.meets[index]),
        )

    def figure_map(self, index: int) -> dict[str, float]:
        """Return metric -> figure of the configuration at enumeration ``index``."""
        row = self.figures[index]
        return {m: float(v) for m, v in zip(self.metrics, row, strict=True) if not np.isnan(v)}

    def any_meets(self) -> bool:
        """Tell whether some configuration meets the requirements."""
        return bool(self.meets.any())

    def unity_roles(self) -> list[str]:
        """Return the roles simulated as unity gain in some configuration, sorted."""
        return sorted({r for outcomes in self.outcomes for o in outcomes for r in o.unity})


class Ranked(Sequence[Performance]):
    """The configurations of a ``SchemaSimulation`` by rank, each built when read."""

    def __init__(self, report: SchemaSimulation) -> None:
        self.report = report

    def __len__(self) -> int:
        return len(self.report.order)

    @overload
    def __getitem__(self, rank: int) -> Performance: ...

    @overload
    def __getitem__(self, rank: slice) -> list[Performance]: ...

    def __getitem__(self, rank: int | slice) -> Performance | list[Performance]:
        if isinstance(rank, slice):
            return [self[i] for i in range(*rank.indices(len(self)))]
        return self.report.performance(int(self.report.order[rank]))

    def __iter__(self) -> Iterator[Performance]:
        return (self.report.performance(int(i)) for i in self.report.order)


def judge(
    report: SchemaSimulation,
    library: ComponentLibrary,
    pareto: Sequence[str] = (),
) -> None:
    """Fill ``report``'s figures, requirement flags, ranking and front from its tables.

    ``report.configurations``, ``outcomes`` and ``rows`` must be set. A simulated figure
    wins over a library metric of the same name; library metrics are summed over the
    components in role order (as a person would add them up).
    """
    n = len(report.configurations)
    loops = len(report.outcomes)
    rows = report.rows.reshape(n, loops)
    extra = sorted({m for c in library for m in c.metrics} - set(METRICS))
    report.metrics = (*METRICS, *extra)
    figures = np.zeros((n, len(report.metrics)))
    meets = np.ones(n, dtype=bool)
    for j, outcomes in enumerate(report.outcomes):
        table = np.array([[o.result.figure(m) for m in METRICS] for o in outcomes]).reshape(
            len(outcomes), len(METRICS)
        )
        ok = np.array([o.meets_requirements for o in outcomes], dtype=bool)
        column = rows[:, j]
        figures[:, : len(METRICS)] = np.maximum(figures[:, : len(METRICS)], table[column])
        meets &= ok[column]
    if extra:
        figures[:, len(METRICS) :] = _library_sums(library, report.configurations, extra)
    report.figures, report.meets = figures, meets
    # rank_key: meeting the requirements first, then settling time, error, overshoot; ties
    # keep enumeration order (np.lexsort is stable and sorts by its last key first).
    report.order = np.lexsort((np.arange(n), figures[:, 2], figures[:, 1], figures[:, 0], ~meets))
    report.pareto_metrics = tuple(pareto)
    if pareto:
        columns = [report.metrics.index(m) for m in pareto]
        ranked = np.nan_to_num(figures[report.order][:, columns], nan=0.0, posinf=np.inf)
        report.pareto = pareto_front([tuple(float(x) for x in p) for p in ranked])


def _library_sums(
    library: ComponentLibrary, configurations: Sequence[Configuration], metrics: Sequence[str]
) -> Array:
    """Return per configuration each metric summed over its components (NaN when none has it).

    Summed role by role, left to right, so the floating-point result is what adding the
    components' values in role order gives.
    """
    n = len(configurations)
    roles = len(configurations[0].assignment) if n else 0
    out = np.full((n, len(metrics)), np.nan)
    for k, metric in enumerate(metrics):
        value = {c.name: c.metrics[metric] for c in library if metric in c.metrics}
        if not value:
            continue
        cells = np.array(
            [[value.get(name, np.nan) for _, name in c.assignment] for c in configurations]
        ).reshape(n, roles)
        total = np.zeros(n)
        present = np.zeros(n, dtype=bool)
        for r in range(roles):
            has = ~np.isnan(cells[:, r])
            total[has] += cells[has, r]
            present |= has
        out[present, k] = total[present]
    return out
