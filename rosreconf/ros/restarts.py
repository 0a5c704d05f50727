"""Restart in place, hold and release: what ``watch`` does with a component that failed.

Replacing a failed component moves its role to another one and often rewires its neighbours
(ten changes when NSM3 fails). Restarting the same component costs one change, the least any
repair can cost (its role must change or restart), and keeps the configuration and its
wiring: so, when allowed, it is the repair. systemd and Nav2 do the same, with a limit:

- ``limit``: restarts in place allowed per ``window`` seconds (systemd's ``StartLimitBurst``
  and ``StartLimitIntervalSec``) while another configuration is left; 0 turns that off. A
  component that fails more often is **held** failed: the configuration moves away from it.
- ``hold``: how long a held component stays failed. Then it is **released**: a candidate
  again (event ``release``). A configuration that had to leave it is kept (no flapping back
  and forth) unless ``--prefer-after`` says to return to it (``preference``).
- Backoff: a component held again within ``BACKOFF_MEMORY`` holds of its release is held
  twice as long as the time before (at most ``MAX_BACKOFF`` times ``hold``), as systemd's
  ``RestartSteps`` and ``RestartMaxDelaySec`` lengthen its restart delay.
- **The last resort** (``last_resort``): when no configuration is left without a failed
  component, holding it would leave the robot without the skill for a whole hold (a
  minute by default) where a restart brings it back in a fraction of a second. So it is
  restarted in place whatever ``limit`` says, at once the first time, then after a backoff
  that doubles from ``FIRST_BACKOFF`` up to ``hold`` while it keeps failing within
  ``window`` seconds of its last restart (as Kubernetes' CrashLoopBackOff): a component that
  can never start is tried again once per ``hold``, never in a hot loop. Without
  ``--apply`` nothing is started, and it is held as any other.

Every decision is an event: ``restart`` (with the crashes counted in the window; a last
resort with its ``attempt`` in a row and the ``seconds`` it waits first), ``hold`` (with why
and for how long), ``release``. Nothing here prints or acts: the watcher starts what is
restarted or released, and a last resort's restart once it is ``due``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection
from dataclasses import dataclass, field

RESTART_WINDOW = 60.0
"""Seconds over which restarts in place are counted (systemd's default interval is 10 s;
a robot's node that crashes three times in a minute is not going to stay up)."""
HOLD_SECONDS = 60.0
"""Seconds a failed component is held before it is a candidate again."""
MAX_BACKOFF = 8
"""The longest hold, in ``hold``s: 8 min at the default."""
BACKOFF_MEMORY = 10
"""A component released this many (longest) holds ago without failing starts from one hold."""
FIRST_BACKOFF = 1.0
"""Seconds before a last resort's second restart in a row (the first is at once); it doubles."""


@dataclass
class Restarts:
    """Decide, per failed component, restart in place or hold; release held ones in time.

    Attributes:
        say: how an event is said.
        role: the role a component fills, for the messages.
        limit: restarts in place allowed per ``window`` while another configuration is left
            (0: never).
        window: seconds over which restarts are counted, and within which a last resort's
            component that fails again backs off further.
        hold: seconds a held component stays failed; the longest backoff of a last resort.
        crashes: component -> when it failed (monotonic seconds), within the window.
        held: component -> when it is released (monotonic seconds).
        holds: component -> (its last hold's length, when it was released).
        backoff: component -> when its last resort's restart is due (monotonic seconds).
        streak: component -> (last resorts in a row, when the last one restarts it).
    """

    say: Callable[..., None]
    role: Callable[[str], str]
    limit: int = 0
    window: float = RESTART_WINDOW
    hold: float = HOLD_SECONDS
    crashes: dict[str, list[float]] = field(default_factory=dict)
    held: dict[str, float] = field(default_factory=dict)
    holds: dict[str, tuple[float, float]] = field(default_factory=dict)
    backoff: dict[str, float] = field(default_factory=dict)
    streak: dict[str, tuple[int, float]] = field(default_factory=dict)

    def _undecided(self, failed: Collection[str]) -> list[str]:
        """Return those of ``failed`` neither held nor waiting for a last resort's restart."""
        return sorted(set(failed) - set(self.held) - set(self.backoff))

    def restartable(self, failed: Collection[str], can_start: bool) -> set[str]:
        """Return those of ``failed`` to restart in place now, within ``limit`` (said).

        Each failure is counted. ``can_start``: whether the watcher may start processes
        (``--apply``). The others are for ``hold`` or ``last_resort``, once the replan tells
        whether a configuration is left without them.
        """
        now = time.monotonic()
        out: set[str] = set()
        for comp in self._undecided(failed):
            times = [t for t in self.crashes.get(comp, []) if now - t < self.window] + [now]
            self.crashes[comp] = times
            if can_start and len(times) <= self.limit:
                self.say(
                    "restart",
                    f"{comp} ({self.role(comp)}) restarts in place: 1 change, the fewest "
                    f"possible (failure {len(times)} of {self.limit} allowed in "
                    f"{self.window:g} s)",
                    component=comp,
                    crashes=len(times),
                )
                out.add(comp)
        return out

    def hold_failed(self, failed: Collection[str], can_start: bool, theirs: bool = False) -> None:
        """Hold ``failed`` (counted by ``restartable``): a candidate again after ``hold`` s.

        ``theirs``: rosreconf did not start them; what did (a launch file's respawn, a
        person) is given the hold to start them again (``last_resort``).
        """
        now = time.monotonic()
        for comp in self._undecided(failed):
            crashes = len(self.crashes.get(comp, [])) or 1
            seconds = self._hold_for(comp, now)
            self.held[comp] = now + seconds
            if theirs:
                why = (
                    "rosreconf did not start it: whatever did (a launch file's respawn, a "
                    "person) restarts it, and it is taken back when it runs again; rosreconf "
                    "starts its own only after the hold"
                )
            elif not can_start:
                why = "nothing is started without --apply"
            elif not self.limit:
                why = "restart in place is off: --restarts 0"
            else:
                why = f"{crashes} failures in {self.window:g} s, over the limit of {self.limit}"
            if seconds > self.hold:
                why += f"; held again after its release: {seconds / self.hold:g}x the hold"
            self.say(
                "hold",
                f"{comp} ({self.role(comp)}) is held failed for {seconds:g} s ({why}); "
                "then it is a candidate again",
                component=comp,
                seconds=seconds,
                crashes=crashes,
            )

    def last_resort(
        self, failed: Collection[str], can_start: bool, theirs: Collection[str] = ()
    ) -> set[str]:
        """Restart ``failed``, without which no configuration is left; return those due now.

        The first restart in a row is at once; each next one waits twice as long as the one
        before, from ``FIRST_BACKOFF`` up to ``hold`` (at least ``FIRST_BACKOFF``); a
        component that ran ``window`` seconds since its last restart starts a new row.
        The others are ``due`` later. Without ``can_start``, they are held. So are those of
        ``theirs`` (their process was not rosreconf's): what started it (a launch file's
        ``respawn``, a person) restarts it, and a start of rosreconf's would race that into
        two nodes of one name (``hold_failed``, ``theirs``).
        """
        if not can_start:
            self.hold_failed(failed, can_start)
            return set()
        self.hold_failed(set(failed) & set(theirs), can_start, theirs=True)
        failed = set(failed) - set(theirs)
        now = time.monotonic()
        out: set[str] = set()
        for comp in self._undecided(failed):
            row, last = self.streak.get(comp, (0, float("-inf")))
            row = row + 1 if now - last < self.window else 1
            longest = max(self.hold, FIRST_BACKOFF)
            seconds = 0.0 if row == 1 else min(FIRST_BACKOFF * 2 ** (row - 2), longest)
            self.streak[comp] = (row, now + seconds)
            when = "at once" if not seconds else f"in {seconds:g} s"
            again = (
                f"; restart {row} in a row: each waits twice as long, at most {longest:g} s"
                if row > 1
                else ""
            )
            self.say(
                "restart",
                f"{comp} ({self.role(comp)}) restarts in place {when}: no configuration is "
                f"left without it{again}",
                component=comp,
                crashes=len(self.crashes.get(comp, [])) or 1,
                attempt=row,
                seconds=seconds,
                last_resort=True,
            )
            if seconds:
                self.backoff[comp] = now + seconds
            else:
                out.add(comp)
        return out

    def due(self) -> set[str]:
        """Return the components whose last resort's restart is due now, and forget them."""
        now = time.monotonic()
        out = {comp for comp, at in self.backoff.items() if now >= at}
        for comp in out:
            del self.backoff[comp]
        return out

    def next_due(self) -> float | None:
        """Return when the next last resort's restart is due (monotonic seconds), if any."""
        return min(self.backoff.values(), default=None)

    def _hold_for(self, comp: str, now: float) -> float:
        """Return how long to hold ``comp`` now: twice its last hold if it was released lately."""
        last, released = self.holds.get(comp, (0.0, 0.0))
        if not last or now - released > BACKOFF_MEMORY * self.hold * MAX_BACKOFF:
            seconds = self.hold
        else:
            seconds = min(2 * last, MAX_BACKOFF * self.hold)
        self.holds[comp] = (seconds, float("inf"))
        return seconds

    def drop(self, comp: str) -> None:
        """End ``comp``'s hold now, unsaid: it runs again (restarted by hand, ``outsiders``).

        Counted as a release for the backoff: a failure soon after holds it longer.
        """
        if self.held.pop(comp, None) is not None:
            self.holds[comp] = (self.holds[comp][0], time.monotonic())

    def released(self) -> set[str]:
        """Return the held components whose hold is over (said), and forget their hold."""
        now = time.monotonic()
        out = {comp for comp, until in self.held.items() if now >= until}
        for comp in sorted(out):
            del self.held[comp]
            seconds = self.holds[comp][0]
            self.holds[comp] = (seconds, now)
            self.say(
                "release",
                f"{comp} is a candidate again ({seconds:g} s after it was held)",
                component=comp,
            )
        return out
