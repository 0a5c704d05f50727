"""A managed node is not called plain because one read missed its state services.

Once on Kilted an activated standby was read as "a plain node ... serves no /NDC3/get_state"
(``not-managed``), and nothing repaired it: a loaded host's discovery can leave an endpoint
out of a read. rosreconf's reader (``Ros2Source``, read after read as ``watch`` reads, in a
process of its own: ``tests/ros2_state_reads.py``) keeps a node it has seen managed managed
while the same participant runs it, until its ``get_state`` server has been gone from
discovery for ``UNSEEN_AFTER`` s; a read that could not ask keeps the state last answered,
never ``unanswered`` (hung) for an ask its server could not hear.

Real rclpy nodes, the fault injected, named as such (``tests/ros2_state_faults.py``): a
stand-in whose ``get_state`` server leaves discovery on SIGUSR2, for 2 s (NB) or for good
(NG): no real managed node can drop its state services on demand.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from ros2_team import STANDIN
from test_watch_ros2 import _env
from test_watch_wiring import _python

from rosreconf.ros.ros2.lifecycle_state import UNSEEN_AFTER

FAULTS = Path(__file__).with_name("ros2_state_faults.py")
READS = Path(__file__).with_name("ros2_state_reads.py")


def _node(python: Path, env: dict[str, str], name: str) -> subprocess.Popen[bytes]:
    spec = json.dumps({"name": name, "namespace": "/", "lifecycle": True})
    node = subprocess.Popen([str(python), str(FAULTS), str(STANDIN), spec], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    assert node.stdout is not None and b'"ready"' in node.stdout.readline(), name
    return node


def _reader(env: dict[str, str], domain: int, node: str) -> subprocess.Popen[str]:
    argv = [sys.executable, str(READS), str(domain), node, "50", "0.3"]
    return subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)  # fmt: skip


def _until_managed(reader: subprocess.Popen[str], reads: list[dict[str, Any]]) -> None:
    """Read the reader's lines until it has read the node managed and listed three times."""
    assert reader.stdout is not None
    while sum(1 for r in reads if r.get("state") and r.get("listed")) < 3:
        line = reader.stdout.readline()
        assert line, (reads, reader.stderr.read() if reader.stderr else "")
        reads.append(json.loads(line))


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_state_server_gone_from_some_reads_is_no_plain_node_gone_for_good_it_is(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    env = {**_env(tmp_path, python), "ROS_DOMAIN_ID": str(ros2_domain)}
    nodes = {
        "/NB": _node(python, {**env, "STATE_GAP_SECONDS": "2"}, "NB"),
        "/NG": _node(python, env, "NG"),
    }
    readers = {n: _reader(env, ros2_domain, n) for n in nodes}
    try:
        reads: dict[str, list[dict[str, Any]]] = {n: [] for n in nodes}
        for n, reader in readers.items():
            _until_managed(reader, reads[n])
        for node in nodes.values():
            node.send_signal(signal.SIGUSR2)  # its get_state server leaves discovery
        for n, reader in readers.items():
            out, err = reader.communicate(timeout=300)
            assert reader.returncode == 0, err[-3000:]
            reads[n] += [json.loads(line) for line in out.splitlines()]
        # NB: some reads found no get_state server, and it came back; every read after the
        # first kept it managed, in the state it last answered
        blink = reads["/NB"]
        first = next(i for i, r in enumerate(blink) if r.get("state"))
        assert any(not r["listed"] for r in blink[first:]), blink  # the fault happened
        assert blink[-1]["listed"], blink
        assert [r["state"] for r in blink[first:]] == ["unconfigured"] * len(blink[first:]), blink
        # NG: managed while its server is unseen for less than UNSEEN_AFTER, plain after
        gone = reads["/NG"]
        unlisted = next(r["at"] for r in gone if not r["listed"])
        plain = [r for r in gone if r["at"] >= unlisted and r["state"] is None]
        assert plain and gone[-1]["state"] is None, gone
        assert plain[0]["at"] - unlisted >= UNSEEN_AFTER - 1.0, gone
        assert all(
            r["state"] == "unconfigured" for r in gone if unlisted <= r["at"] < plain[0]["at"]
        )
        assert "unanswered" not in {r["state"] for r in [*blink, *gone]}
    finally:
        for p in [*readers.values(), *nodes.values()]:
            p.kill()
            p.wait()
