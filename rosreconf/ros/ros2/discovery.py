"""Read a running ROS 2 graph from DDS discovery, with the ``cyclonedds`` wheel only.

ROS 2 announces its graph over standard DDS discovery, so no ROS 2 installation is needed to
read it (rmw_cyclonedds_cpp and rmw_fastrtps_cpp, Humble to Rolling; the sources this follows
are cited in ``docs/ros2.md``). Three things are read, in one DDS participant of our own that
announces no ROS node (it has no ``enclave=`` user data, so ROS tools ignore it)::

    DDS                                        here
    -----------------------------------------  ---------------------------------------------
    DCPSParticipant, USER_DATA "enclave=..;"   the ROS participants (others are ignored);
                                               one whose lease expires is gone, with its nodes
    DCPSPublication / DCPSSubscription         every endpoint: GUID, topic, type, QoS
    ros_discovery_info (rmw_dds_common         participant GID -> nodes (namespace, name)
      ParticipantEntitiesInfo)                 -> their reader and writer GIDs

A GID is the endpoint's 16-byte DDS GUID, zero-padded to the Gid message's size: 24 bytes up
to Humble, 16 from Iron on (rmw_dds_common #68, same type name). ``distro`` picks the layout;
without it both are read, and each participant's sample is taken in the layout its own
endpoints announce: Iron and later put ``typehash=RIHS01_...;`` in every endpoint's USER_DATA,
Humble does not. A sample is accepted only if its GID is the writing participant's GUID.

``ros_discovery_info`` is not keyed: each participant rewrites its whole state on every change,
all into one instance, so it is read with KEEP_ALL and the newest sample per participant is
kept here (this object is a session: ``watch`` keeps one open). Nothing here prints.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from contextlib import suppress
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.model.qos import Durability, History, Liveliness, QosProfile, Reliability
from rosreconf.ros.livegraph import LiveGraph, LiveNode
from rosreconf.ros.ros2.names import DISCOVERY_TOPIC, Channel, ros_name, ros_type

GID_SIZES = {"humble": 24, "iron": 16, "jazzy": 16, "kilted": 16, "rolling": 16}
"""The Gid message's size in each ROS 2 distribution (Humble's is 24 bytes)."""
DISTROS = tuple(GID_SIZES)
INFINITE_NS = 0x7FFFFFFFFFFFFFFF
"""DDS_INFINITY, how discovery reports "no deadline" and "no lease"."""
_ALIVE = 16
"""DDS_ALIVE_INSTANCE_STATE."""


def graph_uri(domain: int) -> str:
    """Return the ``master_uri`` a ROS 2 live graph of ``domain`` carries."""
    return f"ros2://domain/{domain}"


def check_domain(domain: int) -> None:
    """Refuse a domain id DDS cannot use (0-232 with the default port mapping)."""
    if not 0 <= domain <= 232:
        raise UsageError(f"--domain {domain}: a ROS 2 domain id is 0 to 232 (ROS_DOMAIN_ID)")


def gid_sizes(distro: str | None) -> tuple[int, ...]:
    """Return the Gid layouts to read for ``distro`` (both when it is not given)."""
    if distro is None:
        return (16, 24)
    try:
        return (GID_SIZES[distro.lower()],)
    except KeyError:
        raise UsageError(
            f"--distro {distro}: not a ROS 2 distribution rosreconf knows "
            f"(one of {', '.join(DISTROS)})"
        ) from None


def _dds() -> Any:
    """Import the cyclonedds modules used here, or say how to install them."""
    try:
        import cyclonedds.builtin as builtin
        import cyclonedds.core as core
        import cyclonedds.domain as domain
        import cyclonedds.idl as idl
        import cyclonedds.idl.types as types
        import cyclonedds.qos as qos
        import cyclonedds.sub as sub
        import cyclonedds.topic as topic
        import cyclonedds.util as util
    except ImportError as exc:
        raise ExternalToolError(
            f"reading a ROS 2 graph needs the cyclonedds package ({exc}): "
            "pip install 'rosreconf[ros2]'"
        ) from None
    return _Modules(builtin, core, domain, idl, types, qos, sub, topic, util)


@dataclass(frozen=True)
class _Modules:
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


def _info_type(dds: _Modules, size: int) -> Any:
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


@dataclass(frozen=True)
class Endpoint:
    """One DDS reader or writer as discovery announced it.

    Attributes:
        guid: its 16-byte GUID (its GID, unpadded).
        participant: its participant's GUID.
        topic: the DDS topic name (``rt/chatter``).
        type_name: the DDS type name.
        writer: True for a writer (publication), False for a reader.
        qos: its QoS in rmw terms.
        user_data: its USER_DATA (``typehash=...;`` from Iron on).
    """

    guid: bytes
    participant: bytes
    topic: str
    type_name: str
    writer: bool
    qos: QosProfile
    user_data: bytes


@dataclass(frozen=True)
class NodeInfo:
    """One node of a participant's ``ros_discovery_info`` sample."""

    namespace: str
    name: str
    readers: tuple[bytes, ...]
    writers: tuple[bytes, ...]

    @property
    def full_name(self) -> str:
        """Return the node's global name (``/ns`` + ``name``)."""
        ns = self.namespace.rstrip("/")
        return f"{ns}/{self.name}"


def qos_from_dds(qos: Any, policy: Any) -> QosProfile:
    """Convert a discovered endpoint's DDS QoS to rmw terms, as rmw_cyclonedds does.

    (``dds_qos_to_rmw_qos``: DDS infinity becomes "none"; TRANSIENT and PERSISTENT durability,
    which ROS never sets, count as transient local; manual-by-participant liveliness, which
    ROS never sets either, counts as automatic.)
    """

    def seconds(ns: int) -> float | None:
        return None if ns >= INFINITE_NS else ns / 1e9

    rel = qos[policy.Reliability]
    dur = qos[policy.Durability]
    deadline = qos[policy.Deadline]
    live = qos[policy.Liveliness]
    hist = qos[policy.History]
    keep_all = hist is not None and hist == policy.History.KeepAll
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
        history=History.KEEP_ALL if keep_all else History.KEEP_LAST,
        depth=0 if keep_all or hist is None else int(hist.depth),
    )


def _user_data(qos: Any, policy: Any) -> bytes:
    """Return an entity's USER_DATA bytes (empty when it has none)."""
    data = qos[policy.Userdata]
    return bytes(data.data) if data is not None else b""


@dataclass
class Ros2Discovery:
    """A DDS session on one domain that follows the ROS 2 graph as discovery announces it.

    Use as a context manager (``close`` deletes the participant). ``read`` returns the graph
    now; the first call waits until discovery has settled.

    Attributes:
        domain: the ROS_DOMAIN_ID.
        distro: the ROS 2 distribution, or None to read both Gid layouts.
    """

    domain: int
    distro: str | None = None
    _dds: Any = field(default=None, repr=False)
    _dp: Any = field(default=None, repr=False)
    _readers: dict[str, Any] = field(default_factory=dict, repr=False)
    _info_readers: dict[int, Any] = field(default_factory=dict, repr=False)
    _infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]] = field(default_factory=dict)
    _conditions: dict[str, tuple[Any, Any]] = field(default_factory=dict, repr=False)
    _last_endpoints: dict[bytes, Endpoint] = field(default_factory=dict, repr=False)
    _settled: bool = False

    def __post_init__(self) -> None:
        check_domain(self.domain)
        sizes = gid_sizes(self.distro)
        self._dds = dds = _dds()
        policy = dds.qos.Policy
        try:
            self._dp = dds.domain.DomainParticipant(self.domain)
            b = dds.builtin
            self._readers = {
                "participant": b.BuiltinDataReader(self._dp, b.BuiltinTopicDcpsParticipant),
                "publication": b.BuiltinDataReader(self._dp, b.BuiltinTopicDcpsPublication),
                "subscription": b.BuiltinDataReader(self._dp, b.BuiltinTopicDcpsSubscription),
            }
            core = dds.core
            for name, reader in list(self._readers.items()):
                # Only alive instances are read: a gone participant's or endpoint's last
                # sample carries no valid data, and the binding fails on it ("Sampleinfo
                # errored"); those are taken out separately and dropped.
                any_sample = core.ViewState.Any | core.SampleState.Any
                self._conditions[name] = (
                    core.ReadCondition(reader, any_sample | core.InstanceState.Alive),
                    core.ReadCondition(
                        reader,
                        any_sample
                        | core.InstanceState.NotAliveDisposed
                        | core.InstanceState.NotAliveNoWriters,
                    ),
                )
            info_qos = dds.qos.Qos(
                policy.Reliability.Reliable(max_blocking_time=dds.util.duration(seconds=1)),
                policy.Durability.TransientLocal,
                policy.History.KeepAll,
                policy.DataRepresentation(use_cdrv0_representation=True),
            )
            for size in sizes:
                # One participant per layout: a participant holds one type per topic name.
                dp = self._dp if size == sizes[0] else dds.domain.DomainParticipant(self.domain)
                topic = dds.topic.Topic(dp, DISCOVERY_TOPIC, _info_type(dds, size))
                self._info_readers[size] = dds.sub.DataReader(dp, topic, qos=info_qos)
        except dds.core.DDSException as exc:
            raise ExternalToolError(
                f"cannot join DDS domain {self.domain}: {exc} "
                "(check CYCLONEDDS_URI and the network interface)"
            ) from None

    def __enter__(self) -> Ros2Discovery:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Leave the domain (other participants see us go at once)."""
        self._readers.clear()
        self._info_readers.clear()
        self._dp = None

    def _alive(self, name: str) -> list[Any]:
        """Return the samples of alive instances of a built-in topic; drop the others."""
        reader = self._readers[name]
        alive, gone = self._conditions[name]
        for attempt in range(5):
            # The binding raises a bare Exception on a sample without data; an instance may
            # die between the take and the read, so try again.
            with suppress(Exception):
                reader.take(N=1_000_000, condition=gone)
            try:
                samples: list[Any] = reader.read(N=1_000_000, condition=alive)
            except Exception as exc:
                if attempt == 4:
                    raise ExternalToolError(f"reading DDS {name} discovery failed: {exc}") from None
                time.sleep(0.01)
                continue
            return [s for s in samples if s.sample_info.instance_state == _ALIVE]
        return []

    def _participants(self) -> dict[bytes, bytes]:
        """Return alive participants: GUID -> USER_DATA."""
        policy = self._dds.qos.Policy
        return {s.key.bytes: _user_data(s.qos, policy) for s in self._alive("participant")}

    def _endpoints(self) -> dict[bytes, Endpoint]:
        """Return every alive endpoint, keyed by GUID."""
        policy = self._dds.qos.Policy
        found: dict[bytes, Endpoint] = {}
        for kind in ("publication", "subscription"):
            for s in self._alive(kind):
                found[s.key.bytes] = Endpoint(
                    guid=s.key.bytes,
                    participant=s.participant_key.bytes,
                    topic=s.topic_name,
                    type_name=s.type_name,
                    writer=kind == "publication",
                    qos=qos_from_dds(s.qos, policy),
                    user_data=_user_data(s.qos, policy),
                )
        return found

    def _take_infos(self) -> None:
        """Take new ``ros_discovery_info`` samples; keep each participant's newest."""
        for size, reader in self._info_readers.items():
            for sample in reader.take(N=100_000):
                if not hasattr(sample, "gid"):
                    continue  # an InvalidSample: a writer left, no data
                gid = bytes(sample.gid.data)
                if len(gid) != size or any(gid[16:]):
                    continue  # another layout misread: not a GID
                nodes = tuple(
                    NodeInfo(
                        n.node_namespace,
                        n.node_name,
                        tuple(bytes(g.data)[:16] for g in n.reader_gid_seq),
                        tuple(bytes(g.data)[:16] for g in n.writer_gid_seq),
                    )
                    for n in sample.node_entities_info_seq
                )
                key = gid[:16]
                old = self._infos.get(key)
                if old is None or old[0] == size or size in self._layout_hint(key):
                    self._infos[key] = (size, nodes)

    def _layout_hint(self, participant: bytes) -> tuple[int, ...]:
        """Return the Gid size the participant's endpoints say it uses (typehash: Iron+)."""
        for e in self._last_endpoints.values():
            if e.participant == participant and e.topic == DISCOVERY_TOPIC and e.writer:
                return (16,) if b"typehash=" in e.user_data else (24,)
        return (16, 24)

    def read(self, *, settle: float = 1.0, timeout: float = 8.0) -> LiveGraph:
        """Return the ROS 2 graph now.

        The first call waits (at most ``timeout`` s) until discovery is complete: every ROS
        participant has sent its ``ros_discovery_info`` and every endpoint named there has
        been discovered, and nothing changed for ``settle`` s. Later calls do not wait.
        """
        if self._dp is None:
            raise UsageError("this ROS 2 discovery session is closed")
        start = time.monotonic()
        previous: object = None
        stable_since = start
        while True:
            taken_at = datetime.now(UTC)
            participants = self._participants()
            self._last_endpoints = endpoints = self._endpoints()
            self._take_infos()
            ros = {k for k, ud in participants.items() if b"enclave=" in ud}
            complete = all(k in self._infos for k in ros) and all(
                g in endpoints
                for k in ros
                if k in self._infos
                for n in self._infos[k][1]
                for g in (*n.readers, *n.writers)
            )
            state = (frozenset(participants), frozenset(endpoints), repr(self._infos))
            now = time.monotonic()
            if state != previous:
                previous, stable_since = state, now
            if self._settled or now - start >= timeout:
                break
            if complete and ros and now - stable_since >= settle:
                break
            if not ros and now - start >= max(settle * 2, 1.0):
                break
            time.sleep(0.05)
        self._settled = True
        return build_graph(self.domain, taken_at, ros, self._infos, endpoints)


def build_graph(
    domain: int,
    taken_at: datetime,
    ros_participants: Iterable[bytes],
    infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]],
    endpoints: dict[bytes, Endpoint],
) -> LiveGraph:
    """Join the nodes of alive ROS participants with their endpoints into a live graph."""
    topic_types: dict[str, str] = {}
    service_types: dict[str, str] = {}
    nodes: dict[str, LiveNode] = {}
    for participant in sorted(ros_participants):
        if participant not in infos:
            continue
        for info in infos[participant][1]:
            node = _node(info, endpoints, topic_types, service_types)
            if node.name in nodes:  # two contexts announce one name: ROS 2 allows it; merge
                node = _merge(nodes[node.name], node)
            nodes[node.name] = node
    return LiveGraph(
        graph_uri(domain),
        taken_at,
        tuple(nodes.values()),
        topic_types,
        ros_version=2,
        service_types=service_types,
    )


def _node(
    info: NodeInfo,
    endpoints: dict[bytes, Endpoint],
    topic_types: dict[str, str],
    service_types: dict[str, str],
) -> LiveNode:
    """Build one live node from its discovery entry and the endpoints its GIDs name."""
    pubs: dict[str, QosProfile] = {}
    subs: dict[str, QosProfile] = {}
    serves: set[str] = set()
    clients: set[str] = set()
    for gid in (*info.readers, *info.writers):
        e = endpoints.get(gid)
        if e is None:
            continue  # not discovered (yet), or gone
        named = ros_name(e.topic)
        typ = ros_type(e.type_name)
        if named is None or typ is None:
            continue
        channel, name = named
        if channel is Channel.TOPIC:
            (pubs if e.writer else subs).setdefault(name, e.qos)
            topic_types.setdefault(name, typ)
        else:
            service_types.setdefault(name, typ)
            server = (channel is Channel.REQUEST) != e.writer
            (serves if server else clients).add(name)
    return LiveNode(
        name=info.full_name,
        publishes=tuple(sorted(pubs)),
        subscribes=tuple(sorted(subs)),
        serves=tuple(sorted(serves)),
        clients=tuple(sorted(clients)),
        alive=True,
        publish_qos=pubs,
        subscribe_qos=subs,
    )


def _merge(a: LiveNode, b: LiveNode) -> LiveNode:
    """Join two announcements of one node name (ROS 2 does not forbid duplicates)."""
    return LiveNode(
        name=a.name,
        publishes=tuple(sorted({*a.publishes, *b.publishes})),
        subscribes=tuple(sorted({*a.subscribes, *b.subscribes})),
        serves=tuple(sorted({*a.serves, *b.serves})),
        clients=tuple(sorted({*a.clients, *b.clients})),
        alive=True,
        publish_qos={**b.publish_qos, **a.publish_qos},
        subscribe_qos={**b.subscribe_qos, **a.subscribe_qos},
    )


def read_ros2_graph(
    domain: int, *, distro: str | None = None, settle: float = 1.0, timeout: float = 8.0
) -> LiveGraph:
    """Join ``domain``, wait for discovery to settle, and return the ROS 2 graph."""
    with Ros2Discovery(domain, distro) as session:
        return session.read(settle=settle, timeout=timeout)
