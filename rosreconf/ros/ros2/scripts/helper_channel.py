"""Give one of rosreconf's helpers a channel of its own, apart from what its libraries print.

A helper (the lifecycle agent, the stand-in zygote) answers rosreconf in JSON lines on the
pipe rosreconf gave it as stdout. But the C libraries under rclpy write to file descriptor
1 as well: Fast DDS prints ``[RTPS_TRANSPORT_SHM Error] Failed init_port ...`` there when it
meets shared-memory debris, and rcutils may log there. On a shared descriptor one such line
is read as the helper's answer, and every later answer is one line behind. So a helper
takes, before anything can print: a private duplicate of that pipe, written only by its
protocol, and fd 1 pointed at its log (fd 2), where everything a library prints belongs.

This file is never imported by rosreconf; the helpers run under the ROS 2 Python and import
it from their own folder.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
from typing import Any


class Channel:
    """The helper's own answer channel: whole JSON lines, from any thread, never interleaved."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self._lock = threading.Lock()

    def say(self, said: dict[str, Any]) -> None:
        """Write ``said`` as one line, in one write."""
        data = (json.dumps(said) + "\n").encode()
        with self._lock:
            os.write(self.fd, data)

    def beat(self, every: float) -> None:
        """Say ``{"alive": ...}`` every ``every`` seconds, from a thread, while the helper runs.

        rosreconf takes a helper that has said nothing for a while (no answer, no beat) for
        hung, as a stopped (SIGSTOP) or deadlocked one is, and starts another: the beat tells
        a helper that works on a long request from one that no longer runs at all. Not for a
        helper that forks (the zygote): a child forked beside a thread may inherit its locks.
        """

        def run() -> None:
            while True:
                self.say({"alive": time.monotonic()})
                time.sleep(every)

        threading.Thread(target=run, name="rosreconf-heartbeat", daemon=True).start()

    def close_in_child(self) -> None:
        """Close a forked child's copy: only the helper itself answers on the channel."""
        os.close(self.fd)


def take_channel() -> Channel:
    """Return the helper's answer channel; from now on fd 1 (and ``sys.stdout``) is the log.

    The duplicate is not inherited by programs the helper runs (Python makes it close on
    exec); a helper that forks closes it in the child (``Channel.close_in_child``).
    """
    sys.stdout.flush()
    answers = os.dup(1)
    os.dup2(2, 1)
    return Channel(answers)
