"""Every start that fails is said, and a component nothing can replace is restarted, backing off.

A Nav2-shaped stack with one candidate per role (``tests/data/bringup``): no configuration is
left without any of its components. Real rclpy stand-ins under ``watch --ros2 --apply``
(Jazzy and Kilted); what watch did is read from its JSON log (times included), the end state
from rclpy's own graph and the nodes' ``get_state`` (``tests/ros2_probe.py``).

Before, a stand-in that exited at once (a ROS 2 Python without test_msgs: no action type to
pose nav2_msgs' as) left watch silent after ``launch`` for good: the lifecycle agent waited
30 s for each missing node's services in turn, the managed nodes that did start were never
configured, and nothing said why. And a failed component with no configuration left without
it was held failed for a minute (``--hold``) before it was tried again.
"""

from __future__ import annotations

import itertools
import os
import signal
import time
from datetime import datetime
from pathlib import Path
from typing import Any

import pytest
from test_watch_ros2 import ROOT, Watch, alive, probe

DATA = ROOT / "tests" / "data" / "bringup"
FILES = ("--library", str(DATA / "library.yaml"), "--schema", str(DATA / "schema.yaml"))
ALL = ["ODOMETRY", "MAP_SERVER", "AMCL", "PLANNER", "CONTROLLER", "NAVIGATOR"]
ACTING = ["PLANNER", "CONTROLLER", "NAVIGATOR"]
"""The components whose stand-ins act out nav2_msgs actions (posed with test_msgs')."""
ROLES = {"PLANNER": "planner", "CONTROLLER": "controller", "NAVIGATOR": "navigator"}
NODES = {"MAP_SERVER": "/map_server", "AMCL": "/amcl", "PLANNER": "/planner_server",
         "NAVIGATOR": "/bt_navigator"}  # fmt: skip
"""The managed components' nodes (the controller and the odometry are plain ones)."""
WITHOUT = ("test_msgs", "example_interfaces")
"""What the stand-ins pose actions with: a ROS 2 Python without them cannot act one out."""


def _python(distro: str) -> Path:
    python = ROOT / f".venv-ros2-{distro}" / "bin" / "python"
    if not python.exists():  # make test builds it: missing is a failure, never a skip
        pytest.fail(f"the {distro} venv is missing: run `make ros2-venvs`", pytrace=False)
    return python


def _python_without_test_msgs(distro: str, tmp: Path) -> Path:
    """Return a ROS 2 Python without test_msgs and example_interfaces, as a user's may be.

    Not a fake: the distro's venv with every entry linked (the same interpreter, rclpy, Fast
    DDS and message packages) but those two, so they cannot be imported, as when they were
    never installed.
    """
    real = _python(distro).parent.parent
    venv = tmp / f"ros2-{distro}-without-test-msgs"
    (venv / "bin").mkdir(parents=True)
    (venv / "bin" / "python").symlink_to((real / "bin" / "python").resolve())
    (venv / "pyvenv.cfg").write_text((real / "pyvenv.cfg").read_text())
    for entry in real.iterdir():
        if entry.name not in ("bin", "lib", "lib64", "pyvenv.cfg"):
            (venv / entry.name).symlink_to(entry)
    (venv / "lib").mkdir()
    for entry in (real / "lib").iterdir():
        if not entry.name.startswith("python3"):
            (venv / "lib" / entry.name).symlink_to(entry)
    (site,) = (real / "lib").glob("python3*/site-packages")
    mine = venv / "lib" / site.parent.name / "site-packages"
    mine.mkdir(parents=True)
    for entry in site.iterdir():
        name = entry.name.removeprefix("ros_").removeprefix(f"{distro}_")
        if not name.startswith(WITHOUT):
            (mine / entry.name).symlink_to(entry)
    return venv / "bin" / "python"


def _at(event: dict[str, Any]) -> float:
    """Return when an event was said, in seconds since the epoch (the JSON log's time)."""
    return datetime.fromisoformat(event["time"]).timestamp()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_stand_ins_that_cannot_start_are_said_at_once_and_the_rest_comes_up(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    """Three stand-ins exit 3 at once (two managed, one plain): each is ``failed`` with its
    exit status and why, from its log, within seconds of ``launch``; the managed nodes that
    did start are made active meanwhile;
    and the three, with no configuration left without them, are restarted in place with a
    backoff that doubles (a crash loop, never a hot one)."""
    python = _python_without_test_msgs(distro, tmp_path)
    watch = Watch(tmp_path, ros2_domain, *FILES, python=python)
    try:
        launch = watch.wait("launch")
        assert sorted(launch["components"]) == sorted(ALL)

        def restarts(events: list[dict[str, Any]]) -> list[dict[str, Any]]:
            return [e for e in events if e["event"] == "restart" and e["component"] == "PLANNER"]

        watch.wait("lifecycle")  # the first transition: the nodes that came up are in hand
        deadline = time.monotonic() + 120
        while len(restarts(watch.events())) < 5:  # at once, then in 1, 2, 4 and 8 s
            assert time.monotonic() < deadline, [e["message"] for e in watch.events()[-8:]]
            time.sleep(0.2)
        events = watch.events()
        said = [e["message"] for e in events]
        first = events.index(launch)
        failed = {}
        for e in events[first:]:
            if e["event"] == "failed":
                failed.setdefault(e["component"], e)
        assert sorted(failed) == sorted(ACTING), said
        for comp, e in failed.items():
            assert (e["how"], e["returncode"]) == ("exited-before-ready", 3), e
            assert _at(e) - _at(launch) < 15.0, said  # said as it happened, not waited for
            assert e["message"].startswith(f"{comp} ({ROLES[comp]}) exited (3) before it was ready")
            reason = " ".join(e["log"])  # the stand-in's own words, from its log
            assert "cannot act out action" in reason and "is not installed" in reason, e
            assert "test-msgs" in reason and all(line in e["message"] for line in e["log"]), e
        active = {e["component"] for e in events if e.get("state") == "active" and e["ok"]}
        assert active == {"MAP_SERVER", "AMCL"}, said
        seen = probe(watch.env, ros2_domain, "/map_server", "/amcl", wait_for=["/odometry"],
                     python=_python(distro))  # fmt: skip
        assert "/odometry" in seen["nodes"], seen["nodes"]
        states = seen["states"]
        assert (states["/map_server"], states["/amcl"]) == ("active", "active"), states
        # the crash loop: restarted in place, each wait twice the one before, said and kept
        tries = restarts(events)[:5]
        assert [e["seconds"] for e in tries] == [0, 1, 2, 4, 8], said
        assert all("no configuration is left without it" in e["message"] for e in tries)
        assert not [e for e in events if e["event"] == "hold"], said  # never held a minute
        launches = [_at(e) for e in events[first + 1 :] if "PLANNER" in e.get("components", ())]
        gaps = [b - a for a, b in itertools.pairwise(launches)]
        assert len(gaps) >= 3, said  # the restarts at once, in 1, 2 and 4 s: 8 s is to come
        for gap, wait in zip(gaps, (1, 2, 4), strict=False):
            assert gap >= wait - 0.05, (gaps, said)  # backed off: no busy loop
    finally:
        watch.stop(signal.SIGKILL)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_the_only_candidate_killed_is_restarted_in_place_at_once(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    """``kill -9`` of the only planner: restarted in place at once (the default, no
    ``--restarts``), not held for ``--hold``; every managed node active again (rclpy's view)."""
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, *FILES, python=python)
    try:
        watch.wait("conformant")
        before = len(watch.events())
        pid = watch.pids()["PLANNER"]
        killed = time.time()
        os.kill(pid, signal.SIGKILL)
        done = watch.wait("conformant", after=before)
        after = watch.events()[before:]
        said = [e["message"] for e in after]
        kinds = [e["event"] for e in after]
        assert kinds.index("failed") < kinds.index("restart") < kinds.index("conformant"), said
        restart = after[kinds.index("restart")]
        assert (restart["component"], restart["seconds"], restart["attempt"]) == ("PLANNER", 0, 1)
        assert restart["last_resort"] and "hold" not in kinds, said
        (launch,) = (e for e in after if e["event"] == "launch")
        assert launch["components"] == ["PLANNER"] and not alive(pid)
        assert done["configuration"] == watch.events()[0]["configuration"]  # the same one
        took = _at(done) - killed
        assert took < 30.0, said  # the hold it replaces was 60 s
        print(f"{distro}: kill -9 -> restart {_at(restart) - killed:.2f} s, "
              f"-> conformant {took:.2f} s")  # fmt: skip
        seen = probe(watch.env, ros2_domain, *NODES.values(), python=python, until_wired=True)
        assert set(seen["states"].values()) == {"active"}, seen["states"]
        assert seen["dangling"] == {"calls": [], "subscriptions": []}, seen["dangling"]
    finally:
        watch.stop(signal.SIGKILL)
