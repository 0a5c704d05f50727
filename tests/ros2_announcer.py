"""Announce ROS 2 nodes over real DDS exactly as rmw_cyclonedds_cpp does, without ROS 2.

Test code, written from the rmw sources and independent of ``rosreconf.ros.ros2`` (the decoder
under test): it must not import rosreconf. One process is one ROS 2 context, that is one DDS
participant (Humble and later), holding any number of nodes. What it announces, and where
each fact comes from:

- the participant's USER_DATA ``enclave=<enclave>;`` (rmw_cyclonedds_cpp rmw_node.cpp,
  ``rmw_context_impl_s::init``);
- per publisher a DDS writer on ``rt<topic>`` and per subscription a reader, of type
  ``<pkg>::msg::dds_::<Name>_`` (``make_fqtopic``, ``MessageTypeSupport``); a service server
  is a reader on ``rq<service>Request`` plus a writer on ``rr<service>Reply`` with types
  ``<pkg>::srv::dds_::<Name>_Request_`` / ``_Response_``, a client the reverse
  (``rmw_create_service`` / ``rmw_create_client``, ``ServiceTypeSupport``);
- endpoint QoS as ``create_readwrite_qos`` sets it (deadline and lease only when given),
  XCDR1 data representation, and on Iron and later the endpoint USER_DATA
  ``typehash=RIHS01_<64 hex>;``;
- the plumbing every rclcpp node has: ``rt/rosout``, ``rt/parameter_events`` (publisher and
  subscription) and the parameter services;
- one ``ros_discovery_info`` sample (rmw_dds_common ``ParticipantEntitiesInfo``, RELIABLE,
  TRANSIENT_LOCAL, KEEP_LAST 1) mapping the participant's GID and each node's reader and
  writer GIDs (readers first in the message) to the node's namespace and name. A GID is the
  16-byte DDS GUID, zero-padded to 24 bytes on Humble (``convert_guid_to_gid``).

Usage: ``python tests/ros2_announcer.py SPEC.json``; prints ``ready`` on stdout once the
discovery sample is written, then waits for SIGTERM/SIGINT. The spec::

    {"domain": 42, "gid_size": 16, "enclave": "/", "ros_participant": true,
     "nodes": [{"namespace": "/", "name": "talker",
                "publishers": [{"name": "/chatter", "type": "std_msgs/msg/String",
                                "qos": {"reliability": "best_effort"}}],
                "subscriptions": [], "servers": [], "clients": []}]}

The network configuration comes from CYCLONEDDS_URI (the tests give a loopback-only one).

Faults real nodes cannot be made to show (imitation, named as such in the tests):
``"unbounded_names": true`` writes node names as unbounded strings, so a name longer than the
Gid message's 256 characters makes every reader fail to decode the sample; ``"repeat": N``
writes the sample N times; ``"forge": "other"`` waits for another ROS participant and keeps
writing ros_discovery_info carrying THAT participant's GID (with this spec's nodes), every
0.2 s, as an attacker would.
"""

from __future__ import annotations

import hashlib
import json
import signal
import sys
import threading
from typing import Any

from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct, make_idl_struct
from cyclonedds.idl.types import array, bounded_str, sequence, uint8
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic
from cyclonedds.util import duration

PARAMETER_SERVICES = (
    ("describe_parameters", "rcl_interfaces/srv/DescribeParameters"),
    ("get_parameter_types", "rcl_interfaces/srv/GetParameterTypes"),
    ("get_parameters", "rcl_interfaces/srv/GetParameters"),
    ("list_parameters", "rcl_interfaces/srv/ListParameters"),
    ("set_parameters", "rcl_interfaces/srv/SetParameters"),
    ("set_parameters_atomically", "rcl_interfaces/srv/SetParametersAtomically"),
)


def gid_types(size: int, bounded: bool = True) -> type[IdlStruct]:
    """Build rmw_dds_common's ParticipantEntitiesInfo for a ``size``-byte Gid (16 or 24)."""
    name_type: Any = bounded_str[256] if bounded else str
    gid = make_idl_struct("Gid_", "rmw_dds_common::msg::dds_::Gid_", {"data": array[uint8, size]})
    node = make_idl_struct(
        "NodeEntitiesInfo_",
        "rmw_dds_common::msg::dds_::NodeEntitiesInfo_",
        {
            "node_namespace": name_type,
            "node_name": name_type,
            "reader_gid_seq": sequence[gid],
            "writer_gid_seq": sequence[gid],
        },
    )
    info = make_idl_struct(
        "ParticipantEntitiesInfo_",
        "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_",
        {"gid": gid, "node_entities_info_seq": sequence[node]},
    )
    info.gid_type = gid  # type: ignore[attr-defined]
    info.node_type = node  # type: ignore[attr-defined]
    return info


_TYPES: dict[str, type[IdlStruct]] = {}


def dds_type(ros_type: str, suffix: str = "") -> type[IdlStruct]:
    """Return a DDS struct named as rosidl names ``ros_type`` (``pkg/msg/Name``), + ``suffix``."""
    pkg, kind, name = ros_type.split("/")
    typename = f"{pkg}::{kind}::dds_::{name}{suffix}_"
    if typename not in _TYPES:
        cls_name = typename.replace(":", "_")
        _TYPES[typename] = make_idl_struct(cls_name, typename, {"data": str})
    return _TYPES[typename]


def _seconds(value: float | None) -> int:
    return duration(infinite=True) if value is None else duration(seconds=value)


def endpoint_qos(spec: dict[str, Any], typehash: bytes | None) -> Qos:
    """Return the QoS rmw_cyclonedds gives an endpoint with the rmw profile ``spec``."""
    policies: list[Any] = [Policy.WriterDataLifecycle(autodispose=False)]
    depth = int(spec.get("depth", 10))
    policies.append(Policy.History.KeepLast(depth))
    if spec.get("reliability", "reliable") == "reliable":
        policies.append(Policy.Reliability.Reliable(max_blocking_time=duration(infinite=True)))
    else:
        policies.append(Policy.Reliability.BestEffort)
    if spec.get("durability", "volatile") == "transient_local":
        policies.append(Policy.Durability.TransientLocal)
        policies.append(
            Policy.DurabilityService(
                cleanup_delay=0,
                history=Policy.History.KeepLast(depth),
                max_samples=-1,
                max_instances=-1,
                max_samples_per_instance=-1,
            )
        )
    else:
        policies.append(Policy.Durability.Volatile)
    if spec.get("deadline") is not None:
        policies.append(Policy.Deadline(deadline=_seconds(spec["deadline"])))
    lease = _seconds(spec.get("lease_duration"))
    if spec.get("liveliness", "automatic") == "manual_by_topic":
        policies.append(Policy.Liveliness.ManualByTopic(lease_duration=lease))
    else:
        policies.append(Policy.Liveliness.Automatic(lease_duration=lease))
    policies.append(Policy.DataRepresentation(use_cdrv0_representation=True))
    if typehash is not None:
        policies.append(Policy.Userdata(data=typehash))
    return Qos(*policies)


def _typehash(ros_type: str, iron_or_later: bool) -> bytes | None:
    """Return an endpoint's ``typehash=RIHS01_<hex>;`` user data (Iron+), else None.

    The real hash is over the type description; a stable stand-in of the same form serves,
    since the decoder only has to tolerate it.
    """
    if not iron_or_later:
        return None
    digest = hashlib.sha256(ros_type.encode()).hexdigest()
    return f"typehash=RIHS01_{digest};".encode()


class Announcer:
    """One ROS 2 context: a participant, its nodes' endpoints and its ros_discovery_info."""

    def __init__(self, spec: dict[str, Any]) -> None:
        self.spec = spec
        self.gid_size = int(spec.get("gid_size", 16))
        iron = self.gid_size == 16
        qos = None
        if spec.get("ros_participant", True):
            enclave = spec.get("enclave", "/")
            qos = Qos(Policy.Userdata(data=f"enclave={enclave};".encode()))
        self.dp = DomainParticipant(int(spec["domain"]), qos=qos)
        self.pub = Publisher(self.dp)
        self.sub = Subscriber(self.dp)
        self.keep: list[Any] = []
        self.topics: dict[tuple[str, str], Topic[Any]] = {}
        self.info_type = gid_types(self.gid_size, not spec.get("unbounded_names", False))
        nodes = []
        for node in spec["nodes"]:
            readers: list[bytes] = []
            writers: list[bytes] = []
            ns, name = node.get("namespace", "/"), node["name"]
            full = ("" if ns == "/" else ns) + "/" + name
            default = {"reliability": "reliable", "durability": "volatile", "depth": 10}
            pubs = [*node.get("publishers", [])]
            subs = [*node.get("subscriptions", [])]
            servers = [*node.get("servers", [])]
            if node.get("plumbing", True):
                pubs.append({"name": "/rosout", "type": "rcl_interfaces/msg/Log"})
                pubs.append(
                    {"name": "/parameter_events", "type": "rcl_interfaces/msg/ParameterEvent"}
                )
                subs.append(
                    {"name": "/parameter_events", "type": "rcl_interfaces/msg/ParameterEvent"}
                )
                servers += [{"name": f"{full}/{s}", "type": t} for s, t in PARAMETER_SERVICES]
            for p in pubs:
                writers.append(self._writer("rt" + p["name"], dds_type(p["type"]), p, iron))
            for s in subs:
                readers.append(self._reader("rt" + s["name"], dds_type(s["type"]), s, iron))
            for s in servers:
                req, rep = dds_type(s["type"], "_Request"), dds_type(s["type"], "_Response")
                readers.append(self._reader(f"rq{s['name']}Request", req, default, iron))
                writers.append(self._writer(f"rr{s['name']}Reply", rep, default, iron))
            for c in node.get("clients", []):
                req, rep = dds_type(c["type"], "_Request"), dds_type(c["type"], "_Response")
                writers.append(self._writer(f"rq{c['name']}Request", req, default, iron))
                readers.append(self._reader(f"rr{c['name']}Reply", rep, default, iron))
            nodes.append(
                self.info_type.node_type(  # type: ignore[attr-defined]
                    node_namespace=ns,
                    node_name=name,
                    reader_gid_seq=[self._gid(g) for g in readers],
                    writer_gid_seq=[self._gid(g) for g in writers],
                )
            )
        info_qos = endpoint_qos(
            {"reliability": "reliable", "durability": "transient_local", "depth": 1},
            _typehash("rmw_dds_common/msg/ParticipantEntitiesInfo", iron),
        )
        topic = Topic(self.dp, "ros_discovery_info", self.info_type)
        self.info_writer = DataWriter(self.pub, topic, qos=info_qos)
        self.info = self.info_type(
            gid=self._gid(self.dp.get_guid().bytes), node_entities_info_seq=nodes
        )

    def _topic(self, name: str, cls: type[IdlStruct]) -> Topic[Any]:
        key = (name, cls.__name__)
        if key not in self.topics:
            self.topics[key] = Topic(self.dp, name, cls)
        return self.topics[key]

    def _writer(self, name: str, cls: type[IdlStruct], qos: dict[str, Any], iron: bool) -> bytes:
        spec = qos.get("qos", qos)
        hashed = _typehash(cls.__name__, iron)
        w = DataWriter(self.pub, self._topic(name, cls), qos=endpoint_qos(spec, hashed))
        self.keep.append(w)
        return w.get_guid().bytes

    def _reader(self, name: str, cls: type[IdlStruct], qos: dict[str, Any], iron: bool) -> bytes:
        spec = qos.get("qos", qos)
        hashed = _typehash(cls.__name__, iron)
        r = DataReader(self.sub, self._topic(name, cls), qos=endpoint_qos(spec, hashed))
        self.keep.append(r)
        return r.get_guid().bytes

    def _gid(self, guid: bytes) -> Any:
        data = list(guid) + [0] * (self.gid_size - len(guid))
        return self.info_type.gid_type(data=data)  # type: ignore[attr-defined]

    def announce(self) -> None:
        """Write the participant's whole state to ros_discovery_info (rmw does on each change)."""
        info = self.info
        if self.spec.get("stale_newest"):
            # A fake: the info without the last node, as a reader holds it when the newest
            # sample never arrives or does not decode (Cyclone failed one of a Fast DDS
            # participant's at 40 real Jazzy nodes); the last node's endpoints exist.
            older = info.node_entities_info_seq[:-1]
            info = self.info_type(gid=info.gid, node_entities_info_seq=older)
        for _ in range(int(self.spec.get("repeat", 1))):
            self.info_writer.write(info)

    def forge(self, done: threading.Event) -> None:
        """Keep writing this spec's nodes under another ROS participant's GID (an attack)."""
        from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant

        reader = BuiltinDataReader(self.dp, BuiltinTopicDcpsParticipant)
        own = self.dp.get_guid().bytes
        victim = None
        while victim is None and not done.is_set():
            for p in reader.read(N=64):
                data = p.qos[Policy.Userdata]
                if p.key.bytes != own and data is not None and b"enclave=" in bytes(data.data):
                    victim = p.key.bytes
            done.wait(0.1)
        forged = self.info_type(
            gid=self._gid(victim), node_entities_info_seq=self.info.node_entities_info_seq
        )
        print("ready", flush=True)
        while not done.is_set():
            self.info_writer.write(forged)
            done.wait(0.2)


def main() -> None:
    """Announce the spec file's nodes until SIGTERM or SIGINT."""
    with open(sys.argv[1], encoding="utf-8") as f:
        spec = json.load(f)
    announcer = Announcer(spec)
    done = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: done.set())
    signal.signal(signal.SIGINT, lambda *_: done.set())
    if spec.get("forge") == "other":
        announcer.forge(done)
        return
    announcer.announce()
    print("ready", flush=True)
    done.wait()


if __name__ == "__main__":
    main()
