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
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection
from dataclasses import dataclass

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.ros.replanning import Change, changes_between, changes_data, changes_text

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
    """

    say: Say
    after: float = 0.0
    preferred: Configuration | None = None
    since: float | None = None

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
