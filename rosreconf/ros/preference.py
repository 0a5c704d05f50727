"""Return to the configuration a failure made ``watch`` leave, once it is whole again.

A failure moves the watcher to the fewest-change configuration without the failed component
(``replanning``). That one is valid, but it is not what the team chose: with
``--prefer-after S``, the configuration in effect before the first failure (the
**preferred** one) is remembered, and ``watch --apply`` returns to it once every one of its
components has been a candidate (neither failed nor held) for ``S`` seconds without a break.

Never flapping between two configurations rests on three things: the return waits ``S``
seconds of its components being candidates (a released component that fails again before
then resets the wait); a component that fails after a return is held again, each hold
twice as long as the one before (``restarts.Restarts``' backoff); and a return is a planned
switch, made only while nothing is failing or being confirmed. The return is the event
``return``, with its changes; nothing here prints or acts.

With ``--prefer METRIC=WEIGHT`` (the weights of ``enumerate --best --objective``), the
watcher also moves to the best configuration by those weights among the ones it may use
now (no component failed, held, or ruled out by context) whenever its weighted metric sum
is less than the running one's: after context ruled a better component out and the
readings allow it again, or after a hold is over. It cannot flap: a move needs a sum
strictly less, so two configurations cannot each be better than the other under one set of
usable components, and that set changes only after context's dwell (``livecontext``) or a
failure's hold (``restarts``). The move is the event ``prefer``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection
from dataclasses import dataclass, field
from typing import Any

from rosreconf.model import EMPTY, ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.ros.replanning import Change, changes_between, changes_data, changes_text
from rosreconf.solve.objective import METRIC_SCALE, Objective, scaled_metric
from rosreconf.solve.solver import best_configuration

Say = Callable[..., None]


@dataclass
class Preference:
    """Remember the configuration left after a failure; say when to go back to it.

    Attributes:
        say: how the return is said.
        after: seconds every component of the preferred configuration must have been a
            candidate before the return (``--prefer-after``; 0: never return).
        preferred: the configuration left at the first failure (None: none left, or back).
        since: when the preferred configuration's components last became all candidates.
        weights: metric -> weight (``--prefer``; empty: no move to a better configuration).
    """

    say: Say
    after: float = 0.0
    preferred: Configuration | None = None
    since: float | None = None
    weights: tuple[tuple[str, float], ...] = ()
    _best: tuple[Any, Configuration | None] | None = field(default=None, repr=False)

    def leaving(self, current: Configuration) -> None:
        """Remember ``current`` as the one to return to, unless one is remembered already.

        After two failures in a row the first configuration stays the preferred one: it is
        the team's, the one in between was only the watcher's.
        """
        if self.after > 0 and self.preferred is None:
            self.preferred = current

    def due(self, current: Configuration, unavailable: Collection[str]) -> Configuration | None:
        """Return the preferred configuration when it is time to go back to it, else None.

        ``unavailable``: the components failed or held now.
        """
        preferred = self.preferred
        if preferred is None or preferred.mapping == current.mapping:
            self.preferred = self.since = None  # back (by a replan, or by hand)
            return None
        if set(preferred.components) & set(unavailable):
            self.since = None  # not whole: the wait starts again when it is
            return None
        now = time.monotonic()
        if self.since is None:
            self.since = now
        if now - self.since < self.after:
            return None
        self.preferred = self.since = None
        return preferred

    def returning(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        current: Configuration,
        unavailable: Collection[str],
    ) -> tuple[Configuration, list[Change]] | None:
        """Return the preferred configuration and the changes back to it, when it is time
        (``due``; said, event ``return``), else None.
        """
        back = self.due(current, unavailable)
        if back is None:
            return None
        changes = changes_between(library, schema, current, back)
        self.say(
            "return",
            f"returning to the configuration left after a failure (its components have been "
            f"candidates for {self.after:g} s): {len(changes)} change(s): "
            f"{changes_text(changes)}",
            configuration=back.shown,
            changes=changes_data(changes),
        )
        return back, changes

    def better(
        self,
        library: ComponentLibrary,
        schema: InteroperabilitySchema,
        current: Configuration,
        unavailable: Collection[str],
    ) -> tuple[Configuration, list[Change]] | None:
        """With ``weights``, return the best configuration by them and the changes to it,
        when its weighted metric sum is strictly less than ``current``'s (said, event
        ``prefer``); else None. ``unavailable``: the components failed, held or ruled out.
        """
        if not self.weights:
            return None
        objective = Objective(weights=dict(self.weights))
        key = (schema.name, frozenset(unavailable))
        if self._best is None or self._best[0] != key:  # solved again only when it changed
            self._best = key, _best(library, schema, objective, unavailable)
        best = self._best[1]
        if best is None or best.mapping == current.mapping:
            return None
        now, then = (_sum(objective, library, c) for c in (current, best))
        if then >= now:
            return None
        changes = changes_between(library, schema, current, best)
        weights = " ".join(f"{m}={w:g}" for m, w in self.weights)
        self.say(
            "prefer",
            f"moving to the best configuration by --prefer {weights} (weighted metric sum "
            f"{then / METRIC_SCALE:g}, now {now / METRIC_SCALE:g}): {len(changes)} change(s): "
            f"{changes_text(changes)}",
            configuration=best.shown,
            changes=changes_data(changes),
            metric=then / METRIC_SCALE,
            previous_metric=now / METRIC_SCALE,
        )
        return best, changes


def _best(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    objective: Objective,
    unavailable: Collection[str],
) -> Configuration | None:
    """Return the best configuration by ``objective``'s weights without ``unavailable``; one
    that meets the schema's performance requirements, when it has some (``analysis.choice``;
    None too when the search for one is spent: no move is better than a guess)."""
    best = best_configuration(library, schema, objective, unavailable)
    if best is None or schema.simulation is None:
        return best
    from rosreconf.analysis.choice import SearchExhausted, choose  # imports numpy

    try:
        weights = dict(objective.weights)
        return choose(library, schema, best, {}, weights, unavailable).configuration
    except SearchExhausted:
        return None


def _sum(objective: Objective, library: ComponentLibrary, config: Configuration) -> int:
    """Return ``config``'s weighted metric sum, scaled as the solvers compare it."""
    known = library.by_name
    return sum(scaled_metric(objective, known[c]) for _, c in config.assignment if c != EMPTY)
