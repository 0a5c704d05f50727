"""The CLI's two output streams: one owner, so that every verb writes the same way.

``--json`` documents go to stdout through ``write_stdout`` exactly as built (rich must not
re-wrap them); human output, progress and errors go through the rich consoles.
"""

from __future__ import annotations

import sys

from rich.console import Console

from rosreconf.outfiles import OutputTarget, write_atomic

# emoji=False: names come from users' files, and ``:warning:`` in a component name must print
# as written, not as a picture (it also spares every command importing rich's emoji table).
stdout = Console(highlight=False, soft_wrap=True, emoji=False)
stderr = Console(stderr=True, highlight=False, soft_wrap=True, emoji=False)


def write_stdout(text: str) -> None:
    """Write ``text`` to stdout exactly (JSON documents must not be re-wrapped by rich)."""
    sys.stdout.write(text)
    sys.stdout.flush()


def write_output(target: OutputTarget, data: bytes | str) -> str:
    """Write ``data`` to an ``-o`` target (a file, atomically, or stdout); name where it went."""
    if not target.is_stdout:
        write_atomic(target.shown, data)
        return target.shown
    sys.stdout.flush()
    sys.stdout.buffer.write(data.encode("utf-8") if isinstance(data, str) else data)
    sys.stdout.buffer.flush()
    return "stdout"
