"""rosreconf resolves ROS names as rcl and rospy do, and wires and restarts by resolved names.

``rosreconf.model.wiring.resolve_name`` is the one resolver of wiring, conformance, launch
files and stand-ins. Its table is rcl's own test expectations (ros2/rcl
``rcl/test/rcl/test_expand_topic_name.cpp`` ``various_valid_topics`` and
``test_remap.cpp``) and the namespace cases a robot has. Then the same table is resolved by
rcl itself through real rclpy nodes (``tests/ros2_resolve.py``, Jazzy and Kilted) and, for
ROS 1's spellings, by rospy's own ``rospy.names`` (the system Python), and the answers must
be equal. Last, what a user sees: ``rosreconf launch`` writes a remap exactly where the
resolved names differ, and ``plan`` restarts a kept consumer exactly when they change.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
import xmlrpc.client
from pathlib import Path

import pytest
import ros2_real
import ros_harness
from test_launchfiles import SYSTEM_PYTHON
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.model.wiring import remap_rules, resolve_name, rule_spelling

DATA = Path(__file__).with_name("data") / "namespaces"
FILES = ["-l", str(DATA / "library.yaml"), "-s", str(DATA / "schema.yaml")]
RESOLVE = Path(__file__).with_name("ros2_resolve.py")

Case = tuple[str, str, str, tuple[tuple[str, str], ...], str]
"""(name, node, namespace, remap rules in order, the resolved name)."""

RCL: list[Case] = [
    # test_expand_topic_name.cpp, various_valid_topics
    ("/chatter", "my_node", "/my_ns", (), "/chatter"),
    ("chatter", "my_node", "/my_ns", (), "/my_ns/chatter"),
    ("{node}/chatter", "my_node", "/my_ns", (), "/my_ns/my_node/chatter"),
    ("/{node}", "my_node", "/my_ns", (), "/my_node"),
    ("{node}", "my_node", "/my_ns", (), "/my_ns/my_node"),
    ("{ns}", "my_node", "/my_ns", (), "/my_ns"),
    ("{namespace}", "my_node", "/my_ns", (), "/my_ns"),
    ("{namespace}/{node}/chatter", "my_node", "/my_ns", (), "/my_ns/my_node/chatter"),
    ("ping", "my_node", "/", (), "/ping"),
    ("ping", "my_node", "/my_ns", (), "/my_ns/ping"),
    ("/ping", "my_node", "/", (), "/ping"),
    ("/ping", "my_node", "/my_ns", (), "/ping"),
    ("~", "my_node", "/", (), "/my_node"),
    ("~", "my_node", "/my_ns", (), "/my_ns/my_node"),
    ("~/ping", "my_node", "/", (), "/my_node/ping"),
    ("~/ping", "my_node", "/my_ns", (), "/my_ns/my_node/ping"),
    # test_remap.cpp: the rule's from is expanded for the node, and matched whole
    ("/bar/foo", "NodeName", "/", (("/bar/foo", "/foo/bar"),), "/foo/bar"),
    ("/foo/bar", "NodeName", "/", (("/bar/foo", "/foo/bar"),), "/foo/bar"),
    ("/ns/foo", "NodeName", "/ns", (("foo", "bar"),), "/ns/bar"),
    ("/foobar", "NodeName", "/", (("__ns", "/namespace"), ("/foobar", "/foo/bar")), "/foo/bar"),
    # local_topic_replacement_before_global: the first rule that matches wins
    ("/bar/foo", "NodeName", "/", (("/bar/foo", "/foo/local_args"), ("/bar/foo", "/x")),
     "/foo/local_args"),
    # a robot's namespaces: what wiring writes, and what it must not assume
    ("scan", "estimator", "/", (("scan", "/sensors/scan"),), "/sensors/scan"),
    ("scan", "monitor", "/sensors", (), "/sensors/scan"),
    ("scan", "monitor", "/sensors", (("scan", "/scan"),), "/scan"),
    ("scan", "monitor", "/sensors", (("/scan", "/elsewhere"),), "/sensors/scan"),
    ("~/scan_in", "tracker", "/nav", (("~/scan_in", "/sensors/scan"),), "/sensors/scan"),
    ("/nav/tracker/scan_in", "tracker", "/nav", (("~/scan_in", "/s"),), "/s"),
    ("~/scan_in", "tracker", "/nav", (("scan_in", "/s"),), "/nav/tracker/scan_in"),
    ("scan", "n", "/a/b", (("scan", "other"),), "/a/b/other"),
    ("scan", "n", "/a", (("scan", "~/mine"),), "/a/n/mine"),
    ("a", "n", "/", (("a", "b"), ("b", "c")), "/b"),  # one rule applies, never a chain
    ("relocalize/_action/send_goal", "tracker", "/nav",
     (("relocalize/_action/send_goal", "/relocalize/_action/send_goal"),),
     "/relocalize/_action/send_goal"),
]  # fmt: skip

ROS1: list[Case] = [
    # ROS 1's private spelling ~x, and remapping keys of either spelling (rosgraph.names)
    ("~odom", "wheel_odom", "/base", (), "/base/wheel_odom/odom"),
    ("~odom", "wheel_odom", "/", (), "/wheel_odom/odom"),
    ("odom", "wheel_odom", "/base", (), "/base/odom"),
    ("/odom", "wheel_odom", "/base", (), "/odom"),
    ("~scan_in", "tracker", "/nav", (("~scan_in", "/sensors/scan"),), "/sensors/scan"),
    ("~scan_in", "tracker", "/nav", (("~/scan_in", "/sensors/scan"),), "/sensors/scan"),
    ("scan", "estimator", "/", (("scan", "/sensors/scan"),), "/sensors/scan"),
    ("scan", "monitor", "/sensors", (("scan", "other"),), "/sensors/other"),
    ("follow_path/goal", "nav", "/robot", (("follow_path/goal", "/rpp/follow_path/goal"),),
     "/rpp/follow_path/goal"),
]  # fmt: skip


@pytest.mark.parametrize("case", RCL + ROS1, ids=lambda c: f"{c[2]}:{c[1]}:{c[0]}")
def test_resolve_name_follows_rcl_and_ros1(case: Case) -> None:
    name, node, namespace, rules, expected = case
    assert resolve_name(name, node, namespace, rules) == expected


def test_a_namespace_is_absolute_and_an_unknown_substitution_is_refused() -> None:
    assert resolve_name("scan", "n", "sensors") == "/sensors/scan"  # rcl_node_init adds the /
    assert resolve_name("scan", "n", None) == resolve_name("scan", "n", "") == "/scan"
    with pytest.raises(ValueError, match=r"unknown substitution \{robot\}"):
        resolve_name("{robot}/scan", "n", "/")


def test_a_relative_namespace_is_started_absolute_as_rcl_requires() -> None:
    """The monitor's library says ``namespace: sensors``; rcl refuses ``-r __ns:=sensors``."""
    from rosreconf.formats.loader import load_paths
    from rosreconf.ros.launchfiles import ros2_node_arguments

    library = load_paths([DATA / "library.yaml"]).library
    assert library["monitor"].namespace == "sensors"
    args = ros2_node_arguments(library, "monitor", {})
    assert args[:5] == ["--ros-args", "-r", "__node:=monitor", "-r", "__ns:=/sensors"]


def test_rules_spell_a_private_name_for_rcl_and_move_each_name_under_an_action() -> None:
    assert rule_spelling("~scan_in") == "~/scan_in"
    assert rule_spelling("~/scan_in") == "~/scan_in" and rule_spelling("~") == "~"
    assert remap_rules("~scan", "/s", False, 2) == [("~/scan", "/s")]
    assert remap_rules("~scan", "/s", False, 1) == [("~scan", "/s")]  # ROS 1 keeps its own
    assert [a for a, _ in remap_rules("act", "/x/act", True, 2)] == [
        f"act/_action/{p}" for p in ("send_goal", "cancel_goal", "get_result", "feedback", "status")
    ]
    assert remap_rules("act", "/x/act", True, 1)[0] == ("act/goal", "/x/act/goal")


def _rcl(distro: str, cases: list[Case], domain: int, home: Path) -> list[object]:
    """Return rcl's own resolution of ``cases``, through real rclpy nodes of ``distro``."""
    table = [[n, node, ns, [list(r) for r in rules]] for n, node, ns, rules, _ in cases]
    env = ros2_real.node_env(domain, home)
    out = subprocess.run(
        [str(ros2_real.python_of(distro)), str(RESOLVE)], input=json.dumps(table),
        capture_output=True, text=True, timeout=120, env=env, check=False,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr[-3000:]
    return list(json.loads(out.stdout.splitlines()[-1]))


@pytest.mark.parametrize("distro", ros2_real.DISTROS)
def test_real_rclpy_resolves_every_name_of_the_table_as_rosreconf_does(
    distro: str, ros2_domain: int, tmp_path: Path
) -> None:
    got = _rcl(distro, RCL, ros2_domain, tmp_path)
    ours = [resolve_name(n, node, ns, rules) for n, node, ns, rules, _ in RCL]
    assert got == ours == [case[-1] for case in RCL]
    # rcl refuses ROS 1's ~x, which is why a ROS 2 rule spells it ~/x
    (refused,) = _rcl(distro, [("~odom", "n", "/", (), "")], ros2_domain, tmp_path)
    assert isinstance(refused, dict) and "tilde" in refused["error"]


ROSPY = """
import json, sys
import rosgraph.names, rospy.names
out = []
for name, node, ns, rules in json.load(sys.stdin):
    caller = rosgraph.names.ns_join(ns, node)
    rospy.names._mappings = rosgraph.names.load_mappings([f"{f}:={t}" for f, t in rules])
    rospy.names.initialize_mappings(caller)
    out.append(rospy.names.resolve_name(name, caller))
print(json.dumps(out))
"""
"""rospy's own resolution: its mappings resolved for the node, then the name looked up."""


@pytest.mark.ros
def test_rospy_resolves_the_ros1_spellings_as_rosreconf_does() -> None:
    # ROS 1 has no {substitutions}; rospy reads a ~/x in code as /x (roscpp as rcl does), so a
    # ROS 1 library spells it ~x; its mappings are a dict, one rule per from (as rosreconf
    # writes them), where rcl takes the first of two
    plain = [
        c for c in RCL
        if "{" not in c[0] and not c[0].startswith("~/") and c[0] != "~"
        and len({f for f, _ in c[3]}) == len(c[3])
    ]  # fmt: skip
    cases = plain + ROS1
    table = [[n, node, ns, [list(r) for r in rules if r[0] != "__ns"]] for n, node, ns, rules, _
             in cases]  # fmt: skip
    out = subprocess.run(
        [SYSTEM_PYTHON, "-c", ROSPY], input=json.dumps(table), capture_output=True, text=True,
        timeout=60, check=True,
    )  # fmt: skip
    assert json.loads(out.stdout) == [resolve_name(*c[:4]) for c in cases]


def _remaps(version: str, *fail: str) -> dict[str, list[tuple[str | None, str | None]]]:
    """Return node -> its remaps (from, to) in the file ``rosreconf launch`` writes."""
    result = CliRunner().invoke(app, ["launch", version, *FILES, *fail, "-o", "-"])
    assert result.exit_code == 0, result.output
    root = ET.fromstring(result.stdout[: result.stdout.rindex("</launch>") + len("</launch>")])
    return {
        str(n.get("name")): [(r.get("from"), r.get("to")) for r in n.iter("remap")]
        for n in root.iter("node")
    }


GOAL_PARTS = ("send_goal", "cancel_goal", "get_result", "feedback", "status")


def test_launch_ros2_fail_lidar_wires_the_kept_estimator_to_the_sonar_in_its_namespace() -> None:
    relocalize = [(f"relocalize/_action/{p}", f"/relocalize/_action/{p}") for p in GOAL_PARTS]
    assert _remaps("--ros2", "--fail", "lidar") == {
        "sonar_array": [],
        "wheel_odom": [],
        "estimator": [("odom", "/base/wheel_odom/odom"), ("scan", "/sensors/scan")],
        "tracker": [*relocalize, ("reset_odom", "/base/reset_odom"),
                    ("~/scan_in", "/sensors/scan")],
        "monitor": [],  # /sensors/monitor resolves scan as /sensors/scan already
    }  # fmt: skip
    nominal = _remaps("--ros2")
    assert nominal["estimator"] == [("odom", "/base/wheel_odom/odom")]  # /scan is /scan
    assert nominal["monitor"] == [("scan", "/scan")]  # in /sensors, the lidar's /scan
    assert ("~/scan_in", "/scan") in nominal["tracker"]


def test_launch_ros1_writes_the_same_wiring_in_actionlib_terms() -> None:
    remaps = _remaps("--ros1", "--fail", "lidar")
    assert remaps["estimator"] == [("odom", "/base/wheel_odom/odom"), ("scan", "/sensors/scan")]
    assert ("~/scan_in", "/sensors/scan") in remaps["tracker"]  # as the library spells it
    assert ("relocalize/goal", "/relocalize/goal") in remaps["tracker"]
    assert remaps["monitor"] == []


@pytest.mark.ros
def test_roslaunch_reads_the_namespaced_remaps(tmp_path: Path) -> None:
    from test_launchfiles import ROSLAUNCH_READER

    path = tmp_path / "namespaces.launch"
    result = CliRunner().invoke(
        app, ["launch", "--ros1", *FILES, "--fail", "lidar", "-o", str(path)]
    )
    assert result.exit_code == 0, result.output
    out = subprocess.run([SYSTEM_PYTHON, "-c", ROSLAUNCH_READER, str(path)], capture_output=True,
                         text=True, timeout=60, check=True)  # fmt: skip
    nodes = json.loads(out.stdout)["nodes"]
    assert sorted(map(tuple, nodes["estimator"]["remaps"])) == [
        ("odom", "/base/wheel_odom/odom"), ("scan", "/sensors/scan")]  # fmt: skip
    assert ["~/scan_in", "/sensors/scan"] in nodes["tracker"]["remaps"]


REAR_LIDAR = """
  - name: rear_lidar
    abstraction: ranger
    provides:
      - {topic: scan, type: sensor_msgs/msg/LaserScan}
    ros: {package: drivers, executable: lidar, namespace: /rear, remappings: {scan: /scan}}
"""
"""A second lidar in another namespace, publishing the same absolute /scan."""


def _plan(library: Path) -> dict[str, object]:
    argv = ["plan", "-l", str(library), "-s", str(DATA / "schema.yaml"), "--fail", "lidar",
            "--json"]  # fmt: skip
    result = CliRunner().invoke(app, argv)
    assert result.exit_code == 0, result.output
    (schema,) = json.loads(result.stdout)["schemas"]
    return {c["role"]: (c["kind"], c["after"]) for c in schema["changes"] if c["kind"] != "keep"}


def test_a_kept_consumer_restarts_exactly_when_its_resolved_wiring_changes(tmp_path: Path) -> None:
    # the sonar in /sensors: every consumer of scan resolves another name than /scan now
    changes = _plan(DATA / "library.yaml")
    assert changes["ranger"][1] == "sonar"
    assert {r for r, (kind, _) in changes.items() if kind == "restart"} == {
        "estimator", "tracker", "monitor"}  # fmt: skip
    # a lidar in /rear publishing the same absolute /scan: nobody's resolved wiring changes,
    # so none restarts and it is the fewest-change repair
    library = tmp_path / "library.yaml"
    library.write_text((DATA / "library.yaml").read_text() + REAR_LIDAR)
    assert _plan(library) == {"ranger": ("replace", "rear_lidar")}


def _events(log: Path) -> list[dict[str, object]]:
    if not log.exists():
        return []
    return [json.loads(x) for x in log.read_text().splitlines() if x.endswith("}")]


def _wait(log: Path, kind: str, after: int, watch: subprocess.Popen[bytes]) -> None:
    """Wait (at most 120 s, a loaded host) for a ``kind`` event after the first ``after``."""
    deadline = time.monotonic() + 120
    while not any(e["event"] == kind for e in _events(log)[after:]):
        assert watch.poll() is None, _events(log)[-5:]
        assert time.monotonic() < deadline, [e["message"] for e in _events(log)[-6:]]
        time.sleep(0.2)


@pytest.mark.ros
def test_ros1_watch_repairs_onto_the_namespaced_sonar_and_the_master_shows_it_wired(
    ros_master: ros_harness.Master, tmp_path: Path
) -> None:
    """The sonar case on a real roscore: rospy stand-ins, wired by roslaunch remappings."""
    log = tmp_path / "watch.jsonl"
    argv = [sys.executable, "-m", "rosreconf", "watch", "--master", ros_master.uri, *FILES,
            "--apply", "--stand-ins", "--interval", "0.5", "--json-log", str(log)]  # fmt: skip
    watch = subprocess.Popen(argv, env=ros_master.env(), stderr=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, start_new_session=True)  # fmt: skip
    try:
        _wait(log, "conformant", 0, watch)
        _, subs, _ = ros_harness.registered(ros_master.uri, "/sensors/monitor")
        assert subs == {"/scan"}  # in /sensors, wired to the lidar's absolute /scan
        before = len(_events(log))
        master = xmlrpc.client.ServerProxy(ros_master.uri)
        lidar = xmlrpc.client.ServerProxy(master.lookupNode("/test", "/front/lidar")[2])
        os.kill(lidar.getPid("/test")[2], signal.SIGKILL)
        _wait(log, "conformant", before, watch)
        pubs, _, _ = ros_harness.registered(ros_master.uri, "/sensors/sonar_array")
        assert pubs - {"/rosout"} == {"/sensors/scan"}
        server = {"/relocalize/goal", "/relocalize/cancel"}  # actionlib: what a server reads
        client = {"/relocalize/status", "/relocalize/feedback", "/relocalize/result"}
        for node, topics in (
            ("/estimator", {"/sensors/scan", "/base/wheel_odom/odom"} | server),
            ("/nav/tracker", {"/sensors/scan"} | client),
            ("/sensors/monitor", {"/sensors/scan"}),
        ):
            _, subs, _ = ros_harness.registered(ros_master.uri, node)
            assert subs == topics, node
    finally:
        ros_harness.stop(watch)
