"""Stop the process of one outside node: SIGINT, SIGTERM, then SIGKILL, never for a neighbour.

ROS 2 has no remote "kill node" (ros2/ros2cli#535): stopping a node rosreconf did not start
means signalling its process, which takes down every node of that process. So a process is
signalled only when /proc confirmed it runs the node (``hostprocs``), the kernel proved that
it sends the node's participant's datagrams (``provenance``: a GUID is wire data anyone can
forge), and it runs no other node; otherwise the refusal says why, naming the nodes it would
take down.

SIGINT first, as Ctrl-C and ``ros2 launch`` do: rclpy and rclcpp shut down cleanly and the
participant says goodbye, so other readers see it go at once (0.03 s) instead of after its
lease. SIGTERM next, then SIGKILL. Every signal goes through a pidfd opened for exactly the
confirmed process (pidfd_send_signal, Linux 5.1), so a pid recycled meanwhile is never hit;
without pidfds the start time is checked before each ``kill``. A stopped process (SIGSTOP)
queues SIGINT and SIGTERM unhandled: it is sent SIGCONT after each so it can act on them.
"""

from __future__ import annotations

import os
import select
import signal
import time
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from rosreconf.procs.ladder import LADDER, climb
from rosreconf.procs.procstat import PROC
from rosreconf.ros.ros2.hostprocs import ProcId, read_proc_id
from rosreconf.ros.ros2.pidwatch import STOPPED_STATES, open_pidfd, pidfd_supported, proc_state

GRACE = 3.0
"""Seconds a node is given after SIGINT, and again after SIGTERM, before the next signal
(rclpy nodes here left 0.03 s after SIGINT; a node saving state takes longer)."""


class Stopped(StrEnum):
    """How a stop ended."""

    STOPPED = "stopped"  # the process exited after ``signal_used``
    GONE = "gone"  # it had exited already: nothing was signalled
    REFUSED = "refused"  # it runs other nodes too: nothing was signalled
    UNPROVEN = "unproven"  # not proven to run the node (``provenance``): nothing was signalled
    FAILED = "failed"  # it outlived SIGKILL's grace (uninterruptible sleep): said as such


@dataclass(frozen=True)
class StopResult:
    """What stopping one node's process did.

    Attributes:
        outcome: how it ended.
        node: the node it was for.
        proc: the process.
        signal_used: the last signal sent (None: none was).
        seconds: from the first signal to the exit seen.
        others: the other nodes the process runs (why it was refused).
        why: why the process is not proven to run the node (``UNPROVEN``).
    """

    outcome: Stopped
    node: str
    proc: ProcId
    signal_used: signal.Signals | None = None
    seconds: float = 0.0
    others: tuple[str, ...] = ()
    why: str = ""

    @property
    def message(self) -> str:
        """Return one sentence for a person."""
        if self.outcome is Stopped.REFUSED:
            return (
                f"process {self.proc.pid} runs {self.node} and also "
                f"{', '.join(self.others)}: not stopped (it would take them down)"
            )
        if self.outcome is Stopped.UNPROVEN:
            return (
                f"process {self.proc.pid} is not proven to run {self.node} ({self.why}): "
                "not signalled"
            )
        if self.outcome is Stopped.STOPPED and self.signal_used is not None:
            return (
                f"process {self.proc.pid} of {self.node} stopped by {self.signal_used.name} "
                f"in {self.seconds:.2f} s"
            )
        if self.outcome is Stopped.GONE:
            return f"process {self.proc.pid} of {self.node} had exited already"
        return f"process {self.proc.pid} of {self.node} outlived SIGKILL"


def stop_node_process(
    proc: ProcId,
    node: str,
    process_nodes: Sequence[str],
    *,
    grace: float = GRACE,
    proc_root: Path = PROC,
) -> StopResult:
    """Stop ``proc`` for ``node`` when it runs no other node; return what happened.

    ``proc`` must be a confirmed process (``Located.proc``) and ``process_nodes`` every node
    it runs (``nodes_by_process``). Blocks at most about ``3 * grace`` s.
    """
    others = tuple(sorted({n for n in process_nodes if n != node}))
    if others:
        return StopResult(Stopped.REFUSED, node, proc, others=others)
    fd = open_pidfd(proc, proc_root) if pidfd_supported() else None
    if fd is None and read_proc_id(proc.pid, proc_root) != proc:
        return StopResult(Stopped.GONE, node, proc)
    start = time.monotonic()
    try:
        climbed = climb(
            lambda sig: _send(proc, fd, sig, proc_root),  # False: exited between two signals
            lambda wait: _exited(proc, fd, wait, proc_root),
            grace,
            LADDER,
        )
    finally:
        if fd is not None:
            os.close(fd)
    seconds = time.monotonic() - start
    if not climbed.gone:
        return StopResult(Stopped.FAILED, node, proc, climbed.last, seconds)
    if climbed.last is None:
        return StopResult(Stopped.GONE, node, proc)
    return StopResult(Stopped.STOPPED, node, proc, climbed.last, seconds)


def _send(proc: ProcId, fd: int | None, sig: signal.Signals, proc_root: Path) -> bool:
    """Send ``sig`` to exactly ``proc`` (and SIGCONT when it is stopped); False: it is gone."""
    try:
        if fd is not None:
            signal.pidfd_send_signal(fd, sig)
        else:
            if read_proc_id(proc.pid, proc_root) != proc:
                return False
            os.kill(proc.pid, sig)
        if sig != signal.SIGKILL and proc_state(proc.pid, proc_root) in STOPPED_STATES:
            if fd is not None:
                signal.pidfd_send_signal(fd, signal.SIGCONT)
            else:
                os.kill(proc.pid, signal.SIGCONT)
    except ProcessLookupError:
        return False
    return True


def _exited(proc: ProcId, fd: int | None, grace: float, proc_root: Path) -> bool:
    """Return True once ``proc`` has exited, waiting at most ``grace`` s."""
    if fd is not None:
        poller = select.poll()
        poller.register(fd, select.POLLIN)
        return bool(poller.poll(int(grace * 1000)))
    deadline = time.monotonic() + grace
    while time.monotonic() < deadline:
        if read_proc_id(proc.pid, proc_root) != proc or proc_state(proc.pid, proc_root) == "Z":
            return True
        time.sleep(0.02)
    return False
