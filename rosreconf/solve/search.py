"""Walk valid configurations in order of the objective, forbidding what failed: lazily.

``plan`` and ``watch`` need the best configuration (fewest changes, then the weighted metrics)
that also meets the schema's performance requirements. Whether a configuration performs is
known only by simulating its loops, and a loop's result depends only on the components in
its roles. So the search is counterexample-guided: ask clingo for the optimum, simulate its
loops, and for every loop that fails forbid that assignment of its roles (a nogood) before
asking again. Each optimum is the best configuration that contains no assignment known to
fail, so the first one that performs is the best that performs; every failing answer adds
at least one nogood, so the walk ends. Memory grows with the nogoods and simulated loops
(bounded by the caller's budget), never with the number of valid configurations: each
question grounds the instance and the nogoods afresh, and nothing else is kept.

``at_level`` lists the configurations with exactly a given number of changes (for an
objective on simulated figures, which are not sums over roles), streaming, under the same
nogoods.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rosreconf.model import Configuration
from rosreconf.solve.emptyroles import as_candidate
from rosreconf.solve.instance import Instance
from rosreconf.solve.objective import Objective
from rosreconf.solve.solver import OPTIMISE, PROGRAM, _facts, _Reader

if TYPE_CHECKING:
    import clingo

SEARCH_LIMIT = 2000
"""Default most configurations ``choose`` simulates before giving up (``--search-limit``)."""

SEARCH_TIME = 120.0
"""Default most seconds ``analysis.choice.choose`` searches before giving up (``--search-time``)."""


@dataclass(frozen=True)
class Budget:
    """How far ``analysis.choice.choose`` may search for a configuration that performs.

    Attributes:
        configurations: the most configurations simulated (each distinct loop once).
        seconds: the most wall-clock seconds spent searching (None: no limit).
    """

    configurations: int = SEARCH_LIMIT
    seconds: float | None = SEARCH_TIME


CHANGED = "changed(R) :- x(R,C), current(R,D), C != D.\n"


class OutOfTime(Exception):
    """The search's deadline passed while clingo was solving."""


class Search:
    """Clingo questions over one instance, with nogoods added as the walk goes.

    Attributes:
        nogoods: how many role assignments have been forbidden so far.
    """

    def __init__(self, inst: Instance, objective: Objective, deadline: float | None) -> None:
        """Prepare the instance's facts; ``deadline`` is a ``time.monotonic()`` instant or None."""
        self._inst = inst
        self._objective = objective
        self._deadline = deadline
        self._ids = {c.name: i for i, c in enumerate(inst.library.components)}
        self._roles = inst.role_index
        self._facts = _facts(inst, objective)
        self._forbidden: list[str] = []
        self._empty = any(not d for d in inst.domains)
        self._read = _Reader(inst)
        self.nogoods = 0

    def _control(self, program: str, args: list[str]) -> clingo.Control:
        import clingo

        ctl = clingo.Control(["--warn=none", *args])
        ctl.add("base", [], program + CHANGED)
        ctl.add("base", [], self._facts)
        for rule in self._forbidden:
            ctl.add("base", [], rule)
        ctl.ground([("base", [])])
        return ctl

    def forbid(self, assignment: Iterable[tuple[str, str]]) -> None:
        """Forbid every configuration that puts these components in these roles together.

        An optional role left empty (``EMPTY``) is its empty choice here, as in the tables.
        """
        ids = self._ids
        body = ", ".join(f"x({self._roles[r]},{ids[as_candidate(r, c)]})" for r, c in assignment)
        self._forbidden.append(f":- {body}.\n")
        self.nogoods += 1

    def best(self) -> Configuration | None:
        """Return the optimum under the nogoods so far (None: nothing valid is left).

        Raises:
            OutOfTime: the deadline passed first.
        """
        if self._empty:
            return None
        found: list[Configuration] = []

        def keep(model: clingo.Model) -> None:
            found.append(self._read(model))

        # grounded afresh each time: one control kept across solves grew by the cores its
        # optimisation learnt (250 MB a round at 1000 roles), a fresh one stays flat
        ctl = self._control(PROGRAM + OPTIMISE, ["--opt-mode=opt", "--opt-strategy=usc"])
        self._solve(ctl, keep)
        # each model improves on the last; the final one is optimal
        return found[-1] if found else None

    def at_level(self, changes: int) -> Iterator[Configuration]:
        """Yield the configurations with exactly ``changes`` changes, under the nogoods.

        Raises:
            OutOfTime: the deadline passed (between two configurations or while solving).
        """
        if self._empty:
            return
        rule = f":- not {changes} #count {{ R : changed(R) }} {changes}.\n"
        ctl = self._control(PROGRAM + rule, ["--models=0", "--heuristic=Domain", "--enum-mode=bt"])
        with ctl.solve(yield_=True, async_=True) as handle:
            while True:
                handle.resume()
                if not handle.wait(self._remaining()):
                    handle.cancel()
                    raise OutOfTime
                model = handle.model()
                if model is None:
                    return
                yield self._read(model)

    def _remaining(self) -> float:
        """Return the seconds left before the deadline (a large number when there is none)."""
        if self._deadline is None:
            return 1e9
        return max(0.0, self._deadline - time.monotonic())

    def _solve(self, ctl: clingo.Control, on_model: Callable[[clingo.Model], None]) -> None:
        """Solve ``ctl`` in the background, giving up when the deadline passes."""
        with ctl.solve(on_model=on_model, async_=True) as handle:
            if not handle.wait(self._remaining()):
                handle.cancel()
                raise OutOfTime
