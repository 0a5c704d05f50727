"""Speak DDS through the ``cyclonedds`` wheel: its modules, rmw's discovery type, QoS in rmw terms.

``cyclonedds`` is an optional extra (``rosreconf[ros2]``): ``load_dds`` imports it on first
use and says how to install it. ``info_type`` builds rmw_dds_common's
``ParticipantEntitiesInfo`` (the ``ros_discovery_info`` sample) for one Gid layout;
``qos_from_dds`` turns a discovered endpoint's DDS QoS into the ``QosProfile`` the model
checks, the way rmw_cyclonedds does. Nothing here joins a domain: ``discovery`` does.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rosreconf.errors import ExternalToolError
from rosreconf.model.qos import Durability, History, Liveliness, QosProfile, Reliability

INFINITE_NS = 0x7FFFFFFFFFFFFFFF
"""DDS_INFINITY, how discovery reports "no deadline" and "no lease"."""
ALIVE = 16
"""DDS_ALIVE_INSTANCE_STATE."""


CYCLONE_COMPATIBILITY = (
    '<CycloneDDS><Domain Id="any"><Compatibility>'
    "<IgnoreTypeInformation>1.15</IgnoreTypeInformation>"
    "</Compatibility></Domain></CycloneDDS>"
)
"""What rosreconf adds to the user's Cyclone configuration: ignore the XTypes type information
of eProsima's participants (vendor id 1.15), which Cyclone 11 rejects for Fast DDS 3's
``ros_discovery_info`` (eclipse-cyclonedds/cyclonedds#2333)."""


def cyclone_config(user: str | None) -> str:
    """Return the Cyclone configuration: the user's ``CYCLONEDDS_URI`` first, then ours.

    Cyclone takes a comma-separated list of files and XML fragments and merges them in
    order, so everything the user set stays (network interfaces, peers, leases, tracing).
    """
    user = (user or "").strip().strip(",")
    return f"{user},{CYCLONE_COMPATIBILITY}" if user else CYCLONE_COMPATIBILITY


_BATCH = 1024
"""Samples asked for per call: the binding allocates buffers for N, whatever arrives
(N = 10^6 cost 0.27 s per call here, which made every read take over a second)."""


def take_all(reader: Any, **kw: Any) -> list[Any]:
    """Take every sample, in batches."""
    out: list[Any] = []
    while True:
        batch = reader.take(N=_BATCH, **kw)
        out += batch
        if len(batch) < _BATCH:
            return out


def read_new(reader: Any, **kw: Any) -> list[Any]:
    """Read every sample not read before, a batch at a time, keeping every batch.

    For a condition on unread samples: each read marks its batch read, so asking again with
    room for more (as ``read_all`` does) would return only the rest and lose the first batch.
    """
    out: list[Any] = []
    while True:
        batch: list[Any] = reader.read(N=_BATCH, **kw)
        out += batch
        if len(batch) < _BATCH:
            return out


def read_all(reader: Any, **kw: Any) -> list[Any]:
    """Read every sample (reading keeps them: ask again for more when a batch is full).

    Only for conditions that select samples whether read or not (``read_new`` otherwise).
    """
    n = _BATCH
    while True:
        batch: list[Any] = reader.read(N=n, **kw)
        if len(batch) < n:
            return batch
        n *= 8


def load_dds() -> Modules:
    """Import the cyclonedds modules used here, or say how to install them."""
    try:
        import cyclonedds.builtin as builtin
        import cyclonedds.core as core
        import cyclonedds.domain as domain
        import cyclonedds.idl as idl
        import cyclonedds.idl.types as types
        import cyclonedds.pub as pub
        import cyclonedds.qos as qos
        import cyclonedds.sub as sub
        import cyclonedds.topic as topic
        import cyclonedds.util as util
    except ImportError as exc:
        raise ExternalToolError(
            f"reading a ROS 2 graph needs the cyclonedds package ({exc}): "
            "pip install 'rosreconf[ros2]'"
        ) from None
    return Modules(builtin, core, domain, idl, types, qos, sub, topic, util, pub)


@dataclass(frozen=True)
class Modules:
    """The cyclonedds modules, imported on first use (the extra is optional)."""

    builtin: Any
    core: Any
    domain: Any
    idl: Any
    types: Any
    qos: Any
    sub: Any
    topic: Any
    util: Any
    pub: Any


def info_type(dds: Modules, size: int) -> Any:
    """Build rmw_dds_common's ``ParticipantEntitiesInfo`` with a ``size``-byte Gid.

    From ``rmw_dds_common/msg/*.msg``: ``Gid {char[N] data}``, ``NodeEntitiesInfo
    {string<=256 node_namespace; string<=256 node_name; Gid[] reader_gid_seq; Gid[]
    writer_gid_seq}``, ``ParticipantEntitiesInfo {Gid gid; NodeEntitiesInfo[]
    node_entities_info_seq}``; ROS ``char`` is a uint8.
    """
    t, make = dds.types, dds.idl.make_idl_struct
    gid = make(f"Gid{size}_", "rmw_dds_common::msg::dds_::Gid_", {"data": t.array[t.uint8, size]})
    node = make(
        f"NodeEntitiesInfo{size}_",
        "rmw_dds_common::msg::dds_::NodeEntitiesInfo_",
        {
            "node_namespace": t.bounded_str[256],
            "node_name": t.bounded_str[256],
            "reader_gid_seq": t.sequence[gid],
            "writer_gid_seq": t.sequence[gid],
        },
    )
    return make(
        f"ParticipantEntitiesInfo{size}_",
        "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_",
        {"gid": gid, "node_entities_info_seq": t.sequence[node]},
    )


def qos_from_dds(qos: Any, policy: Any) -> QosProfile:
    """Convert a discovered endpoint's DDS QoS to rmw terms, as rmw_cyclonedds does.

    (``dds_qos_to_rmw_qos``: DDS infinity becomes "none"; TRANSIENT and PERSISTENT durability,
    which ROS never sets, count as transient local; manual-by-participant liveliness, which
    ROS never sets either, counts as automatic.) History and depth are not part of what
    DDS discovery announces (the RTPS publication and subscription data have no HISTORY), so
    the depth is None, "unknown", never a made-up value.
    """

    def seconds(ns: int) -> float | None:
        return None if ns >= INFINITE_NS else ns / 1e9

    rel = qos[policy.Reliability]
    dur = qos[policy.Durability]
    deadline = qos[policy.Deadline]
    live = qos[policy.Liveliness]
    return QosProfile(
        reliability=(
            Reliability.BEST_EFFORT
            if rel == policy.Reliability.BestEffort
            else Reliability.RELIABLE
        ),
        durability=(
            Durability.VOLATILE
            if dur is None or dur == policy.Durability.Volatile
            else Durability.TRANSIENT_LOCAL
        ),
        deadline=None if deadline is None else seconds(deadline.deadline),
        liveliness=(
            Liveliness.MANUAL_BY_TOPIC
            if isinstance(live, policy.Liveliness.ManualByTopic)
            else Liveliness.AUTOMATIC
        ),
        lease_duration=None if live is None else seconds(live.lease_duration),
        history=History.KEEP_LAST,
        depth=None,
    )


def user_data(qos: Any, policy: Any) -> bytes:
    """Return an entity's USER_DATA bytes (empty when it has none)."""
    data = qos[policy.Userdata]
    return bytes(data.data) if data is not None else b""
