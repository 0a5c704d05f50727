"""Handle the signals between rosreconf and the programs it runs.

Two directions: a SIGTERM that reaches rosreconf while it owns a program or a temp dir must
run the cleanup code (``sigterm_raises`` turns it into ``Terminated``), and the signals
rosreconf sends go to a whole process group, which may already be gone (``signal_group``).
SIGINT's inherited "ignore" is undone in children (``sigint_ignored``, ``sigint_default``):
see the rules in the ``rosreconf.procs`` docstring.
"""

from __future__ import annotations

import contextlib
import functools
import os
import signal
import threading
from collections.abc import Callable, Iterator
from types import FrameType


class Terminated(SystemExit):
    """Stop rosreconf cleanly when it receives SIGTERM while a program or a workdir is live.

    Raised from a SIGTERM handler that ``run_program`` and ``private_workdir`` install in the
    main thread (only when SIGTERM still has its default action), so that ``finally`` blocks
    kill the program's group and remove temp dirs. It is a ``SystemExit`` with code 143
    (128 + SIGTERM), so an uncaught one ends rosreconf the way the shell expects, silently.
    """


@contextlib.contextmanager
def sigterm_raises() -> Iterator[None]:
    """Turn SIGTERM into ``Terminated`` while the block runs, so its cleanup code runs.

    Only in the main thread (Python delivers signals there) and only when SIGTERM still has
    its default action: an application's own handler is never replaced, and nested uses are
    no-ops. Loops that own ``Background`` programs use it too.
    """
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGTERM) != signal.SIG_DFL
    ):
        yield
        return

    def handler(signum: int, frame: FrameType | None) -> None:
        raise Terminated(128 + signum)

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def sigint_ignored() -> bool:
    """Tell whether rosreconf runs with SIGINT ignored (a background job of a shell script)."""
    return signal.getsignal(signal.SIGINT) == signal.SIG_IGN


def sigint_default() -> Callable[[], None]:
    """Return a preexec_fn giving SIGINT back its default action (see ``rosreconf.procs``)."""

    def setup() -> None:
        signal.signal(signal.SIGINT, signal.SIG_DFL)

    return setup


def signal_group(pgid: int, sig: signal.Signals) -> None:
    """Send ``sig`` to a process group; a group that is already gone is fine."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, sig)


STOPS = frozenset({signal.SIGINT, signal.SIGTERM})
"""The signals that stop rosreconf (a terminal's Ctrl-C, a service manager's SIGTERM)."""


@contextlib.contextmanager
def stops_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM (blocked, so kept pending) in this thread while the block runs.

    For the moments a process pool forks its workers. Python runs ``os.fork``'s hooks in
    both processes; a Ctrl-C that lands in one is "ignored" there: in a worker that has not
    yet ignored SIGINT it printed a KeyboardInterrupt traceback, and in rosreconf it was lost,
    so the sweep went on to its end with exit 0 (2 of 40 Ctrl-Cs to ``simulate --workers 2``
    as its workers started; in a fresh clone's CI the sweep outlived the test's 20 s). Held,
    the signal reaches rosreconf when the block ends, and the forked worker starts with it
    blocked until ``pool_worker_setup`` has chosen what it does with each.
    """
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, STOPS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


_deferring = [0]
"""How deep the main thread is in ``stops_deferred`` blocks."""
_kept: list[int] = []
"""The stop that arrived inside them (the first one), raised when the outermost ends."""


@contextlib.contextmanager
def stops_deferrable() -> Iterator[None]:
    """Let ``stops_deferred`` blocks keep a Ctrl-C or SIGTERM until they end (main thread).

    For the lifetime of a worker pool. Python raises a signal's exception (KeyboardInterrupt,
    ``Terminated``) at whatever bytecode the main thread runs, also right after a lock was
    taken in a ``with`` block's ``__enter__`` and before its ``__exit__`` is armed (CPython
    bpo-29988); a ``threading.Condition``'s ``__enter__`` is such a place, and every future
    has one. The lock then stays taken: the process pool's manager thread, which settles and
    cancels those futures, waits for it for ever, and so does the interpreter's exit, which
    joins that thread (``simulate --workers 2`` hung after "rosreconf: interrupted", 2 runs in
    60 beside a load; its stacks showed the manager in ``Future.cancel``). Only handlers that
    raise are wrapped; an ignored SIGINT stays ignored.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous: dict[int, Callable[[int, FrameType | None], object]] = {}
    for sig in STOPS:
        handler = signal.getsignal(sig)
        if callable(handler):
            previous[sig] = handler
            signal.signal(sig, functools.partial(_keep_or_raise, handler))
    try:
        yield
    finally:
        for signum, kept in previous.items():
            signal.signal(signum, kept)


def _keep_or_raise(
    handler: Callable[[int, FrameType | None], object], signum: int, frame: FrameType | None
) -> None:
    if _deferring[0]:
        if not _kept:  # the first stop is the one raised
            _kept.append(signum)
        return
    handler(signum, frame)


@contextlib.contextmanager
def stops_deferred() -> Iterator[None]:
    """Keep a stop that arrives in the block; raise it as the block ends (``stops_deferrable``).

    For the code that takes the futures' locks: handing work out, waiting for results. Keep
    its waits short (polls), so that a stop is raised soon.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _deferring[0] += 1
    try:
        yield
    finally:
        _deferring[0] -= 1
        if not _deferring[0] and _kept:
            signum = _kept.pop()
            handler = signal.getsignal(signum)
            if callable(handler):
                handler(signum, None)  # raises its KeyboardInterrupt or Terminated
