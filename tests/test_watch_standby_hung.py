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

from test_watch_ros2 import (
    DC_ARM,
    NOMINAL,
    UP_TIMEOUT,
    alive,
    probe,
    standby_watch,
)


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
