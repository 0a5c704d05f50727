"""Nodes restarted by hand, and squatters: a node of a component's name that rosreconf did not
start is judged by what it offers and how it is wired, never taken on its name alone.

- A kept outside consumer a person restarts with its old ``-r`` rules runs, with the
  component's endpoints but the wrong wiring: ``unwired`` (with the rules that wire it), never
  ``failed`` while it runs, and ``watch`` never starts a second node of its name.
- A bare rclpy node holding a component's name (no endpoints) is a name clash, there before
  ``watch`` or after it. The squatter is named for a person, the component failed and replaced
  (no alternative: started once the name is free); or, with ``--stop-outside``, the squatter's
  process (confirmed through /proc) is stopped and the component started under its own name.
  Beside the running component it is a duplicate name, said when it appears.

Real rclpy nodes under the Jazzy and Kilted venvs; ``watch`` as a subprocess (its JSON log);
the end state read by rclpy's own graph API (``tests/ros2_probe.py``). No timing is asserted.
"""

from __future__ import annotations

import json
import signal
import subprocess
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from ros2_team import STANDIN
from test_watch_outside import _end, _team
from test_watch_ros2 import (
    DC_ARM,
    REPLACED,
    Watch,
    _env,
    _stop_by_hand,
    alive,
    probe,
    watched_by_process,
)
from test_watch_wiring import _python


def _squatter(tmp: Path, domain: int, name: str, python: Path) -> subprocess.Popen[bytes]:
    """Start a bare rclpy node named ``/name``: no endpoints of its own (plumbing only)."""
    env = {**_env(tmp, python), "ROS_DOMAIN_ID": str(domain)}
    spec = json.dumps({"name": name, "namespace": "/"})
    node = subprocess.Popen([str(python), str(STANDIN), spec], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)  # fmt: skip
    assert node.stdout is not None and b'"ready"' in node.stdout.readline()
    return node


def _one_of_each(seen: dict[str, Any]) -> None:
    """Assert rclpy's graph has no two nodes of one name."""
    twice = [n for n, k in Counter(seen["nodes"]).items() if k > 1]
    assert not twice, seen["nodes"]


def _wired_once_each(watch: Watch, domain: int, done: dict[str, Any], python: Path) -> None:
    """Assert rclpy's own view: every node of ``done``'s configuration runs once, all wired."""
    nodes = {f"/{c}" for c in done["configuration"].values() if c}
    seen = probe(watch.env, domain, wait_for=nodes, python=python, until_wired=True)
    _one_of_each(seen)
    assert nodes <= set(seen["nodes"])
    assert seen["dangling"] == {"calls": [], "subscriptions": []}


def _kill(node: subprocess.Popen[bytes] | None) -> None:
    if node is not None and node.poll() is None:
        node.kill()
    if node is not None:
        node.wait()


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_bare_node_with_a_components_name_before_watch_is_a_squatter_replaced(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """/NSM3 runs with no endpoints before watch starts: never taken for NSM3. NSM3 is failed
    (a name clash), the arm moves to NDC3, and the squatter is named for a person."""
    python = _python(distro)
    squatter = _squatter(tmp_path, ros2_domain, "NSM3", python)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", python=python)
        clash = watch.wait("failed")
        assert (clash["component"], clash["how"], clash["node"]) == ("NSM3", "name-clash", "/NSM3")
        assert "no endpoints at all" in clash["message"], clash["message"]
        assert not [e for e in watch.events() if e["event"] == "running"]  # never "all run"
        done = watch.wait("conformant", after=watch.events().index(clash))
        assert done["configuration"]["elbow_joint"] == "NDC3"
        events = watch.events()
        (replanned,) = [e for e in events if e["event"] == "replanned"]
        assert replanned["failed"] == ["NSM3"], replanned
        assert "NSM3" not in watch.pids()  # never started beside the squatter
        said = [e for e in events if e["event"] in ("stop", "stop-by-hand")]
        said = [e for e in said if e.get("node") == "/NSM3"]
        assert [e["event"] for e in said] == ["stop-by-hand"], said  # named once, for a person
        assert "name clash" in said[0]["message"] and str(squatter.pid) in said[0]["message"]
        assert squatter.poll() is None  # not rosreconf's: left running
        _wired_once_each(watch, ros2_domain, done, python)
    finally:
        if watch is not None:
            watch.stop(signal.SIGKILL)
        _kill(squatter)


def test_with_stop_outside_a_squatter_is_stopped_and_the_component_started_in_its_name(
    ros2_domain: int, tmp_path: Path
) -> None:
    """--stop-outside: the squatter's process, confirmed through /proc, is stopped, and NSM3
    is started under its own name at once: one start, no replacement of the arm."""
    python = _python("jazzy")
    squatter = _squatter(tmp_path, ros2_domain, "NSM3", python)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--stop-outside",
                      python=python)  # fmt: skip
        clash = watch.wait("failed")
        assert (clash["component"], clash["how"], clash["node"]) == ("NSM3", "name-clash", "/NSM3")
        stop = watch.wait("stop")
        assert (stop["node"], stop["how"], stop["pid"]) == ("/NSM3", "signal", squatter.pid)
        assert "name clash" in stop["message"]
        assert squatter.wait(10) is not None  # stopped by rosreconf, not by the test
        release = watch.wait("release")  # the name is free: NSM3 is a candidate again
        assert (release["component"], release["node"]) == ("NSM3", "/NSM3")
        done = watch.wait("conformant")
        assert done["configuration"]["elbow_joint"] == "NSM3"
        events = watch.events()
        kinds = [e["event"] for e in events]
        assert not {"replanned", "no-configuration", "stop-by-hand", "not-conformant"} & set(kinds)
        assert "running" not in kinds[: kinds.index("stop")]
        assert kinds.index("failed") < kinds.index("stop") < kinds.index("release")
        nsm3 = [e for e in events if e["event"] == "launch" and "NSM3" in e["components"]]
        assert len(nsm3) == 1 and events.index(nsm3[0]) > events.index(release)
        _wired_once_each(watch, ros2_domain, done, python)
    finally:
        if watch is not None:
            watch.stop(signal.SIGKILL)
        _kill(squatter)


def test_a_squatter_on_the_only_reasoner_is_named_and_the_reasoner_started_once_it_is_gone(
    ros2_domain: int, tmp_path: Path
) -> None:
    """/NREA runs bare and NREA has no alternative: no configuration without it. watch names
    the squatter and never starts a second /NREA, not even when NREA's hold is over; a person
    stops the squatter, and watch starts NREA at once (the name is free)."""
    python = _python("kilted")
    squatter = _squatter(tmp_path, ros2_domain, "NREA", python)
    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--hold", "3",
                      python=python)  # fmt: skip
        clash = watch.wait("failed")
        assert (clash["component"], clash["how"]) == ("NREA", "name-clash")
        after = watch.events().index(clash)
        watch.wait("no-configuration", after=after)
        named = watch.wait("stop-by-hand", after=after)
        assert named["node"] == "/NREA" and "name clash" in named["message"]
        taken = watch.wait("name-taken", after=after)  # its hold over: still not started
        assert (taken["component"], taken["node"]) == ("NREA", "/NREA")
        seen = probe(watch.env, ros2_domain, wait_for=["/NREA"], python=python)
        assert seen["nodes"].count("/NREA") == 1  # the squatter alone
        assert squatter.poll() is None and "NREA" not in watch.pids()
        mark = len(watch.events())
        _stop_by_hand(squatter)  # the person does it
        # NREA starts once its name is free: said as a release naming /NREA, or, when its
        # hold ended as the squatter went, started as a missing component of the configuration
        launch = watch.wait("launch", after=mark)
        while "NREA" not in launch["components"]:
            launch = watch.wait("launch", after=watch.events().index(launch) + 1)
        done = watch.wait("conformant", after=watch.events().index(launch))
        assert done["configuration"]["reasoner"] == "NREA"
        events = watch.events()
        freed = [e for e in events[mark:] if e["event"] == "release" and "node" in e]
        assert all((e["component"], e["node"]) == ("NREA", "/NREA") for e in freed), freed
        launched = [e for e in events if e["event"] == "launch" and "NREA" in e["components"]]
        assert len(launched) == 1 and events.index(launched[0]) >= mark  # never beside it
        _wired_once_each(watch, ros2_domain, done, python)
    finally:
        if watch is not None:
            watch.stop(signal.SIGKILL)
        _kill(squatter)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_squatter_beside_the_running_component_is_a_duplicate_said_and_stopped(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """watch runs the configuration; then a bare /NSM3 starts beside watch's own NSM3. The
    duplicate name is said when it appears; the squatter (not rosreconf's, its process
    confirmed) is stopped with --stop-outside, NSM3 keeps running, and conformant follows."""
    python = _python(distro)
    watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--stop-outside",
                  python=python)  # fmt: skip
    squatter = None
    try:
        watch.wait("conformant")
        own = watch.pids()["NSM3"]
        before = len(watch.events())
        squatter = _squatter(tmp_path, ros2_domain, "NSM3", python)
        dup = watch.wait("duplicate", after=before)
        assert (dup["node"], dup["component"]) == ("/NSM3", "NSM3"), dup
        stop = watch.wait("stop", after=before)
        assert (stop["node"], stop["how"], stop["pid"]) == ("/NSM3", "signal", squatter.pid)
        assert squatter.wait(10) is not None
        watch.wait("conformant", after=before)
        after = watch.events()[before:]
        assert not [e for e in after if e["event"] in ("failed", "replanned", "launch")], after
        assert alive(own)  # the component itself was never touched
        seen = probe(watch.env, ros2_domain, wait_for=["/NSM3"], python=python)
        assert seen["nodes"].count("/NSM3") == 1
    finally:
        watch.stop(signal.SIGKILL)
        _kill(squatter)


@pytest.mark.parametrize("distro", ["jazzy", "kilted"])
def test_a_kept_outside_consumer_restarted_by_hand_with_its_old_wiring_is_unwired(
    ros2_domain: int, tmp_path: Path, distro: str
) -> None:
    """The team's own nodes; NSM3 dies, watch moves the arm to NDC3 (stopping the replaced team
    nodes with --stop-outside) and names NREA to restart rewired; a person does, conformant.
    Then a person restarts NREA with its old rules: it runs, with NREA's endpoints but the
    wrong wiring. watch says so (``unwired``, with the rules) and never starts an NREA of its
    own; a person restarts it with the rules, and watch confirms."""
    from rosreconf.formats.loader import load_bundled
    from rosreconf.model import Configuration
    from rosreconf.ros.launchfiles import ros2_node_arguments, wiring
    from rosreconf.ros.standin_spec import ros2_standin_spec

    python = _python(distro)
    bundle = load_bundled()
    schema = next(s for s in bundle.schemas if s.name == "object_repositioning")
    nominal = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    old = ros2_node_arguments(bundle.library, "NREA", wiring(bundle.library, schema, nominal))
    team, ours = _team(tmp_path, ros2_domain, python=python)
    spec = json.dumps(ros2_standin_spec(bundle.library["NREA"]))

    def start_nrea(args: list[str]) -> None:
        ours["NREA"] = team.start("NREA", [str(python), str(STANDIN), spec, *args])

    watch: Watch | None = None
    try:
        watch = Watch(tmp_path, ros2_domain, "--only", "object_repositioning", "--stop-outside",
                      python=python)  # fmt: skip
        watch.wait("running")
        replaced = {f"/{c}" for c in REPLACED}  # each one's process known before the kill
        watch.until(lambda ev: replaced <= watched_by_process(ev).keys(),
                    "'watched' by its process for each replaced node")  # fmt: skip
        before = len(watch.events())
        ours["NSM3"].kill()
        restart = watch.wait("restart-by-hand", after=before)
        assert restart["component"] == "NREA"
        rules = [a for r in restart["remappings"] for a in ("-r", r)]
        _stop_by_hand(ours["NREA"])
        start_nrea(["--ros-args", "-r", "__node:=NREA", *rules])
        first = watch.wait("conformant", after=before)
        assert first["configuration"]["elbow_joint"] == "NDC3"
        mark = watch.events().index(first) + 1
        _stop_by_hand(ours["NREA"])  # a person restarts NREA with its old rules
        start_nrea(old)
        unwired = watch.wait("unwired", after=mark)
        assert (unwired["component"], unwired["node"]) == ("NREA", "/NREA")
        assert sorted(unwired["remappings"]) == sorted(restart["remappings"])
        assert any("NREA is not wired" in f for f in unwired["findings"]), unwired
        left = watch.wait("left-running", after=mark)
        while "restart rewired by hand: /NREA" not in left["message"]:
            left = watch.wait("left-running", after=watch.events().index(left) + 1)
        since = watch.events()[watch.events().index(unwired) :]
        assert not [e for e in since if e["event"] == "failed"], since  # it runs: not failed
        _stop_by_hand(ours["NREA"])  # a person restarts it with the rules
        start_nrea(["--ros-args", "-r", "__node:=NREA", *rules])
        done = watch.wait("conformant", after=watch.events().index(unwired))
        assert done["configuration"]["reasoner"] == "NREA"
        events = watch.events()
        launched = [e for e in events if e["event"] == "launch" and "NREA" in e["components"]]
        assert not launched, "watch started an NREA of its own"
        assert not [e for e in events[mark:] if e["event"] in ("replanned", "launch")]
        # rclpy's own view: one /NREA, and nothing dangles but NREA's own names for the
        # unchosen (digital) arm, which a team node acting out its whole entry keeps calling
        for _ in range(3):  # read again while discovery of the team's nodes is still going on
            arm = [f"/{c}" for c in DC_ARM]  # until they are wired: NREA dangles for good
            seen = probe(watch.env, ros2_domain, wait_for=["/NREA", *arm], wired=arm,
                         python=python)  # fmt: skip
            calls = seen["dangling"]["calls"]
            rest = [c for c in calls if c[0] != "/NREA" or "digital_servo_command" not in c[1]]
            if not rest and not seen["dangling"]["subscriptions"]:
                break
        _one_of_each(seen)
        assert not rest and not seen["dangling"]["subscriptions"], seen["dangling"]
        assert [c for c in calls if c[0] == "/NREA"], "NREA acts out its unchosen alternative"
    finally:
        _end(watch, team, ours)
