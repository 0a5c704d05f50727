"""What a Fast DDS GUID says of its process (host id, pid bits), and a domain's RTPS ports.

Fast DDS (eProsima/Fast-DDS ``src/cpp/rtps/common/GuidUtils.hpp``, 2.x and 3.x) fills each
participant's 12-byte GUID prefix as: bytes 0-1 the vendor id 01 0f, bytes 2-3 a host id
(little endian), bytes 4-5 the 16 low bits of getpid() (little endian), bytes 6-7 random,
bytes 8-11 a per-process participant counter. The host id is ``Host::compute_id``
(``src/cpp/utils/Host.hpp``), recomputed here the same way so that a participant of this
host is told from another host's without any process of ours speaking Fast DDS: rosreconf's
own participant is Cyclone's (vendor 01 10), whose GUIDs carry no pid.
Checked against real participants: Jazzy (Fast DDS 2.14) and Kilted (3.2) on this host
both wrote the host id computed here.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import hashlib
from collections.abc import Sequence

FASTDDS_VENDOR = b"\x01\x0f"
"""eProsima's RTPS vendor id, the first two bytes of every Fast DDS GUID."""

_IFF_RUNNING = 0x40
_AF_INET = 2


def fastdds_fields(guid: bytes) -> tuple[int, int] | None:
    """Return (host id, pid low 16 bits) of a Fast DDS GUID, or None for another vendor."""
    if len(guid) < 12 or guid[:2] != FASTDDS_VENDOR:
        return None
    return int.from_bytes(guid[2:4], "little"), int.from_bytes(guid[4:6], "little")


def low_pid(pid: int) -> int:
    """Return the bits of ``pid`` a Fast DDS GUID carries (its low 16)."""
    return pid & 0xFFFF


def may_be_of(guid: bytes, pid: int) -> bool:
    """Tell whether participant ``guid`` may be process ``pid``'s: a Fast DDS GUID must carry
    its low pid bits; another vendor's carries nothing to tell by.
    """
    fields = fastdds_fields(guid)
    return fields is None or fields[1] == low_pid(pid)


def compute_host_id(ipv4: Sequence[bytes]) -> int:
    """Return Fast DDS's host id for these IPv4 addresses, in ``getifaddrs`` order.

    ``Host::compute_id`` (Fast DDS 2.14 and 3.2): MD5 over each address as a 16-byte locator
    address (12 zero bytes, then the 4 address bytes), the digest folded by XOR into 16 bits
    read big endian; no address gives bytes 127, 1.
    """
    if not ipv4:
        return int.from_bytes(bytes((127, 1)), "little")
    md5 = hashlib.md5(usedforsecurity=False)
    for address in ipv4:
        md5.update(bytes(12) + address)
    digest = md5.digest()
    value = 0
    for i in range(0, 16, 2):
        value ^= (digest[i] << 8) | digest[i + 1]
    return value


class _SockaddrIn(ctypes.Structure):
    _fields_ = (
        ("family", ctypes.c_ushort),
        ("port", ctypes.c_ushort),
        ("addr", ctypes.c_ubyte * 4),
    )


class _Ifaddrs(ctypes.Structure):
    pass


_Ifaddrs._fields_ = (
    ("next", ctypes.POINTER(_Ifaddrs)),
    ("name", ctypes.c_char_p),
    ("flags", ctypes.c_uint),
    ("addr", ctypes.POINTER(_SockaddrIn)),
    ("netmask", ctypes.c_void_p),
    ("ifu", ctypes.c_void_p),
    ("data", ctypes.c_void_p),
)


def fastdds_ipv4() -> list[bytes]:
    """Return the IPv4 addresses Fast DDS hashes into its host id, in its order.

    ``IPFinder::getIP4Address``: every running interface's IPv4 address from
    ``getifaddrs``, in that order, without 127.0.0.1. The order matters to the hash, so
    this asks libc as Fast DDS does (no other source keeps it).
    """
    libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
    head = ctypes.POINTER(_Ifaddrs)()
    if libc.getifaddrs(ctypes.byref(head)) != 0:
        return []
    found: list[bytes] = []
    try:
        entry = head
        while entry:
            ifa = entry.contents
            if ifa.addr and ifa.flags & _IFF_RUNNING and ifa.addr.contents.family == _AF_INET:
                address = bytes(ifa.addr.contents.addr)
                if address != b"\x7f\x00\x00\x01":
                    found.append(address)
            entry = ifa.next
    finally:
        libc.freeifaddrs(head)
    return found


def this_host_id() -> int:
    """Return the host id a Fast DDS process started here now writes into its GUIDs.

    A process started before an interface changed (DHCP, Wi-Fi) computed another id: it is
    then taken for another host and watched by its lease, which is slower but never wrong.
    """
    return compute_host_id(fastdds_ipv4())


def domain_ports(domain: int) -> tuple[frozenset[int], frozenset[tuple[int, int]]]:
    """Return the domain's RTPS discovery multicast port and its unicast port pairs.

    RTPS 2.x port mapping (PB 7400, DG 250, PG 2, d0 0, d1 10, d3 11): participant i of
    domain d takes 7410 + 250 d + 2 i (discovery) and the next port (user traffic).
    """
    base = 7400 + 250 * domain
    pairs = frozenset((base + 10 + 2 * i, base + 11 + 2 * i) for i in range(120))
    return frozenset({base}), pairs
