"""Restart in place, hold and release: what ``watch`` does with a component that failed.

Replacing a failed component moves its role to another one and often rewires its neighbours
(ten changes when NSM3 fails). Restarting the same component costs one change, the least any
repair can cost (its role must change or restart), and keeps the configuration and its
wiring: so, when allowed, it is the repair. systemd and Nav2 do the same, with a limit:

- ``limit``: restarts in place allowed per ``window`` seconds (systemd's ``StartLimitBurst``
  and ``StartLimitIntervalSec``); 0 turns restart in place off. A component that fails more
  often is **held** failed: the configuration moves away from it, as without restarts.
- ``hold``: how long a held component stays failed. Then it is **released**: a candidate
  again (event ``release``). A configuration that had to leave it is kept (no flapping back
  and forth) unless ``--prefer-after`` says to return to it (``preference``); when no
  configuration was left, ``watch`` tries again with it.
- Backoff: a component held again within ``BACKOFF_MEMORY`` holds of its release is held
  twice as long as the time before (at most ``MAX_BACKOFF`` times ``hold``), as systemd's
  ``RestartSteps`` and ``RestartMaxDelaySec`` lengthen its restart delay.

Every decision is an event: ``restart`` (with the crashes counted in the window), ``hold``
(with why and for how long), ``release``. Nothing here prints or acts: the watcher starts
what is restarted or released.
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


@dataclass
class Restarts:
    """Decide, per failed component, restart in place or hold; release held ones in time.

    Attributes:
        say: how an event is said.
        role: the role a component fills, for the messages.
        limit: restarts in place allowed per ``window`` (0: never restart in place).
        window: seconds over which restarts are counted.
        hold: seconds a held component stays failed.
        crashes: component -> when it failed (monotonic seconds), within the window.
        held: component -> when it is released (monotonic seconds).
        holds: component -> (its last hold's length, when it was released).
    """

    say: Callable[..., None]
    role: Callable[[str], str]
    limit: int = 0
    window: float = RESTART_WINDOW
    hold: float = HOLD_SECONDS
    crashes: dict[str, list[float]] = field(default_factory=dict)
    held: dict[str, float] = field(default_factory=dict)
    holds: dict[str, tuple[float, float]] = field(default_factory=dict)

    def restartable(self, failed: Collection[str], can_start: bool) -> set[str]:
        """Return those of ``failed`` to restart in place now; hold the others (said).

        ``can_start``: whether the watcher may start processes (``--apply``).
        """
        now = time.monotonic()
        out: set[str] = set()
        for comp in sorted(set(failed) - set(self.held)):
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
                continue
            seconds = self._hold_for(comp, now)
            self.held[comp] = now + seconds
            if not self.limit:
                why = "restart in place is off: --restarts 0"
            elif not can_start:
                why = "nothing is started without --apply"
            else:
                why = f"{len(times)} failures in {self.window:g} s, over the limit of {self.limit}"
            if seconds > self.hold:
                why += f"; held again after its release: {seconds / self.hold:g}x the hold"
            self.say(
                "hold",
                f"{comp} ({self.role(comp)}) is held failed for {seconds:g} s ({why}); "
                "then it is a candidate again",
                component=comp,
                seconds=seconds,
                crashes=len(times),
            )
        return out

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

        Counted as a release for the backoff: a failure soon after holds it longer."""
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
