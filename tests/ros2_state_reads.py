"""Read one managed node's lifecycle state as ``watch`` does, read after read; print each.

A process of its own, so that the fault injector (``tests/faults/drop_received.c``, loaded
with LD_PRELOAD) loses datagrams only here::

    python tests/ros2_state_reads.py DOMAIN NODE READS INTERVAL

One ``rosreconf.ros.ros2.source.Ros2Source`` (its ``StateReader`` kept, as watch keeps it)
reads the domain READS times, INTERVAL s apart; each read prints one JSON line, the state
of NODE (``null`` when not seen or not managed), whether the graph lists NODE serving
``NODE/get_state`` (``listed``), and when (``at``: seconds since the first read began), or
the read's error.
"""

from __future__ import annotations

import json
import sys
import time

from rosreconf.errors import RosreconfError
from rosreconf.ros.ros2.source import Ros2Source


def main(argv: list[str]) -> int:
    domain, node, reads, interval = int(argv[0]), argv[1], int(argv[2]), float(argv[3])
    source = Ros2Source(domain, empty_ok=True)
    start = time.monotonic()
    try:
        for _ in range(reads):
            try:
                graph = source.read()
            except RosreconfError as exc:
                print(json.dumps({"error": str(exc)}), flush=True)
            else:
                states = {n.name: n.lifecycle_state for n in graph.nodes}
                listed = any(f"{node}/get_state" in n.serves for n in graph.nodes if n.name == node)
                at = round(time.monotonic() - start, 3)
                said = {"state": states.get(node), "listed": listed, "at": at}
                print(json.dumps(said), flush=True)
            time.sleep(interval)
    finally:
        source.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
