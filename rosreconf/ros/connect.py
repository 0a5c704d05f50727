"""Open the live source the options name: a ROS 1 master, a ROS 2 domain or a snapshot.

The one place that knows both middlewares (``ros1.source``, ``ros2.source``); everything else
in ``rosreconf.ros`` works on a ``LiveSource`` (``rosreconf.ros.sources``).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros1.rosmaster import DEFAULT_MAX_BYTES, DEFAULT_TIMEOUT, read_live
from rosreconf.ros.ros1.source import MasterSource
from rosreconf.ros.ros2.names import check_domain, gid_sizes
from rosreconf.ros.ros2.source import Ros2Source


def open_source(
    master: str | None,
    ros2: bool,
    domain: int,
    distro: str | None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
) -> MasterSource | Ros2Source:
    """Return the source the options name: ``--master URI`` or ``--ros2 [--domain N]``.

    Raises:
        UsageError: both or neither are given, or ``--distro`` without ``--ros2``.
    """
    if ros2 == (master is not None):
        raise UsageError("give exactly one of --master URI and --ros2 [--domain N]")
    if master is not None:
        if distro is not None:
            raise UsageError("--distro is for --ros2 (ROS 2 over DDS) only")
        return MasterSource(master, timeout, max_bytes)
    check_domain(domain)
    gid_sizes(distro)  # refuse an unknown distribution before joining the domain
    return Ros2Source(domain, distro)


def read_any(
    master: str | None,
    snapshot: Path | None,
    ros2: bool = False,
    domain: int = 0,
    distro: str | None = None,
    *,
    timeout: float = DEFAULT_TIMEOUT,
    max_bytes: int = DEFAULT_MAX_BYTES,
    on_note: Callable[[str], None] | None = None,
) -> LiveGraph:
    """Read the live graph from exactly one of a master, ROS 2 discovery and a snapshot.

    A ROS 2 read also asks every managed node its lifecycle state, and says through
    ``on_note`` what it had to leave out (undecodable or forged discovery samples).

    Raises:
        UsageError: not exactly one is given, or the snapshot cannot be read.
        ExternalToolError: the master does not answer, DDS cannot be used, or nothing ROS 2
            was seen on the domain.
    """
    if sum((master is not None, snapshot is not None, ros2)) != 1:
        raise UsageError("give exactly one of --master URI, --ros2 and --snapshot FILE")
    if snapshot is not None:
        return read_live(None, snapshot)
    source = open_source(master, ros2, domain, distro, timeout=timeout, max_bytes=max_bytes)
    if isinstance(source, Ros2Source):
        source.on_note = on_note
    try:
        return source.read()
    finally:
        source.close()
