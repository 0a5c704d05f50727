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
Humble does not. A sample is accepted only if its GID is the writing participant's GUID
(the writer's participant, as DDS matched it): another participant cannot speak for a third.

It joins with the user's ``CYCLONEDDS_URI`` plus ``dds.CYCLONE_COMPATIBILITY`` (Cyclone 11
rejects Fast DDS 3's XTypes type information: Kilted's nodes would stay unseen). A writer whose
samples never decode (another Gid layout) is undecodable after ``UNDECODABLE_AFTER`` s, not
waited for. When a participant's newest sample fails to decode (once in 7 reads at 40 Jazzy
nodes), its ROS endpoints are named by no node of the older sample (``stale``): the read then
makes fresh readers, at most every ``RENEW_EVERY`` s, which are sent the newest sample again.
KEEP_ALL, newest per participant.
"""

from __future__ import annotations

import os
import time
from collections.abc import Collection
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.ros.livegraph import LiveGraph
from rosreconf.ros.ros2 import cstderr
from rosreconf.ros.ros2.builtin import AliveFollower
from rosreconf.ros.ros2.dds import (
    cyclone_config,
    info_type,
    load_dds,
    qos_from_dds,
    take_all,
    user_data,
)
from rosreconf.ros.ros2.graph import (
    Endpoint,
    NodeInfo,
    build_graph,
    silent_participants,
    stale_participants,
    writing_since,
)
from rosreconf.ros.ros2.names import (
    DISCOVERY_TOPIC,
    check_domain,
    gid_sizes,
    ros_name,
)

__all__ = ["Ros2Discovery", "read_ros2_graph"]

UNDECODABLE_AFTER = 4.5
"""Seconds a ``ros_discovery_info`` writer may be known without one decodable sample: more
than Fast DDS's 3 s heartbeat, after which a sample Cyclone failed to take is sent again
(measured: a Jazzy participant's info arrived 0.03 to 3.03 s after its writer)."""

FIRST_READ_AT_LEAST = 3.5
"""Seconds the first read listens before it may settle or call the domain empty: Fast DDS
re-announces each participant every 3 s (``leaseDuration_announcementperiod``), and a
participant not yet heard of cannot hold a read back. Settling on 1 s of stillness alone
returned 24 of 40 real Jazzy nodes once, exit 0, on a loaded machine: two of five
participants had not answered yet, and a read moments later saw all 40."""

RENEW_EVERY = 5.0
"""Seconds between fresh ``ros_discovery_info`` readers while a participant stays stale (each
is sent every participant's newest sample again: cheap, but not for every poll)."""


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
    _readers: dict[str, AliveFollower] = field(default_factory=dict, repr=False)
    _info_readers: dict[int, Any] = field(default_factory=dict, repr=False)
    _infos: dict[bytes, tuple[int, tuple[NodeInfo, ...]]] = field(default_factory=dict)
    _converted: dict[bytes, tuple[Any, Endpoint]] = field(default_factory=dict, repr=False)
    _last_endpoints: dict[bytes, Endpoint] = field(default_factory=dict, repr=False)
    _settled: bool = False
    _renew: list[Any] = field(default_factory=list, repr=False)
    _renewed_at: float = float("-inf")
    _stale_since: float | None = None
    _domain: Any = field(default=None, repr=False)
    _writer_of: dict[int, bytes] = field(default_factory=dict, repr=False)
    _info_writer_since: dict[bytes, float] = field(default_factory=dict, repr=False)
    _present: frozenset[bytes] = frozenset()
    forged: int = 0
    """How many ``ros_discovery_info`` samples named a participant other than their writer's."""
    undecodable: frozenset[bytes] = frozenset()
    """ROS participants whose ``ros_discovery_info`` never decoded (their nodes are unseen)."""
    stale: frozenset[bytes] = frozenset()
    """ROS participants whose ROS endpoints the last read found named by none of their nodes
    (their newest ``ros_discovery_info`` was not received: the node list is out of date)."""
    participants: int = 0
    """How many DDS participants (ROS or not) the last read saw."""
    endpoints: int = 0
    """How many ROS endpoints (rt/, rq/, rr/ topics) the last read saw."""
    ros_participants: int = 0
    """How many ROS participants (``enclave=`` user data) the last read saw."""

    def __post_init__(self) -> None:
        check_domain(self.domain)
        sizes = gid_sizes(self.distro)
        self._dds = dds = load_dds()
        policy = dds.qos.Policy
        cstderr.hold()
        try:
            self._domain = self._join(dds)
            self._dp = dds.domain.DomainParticipant(self.domain)
            b = dds.builtin
            self._readers = {
                name: AliveFollower(dds, b.BuiltinDataReader(self._dp, topic), name)
                for name, topic in (
                    ("participant", b.BuiltinTopicDcpsParticipant),
                    ("publication", b.BuiltinTopicDcpsPublication),
                    ("subscription", b.BuiltinTopicDcpsSubscription),
                )
            }
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
                self._renew.append((size, dp, topic, info_qos))
        except dds.core.DDSException as exc:
            self.close()
            raise ExternalToolError(
                f"cannot join DDS domain {self.domain}: {exc} "
                "(check CYCLONEDDS_URI and the network interface)"
            ) from None

    def _join(self, dds: Any) -> Any:
        """Create the domain with the user's configuration and ours (None: it exists here)."""
        try:
            return dds.domain.Domain(self.domain, cyclone_config(os.environ.get("CYCLONEDDS_URI")))
        except dds.core.DDSException as exc:
            if "PRECONDITION" in str(exc).upper() or "-4" in str(exc):
                return None  # this process already has the domain (configured here before)
            raise

    @property
    def last_endpoints(self) -> dict[bytes, Endpoint]:
        """Return the endpoints the last read saw, keyed by GUID."""
        return dict(self._last_endpoints)

    @property
    def participant_nodes(self) -> dict[bytes, tuple[str, ...]]:
        """Return each alive participant's GUID -> its nodes (last read): one process each."""
        alive = {e.participant for e in self._last_endpoints.values()}
        return {k: tuple(n.full_name for n in v[1]) for k, v in self._infos.items() if k in alive}

    @property
    def participant(self) -> Any:
        """Return this session's DDS participant (for request/reply on the same domain)."""
        if self._dp is None:
            raise UsageError("this ROS 2 discovery session is closed")
        return self._dp

    def __enter__(self) -> Ros2Discovery:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Leave the domain (other participants see us go at once); give fd 2 back."""
        if self._dds is None:
            return
        self._readers.clear()
        self._info_readers.clear()
        self._dp = None
        self._domain = None
        self._dds = None
        cstderr.release()

    def _participants(self) -> dict[bytes, bytes]:
        """Return alive participants: GUID -> USER_DATA."""
        policy = self._dds.qos.Policy
        return {s.key.bytes: user_data(s.qos, policy) for s in self._readers["participant"].alive()}

    def _endpoints(self) -> dict[bytes, Endpoint]:
        """Return every alive endpoint, keyed by GUID."""
        policy = self._dds.qos.Policy
        found: dict[bytes, Endpoint] = {}
        for kind in ("publication", "subscription"):
            for s in self._readers[kind].alive():
                key = s.key.bytes
                known = self._converted.get(key)
                if known is not None and known[0] is s:  # converted once already
                    found[key] = known[1]
                    continue
                found[key] = Endpoint(
                    guid=s.key.bytes,
                    participant=s.participant_key.bytes,
                    topic=s.topic_name,
                    type_name=s.type_name,
                    writer=kind == "publication",
                    qos=qos_from_dds(s.qos, policy),
                    user_data=user_data(s.qos, policy),
                )
                self._converted[key] = (s, found[key])
        self._converted = {k: v for k, v in self._converted.items() if k in found}
        return found

    def _take_infos(self) -> None:
        """Take new ``ros_discovery_info`` samples; keep each participant's newest."""
        for size, reader in self._info_readers.items():
            for sample in take_all(reader):
                if not hasattr(sample, "gid"):
                    continue  # an InvalidSample: a writer left, no data
                gid = bytes(sample.gid.data)
                if len(gid) != size or any(gid[16:]):
                    continue  # another layout misread: not a GID
                writer = self._writer(reader, sample.sample_info.publication_handle)
                if writer is None:
                    continue  # its writer is gone already
                if writer != gid[:16]:
                    self.forged += 1  # only a participant's own GID counts (rmw does the same)
                    continue
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

    def _forget(self, gone: Collection[bytes]) -> None:
        """Drop what is kept of participants that left: a watch that repairs for days sees
        new processes, each a new participant, on every repair.

        Only those seen and then gone: a ``ros_discovery_info`` sample can arrive before its
        participant is discovered, and it is sent once (transient local); a participant found
        again after its lease ran out is matched anew and sends it again.
        """
        if not gone:
            return
        for k in gone:
            self._infos.pop(k, None)
            self._info_writer_since.pop(k, None)
        self._writer_of = {h: p for h, p in self._writer_of.items() if p not in gone}

    def _writer(self, reader: Any, handle: int) -> bytes | None:
        """Return the participant GUID of the writer behind ``handle`` (cached; None: gone)."""
        if handle not in self._writer_of:
            try:
                found = reader.get_matched_publication_data(handle)
            except Exception:
                return None
            if found is None:
                return None
            self._writer_of[handle] = found.participant_key.bytes
        return self._writer_of[handle]

    def _layout_hint(self, participant: bytes) -> tuple[int, ...]:
        """Return the Gid size the participant's endpoints say it uses (typehash: Iron+)."""
        for e in self._last_endpoints.values():
            if e.participant == participant and e.topic == DISCOVERY_TOPIC and e.writer:
                return (16,) if b"typehash=" in e.user_data else (24,)
        return (16, 24)

    def read(
        self,
        *,
        settle: float = 1.0,
        timeout: float | None = None,
        at_least: float = FIRST_READ_AT_LEAST,
    ) -> LiveGraph:
        """Return the ROS 2 graph now.

        The first call waits until discovery is complete: every ROS participant has sent its
        ``ros_discovery_info`` and every endpoint named there has been discovered, nothing
        changed for ``settle`` s, and it has listened for at least ``at_least`` s (a user's
        ``--spin-time``: a loaded host answers late). It waits at most ``timeout`` s, by
        default ``at_least`` plus ``UNDECODABLE_AFTER`` (8 s by default). Later calls do not
        wait.
        """
        if timeout is None:
            timeout = at_least + UNDECODABLE_AFTER
        if self._dp is None:
            raise UsageError("this ROS 2 discovery session is closed")
        start = time.monotonic()
        previous: object = None
        stable_since = start
        while True:
            taken_at = datetime.now(UTC)
            participants = self._participants()
            self._forget(self._present - participants.keys())
            self._present = frozenset(participants)
            self._last_endpoints = endpoints = self._endpoints()
            self._take_infos()
            ros = {k for k, ud in participants.items() if b"enclave=" in ud}
            silent = self._silent(ros, endpoints)
            named = {g for k in ros for n in self._infos.get(k, (0, ()))[1] for g in n.gids}
            stale = stale_participants(named, self._infos, endpoints) & ros
            complete = all(k in self._infos or k in silent for k in ros)
            complete = complete and not stale and named <= endpoints.keys()
            state = (frozenset(participants), frozenset(endpoints), repr(self._infos))
            now = time.monotonic()
            if state != previous:
                previous, stable_since = state, now
            self._renew_if_stale(stale | silent, now, still=now - stable_since >= settle)
            if self._settled or now - start >= timeout:
                break
            listened = now - start >= at_least
            if listened and ros and complete and now - stable_since >= settle:
                break
            if listened and not ros and now - start >= max(settle * 2, 1.0):
                break
            time.sleep(0.05)
        self._settled = True
        self.undecodable = frozenset(self._silent(ros, endpoints))
        self.stale = stale
        self.participants = len(participants)
        self.ros_participants = len(ros)
        self.endpoints = sum(1 for e in endpoints.values() if ros_name(e.topic) is not None)
        return build_graph(self.domain, taken_at, ros, self._infos, endpoints)

    def _renew_if_stale(self, stale: Collection[bytes], now: float, *, still: bool) -> None:
        """Make fresh info readers when participants stay stale or silent (transient local
        resends each writer's newest sample to a new reader). A silent one's single sample may
        have been lost to the old reader (taken before its writer was matched, or undecodable
        once): nothing else would send it again, and its nodes would stay unseen for good.

        The first read waits for the graph to be ``still``; later reads (one pass each, as
        ``watch`` polls) for the same participants to be stale since ``RENEW_EVERY`` s.
        """
        if not stale:
            self._stale_since = None
            return
        if self._stale_since is None:
            self._stale_since = now
        waited = now - self._stale_since >= RENEW_EVERY if self._settled else still
        if waited and now - self._renewed_at >= RENEW_EVERY:
            for size, dp, topic, qos in self._renew:
                self._info_readers[size] = self._dds.sub.DataReader(dp, topic, qos=qos)
            self._renewed_at = now

    def _silent(self, ros: set[bytes], endpoints: dict[bytes, Endpoint]) -> set[bytes]:
        """Return ROS participants whose discovery writer has sent nothing decodable for
        ``UNDECODABLE_AFTER`` s (``graph.silent_participants``)."""
        writing = writing_since(self._info_writer_since, endpoints, time.monotonic())
        return silent_participants(ros, self._infos, writing, UNDECODABLE_AFTER)


def read_ros2_graph(
    domain: int, *, distro: str | None = None, settle: float = 1.0, timeout: float | None = None
) -> LiveGraph:
    """Join ``domain``, wait for discovery to settle, and return the ROS 2 graph."""
    with Ros2Discovery(domain, distro) as session:
        return session.read(settle=settle, timeout=timeout)
