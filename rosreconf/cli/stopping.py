"""Stop a long-running command on SIGTERM or SIGINT, every time, within a bounded time.

``watch`` used to turn SIGTERM into an exception raised wherever its main thread was. When
that is inside a finalizer (``__del__``: cyclonedds' entities have one, and the garbage
collector runs them at any allocation) or a weakref callback, Python prints "Exception
ignored" and drops it, and ``watch`` runs on as if nothing came (shown here with a finalizer
that receives SIGTERM: the ``Terminated`` is printed and the program continues). That fits the
issue's ``watch --ros2 --apply`` ignoring SIGTERM 2 times in 10, once for 10 minutes, and a
second SIGTERM always working. Here the handlers only set a
flag, which the watcher polls between steps and in every wait (``Watcher.stop_requested``),
so nothing is ever raised into foreign code; and the first signal arms a deadline: if the
clean shutdown has not finished ``HARD_STOP_SECONDS`` later (a call stuck in C), the process
ends with ``os._exit``. The deadline is armed by a thread woken through
``signal.set_wakeup_fd``, which the interpreter's C-level handler writes at once, so it holds
even when the main thread is stuck in C and Python handlers cannot run. Ending so still stops
everything it started: every child has a parent-death signal and a watchdog on a pipe that
closes with the process (``rosreconf.procs``).
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
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

    def _deadline(self, wakeup: socket.socket) -> None:
        """Wait for the first signal's byte, then give the clean shutdown its time."""
        with contextlib.suppress(OSError), wakeup:
            while not self._done.is_set():
                data = wakeup.recv(1)
                if not data:
                    return
                if data[0] in (signal.SIGTERM, signal.SIGINT):
                    if self.signum is None:
                        self.signum = data[0]
                    if not self._done.wait(HARD_STOP_SECONDS):
                        os._exit(128 + data[0])  # children die with us: death signal, watchdogs
                    return

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
    reader, writer = socket.socketpair()
    writer.setblocking(False)
    previous = {s: signal.signal(s, flags._handle) for s in (signal.SIGTERM, signal.SIGINT)}
    old_fd = signal.set_wakeup_fd(writer.fileno(), warn_on_full_buffer=False)
    threading.Thread(target=flags._deadline, args=(reader,), daemon=True).start()
    try:
        yield flags
    finally:
        signal.set_wakeup_fd(old_fd)
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        flags.finish()
        writer.close()
