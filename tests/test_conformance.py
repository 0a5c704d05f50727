"""Name mapping, live-vs-expected comparison, library drafts and launch files, without ROS."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from datetime import UTC, datetime
from pathlib import Path
from types import MappingProxyType
from typing import Any

from rosreconf.cli.app import app
from rosreconf.errors import Severity
from rosreconf.formats.loader import Source, check_loaded, load_bundled, load_sources
from rosreconf.model import Component, Configuration, RosLaunch
from rosreconf.ros.conformance import compare, interface_live_name, node_live_name
from rosreconf.ros.importer import component_name, draft_library
from rosreconf.ros.launchfiles import RosVersion, launch_file, wiring
from rosreconf.ros.livegraph import LiveGraph, LiveNode, to_json
from rosreconf.ros.standins import STANDIN_PACKAGE, standin_spec

WHEN = datetime(2026, 1, 1, tzinfo=UTC)
BUNDLE = load_bundled()
LIB = BUNDLE.library
SCHEMA = next(s for s in BUNDLE.schemas if s.name == "object_repositioning")
NOMINAL = Configuration.of(SCHEMA.name, SCHEMA.nominal, SCHEMA.graph.roles)


def _live(nodes: list[LiveNode], types: dict[str, str] | None = None) -> LiveGraph:
    return LiveGraph("http://127.0.0.1:11311/", WHEN, tuple(nodes), types or {})


def _running(config: Configuration, pid: int | None = 1) -> list[LiveNode]:
    """Return live nodes acting out ``config`` exactly (each serves its remapped services)."""
    out = []
    for c in config.components:
        comp = LIB[c]
        spec = standin_spec(comp)
        serves = tuple(s["service"] for s in spec["serve"])
        out.append(LiveNode(node_live_name(comp), "http://127.0.0.1:1/", pid, (), (), serves))
    return out


def test_names_follow_remappings_and_namespaces() -> None:
    assert node_live_name(LIB["NSM3"]) == "/NSM3"
    assert interface_live_name(LIB["NSM3"], "elbow/digital_servo_command") == (
        "/arm_servo/elbow/servo_command"
    )
    launch = RosLaunch("p", "e", remappings=MappingProxyType({"a": "b/c"}), namespace="/arm")
    comp = Component("X", "x", launch=launch)
    assert node_live_name(comp) == "/arm/X"
    assert interface_live_name(comp, "a") == "/arm/b/c"
    assert interface_live_name(comp, "joint_states") == "/arm/joint_states"
    assert interface_live_name(comp, "/abs") == "/abs"
    assert interface_live_name(Component("Y", "y"), "t") == "/t"


def test_nominal_running_conforms_and_plumbing_is_ignored() -> None:
    nodes = [*_running(NOMINAL), LiveNode("/rosout", "http://x:1/", 2, ("/rosout_agg",))]
    assert compare(NOMINAL, LIB, SCHEMA, _live(nodes)).ok


def test_a_dead_node_is_named_with_its_unmet_requirements() -> None:
    nodes = [n if n.name != "/NSM3" else LiveNode(n.name, n.uri, None, (), (), n.serves)
             for n in _running(NOMINAL)]  # fmt: skip
    nodes.append(LiveNode("/intruder", "http://x:2/", 3))
    result = compare(NOMINAL, LIB, SCHEMA, _live(nodes))
    assert not result.ok
    assert result.failed_components == ("NSM3",)
    codes = {(f.code, f.component) for f in result.findings}
    assert ("dead-node", "NSM3") in codes and ("extra-node", None) in codes
    assert ("unmet-requirement", "NREA") in codes
    doc = result.to_dict()
    assert doc["conformant"] is False and doc["expected_nodes"]["NSM3"] == "/NSM3"


def test_missing_service_and_wrong_topic_type() -> None:
    nodes = [n if n.name != "/NCA1" else LiveNode(n.name, n.uri, 1) for n in _running(NOMINAL)]
    result = compare(NOMINAL, LIB, SCHEMA, _live(nodes))
    assert ("missing-service", "NCA1") in {(f.code, f.component) for f in result.findings}


def test_topics_are_checked_for_publishers_subscribers_and_types() -> None:
    mobile = next(s for s in BUNDLE.schemas if s.name == "indoor_navigation")
    config = Configuration.of(mobile.name, mobile.nominal, mobile.graph.roles)
    live = []
    # each subscriber wired to its publisher's name, as the launch file's remappings do (a
    # stand-in subscribes under its own label, which is not the publisher's name: /odom)
    remaps = wiring(LIB, mobile, config)
    for c in config.components:
        spec: dict[str, Any] = standin_spec(LIB[c])
        pubs = tuple(p["topic"] for p in spec["publish"])
        wired = {f"/{old}": "/" + new.lstrip("/") for old, new, _ in remaps.get(c, [])}
        subs = tuple(wired.get(p["topic"], p["topic"]) for p in spec["subscribe"])
        serves = tuple(p["service"] for p in spec["serve"])
        live.append(LiveNode(node_live_name(LIB[c]), "http://x:1/", 1, pubs, subs, serves))
    types = {p["topic"]: p["type"] for c in config.components
             for p in standin_spec(LIB[c])["publish"]}  # fmt: skip
    assert types and compare(config, LIB, mobile, _live(live, types)).ok
    wrong = {t: "wrong_msgs/Nope" for t in types}
    assert {f.code for f in compare(config, LIB, mobile, _live(live, wrong)).findings} == {
        "wrong-type"
    }
    deaf = [LiveNode(n.name, n.uri, 1, n.publishes, (), n.serves) for n in live]
    codes = {f.code for f in compare(config, LIB, mobile, _live(deaf, types)).findings}
    assert codes == {"missing-topic"}


def test_draft_library_validates_and_maps_names(tmp_path: Path, runner: Any) -> None:
    nodes = [
        LiveNode("/cam", "http://x:1/", 1, ("/image", "/rosout"), (), ("/cam/get_loggers",)),
        LiveNode("/arm/driver", "http://x:2/", 2, (), ("/image", "/nobody"), ("/arm/cmd",)),
        LiveNode("/other/driver", "http://x:3/", None),
        LiveNode("/rosout", "http://x:4/", 4, ("/rosout_agg",)),
    ]
    graph = _live(nodes, {"/image": "sensor_msgs/Image", "/nobody": "std_msgs/Empty"})
    text = draft_library(graph, "robot")
    assert text.startswith("# yaml-language-server: $schema=")
    loaded = load_sources([Source("draft.yaml", text.encode())])
    problems = [*loaded.problems, *check_loaded(loaded)]
    assert not [p for p in problems if p.severity is Severity.ERROR], problems
    lib = loaded.library
    assert [c.name for c in lib] == ["driver", "other_driver", "cam"] or {c.name for c in lib} == {
        "cam", "driver", "other_driver"
    }  # fmt: skip
    assert lib["driver"].launch is not None and lib["driver"].launch.namespace == "/arm"
    assert node_live_name(lib["driver"]) == "/arm/driver"
    (req,) = lib["driver"].requires
    assert req.options[0].label == "/image" and req.options[0].type == "sensor_msgs/Image"
    assert '# TODO: subscribes {topic: "/nobody"' in text
    assert all(c.abstraction.startswith("TODO_") for c in lib)
    snap = tmp_path / "snap.json"
    snap.write_text(to_json(graph))
    out = tmp_path / "lib.yaml"
    result = runner.invoke(app, ["import", "--snapshot", str(snap), "-o", str(out)])
    assert result.exit_code == 0, result.stderr
    assert out.read_text() == draft_library(graph, "imported")
    both = runner.invoke(app, ["import", "--snapshot", str(snap), "--master", "x", "-o", "y"])
    assert both.exit_code == 2


def test_component_names_are_unique_case_insensitively() -> None:
    taken: set[str] = set()
    names = [component_name(n, taken) for n in ("/a/x", "/b/X", "/b/x", "/9lives", "/a-b")]
    assert names == ["x", "b_X", "b_x_2", "N9lives", "a_b"]


def test_launch_files_real_and_stand_in() -> None:
    schema = BUNDLE.configurations.get("object_repositioning")
    config = Configuration.of(schema.name, dict(schema.nominal), schema.graph.roles)
    real = ET.fromstring(
        launch_file(LIB, schema, config, RosVersion.ROS1, only={"NSM3", "NVP1"}).text
    )
    nodes = real.findall("node")
    assert [n.get("name") for n in nodes] == ["NSM3", "NVP1"]
    assert nodes[0].get("pkg") == "robot_arm_servo" and nodes[0].find("param") is not None
    # NVP1 is wired to the camera and gripper sensor of the whole configuration.
    assert {r.get("to") for r in nodes[1].findall("remap")} == {
        "/camera1/image",
        "/gripper1/feeling",
    }
    fake = ET.fromstring(
        launch_file(
            LIB, schema, config, RosVersion.ROS1, only={"NSM3", "NVP1"}, stand_ins=True
        ).text
    )
    nodes = fake.findall("node")
    assert [n.get("pkg") for n in nodes] == [STANDIN_PACKAGE] * 2
    spec = json.loads(str(nodes[0].get("args")).strip("'"))
    assert spec["serve"] == [
        {"service": "/arm_servo/elbow/servo_command", "type": "robot_arm_msgs/DigitalServoCommand"}
    ]
