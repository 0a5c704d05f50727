"""``inspect`` and ``watch --standby`` agree on parked standbys: listed, not extra nodes.

``watch --standby`` starts the managed alternatives of the schema's roles, configured and held
``inactive`` so that a failover is one ``activate``, and says ``conformant`` with them running.
``inspect --configuration`` on the same graph exited 1 with an ``extra-node`` finding for each.
Now it lists them as ``standby`` (text and ``--json``) and exits 0. Real rclpy stand-ins, every
component managed; the standbys' states are read with the tests' own rclpy probe.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from test_watch_ros2 import NOMINAL, SCHEMAS, UP_TIMEOUT, probe, standby_watch
from test_watch_wiring import _python


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_inspect_lists_the_standbys_watch_parks_and_conforms_as_watch_says(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    watch = standby_watch(tmp_path, ros2_domain, python=python)
    try:
        done = watch.wait("conformant")
        deadline = time.monotonic() + UP_TIMEOUT
        while True:  # every standby started is configured (a ready standby: inactive)
            standby = {c for e in watch.events() if e["event"] == "launch" and e.get("standby")
                       for c in e["components"]}  # fmt: skip
            if standby and {*NOMINAL, *standby} <= watch.configured():
                break
            assert time.monotonic() < deadline, watch.events()[-5:]
            time.sleep(0.2)
        names = sorted(f"/{c}" for c in standby)
        seen = probe(watch.env, ros2_domain, *names, python=python)
        assert seen["states"] == dict.fromkeys(names, "inactive"), seen["states"]
        current = tmp_path / "current.json"
        current.write_text(json.dumps({"format": "rosreconf/configuration", "version": 1,
                                       "configurations": {"object_repositioning":
                                                          done["configuration"]}}))  # fmt: skip
        library = tmp_path / "robot_arms_managed.yaml"  # standby_watch's
        files = ["--library", str(library), "--schema", str(SCHEMAS / "object_repositioning.yaml")]
        # --spin-time 8: on a loaded host a one-shot read of 3.5 s once left a standby out
        # (fc11: 10 of 11 listed, NFB11's participant not heard yet)
        argv = [sys.executable, "-m", "rosreconf", "inspect", "--ros2", "--domain",
                str(ros2_domain), "--spin-time", "8", "--configuration", str(current),
                *files]  # fmt: skip
        out = subprocess.run([*argv, "--json"], env=watch.env, capture_output=True, text=True,
                             timeout=120)  # fmt: skip
        doc = json.loads(out.stdout)
        assert out.returncode == 0, doc["findings"]  # as watch says: conformant
        assert [s["node"] for s in doc["standby"]] == names
        assert all(s["state"] == "inactive" for s in doc["standby"]), doc["standby"]
        text = subprocess.run(argv, env=watch.env, capture_output=True, text=True, timeout=120)
        assert text.returncode == 0 and "extra-node" not in text.stdout, text.stdout
        assert "standby (managed nodes of the library, out of service):" in text.stdout
        assert all(f"  {n} ({n[1:]}): inactive\n" in text.stdout for n in names), text.stdout
    finally:
        watch.stop(signal.SIGKILL)
