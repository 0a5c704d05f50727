"""On Kilted, ``watch``'s own participants run no type lookup, and still talk to nodes that do.

Fast DDS 3.2 (Kilted's rmw_fastrtps) runs an XTypes type lookup service in every participant,
and its reply thread reads a table the discovery thread writes without their common lock: a
stand-in that discovers many endpoints as it starts (a repair) sometimes died of SIGSEGV in
``TypeLookupManager::notify_callbacks`` (cores read with gdb; the rate, measured with
``benchmarks/standin_starts.py``, is in docs/live.md). rosreconf's own participants (the
stand-ins and the lifecycle agent) therefore get ``fastdds.type_propagation`` ``disabled``
in their Fast DDS profile. The crash is too rare to be a test's subject; what is held here:
the stand-ins and the agent ``watch`` starts run no type lookup threads (``ps -T`` shows
Fast DDS's thread names), a plain Kilted rclpy process does (so the check can fail), and such
a node, type information and all, still receives a stand-in's messages and its service's
answers: endpoints without type information are matched by type name.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from test_watch_ros2 import ROOT, Watch

KILTED = ROOT / ".venv-ros2-kilted" / "bin" / "python"
DATA = Path(__file__).with_name("data") / "wiring"
EXCHANGE = Path(__file__).with_name("ros2_exchange.py")
TYPE_LOOKUP = ("dds.tls.request", "dds.tls.replies")
"""Fast DDS 3's names for its type lookup service's two threads."""


def _threads(pid: int) -> list[str]:
    """Return the names of process ``pid``'s threads, as ``ps -T`` shows them."""
    tasks = Path(f"/proc/{pid}/task")
    return sorted((t / "comm").read_text().strip() for t in tasks.iterdir())


def _children(pid: int, script: str) -> list[int]:
    """Return the pids of ``pid``'s children running ``script``."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        if int(stat.rsplit(")", 1)[1].split()[1]) == pid and script.encode() in cmdline:
            found.append(int(entry.name))
    return found


def test_own_participants_run_no_type_lookup_and_talk_to_nodes_that_do(
    ros2_domain: int, tmp_path: Path
) -> None:
    if not KILTED.exists():
        pytest.fail("the Kilted venv is missing: run `make ros2-venvs`", pytrace=False)
    files = ["-l", str(DATA / "pair_library.yaml"), "-s", str(DATA / "pair_managed_schema.yaml")]
    watch = Watch(tmp_path, ros2_domain, *files, python=KILTED)  # the client is managed
    try:
        watch.wait("conformant")
        pids = watch.pids()
        agents = _children(watch.process.pid, "lifecycle_agent.py")
        assert sorted(pids) == ["MANAGED_CLIENT", "SERVER"] and len(agents) == 1, agents
        own = {**pids, "lifecycle agent": agents[0]}
        threads = {name: _threads(pid) for name, pid in own.items()}
        assert all(any(t.startswith("dds.") for t in ts) for ts in threads.values()), threads
        assert {n: [t for t in ts if t in TYPE_LOOKUP] for n, ts in threads.items()} == {
            n: [] for n in own
        }
        exchange = subprocess.run(
            [str(KILTED), str(EXCHANGE), "/real/t_data", "/real/svc_a", "60"],
            env={**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)},
            capture_output=True, text=True, timeout=120, check=False,
        )  # fmt: skip
        assert exchange.returncode == 0, exchange.stderr[-3000:]
        said = json.loads(exchange.stdout.strip().splitlines()[-1])
        assert set(TYPE_LOOKUP) <= set(said["threads"])  # Fast DDS 3's default: type lookup
        assert said["message"] is not None  # the stand-in SERVER publishes (1 Hz)
        assert said["answer"] == [True, "stand-in /server"]
    finally:
        watch.stop()
