"""The CLI's two output streams: one owner, so that every verb writes the same way.

``--json`` documents go to stdout through ``write_stdout`` exactly as built (rich must not
re-wrap them); human output, progress and errors go through the rich consoles.
"""

from __future__ import annotations

import errno
import shutil
import sys
import tempfile
from collections.abc import Iterable
from typing import Any

from rich.console import Console

from rosreconf.errors import OutOfResourcesError
from rosreconf.outfiles import OutputTarget, write_atomic
from rosreconf.printable import terminal_text

SPOOL_IN_MEMORY = 8 * 1024 * 1024
"""Bytes of a streamed document kept in memory; the rest is spooled to a temporary file."""


class _PersonConsole(Console):
    """A rich console that never passes an escape sequence from a path or a name through.

    Messages quote paths (any bytes but ``/`` and NUL) and names from files and from the
    wire; ``\x1b[2J`` in a file name must show as those characters, not clear the screen.
    """

    def print(self, *objects: Any, **kwargs: Any) -> None:
        """Print as rich does, each plain string first made fit for a terminal."""
        super().print(*(terminal_text(o) if isinstance(o, str) else o for o in objects), **kwargs)


# emoji=False: names come from users' files, and ``:warning:`` in a component name must print
# as written, not as a picture (it also spares every command importing rich's emoji table).
stdout = _PersonConsole(highlight=False, soft_wrap=True, emoji=False)
stderr = _PersonConsole(stderr=True, highlight=False, soft_wrap=True, emoji=False)


def write_stdout(text: str) -> None:
    """Write ``text`` to stdout exactly (JSON documents must not be re-wrapped by rich)."""
    sys.stdout.write(text)
    sys.stdout.flush()


def write_stdout_pieces(pieces: Iterable[str]) -> None:
    """Write a document made piece by piece to stdout, whole or not at all.

    The pieces go to a temporary file (in memory up to ``SPOOL_IN_MEMORY``, then on disk in
    TMPDIR) and are copied to stdout only once the last one is made: memory stays bounded by
    one piece however long the document, and an error while making it (out of memory, a
    NaN) leaves stdout empty instead of half a JSON document. Disk full is exit 3.
    """
    with tempfile.SpooledTemporaryFile(SPOOL_IN_MEMORY, "w+", encoding="utf-8") as spool:
        try:
            for piece in pieces:
                spool.write(piece)
            spool.flush()
        except OSError as exc:
            if exc.errno not in (errno.ENOSPC, errno.EDQUOT, errno.EFBIG):
                raise
            raise OutOfResourcesError(
                f"no room for the JSON document in {tempfile.gettempdir()} (set TMPDIR): {exc}"
            ) from None
        spool.seek(0)
        sys.stdout.flush()
        shutil.copyfileobj(spool, sys.stdout, 1024 * 1024)
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
