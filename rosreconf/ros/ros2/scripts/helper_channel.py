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

import os
import sys
from typing import TextIO


def take_channel() -> TextIO:
    """Return the helper's answer channel; from now on fd 1 (and ``sys.stdout``) is the log.

    The duplicate is not inherited by programs the helper runs (Python makes it close on
    exec); a helper that forks must close it in the child (``close_channel``).
    """
    sys.stdout.flush()
    answers = os.dup(1)
    os.dup2(2, 1)
    return os.fdopen(answers, "w", buffering=1, encoding="utf-8")


def close_channel(channel: TextIO) -> None:
    """Close a forked child's copy of the channel: only the helper itself answers on it."""
    os.close(channel.fileno())
