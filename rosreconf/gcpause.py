"""Pause the cyclic garbage collector while a command builds objects that live to its end.

Loading a library and compiling its tables only add objects: tuples of strings and
integers, model records. Reference counting frees those; but each collection of the cyclic
collector would walk everything built so far, and at 1000 roles x 10 those walks cost more
than the loading or the elimination itself. So both pause it (``paused_gc``).

What is still alive at the end (the loaded model, a compiled instance, an answer) is frozen
(``gc.freeze``): every object made while the collector was paused sits in its youngest
generation, and the first allocation after re-enabling it would walk them all (0.02-0.03
CPU s after compiling 1000 roles x 10). Frozen objects are still freed by reference
counting; only a reference cycle made during the pause would outlive its use.

A process that runs on (``watch``) freezes no more once it is set up (``stop_freezing``):
``gc.freeze`` also freezes the cyclic garbage not collected yet, made before the pause
(networkx graphs are cycles: each ``compare`` builds one), and a frozen cycle is never freed.
Each repair's replan pauses the collector, and so froze 100-300 KiB more for good.
"""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Iterator

_freezing = True


def stop_freezing() -> None:
    """Have later pauses re-enable the collector without freezing (a long-running process,
    once it is set up: see the module docstring)."""
    global _freezing
    _freezing = False


@contextlib.contextmanager
def paused_gc() -> Iterator[None]:
    """Disable the cyclic collector for the block, then freeze what it built and re-enable.

    Nested pauses are no-ops: only the outermost one (the collector was enabled when it
    began) freezes and re-enables. After ``stop_freezing`` it only re-enables.
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            if _freezing:
                gc.freeze()
            gc.enable()
