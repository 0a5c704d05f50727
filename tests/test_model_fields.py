"""Node names, args, optional edges and TODO marks: read, then used by import, launch, validate."""

from __future__ import annotations

import json
import shlex
import xml.etree.ElementTree as ET
from dataclasses import replace
from datetime import UTC, datetime
from importlib.resources import as_file
from pathlib import Path

import pytest
import xmlschema
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import RosreconfError
from rosreconf.formats.loader import load_bundled, load_paths
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import node_live_name
from rosreconf.procs import run_program
from rosreconf.resources import Bundle, bundled
from rosreconf.ros.importer import draft_library, is_anonymous
from rosreconf.ros.launchfiles import RosVersion, launch_file
from rosreconf.ros.livegraph import LiveGraph, LiveNode, to_json

LIBRARY = """\
format: rosreconf/component-library
version: 1
name: fields
components:
  - name: scan_listener_2
    abstraction: listener
    requires: [{topic: scan, type: sensor_msgs/LaserScan}]
    ros:
      package: rospy_tutorials
      executable: listener
      node: scan_listener
      namespace: /robot
      args: [pub, -r, "1", /chatter]
  - name: laser
    abstraction: sensor
    provides: [{topic: scan, type: sensor_msgs/LaserScan}]
"""

SCHEMA = """\
format: rosreconf/interoperability-schema
version: 1
name: s
skill: listen
environment: lab
roles:
  - {name: ear, abstraction: listener}
  - {name: eye, abstraction: sensor}
edges:
  - {consumer: ear, providers: [eye], optional: true}
  - {consumer: eye, providers: [ear]}
"""


def test_node_name_namespace_and_args_are_read(tmp_path: Path) -> None:
    (tmp_path / "lib.yaml").write_text(LIBRARY, encoding="utf-8")
    library = load_paths([tmp_path / "lib.yaml"]).library
    comp = library["scan_listener_2"]
    assert comp.node_name == "scan_listener"
    assert comp.namespace == "/robot"
    assert comp.launch is not None and comp.launch.args == ("pub", "-r", "1", "/chatter")
    laser = library["laser"]
    assert laser.node_name == "laser" and laser.namespace is None


def test_optional_edge_is_read_and_plain_edges_stay_required(tmp_path: Path) -> None:
    (tmp_path / "s.yaml").write_text(SCHEMA, encoding="utf-8")
    schema = load_paths([tmp_path / "s.yaml"]).schemas[0]
    assert [(e.consumer, e.provider, e.optional) for e in schema.graph.edges] == [
        ("ear", "eye", True),
        ("eye", "ear", False),
    ]


# --- import: node names, anonymous names, TODO marks, $schema --------------------------------

WHEN = datetime(2026, 1, 1, tzinfo=UTC)
LIVE = LiveGraph(
    "http://127.0.0.1:11311/",
    WHEN,
    (
        LiveNode("/robot/scan_listener", "http://x:1/", 1, (), ("/scan",)),
        LiveNode("/scan_listener", "http://x:2/", 2, (), ("/scan",)),
        LiveNode("/laser", "http://x:3/", 3, ("/scan",)),
        LiveNode("/rostopic_4711_1700000000000", "http://x:4/", 4, ("/chatter",)),
    ),
    {"/scan": "sensor_msgs/LaserScan", "/chatter": "std_msgs/String"},
)


def _draft(tmp_path: Path) -> tuple[Path, ComponentLibrary]:
    path = tmp_path / "draft.yaml"
    path.write_text(draft_library(LIVE, "robot"), encoding="utf-8")
    return path, load_paths([path]).library


def test_import_keeps_each_live_node_name(tmp_path: Path) -> None:
    """Every drafted component maps back to the live node it came from (was: /scan_listener_2)."""
    _, library = _draft(tmp_path)
    by_live = {node_live_name(c): c.name for c in library}
    assert set(by_live) == {n.name for n in LIVE.nodes}
    assert library[by_live["/scan_listener"]].node_name == "scan_listener"


def test_import_says_anonymous_names_change(tmp_path: Path, runner: CliRunner) -> None:
    text = draft_library(LIVE, "robot")
    assert "/rostopic_4711_1700000000000 is an anonymous name" in text
    snap = tmp_path / "snap.json"
    snap.write_text(to_json(LIVE), encoding="utf-8")
    result = runner.invoke(app, ["import", "--snapshot", str(snap), "-o", str(tmp_path / "l.yaml")])
    assert result.exit_code == 0, result.stderr
    assert "/rostopic_4711_1700000000000 has an anonymous name" in result.stderr
    assert is_anonymous("/rostopic_4711_1700000000000") and not is_anonymous("/scan_listener")


def test_draft_schema_line_points_at_an_existing_file(tmp_path: Path) -> None:
    first = draft_library(LIVE, "robot").splitlines()[0]
    uri = first.split("$schema=", 1)[1]
    assert uri.startswith("file://")
    assert Path(uri.removeprefix("file://")).is_file()


def test_strict_validate_fails_on_todo_marks(tmp_path: Path, runner: CliRunner) -> None:
    path, _ = _draft(tmp_path)
    loose = runner.invoke(app, ["validate", str(path)])
    assert loose.exit_code == 0, loose.stdout
    assert "unfinished draft: a TODO mark is left" in loose.stdout
    strict = runner.invoke(app, ["validate", "--strict", str(path)])
    assert strict.exit_code == 1, strict.stdout
    first_todo = next(
        i for i, line in enumerate(path.read_text().splitlines(), 1) if "TODO" in line
    )
    assert f"draft.yaml:{first_todo}:" in strict.stdout


def test_finished_files_have_no_todo_warning(runner: CliRunner, tmp_path: Path) -> None:
    (tmp_path / "lib.yaml").write_text(LIBRARY, encoding="utf-8")
    result = runner.invoke(app, ["validate", "--strict", str(tmp_path / "lib.yaml")])
    assert result.exit_code == 0, result.stdout


# --- launch files: node name, args ---------------------------------------------------------


def _nav() -> tuple[ComponentLibrary, InteroperabilitySchema, Configuration]:
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "map_navigation")
    mapping = {**schema.nominal, "lidar": "SICK_TIM781"}
    return loaded.library, schema, Configuration.of(schema.name, mapping, schema.graph.roles)


def test_launch_uses_node_name_and_args() -> None:
    library, schema, config = _nav()
    for version in RosVersion:
        root = ET.fromstring(launch_file(library, schema, config, version).text)
        (sick,) = [n for n in root.iter("node") if n.get("pkg") == "sick_scan"]
        assert sick.get("name") == "sick_tim781"
        assert sick.get("args") == "scanner_type:=sick_tim_7xx"
        (maps,) = [n for n in root.iter("node") if n.get("pkg") == "map_server"]
        assert maps.get("args") == "office.yaml"
    with as_file(bundled(Bundle.DATA, "ros2-launch.xsd")) as xsd:
        xmlschema.XMLSchema(str(xsd)).validate(
            launch_file(library, schema, config, RosVersion.ROS2).text
        )


def test_launch_quotes_args_like_a_shell() -> None:
    library, schema, config = _nav()
    sick = library["SICK_TIM781"]
    assert sick.launch is not None
    spaced = replace(sick, launch=replace(sick.launch, args=("a b", "it's")))
    lib = ComponentLibrary("l", tuple(spaced if c.name == sick.name else c for c in library))
    root = ET.fromstring(launch_file(lib, schema, config, RosVersion.ROS1).text)
    (node,) = [n for n in root.iter("node") if n.get("pkg") == "sick_scan"]
    assert shlex.split(str(node.get("args"))) == ["a b", "it's"]


def test_launch_refuses_two_components_as_one_node() -> None:
    library, schema, config = _nav()
    lidar = library["SICK_TIM781"]
    assert lidar.launch is not None
    twin = replace(lidar, launch=replace(lidar.launch, node="KOBUKI_BASE"))
    lib = ComponentLibrary("l", tuple(twin if c.name == lidar.name else c for c in library))
    with pytest.raises(RosreconfError, match="would both run as the ROS node /KOBUKI_BASE"):
        launch_file(lib, schema, config, RosVersion.ROS1)


@pytest.mark.ros
def test_roslaunch_reads_node_name_and_args(tmp_path: Path) -> None:
    library, schema, config = _nav()
    path = tmp_path / "nav.launch"
    path.write_text(launch_file(library, schema, config, RosVersion.ROS1).text)
    reader = (
        "import json, sys\n"
        "import roslaunch.config, roslaunch.xmlloader\n"
        "c = roslaunch.config.ROSLaunchConfig()\n"
        "roslaunch.xmlloader.XmlLoader(resolve_anon=False).load(sys.argv[1], c, verbose=False)\n"
        "print(json.dumps({n.name: n.args for n in c.nodes}))\n"
    )
    result = run_program(["/usr/bin/python3", "-c", reader, str(path)], timeout=60).check()
    read = json.loads(result.stdout)
    assert read["sick_tim781"] == "scanner_type:=sick_tim_7xx"
    assert read["NAV_MAP_SERVER"] == "office.yaml"


# --- one label, two types ---------------------------------------------------------------------

CAMERAS = """\
format: rosreconf/component-library
version: 1
name: cameras
components:
  - name: RAW_CAMERA
    abstraction: camera
    provides: [{topic: image, type: sensor_msgs/Image}]
  - name: COMPRESSED_CAMERA
    abstraction: camera
    provides: [{topic: image, type: sensor_msgs/CompressedImage}]
"""


def test_alternatives_may_share_a_label_with_two_types(tmp_path: Path, runner: CliRunner) -> None:
    """Was refused outright; now a warning, and no configuration chooses both."""
    path = tmp_path / "cameras.yaml"
    path.write_text(CAMERAS, encoding="utf-8")
    loose = runner.invoke(app, ["validate", str(path)])
    assert loose.exit_code == 0, loose.stdout
    assert "warning: topic 'image' has type sensor_msgs/CompressedImage" in loose.stdout
    assert runner.invoke(app, ["validate", "--strict", str(path)]).exit_code == 1
