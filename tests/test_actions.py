"""ROS 2 type names and ROS actions in libraries, through every stage (issue 21, item 8).

The held-out case tests/cases/valid/nav2_actions is a small Nav2-like stack written with ROS
2's names (``sensor_msgs/msg/LaserScan``) and actions (``nav2_msgs/action/FollowPath``).
Its reference answers are independent of the solvers: the same library rewritten with ROS 1
names (``pkg/Type``), and brute force over every assignment checked by the definition
(``is_valid``). The live side is checked on a snapshot of real rclpy nodes
(tests/snapshots/valid/ros2_fibonacci_action.json, written by ``rosreconf snapshot --ros2``
from tests/ros2_action_nodes.py) and, once, on real nodes started by the test.
"""

from __future__ import annotations

import itertools
import json
import os
import re
import select
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import replace
from importlib.resources import as_file
from pathlib import Path
from typing import Any

import jsonschema
import pydot
import pytest
import xmlschema
import yaml
from pddlcheck import plan_all
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_paths
from rosreconf.model import (
    Component,
    ComponentLibrary,
    Configuration,
    Interface,
    InterfaceKind,
    InteroperabilitySchema,
    VertexKind,
    type_key,
)
from rosreconf.model.validity import is_valid, ros_graph, type_clash, violations
from rosreconf.render.pictures import RosPicture, ros_dot
from rosreconf.resources import Bundle, bundled
from rosreconf.ros.conformance import compare
from rosreconf.ros.launchfiles import RosVersion, launch_file
from rosreconf.ros.liveactions import live_actions
from rosreconf.ros.livegraph import LiveGraph, LiveNode, from_json
from rosreconf.ros.standin_spec import standin_spec
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import ClingoEngine, EliminationEngine, Objective

HERE = Path(__file__).parent
CASE = HERE / "cases" / "valid" / "nav2_actions"
SNAPSHOT = HERE / "snapshots" / "valid" / "ros2_fibonacci_action.json"
REPO = HERE.parent
ROS2_PYTHON = REPO / ".venv-ros2-jazzy" / "bin" / "python"
ROS2_NAME = re.compile(r"\b(\w+)/(?:msg|srv|action)/(\w+)\b")
WIRED_ACTIONS = {"compute_path_to_pose", "follow_path", "navigate_to_pose"}


def _load(folder: Path) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    loaded = load_paths([folder])
    assert not [p for p in loaded.problems if p.severity == "error"], loaded.problems
    (schema,) = loaded.schemas
    return loaded.library, schema


def _ros1_copy(tmp_path: Path) -> Path:
    """Copy the case with every ROS 2 type name written the ROS 1 way (pkg/Type)."""
    folder = tmp_path / "ros1"
    shutil.copytree(CASE, folder)
    lib = folder / "lib.yaml"
    text = ROS2_NAME.sub(r"\1/\2", lib.read_text("utf-8"))
    assert not re.search(r"type: \w+/(msg|srv|action)/", text)
    lib.write_text(text, "utf-8")
    return folder


def _brute_force(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: tuple[str, ...] = ()
) -> set[Configuration]:
    """Return every configuration the definition accepts, trying each component everywhere.

    A role takes only a component of its own abstraction (Def. 5): that each other component
    is refused in each role is checked once per (role, component), the other roles holding
    components of their abstractions; the configurations are then every combination of those
    (here 8-12 combinations and 45-54 refusals, against 531,441-1,000,000 checks for the whole
    product of 9-10 components over 6 roles: 29 CPU s of the suite before).
    """
    roles = schema.graph.roles
    names = [c.name for c in library]
    matching = {r.name: [c.name for c in library if c.abstraction == r.abstraction] for r in roles}
    some = {r: (m[0] if m else names[0]) for r, m in matching.items()}
    for role in roles:
        for name in names:
            if name not in matching[role.name]:
                alien = Configuration.of(schema.name, {**some, role.name: name}, roles)
                assert not is_valid(alien, library, schema, failed), (role.name, name)
    out = set()
    for combo in itertools.product(*(matching[r.name] for r in roles)):
        mapping = dict(zip([r.name for r in roles], combo, strict=True))
        config = Configuration.of(schema.name, mapping, roles)
        if is_valid(config, library, schema, failed):
            out.add(config)
    return out


def _listed(library: ComponentLibrary, schema: InteroperabilitySchema) -> set[Configuration]:
    return set(ClingoEngine().configurations(compile_instance(library, schema)))


def _actions_of(library: ComponentLibrary, schema: InteroperabilitySchema, c: Configuration) -> set:
    g = ros_graph(c, library, schema)
    return {d["label"] for v, d in g.nodes(data=True) if v[0] is VertexKind.ACTION}


# --- one type key --------------------------------------------------------------------------


def test_ros2_type_names_compare_equal_to_ros1_names_and_keep_their_spelling() -> None:
    assert type_key("sensor_msgs/msg/LaserScan") == "sensor_msgs/LaserScan"
    assert type_key("nav2_msgs/action/FollowPath") == "nav2_msgs/FollowPath"
    assert type_key("std_srvs/srv/Trigger") == "std_srvs/Trigger"
    assert type_key("pkg/other/Name") == "pkg/other/Name"  # not a ROS 2 folder
    ros2 = Interface(InterfaceKind.TOPIC, "scan", "sensor_msgs/msg/LaserScan")
    ros1 = Interface(InterfaceKind.TOPIC, "scan", "sensor_msgs/LaserScan")
    assert ros2 == ros1 and hash(ros2) == hash(ros1) and ros2.written != ros1.written
    assert str(ros2) == "topic 'scan' (sensor_msgs/msg/LaserScan)"
    action = Interface(InterfaceKind.ACTION, "scan", "sensor_msgs/LaserScan")
    assert action != ros1  # the kind is part of the match


def test_two_spellings_of_one_type_do_not_clash_but_two_types_do() -> None:
    """Rule one-type-per-label compares the key: two providers of scan may spell it apart."""

    def scanner(name: str, typ: str) -> Component:
        return Component(name, "lidar", frozenset({Interface(InterfaceKind.TOPIC, "scan", typ)}))

    ros2 = scanner("A", "sensor_msgs/msg/LaserScan")
    assert type_clash(ros2, scanner("B", "sensor_msgs/LaserScan")) is None
    clash = type_clash(ros2, scanner("C", "sensor_msgs/msg/PointCloud2"))
    assert clash is not None and clash[0].written == "sensor_msgs/msg/LaserScan"


def test_a_library_with_ros2_names_has_the_configurations_of_its_ros1_spelling(
    runner: CliRunner, tmp_path: Path
) -> None:
    ros1_folder = _ros1_copy(tmp_path)
    for folder in (CASE, ros1_folder):
        result = runner.invoke(app, ["validate", "--strict", str(folder)])
        assert result.exit_code == 0, result.output
        assert "0 error(s), 0 warning(s)" in result.output
    library, schema = _load(CASE)
    library1, schema1 = _load(ros1_folder)
    reference = _brute_force(library1, schema1)
    assert len(reference) == 8  # 2 lidars x 2 planners x 2 controllers, all wire their actions
    assert _brute_force(library, schema) == reference
    assert _listed(library, schema) == reference == _listed(library1, schema1)
    assert count(compile_instance(library, schema)) == 8
    best = EliminationEngine().best(compile_instance(library, schema), Objective())
    assert best is not None and best in reference
    for c in reference:
        assert _actions_of(library, schema, c) == WIRED_ACTIONS


def test_enumerate_json_carries_actions_as_written(runner: CliRunner) -> None:
    args = ["enumerate", "--library", str(CASE / "lib.yaml"), "--schema", str(CASE / "task.yaml")]
    result = runner.invoke(app, [*args, "--json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    schema = json.loads(bundled(Bundle.DATA, "output-enumerate.schema.json").read_text("utf-8"))
    jsonschema.validate(doc, schema)
    (task,) = doc["schemas"]
    assert task["count"] == 8
    for config in task["configurations"]:
        graph = config["ros_graph"]
        controller = config["assignment"]["controller"]
        actions = {a["label"]: a for a in graph["actions"]}
        assert set(actions) == WIRED_ACTIONS
        assert actions["follow_path"]["id"] == f"{controller}/follow_path"
        # the provider's spelling: RPP writes nav2_msgs/FollowPath, DWB the ROS 2 name
        spelled = (
            "nav2_msgs/FollowPath"
            if controller == "CONTROLLER_RPP"
            else ("nav2_msgs/action/FollowPath")
        )
        assert actions["follow_path"]["type"] == spelled
        kinds = {(e["from_kind"], e["to_kind"]) for e in graph["edges"]}
        assert ("node", "action") in kinds and ("action", "node") in kinds


def test_an_action_of_the_wrong_type_is_not_a_configuration(tmp_path: Path) -> None:
    folder = tmp_path / "wrong"
    shutil.copytree(CASE, folder)
    with (folder / "lib.yaml").open("a", encoding="utf-8") as lib:
        lib.write(
            "  - name: PLANNER_OLD\n"
            "    abstraction: planner\n"
            "    provides:\n"
            "      - {action: compute_path_to_pose,"
            " type: nav2_msgs/action/ComputePathThroughPoses}\n"
        )
    library, schema = _load(folder)
    reference = _brute_force(library, schema)
    assert len(reference) == 8 and not any("PLANNER_OLD" in c.components for c in reference)
    assert _listed(library, schema) == reference
    assert count(compile_instance(library, schema)) == 8
    nominal = dict(schema.nominal, planner="PLANNER_OLD")
    why = {v.code for v in violations(Configuration.of(schema.name, nominal, schema.graph.roles),
                                      library, schema)}  # fmt: skip
    assert {"edge-unrealised", "requirement-unmet"} <= why
    failed = ("PLANNER_NAVFN", "PLANNER_SMAC")
    assert _brute_force(library, schema, failed) == set()
    assert count(compile_instance(library, schema, failed)) == 0


@pytest.mark.planner
def test_fast_downward_finds_the_configurations_that_wire_actions() -> None:
    library, schema = _load(CASE)
    after = plan_all(library, schema, ("PLANNER_NAVFN",))
    assert after == _brute_force(library, schema, ("PLANNER_NAVFN",)) and len(after) == 4


# --- pictures and launch files -------------------------------------------------------------


def test_the_ros_picture_draws_actions_as_octagons_with_a_legend() -> None:
    library, schema = _load(CASE)
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    (graph,) = pydot.graph_from_dot_data(ros_dot(library, [RosPicture(schema, config)]))
    shapes: dict[str, str] = {}
    for sub in [graph, *graph.get_subgraphs()]:
        for node in sub.get_nodes():
            shapes[node.get_name().strip('"')] = str(node.get("shape")).strip('"')
    octagons = {n for n, s in shapes.items() if s == "octagon"}
    assert octagons == {
        f"{schema.name}:action:PLANNER_NAVFN/compute_path_to_pose",
        f"{schema.name}:action:CONTROLLER_RPP/follow_path",
        f"{schema.name}:action:BT_NAVIGATOR/navigate_to_pose",
        "legend:action",
    }


def test_launch_files_remap_each_name_under_an_action_ros2_and_ros1() -> None:
    """A rule for an action's own name moves nothing on Jazzy (rcl 9) nor on ROS 1.

    tests/test_ros2_namespaces.py shows the five ROS 2 rules moving a real rclpy client.
    """
    library, schema = _load(CASE)
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    ros2 = launch_file(library, schema, config, RosVersion.ROS2).text
    with as_file(bundled(Bundle.DATA, "ros2-launch.xsd")) as xsd:
        xmlschema.XMLSchema(str(xsd)).validate(ros2)
    (nav,) = [n for n in ET.fromstring(ros2).iter("node") if n.get("name") == "BT_NAVIGATOR"]
    assert [(r.get("from"), r.get("to")) for r in nav.iter("remap")] == [
        (f"follow_path/_action/{p}", f"/rpp/follow_path/_action/{p}")
        for p in ("send_goal", "cancel_goal", "get_result", "feedback", "status")
    ]
    ros1 = launch_file(library, schema, config, RosVersion.ROS1).text
    (nav,) = [n for n in ET.fromstring(ros1).iter("node") if n.get("name") == "BT_NAVIGATOR"]
    assert {(r.get("from"), r.get("to")) for r in nav.iter("remap")} == {
        (f"follow_path/{t}", f"/rpp/follow_path/{t}")
        for t in ("goal", "cancel", "status", "feedback", "result")
    }


@pytest.mark.ros
def test_roslaunch_reads_the_five_actionlib_remappings(tmp_path: Path) -> None:
    from test_launchfiles import ROSLAUNCH_READER, SYSTEM_PYTHON

    library, schema = _load(CASE)
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    path = tmp_path / "nav.launch"
    path.write_text(launch_file(library, schema, config, RosVersion.ROS1).text, "utf-8")
    out = subprocess.run(
        [SYSTEM_PYTHON, "-c", ROSLAUNCH_READER, str(path)],
        capture_output=True, text=True, timeout=60, check=True,
    )  # fmt: skip
    nodes = json.loads(out.stdout)["nodes"]
    assert sorted(map(tuple, nodes["BT_NAVIGATOR"]["remaps"])) == sorted(
        (f"follow_path/{t}", f"/rpp/follow_path/{t}")
        for t in ("goal", "cancel", "status", "feedback", "result")
    )


# --- live graphs: import and inspect -------------------------------------------------------

FIB_LIBRARY = """\
format: rosreconf/component-library
version: 1
name: fibonacci
components:
  - name: FIB_SERVER
    abstraction: fib_server
    provides:
      - {action: /fibonacci, type: TYPE}
    ros: {package: demo, executable: server, node: fib_server}
  - name: FIB_CLIENT
    abstraction: fib_client
    requires:
      - {action: /fibonacci, type: TYPE}
    ros: {package: demo, executable: client, node: fib_client}
"""
FIB_SCHEMA = """\
format: rosreconf/interoperability-schema
version: 1
name: fib
skill: compute Fibonacci numbers by a ROS 2 action
environment: anywhere
roles:
  - {name: server, abstraction: fib_server}
  - {name: client, abstraction: fib_client}
edges:
  - {consumer: client, providers: [server]}
nominal: {server: FIB_SERVER, client: FIB_CLIENT}
"""


def _fib_files(tmp_path: Path, typ: str = "test_msgs/action/Fibonacci") -> list[str]:
    (tmp_path / "lib.yaml").write_text(FIB_LIBRARY.replace("TYPE", typ), "utf-8")
    (tmp_path / "task.yaml").write_text(FIB_SCHEMA, "utf-8")
    return ["--library", str(tmp_path / "lib.yaml"), "--schema", str(tmp_path / "task.yaml")]


def _inspect(runner: CliRunner, files: list[str], snapshot: Path) -> tuple[int, dict[str, Any]]:
    result = runner.invoke(app, ["inspect", "--snapshot", str(snapshot), *files, "--json"])
    doc = json.loads(result.stdout)
    schema = json.loads(bundled(Bundle.DATA, "output-inspect.schema.json").read_text("utf-8"))
    jsonschema.validate(doc, schema)
    return result.exit_code, doc


def _findings(doc: dict[str, Any]) -> set[tuple[str, str | None]]:
    return {(f["code"], f["component"]) for f in doc["findings"]}


def test_a_real_ros2_graph_shows_its_action_with_server_client_and_type() -> None:
    live = from_json(SNAPSHOT.read_text("utf-8"), str(SNAPSHOT))
    (action,) = live_actions(live).values()
    assert (action.name, action.type) == ("/fibonacci", "test_msgs/action/Fibonacci")
    assert (action.servers, action.clients) == (("/fib_server",), ("/fib_client",))


def test_import_drafts_action_entries_from_a_real_ros2_graph(
    runner: CliRunner, tmp_path: Path
) -> None:
    out = tmp_path / "draft.yaml"
    result = runner.invoke(app, ["import", "--snapshot", str(SNAPSHOT), "-o", str(out)])
    assert result.exit_code == 0, result.output
    text = out.read_text("utf-8")
    assert "_action" not in text  # the parts are folded into the action
    doc = yaml.safe_load(text)
    by_name = {c["name"]: c for c in doc["components"]}
    entry = {"action": "/fibonacci", "type": "test_msgs/action/Fibonacci"}
    assert by_name["fib_server"]["provides"] == [entry]
    assert by_name["fib_client"]["requires"] == [entry]
    result = runner.invoke(app, ["validate", str(out)])
    assert result.exit_code == 0, result.output


def test_inspect_compares_a_live_action_with_the_configuration(
    runner: CliRunner, tmp_path: Path
) -> None:
    code, doc = _inspect(runner, _fib_files(tmp_path), SNAPSHOT)
    assert code == 0 and doc["conformant"], doc
    code, doc = _inspect(runner, _fib_files(tmp_path, "test_msgs/NestedMessage"), SNAPSHOT)
    assert code == 1 and _findings(doc) == {("wrong-type", "FIB_SERVER")}
    # the server drops its action: no server, and the client's requirement is unmet
    snap = json.loads(SNAPSHOT.read_text("utf-8"))
    for node in snap["nodes"]:
        if node["name"] == "/fib_server":
            node["serves"] = [s for s in node["serves"] if "/_action/" not in s]
            node["publishes"] = [t for t in node["publishes"] if "/_action/" not in t]
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps(snap), "utf-8")
    code, doc = _inspect(runner, _fib_files(tmp_path), broken)
    assert code == 1
    # /fib_server now shows none of FIB_SERVER's endpoints: besides the missing action, a node
    # of that name with nothing of the component's is a name clash (it may be another node)
    assert _findings(doc) == {
        ("missing-action", "FIB_SERVER"),
        ("unmet-requirement", "FIB_CLIENT"),
        ("name-clash", "FIB_SERVER"),
    }


def test_ros1_actionlib_topics_of_stand_ins_make_a_conformant_graph() -> None:
    """A ROS 1 stand-in acts an action out as its five actionlib topics; inspect reads them."""
    library, schema = _load(CASE)
    config = Configuration.of(schema.name, schema.nominal, schema.graph.roles)
    specs = {c: standin_spec(library[c]) for c in config.components}
    nodes = [
        LiveNode(
            f"/{spec['name']}", "http://127.0.0.1:1/", 1,
            tuple(sorted({p["topic"] for p in spec["publish"]})),
            tuple(sorted({s["topic"] for s in spec["subscribe"]})),
        )
        for spec in specs.values()
    ]  # fmt: skip
    types = {
        e["topic"]: e["type"] for s in specs.values() for e in (*s["publish"], *s["subscribe"])
    }
    live = LiveGraph("http://127.0.0.1:11311/", from_json(SNAPSHOT.read_text()).taken_at,
                     tuple(nodes), types)  # fmt: skip
    actions = live_actions(live)
    served = {a: (x.type, x.servers) for a, x in actions.items() if x.servers}
    assert served == {
        "/compute_path_to_pose": ("nav2_msgs/ComputePathToPose", ("/planner_server",)),
        "/rpp/follow_path": ("nav2_msgs/FollowPath", ("/rpp_controller",)),
        "/navigate_to_pose": ("nav2_msgs/NavigateToPose", ("/BT_NAVIGATOR",)),
    }
    # a stand-in calls an action by its own name, as it uses its own topic names (no remaps):
    # unwired, as the controller serves it as /rpp/follow_path; its goals reach nobody
    assert actions["/follow_path"].clients == ("/BT_NAVIGATOR",)
    unwired = compare(config, library, schema, live)
    assert [(f.code, f.component, f.live_name) for f in unwired.findings] == [
        ("unwired", "BT_NAVIGATOR", "/follow_path")
    ]
    said = unwired.findings[0].message  # one rule per actionlib topic: a name's moves none
    for part in ("goal", "cancel", "status", "feedback", "result"):
        assert f"-r follow_path/{part}:=/rpp/follow_path/{part}" in said
    # wired as its launch file remaps it (roslaunch remaps the action's namespace)
    nodes = [
        replace(n, publishes=tuple(t.replace("/follow_path/", "/rpp/follow_path/")
                                   for t in n.publishes),
                subscribes=tuple(t.replace("/follow_path/", "/rpp/follow_path/")
                                 for t in n.subscribes))
        if n.name == "/BT_NAVIGATOR" else n
        for n in nodes
    ]  # fmt: skip
    live = replace(live, nodes=tuple(nodes))
    assert compare(config, library, schema, live).ok
    # the navigator stops sending goals to the controller: it is no longer its client
    quiet = [
        n if n.name != "/BT_NAVIGATOR" else LiveNode(n.name, n.uri, n.pid, tuple(
            t for t in n.publishes if "follow_path" not in t), n.subscribes)
        for n in nodes
    ]  # fmt: skip
    result = compare(config, library, schema, LiveGraph(live.master_uri, live.taken_at,
                                                         tuple(quiet), types))  # fmt: skip
    assert {(f.code, f.component) for f in result.findings} == {
        ("missing-action-client", "BT_NAVIGATOR")
    }


@pytest.mark.ros
def test_ros1_stand_ins_act_out_actions_on_a_real_master(
    ros_master: Any, standin: Any, runner: CliRunner, tmp_path: Path
) -> None:
    """Real roscore and rospy stand-ins: the actionlib topics carry the nominal's actions."""
    for c in ("PLANNER_NAVFN", "CONTROLLER_RPP", "BT_NAVIGATOR"):
        library, _ = _load(CASE)
        standin(standin_spec(library[c]))
    files = ["--library", str(CASE / "lib.yaml"), "--schema", str(CASE / "task.yaml")]
    result = runner.invoke(app, ["inspect", "--master", ros_master.uri, *files, "--json"])
    doc = json.loads(result.stdout)
    # the three action nodes run; every action of the nominal is served and called, but the
    # navigator's stand-in, started without remappings, sends its follow_path goals to its own
    # /follow_path while the controller serves /rpp/follow_path: unwired
    acting = [(f["code"], f["live_name"]) for f in doc["findings"]
              if "action" in f["code"] or f["code"] == "unwired"]  # fmt: skip
    assert acting == [("unwired", "/follow_path")], doc["findings"]
    codes = {f["code"] for f in doc["findings"]}
    assert codes <= {"missing-node", "unmet-requirement", "missing-topic", "unwired"}, doc
    draft = tmp_path / "draft.yaml"
    result = runner.invoke(app, ["import", "--master", ros_master.uri, "-o", str(draft)])
    assert result.exit_code == 0, result.output
    comps = {c["name"]: c for c in yaml.safe_load(draft.read_text("utf-8"))["components"]}
    assert {"action": "/rpp/follow_path", "type": "nav2_msgs/action/FollowPath"} in comps[
        "rpp_controller"
    ]["provides"]


# --- real rclpy nodes ----------------------------------------------------------------------


def test_real_rclpy_action_nodes_are_imported_and_inspected(
    runner: CliRunner, domain_id: int, tmp_path: Path
) -> None:
    if not ROS2_PYTHON.exists():
        pytest.fail(f"{ROS2_PYTHON} is missing: run make ros2-venvs (make test does)")
    env = {**os.environ, "ROS_DOMAIN_ID": str(domain_id), "ROS_LOG_DIR": str(tmp_path)}
    env.pop("CYCLONEDDS_URI", None)
    argv = [str(ROS2_PYTHON), str(HERE / "ros2_action_nodes.py"), "/fibonacci",
            "server=fib_server", "client=fib_client"]  # fmt: skip
    nodes = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, text=True)
    snapshot = tmp_path / "live.json"
    try:
        assert nodes.stdout is not None
        # a node that never gets ready must fail the test, never hang the suite on a read
        up, _, _ = select.select([nodes.stdout], [], [], 60.0)
        assert up and nodes.stdout.readline().strip() == "ready", "action nodes not ready in 60 s"
        for _ in range(5):  # discovery may not have met both nodes at the first read
            taken = subprocess.run(
                [sys.executable, "-m", "rosreconf", "snapshot", "--ros2", "--domain",
                 str(domain_id), "-o", str(snapshot)],
                env=env, capture_output=True, text=True, timeout=120,
            )  # fmt: skip
            assert taken.returncode == 0, taken.stderr
            found = live_actions(from_json(snapshot.read_text("utf-8"))).values()
            if any(a.servers and a.clients for a in found):
                break
    finally:
        nodes.kill()
        nodes.wait(timeout=30)
    live = from_json(snapshot.read_text("utf-8"))
    (action,) = live_actions(live).values()
    assert (action.type, action.servers, action.clients) == (
        "test_msgs/action/Fibonacci",
        ("/fib_server",),
        ("/fib_client",),
    )
    code, doc = _inspect(runner, _fib_files(tmp_path), snapshot)
    assert code == 0, doc
