"""``plan --switch-to``: a task switch at design time on the paper's example (issue 46).

The robot runs Object Repositioning on the DC arm (the first configuration ``enumerate``
lists) and switches to Disc Loading, which the DC arm may not serve (Table 1's In Schema
column). The number of changes is checked against a brute-force minimum computed here on
its own: every valid Disc Loading configuration from ``enumerate --json``, each counted by
the simple rule below (docs/pddl.md, "Task switches"), reading the wiring from the
ROS-graphs ``enumerate`` prints and the served names from the library file.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import yaml
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.resources import Bundle, bundled

pytestmark = pytest.mark.planner

LIBRARY = Path(__file__).resolve().parent.parent / "libraries" / "robot_arms.yaml"


def enumerate_json(runner: CliRunner, schema: str, *fail: str) -> dict[str, Any]:
    """Return ``enumerate --json`` of one schema: every valid configuration, none left out."""
    args = ["enumerate", "--only", schema, "--json", "--limit", "100000"]
    for name in fail:
        args += ["--fail", name]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.stderr
    doc: dict[str, Any] = json.loads(result.stdout)
    return doc["schemas"][0]  # type: ignore[no-any-return]


def served_names() -> dict[tuple[str, str], str]:
    """Return (component, label) -> the absolute name it serves it at, from the library file.

    Every remapping of the paper's library is absolute and no component has a namespace, so
    the served name is the remapping, else ``/label``: no name resolution needed.
    """
    doc = yaml.safe_load(LIBRARY.read_text(encoding="utf-8"))
    out = {}
    for comp in doc["components"]:
        ros = comp.get("ros") or {}
        assert not ros.get("namespace")
        for kind in comp.get("provides", []):
            label = next(kind[k] for k in ("topic", "service", "action") if k in kind)
            name = (ros.get("remappings") or {}).get(label, "/" + label)
            assert name.startswith("/")
            out[(comp["name"], label)] = name
    return out


def wiring(
    config: dict[str, Any], served: dict[tuple[str, str], str]
) -> dict[str, set[tuple[str, str]]]:
    """Return node -> (label, name) for each interface its ROS-graph edges bring it from a provider.

    A consumer's edges run from the provider's interface to it (``enumerate``'s ROS-graph).
    """
    owner = {}
    for kind in ("topics", "services", "actions"):
        for item in config["ros_graph"][kind]:
            provider = item["id"][: -len(item["label"]) - 1]
            owner[item["id"]] = (item["label"], served[(provider, item["label"])])
    wires: dict[str, set[tuple[str, str]]] = {n["id"]: set() for n in config["ros_graph"]["nodes"]}
    for edge in config["ros_graph"]["edges"]:
        if edge["to_kind"] == "node" and edge["from"] in owner:
            wires[edge["to"]].add(owner[edge["from"]])
    return wires


def count(before: dict[str, Any], after: dict[str, Any], served: dict[tuple[str, str], str]) -> int:
    """Count a switch's changes the simple way: the two schemas have the same roles here.

    Per role: the same component, wired alike: 0; the same, wired otherwise: 1 (restart);
    another component: 1 (the old stops, the new starts in its place).
    """
    old, new = before["assignment"], after["assignment"]
    was, now = wiring(before, served), wiring(after, served)
    return sum(1 for role, comp in new.items() if comp != old[role] or was[comp] != now[comp])


def dc_arm(runner: CliRunner, tmp_path: Path) -> tuple[Path, dict[str, Any]]:
    """Write Object Repositioning on the DC arm as a --current file; return it and its entry."""
    doc = enumerate_json(runner, "object_repositioning")
    first = doc["configurations"][0]
    assert first["assignment"]["base_joint"] == "NDC1"
    path = tmp_path / "running.json"
    path.write_text(json.dumps({"schemas": [{**doc, "configurations": [first]}]}))
    return path, first


def test_repositioning_on_the_dc_arm_switches_to_disc_loading_with_the_fewest_changes(
    runner: CliRunner, tmp_path: Path
) -> None:
    current, running = dc_arm(runner, tmp_path)
    args = ["plan", "--switch-to", "disc_loading", "--only", "object_repositioning"]
    result = runner.invoke(app, [*args, "--current", str(current), "--json"])
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    schema = json.loads(bundled(Bundle.DATA, "output-plan.schema.json").read_text())
    jsonschema.validate(doc, schema)
    switch = doc["switch"]
    assert (switch["from"], switch["to"]) == ("object_repositioning", "disc_loading")
    kinds = {(c["component"], c["kind"]) for c in switch["changes"]}
    # the DC arm and its controllers go, the servo arm and its controllers come
    for joint in range(1, 6):
        assert (f"NDC{joint}", "stop") in kinds and (f"NSM{joint}", "start") in kinds
    assert ("NCA1", "keep") in kinds and ("NVP1", "keep") in kinds
    # NREA stays but called /arm_dc/...: it restarts to call /arm_servo/...
    assert ("NREA", "restart") in kinds
    # brute force: every valid Disc Loading configuration, counted independently
    served = served_names()
    every = enumerate_json(runner, "disc_loading")["configurations"]
    fewest = min(count(running, c, served) for c in every)
    assert switch["count"] == switch["fewest_changes"] == fewest == 10
    new = doc["schemas"][0]["configurations"][0]["assignment"]
    chosen = next(c for c in every if c["assignment"] == new)
    assert count(running, chosen, served) == fewest
    assert any(
        s.startswith("restart NREA as reasoner (rewired)") for s in doc["schemas"][0]["steps"]
    )
    why = " ".join(doc["schemas"][0]["explanation"])
    assert "base_joint: NDC1 cannot stay (NDC1 may only serve in object_repositioning" in why
    assert "the fewest possible" in why


def test_the_text_report_lists_each_component_with_why(runner: CliRunner, tmp_path: Path) -> None:
    current, _ = dc_arm(runner, tmp_path)
    args = ["plan", "--switch-to", "disc_loading", "--current", str(current)]
    result = runner.invoke(app, args)  # the running schema: the one the file names
    assert result.exit_code == 0, result.stderr
    out = result.stdout
    assert "switch from Object Repositioning (object_repositioning) to Disc Loading" in out
    assert "changes (10, fewest possible: 10):" in out
    assert "restart  NREA" in out and "keep     NCA1" in out and "stop     NDC1" in out


def test_the_nominal_servo_arm_switches_with_nothing_to_change(runner: CliRunner) -> None:
    args = ["plan", "--switch-to", "disc_loading", "--only", "object_repositioning", "--json"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.stderr
    switch = json.loads(result.stdout)["switch"]
    assert switch["count"] == switch["fewest_changes"] == 0
    assert {c["kind"] for c in switch["changes"]} == {"keep"}


def test_a_switch_with_nsm3_failed_is_impossible_and_says_why(
    runner: CliRunner, tmp_path: Path
) -> None:
    current, _ = dc_arm(runner, tmp_path)
    args = ["plan", "--switch-to", "disc_loading", "--current", str(current), "--fail", "NSM3"]
    result = runner.invoke(app, args)
    assert result.exit_code == 1, result.stderr
    assert "the switch is impossible" in result.stdout
    assert "NSM3 has failed" in result.stdout
    assert "NDC3 may only serve in object_repositioning" in result.stdout
    done = runner.invoke(app, [*args, "--json"])
    assert done.exit_code == 1
    doc = json.loads(done.stdout)
    assert doc["schemas"][0]["status"] == "unsolvable-proven"
    assert doc["switch"]["count"] is None and doc["switch"]["changes"] == []
    assert "NSM3 has failed" in doc["schemas"][0]["why_not"]


def test_a_failure_is_unusable_in_the_new_task(runner: CliRunner) -> None:
    args = ["plan", "--switch-to", "disc_loading", "--only", "object_repositioning"]
    result = runner.invoke(app, [*args, "--fail", "NCA1", "--json"])
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    new = doc["schemas"][0]["configurations"][0]["assignment"]
    assert new["camera"] == "NCA2" and "NCA1" not in new.values()
    kinds = {c["component"]: c["kind"] for c in doc["switch"]["changes"]}
    assert kinds["NCA1"] == "stop" and kinds["NCA2"] == "start"
    assert doc["switch"]["count"] == doc["switch"]["fewest_changes"]


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (
            ["--switch-to", "disc_load", "--only", "object_repositioning"],
            "did you mean disc_loading",
        ),
        (["--switch-to", "nowhere", "--only", "object_repositioning"], "no such schema"),
        (["--switch-to", "disc_loading", "--only", "nowhere"], "--only nowhere: no such schema"),
        (["--switch-to", "disc_loading"], "name the running schema with --only"),
        (
            ["--switch-to", "disc_loading", "--only", "object_repositioning", "--only", "x"],
            "--only names the one running schema",
        ),
    ],
)
def test_bad_switch_input_is_a_usage_error(runner: CliRunner, args: list[str], said: str) -> None:
    result = runner.invoke(app, ["plan", *args])
    assert result.exit_code == 2
    assert said in result.stderr
    assert "Traceback" not in result.stderr + result.stdout


def test_a_switch_to_the_running_schema_is_its_re_plan(runner: CliRunner) -> None:
    """One objective for both: switching Object Repositioning to itself under --fail NSM3
    chooses what ``plan --fail NSM3`` chooses, with the same number of changes."""
    only = ["--only", "object_repositioning", "--fail", "NSM3", "--json"]
    switched = runner.invoke(app, ["plan", "--switch-to", "object_repositioning", *only])
    replanned = runner.invoke(app, ["plan", *only])
    assert switched.exit_code == replanned.exit_code == 0, switched.stderr + replanned.stderr
    a, b = json.loads(switched.stdout), json.loads(replanned.stdout)
    assert a["schemas"][0]["configurations"] == b["schemas"][0]["configurations"]
    assert (
        a["switch"]["count"] == a["switch"]["fewest_changes"] == b["schemas"][0]["fewest_changes"]
    )
