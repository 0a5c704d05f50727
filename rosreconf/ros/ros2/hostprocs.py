"""Find the process on this host that runs a ROS 2 participant, and prove it through /proc.

Supervising nodes rosreconf did not start needs their processes: a process watched for its
exit is seen failing in milliseconds, where a DDS lease takes 20 s (Fast DDS's default).
ROS 2 offers no "pid of node" query, but Fast DDS (the default middleware) writes one into
each participant's GUID prefix (eProsima/Fast-DDS ``src/cpp/rtps/common/GuidUtils.hpp``,
2.x and 3.x)::

    bytes 0-1  vendor id 01 0f (eProsima)
    bytes 2-3  host id, little endian (``Host::compute_id``: the same for a host's processes)
    bytes 4-5  the 16 low bits of getpid(), little endian
    bytes 6-7  random; bytes 8-11 a per-process participant counter

A participant's ROS GID is its GUID, so ``ros_discovery_info`` links nodes to it. The pid
bits are a hint, not an identity (pids wrap at 16 bits, and pid namespaces renumber), so a
candidate is **confirmed** only when /proc proves it: it started before the participant was
seen, and it holds UDP sockets on the domain's RTPS well-known ports (7400 + 250 d: the
multicast discovery port, or a unicast pair 7410 + 250 d + 2 i and the next port), which
only a DDS participant of that domain binds. Exactly one such process, with no candidate
left unreadable, is a confirmed pid; anything else is said as such and never guessed.
``__node:=`` arguments on the command line are reported as extra evidence only: most
launched processes (``ros2 run``, component containers) carry none.

A participant of this host whose process is **gone** is proven so, not guessed, before its
lease ends (Fast DDS: 20 s): no process here whose own pid (its innermost namespace's, as
``getpid`` gave Fast DDS) has the GUID's 16 low bits started before the participant was
seen, and every UDP socket of this network namespace on the domain's RTPS ports belongs to
a process read here. The second half is what makes the first a proof: a participant that
writes this host's id hashed this network namespace's addresses (``fastdds_ids``), so while
it lives it holds sockets of the domain here; a process out of sight (another pid
namespace, as a sibling container of a pod sharing the network; another user's process,
whose file descriptors are closed to us) would leave such a socket unaccounted for, and the
participant is then only "no candidate", watched by its lease. What is left is a 16-bit host
id: another machine whose addresses hash to this host's (about 1 in 65,536) is taken for
this host, by locating as well.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from pathlib import Path

from rosreconf.procs.procstat import PROC, read_stat
from rosreconf.ros.ros2.fastdds_ids import domain_ports, fastdds_fields, low_pid, this_host_id


class Found(StrEnum):
    """What locating a participant's process came to (only CONFIRMED carries a pid)."""

    CONFIRMED = "confirmed"
    OTHER_VENDOR = "other-vendor"  # not Fast DDS: the GUID carries no pid (watch by lease)
    OTHER_HOST = "other-host"  # Fast DDS on another host id (watch by lease)
    NO_CANDIDATE = "no-candidate"  # no process here has those pid bits and started before
    GONE = "gone"  # no candidate, and no process out of sight could hold it: it has ended
    NOT_READABLE = "not-readable"  # a candidate's /proc/<pid>/fd is not ours to read
    UNCONFIRMED = "unconfirmed"  # candidates, but none holds the domain's sockets
    AMBIGUOUS = "ambiguous"  # more than one candidate holds the domain's sockets


@dataclass(frozen=True, order=True)
class ProcId:
    """A process as the kernel names it once: its pid and its start time.

    A pid alone is recycled; with the start time (clock ticks after boot, /proc/<pid>/stat
    field 22) it names one process for ever, so a later signal or pidfd can check that the
    pid still belongs to it.
    """

    pid: int
    start_ticks: int


@dataclass(frozen=True)
class Located:
    """Where a participant's process is, or why it is not known.

    Attributes:
        participant: the participant's 16-byte GUID.
        found: what the search came to.
        proc: the confirmed process (only when ``found`` is CONFIRMED).
        nodes: the participant's nodes (every node the process runs through it).
        detail: one sentence for a person: the evidence, or why there is none.
        candidates: pids whose low 16 bits matched (for the message).
    """

    participant: bytes
    found: Found
    proc: ProcId | None
    nodes: tuple[str, ...]
    detail: str
    candidates: tuple[int, ...] = ()

    @property
    def confirmed(self) -> bool:
        """Return True when ``proc`` is proven to run the participant."""
        return self.found is Found.CONFIRMED


@dataclass(frozen=True)
class _Proc:
    proc: ProcId
    inner_pid: int  # the pid the process sees itself as (its innermost namespace)


def read_proc_id(pid: int, proc_root: Path = PROC) -> ProcId | None:
    """Return the ProcId of a live pid (None: no such process)."""
    stat = read_stat(pid, proc_root)
    return None if stat is None else ProcId(pid, stat.start_ticks)


def _processes(proc_root: Path) -> list[_Proc]:
    """Return every visible process with the pid it knows itself by."""
    found: list[_Proc] = []
    for entry in os.scandir(proc_root):
        if not entry.name.isdigit():
            continue
        pid = int(entry.name)
        stat = read_stat(pid, proc_root)
        inner = pid
        try:
            for line in (proc_root / entry.name / "status").read_text().splitlines():
                if line.startswith("NSpid:"):
                    inner = int(line.split()[-1])
                    break
        except (OSError, ValueError):
            pass
        if stat is not None and stat.state not in "ZX":  # a zombie runs nothing any more
            found.append(_Proc(ProcId(pid, stat.start_ticks), inner))
    return found


def _udp_ports(proc_root: Path, pid: int | str) -> dict[int, int]:
    """Return socket inode -> local UDP port in the process's own network namespace.

    ``pid`` may be ``"self"``: this process's network namespace.
    """
    ports: dict[int, int] = {}
    for name in ("udp", "udp6"):
        try:
            lines = (proc_root / str(pid) / "net" / name).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            cols = line.split()
            if len(cols) > 9:
                ports[int(cols[9])] = int(cols[1].rsplit(":", 1)[1], 16)
    return ports


def _socket_inodes(proc_root: Path, pid: int) -> set[int]:
    """Return the inodes of the sockets a process holds (PermissionError: not ours to read)."""
    fd_dir = proc_root / str(pid) / "fd"
    inodes: set[int] = set()
    for fd in os.listdir(fd_dir):  # PermissionError for another user's process
        try:
            target = os.readlink(fd_dir / fd)
        except OSError:
            continue
        if target.startswith("socket:["):
            inodes.add(int(target[8:-1]))
    return inodes


def socket_ports(pid: int, proc_root: Path = PROC) -> frozenset[int]:
    """Return the UDP ports a process holds open (PermissionError: not ours to read)."""
    inodes = _socket_inodes(proc_root, pid)
    by_inode = _udp_ports(proc_root, pid)
    return frozenset(by_inode[i] for i in inodes if i in by_inode)


def udp_port_holders(ports: Collection[int], proc_root: Path = PROC) -> set[int]:
    """Return the pids of the processes here that hold one of the UDP ``ports`` open.

    Only processes whose descriptors this one may read are seen (all of them, as root).
    """
    found: set[int] = set()
    wanted = set(ports)
    for entry in os.scandir(proc_root):
        if entry.name.isdigit():
            with contextlib.suppress(OSError):
                if socket_ports(int(entry.name), proc_root) & wanted:
                    found.add(int(entry.name))
    return found


def domain_sockets(domain: int, proc_root: Path = PROC) -> set[int] | None:
    """Return the inodes of this network namespace's UDP sockets on ``domain``'s RTPS ports.

    None when the table cannot be read (nothing can then be proven from it).
    """
    if not (proc_root / "self" / "net" / "udp").exists():
        return None
    multicast, pairs = domain_ports(domain)
    ports = {*multicast, *(p for pair in pairs for p in pair)}
    return {inode for inode, port in _udp_ports(proc_root, "self").items() if port in ports}


def holds_domain(ports: Iterable[int], domain: int) -> bool:
    """Return True when ``ports`` include the domain's discovery multicast port or a pair."""
    held = set(ports)
    multicast, pairs = domain_ports(domain)
    return bool(held & multicast) or any(a in held and b in held for a, b in pairs)


def cmdline_names(pid: int, proc_root: Path = PROC) -> tuple[str, ...]:
    """Return the node names a process's ``__node:=`` / ``__name:=`` arguments give it."""
    try:
        args = (proc_root / str(pid) / "cmdline").read_bytes().split(b"\0")
    except OSError:
        return ()
    names = []
    for arg in args:
        text = arg.decode(errors="replace")
        for key in ("__node:=", "__name:="):
            if key in text:
                names.append(text.split(key, 1)[1])
    return tuple(names)


def boot_seconds() -> float:
    """Return seconds since boot on the clock /proc start times count in."""
    return time.clock_gettime(time.CLOCK_BOOTTIME)


class HostProcesses:
    """One scan of this host's processes, to locate many participants against.

    Attributes:
        host_ids: the Fast DDS host ids taken as this host's.
        proc_root: where /proc is (a test may point elsewhere).
    """

    def __init__(self, host_ids: Iterable[int] | None = None, proc_root: Path = PROC) -> None:
        self.proc_root = proc_root
        self.host_ids = frozenset(host_ids) if host_ids is not None else {this_host_id()}
        self._ticks = os.sysconf("SC_CLK_TCK")
        self._by_low: dict[int, list[_Proc]] = {}
        self._in_sight: dict[int, bool] = {}
        for p in _processes(proc_root):
            self._by_low.setdefault(low_pid(p.inner_pid), []).append(p)

    def domain_in_sight(self, domain: int) -> bool:
        """Tell whether every socket of ``domain`` in this network namespace is a process's
        seen here: then no participant of this host's id runs out of sight (module docstring).

        Read once per scan; it reads every process's file descriptors, so only when a
        participant has no candidate at all (its process is likely gone).
        """
        if domain not in self._in_sight:
            left = domain_sockets(domain, self.proc_root)
            for p in (p for procs in self._by_low.values() for p in procs):
                if not left:
                    break
                try:
                    left -= _socket_inodes(self.proc_root, p.proc.pid)
                except OSError:  # not ours to read, or gone: its sockets stay unexplained
                    continue
            self._in_sight[domain] = left is not None and not left
        return self._in_sight[domain]

    def locate(
        self,
        participant: bytes,
        domain: int,
        nodes: Sequence[str] = (),
        *,
        seen_at: float | None = None,
    ) -> Located:
        """Return the process that runs ``participant`` on ``domain``, or why none is known.

        ``seen_at`` is when the participant was first seen, in ``boot_seconds()``; a process
        started later cannot hold it (its pid was recycled). Default: now.
        """
        nodes = tuple(nodes)

        def said(found: Found, detail: str, cands: Sequence[int] = ()) -> Located:
            return Located(participant, found, None, nodes, detail, tuple(cands))

        fields = fastdds_fields(participant)
        if fields is None:
            vendor = participant[:2].hex(" ")
            return said(Found.OTHER_VENDOR, f"vendor {vendor} is not Fast DDS: no pid in its GUID")
        host, low = fields
        if host not in self.host_ids:
            mine = ", ".join(f"{h:#06x}" for h in sorted(self.host_ids))
            return said(Found.OTHER_HOST, f"Fast DDS host id {host:#06x}, this host's {mine}")
        seen = boot_seconds() if seen_at is None else seen_at
        cands = [
            p.proc
            for p in self._by_low.get(low, ())
            if p.proc.start_ticks / self._ticks <= seen + 1.0 / self._ticks
        ]
        pids = [c.pid for c in cands]
        if not cands and self.domain_in_sight(domain):
            return said(
                Found.GONE,
                f"no process here has the pid its GUID ends in ({low:#06x}), and every "
                f"socket of domain {domain} here is a process's seen here: its process has ended",
            )
        if not cands:
            return said(
                Found.NO_CANDIDATE,
                f"no process here whose pid ends in {low:#06x} started before it was seen "
                "(gone, or in a pid namespace this one cannot see)",
            )
        holding: list[ProcId] = []
        unreadable: list[int] = []
        for c in cands:
            try:
                ports = socket_ports(c.pid, self.proc_root)
            except PermissionError:
                unreadable.append(c.pid)
                continue
            except OSError:
                continue  # it exited meanwhile
            if holds_domain(ports, domain) and read_proc_id(c.pid, self.proc_root) == c:
                holding.append(c)
        if len(holding) > 1 or (holding and unreadable):
            return said(
                Found.AMBIGUOUS,
                f"pids {', '.join(map(str, pids))} all may hold it (domain {domain} sockets)",
                pids,
            )
        if holding:
            proc = holding[0]
            named = [n for n in cmdline_names(proc.pid, self.proc_root) if _names(n, nodes)]
            extra = f"; its command line names {', '.join(named)}" if named else ""
            return Located(
                participant,
                Found.CONFIRMED,
                proc,
                nodes,
                f"pid {proc.pid} holds domain {domain}'s RTPS sockets and started before the "
                f"participant{extra}",
                tuple(pids),
            )
        if unreadable:
            return said(
                Found.NOT_READABLE,
                f"cannot read /proc/<pid>/fd of pid {', '.join(map(str, unreadable))} "
                "(another user's process)",
                pids,
            )
        return said(
            Found.UNCONFIRMED,
            f"pid {', '.join(map(str, pids))} ends in {low:#06x} but holds no socket of "
            f"domain {domain}",
            pids,
        )


def _names(arg: str, nodes: Sequence[str]) -> bool:
    """Return True when a ``__node:=`` value names one of ``nodes`` (by its last part)."""
    return any(n.rsplit("/", 1)[-1] == arg for n in nodes)


def locate_participants(
    participants: Mapping[bytes, Sequence[str]],
    domain: int,
    *,
    seen_at: Mapping[bytes, float] | None = None,
    host: HostProcesses | None = None,
) -> dict[bytes, Located]:
    """Locate each participant (GUID -> its node names) with one scan of /proc."""
    host = host or HostProcesses()
    seen = seen_at or {}
    return {
        guid: host.locate(guid, domain, nodes, seen_at=seen.get(guid))
        for guid, nodes in participants.items()
    }


def nodes_by_process(located: Mapping[bytes, Located]) -> dict[ProcId, tuple[str, ...]]:
    """Return each confirmed process with every node it runs, over all its participants.

    A process may hold several participants (rclpy contexts) and a participant several
    nodes (a component container, an executor with many nodes): signalling the process for
    one of them takes all of these down.
    """
    found: dict[ProcId, list[str]] = {}
    for where in located.values():
        if where.proc is not None:
            found.setdefault(where.proc, []).extend(where.nodes)
    return {proc: tuple(sorted(set(names))) for proc, names in found.items()}
