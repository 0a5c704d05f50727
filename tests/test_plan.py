"""Tests for rosreconf plan / render-pddl and rosreconf.planning.replan on the bundled example."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml
from conftest import fake
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.configfile import read_configurations
from rosreconf.formats.loader import load_bundled
from rosreconf.planning.planners import PLANNERS, FastDownward, TaskFiles
from rosreconf.planning.replan import unaffected
from rosreconf.resources import Bundle, bundled
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.running import running_configuration
from rosreconf.solve.solver import Objective, optimise


def by_name(doc: dict[str, object]) -> dict[str, dict[str, object]]:
    schemas = doc["schemas"]
    assert isinstance(schemas, list)
    return {s["name"]: s for s in schemas}


@pytest.mark.planner
def test_nsm3_failing_moves_repositioning_to_the_dc_arm_and_ends_disc_loading(
    runner: CliRunner,
) -> None:
    result = runner.invoke(app, ["plan", "--fail", "NSM3", "--json"])
    assert result.exit_code == 1, result.stderr  # one task is impossible: exit 1
    schemas = by_name(json.loads(result.stdout))
    moved = schemas["object_repositioning"]
    assert moved["status"] == "solved"
    new = moved["configurations"][0]["assignment"]  # type: ignore[index]
    assert [new[r] for r in ("base_joint", "elbow_joint", "positioning")] == [
        "NDC1",
        "NDC3",
        "NFB11",
    ]
    # 9 roles change and the kept reasoner NREA restarts: it called the servo arm's
    # /arm_servo/<joint>/servo_command, and ROS fixes a node's remappings when it starts, so
    # it must restart to call the DC arm's /arm_dc/<joint>/servo_command (the wiring model)
    assert moved["fewest_changes"] == 10
    kinds = {c["role"]: c["kind"] for c in moved["changes"]}  # type: ignore[attr-defined]
    assert kinds["reasoner"] == "restart" and kinds["camera"] == "keep"
    assert sum(k != "keep" for k in kinds.values()) == 10
    text = " ".join(moved["explanation"])  # type: ignore[arg-type]
    assert "NREA (reasoner) restarts to be rewired" in text
    assert "10 part(s) change (9 replaced or started, 1 restarted to be rewired)" in text
    assert (
        "positioning: NFB21 cannot stay (it needs elbow/digital_servo_command, which only NSM3 "
        "provides and NSM3 failed" in text
    )
    assert (
        "base_joint: NSM1 cannot stay (NFB11, NFB12, NFB13 and NFB14 need base/dc_servo_command, "
        "which NSM1 does not provide); NDC1 takes over." in text
    )
    gone = schemas["disc_loading"]
    assert gone["status"] == "unsolvable-proven" and gone["configurations"] == []
    assert "NSM3 has failed" in str(gone["why_not"])
    assert "Disc Loading is no longer possible" in " ".join(gone["explanation"])  # type: ignore[arg-type]


@pytest.mark.planner
def test_nca1_failing_changes_only_camera_sensor_and_perception(
    runner: CliRunner, tmp_path: Path
) -> None:
    only = ["--only", "object_repositioning", "--only", "disc_loading"]
    result = runner.invoke(app, ["plan", "--fail", "NCA1", *only, "--json"])
    assert result.exit_code == 0, result.stderr
    # NCO2 serves gripper_feeling at /gripper2/feeling where NCO1 served /gripper1/feeling:
    # every kept consumer of it restarts to be rewired (its remappings are fixed at start)
    library = yaml.safe_load(bundled(Bundle.LIBRARIES, "robot_arms.yaml").read_text("utf-8"))
    feeling = {
        c["name"]
        for c in library["components"]
        if any(r.get("service") == "gripper_feeling" for r in c.get("requires", []))
    }
    for s in by_name(json.loads(result.stdout)).values():
        kinds = {c["role"]: c["kind"] for c in s["changes"]}  # type: ignore[attr-defined]
        replaced = {r for r, k in kinds.items() if k == "replace"}
        assert replaced == {"camera", "gripper_sensor", "perception"}
        assignment = s["configurations"][0]["assignment"]  # type: ignore[index]
        restarted = {r for r, k in kinds.items() if k == "restart"}
        assert restarted == {r for r, c in assignment.items() if c in feeling} - replaced
        assert restarted and s["fewest_changes"] == 3 + len(restarted)
        assert assignment["camera"] == "NCA2"
    saved = tmp_path / "now.json"
    saved.write_text(result.stdout, encoding="utf-8")
    assert read_configurations(saved)["disc_loading"]["perception"] == "NVP2"
    again = runner.invoke(app, ["plan", "--fail", "NCA1", *only, "--current", str(saved)])
    assert again.exit_code == 0, again.stderr
    assert "Nothing has to change." in again.stdout


@pytest.mark.planner
def test_text_output_lists_steps_configuration_change_and_why(runner: CliRunner) -> None:
    result = runner.invoke(app, ["plan", "--fail", "NSM3", "--only", "object_repositioning"])
    assert result.exit_code == 0, result.stderr
    for part in ("1. stop NSM1, start NDC1 as base_joint", "new configuration:", "change:", "why:"):
        assert part in result.stdout
    # One connection per joint, as in the paper's Figure 8.
    for joint in ("base", "shoulder", "elbow", "wrist", "gripper"):
        step = "connect NFB11 (positioning) to NDC"
        assert f"({joint}_joint) for {joint}/dc_servo_command" in result.stdout
        assert step in result.stdout


class FakeUnknown(FastDownward):
    """Fake planner: a Fast Downward-shaped script that plans actions no domain declares."""

    def __init__(self, search: str = "fake") -> None:
        super().__init__("fake")

    def command(self, files: TaskFiles, *, timeout: float, memory_limit_mb: int) -> list[str]:
        plan = ["--plan-file", str(files.plan), str(files.domain), str(files.problem)]
        return fake("unknown_actions.py", *plan)


def test_a_plan_with_an_unknown_action_exits_3(
    runner: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(PLANNERS, "fake", FakeUnknown)
    args = ["plan", "--fail", "NSM3", "--only", "object_repositioning", "--planner", "fake"]
    result = runner.invoke(app, args)
    assert result.exit_code == 3
    assert "plan names unknown action (teleport robot_1 nowhere)" in result.stderr


@pytest.mark.parametrize(
    "args",
    [
        ["plan"],
        ["plan", "--fail", "NOPE"],
        ["plan", "--fail", "NSM3", "--planner", "bogus"],
        ["plan", "--fail", "NSM3", "--objective", "cost"],
    ],
)
def test_usage_errors_exit_2(runner: CliRunner, args: list[str]) -> None:
    assert runner.invoke(app, args).exit_code == 2


def test_render_pddl_writes_every_schema(runner: CliRunner, tmp_path: Path) -> None:
    result = runner.invoke(app, ["render-pddl", "--fail", "NSM3", "-o", str(tmp_path)])
    assert result.exit_code == 0, result.stderr
    for name in ("disc_loading", "object_repositioning", "indoor_navigation"):
        assert (tmp_path / name / "domain.pddl").read_text().startswith(";; rosreconf")
        assert "(failed nsm3)" in (tmp_path / name / "problem.pddl").read_text() or (
            name == "indoor_navigation"
        )
    assert not list(tmp_path.rglob("*.tmp"))


@pytest.mark.planner
def test_a_schema_without_a_failed_component_keeps_running_and_runs_no_planner(
    runner: CliRunner,
) -> None:
    result = runner.invoke(app, ["plan", "--fail", "NSM3", "--json"])
    schemas = by_name(json.loads(result.stdout))
    kept = schemas["indoor_navigation"]
    assert kept["status"] == "solved" and kept["steps"] == [] and kept["actions"] == []
    assert kept["elapsed"] is None and kept["cost"] is None  # no planner ran
    assert "NSM3 not among them" in str(kept["unaffected"])
    assert kept["configurations"] == [{"assignment": kept["current"]}]
    assert schemas["object_repositioning"]["unaffected"] is None  # re-planned
    assert schemas["object_repositioning"]["elapsed"] is not None


def test_unaffected_agrees_with_the_proven_fewest_changes() -> None:
    """Where ``unaffected`` skips the planner, the optimum proves zero changes are needed;
    where a running component failed, it never skips."""
    loaded = load_bundled()
    library = loaded.library
    for schema in loaded.schemas:
        running = running_configuration(library, schema)
        assert running is not None
        current = running.mapping
        for failed in [frozenset({c.name}) for c in library]:
            inst = compile_instance(library, schema, failed)
            best = optimise(inst, Objective(current)).configuration
            kept = unaffected(library, schema, failed, current)
            if failed & set(current.values()):
                assert kept is None
            elif kept is not None:
                assert best is not None and Objective(current).score(inst, best)[0] == 0
                assert kept[0] == best


ROLE_NAMED_LIKE_COMPONENT_LIBRARY = """\
format: rosreconf/component-library
version: 1
name: named_alike
components:
  - name: camera
    abstraction: camera
    provides: [{topic: image, type: sensor_msgs/Image}]
  - name: Viewer
    abstraction: viewer
    requires: [{topic: image, type: sensor_msgs/Image}]
  - name: viewer2
    abstraction: viewer
    requires: [{topic: image, type: sensor_msgs/Image}]
"""
ROLE_NAMED_LIKE_COMPONENT_SCHEMA = """\
format: rosreconf/interoperability-schema
version: 1
name: look
skill: look at the image
environment: anywhere
roles:
  - {name: camera, abstraction: camera}
  - {name: viewer, abstraction: viewer}
edges:
  - {consumer: viewer, providers: [camera]}
nominal: {camera: camera, viewer: Viewer}
"""


@pytest.mark.planner
def test_a_role_named_like_its_only_component_is_planned(runner: CliRunner, tmp_path: Path) -> None:
    """Issue 22: validate passed it, plan refused it ("both become the PDDL name") with no JSON.

    Role ``camera`` is filled by component ``camera`` and role ``viewer`` by ``Viewer`` (one
    PDDL name apart from case): plan must still work and print one JSON document.
    """
    lib, sch = tmp_path / "lib.yaml", tmp_path / "task.yaml"
    lib.write_text(ROLE_NAMED_LIKE_COMPONENT_LIBRARY, encoding="utf-8")
    sch.write_text(ROLE_NAMED_LIKE_COMPONENT_SCHEMA, encoding="utf-8")
    files = ["-l", str(lib), "-s", str(sch)]
    assert runner.invoke(app, ["validate", str(lib), str(sch)]).exit_code == 0
    result = runner.invoke(app, ["plan", *files, "--fail", "Viewer", "--json"])
    assert result.exit_code == 0, result.stderr
    (look,) = json.loads(result.stdout)["schemas"]
    assert look["status"] == "solved"
    assert look["configurations"][0]["assignment"] == {"camera": "camera", "viewer": "viewer2"}
    assert look["fewest_changes"] == 1
    pddl = runner.invoke(app, ["render-pddl", *files, "-o", str(tmp_path / "pddl")])
    assert pddl.exit_code == 0, pddl.stderr
