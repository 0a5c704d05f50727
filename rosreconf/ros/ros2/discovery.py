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

The cyclonedds binding, rmw's discovery type and QoS conversion are in ``dds``; joining the
samples into a ``LiveGraph`` is ``graph`` (pure data, testable without DDS).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2.dds import ALIVE, info_type, load_dds, qos_from_dds, user_data
from rosreconf.ros.ros2.graph import Endpoint, NodeInfo, build_graph, graph_uri
from rosreconf.ros.ros2.names import DISCOVERY_TOPIC

__all__ = [
    "DISTROS",
    "GID_SIZES",
    "Ros2Discovery",
    "check_domain",
    "gid_sizes",
    "graph_uri",
    "read_ros2_graph",
]

GID_SIZES = {"humble": 24, "iron": 16, "jazzy": 16, "kilted": 16, "rolling": 16}
"""The Gid message's size in each ROS 2 distribution (Humble's is 24 bytes)."""
DISTROS = tuple(GID_SIZES)


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
    _conditions: dict[str, tuple[Any, Any, Any]] = field(default_factory=dict, repr=False)
    _last_endpoints: dict[bytes, Endpoint] = field(default_factory=dict, repr=False)
    _kept: dict[str, dict[bytes, Any]] = field(default_factory=dict, repr=False)
    _changed: dict[str, bool] = field(default_factory=dict, repr=False)
    _settled: bool = False

    def __post_init__(self) -> None:
        check_domain(self.domain)
        sizes = gid_sizes(self.distro)
        self._dds = dds = load_dds()
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
                    core.ReadCondition(
                        reader,
                        core.ViewState.Any | core.SampleState.NotRead | core.InstanceState.Alive,
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
                topic = dds.topic.Topic(dp, DISCOVERY_TOPIC, info_type(dds, size))
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
        """Return the samples of alive instances of a built-in topic; drop the others.

        Converting a sample costs the binding about 1.6 ms on a busy machine (its QoS), so a
        graph of 1,000 endpoints took over a second to read: what was read is kept, only
        new samples are read, and everything is read again only when an instance has gone.
        """
        reader = self._readers[name]
        alive, gone, fresh = self._conditions[name]
        for attempt in range(5):
            # The binding raises a bare Exception on a sample without data; an instance may
            # die between the take and the read, so try again.
            left = False
            try:
                while (n := len(reader.take(N=BATCH, condition=gone))) > 0:
                    left = True
                    if n < BATCH:
                        break
            except Exception:
                left = True
            try:
                kept = self._kept.get(name)
                if kept is not None and not left:
                    new = _read_new(reader, fresh)
                    kept.update((s.key.bytes, s) for s in new if _is_alive(s))
                    self._changed[name] = bool(new)
                    return list(kept.values())
                samples: list[Any] = _read_all(reader, alive)
            except Exception as exc:
                if attempt == 4:
                    raise ExternalToolError(f"reading DDS {name} discovery failed: {exc}") from None
                time.sleep(0.01)
                continue
            self._kept[name] = {s.key.bytes: s for s in samples if _is_alive(s)}
            self._changed[name] = True
            return list(self._kept[name].values())
        return []

    def _participants(self) -> dict[bytes, bytes]:
        """Return alive participants: GUID -> USER_DATA."""
        policy = self._dds.qos.Policy
        return {s.key.bytes: user_data(s.qos, policy) for s in self._alive("participant")}

    def _endpoints(self) -> dict[bytes, Endpoint]:
        """Return every alive endpoint, keyed by GUID (converted again only after a change)."""
        policy = self._dds.qos.Policy
        samples = {kind: self._alive(kind) for kind in ("publication", "subscription")}
        if self._last_endpoints and not any(self._changed.get(k, True) for k in samples):
            return self._last_endpoints
        found: dict[bytes, Endpoint] = {}
        for kind, alive in samples.items():
            for s in alive:
                found[s.key.bytes] = Endpoint(
                    guid=s.key.bytes,
                    participant=s.participant_key.bytes,
                    topic=s.topic_name,
                    type_name=s.type_name,
                    writer=kind == "publication",
                    qos=qos_from_dds(s.qos, policy),
                    user_data=user_data(s.qos, policy),
                )
        return found

    def _take_infos(self) -> None:
        """Take new ``ros_discovery_info`` samples; keep each participant's newest."""
        for size, reader in self._info_readers.items():
            for sample in _take_all(reader):
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


BATCH = 256
"""Samples asked for per call: the binding allocates room for N samples on every call, so
N = 1,000,000 cost about 0.27 s a call (measured: 3 reads of a 15-endpoint graph, 4.9 s)."""


def _is_alive(sample: Any) -> bool:
    return bool(sample.sample_info.instance_state == ALIVE)


def _read_all(reader: Any, condition: Any) -> list[Any]:
    """Read every sample the condition selects, asking for room only as it is needed."""
    size = BATCH
    while True:
        samples: list[Any] = reader.read(N=size, condition=condition)
        if len(samples) < size:
            return samples
        size *= 8


def _read_new(reader: Any, condition: Any) -> list[Any]:
    """Read every sample not read before, a batch at a time (each read marks its batch read)."""
    new: list[Any] = []
    while True:
        batch: list[Any] = reader.read(N=BATCH, condition=condition)
        new += batch
        if len(batch) < BATCH:
            return new


def _take_all(reader: Any) -> list[Any]:
    """Take every sample there is, a batch at a time."""
    taken: list[Any] = []
    while True:
        batch: list[Any] = reader.take(N=BATCH)
        taken += batch
        if len(batch) < BATCH:
            return taken


def read_ros2_graph(
    domain: int, *, distro: str | None = None, settle: float = 1.0, timeout: float = 8.0
) -> LiveGraph:
    """Join ``domain``, wait for discovery to settle, and return the ROS 2 graph."""
    with Ros2Discovery(domain, distro) as session:
        return session.read(settle=settle, timeout=timeout)
