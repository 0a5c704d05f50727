"""Find which failure sets each schema survives, and with which configuration.

Only components that appear in some valid configuration (clingo's brave consequences) can
kill a schema; any other failure changes nothing, so failure sets are enumerated over those
"relevant" components only and the rest are counted in by combinatorics when the shares of
all k-failure sets are computed.

Two facts keep solver calls rare. A superset of a killing set kills (failures only remove
candidates), and a set that misses every component of a known surviving configuration (the
witness of one of its subsets) survives with that configuration. Only the remaining sets go
to the solver, in chunks, through ``evaluate_chunk`` (``failsolve``): a pure function of a picklable
``Chunk`` that grounds the schema once and solves each set under assumptions, so it can run
in a process pool here or on Dask/Ray workers unchanged (docs/whatif.md).
"""

from __future__ import annotations

import functools
import itertools
import math
import time
from collections.abc import Callable, Collection, Iterable, Iterator, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field

from rosreconf.analysis.failsolve import (
    Chunk,
    Outcome,
    Task,
    evaluate,
    evaluate_chunk,
    make_task,
    relevant_components,
)
from rosreconf.analysis.marginals import Marginals, marginals
from rosreconf.analysis.results import Results
from rosreconf.analysis.workers import executor as open_executor
from rosreconf.errors import ExternalToolError
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.factors import TooHard, paused_gc
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import ClingoEngine, first_configuration
from rosreconf.solve.swaps import Swapped, Swaps

__all__ = [  # the unit of work lives in failsolve; these names are its documented way in
    "LISTED",
    "Chunk",
    "Outcome",
    "SchemaReport",
    "SweepOutOfTime",
    "Task",
    "analyse",
    "evaluate",
    "evaluate_chunk",
    "make_task",
    "relevant_components",
    "sweep",
]

LISTED = 10_000
"""Most failure sets a report keeps for listing (the JSON's ``failure_sets``), fewest first.

Every set used to be kept: ``-k 2`` on 1000 roles x 10 candidates reached 8.9 GB.
The summaries (shares, critical components and pairs) are reduced from every set as it is
decided; only sets smaller than the largest asked for are kept whole, for pruning."""


@dataclass
class SchemaReport:
    """What failures do to one schema.

    Attributes:
        schema: the schema's name.
        components: the library's size N (every component may fail).
        relevant: components in some valid configuration, in library order.
        outcomes: failure set (over relevant components) -> outcome, for sizes below the
            largest asked for (and single failures always): what pruning reads.
        solver_calls: failure sets the solver decided (the rest were pruned).
        alive_by_size: per size j, the surviving j-sets over the relevant components.
        decided_by_size: per size j, the j-sets decided so far.
        listed: the first ``LISTED`` failure sets by (size, names), for the JSON listing.
        listed_all: ``listed`` holds every decided failure set.
    """

    schema: str
    components: int
    relevant: tuple[str, ...]
    outcomes: dict[frozenset[str], Outcome] = field(default_factory=dict)
    solver_calls: int = 0
    alive_by_size: list[int] = field(default_factory=list)
    decided_by_size: list[int] = field(default_factory=list)
    listed: list[Outcome] = field(default_factory=list)
    listed_all: bool = True
    _pairs: list[tuple[str, str]] = field(default_factory=list)

    def note(self, outcome: Outcome, *, keep: bool) -> None:
        """Reduce one decided failure set into the summaries; keep it whole when ``keep``."""
        size = len(outcome.failed)
        while len(self.alive_by_size) <= size:
            self.alive_by_size.append(0)
            self.decided_by_size.append(0)
        self.alive_by_size[size] += outcome.survives
        self.decided_by_size[size] += 1
        if keep:
            self.outcomes[frozenset(outcome.failed)] = outcome
        if size == 2 and not outcome.survives:
            a, b = outcome.failed
            if self._survives(frozenset((a,))) and self._survives(frozenset((b,))):
                self._pairs.append((a, b))
        self.listed.append(outcome)
        if len(self.listed) >= 2 * LISTED:
            self._trim()

    def _trim(self) -> None:
        self.listed.sort(key=lambda o: (len(o.failed), o.failed))
        if len(self.listed) > LISTED:
            del self.listed[LISTED:]
            self.listed_all = False

    def finish(self) -> None:
        """Sort and bound ``listed`` once every set is decided."""
        self._trim()

    @property
    def critical(self) -> list[str]:
        """Return the components whose failure alone kills the schema."""
        return [c for c in self.relevant if not self._survives(frozenset((c,)))]

    @property
    def critical_pairs(self) -> list[tuple[str, str]]:
        """Return the pairs that kill the schema although neither failure alone does.

        Reduced from the decided pairs as they come, not from every pair of relevant
        components (with 7,500 relevant components that loop alone was 28 million sets).
        """
        rank = {c: i for i, c in enumerate(self.relevant)}
        pairs = [tuple(sorted(ab, key=rank.__getitem__)) for ab in self._pairs]
        return sorted(((a, b) for a, b in pairs), key=lambda ab: (rank[ab[0]], rank[ab[1]]))

    def _survives(self, failed: frozenset[str]) -> bool:
        outcome = self.outcomes.get(failed)
        return outcome is not None and outcome.survives

    def survived(self, k: int) -> tuple[int, int]:
        """Return (surviving, all) k-failure sets over the whole library (exact integers)."""
        n, m = self.components, len(self.relevant)
        by_size = [
            self.alive_by_size[j] if j < len(self.alive_by_size) else 0 for j in range(k + 1)
        ]
        alive = sum(by_size[j] * math.comb(n - m, k - j) for j in range(k + 1))
        return alive, math.comb(n, k)


SWEEP_TIME = 600.0
"""Default most seconds a ``whatif`` sweep takes before it stops with exit 3 (``--search-time``).

``-k 2`` on 1000 roles x 10 candidates ran past 300 s: C(9962, 2) pairs, and a
solve for every pair of the first configuration's components without a working twin."""


Progress = Callable[[int], None]
"""Called with the number of failure sets just decided (for a progress display)."""


def analyse(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    max_failures: int = 2,
    executor: Executor | None = None,
    progress: Progress | None = None,
    chunk_size: int = 64,
    deadline: float | None = None,
    failed: Collection[str] = (),
) -> SchemaReport:
    """Decide every failure set of up to ``max_failures`` relevant components of ``schema``.

    The relevant components, the first configuration and which single failures kill the
    schema come from counting's marginals (``rosreconf.analysis.marginals``) when the system
    graph is sparse enough to eliminate; clingo is grounded only if some set is left to
    solve (a surviving single failure of the first configuration needs its witness).

    Raises:
        SweepOutOfTime: ``deadline`` (a ``time.monotonic()`` instant) passed first; it says
            which failure sets were decided.
    """
    with paused_gc():
        inst = compile_instance(library, schema, failed)
    try:
        marg: Marginals | None = marginals(inst)
    except TooHard:
        marg = None
    task: Task | None = None
    if marg is None:
        task = make_task(library, schema, failed)
        relevant = relevant_components(task)
        first = ClingoEngine().first(inst)
    else:
        relevant = frozenset(marg.usable())
        first = first_configuration(inst) if marg.total else None
    swaps = None if first is None else Swaps(inst, first)
    base = Outcome((), None if swaps is None else swaps.whole)
    in_every = frozenset(marg.in_every()) if marg is not None else frozenset()
    order = tuple(c.name for c in library.components if c.name in relevant)
    report = SchemaReport(schema.name, len(library), order)
    report.note(base, keep=True)
    report.solver_calls = 1
    if swaps is None:
        report.finish()
        return report
    for k in range(1, max_failures + 1):
        keep = k < max_failures or k == 1  # the largest sets are reduced, never kept whole
        pruned = 0

        def undecided(k: int = k, keep: bool = keep) -> Iterator[tuple[str, ...]]:
            nonlocal pruned
            for i, failed in enumerate(itertools.combinations(order, k)):
                if i % 1024 == 0:
                    _check(report, deadline, k)
                decided = _prune(report.outcomes, failed)
                if decided is None and k == 1 and failed[0] in in_every:
                    decided = Outcome(failed, None, solved=False)
                if decided is None and (twins := swaps.avoiding(failed)) is not None:
                    decided = Outcome(failed, twins, solved=False)
                if decided is None:
                    yield failed
                else:
                    report.note(decided, keep=keep)
                    pruned += 1

        pending = undecided()
        head = next(pending, None)
        if head is not None and task is None:
            task = make_task(library, schema, failed)
        chunks = (
            ()
            if task is None or head is None
            else _chunks(task, itertools.chain((head,), pending), chunk_size)
        )
        for outcomes in _run(chunks, executor):
            for outcome in outcomes:
                report.note(outcome, keep=keep)
            report.solver_calls += len(outcomes)
            _check(report, deadline, k)
            if progress:
                progress(len(outcomes) + pruned)
                pruned = 0
        if progress and pruned:
            progress(pruned)
    report.finish()
    return report


class SweepOutOfTime(ExternalToolError):
    """The sweep's time budget ran out before every failure set was decided (exit 3)."""


def _check(report: SchemaReport, deadline: float | None, k: int) -> None:
    """Raise ``SweepOutOfTime`` when ``deadline`` has passed, saying what was decided."""
    if deadline is None or time.monotonic() < deadline:
        return
    m = len(report.relevant)
    done = report.decided_by_size[k] if k < len(report.decided_by_size) else 0
    covered = (
        f"every set of up to {k - 1} failed component(s) was decided "
        f"(critical components: {', '.join(report.critical) or 'none'}), and "
        if k > 1
        else ""
    )
    raise SweepOutOfTime(
        f"schema '{report.schema}': {covered}{done:,} of the {math.comb(m, k):,} sets of "
        f"{k} failed component(s) (of its {m:,} relevant components) were decided "
        f"({report.solver_calls:,} solver call(s))"
    )


def _chunks(task: Task, sets: Iterable[tuple[str, ...]], size: int) -> Iterator[Chunk]:
    """Cut the failure sets into chunks as they come (never all of them at once)."""
    it = iter(sets)
    while batch := tuple(itertools.islice(it, size)):
        yield Chunk(task, batch)


SchemaProgress = Callable[[InteroperabilitySchema, int], None]
"""Called with 0 when a schema's analysis starts, then with each number of sets decided."""


def sweep(
    library: ComponentLibrary,
    schemas: Sequence[InteroperabilitySchema],
    max_failures: int = 2,
    workers: int | None = None,
    cluster: str | None = None,
    progress: SchemaProgress | None = None,
    seconds: float | None = None,
    *,
    failed: Collection[str] = (),
) -> list[SchemaReport]:
    """Analyse every schema on one pool: local worker processes, or a Dask cluster.

    The pool is ``rosreconf.analysis.workers.executor`` (``--workers N`` / ``--cluster
    ADDRESS``), the one that also runs ``simulate``'s sweep, so both commands run their units
    of work the same way. ``progress`` is how a caller shows progress: this never prints.

    ``seconds`` bounds the whole sweep (``--search-time``; None: no bound). ``failed``
    components (those context rules out) are gone in every failure set and in none swept.

    Raises:
        UsageError: both ``workers`` and ``cluster`` were given.
        ExternalToolError: the cluster cannot be reached (or ``distributed`` is missing).
        SweepOutOfTime: ``seconds`` passed before every failure set was decided.
    """
    reports = []
    deadline = None if seconds is None else time.monotonic() + seconds
    with open_executor(workers, cluster) as pool:
        for schema in schemas:
            tick = None if progress is None else functools.partial(progress, schema)
            if tick is not None:
                tick(0)
            try:
                reports.append(
                    analyse(
                        library, schema, max_failures, pool, tick, deadline=deadline, failed=failed
                    )
                )
            except SweepOutOfTime as exc:
                done = f"; {len(reports)} schema(s) before it were swept" if reports else ""
                raise SweepOutOfTime(
                    f"the what-if sweep ran out of its time (--search-time {seconds:g}): "
                    f"{exc}{done} (raise --search-time, or lower --max-failures)"
                ) from None
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
    for config in witnesses:  # a swapped view answers ``in`` in O(1), a tuple in O(roles)
        if isinstance(config, Swapped) and not any(f in config for f in failed):
            return Outcome(failed, config, solved=False)
        if not isinstance(config, Swapped) and as_set.isdisjoint(config):
            return Outcome(failed, config, solved=False)
    return None


IN_FLIGHT = 64
"""Most chunks handed to the pool at once: the rest are made only as results come back."""


def _run(chunks: Iterable[Chunk], executor: Executor | None) -> Iterable[list[Outcome]]:
    """Yield each chunk's outcomes; in the pool, at most ``IN_FLIGHT`` chunks at a time."""
    if executor is None:
        for chunk in chunks:
            yield evaluate_chunk(chunk)
        return
    results: Results[list[Outcome]] = Results()
    for chunk in chunks:
        results.watch(executor.submit(evaluate_chunk, chunk))
        if results.pending >= IN_FLIGHT:
            yield results.next()[1]
    while results.pending:
        yield results.next()[1]
