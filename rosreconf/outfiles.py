"""Write output files atomically, so a failed or interrupted run never leaves half a file.

Pictures, launch files and configuration documents are read by other programs (a browser,
roslaunch, the next rosreconf run); a truncated file would be worse than none. Every writer
therefore goes through ``write_atomic``: the bytes land in a temporary file beside the target,
are flushed to disk, and only then renamed over it (``os.replace`` is atomic on POSIX).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from rosreconf.errors import UsageError


def write_atomic(path: Path, data: bytes | str) -> None:
    """Replace ``path`` by ``data`` in one step; leave ``path`` untouched on any failure.

    Text is written as UTF-8. The new file gets the usual permissions (0666 minus umask).

    Raises:
        UsageError: the directory does not exist or cannot be written.
    """
    payload = data.encode("utf-8") if isinstance(data, str) else data
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise UsageError(f"{target}: cannot write: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(payload)
            out.flush()
            os.fsync(out.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise UsageError(f"{target}: cannot write: {exc.strerror or exc}") from None
        raise
