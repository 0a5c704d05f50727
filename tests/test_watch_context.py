"""A running ``watch --ros2`` follows what the robot measures (context read live).

The SUAVE-like example (docs/examples/suave): spiral_high is usable only while the water
visibility is at least 3.25, spiral_medium 2.25. The tests' own rclpy publisher
(tests/ros2_context_publisher.py) sends ``/water_visibility``; real rclpy stand-ins under
Jazzy and Kilted run the configuration; what watch did is read from its JSON log, the end
state from rclpy's own graph (tests/ros2_probe.py).

One run per distro goes through every live rule in turn, each against what the publisher
sent and when: a noisy reading crossing the bound faster than the dwell changes nothing; a
steady drop rules spiral_high out after the dwell (not before, and within a second after),
and the fewest-change configuration replaces it, nothing dangling; with ``--prefer cost=1``
the better configuration is taken back once the reading recovers, once, never back and
forth; a topic gone silent is said. Two more runs on Jazzy: ``--no-face`` reads context
through a node of its own; ``--context-lost fail`` rules out what a silent topic
conditions, keeping the running configuration when nothing is left; a NaN is no reading, and
a topic whose type cannot be imported is said; and a robot's shape, the search paths sharing
one namespaced node name, replaced in place and wired across the namespace.
"""

from __future__ import annotations

import json
import subprocess
import time
from datetime import datetime
from pathlib import Path
from typing import IO, Any

import pytest
from test_watch_ros2 import Watch, probe
from test_watch_tasks import _heard, listen
from test_watch_wiring import _python

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "suave"
PUBLISHER = Path(__file__).with_name("ros2_context_publisher.py")
DWELL = 2.0  # watch's default
SILENCE = 3.0


class Publisher:
    """The tests' publisher of /water_visibility; ``send`` returns when the value went out."""

    def __init__(self, python: Path, env: dict[str, str]) -> None:
        self.process = subprocess.Popen(
            [str(python), str(PUBLISHER), "/water_visibility"], env=env, text=True,
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
        )  # fmt: skip
        assert self._line()["ready"] == "/water_visibility"

    def _line(self) -> dict[str, Any]:
        out: IO[str] | None = self.process.stdout
        assert out is not None
        return dict(json.loads(out.readline()))

    def send(self, value: float) -> float:
        """Publish ``value`` from now on; return the wall time its first message went out."""
        self._say(str(value))
        return float(self._line()["at"])

    def silent(self) -> None:
        self._say("silent")

    def _say(self, text: str) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write(text + "\n")
        self.process.stdin.flush()

    def stop(self) -> None:
        self.process.kill()
        self.process.wait(timeout=10)


def _at(event: dict[str, Any]) -> float:
    return datetime.fromisoformat(event["time"]).timestamp()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_watch_follows_the_visibility_without_flapping(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, "--library", str(EXAMPLE / "library.yaml"),
                  "--schema", str(EXAMPLE / "schema.yaml"), "--prefer", "cost=1",
                  "--context-silence", str(SILENCE), python=python)  # fmt: skip
    env = {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)}
    publisher = Publisher(python, env)
    heard = tmp_path / "heard.jsonl"
    listener = listen(python, env, heard)
    try:
        publisher.send(4.0)
        first = watch.wait("conformant")
        assert first["configuration"]["search"] == "spiral_high"

        # noise across the bound, each side held 0.5 s (under the dwell): no switch
        before = len(watch.events())
        for value in (3.0, 4.0) * 4:
            publisher.send(value)
            time.sleep(0.5)
        time.sleep(DWELL + 1.0)
        noisy = watch.events()[before:]
        assert not [e for e in noisy if e["event"] in ("context", "replanned", "prefer")], noisy

        # a steady drop: ruled out after the dwell, replaced by the fewest-change choice
        before = len(watch.events())
        dropped = publisher.send(3.0)
        ruled = watch.wait("context", after=before)
        assert ruled["component"] == "spiral_high" and not ruled["usable"]
        assert ruled["reason"] == "spiral_high needs visibility >= 3.25; it is 3.0"
        assert DWELL <= _at(ruled) - dropped <= DWELL + 1.0, _at(ruled) - dropped
        done = watch.wait("conformant", after=before)
        replanned = next(e for e in watch.events()[before:] if e["event"] == "replanned")
        assert [(c["from"], c["to"]) for c in replanned["changes"]] == [
            ("spiral_high", "spiral_medium")
        ]
        why = [e["message"] for e in watch.events()[before:] if e["event"] == "why"]
        assert any("is ruled out: spiral_high needs visibility >= 3.25" in w for w in why), why
        assert done["configuration"]["search"] == "spiral_medium"
        # /diagnostics: the value and what it rules out, on the face's next message
        rows = [(m["at"], s) for m in _heard(heard, "/diagnostics") for s in m["status"]
                if s["name"] == "rosreconf: context/visibility"]  # fmt: skip
        shown = next(at for at, s in rows if "rules out spiral_high" in s["message"])
        assert shown - _at(ruled) <= 1.0, shown - _at(ruled)
        row = next(s for at, s in rows if at == shown)
        assert row["level"] == 0 and row["values"]["value"] == "3.0"
        assert row["values"]["rules out spiral_high"] == ruled["reason"]
        nodes = {f"/{c}" for c in done["configuration"].values()}
        # wired=nodes: until these leave nothing dangling (the face's /battery_state
        # subscription dangles for good: waiting on every node took the probe's whole 60 s)
        seen = probe(watch.env, ros2_domain, wait_for=nodes, wired=nodes, python=python)
        assert "/spiral_high" not in seen["nodes"] and nodes <= set(seen["nodes"])
        # rosreconf's face subscribes to /battery_state too, which nobody publishes here (said
        # as context-lost); the configuration's own nodes leave nothing dangling
        ours = {k: [x for x in v if x[0] != "/rosreconf"] for k, v in seen["dangling"].items()}
        assert ours == {"calls": [], "subscriptions": []}, seen["dangling"]

        # the reading recovers: --prefer takes the better configuration back, once
        before = len(watch.events())
        recovered = publisher.send(4.0)
        usable = watch.wait("context", after=before)
        assert usable["component"] == "spiral_high" and usable["usable"]
        assert _at(usable) - recovered >= DWELL
        back = watch.wait("conformant", after=before)
        moved = [e for e in watch.events()[before:] if e["event"] == "prefer"]
        assert len(moved) == 1 and moved[0]["metric"] < moved[0]["previous_metric"]
        assert back["configuration"]["search"] == "spiral_high"
        nodes = {f"/{c}" for c in back["configuration"].values()}
        seen = probe(watch.env, ros2_domain, wait_for=nodes, wired=nodes, python=python)
        assert "/spiral_medium" not in seen["nodes"] and nodes <= set(seen["nodes"])
        ours = {k: [x for x in v if x[0] != "/rosreconf"] for k, v in seen["dangling"].items()}
        assert ours == {"calls": [], "subscriptions": []}, seen["dangling"]
        time.sleep(DWELL + 1.0)
        after = watch.events()[before:]
        assert [e["event"] for e in after].count("prefer") == 1  # no back and forth
        assert not [e for e in after if e["event"] in ("replanned", "failed")], after

        # silence: said, and the last value kept (the default): nothing changes
        before = len(watch.events())
        publisher.silent()
        lost = watch.wait("context-lost", after=before, timeout=SILENCE + 30)
        assert lost["name"] == "visibility" and lost["policy"] == "keep"
        assert "its last value 4.0 is kept" in lost["message"]
        time.sleep(DWELL + 1.0)
        assert not [e for e in watch.events()[before:] if e["event"] == "replanned"]
    finally:
        listener.kill()
        publisher.stop()
        watch.stop()


def test_without_the_face_context_is_still_read_by_a_node_of_its_own(
    ros2_domain: int, tmp_path: Path
) -> None:
    """``--no-face``: no /rosreconf node, but /rosreconf_context reads the topics; a drop
    below two bounds at once moves the search to the one path still usable."""
    python = _python("jazzy")
    watch = Watch(tmp_path, ros2_domain, "--library", str(EXAMPLE / "library.yaml"),
                  "--schema", str(EXAMPLE / "schema.yaml"), "--no-face", "--dwell", "1",
                  python=python)  # fmt: skip
    publisher = Publisher(python, {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)})
    try:
        publisher.send(4.0)
        watch.wait("conformant")
        before = len(watch.events())
        publisher.send(2.0)
        done = watch.wait("conformant", after=before)
        said = watch.events()[before:]
        ruled = {e["component"] for e in said if e["event"] == "context" and not e["usable"]}
        assert ruled == {"spiral_high", "spiral_medium"}
        assert done["configuration"]["search"] == "spiral_low"
        seen = probe(watch.env, ros2_domain, wait_for={"/spiral_low", "/rosreconf_context"},
                     python=python)  # fmt: skip
        assert "/rosreconf_context" in seen["nodes"] and "/rosreconf" not in seen["nodes"]
    finally:
        publisher.stop()
        watch.stop()


def test_with_context_lost_fail_a_silent_topic_rules_its_components_out(
    ros2_domain: int, tmp_path: Path
) -> None:
    """``--context-lost fail``: a topic never heard, or gone silent, fails the conditions on
    it. /battery_state is never published, so controller_fast is replanned away; when
    /water_visibility falls silent every search path is ruled out, no configuration is left,
    and the running one is kept (nothing stopped)."""
    python = _python("jazzy")
    watch = Watch(tmp_path, ros2_domain, "--library", str(EXAMPLE / "library.yaml"),
                  "--schema", str(EXAMPLE / "schema.yaml"), "--context-lost", "fail",
                  "--context-silence", "2", "--dwell", "1", python=python)  # fmt: skip
    publisher = Publisher(python, {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)})
    try:
        publisher.send(4.0)
        lost = watch.wait("context-lost")
        assert (lost["name"], lost["policy"]) == ("battery", "fail"), lost
        assert "taken to fail (--context-lost fail)" in lost["message"]
        ruled = watch.wait("context")
        assert ruled["component"] == "controller_fast" and not ruled["usable"]
        assert ruled["reason"] == (
            "controller_fast needs battery >= 0.3; battery is silent (--context-lost fail)"
        )
        replanned = watch.wait("replanned")
        assert [(c["from"], c["to"]) for c in replanned["changes"]] == [
            ("controller_fast", "controller_slow")
        ]
        slow = watch.wait("conformant", after=watch.events().index(replanned))
        assert slow["configuration"] == {
            "search": "spiral_high",
            "control": "controller_slow",
            "thrusters": "thrusters",
        }

        before = len(watch.events())
        publisher.silent()
        watch.wait("no-configuration", after=before, timeout=30)
        said = watch.events()[before:]
        gone = [e for e in said if e["event"] == "context-lost"]
        assert [(e["name"], e["policy"]) for e in gone] == [("visibility", "fail")], gone
        ruled_out = {e["component"] for e in said if e["event"] == "context" and not e["usable"]}
        assert ruled_out == {"spiral_high", "spiral_medium", "spiral_low"}, said
        time.sleep(2.0)  # another look or two: still nothing stopped, nothing said again
        said = watch.events()[before:]
        assert not [e for e in said if e["event"] in ("replanned", "stopped")], said
        assert [e["event"] for e in said].count("no-configuration") == 1, said
        seen = probe(watch.env, ros2_domain, wait_for={"/spiral_high", "/controller_slow"},
                     python=python)  # fmt: skip
        assert {"/spiral_high", "/controller_slow", "/thrusters"} <= set(seen["nodes"])
    finally:
        publisher.stop()
        watch.stop()


def test_a_nan_reading_is_no_reading_and_an_unreadable_topic_is_said(
    ros2_domain: int, tmp_path: Path
) -> None:
    """A NaN is no reading (an unmeasured ``BatteryState.percentage`` is NaN): a topic that
    sends only NaN falls silent, its last value kept, and nothing switches. A context whose
    message type this ROS 2 Python cannot import is said once, as ``context-error``."""
    library = tmp_path / "library.yaml"
    text = (EXAMPLE / "library.yaml").read_text()
    battery = next(line for line in text.splitlines() if "{name: battery," in line)
    depth = "  - {name: depth, topic: /depth, type: rosreconf_test_msgs/msg/Depth, field: data}"
    library.write_text(text.replace(battery, f"{battery}\n{depth}"))
    python = _python("jazzy")
    watch = Watch(tmp_path, ros2_domain, "--library", str(library),
                  "--schema", str(EXAMPLE / "schema.yaml"), "--context-silence", "2",
                  python=python)  # fmt: skip
    publisher = Publisher(python, {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)})
    try:
        publisher.send(4.0)
        error = watch.wait("context-error")
        assert error["name"] == "depth"
        assert "cannot subscribe to /depth as rosreconf_test_msgs/msg/Depth" in error["message"]
        up = watch.wait("conformant")
        assert up["configuration"]["search"] == "spiral_high"

        before = len(watch.events())
        nan = publisher.send(float("nan"))
        lost = watch.wait("context-lost", after=before, timeout=30)
        while lost["name"] != "visibility":  # battery and depth, never heard, may come first
            lost = watch.wait("context-lost", after=watch.events().index(lost) + 1, timeout=30)
        assert "its last value 4.0 is kept" in lost["message"], lost
        assert _at(lost) - nan >= 2.0 - 0.2  # silent since the last real reading (10 Hz)
        time.sleep(DWELL + 1.0)
        said = watch.events()[before:]
        assert not [e for e in said if e["event"] in ("context", "replanned")], said
        assert [e["event"] for e in watch.events()].count("context-error") == 1
    finally:
        publisher.stop()
        watch.stop()


def _shaped_library(tmp: Path) -> Path:
    """The example with a robot's shape: the three search paths are alternatives of one node,
    ``/auv/search`` (a namespace, one node name shared), as Nav2's planners share one; the
    controller stays outside the namespace, so its requirement is wired across it."""
    text = (EXAMPLE / "library.yaml").read_text()
    for name in ("spiral_high", "spiral_medium", "spiral_low"):
        anchor = f"  - name: {name}\n"
        assert anchor in text
        text = text.replace(anchor, anchor + "    ros: {package: suave_search, executable: "
                            f"{name}, node: search, namespace: /auv}}\n")  # fmt: skip
    library = tmp / "suave_shaped.yaml"
    library.write_text(text)
    return library


def _pids(watch: Watch, component: str) -> list[int]:
    """Return the pids watch's log says it started ``component``'s node in."""
    return [e["pids"][component] for e in watch.events()
            if e["event"] == "launch" and component in e.get("pids", {})]  # fmt: skip


def test_a_ruled_out_alternative_sharing_a_namespaced_node_name_is_replaced_wired(
    ros2_domain: int, tmp_path: Path
) -> None:
    """A drop in visibility rules spiral_high out; spiral_medium runs as the same node
    ``/auv/search``. Read by rclpy, not by rosreconf: exactly one ``/auv/search``, the
    controller's subscription wired to it across the namespace (nothing dangling), and the
    process spiral_high ran in is gone (/proc), not left beside its successor."""
    python = _python("jazzy")
    watch = Watch(tmp_path, ros2_domain, "--library", str(_shaped_library(tmp_path)),
                  "--schema", str(EXAMPLE / "schema.yaml"), python=python)  # fmt: skip
    publisher = Publisher(python, {**watch.env, "ROS_DOMAIN_ID": str(ros2_domain)})
    try:
        publisher.send(4.0)
        first = watch.wait("conformant")
        assert first["configuration"]["search"] == "spiral_high"
        before = len(watch.events())
        publisher.send(3.0)
        done = watch.wait("conformant", after=before)
        assert done["configuration"]["search"] == "spiral_medium"
        nodes = {"/auv/search", "/controller_fast", "/thrusters"}
        # wired=nodes: until these leave nothing dangling (the face's /battery_state
        # subscription dangles for good: waiting on every node took the probe's whole 60 s)
        seen = probe(watch.env, ros2_domain, wait_for=nodes, wired=nodes, python=python)
        assert seen["nodes"].count("/auv/search") == 1, seen["nodes"]
        assert "/auv/search_path" in seen["topics"] and "/search_path" not in seen["topics"]
        ours = {k: [x for x in v if x[0] != "/rosreconf"] for k, v in seen["dangling"].items()}
        assert ours == {"calls": [], "subscriptions": []}, seen["dangling"]
        old = _pids(watch, "spiral_high")
        assert old and not [p for p in old if Path(f"/proc/{p}").exists()], old
        assert _pids(watch, "spiral_medium"), watch.events()[before:]
    finally:
        publisher.stop()
        watch.stop()
