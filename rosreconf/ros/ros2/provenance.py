"""Prove which local process sends a DDS participant's datagrams, by what the kernel says.

``hostprocs`` finds a participant's process from its GUID prefix (Fast DDS writes the host id
and the low bits of the pid there) and /proc. That is good enough to *watch* a process for
its exit, but not to *signal* it: the GUID is unauthenticated wire data. Any participant of
the domain can put any prefix in its XML profile (one line), this host's id and a
bystander's pid among them, and every participant of a domain holds the domain's well-known
ports, so "it holds the domain's sockets" proves nothing either. A watch told to stop that
node (``--stop-outside``) would then signal the bystander, and a watch run as root other
users' processes.

What a third party on the domain cannot forge is where its datagrams come from. Every
participant announces itself (SPDP) to the domain's multicast group
(``239.255.0.1:7400 + 250 d``) every few seconds, from a UDP socket of its own; a datagram
received here carries the sender's GUID prefix in its RTPS header and, from the kernel, the
address and port it was sent from. On this host, the kernel also says (``/proc/net/udp`` and
each process's descriptors) which process holds that source port. So a process is proven to
run a participant when every datagram of that prefix that came from a local address came
from a port that process holds, and no other process holds it:

- a forger sending under a bystander's prefix sends from its own socket: the evidence names
  the forger, never the bystander, and with two holders of the prefix's ports nothing is
  proven (the node is then named for a person, never signalled);
- sending from a port another process holds needs that port (taken: the bind fails) or raw
  sockets (``CAP_NET_RAW``, root's): a user who is root on the host is outside this model.

Only processes of the user ``watch`` runs as are ever signalled: a watch run as root does
not stop another user's process for a node it was told about over the network.

A domain whose participants do not announce by multicast (``ROS_AUTOMATIC_DISCOVERY_RANGE``
of Jazzy, static peers) gives no evidence here: its nodes are named for a person, as any node
whose process is not proven.
"""

from __future__ import annotations

import contextlib
import os
import socket
import struct
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.procs.procstat import PROC
from rosreconf.ros.ros2.fastdds_ids import fastdds_ipv4
from rosreconf.ros.ros2.hostprocs import ProcId, socket_ports, udp_port_holders

SPDP_GROUP = "239.255.0.1"
"""The RTPS discovery multicast group (the DDSI-RTPS specification's default)."""
EVIDENCE_SECONDS = 30.0
"""How old a datagram may be and still count (Fast DDS announces every 3 s by default)."""
WAIT_SECONDS = 3.5
"""How long a proof waits for a first datagram of a participant (one announcement period)."""


def spdp_port(domain: int) -> int:
    """Return the domain's discovery multicast port (PB 7400, DG 250, d0 0)."""
    return 7400 + 250 * domain


def _uid(pid: int, proc_root: Path) -> int | None:
    """Return the real user id of ``pid`` (None: gone)."""
    try:
        for line in (proc_root / str(pid) / "status").read_text().splitlines():
            if line.startswith("Uid:"):
                return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        return None
    return None


@dataclass
class SourcePorts:
    """Listen to one domain's discovery multicast and remember where each prefix came from.

    Attributes:
        domain: the DDS domain.
        seen: GUID prefix (12 bytes) -> (source address, port) -> when last received.
    """

    domain: int
    seen: dict[bytes, dict[tuple[str, int], float]] = field(default_factory=dict)
    _sock: socket.socket | None = field(default=None, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def start(self) -> SourcePorts:
        """Join the domain's discovery group and read it on a thread; say nothing if it fails.

        A host with no multicast route gives no evidence, and every proof then fails: safe.
        """
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind(("", spdp_port(self.domain)))
            group = struct.pack("4s4s", socket.inet_aton(SPDP_GROUP), socket.inet_aton("0.0.0.0"))
            sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, group)
        except OSError:
            sock.close()
            return self
        self._sock = sock
        threading.Thread(target=self._read, args=(sock,), daemon=True).start()
        return self

    def _read(self, sock: socket.socket) -> None:
        while True:
            try:
                data, (address, port) = sock.recvfrom(65536)
            except OSError:  # closed
                return
            if len(data) >= 20 and data[:4] == b"RTPS":
                with self._lock:
                    self.seen.setdefault(data[8:20], {})[(address, port)] = time.monotonic()

    def close(self) -> None:
        """Leave the group."""
        if self._sock is not None:
            with contextlib.suppress(OSError):
                self._sock.shutdown(socket.SHUT_RDWR)
            self._sock.close()
            self._sock = None

    def sources(self, prefix: bytes) -> set[tuple[str, int]]:
        """Return the recent (address, port) sources of ``prefix``'s datagrams."""
        now = time.monotonic()
        with self._lock:
            return {s for s, t in self.seen.get(prefix, {}).items() if now - t < EVIDENCE_SECONDS}

    def unproven(
        self, guid: bytes, proc: ProcId, proc_root: Path = PROC, wait: float = WAIT_SECONDS
    ) -> str | None:
        """Return why ``proc`` is not proven to run participant ``guid`` (None: proven).

        See the module docstring. Waits up to ``wait`` seconds for a first datagram.
        """
        if _uid(proc.pid, proc_root) != os.getuid():
            return f"process {proc.pid} runs as another user than this watch"
        prefix = guid[:12]
        deadline = time.monotonic() + wait
        while not (sources := self.sources(prefix)) and time.monotonic() < deadline:
            time.sleep(0.1)
        local = {socket.inet_ntoa(a) for a in fastdds_ipv4()}
        ports = {p for a, p in sources if a in local or a.startswith("127.")}
        if not ports:
            return (
                "no discovery datagram of its participant came from this host "
                f"(listened on {SPDP_GROUP}:{spdp_port(self.domain)})"
            )
        try:
            held = socket_ports(proc.pid, proc_root)
        except OSError as exc:
            return f"process {proc.pid}'s sockets cannot be read ({exc.strerror})"
        if not ports <= held:
            senders = udp_port_holders(ports - held, proc_root) - {proc.pid}
            by = f" (process(es) {sorted(senders)} do)" if senders else ""
            return (
                f"its participant's datagrams come from port(s) {sorted(ports - held)}, which "
                f"process {proc.pid} does not hold{by}"
            )
        others = udp_port_holders(ports, proc_root) - {proc.pid}
        if others:
            return (
                f"port(s) {sorted(ports)} of its participant are held by process(es) "
                f"{sorted(others)} too"
            )
        return None
