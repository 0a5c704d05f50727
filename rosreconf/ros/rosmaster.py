"""Ask a running ROS 1 master what is running, with the standard library's XML-RPC only.

rosreconf's own environment has no rospy, and needs none: the master API
(http://wiki.ros.org/ROS/Master_API) and every node's own API
(http://wiki.ros.org/ROS/Slave_API) are plain XML-RPC, each call answering
``[code, status, value]`` with code 1 for success. Every failure (nothing listening, no
answer within ``timeout``, an answer that is not that shape) becomes ``ExternalToolError``
naming the URI; nothing here prints.

What the master does not do: it never checks that a registered node is alive. A node that
shuts down cleanly (SIGINT/SIGTERM) unregisters itself; a node killed with SIGKILL stays
listed, with its topics and services, until someone unregisters it. ``alive`` asks a node
for its pid to tell the difference, and ``purge_dead`` unregisters the dead ones, the way
``rosnode cleanup`` does.
"""

from __future__ import annotations

import http.client
import xmlrpc.client
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from datetime import UTC, datetime
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit
from xml.parsers.expat import ExpatError

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.ros.livegraph import LiveGraph, LiveNode, from_json

__all__ = [
    "LiveGraph",
    "LiveNode",
    "alive",
    "node_pid",
    "purge_dead",
    "read_live_graph",
    "shutdown_node",
]

_PID_WORKERS = 8
"""How many nodes are asked for their pid at once, so hung nodes cost one timeout, not many."""


class _TimeoutTransport(xmlrpc.client.Transport):
    """An XML-RPC transport whose connections give up after ``timeout`` seconds."""

    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        conn = super().make_connection(host)
        conn.timeout = self._timeout
        return conn


def _check_uri(uri: str, what: str) -> None:
    """Refuse a URI that cannot be an XML-RPC endpoint, before any connection is tried."""
    parts = urlsplit(uri)
    try:
        port = parts.port
    except ValueError:
        port = None
    if parts.scheme != "http" or not parts.hostname or port is None:
        raise UsageError(f"{what} URI {uri!r} is not of the form http://HOST:PORT/")


def _call(uri: str, who: str, timeout: float, method: str, *args: object) -> Any:
    """Call ``method`` at ``uri`` and return the value of a code-1 answer, or raise."""
    proxy = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout))
    try:
        answer = getattr(proxy, method)(*args)
    except TimeoutError:
        msg = f"{who} at {uri} did not answer {method} within {timeout:g} s"
        raise ExternalToolError(msg) from None
    except ConnectionRefusedError:
        msg = f"{who} at {uri} refused the connection (is it running on that port?)"
        raise ExternalToolError(msg) from None
    except (OSError, xmlrpc.client.Error, http.client.HTTPException, ExpatError) as e:
        msg = f"{who} at {uri}: {method} failed: {e or type(e).__name__}"
        raise ExternalToolError(msg) from None
    finally:
        proxy("close")()
    if not (isinstance(answer, list) and len(answer) == 3 and isinstance(answer[0], int)):
        msg = f"{who} at {uri}: {method} gave {answer!r:.200}, not [code, status, value]"
        raise ExternalToolError(msg)
    if answer[0] != 1:
        raise ExternalToolError(f"{who} at {uri}: {method} failed: {answer[1]}")
    return answer[2]


def _bad(uri: str, method: str, value: object) -> ExternalToolError:
    """Build the error for a code-1 answer whose value has the wrong shape."""
    return ExternalToolError(f"ROS master at {uri}: {method} gave an unexpected {value!r:.200}")


def _registrations(uri: str, value: object) -> tuple[dict[str, set[str]], ...]:
    """Turn getSystemState's ``[pubs, subs, srvs]`` into three maps node -> names."""
    if not (isinstance(value, list) and len(value) == 3):
        raise _bad(uri, "getSystemState", value)
    maps: list[dict[str, set[str]]] = []
    for section in value:
        by_node: dict[str, set[str]] = {}
        if not isinstance(section, list):
            raise _bad(uri, "getSystemState", value)
        for entry in section:
            ok = isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], str)
            if not (ok and isinstance(entry[1], list)):
                raise _bad(uri, "getSystemState", entry)
            for node in entry[1]:
                if not isinstance(node, str):
                    raise _bad(uri, "getSystemState", entry)
                by_node.setdefault(node, set()).add(entry[0])
        maps.append(by_node)
    return maps[0], maps[1], maps[2]


def _topic_types(uri: str, value: object) -> dict[str, str]:
    """Turn getTopicTypes' ``[[topic, type], ...]`` into a dict."""
    if not isinstance(value, list):
        raise _bad(uri, "getTopicTypes", value)
    types: dict[str, str] = {}
    for entry in value:
        if not (isinstance(entry, list) and [type(x) for x in entry] == [str, str]):
            raise _bad(uri, "getTopicTypes", entry)
        types[entry[0]] = entry[1]
    return types


def _lookup_node(master_uri: str, name: str, timeout: float, caller_id: str) -> str | None:
    """Return the API URI of node ``name``, or None if the master does not know it now."""
    proxy = xmlrpc.client.ServerProxy(master_uri, transport=_TimeoutTransport(timeout))
    try:
        answer = proxy.lookupNode(caller_id, name)
    except (OSError, xmlrpc.client.Error, http.client.HTTPException, ExpatError) as e:
        msg = f"ROS master at {master_uri}: lookupNode({name}) failed: {e or type(e).__name__}"
        raise ExternalToolError(msg) from None
    finally:
        proxy("close")()
    if isinstance(answer, list) and len(answer) == 3 and answer[0] == 1:
        return answer[2] if isinstance(answer[2], str) else None
    return None


def node_pid(node_uri: str, *, timeout: float = 1.0, caller_id: str = "/rosreconf") -> int | None:
    """Return the pid a node's own API reports, or None when it does not answer properly."""
    try:
        _check_uri(node_uri, "node")
        pid = _call(node_uri, "node", timeout, "getPid", caller_id)
    except (ExternalToolError, UsageError):
        return None
    return pid if isinstance(pid, int) and not isinstance(pid, bool) else None


def alive(node: LiveNode | str, *, timeout: float = 1.0, caller_id: str = "/rosreconf") -> bool:
    """Tell whether a node (a ``LiveNode`` or its API URI) answers ``getPid`` right now.

    For a ``LiveNode`` read with a pid, the answer must also be that pid: a new process
    that happens to listen on a dead node's port is not that node.
    """
    if isinstance(node, str):
        return node_pid(node, timeout=timeout, caller_id=caller_id) is not None
    if node.uri is None:
        return False
    pid = node_pid(node.uri, timeout=timeout, caller_id=caller_id)
    return pid is not None and (node.pid is None or pid == node.pid)


def read_live_graph(
    master_uri: str, *, timeout: float = 3.0, caller_id: str = "/rosreconf"
) -> LiveGraph:
    """Return what the master at ``master_uri`` lists, with each node's API URI and pid.

    ``timeout`` bounds each XML-RPC call (two to the master, one ``lookupNode`` per node,
    then ``getPid`` to every node, eight at a time so hung nodes do not add up). A node
    that does not answer ``getPid`` gets ``pid=None``; only master failures raise.
    """
    _check_uri(master_uri, "ROS master")
    who = "ROS master"
    taken_at = datetime.now(UTC)
    state = _call(master_uri, who, timeout, "getSystemState", caller_id)
    pubs, subs, srvs = _registrations(master_uri, state)
    types = _topic_types(master_uri, _call(master_uri, who, timeout, "getTopicTypes", caller_id))
    names = sorted({*pubs, *subs, *srvs})
    uris = [_lookup_node(master_uri, n, timeout, caller_id) for n in names]

    def pid_of(uri: str | None) -> int | None:
        return None if uri is None else node_pid(uri, timeout=timeout, caller_id=caller_id)

    with ThreadPoolExecutor(max_workers=_PID_WORKERS) as pool:
        pids = list(pool.map(pid_of, uris))
    nodes = tuple(
        LiveNode(
            name=name,
            uri=uri,
            pid=pid,
            publishes=tuple(sorted(pubs.get(name, ()))),
            subscribes=tuple(sorted(subs.get(name, ()))),
            serves=tuple(sorted(srvs.get(name, ()))),
        )
        for name, uri, pid in zip(names, uris, pids, strict=True)
    )
    return LiveGraph(master_uri, taken_at, nodes, types)


def purge_dead(
    master_uri: str,
    graph: LiveGraph,
    *,
    only: Iterable[str] | None = None,
    timeout: float = 3.0,
    caller_id: str = "/rosreconf",
) -> tuple[str, ...]:
    """Unregister, like ``rosnode cleanup``, every node of ``graph`` that no longer answers.

    Each registration is withdrawn in the dead node's name (the master checks the caller's
    API URI). ``only`` restricts the purge to those node names. Returns the purged names.
    """
    _check_uri(master_uri, "ROS master")
    wanted = None if only is None else frozenset(only)
    purged: list[str] = []

    def ask(method: str, *args: object) -> Any:
        return _call(master_uri, "ROS master", timeout, method, *args)

    for node in graph.nodes:
        if (wanted is not None and node.name not in wanted) or node.uri is None:
            continue
        if alive(node.uri, timeout=timeout, caller_id=caller_id):
            continue
        for topic in node.publishes:
            ask("unregisterPublisher", node.name, topic, node.uri)
        for topic in node.subscribes:
            ask("unregisterSubscriber", node.name, topic, node.uri)
        for service in node.serves:
            try:
                service_uri = ask("lookupService", caller_id, service)
            except ExternalToolError:
                continue  # the master no longer lists it
            ask("unregisterService", node.name, service, service_uri)
        purged.append(node.name)
    return tuple(purged)


def shutdown_node(
    node_uri: str, reason: str, *, timeout: float = 2.0, caller_id: str = "/rosreconf"
) -> bool:
    """Ask a node, through its own API, to shut down (what ``rosnode kill`` does).

    Works for any rospy/roscpp node, whoever started it. Returns whether the node accepted;
    a node that is already gone is not an error.
    """
    try:
        _check_uri(node_uri, "node")
        _call(node_uri, "node", timeout, "shutdown", caller_id, reason)
    except (ExternalToolError, UsageError):
        return False
    return True


def read_live(master: str | None, snapshot: Path | None) -> LiveGraph:
    """Read the live graph from exactly one of a master's URI and a saved snapshot file.

    Raises:
        UsageError: both or neither are given, or the snapshot cannot be read.
        ExternalToolError: the master does not answer.
    """
    if (master is None) == (snapshot is None):
        raise UsageError("give exactly one of --master URI and --snapshot FILE")
    if snapshot is not None:
        try:
            return from_json(snapshot.read_text(encoding="utf-8"), str(snapshot))
        except OSError as exc:
            raise UsageError(f"{snapshot}: cannot read: {exc.strerror}") from None
    assert master is not None
    return read_live_graph(master)
