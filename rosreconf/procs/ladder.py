"""Stop processes by asking ever more firmly: SIGINT, then SIGTERM, then SIGKILL, a grace apart.

SIGINT first, as a terminal's Ctrl-C and ``ros2 launch`` do: roslaunch stops its nodes on it,
and rclpy and rclcpp nodes shut down cleanly, so their participants say goodbye and readers
see them go at once instead of after a lease. SIGTERM next, for a program that handles
SIGINT but did not end; SIGKILL last, which no program can ignore. After each signal the
processes get ``grace`` seconds, and the climb ends as soon as they have all gone: a node
that leaves on SIGINT never sees SIGTERM.

Only the order and the waiting are shared. What a signal is sent to, and when one may be
sent at all, belongs to each caller: the process groups of the programs rosreconf started
(``background``, the ROS 2 node processes), or one process rosreconf did not start, signalled
only through a pidfd for exactly that process (``ros.ros2.stopproc``). Each also keeps its
own last resort: a group is SIGKILLed whatever the climb came to, with every descendant
that left it.
"""

from __future__ import annotations

import signal
import subprocess
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Protocol

LADDER = (signal.SIGINT, signal.SIGTERM, signal.SIGKILL)
"""The signals in the order they are sent."""


@dataclass(frozen=True)
class Climbed:
    """Where a climb stopped.

    Attributes:
        last: the last signal sent (None: none was, the processes had gone already).
        gone: the processes have gone (False: still there after the last signal's grace).
    """

    last: signal.Signals | None
    gone: bool


def climb(
    send: Callable[[signal.Signals], bool],
    gone: Callable[[float], bool],
    grace: float,
    steps: Sequence[signal.Signals] = LADDER,
) -> Climbed:
    """Send each signal of ``steps`` in turn, each followed by up to ``grace`` s for the exit.

    ``send(sig)`` signals what is still running and returns False when nothing was left to
    signal; ``gone(grace)`` waits at most ``grace`` s and returns True once everything has
    ended. The climb stops at the first of either.
    """
    last: signal.Signals | None = None
    for sig in steps:
        if not send(sig):
            return Climbed(last, gone=True)
        last = sig
        if gone(grace):
            return Climbed(last, gone=True)
    return Climbed(last, gone=False)


class Waitable(Protocol):
    """A child process that can be waited for: ``subprocess.Popen`` or a forked stand-in."""

    def wait(self, timeout: float | None = None) -> int:
        """Wait until it has ended (``subprocess.TimeoutExpired`` after ``timeout``)."""


def wait_all(processes: Iterable[Waitable], grace: float) -> bool:
    """Wait for every process within one shared ``grace``; return True when all have ended.

    The grace is shared, not given to each in turn: stopping ten processes takes at most
    ``grace`` s, not ten times that. Every process is still waited for (with no time left, a
    poll) after one has timed out, so each that has ended is reaped.
    """
    deadline = time.monotonic() + grace
    ended = True
    for proc in processes:
        try:
            proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            ended = False
    return ended
