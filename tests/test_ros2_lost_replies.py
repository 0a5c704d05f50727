"""A lost state reply is made up by the next ask: a healthy node is never read as hung (issue 32).

Fresh clone fc198: twelve healthy managed nodes were failed at once as hung ("stopped
answering its state query") just after twelve standbys started and configured on two cores.
A loaded host loses UDP datagrams in bursts (receive buffers overflow: this machine's
/proc/net/snmp counts millions, RcvbufErrors). rosreconf asks each managed node's state with
a request/reply pair of its own; with a reliable reply reader, one reply lost held every
later reply of that node behind it until the server's writer heartbeated (Fast DDS: every
3 s), so the node looked silent for up to 3 s and was read ``unanswered`` after 1.5 s.

Real parts: a real rclpy managed node (unconfigured, answering ``get_state``), rosreconf's
own reader (``Ros2Source``, read after read as ``watch`` reads) in a process of its own.
The fault is injected, named as such (``tests/faults/drop_received.c``): that process loses
every fifth datagram it receives that carries the node's answer ("unconfigured"), as a full
receive buffer would. No timing is asserted.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from ros2_team import STANDIN
from test_watch_ros2 import _env
from test_watch_wiring import _python

FAULTS = Path(__file__).with_name("faults")
READS = Path(__file__).with_name("ros2_state_reads.py")
LOST_EVERY = 5
"""Every fifth answer the reader's process receives is lost (never two in a row)."""


@pytest.fixture(scope="session")
def drop_received(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Build the fault injector (gcc: ``make system-deps`` installs it)."""
    gcc = shutil.which("gcc")
    if gcc is None:  # make test installs it: missing is a failure, never a skip
        pytest.fail("gcc is missing: run `make system-deps`", pytrace=False)
    library = tmp_path_factory.mktemp("faults") / "drop_received.so"
    source = FAULTS / "drop_received.c"
    subprocess.run([gcc, "-shared", "-fPIC", "-O2", "-o", str(library), str(source), "-ldl"],
                   check=True, capture_output=True)  # fmt: skip
    return library


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])  # Fast DDS 2.14 and 3.2 answer
def test_a_lost_state_reply_is_made_up_by_the_next_ask_never_read_as_hung(
    ros2_domain: int, tmp_path: Path, distro: str, drop_received: Path
) -> None:
    python = _python(distro)
    env = {**_env(tmp_path, python), "ROS_DOMAIN_ID": str(ros2_domain)}
    spec = json.dumps({"name": "NX", "namespace": "/", "lifecycle": True})
    node = subprocess.Popen([str(python), str(STANDIN), spec], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    try:
        assert node.stdout is not None and b'"ready"' in node.stdout.readline()
        log = tmp_path / "dropped.log"
        lossy = {**env, "LD_PRELOAD": str(drop_received), "DROP_MARK": "unconfigured",
                 "DROP_EVERY": str(LOST_EVERY), "DROP_LOG": str(log)}  # fmt: skip
        out = subprocess.run([sys.executable, str(READS), str(ros2_domain), "/NX", "40", "0.3"],
                             env=lossy, capture_output=True, text=True, timeout=300)  # fmt: skip
        assert out.returncode == 0, out.stderr[-3000:]
        reads = [json.loads(line) for line in out.stdout.splitlines()]
        states = [r.get("state") for r in reads]
        # the fault happened: answers were lost, more than one
        lost = log.read_text().count("dropped") if log.exists() else 0
        assert lost >= 4, (lost, reads)
        # each lost answer cost one ask; the node was never read as hung, and is read as it is
        assert "unanswered" not in states, states
        assert states[-5:] == ["unconfigured"] * 5, reads
    finally:
        node.kill()
        node.wait()
