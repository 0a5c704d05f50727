"""Stop a long-running command on SIGTERM or SIGINT, every time, within a bounded time.

``watch`` used to turn SIGTERM into an exception raised wherever its main thread was. An
exception raised inside Python code that a C library calls back (cyclonedds deserialises
samples through Python) is printed and swallowed there, and then the signal is lost: the
issue saw ``watch --ros2 --apply`` ignore SIGTERM 2 times in 10. Here the handlers only set a
flag, which the watcher polls between steps and in every wait (``Watcher.stop_requested``),
so nothing is ever raised into foreign code; and the first signal arms a deadline: if the
clean shutdown has not finished ``HARD_STOP_SECONDS`` later (a call stuck in C), the process
ends with ``os._exit``. That still stops everything it started: every child has a
parent-death signal and a watchdog on a pipe that closes with the process
(``rosreconf.procs``).
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Iterator
from types import FrameType

HARD_STOP_SECONDS = 4.0
"""After the first signal, the clean shutdown may take this long before the process ends."""


class StopSignals:
    """The flag the handlers set, and which signal set it (for the exit status 128 + n)."""

    def __init__(self) -> None:
        self.signum: int | None = None
        self._done = threading.Event()

    def requested(self) -> bool:
        """Tell whether SIGTERM or SIGINT has arrived."""
        return self.signum is not None

    def _handle(self, signum: int, frame: FrameType | None) -> None:
        if self.signum is None:
            self.signum = signum
            timer = threading.Thread(target=self._deadline, args=(signum,), daemon=True)
            timer.start()

    def _deadline(self, signum: int) -> None:
        if not self._done.wait(HARD_STOP_SECONDS):
            os._exit(128 + signum)  # children die with us: parent-death signal, watchdogs

    def finish(self) -> None:
        """Disarm the deadline: the clean shutdown is over."""
        self._done.set()


@contextlib.contextmanager
def stop_on_signals() -> Iterator[StopSignals]:
    """Install flag-setting SIGTERM and SIGINT handlers for the block (main thread only)."""
    flags = StopSignals()
    if threading.current_thread() is not threading.main_thread():
        yield flags
        return
    previous = {s: signal.signal(s, flags._handle) for s in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield flags
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        flags.finish()
