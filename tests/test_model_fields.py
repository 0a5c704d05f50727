"""The format can say a node's own ROS name, its arguments and an optional edge."""

from __future__ import annotations

from pathlib import Path

from rosreconf.formats.loader import load_paths

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
