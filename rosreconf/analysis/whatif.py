"""Find which failure sets each schema survives, and with which configuration.

Only components that appear in some valid configuration (clingo's brave consequences) can
kill a schema; any other failure changes nothing, so failure sets are enumerated over those
"relevant" components only and the rest are counted in by combinatorics when the shares of
all k-failure sets are computed.

Two facts keep solver calls rare. A superset of a killing set kills (failures only remove
candidates), and a set that misses every component of a known surviving configuration (the
witness of one of its subsets) survives with that configuration. Only the remaining sets go
to the solver, in chunks, through ``evaluate_chunk``: a pure function of a picklable
``Chunk`` that grounds the schema once and solves each set under assumptions, so it can run
in a process pool here or on Dask/Ray workers unchanged (docs/whatif.md).
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass, field

import clingo

from rosreconf.analysis.marginals import Marginals, marginals
from rosreconf.analysis.workers import executor as open_executor
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.emptyroles import as_chosen
from rosreconf.solve.factors import TooHard, paused_gc
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import PROGRAM, _facts, first_configuration


@dataclass(frozen=True)
class Task:
    """Everything a worker needs to solve one schema under failures (plain, picklable data).

    Attributes:
        schema: the schema's name.
        program: the ASP program with the schema's ground facts.
        roles: role names, by role index.
        components: component names, by component id.
        atoms: component name -> the (role index, component id) pairs it may fill.
    """

    schema: str
    program: str
    roles: tuple[str, ...]
    components: tuple[str, ...]
    atoms: Mapping[str, tuple[tuple[int, int], ...]]


@dataclass(frozen=True)
class Chunk:
    """A unit of work: some failure sets of one task."""

    task: Task
    failure_sets: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class Outcome:
    """Whether a schema survives one failure set.

    Attributes:
        failed: the failed components, in library order.
        configuration: the surviving configuration's components in role order, or None
            when the schema has no configuration under these failures.
        solved: True when the solver decided it, False when pruning did.
    """

    failed: tuple[str, ...]
    configuration: tuple[str, ...] | None
    solved: bool = True

    @property
    def survives(self) -> bool:
        """Tell whether the schema still has a configuration."""
        return self.configuration is not None


def make_task(library: ComponentLibrary, schema: InteroperabilitySchema) -> Task:
    """Compile ``schema`` over ``library`` into a worker's task description."""
    inst = compile_instance(library, schema)
    # the instance's library: the library with each optional role's empty choice after it
    ids = {c.name: i for i, c in enumerate(inst.library.components)}
    atoms: dict[str, list[tuple[int, int]]] = {}
    for r, dom in enumerate(inst.domains):
        for c in dom:
            atoms.setdefault(c.name, []).append((r, ids[c.name]))
    return Task(
        schema.name,
        PROGRAM + _facts(inst),
        tuple(r.name for r in inst.roles),
        tuple(as_chosen(c.name) for c in inst.library.components),
        {name: tuple(pairs) for name, pairs in atoms.items()},
    )


def _control(task: Task, args: Sequence[str]) -> clingo.Control:
    ctl = clingo.Control(["--warn=none", *args])
    ctl.add("base", [], task.program)
    ctl.ground([("base", [])])
    return ctl


def evaluate_chunk(chunk: Chunk) -> list[Outcome]:
    """Solve every failure set of ``chunk`` (one grounding, one solve per set)."""
    task = chunk.task
    ctl = _control(task, ["--heuristic=Domain", "--models=1"])
    out = []
    for failed in chunk.failure_sets:
        assumptions = [
            (clingo.Function("x", [clingo.Number(r), clingo.Number(c)]), False)
            for name in failed
            for r, c in task.atoms.get(name, ())
        ]
        found: list[tuple[str, ...]] = []
        ctl.solve(assumptions=assumptions, on_model=functools.partial(_keep, task, found))
        out.append(Outcome(tuple(failed), found[0] if found else None))
    return out


def _keep(task: Task, found: list[tuple[str, ...]], model: clingo.Model) -> None:
    chosen = {s.arguments[0].number: s.arguments[1].number for s in model.symbols(shown=True)}
    picked = (task.components[chosen[r]] for r in range(len(task.roles)))
    found.append(tuple(name for name in picked if name))  # an empty optional role: nothing


def evaluate(task: Task, failed: Iterable[str]) -> Outcome:
    """Solve one failure set (the single-set form of ``evaluate_chunk``)."""
    return evaluate_chunk(Chunk(task, (tuple(failed),)))[0]


def relevant_components(task: Task) -> frozenset[str]:
    """Return the components that appear in some valid configuration (brave consequences)."""
    ctl = _control(task, ["--enum-mode=brave", "--models=0"])
    last: list[str] = []

    def on_model(model: clingo.Model) -> None:
        picked = (task.components[s.arguments[1].number] for s in model.symbols(shown=True))
        last[:] = [name for name in picked if name]  # an empty optional role is no component

    result = ctl.solve(on_model=on_model)
    return frozenset(last) if result.satisfiable else frozenset()


@dataclass
class SchemaReport:
    """What failures do to one schema.

    Attributes:
        schema: the schema's name.
        components: the library's size N (every component may fail).
        relevant: components in some valid configuration, in library order.
        outcomes: failure set (over relevant components) -> outcome, for sizes 0..K.
        solver_calls: failure sets the solver decided (the rest were pruned).
    """

    schema: str
    components: int
    relevant: tuple[str, ...]
    outcomes: dict[frozenset[str], Outcome] = field(default_factory=dict)
    solver_calls: int = 0

    @property
    def critical(self) -> list[str]:
        """Return the components whose failure alone kills the schema."""
        return [c for c in self.relevant if not self._survives(frozenset((c,)))]

    @property
    def critical_pairs(self) -> list[tuple[str, str]]:
        """Return the pairs that kill the schema although neither failure alone does.

        Read from the decided pairs, not from every pair of relevant components (with 7,500
        relevant components that loop alone was 28 million sets even at one failure).
        """
        rank = {c: i for i, c in enumerate(self.relevant)}
        pairs = []
        for key, outcome in self.outcomes.items():
            if len(key) != 2 or outcome.survives:
                continue
            a, b = sorted(key, key=rank.__getitem__)
            if self._survives(frozenset((a,))) and self._survives(frozenset((b,))):
                pairs.append((a, b))
        return sorted(pairs, key=lambda ab: (rank[ab[0]], rank[ab[1]]))

    def _survives(self, failed: frozenset[str]) -> bool:
        outcome = self.outcomes.get(failed)
        return outcome is not None and outcome.survives

    def survived(self, k: int) -> tuple[int, int]:
        """Return (surviving, all) k-failure sets over the whole library (exact integers)."""
        n, m = self.components, len(self.relevant)
        by_size = [0] * (k + 1)
        for failed, outcome in self.outcomes.items():
            if len(failed) <= k and outcome.survives:
                by_size[len(failed)] += 1
        alive = sum(by_size[j] * math.comb(n - m, k - j) for j in range(k + 1))
        return alive, math.comb(n, k)


Progress = Callable[[int], None]
"""Called with the number of failure sets just decided (for a progress display)."""


def analyse(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    max_failures: int = 2,
    executor: Executor | None = None,
    progress: Progress | None = None,
    chunk_size: int = 64,
) -> SchemaReport:
    """Decide every failure set of up to ``max_failures`` relevant components of ``schema``.

    The relevant components, the first configuration and which single failures kill the
    schema come from counting's marginals (``rosreconf.analysis.marginals``) when the system
    graph is sparse enough to eliminate; clingo is grounded only if some set is left to
    solve (a surviving single failure of the first configuration needs its witness).
    """
    with paused_gc():
        inst = compile_instance(library, schema)
    try:
        marg: Marginals | None = marginals(inst)
    except TooHard:
        marg = None
    task: Task | None = None
    if marg is None:
        task = make_task(library, schema)
        relevant = relevant_components(task)
        base = evaluate(task, ())
    else:
        relevant = frozenset(marg.usable())
        first = first_configuration(inst) if marg.total else None
        base = Outcome((), None if first is None else first.components)
    in_every = frozenset(marg.in_every()) if marg is not None else frozenset()
    order = tuple(c.name for c in library.components if c.name in relevant)
    report = SchemaReport(schema.name, len(library), order)
    report.outcomes[frozenset()] = base
    report.solver_calls = 1
    if not base.survives:
        return report
    for k in range(1, max_failures + 1):
        pending: list[tuple[str, ...]] = []
        for failed in itertools.combinations(order, k):
            decided = _prune(report.outcomes, failed)
            if decided is None and k == 1 and failed[0] in in_every:
                decided = Outcome(failed, None, solved=False)
            if decided is None:
                pending.append(failed)
            else:
                report.outcomes[frozenset(failed)] = decided
        if pending and task is None:
            task = make_task(library, schema)
        if progress:
            progress(math.comb(len(order), k) - len(pending))
        chunks = (
            []
            if task is None
            else [
                Chunk(task, tuple(pending[i : i + chunk_size]))
                for i in range(0, len(pending), chunk_size)
            ]
        )
        for outcomes in _run(chunks, executor):
            for outcome in outcomes:
                report.outcomes[frozenset(outcome.failed)] = outcome
            report.solver_calls += len(outcomes)
            if progress:
                progress(len(outcomes))
    return report


SchemaProgress = Callable[[InteroperabilitySchema, int], None]
"""Called with 0 when a schema's analysis starts, then with each number of sets decided."""


def sweep(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    max_failures: int = 2,
    workers: int | None = None,
    cluster: str | None = None,
    progress: SchemaProgress | None = None,
) -> list[SchemaReport]:
    """Analyse every schema on one pool: local worker processes, or a Dask cluster.

    The pool is ``rosreconf.analysis.workers.executor`` (``--workers N`` / ``--cluster
    ADDRESS``), the one that also runs ``simulate``'s sweep, so both commands run their units
    of work the same way. ``progress`` is how a caller shows progress: this never prints.

    Raises:
        UsageError: both ``workers`` and ``cluster`` were given.
        ExternalToolError: the cluster cannot be reached (or ``distributed`` is missing).
    """
    reports = []
    with open_executor(workers, cluster) as pool:
        for schema in schemas:
            tick = None if progress is None else functools.partial(progress, schema)
            if tick is not None:
                tick(0)
            reports.append(analyse(library, schema, max_failures, pool, tick))
    return reports


def _prune(known: dict[frozenset[str], Outcome], failed: tuple[str, ...]) -> Outcome | None:
    """Decide ``failed`` from its subsets' outcomes, or return None when the solver must."""
    as_set = frozenset(failed)
    witnesses = []
    for drop in failed:
        sub = known[as_set - {drop}]
        if sub.configuration is None:
            return Outcome(failed, None, solved=False)
        witnesses.append(sub.configuration)
    for config in witnesses:
        if as_set.isdisjoint(config):
            return Outcome(failed, config, solved=False)
    return None


def _run(chunks: list[Chunk], executor: Executor | None) -> Iterable[list[Outcome]]:
    if executor is None or len(chunks) < 2:
        for chunk in chunks:
            yield evaluate_chunk(chunk)
        return
    futures = [executor.submit(evaluate_chunk, chunk) for chunk in chunks]
    for future in as_completed(futures):
        yield future.result()
