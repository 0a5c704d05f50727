"""Run a ``Watcher`` step after step: the poll loop of ``rosreconf watch``.

The watcher decides what one look at the system means (``Watcher.step``); this loop decides
when to look. Between steps it sleeps ``interval`` seconds, but wakes at once when a watched
node process exits or hangs, when a failure seen while confirming waits for its replan, when
a restart's backoff is over, or when a stop is asked (``stop_requested``, polled every
20 ms). A read that fails before any has succeeded is an error (a wrong master URI or domain
fails fast); after one, a failed read (a restarting master, a ROS 2 graph caught
half-announced) is retried, with one event when the master goes (``master-lost``) and one
when it is back (``master-back``).
"""

from __future__ import annotations

import time

from rosreconf.errors import ExternalToolError
from rosreconf.ros.conformance import Conformance
from rosreconf.ros.events import Event
from rosreconf.ros.watcher import Watcher

SLICE = 0.02
"""Seconds between looks at the watched processes and the stop request while sleeping."""


def poll(watcher: Watcher, interval: float, *, once: bool = False) -> Conformance:
    """Step ``watcher`` every ``interval`` seconds until stopped; with ``once``, step once.

    Returns the last conformance check.

    Raises:
        ExternalToolError: the master does not answer the first poll (or, with ``once``,
            any poll).
    """
    if watcher.schema.simulation is not None:  # numpy and the loops: not at the first failure
        import rosreconf.analysis.simulate  # noqa: F401
    started, lost_at, check = False, None, None
    while True:
        try:
            check = watcher.step()
        except ExternalToolError as exc:
            if (not started and not watcher.has_read()) or once:
                raise
            if lost_at is None:
                lost_at = time.monotonic()
                watcher.log(Event("master-lost", f"{exc}; retrying every {interval:g} s"))
            _wait(watcher, interval)
            if watcher.stop_requested() and check is not None:
                return check
            continue
        started = True
        if lost_at is not None:
            gone = time.monotonic() - lost_at
            watcher.log(Event("master-back", f"the master answers again after {gone:.1f} s"))
            lost_at = None
        if once or watcher.stop_requested():
            return check
        _wait(watcher, interval)
        if watcher.stop_requested():
            return check


def _wait(watcher: Watcher, seconds: float) -> None:
    """Sleep between polls; end early when a node process exits or a stop is asked."""
    if watcher.replan_due():
        return  # a failure seen while confirming: replan now
    deadline = min(time.monotonic() + seconds, watcher.due_at() or float("inf"))
    while not watcher.stop_requested() and (left := deadline - time.monotonic()) > 0:
        if watcher.exited():
            return
        time.sleep(min(left, SLICE))
