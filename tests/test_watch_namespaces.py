"""A repair onto a provider in another namespace leaves every consumer wired to it, on real rclpy.

Names are resolved as ROS resolves them, for each node in its own namespace
(``rosreconf.model.wiring.resolve_name``): the sonar driver ``/sensors/sonar_array``
publishes its relative ``scan`` as ``/sensors/scan``, so the kept estimator in ``/`` is
restarted with ``-r scan:=/sensors/scan``, the tracker in ``/nav`` with
``-r ~/scan_in:=/sensors/scan`` (it subscribes a private name), and the monitor in
``/sensors`` with no rule at all. The library is ``tests/data/namespaces``; ``watch --ros2
--apply --stand-ins`` runs as a subprocess on the Jazzy and Kilted venvs, and the end state
is read by rclpy's own graph API (``tests/ros2_probe.py``), never by rosreconf's reader.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from test_watch_ros2 import ROOT, Watch, probe

DATA = Path(__file__).with_name("data") / "namespaces"
FILES = ["--library", str(DATA / "library.yaml"), "--schema", str(DATA / "schema.yaml")]
NODES = {
    "lidar": "/front/lidar",
    "sonar": "/sensors/sonar_array",
    "wheel_odom": "/base/wheel_odom",
    "estimator": "/estimator",
    "tracker": "/nav/tracker",
    "monitor": "/sensors/monitor",
}
"""Component -> the full name of its node."""
GOALS = "/relocalize"
"""The action the tracker sends goals to (``_uses`` reads its client off rcl_action's names)."""


def _python(distro: str) -> Path:
    python = ROOT / f".venv-ros2-{distro}" / "bin" / "python"
    if not python.exists():  # make test builds it: missing is a failure, never a skip
        pytest.fail(f"the {distro} venv is missing: run `make ros2-venvs`", pytrace=False)
    return python


def _plan(failed: str) -> dict[str, str | None]:
    """Return role -> new component of ``rosreconf plan --fail``'s changes (restarts too)."""
    argv = [sys.executable, "-m", "rosreconf", "plan", *FILES, "--fail", failed, "--json"]
    out = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    (schema,) = json.loads(out.stdout)["schemas"]
    return {c["role"]: c["after"] for c in schema["changes"] if c["kind"] != "keep"}


def _uses(seen: dict[str, Any], node: str) -> tuple[list[str], list[str]]:
    """Return what ``node`` subscribes to and calls, as rclpy reads it, an action as itself.

    An action client is three service clients and two subscriptions under the action's name
    (``<a>/_action/send_goal`` ...): the action is named once, and only when all five are
    there.
    """
    ends = seen["endpoints"][node]
    parts = {"send_goal", "cancel_goal", "get_result", "feedback", "status"}
    under: dict[str, set[str]] = {}
    for name in (*ends["subscribes"], *ends["calls"]):
        action, marker, part = name.partition("/_action/")
        if marker:
            under.setdefault(action, set()).add(part)
    plain = [n for n in ends["calls"] if "/_action/" not in n]
    actions = [a for a, got in under.items() if got == parts]
    subscribes = [n for n in ends["subscribes"] if "/_action/" not in n]
    return subscribes, sorted(
        plain + actions + [f"{a} (in part)" for a in under if under[a] != parts]
    )


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_failover_to_a_namespaced_provider_rewires_every_consumer_by_resolved_names(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, *FILES, python=python)
    try:
        watch.wait("conformant")
        running = [NODES[c] for c in ("lidar", "wheel_odom", "estimator", "tracker", "monitor")]
        seen = probe(watch.env, ros2_domain, wait_for=running, python=python, until_wired=True)
        # the lidar publishes the absolute /scan from /front: the consumers in /nav and
        # /sensors are remapped to it, the estimator in / uses /scan as it is; the private
        # ~/odom of /base/wheel_odom and the relative reset_odom of /base are reached from
        # / and /nav, and the tracker in /nav sends goals to the estimator's /relocalize
        assert _uses(seen, "/estimator") == (["/base/wheel_odom/odom", "/scan"], [])
        assert _uses(seen, "/nav/tracker") == (["/scan"], ["/base/reset_odom", GOALS])
        assert _uses(seen, "/sensors/monitor") == (["/scan"], [])
        assert seen["dangling"] == {"calls": [], "subscriptions": []}

        before = len(watch.events())
        os.kill(watch.pids()["lidar"], signal.SIGKILL)
        watch.wait("conformant", after=before)
        after = watch.events()[before:]
        (replanned,) = (e for e in after if e["event"] == "replanned")
        changes = {c["role"]: c["to"] for c in replanned["changes"]}
        assert changes == _plan("lidar")  # what it did is what plan proves fewest
        restarted = sorted(c["to"] for c in replanned["changes"] if c["restart"])
        assert restarted == ["estimator", "monitor", "tracker"]

        running = [NODES[c] for c in ("sonar", "wheel_odom", "estimator", "tracker", "monitor")]
        seen = probe(watch.env, ros2_domain, wait_for=running, python=python, until_wired=True)
        assert set(running) <= set(seen["nodes"]) and "/front/lidar" not in seen["nodes"]
        assert seen["endpoints"]["/sensors/sonar_array"]["publishes"] == ["/sensors/scan"]
        # the sonar case: the estimator in / now subscribes /sensors/scan
        assert _uses(seen, "/estimator") == (["/base/wheel_odom/odom", "/sensors/scan"], [])
        assert _uses(seen, "/nav/tracker") == (["/sensors/scan"], ["/base/reset_odom", GOALS])
        assert _uses(seen, "/sensors/monitor") == (["/sensors/scan"], [])
        assert seen["dangling"] == {"calls": [], "subscriptions": []}
        assert "/scan" not in seen["topics"]
    finally:
        watch.stop(signal.SIGKILL)
