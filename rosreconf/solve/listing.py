"""List or count one schema's valid configurations, streaming, and say why there are none.

``rosreconf enumerate`` drives a ``Listing`` per schema: it iterates ``configurations()``
(flat memory: each is reported as soon as clingo finds it) and then reads ``total`` and
``why_not``. Counting without listing uses the exact counter (``rosreconf.solve.counting``)
and falls back to clingo's enumeration when the counter cannot decompose the schema.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.solve.counting import CountTooHard, count
from rosreconf.solve.factors import paused_gc
from rosreconf.solve.instance import Instance, compile_instance
from rosreconf.solve.objective import Objective
from rosreconf.solve.solver import ClingoEngine, first_configuration, optimise
from rosreconf.solve.unfillable import explain


class Listing:
    """The valid configurations of one schema under failures, listed once or counted.

    Attributes:
        schema: the schema.
        limit: stop listing after this many (None: all).
        count_only: count exactly instead of listing.
        total: how many there are, once known (None: the limit stopped the listing).
        listed: how many ``configurations()`` yielded.
        first: the first configuration (listed, or found for a picture when counting).
        why_not: why there is none (None unless ``total`` is 0).
        best: the objective ``--best`` minimises (None: list or count).
        optimum: with ``best``, the weights, the optimum's weighted sum and the engine that
            proved it (None when there is no configuration).
        counted_by_listing: exact counting would have needed too large a table, so the count
            was made by listing every configuration (slow; the CLI says so).
    """

    def __init__(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        failed: Collection[str],
        *,
        limit: int | None = None,
        count_only: bool = False,
        want_first: bool = False,
        best: Objective | None = None,
    ) -> None:
        self.schema = schema
        self.limit = limit
        self.count_only = count_only
        self.best = best
        with paused_gc():  # compiling allocates many small tuples; collections would find none
            self._inst = compile_instance(library, schema, failed)
        self.total: int | None = None
        self.listed = 0
        self.first: Configuration | None = None
        self.why_not: str | None = None
        self.optimum: dict[str, object] | None = None
        self.counted_by_listing = False
        if count_only:
            try:
                self.total = count(self._inst)
            except CountTooHard:  # said in the output: the user asked for a count, not a list
                self.counted_by_listing = True
                self.total = sum(1 for _ in ClingoEngine().configurations(self._inst))
            if want_first and self.total:
                self.first = first_configuration(self._inst)
            self._finish()

    def configurations(self) -> Iterator[Configuration]:
        """Yield the configurations in the solver's deterministic order (none when counting)."""
        if self.count_only:
            return
        if self.best is not None:
            yield from self._optimum(self.best)
            return
        for n, config in enumerate(_listed(self._inst, self.limit), 1):
            self.listed = n
            if n == 1:
                self.first = config
            yield config
        limited = self.limit is not None and self.listed >= self.limit
        self.total = None if limited else self.listed
        self._finish()

    def _optimum(self, objective: Objective) -> Iterator[Configuration]:
        """Yield the proven optimum alone; ``total`` stays None (not counted) unless none."""
        found = optimise(self._inst, objective)
        if found.configuration is None:
            self.total = 0
            self._finish()
            return
        self.listed = 1
        self.first = found.configuration
        self.optimum = {
            "weights": dict(objective.weights),
            "weighted_sum": objective.score(self._inst, found.configuration)[1],
            "engine": found.engine,
        }
        yield found.configuration

    def _finish(self) -> None:
        self.why_not = explain(self._inst) if self.total == 0 else None


def _listed(inst: Instance, limit: int | None) -> Iterator[Configuration]:
    """Yield configurations in enumeration order; the first alone comes without clingo.

    ``--limit 1`` needs only the first, which counting's tables give by elimination
    (``first_configuration``) without clingo's grounding, the larger part of clingo's time on
    large libraries; tests/test_first.py holds it to clingo's first.
    """
    if limit == 1:
        found = first_configuration(inst)
        yield from () if found is None else (found,)
        return
    yield from ClingoEngine().configurations(inst, limit)
