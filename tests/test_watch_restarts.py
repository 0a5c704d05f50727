"""Restart in place, hold, release (issue 31): a failed component is tried again, with a limit.

Real rclpy stand-ins under ``watch --ros2 --apply`` (Jazzy); what watch did is read from its
JSON log, each node's process from the pids it logged. No timing is asserted beyond the
order of events.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

from test_watch_ros2 import NOMINAL, Watch, alive, probe


def test_a_failed_component_restarts_in_place_until_its_limit_then_is_held_and_released(
    ros2_domain: int, tmp_path: Path
) -> None:
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--restarts", "2",
                  "--restart-window", "600", "--hold", "4")  # fmt: skip
    try:
        watch.wait("conformant")
        for n in (1, 2):  # restarted in place: one change, the configuration kept
            before = len(watch.events())
            pid = watch.pids()["NSM3"]
            os.kill(pid, signal.SIGKILL)
            restart = watch.wait("restart", after=before)
            assert (restart["component"], restart["crashes"]) == ("NSM3", n)
            done = watch.wait("conformant", after=before)
            assert done["configuration"]["elbow_joint"] == "NSM3"
            assert watch.pids()["NSM3"] != pid and alive(watch.pids()["NSM3"])
            assert not [e for e in watch.events()[before:] if e["event"] == "replanned"]
        # rclpy's own view, not rosreconf's: every call and subscription is served by a live node
        seen = probe(watch.env, ros2_domain, wait_for=[f"/{c}" for c in NOMINAL], until_wired=True)
        assert seen["dangling"] == {"calls": [], "subscriptions": []}, seen["dangling"]
        before = len(watch.events())
        os.kill(watch.pids()["NSM3"], signal.SIGKILL)  # the third within the window: held
        hold = watch.wait("hold", after=before)
        assert (hold["component"], hold["crashes"]) == ("NSM3", 3)
        done = watch.wait("conformant", after=before)
        assert done["configuration"]["elbow_joint"] == "NDC3"  # moved away from it
        seen = probe(watch.env, ros2_domain, wait_for=["/NDC3", "/NREA"], until_wired=True)
        assert seen["dangling"] == {"calls": [], "subscriptions": []}, seen["dangling"]
        release = watch.wait("release", after=before)
        assert release["component"] == "NSM3"
        after = watch.events()[watch.events().index(release) :]
        assert not [e for e in after if e["event"] in ("replanned", "launch")]  # no flapping
    finally:
        watch.stop()


def test_with_no_configuration_left_watch_tries_again_once_the_hold_is_over(
    ros2_domain: int, tmp_path: Path
) -> None:
    """NREA is the only reasoner: killed, nothing can replace it. Before, watch stayed at
    "no configuration" for good; now NREA is a candidate again after its hold, and started."""
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--hold", "3")
    try:
        watch.wait("conformant")
        before = len(watch.events())
        os.kill(watch.pids()["NREA"], signal.SIGKILL)
        watch.wait("no-configuration", after=before)
        hold = watch.wait("hold", after=before)
        assert hold["component"] == "NREA" and "--restarts 0" in hold["message"]
        watch.wait("release", after=before)
        done = watch.wait("conformant", after=before)
        assert done["configuration"]["reasoner"] == "NREA"
        launches = [e for e in watch.events()[before:] if e["event"] == "launch"]
        assert [e["components"] for e in launches] == [["NREA"]]
    finally:
        watch.stop()
