"""``analyse``'s context thresholds, against counts worked out by hand on a small library.

Four sensors can fill one role (a driver fills the other):

- camera_day: dark = false
- sonar: 2 <= depth <= 10
- camera_night: dark = true and depth <= 5
- lidar: weather = clear and depth <= 2

By depth, with dark and weather unconstrained (their conditions taken to hold), the usable
sensors are: below 2, day, night and lidar (3); at 2 exactly, all four (4); above 2 up to 5,
day, sonar, night (3); above 5 up to 10, day and sonar (2); above 10, day alone (1).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.resources import Bundle, bundled

LIBRARY = """\
format: rosreconf/component-library
version: 1
name: sensing
context:
  - {name: depth, topic: /depth, type: std_msgs/msg/Float64, field: data}
  - {name: dark, topic: /dark, type: std_msgs/msg/Bool, field: data}
  - {name: weather, topic: /weather, type: std_msgs/msg/String, field: data}
components:
  - name: camera_day
    abstraction: sensor
    when: {dark: {equals: false}}
    provides: [{topic: reading, type: std_msgs/msg/Float64}]
  - name: sonar
    abstraction: sensor
    when: {depth: {at_least: 2, at_most: 10}}
    provides: [{topic: reading, type: std_msgs/msg/Float64}]
  - name: camera_night
    abstraction: sensor
    when: {dark: {equals: true}, depth: {at_most: 5}}
    provides: [{topic: reading, type: std_msgs/msg/Float64}]
  - name: lidar
    abstraction: sensor
    when: {weather: {equals: clear}, depth: {at_most: 2}}
    provides: [{topic: reading, type: std_msgs/msg/Float64}]
  - name: driver
    abstraction: driver
    requires: [{topic: reading, type: std_msgs/msg/Float64}]
"""

SCHEMA = """\
format: rosreconf/interoperability-schema
version: 1
name: sense
skill: Sense and drive.
environment: Anywhere.
roles:
  - {name: sensor, abstraction: sensor}
  - {name: driver, abstraction: driver}
edges:
  - {consumer: driver, providers: [sensor]}
"""


@pytest.fixture
def files(tmp_path: Path) -> list[str]:
    (tmp_path / "lib.yaml").write_text(LIBRARY, encoding="utf-8")
    (tmp_path / "schema.yaml").write_text(SCHEMA, encoding="utf-8")
    return ["-l", str(tmp_path / "lib.yaml"), "-s", str(tmp_path / "schema.yaml")]


def _analyse(runner: CliRunner, files: list[str], *args: str) -> dict[str, Any]:
    result = runner.invoke(app, ["analyse", "--json", "--ignore-context", *args, *files])
    assert result.exit_code in (0, 1), result.stderr
    doc: dict[str, Any] = json.loads(result.stdout)
    schema = json.loads(bundled(Bundle.DATA, "output-analyse.schema.json").read_text("utf-8"))
    jsonschema.validate(doc, schema)
    return doc


def _table(doc: dict[str, Any], variable: str) -> list[tuple[str, int]]:
    (t,) = [t for t in doc["context"]["thresholds"] if t["variable"] == variable]
    rows = t["intervals"] or t["values"]
    return [(r["text"], r["configurations"]) for r in rows]


def test_depth_table_unconstrained(runner: CliRunner, files: list[str]) -> None:
    doc = _analyse(runner, files)
    assert _table(doc, "depth") == [
        ("depth < 2.0", 3),
        ("depth = 2.0", 4),
        ("2.0 < depth <= 5.0", 3),
        ("5.0 < depth <= 10.0", 2),
        ("depth > 10.0", 1),
    ]
    (depth,) = [t for t in doc["context"]["thresholds"] if t["variable"] == "depth"]
    assert depth["intervals"][0] == {
        "from": None,
        "from_included": False,
        "to": 2.0,
        "to_included": False,
        "text": "depth < 2.0",
        "configurations": 3,
    }
    assert _table(doc, "dark") == [("dark = true", 3), ("dark = false", 3)]
    assert _table(doc, "weather") == [("weather = clear", 4), ("weather = any other value", 3)]


def test_depth_table_with_dark_given(runner: CliRunner, files: list[str]) -> None:
    doc = _analyse(runner, files, "--context", "dark=true")
    (depth,) = [t for t in doc["context"]["thresholds"] if t["variable"] == "depth"]
    assert depth["given"] == {"dark": True}
    # camera_day is out: each count above, less one where it counted
    assert _table(doc, "depth") == [
        ("depth < 2.0", 2),
        ("depth = 2.0", 3),
        ("2.0 < depth <= 5.0", 2),
        ("5.0 < depth <= 10.0", 1),
        ("depth > 10.0", 0),
    ]
    assert doc["schemas"][0]["valid"] == 3  # night, sonar, lidar: depth and weather ignored


def test_the_text_table(runner: CliRunner, files: list[str]) -> None:
    result = runner.invoke(app, ["analyse", "--ignore-context", *files])
    assert result.exit_code == 0
    assert (
        "  sense, by depth:\n"
        "    depth < 2.0          3\n"
        "    depth = 2.0          4\n"
        "    2.0 < depth <= 5.0   3\n"
        "    5.0 < depth <= 10.0  2\n"
        "    depth > 10.0         1\n"
    ) in result.stdout


def test_booleans_and_strings_at_design_time(runner: CliRunner, files: list[str]) -> None:
    args = ["--context", "depth=2", "--context", "dark=false", "--context", "weather=clear"]
    result = runner.invoke(app, ["enumerate", "--json", *args, *files])
    doc = json.loads(result.stdout)
    chosen = sorted(c["assignment"]["sensor"] for c in doc["schemas"][0]["configurations"])
    assert chosen == ["camera_day", "lidar", "sonar"]
    assert doc["context"]["ruled_out"] == [
        {
            "component": "camera_night",
            "conditions": ["dark = true"],
            "reason": "camera_night needs dark = true; it is false",
        }
    ]
    args[-1] = "weather=fog"
    result = runner.invoke(app, ["enumerate", *args, *files])
    assert "ruled out: lidar needs weather = clear; it is fog" in result.stdout
    result = runner.invoke(app, ["enumerate", "--ignore-context", "--context", "dark=yes", *files])
    assert result.exit_code == 2
    assert (
        result.stderr
        == "rosreconf: error: --context dark=yes: dark is a boolean: write true or false\n"
    )
    args = ["--context", "depth=12", "--context", "dark=true", "--context", "weather=fog"]
    result = runner.invoke(app, ["enumerate", *args, *files])
    assert result.exit_code == 1
    assert (
        "ruled out: camera_night needs dark = true (it is true) and depth <= 5.0 (it is 12.0)"
        not in result.stdout
    )
    assert "ruled out: camera_night needs depth <= 5.0; it is 12.0" in result.stdout
    assert "ruled out: lidar needs weather = clear (it is fog) and depth <= 2.0 (it is 12.0)" in (
        result.stdout
    )


def test_fail_components_stay_failed_across_the_table(runner: CliRunner) -> None:
    """spiral_high both failed and ruled out: failed at every visibility of the table."""
    example = Path(__file__).resolve().parent.parent / "docs" / "examples" / "suave"
    files = ["-l", str(example / "library.yaml"), "-s", str(example / "schema.yaml")]
    doc = _analyse(runner, files, "--fail", "spiral_high", "--context", "visibility=1.0")
    # battery unconstrained: two controllers per search path
    assert _table(doc, "visibility") == [
        ("visibility < 1.25", 0),
        ("1.25 <= visibility < 2.25", 2),
        ("visibility >= 2.25", 4),
    ]
    assert doc["failed"] == ["spiral_high", "spiral_medium", "spiral_low"]
    assert doc["schemas"][0]["valid"] == 0
