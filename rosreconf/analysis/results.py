"""Take a sweep's results as its units of work finish, and let a Ctrl-C or SIGTERM stop it.

``concurrent.futures.as_completed`` and ``wait`` take every future's lock, and a signal's
exception raised while one is taken can leave it taken (``procs.stops_deferrable``): the pool's
manager thread, and then the interpreter's exit, wait for it for ever. Here each future, as
it finishes, puts itself on a queue (its done callback); the sweep takes from that queue in
short polls inside ``stops_deferred``, so a stop is raised between polls, with no lock taken,
at most ``STOP_POLL_SECONDS`` after it came. One queue for all: each wait costs O(1), where
``wait`` on what is still pending costs O(pending).
"""

from __future__ import annotations

import contextlib
import queue
from concurrent.futures import Future
from typing import Generic, TypeVar

from rosreconf.procs import stops_deferred

T = TypeVar("T")

STOP_POLL_SECONDS = 0.1
"""Longest wait for a result between two chances for a Ctrl-C or SIGTERM to be raised."""


class Results(Generic[T]):
    """The futures handed to ``watch``, taken back by ``next`` in the order they finish."""

    def __init__(self) -> None:
        self._finished: queue.SimpleQueue[Future[T]] = queue.SimpleQueue()
        self.pending = 0
        """Futures watched and not yet taken back."""

    def watch(self, future: Future[T]) -> Future[T]:
        """Have ``future`` report here when it finishes; return it."""
        with stops_deferred():
            future.add_done_callback(self._finished.put)
        self.pending += 1
        return future

    def next(self) -> tuple[Future[T], T]:
        """Wait for the next future to finish; return it and its result (or raise its error)."""
        while True:
            with stops_deferred(), contextlib.suppress(queue.Empty):
                future = self._finished.get(timeout=STOP_POLL_SECONDS)
                self.pending -= 1
                return future, future.result()
