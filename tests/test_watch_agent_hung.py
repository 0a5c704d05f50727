"""A hung lifecycle agent is replaced as a dead one is, within seconds, and no component fails;
one that could not start is started again.

The agent is stopped with SIGSTOP, the real way a process hangs without dying: it still runs
as a process, so only its silence tells (it says ``{"alive": ...}`` every 0.25 s, even in the
middle of a long request). Before, every later transition waited until it was resumed (14 s
in the hostile round). The references are the watch's events, the kernel's view of the
stopped process, and rclpy's own reading of the end state (tests/ros2_probe.py).
"""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import ros2_harness
from test_watch_ros2 import JAZZY, SCHEMAS, Watch, _helper, _managed_library, alive, probe

HUNG_SECONDS = 2.0
"""The agent's allowed silence (rosreconf.ros.ros2.lifecycle.HUNG_SECONDS)."""


def _state(pid: int) -> str:
    """Return the kernel's one-letter state of ``pid`` (``T``: stopped)."""
    return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0]


def test_a_stopped_lifecycle_agent_is_replaced_and_the_failover_conforms(
    ros2_domain: int, tmp_path: Path
) -> None:
    library = _managed_library(tmp_path)
    files = ["--library", str(library), "--schema", str(SCHEMAS / "object_repositioning.yaml")]
    watch = Watch(tmp_path, ros2_domain, *files)
    agent = 0
    try:
        watch.wait("conformant")
        pids = watch.pids()
        agent = _helper(watch, "lifecycle_agent.py")
        before = len(watch.events())
        os.kill(agent, signal.SIGSTOP)
        stopped = time.monotonic()
        while _state(agent) != "T":  # the kernel stops it at its next return to user space
            assert time.monotonic() - stopped < 5.0, _state(agent)
            time.sleep(0.01)
        said = watch.wait("helper", after=before, timeout=30)
        seen_after = time.monotonic() - stopped
        assert "hung" in said["message"] and str(agent) in said["message"], said
        # 2 s of silence, then the next look of the watch loop (0.5 s here), on a loaded host
        assert seen_after < HUNG_SECONDS + 6.0, f"replaced after {seen_after:.1f} s"
        assert not [e for e in watch.events() if e["event"] == "failed"]
        assert all(alive(p) for p in pids.values())  # the stand-ins run on
        # a repair now goes through the new agent, not the stopped one
        before = len(watch.events())
        os.kill(pids["NSM3"], signal.SIGKILL)
        done = watch.wait("conformant", after=before)
        assert done["configuration"]["elbow_joint"] == "NDC3"
        activated = [e for e in watch.events()[before:] if e.get("transition") == "activate"]
        assert activated and all(e["ok"] for e in activated), activated
        chosen = sorted(f"/{c}" for c in done["configuration"].values() if c)
        seen = probe(watch.env, ros2_domain, *chosen)  # their states read too
        assert all(seen["states"].get(n) == "active" for n in chosen), seen["states"]
        # rclpy's view of the wiring: the restarted NREA calls the DC arm, and no node of the
        # configuration calls the dead servo arm's names (its own name for the unchosen
        # digital alternative is the one call nobody serves)
        assert "/arm_dc/elbow/servo_command" in seen["services"]
        dangling = [c for c in seen["dangling"]["calls"] if c[0] in chosen]
        assert not [c for c in dangling if c[1].startswith("/arm_servo/")], dangling
        assert all("digital_servo_command" in s for n, s in dangling if n == "/NREA"), dangling
        assert _helper(watch, "lifecycle_agent.py") != agent  # a new one
        assert not os.path.exists(f"/proc/{agent}")  # the stopped one was killed
    finally:
        if agent and os.path.exists(f"/proc/{agent}"):
            os.kill(agent, signal.SIGCONT)
        watch.stop()


def test_a_lifecycle_agent_that_could_not_start_is_started_again_and_the_nodes_activated(
    ros2_domain: int, tmp_path: Path
) -> None:
    """Fresh clone fc16: 13 Kilted executables starting at once on a loaded host, and the
    agent did not say ready within its 10 s; watch never started it again, so every managed
    node stayed unconfigured and failed. Provoked (a shell "interpreter", named as such): the
    agent's first start hangs, every later one is the real Jazzy Python. Watch must say the
    failed start, start the agent again within seconds, and end conformant with every node
    of the configuration active (read by rclpy)."""
    first = tmp_path / "first-agent-start"
    hang_once = f'[ -e "{first}" ] || {{ : > "{first}"; exec sleep 600; }}'
    python = ros2_harness.fake_python(tmp_path / "python-agent-hangs-once", JAZZY, hang_once,
                                      "lifecycle_agent.py")  # fmt: skip
    library = _managed_library(tmp_path)
    files = ["--library", str(library), "--schema", str(SCHEMAS / "object_repositioning.yaml")]
    watch = Watch(tmp_path, ros2_domain, *files, python=python)
    try:
        done = watch.wait("conformant")
        events = watch.events()
        failed = [
            e for e in events if e["event"] == "lifecycle" and "did not answer" in e["message"]
        ]
        assert failed and first.exists(), events[-5:]
        (again,) = [e for e in events if e["event"] == "helper"]
        assert "started, after a start that failed" in again["message"], again
        assert events.index(failed[0]) < events.index(again) < events.index(done)
        assert not [e for e in events if e["event"] == "failed"], events[-5:]
        chosen = sorted(f"/{c}" for c in done["configuration"].values() if c)
        seen = probe(watch.env, ros2_domain, *chosen)
        assert seen["states"] == dict.fromkeys(chosen, "active"), seen["states"]
    finally:
        watch.stop()
