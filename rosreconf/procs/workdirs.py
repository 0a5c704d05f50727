"""Give each run a private temp dir, and remove the ones a killed rosreconf left behind.

A run's files (Fast Downward's, graphviz's) go to a directory of its own, removed on every way
out; its name carries the owner's pid, so that a directory left by a rosreconf killed with
SIGKILL is recognised and removed by the next run.

A name proves nothing (``rosreconf generate -o /tmp/rosreconf-1000-10`` is the user's): only a
directory rosreconf provably made is ever removed. It holds the marker file rosreconf writes
at creation (``MARKER``, naming the owner's pid as the directory name does), it and the marker
belong to this user, its owner is dead, and the marker is older than ``STALE_AFTER_SECONDS``.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import stat
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

from rosreconf.procs.signals import sigterm_raises

WORKDIR_PREFIX = "rosreconf-"
"""Every temp dir of ours is named ``rosreconf-<pid>-<random>``: recognisable, with its owner."""

MARKER = ".rosreconf-workdir"
"""The file rosreconf writes into each of its temp dirs when it makes them."""
STALE_AFTER_SECONDS = 60.0
"""A temp dir younger than this is never removed: its marker may still be being written, or
its owner may live in another pid namespace that shares this temp folder (a container)."""

_CLEANED: set[str] = set()


def clean_stale_workdirs(parent: Path | None = None) -> list[Path]:
    """Remove temp dirs of ours whose owning process is dead; return what was removed.

    Only directories named ``rosreconf-<pid>-...``, owned by this user, holding rosreconf's
    marker for that pid (older than ``STALE_AFTER_SECONDS``), whose ``<pid>`` is no living
    process are removed: a run killed with SIGKILL leaves its Fast Downward files behind
    (megabytes each), and nothing else can ever remove them; a user's folder that only looks
    like one is never touched. Each parent folder is scanned once per process.
    """
    where = Path(parent) if parent is not None else Path(tempfile.gettempdir())
    if str(where) in _CLEANED:
        return []
    _CLEANED.add(str(where))
    removed: list[Path] = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(where):
            owner = _owner_pid(entry.name)
            if owner is None or owner == os.getpid() or _alive(owner):
                continue
            with contextlib.suppress(OSError):
                info = entry.stat(follow_symlinks=False)
                if (
                    entry.is_dir(follow_symlinks=False)
                    and info.st_uid == os.getuid()
                    and _made_by_rosreconf(Path(entry.path), owner)
                ):
                    shutil.rmtree(entry.path)
                    removed.append(Path(entry.path))
    return removed


def _marker_text(pid: int) -> bytes:
    return f"rosreconf temp dir of process {pid}; removed when that process is gone\n".encode()


def _made_by_rosreconf(path: Path, owner: int) -> bool:
    """Tell whether ``path`` holds our marker for ``owner``, by this user, old enough."""
    marker = path / MARKER
    try:
        info = os.stat(marker, follow_symlinks=False)
        if not stat.S_ISREG(info.st_mode) or info.st_uid != os.getuid():
            return False
        if time.time() - info.st_mtime < STALE_AFTER_SECONDS:
            return False
        with open(marker, "rb") as f:
            return f.read(200) == _marker_text(owner)
    except OSError:
        return False


def _owner_pid(name: str) -> int | None:
    """Return the pid in a ``rosreconf-<pid>-<random>`` name, or None for any other name."""
    if not name.startswith(WORKDIR_PREFIX):
        return None
    pid, sep, rest = name[len(WORKDIR_PREFIX) :].partition("-")
    return int(pid) if sep and rest and pid.isdigit() and pid[0] != "0" else None


def _alive(pid: int) -> bool:
    """Tell whether a process ``pid`` exists (one of another user's counts as alive)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


@contextlib.contextmanager
def private_workdir(parent: Path | None = None) -> Iterator[Path]:
    """Give a run its own temp dir (mode 0700), removed on every way out of the block.

    The directory is removed on normal exit, on exceptions, on KeyboardInterrupt and on SIGTERM
    (turned into ``Terminated`` while the block runs in the main thread). ``parent`` chooses
    where it is made (default: the system temp dir); tests use it to check nothing is left.
    Its name carries this process's pid, and its marker file says rosreconf made it, so that a
    later run can remove it with ``clean_stale_workdirs`` if rosreconf is killed (SIGKILL)
    and no cleanup code runs.
    """
    with sigterm_raises():
        clean_stale_workdirs(parent)
        path = Path(tempfile.mkdtemp(prefix=f"{WORKDIR_PREFIX}{os.getpid()}-", dir=parent))
        try:
            (path / MARKER).write_bytes(_marker_text(os.getpid()))
            yield path
        finally:
            shutil.rmtree(path, ignore_errors=True)
