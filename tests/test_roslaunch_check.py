"""Check that the real roslaunch parser validates launch files naming packages not installed."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path
from typing import Any

import pytest
import ros_harness

CHECK = Path(__file__).with_name("roslaunch_check.py")

GOOD = """<launch>
  <group ns="arm">
    <node pkg="robot_arm_driver" type="dc_servo_node" name="NDC1">
      <param name="gain" value="2.5"/>
      <remap from="servo_command" to="/dc_servo_command"/>
    </node>
  </group>
  <node pkg="robot_vision" type="camera" name="NCA1"/>
</launch>
"""
BROKEN = {
    "mismatched": ('<launch><node pkg="p" type="t" name="n"></launch>', "mismatched tag"),
    "no_type": ('<launch><node pkg="p" name="n"/></launch>', "missing required attribute"),
    "twice": (
        '<launch><node pkg="p" type="t" name="n"/><node pkg="q" type="t" name="n"/></launch>',
        "multiple nodes named",
    ),
    "ns_in_name": ('<launch><node pkg="p" type="t" name="a/b"/></launch>', "namespace"),
    "find": ('<launch><include file="$(find nopkg)/x.launch"/></launch>', "package not found"),
}

pytestmark = pytest.mark.ros  # conftest.require_tool: fails, never skips, without ROS


def run_check(tmp_path: Path, files: dict[str, str]) -> tuple[int, list[dict[str, Any]]]:
    """Write ``files`` and run the checker on them with the system Python."""
    paths = []
    for name, text in files.items():
        (tmp_path / f"{name}.launch").write_text(text)
        paths.append(str(tmp_path / f"{name}.launch"))
    env = ros_harness.ros_env("http://127.0.0.1:1/", tmp_path / "home")
    cmd = [ros_harness.SYSTEM_PYTHON, str(CHECK), *paths]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=30, check=False)
    return done.returncode, json.loads(done.stdout)["files"]


def test_good_file_of_missing_packages_loads(tmp_path: Path) -> None:
    code, (report,) = run_check(tmp_path, {"good": GOOD})
    assert code == 0 and report["error"] is None and report["warnings"] == []
    assert [(n["name"], n["package"], n["type"]) for n in report["nodes"]] == [
        ("/arm/NDC1", "robot_arm_driver", "dc_servo_node"),
        ("/NCA1", "robot_vision", "camera"),
    ]
    assert report["nodes"][0]["remap"] == [["servo_command", "/dc_servo_command"]]
    assert report["params"] == {"/arm/NDC1/gain": 2.5}
    assert not (tmp_path / "home").exists()  # the parser writes no logs


@pytest.mark.parametrize("case", sorted(BROKEN))
def test_broken_file_is_refused(tmp_path: Path, case: str) -> None:
    text, expected = BROKEN[case]
    code, (report,) = run_check(tmp_path, {case: text})
    assert code == 1 and expected in report["error"]


def test_unknown_tags_and_attributes_are_warnings(tmp_path: Path) -> None:
    text = '<launch><nod pkg="x"/><node pkg="p" type="t" name="n" colour="red"/></launch>'
    code, (report,) = run_check(tmp_path, {"warn": text})
    assert code == 1 and report["error"] is None
    assert report["warnings"] == [
        "unrecognized tag nod",
        f"[{tmp_path}/warn.launch] unknown <node> attribute 'colour'",
    ]


def test_roslaunch_nodes_lists_nodes_of_missing_packages(tmp_path: Path) -> None:
    (tmp_path / "good.launch").write_text(GOOD)
    env = ros_harness.ros_env("http://127.0.0.1:1/", tmp_path / "home")
    cmd = ["roslaunch", "--nodes", str(tmp_path / "good.launch")]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=30, check=False)
    assert (done.returncode, done.stdout.split()) == (0, ["/arm/NDC1", "/NCA1"])
