"""Name mapping, live-vs-expected comparison, library drafts and launch files, without ROS."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from dataclasses import replace
from datetime import UTC, datetime
from pathlib import Path
from types import MappingProxyType
from typing import Any

from rosreconf.cli.app import app
from rosreconf.errors import Severity
from rosreconf.formats.loader import Source, check_loaded, load_bundled, load_paths, load_sources
from rosreconf.model import Component, Configuration, RosLaunch
from rosreconf.model.wiring import interface_live_name, node_live_name
from rosreconf.ros.conformance import compare
from rosreconf.ros.importer import component_name, draft_library
from rosreconf.ros.launchfiles import RosVersion, launch_file, wiring
from rosreconf.ros.livegraph import LiveGraph, LiveNode, to_json
from rosreconf.ros.ros1.standins import STANDIN_PACKAGE, standin_spec

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


def _ros2_nodes(config: Configuration, wired_for: Configuration | None) -> dict[str, LiveNode]:
    """Return ROS 2 stand-ins of ``config``, each consumer wired for ``wired_for`` (None: not)."""
    from rosreconf.ros.standin_spec import ros2_standin_spec

    remaps = wiring(LIB, SCHEMA, wired_for) if wired_for is not None else {}
    out = {}
    for c in config.components:
        spec = ros2_standin_spec(LIB[c])
        rule = {f"/{a}": "/" + b.lstrip("/") for a, b, _ in remaps.get(c, [])}
        out[c] = LiveNode(
            node_live_name(LIB[c]), None, None, tuple(p["topic"] for p in spec["publish"]),
            tuple(rule.get(p["topic"], p["topic"]) for p in spec["subscribe"]),
            tuple(p["service"] for p in spec["serve"]),
            tuple(rule.get(p["service"], p["service"]) for p in spec["call"]), alive=True,
        )  # fmt: skip
    return out


def _ros2(nodes: Any) -> LiveGraph:
    return LiveGraph("ros2://domain/1", WHEN, tuple(nodes), ros_version=2)


def test_a_kept_consumer_wired_for_the_old_arm_is_unwired_and_its_old_calls_dangle() -> None:
    dc = Configuration.of(SCHEMA.name, {**SCHEMA.nominal, **{
        r: c for r, c in zip(("base_joint", "shoulder_joint", "elbow_joint", "wrist_joint",
                              "gripper_joint", "positioning", "grasping", "carrying", "placing"),
                             ("NDC1", "NDC2", "NDC3", "NDC4", "NDC5", "NFB11", "NFB12", "NFB13",
                              "NFB14"), strict=True)}}, SCHEMA.graph.roles)  # fmt: skip
    nodes = _ros2_nodes(dc, dc)
    assert compare(dc, LIB, SCHEMA, _ros2(nodes.values())).ok  # NREA's own servo names: excused
    nodes["NREA"] = _ros2_nodes(NOMINAL, NOMINAL)["NREA"]  # kept through the repair
    result = compare(dc, LIB, SCHEMA, _ros2(nodes.values()))
    found = sorted((f.code, f.live_name) for f in result.findings)
    joints = ("base", "elbow", "gripper", "shoulder", "wrist")
    assert found == sorted([("unwired", f"/{j}/dc_servo_command") for j in joints]
                           + [("unserved-client", f"/arm_servo/{j}/servo_command")
                              for j in joints])  # fmt: skip
    elbow = next(f for f in result.findings if f.live_name == "/arm_servo/elbow/servo_command")
    assert "NSM3's name for it" in elbow.message


def test_dangling_uses_count_when_tied_to_a_requirement_or_a_call() -> None:
    nodes = _ros2_nodes(NOMINAL, NOMINAL)
    nvp = nodes["NVP1"]
    nodes["NVP1"] = replace(nvp, subscribes=(*nvp.subscribes, "/initialpose"),
                            clients=(*nvp.clients, "/camera2/image"))  # fmt: skip
    result = compare(NOMINAL, LIB, SCHEMA, _ros2(nodes.values()))
    assert [(f.code, f.component, f.live_name) for f in result.findings] == [
        ("unserved-client", "NVP1", "/camera2/image")
    ]  # NCA2's name for NVP1's camera_image; /initialpose is not the configuration's
    assert "NCA2's name for it" in result.findings[0].message
    assert "NCA1 serves it as /camera1/image" in result.findings[0].message
    assert ("/NVP1", "/camera2/image") in result.checked.calls


def test_not_managed_is_ros2_only() -> None:
    managed = LIB["NSM3"].launch
    assert managed is not None
    lib = replace(LIB, components=tuple(
        replace(c, launch=replace(managed, lifecycle=True)) if c.name == "NSM3" else c
        for c in LIB.components))  # fmt: skip
    nodes = _ros2_nodes(NOMINAL, NOMINAL)
    codes = [
        (f.code, f.component) for f in compare(NOMINAL, lib, SCHEMA, _ros2(nodes.values())).findings
    ]
    assert codes == [("not-managed", "NSM3")]
    ros1 = LiveGraph(
        "http://127.0.0.1:11311/",
        WHEN,
        tuple(replace(n, alive=None, pid=1) for n in nodes.values()),
    )
    assert compare(NOMINAL, lib, SCHEMA, ros1).ok
    # an unconfigured managed node has no endpoints yet: not-active, never a name clash
    nodes["NSM3"] = LiveNode("/NSM3", alive=True, serves=("/NSM3/get_state",),
                             lifecycle_state="unconfigured")  # fmt: skip
    found = compare(NOMINAL, lib, SCHEMA, _ros2(nodes.values())).findings
    assert [f.code for f in found if f.component == "NSM3"] == ["not-active", "missing-service"]


def test_a_node_with_a_components_name_but_none_of_its_endpoints_is_a_name_clash() -> None:
    """The impostor: /NSM3 runs, but offers nothing NSM3 offers. Judged against the ROS-graph
    (every interface NSM3 serves in this configuration), not against the node's name."""
    nodes = _running(NOMINAL)
    clean = compare(NOMINAL, LIB, SCHEMA, _live(nodes))
    assert not [f for f in clean.findings if f.code == "name-clash"], clean.findings
    bare = [replace(n, serves=()) if n.name == "/NSM3" else n for n in nodes]
    check = compare(NOMINAL, LIB, SCHEMA, _live(bare))  # no endpoints at all: a squatter
    (squat,) = [f for f in check.findings if f.code == "name-clash"]
    assert (squat.component, squat.live_name) == ("NSM3", "/NSM3")
    assert "no endpoints at all" in squat.message
    beside = compare(NOMINAL, LIB, SCHEMA, _live([*nodes, LiveNode("/NSM3", "http://h:2/", 2)]))
    assert [(f.code, f.live_name) for f in beside.findings] == [("duplicate-node", "/NSM3")]
    impostor = [replace(n, serves=("/some/other",)) if n.name == "/NSM3" else n for n in nodes]
    check = compare(NOMINAL, LIB, SCHEMA, _live(impostor))
    clashes = [f for f in check.findings if f.code == "name-clash"]
    assert [(f.component, f.live_name) for f in clashes] == [("NSM3", "/NSM3")]
    assert "/arm_servo/elbow/servo_command" in clashes[0].message
    # an endpoint unrelated to NSM3 does not make it NSM3; its own label unwired does (that
    # is NSM3 started without its remapping: missing-service, rewiring, never a clash)
    for serves, clash in (
        (("/some/other",), True),
        (("/NSM3/elbow/digital_servo_command",), False),
    ):
        other = [replace(n, serves=serves) if n.name == "/NSM3" else n for n in nodes]
        check = compare(NOMINAL, LIB, SCHEMA, _live(other))
        assert any(f.code == "name-clash" for f in check.findings) is clash, serves
        assert any(f.code == "missing-service" and f.component == "NSM3" for f in check.findings)


def test_parked_managed_alternatives_are_standbys_not_extra_nodes(
    tmp_path: Path, runner: Any
) -> None:
    """``inspect`` judges a parked standby as ``watch --standby`` does: not an extra node.

    Every component managed; beside the nominal configuration (active) run NCA2 (inactive: a
    ready standby), NCO2 (unconfigured: parked), NVP2 (active: doing work, extra) and a
    managed node the library does not know (inactive, extra)."""
    root = Path(__file__).resolve().parent.parent
    text = (root / "libraries" / "robot_arms.yaml").read_text()
    library = tmp_path / "managed.yaml"
    library.write_text(text.replace("\n    ros:\n", "\n    ros:\n      lifecycle: true\n"))
    alternatives = Configuration.of(SCHEMA.name, {**SCHEMA.nominal, "camera": "NCA2",
                                    "gripper_sensor": "NCO2", "perception": "NVP2"},
                                    SCHEMA.graph.roles)  # fmt: skip
    nodes = [*_ros2_nodes(NOMINAL, NOMINAL).values()]
    states = {"/NCA2": "inactive", "/NCO2": "unconfigured", "/NVP2": "active"}
    nodes += [n for n in _ros2_nodes(alternatives, None).values() if n.name in states]
    nodes.append(LiveNode("/stranger", alive=True))
    nodes = [
        replace(n, serves=(*n.serves, f"{n.name}/get_state"),
                lifecycle_state=states.get(n.name, "inactive" if n.name == "/stranger" else
                                           "active"))
        for n in nodes
    ]  # fmt: skip
    snapshot = tmp_path / "graph.json"
    snapshot.write_text(to_json(_ros2(nodes)))
    files = ["--library", str(library), "--schema", str(root / "schemas/object_repositioning.yaml")]
    out = runner.invoke(app, ["inspect", "--snapshot", str(snapshot), *files, "--json"])
    doc = json.loads(out.stdout)
    assert out.exit_code == 1, out.stdout
    assert sorted((f["code"], f["live_name"]) for f in doc["findings"]) == [
        ("extra-node", "/NVP2"), ("extra-node", "/stranger")]  # fmt: skip
    assert doc["standby"] == [
        {"node": "/NCA2", "components": ["NCA2"], "state": "inactive"},
        {"node": "/NCO2", "components": ["NCO2"], "state": "unconfigured"},
    ]
    shown = runner.invoke(app, ["inspect", "--snapshot", str(snapshot), *files]).stdout
    assert "standby (managed nodes of the library, out of service):" in shown
    assert "  /NCA2 (NCA2): inactive\n" in shown and "  /NCO2 (NCO2): unconfigured\n" in shown
    assert "extra-node: /NCA2" not in shown and "extra-node: /NVP2" in shown


def test_a_node_read_with_a_lifecycle_state_is_managed_whatever_its_listing_shows() -> None:
    """The reader gives a state to a node it knows is managed (seen serving get_state on the
    participant that still runs it) even when a read's listing misses its state services:
    ``unknown`` or hung per the state rules, never ``not-managed``."""
    managed = LIB["NSM3"].launch
    assert managed is not None
    lib = replace(LIB, components=tuple(
        replace(c, launch=replace(managed, lifecycle=True)) if c.name == "NSM3" else c
        for c in LIB.components))  # fmt: skip
    nodes = _ros2_nodes(NOMINAL, NOMINAL)
    for state, code in (("active", None), ("unknown", "not-active"), (None, "not-managed")):
        nodes["NSM3"] = replace(nodes["NSM3"], lifecycle_state=state)
        found = compare(NOMINAL, lib, SCHEMA, _ros2(nodes.values())).findings
        assert [f.code for f in found] == ([code] if code else []), state


def test_a_node_publishing_a_declared_context_topic_is_the_sensor_not_an_extra_node() -> None:
    """The SUAVE-like example declares /water_visibility: the node publishing it is where
    context is read from, not part of the configuration, and no finding; any other node
    outside the configuration is still an extra node."""
    example = Path(__file__).resolve().parent.parent / "docs" / "examples" / "suave"
    loaded = load_paths([example / "library.yaml", example / "schema.yaml"])
    lib, (schema,) = loaded.library, loaded.schemas
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    nodes = [
        LiveNode("/spiral_high", None, None, ("/search_path",), alive=True),
        LiveNode("/controller_fast", None, None, ("/cmd_vel",), ("/search_path",), alive=True),
        LiveNode("/thrusters", None, None, (), ("/cmd_vel",), alive=True),
    ]
    assert compare(config, lib, schema, _ros2(nodes)).ok
    sensor = LiveNode("/visibility_sensor", None, None, ("/water_visibility",), alive=True)
    stranger = LiveNode("/stranger", None, None, ("/sonar",), alive=True)
    result = compare(config, lib, schema, _ros2([*nodes, sensor, stranger]))
    assert [(f.code, f.live_name) for f in result.findings] == [("extra-node", "/stranger")]
