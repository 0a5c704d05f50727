"""Name the broken Fast DDS shared-memory port a node process waits on, so a person can clear it.

Fast DDS's shared-memory transport gives each participant on a host the next port file,
``/dev/shm/fastrtps_port7000``, ``7001``, ... (Fast DDS 3: ``fastdds_port...``), whatever its
domain. A participant killed while it creates one leaves the file 0 bytes long, with no lock
file beside it; every later participant that picks that port waits in boost.interprocess's
open-or-create, inside ``rcl_node_init``, for ever, and Fast DDS's own ``fastdds shm clean``
does not remove it (it looks only at ports with a lock file). rosreconf's own participants
avoid this by running on UDP only (``runtime.OWN_TRANSPORTS``); a team's executable does not,
and from the outside it is just a process that never shows up on the graph.

Such a process has the file open, and the file is still 0 bytes long: that is what is read
here, from ``/proc``, and nothing else is assumed. Nothing is removed: the file is not
rosreconf's, and the processes waiting on it stay stuck even when it goes (they hold it open),
so what to do is said, not done.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable

PORT_FILE = re.compile(r"^/dev/shm/(?:fastrtps|fastdds)_port\d+$")


def broken_ports(pid: int) -> list[str]:
    """Return the 0-byte Fast DDS port files that process ``pid`` has open (none: unreadable)."""
    fds = f"/proc/{pid}/fd"
    try:
        names = os.listdir(fds)
    except OSError:  # gone, or another user's process
        return []
    found: set[str] = set()
    for name in names:
        link = f"{fds}/{name}"
        try:
            target = os.readlink(link)
            if PORT_FILE.match(target) and os.stat(link).st_size == 0:
                found.add(target)
        except OSError:  # closed meanwhile
            continue
    return sorted(found)


def diagnose(stuck: Iterable[tuple[str, int]]) -> str | None:
    """Say which of ``stuck`` (component, pid) wait on a broken port, and what to do; or None."""
    waits = {comp: files for comp, pid in stuck if (files := broken_ports(pid))}
    if not waits:
        return None
    files = sorted({f for fs in waits.values() for f in fs})
    who = ", ".join(sorted(waits))
    return (
        f"{who} wait(s) for ever on Fast DDS shared-memory port {', '.join(files)}: 0 bytes, "
        "left by a process killed while it created it, so no participant that picks that port "
        f"can start. Remove it (rm {' '.join(files)}), then restart {who}; or run the nodes with "
        "FASTDDS_BUILTIN_TRANSPORTS=UDPv4"
    )
