"""Simulate every valid configuration of a schema and rank them: the M-solution's sweep.

A loop's result depends only on the dynamics in its roles (and the plant, reference and
horizon), so configurations are first turned into their loops' ``LoopSpec`` values, the
distinct ones are simulated once each (``performance.simulate_all``, in process, in a
process pool or on a Dask cluster), and every configuration then reads its loops from that
cache. A configuration's figure for a metric is the worst over its loops; it meets the
schema's requirements when every loop does.

``rosreconf.analysis.choice`` is what ``plan`` and ``watch`` use so that they never pick a
configuration that connects but does not perform; it judges configurations one at a time
with ``performance_of`` through the same cache.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field

from rosreconf.analysis.lti import transfer_function
from rosreconf.analysis.numeric import np
from rosreconf.analysis.performance import (
    LoopResult,
    LoopSpec,
    Progress,
    meets,
    simulate_all,
)
from rosreconf.analysis.ranking import LoopOutcome, Performance, SchemaSimulation, judge
from rosreconf.analysis.workers import executor
from rosreconf.errors import UsageError
from rosreconf.model import (
    ComponentLibrary,
    Configuration,
    ControlLoop,
    InteroperabilitySchema,
    Simulation,
    TransferFunction,
)
from rosreconf.model.dynamics import METRICS, UNITY
from rosreconf.solve.solver import configurations

__all__ = [
    "DEFAULT_LIMIT",
    "Cache",
    "LoopOutcome",
    "Performance",
    "SchemaSimulation",
    "Sweep",
    "check_metrics",
    "loop_spec",
    "performance_of",
    "simulate_schema",
    "simulation_of",
    "sweep",
]

Cache = dict[LoopSpec, LoopResult]
"""Simulated loops by content: shared across schemas, configurations and commands."""


def simulation_of(schema: InteroperabilitySchema) -> Simulation:
    """Return the schema's simulation block.

    Raises:
        UsageError: the schema has none.
    """
    if schema.simulation is None:
        raise UsageError(
            f"schema '{schema.name}' has no simulation block (add 'simulation:' with loops, "
            "a duration and requirements; docs/simulation.md)"
        )
    return schema.simulation


def loop_spec(
    library: ComponentLibrary, sim: Simulation, loop: ControlLoop, mapping: Mapping[str, str]
) -> tuple[LoopSpec, tuple[str, ...]]:
    """Return the loop's spec under ``mapping`` and its roles simulated as unity gain.

    A role without dynamics, or an optional role left empty, is simulated as unity gain.
    """
    unity: list[str] = []

    def block(role: str) -> TransferFunction:
        name = mapping[role]  # an empty optional role in a loop passes its signal through
        dyn = library[name].dynamics if name in library else None
        if dyn is None:
            unity.append(role)
            return UNITY
        return transfer_function(dyn)

    forward = tuple(block(r) for r in loop.forward)
    feedback = tuple(block(r) for r in loop.feedback)
    plant = transfer_function(loop.plant)
    spec = LoopSpec(forward, plant, feedback, sim.reference, sim.duration)
    return spec, tuple(unity)


def check_metrics(library: ComponentLibrary, names: Iterable[str]) -> tuple[str, ...]:
    """Return ``names`` if each is simulated or a library metric.

    Raises:
        UsageError: a name is neither.
    """
    known = set(METRICS) | library.metrics
    out = tuple(names)
    for name in out:
        if name not in known:
            raise UsageError(f"unknown metric '{name}' (use one of {', '.join(sorted(known))})")
    return out


DEFAULT_LIMIT = 1000
"""Configurations ``rosreconf simulate`` simulates per schema unless ``--limit`` says otherwise.

Without a bound a schema of 10^97 configurations grew to 6.7 GB in two minutes;
the output says when the limit stopped the listing, and the ranking is over what was
simulated."""


def simulate_schema(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str] = (),
    *,
    limit: int | None = None,
    pareto: Sequence[str] = (),
    cache: Cache | None = None,
    executor: Executor | None = None,
    progress: Progress | None = None,
) -> SchemaSimulation:
    """Simulate the valid configurations of ``schema`` (at most ``limit``) and rank them.

    Each configuration becomes one row of indices, per loop, into that loop's distinct
    assignments of components to its roles; only those distinct loops are simulated, and
    the configurations are judged by table lookup (``ranking.judge``).

    Raises:
        UsageError: the schema has no simulation block, or a ``pareto`` metric is unknown.
    """
    sim = simulation_of(schema)
    metrics = check_metrics(library, pareto)
    cache = {} if cache is None else cache
    index = {r.name: i for i, r in enumerate(schema.graph.roles)}
    positions = [tuple(index[r] for r in loop.roles) for loop in sim.loops]
    # Per loop: the components in its roles -> index of that assignment; and the
    # assignments' specs with their unity-gain roles, in first-seen order.
    seen: list[dict[tuple[str, ...], int]] = [{} for _ in sim.loops]
    assigned: list[list[tuple[LoopSpec, tuple[str, ...]]]] = [[] for _ in sim.loops]
    report = SchemaSimulation(schema)
    rows: list[int] = []
    listed = configurations(library, schema, failed, None if limit is None else limit + 1)
    for n, config in enumerate(listed):
        if limit is not None and n == limit:  # one more than the limit: there are more
            report.limited = True
            break
        names = [c for _, c in config.assignment]
        for i, pos in enumerate(positions):
            key = tuple(names[p] for p in pos)
            found = seen[i].get(key)
            if found is None:
                found = seen[i][key] = len(assigned[i])
                assigned[i].append(loop_spec(library, sim, sim.loops[i], config.mapping))
            rows.append(found)
        report.configurations.append(config)
    distinct = {spec for per_loop in assigned for spec, _ in per_loop}
    before = len(cache)
    simulate_all(distinct, cache, executor, progress=progress)
    report.loops_simulated = len(cache) - before
    report.distinct_loops = len(distinct)
    report.outcomes = [
        [
            LoopOutcome(loop.name, cache[spec], unity, meets(sim.requirements, cache[spec]))
            for spec, unity in per_loop
        ]
        for loop, per_loop in zip(sim.loops, assigned, strict=True)
    ]
    report.rows = np.array(rows, dtype=np.int64).reshape(len(report.configurations), len(sim.loops))
    judge(report, library, metrics)
    return report


@dataclass
class Sweep:
    """What ``rosreconf simulate`` found over several schemas.

    Attributes:
        reports: one per schema with a simulation block, in the order given.
        skipped: (schema, reason) for the schemas that were not simulated.
        failed: the failed components the configurations avoid.
    """

    reports: list[SchemaSimulation] = field(default_factory=list)
    skipped: list[tuple[str, str]] = field(default_factory=list)
    failed: tuple[str, ...] = ()

    @property
    def notes(self) -> list[str]:
        """Return one sentence per skipped schema, for the user."""
        return [f"schema '{name}' not simulated: {why}" for name, why in self.skipped]


def sweep(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    failed: Collection[str] = (),
    limit: int | None = None,
    pareto: Sequence[str] = (),
    workers: int | None = None,
    cluster: str | None = None,
    *,
    explicit: bool = False,
) -> Sweep:
    """Simulate each schema that has a simulation block, sharing one cache of loops.

    With ``explicit`` (the user named the schemas) a schema without a simulation block is an
    error; otherwise it is skipped and said so.

    Raises:
        UsageError: no schema can be simulated, a named one has no block, or a bad metric.
        ExternalToolError: the Dask cluster cannot be used.
    """
    out = Sweep(failed=tuple(failed))
    cache: Cache = {}
    with executor(workers, cluster) as pool:
        for schema in schemas:
            if schema.simulation is None:
                if explicit:
                    simulation_of(schema)  # raises, saying what to add
                out.skipped.append((schema.name, "it has no simulation block"))
                continue
            out.reports.append(
                simulate_schema(
                    library,
                    schema,
                    failed,
                    limit=limit,
                    pareto=pareto,
                    cache=cache,
                    executor=pool,
                )
            )
    if not out.reports:
        raise UsageError(
            "no schema has a simulation block (add 'simulation:' to a schema; docs/simulation.md)"
        )
    return out


def performance_of(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    config: Configuration,
    cache: Cache | None = None,
) -> Performance:
    """Simulate one configuration's loops (through ``cache``) and judge it."""
    sim = simulation_of(schema)
    cache = {} if cache is None else cache
    per = [loop_spec(library, sim, loop, config.mapping) for loop in sim.loops]
    simulate_all((spec for spec, _ in per), cache)
    report = SchemaSimulation(
        schema,
        configurations=[config],
        outcomes=[
            [LoopOutcome(loop.name, cache[spec], unity, meets(sim.requirements, cache[spec]))]
            for loop, (spec, unity) in zip(sim.loops, per, strict=True)
        ],
        rows=np.zeros((1, len(sim.loops)), dtype=np.int64),
    )
    judge(report, library)
    return report.performance(0)
