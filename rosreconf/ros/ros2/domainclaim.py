"""One supervisor per ROS domain on a host: a lock the kernel lets go when its owner dies.

Two ``watch --apply`` on one domain each start and stop nodes against the other. The second
must be told, at once and with the first one's pid. A lock file per domain id, held with
``fcntl.flock``, does that:

- the kernel releases a flock when its last descriptor closes, so a watch killed by SIGKILL
  leaves no stale claim (a pid file alone would need a liveness guess; the pid written in
  the file is only for the message);
- taking it is atomic, so two watches started together cannot both win;
- it is local and immediate, where a marker announced over DDS is seen only after discovery
  (seconds), lingers for a lease after a crash (20 s with Fast DDS), and lets two watches
  starting together both see nothing.

It covers the watches of one host (and one mount namespace: containers need the lock
directory shared). Watches on two hosts of one domain are not seen by it; a DDS marker
could add that later, as a warning. The directory is ``ROSRECONF_LOCK_DIR``, else
``/run/lock`` (world writable, sticky, cleared at boot), else the temporary directory; the
file is opened without following symbolic links and made writable by all (only the pid
in it is at stake), and read-only if another user's file is not (``flock`` needs no write
access), so every user's watch meets the same lock.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

LOCK_DIR_ENV = "ROSRECONF_LOCK_DIR"


def lock_dir() -> Path:
    """Return the directory domain locks live in (the same for every user of the host)."""
    chosen = os.environ.get(LOCK_DIR_ENV)
    if chosen:
        return Path(chosen)
    run_lock = Path("/run/lock")
    if run_lock.is_dir() and os.access(run_lock, os.W_OK | os.X_OK):
        return run_lock
    return Path(tempfile.gettempdir())


def lock_path(domain: int, directory: Path | None = None) -> Path:
    """Return the lock file of ``domain``."""
    return (directory or lock_dir()) / f"rosreconf-ros2-domain-{domain}.lock"


@dataclass
class Claim:
    """This process supervises ``domain`` while the claim is held (close, or exit, ends it)."""

    domain: int
    path: Path
    _fd: int | None = field(default=None, repr=False)

    def __enter__(self) -> Claim:
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()

    @property
    def held(self) -> bool:
        """Return True until released."""
        return self._fd is not None

    def release(self) -> None:
        """Give the domain up (the file stays: removing it could race a new owner)."""
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


@dataclass(frozen=True)
class Owner:
    """Another process supervises the domain.

    Attributes:
        domain: the domain id.
        pid: the owner's pid as it wrote it (None: not written yet, or unreadable).
        path: the lock file.
    """

    domain: int
    pid: int | None
    path: Path

    @property
    def message(self) -> str:
        """Return one sentence for a person."""
        who = f"process {self.pid}" if self.pid is not None else "another process"
        return f"ROS domain {self.domain} is supervised by {who} already (lock {self.path})"


def claim_domain(domain: int, *, directory: Path | None = None) -> Claim | Owner:
    """Take ``domain`` for this process, or return who holds it.

    Raises OSError when the lock file cannot be opened at all (a directory not writable and
    no file there yet): the caller says so rather than supervising unprotected in silence.
    """
    path = lock_path(domain, directory)
    flags = os.O_NOFOLLOW | os.O_CLOEXEC
    try:
        fd = os.open(path, flags | os.O_RDWR | os.O_CREAT, 0o666)
        writable = True
        with contextlib.suppress(PermissionError):  # another user's file, writable already
            os.fchmod(fd, 0o666)  # past the umask: the next owner may be another user
    except PermissionError:
        fd = os.open(path, flags | os.O_RDONLY)  # another user's file: flock needs no write
        writable = False
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError as exc:
        os.close(fd)
        if exc.errno not in (errno.EWOULDBLOCK, errno.EAGAIN):
            raise
        return Owner(domain, _owner_pid(path), path)
    if writable:
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
    return Claim(domain, path, fd)


def _owner_pid(path: Path) -> int | None:
    """Return the pid the owner wrote into the lock file (None: none yet)."""
    try:
        text = path.read_text(encoding="ascii").strip()
    except (OSError, UnicodeDecodeError):
        return None
    return int(text) if text.isdigit() else None
