"""Run a ``Watcher`` step after step: the poll loop of ``rosreconf watch``.

The watcher decides what one look at the system means (``Watcher.step``); this loop decides
when to look. Between steps it sleeps ``interval`` seconds, but wakes at once when a watched
node process exits or hangs (or a switch of task is asked: ``Watcher.exited``), when a
failure seen while confirming waits for its replan, when a restart's backoff is over, or
when a stop is asked (``stop_requested``, polled every 20 ms). A read that fails before any
has succeeded is an error (a wrong master URI or domain fails fast); after one, a failed
read is retried: a restarting master with one event when it goes (``master-lost``) and one
when it is back (``master-back``); a graph caught half-announced (ROS 2 nodes starting:
``UnsettledGraphError``) is no lost source, and is said only when it lasts
``UNSETTLED_SAID_AFTER`` s (``graph-unsettled``, then ``graph-settled``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from rosreconf.errors import ExternalToolError, UnsettledGraphError
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.events import Event


class Pollable(Protocol):
    """What the loop asks of a watcher (``rosreconf.ros.watcher.Watcher`` is one).

    The seam between deciding a step and deciding when to step: the loop's own behaviour
    (retries, what it says of failed reads, waking early) is tested with a stand-in watcher.
    """

    @property
    def schema(self) -> Any:
        """The interoperability schema watched (its simulation part is loaded first)."""

    @property
    def log(self) -> Callable[[Event], None]:
        """Where events go."""

    @property
    def stop_requested(self) -> Callable[[], bool]:
        """Tell whether a stop was asked."""

    def step(self) -> Conformance:
        """Look once and act on what is seen; raise ``ExternalToolError`` if it cannot read."""

    def has_read(self) -> bool:
        """Tell whether a read has succeeded."""

    def replan_due(self) -> bool:
        """Tell whether a failure waits for its replan."""

    def exited(self) -> bool:
        """Tell whether a watched process ended or hung since the last step."""

    def due_at(self) -> float | None:
        """Return when a waiting restart is due (monotonic seconds), if any."""


SLICE = 0.02
"""Seconds between looks at the watched processes and the stop request while sleeping."""

UNSETTLED_SAID_AFTER = 3.0
"""Seconds a graph may stay half-announced before it is said: starting a configuration's
nodes at once makes single reads partial in a normal failover, and that is nobody's fault."""


@dataclass
class _Outage:
    """The failed reads since the last good one: said once as it begins, once as it ends."""

    began: float | None = None
    said: str | None = None  # the event that began it: master-lost or graph-unsettled

    def failed(self, watcher: Pollable, exc: ExternalToolError, interval: float) -> None:
        """Note a failed read; say the outage when it is a lost source, or lasts."""
        now = time.monotonic()
        self.began = now if self.began is None else self.began
        if self.said is not None:
            return
        if not isinstance(exc, UnsettledGraphError):
            self.said = "master-lost"
            watcher.log(Event(self.said, f"{exc}; retrying every {interval:g} s"))
        elif now - self.began >= UNSETTLED_SAID_AFTER:
            self.said = "graph-unsettled"
            lasted = now - self.began
            watcher.log(Event(self.said, f"{exc}; for {lasted:.1f} s now, retrying"))

    def ended(self, watcher: Pollable) -> None:
        """Note a good read; say the end of an outage that was said."""
        if self.began is not None and self.said is not None:
            gone = time.monotonic() - self.began
            if self.said == "master-lost":
                watcher.log(Event("master-back", f"the master answers again after {gone:.1f} s"))
            else:
                watcher.log(
                    Event("graph-settled", f"the graph reads whole again after {gone:.1f} s")
                )
        self.began, self.said = None, None


def poll(watcher: Pollable, interval: float, *, once: bool = False) -> Conformance:
    """Step ``watcher`` every ``interval`` seconds until stopped; with ``once``, step once.

    Returns the last conformance check.

    Raises:
        ExternalToolError: the master does not answer the first poll (or, with ``once``,
            any poll).
    """
    if watcher.schema.simulation is not None:  # numpy and the loops: not at the first failure
        import rosreconf.analysis.simulate  # noqa: F401
    started, outage, check = False, _Outage(), None
    while True:
        try:
            check = watcher.step()
        except ExternalToolError as exc:
            if (not started and not watcher.has_read()) or once:
                raise
            outage.failed(watcher, exc, interval)
            _wait(watcher, interval)
            if watcher.stop_requested() and check is not None:
                return check
            continue
        started = True
        outage.ended(watcher)
        if once or watcher.stop_requested():
            return check
        _wait(watcher, interval)
        if watcher.stop_requested():
            return check


def _wait(watcher: Pollable, seconds: float) -> None:
    """Sleep between polls; end early when a node process exits or a stop is asked."""
    if watcher.replan_due():
        return  # a failure seen while confirming: replan now
    deadline = min(time.monotonic() + seconds, watcher.due_at() or float("inf"))
    while not watcher.stop_requested() and (left := deadline - time.monotonic()) > 0:
        if watcher.exited():
            return
        time.sleep(min(left, SLICE))
