"""A hung standby is replaced in the standby set and never delays a failover (issue 31).

Real rclpy stand-ins under ``watch --ros2 --apply --standby`` with every component managed:
a standby whose process is stopped (SIGSTOP) could answer no ``activate``, and each
transition waits up to its timeout. What watch did is read from its JSON log; no timing is
asserted (``make bench``'s).
"""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path
from typing import Any

from test_watch_ros2 import (
    DC_ARM,
    NOMINAL,
    UP_TIMEOUT,
    Watch,
    _ros2_python,
    alive,
    probe,
    standby_watch,
)


def _hang_ndc1(watch: Watch, deadline: float) -> tuple[int, dict[str, Any]]:
    """Stop (SIGSTOP) standby NDC1's process; wait until watch has stopped it, started it
    anew and configured it. Return the stopped pid and the new process's launch event."""
    first = watch.pids()["NDC1"]
    before = len(watch.events())
    os.kill(first, signal.SIGSTOP)
    hung = watch.wait("standby-hung", after=before)
    assert (hung["component"], hung["pid"]) == ("NDC1", first)
    assert not alive(first)
    again = watch.wait("launch", after=before)
    assert again["components"] == ["NDC1"] and again.get("standby"), again
    while not [e for e in watch.events()[before:] if e.get("transition") == "configure"
               and e["component"] == "NDC1" and e["ok"]]:  # fmt: skip
        assert time.monotonic() < deadline, watch.events()[-5:]
        time.sleep(0.2)
    return first, again


def test_a_hung_standby_is_started_anew_and_one_hung_at_the_failover_is_started_cold(
    ros2_domain: int, tmp_path: Path
) -> None:
    watch = standby_watch(tmp_path, ros2_domain)
    try:
        watch.wait("conformant")
        deadline = time.monotonic() + UP_TIMEOUT
        while not {*NOMINAL, *DC_ARM} <= watch.configured():
            assert time.monotonic() < deadline, watch.events()[-5:]
            time.sleep(0.2)
        # a standby stopped while nothing fails: stopped and started anew, configured again
        _hang_ndc1(watch, deadline)
        # a standby stopped just before the failure it stands by for: never activated
        before = len(watch.events())
        os.kill(watch.pids()["NDC3"], signal.SIGSTOP)
        os.kill(watch.pids()["NSM3"], signal.SIGKILL)
        failed = watch.wait("failed", after=before)
        watch.wait("conformant", after=before)
        after = watch.events()[before:]
        assert [e["component"] for e in after if e["event"] == "standby-hung"] == ["NDC3"]
        # from the failure on, NDC3 is never asked to act while hung: no transition of its
        # times out (one before the failure may: a fresh standby's first configure is tried
        # again on a later tick when its service is not up yet)
        since = watch.events()[watch.events().index(failed) :]
        tried = [e for e in since if e.get("transition") and e["component"] == "NDC3"]
        assert tried and all(e["ok"] for e in tried), tried
        assert tried[-1]["state"] == "active"
        # rclpy's own view, not rosreconf's: the cold NDC3 serves, and no call or
        # subscription of an active node is left on the stopped NDC3 or the dead NSM3
        seen = probe(watch.env, ros2_domain, "/NDC3", "/NREA", wait_for=["/NDC3", "/NREA"],
                     until_wired=True)  # fmt: skip
        assert seen["states"]["/NDC3"] == "active", seen["states"]
        dangling = seen["dangling"]["calls"] + seen["dangling"]["subscriptions"]
        assert not [d for d in dangling if d[0] in ("/NDC3", "/NREA")], dangling
    finally:
        watch.stop(signal.SIGKILL)


NO_GOODBYE_THEN_SLOW = """\
# A FAKE, loaded as sitecustomize by the ROS 2 Python that runs watch's stand-ins (one process,
# forked per node, so a file marker tells NDC1's first process from its next). NDC1's first
# process ignores SIGINT and SIGTERM (a node hung in C code): stopping it ends in SIGKILL, so
# its participant says no DDS goodbye and is announced until its lease ends. Its next process
# takes 6 s to make its node (a slow start).
import os, signal, time

try:
    import rclpy.lifecycle
except ImportError:  # the interpreter's own checks before rclpy: nothing to fake
    rclpy = None

if rclpy is not None:
    real_init = rclpy.lifecycle.LifecycleNode.__init__

    def init(self, name, *args, **kwargs):
        if name == "NDC1":
            marker = os.path.join(os.environ["FAKE_MARKS"], "NDC1-started")
            if os.path.exists(marker):
                time.sleep(6.0)
            else:
                open(marker, "w").close()
                signal.signal(signal.SIGINT, signal.SIG_IGN)
                signal.signal(signal.SIGTERM, signal.SIG_IGN)
        real_init(self, name, *args, **kwargs)

    rclpy.lifecycle.LifecycleNode.__init__ = init
"""

TEAM_LEASE = """\
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com"><profiles>
  <participant profile_name="team" is_default_profile="true"><rtps><builtin><discovery_config>
    <leaseDuration><sec>20</sec><nanosec>0</nanosec></leaseDuration>
    <leaseAnnouncement><sec>3</sec><nanosec>0</nanosec></leaseAnnouncement>
  </discovery_config></builtin></rtps></participant>
</profiles></dds>
"""


def test_a_standby_started_anew_is_never_taken_for_its_dead_predecessor(
    ros2_domain: int, tmp_path: Path
) -> None:
    """A hung standby stopped without a DDS goodbye is announced until its lease ends (the
    team's Fast DDS profile: 20 s). Its state query, unanswered, was read as the state of
    the node started anew under its name: the new, healthy process was then stopped as
    "hung" (fresh clone fc177: at a failover; here, slow to start, on the next ticks)."""
    fake = tmp_path / "fake"
    fake.mkdir()
    (fake / "sitecustomize.py").write_text(NO_GOODBYE_THEN_SLOW)
    python = fake / "python"  # watch hands no PYTHONPATH on: the ROS 2 Python sets it itself
    python.write_text(f'#!/bin/sh\nPYTHONPATH={fake} exec {_ros2_python()} "$@"\n')
    python.chmod(0o755)
    profile = tmp_path / "team_fastdds.xml"
    profile.write_text(TEAM_LEASE)
    env = {"FAKE_MARKS": str(fake), "FASTRTPS_DEFAULT_PROFILES_FILE": str(profile)}
    watch = standby_watch(tmp_path, ros2_domain, env, python)
    try:
        watch.wait("conformant")
        deadline = time.monotonic() + UP_TIMEOUT
        while "NDC1" not in watch.configured():
            assert time.monotonic() < deadline, watch.events()[-5:]
            time.sleep(0.2)
        before = len(watch.events())
        first, again = _hang_ndc1(watch, deadline)  # SIGKILLed: no goodbye
        after = watch.events()[before:]
        hung_pids = [e["pid"] for e in after if e["event"] == "standby-hung"]
        assert hung_pids == [first], [e["message"] for e in after]  # the new one never "hung"
        assert alive(again["pids"]["NDC1"])
        # rclpy's own view, not rosreconf's: /NDC1 answers, a configured standby
        seen = probe(watch.env, ros2_domain, "/NDC1", wait_for=["/NDC1"])
        assert seen["states"]["/NDC1"] == "inactive", seen["states"]
    finally:
        watch.stop(signal.SIGKILL)
