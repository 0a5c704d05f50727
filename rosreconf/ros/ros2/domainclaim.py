"""One supervisor per ROS domain on a host: a claim the kernel lets go when its owner dies.

Two ``watch --apply`` on one domain each start and stop nodes against the other. The second
must be told, at once and with the first one's pid. The claim is a Unix socket bound to a
name in Linux's **abstract namespace** (``\\0rosreconf/ros2-domain/<N>``) and listening:

- binding is atomic, so two watches started together cannot both win;
- the kernel drops the name when the socket's last descriptor closes, so a watch killed by
  SIGKILL leaves no stale claim (no liveness guess);
- it is no file. Nothing lies in a world-writable folder for another user to replace with a
  FIFO (the reader hangs), a folder or a symbolic link (the lock silently not taken), a hard
  link to one of the user's files (truncated and made writable by all, as the lock file
  was), or two gigabytes of digits (read whole for a pid). There is nothing to open, follow,
  truncate or read;
- the owner's pid comes from the kernel, not from a text anybody can write: a second watch
  connects and reads the listener's credentials (``SO_PEERCRED``: the pid and uid of the
  process that called ``listen``).

Another user's process can still bind the name first (any shared mechanism lets a local
user take it first, as running a watch would). Then the second watch is refused with that
process's true pid and user, which a person can act on; it is never turned against the user.
A squatter that binds without listening is "another process" (the kernel refuses the
connection and says nobody's pid).

Abstract names belong to a network namespace: the claim covers the watches of one host, and
containers that share the host's network (as DDS discovery between them mostly needs).
Watches on two hosts of one domain are not seen by it; a DDS marker could add that later, as
a warning. ``scope`` keeps claims apart where several independent sets of watches share one
network namespace on purpose (the tests).
"""

from __future__ import annotations

import contextlib
import errno
import os
import pwd
import socket
import struct
from dataclasses import dataclass, field

PREFIX = "rosreconf/ros2-domain"
"""The abstract socket name's stem; ``/<scope>/<domain>`` follows."""
BACKLOG = 64
"""Connections a claim queues without accepting: each refused second watch leaves one, and a
full queue only makes the next one say "another process" instead of the pid."""


def claim_name(domain: int, scope: str = "") -> bytes:
    """Return the abstract socket address of ``domain``'s claim (a leading NUL byte)."""
    return b"\0" + f"{PREFIX}/{scope}/{domain}".encode()


@dataclass
class Claim:
    """This process supervises ``domain`` while the claim is held (close, or exit, ends it)."""

    domain: int
    name: bytes
    _sock: socket.socket | None = field(default=None, repr=False)

    def __enter__(self) -> Claim:
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()

    @property
    def held(self) -> bool:
        """Return True until released."""
        return self._sock is not None

    def release(self) -> None:
        """Give the domain up: closing the socket frees its name at once."""
        if self._sock is not None:
            self._sock.close()
            self._sock = None


@dataclass(frozen=True)
class Owner:
    """Another process supervises the domain.

    Attributes:
        domain: the domain id.
        pid: the owner's pid, as the kernel says it (None: it does not accept connections).
        uid: the owner's user id, as the kernel says it (None with ``pid``).
    """

    domain: int
    pid: int | None
    uid: int | None = None

    @property
    def message(self) -> str:
        """Return one sentence for a person."""
        if self.pid is None:
            who = "another process"
        else:
            who = f"process {self.pid}"
            if self.uid is not None and self.uid != os.getuid():
                who += f" of user {_user(self.uid)}"
        return f"ROS domain {self.domain} is supervised by {who} already"


def claim_domain(domain: int, *, scope: str = "") -> Claim | Owner:
    """Take ``domain`` for this process, or return who holds it.

    Raises OSError when no Unix socket can be made or bound for another reason than the name
    being taken: the caller says so rather than supervising unprotected in silence.
    """
    name = claim_name(domain, scope)
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM | socket.SOCK_CLOEXEC)
    try:
        sock.bind(name)
    except OSError as exc:
        sock.close()
        if exc.errno != errno.EADDRINUSE:
            raise
        pid, uid = _listener(name)
        return Owner(domain, pid, uid)
    sock.listen(BACKLOG)
    return Claim(domain, name, sock)


def _listener(name: bytes) -> tuple[int | None, int | None]:
    """Return the pid and uid of the process listening at ``name`` (Nones: nobody answers)."""
    probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM | socket.SOCK_CLOEXEC)
    probe.setblocking(False)  # a full queue is EAGAIN, never a wait
    with probe:
        try:
            probe.connect(name)
        except OSError:  # bound, not listening (ECONNREFUSED), or its queue full (EAGAIN)
            return None, None
        cred = probe.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, struct.calcsize("3i"))
    pid, uid, _gid = struct.unpack("3i", cred)
    return (pid, uid) if pid > 0 else (None, None)


def _user(uid: int) -> str:
    """Return ``uid``'s login name, or the number when the host has none for it."""
    with contextlib.suppress(KeyError):
        return pwd.getpwuid(uid).pw_name
    return str(uid)
