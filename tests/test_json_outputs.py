"""Every command's --json output validates against its shipped JSON Schema."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.resources import Bundle, bundled

CASES = Path(__file__).parent / "cases"
SNAPSHOTS = Path(__file__).parent / "snapshots" / "valid"


def schema_of(command: str) -> dict[str, Any]:
    """Return the shipped JSON Schema of ``command``'s --json output."""
    text = bundled(Bundle.DATA, f"output-{command}.schema.json").read_text(encoding="utf-8")
    doc: dict[str, Any] = json.loads(text)
    jsonschema.Draft202012Validator.check_schema(doc)
    return doc


RUNS = [
    ("validate", ["validate", "--format", "json"], None),
    ("validate", ["validate", ".", "--format", "json"], CASES / "invalid" / "schema_errors"),
    ("enumerate", ["enumerate", "--json"], None),
    ("enumerate", ["enumerate", "--json", "--fail", "NSM3", "--limit", "1"], None),
    ("enumerate", ["enumerate", "--json", "--count"], None),
    ("enumerate", ["enumerate", "--json", "--best", "--objective", "cost=1"], None),
    ("analyse", ["analyse", "--json"], None),
    ("redundancy", ["redundancy", "--p", "0.1", "--n", "20", "--q", "0.99", "--json"], None),
    ("whatif", ["whatif", "--only", "object_repositioning", "--workers", "1", "--json"], None),
    ("simulate", ["simulate", "--workers", "1", "--json"], None),
    (
        "simulate",
        [
            "simulate",
            "--workers",
            "1",
            "--json",
            "--fail",
            "NCA1",
            "--pareto",
            "settling_time,cost",
        ],
        None,
    ),
    (
        "inspect",
        [
            "inspect",
            "--snapshot",
            str(SNAPSHOTS / "arm_and_reasoner.json"),
            "--json",
            "--only",
            "object_repositioning",
        ],
        None,
    ),
]


@pytest.mark.parametrize(("command", "args", "where"), RUNS, ids=lambda x: str(x))
def test_output_matches_schema(
    runner: CliRunner, tmp_path: Path, command: str, args: list[str], where: Path | None
) -> None:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(where or tmp_path)
        result = runner.invoke(app, args)
    assert result.exit_code in (0, 1), result.stderr
    jsonschema.validate(json.loads(result.stdout), schema_of(command))


@pytest.mark.planner
def test_plan_output_matches_schema(runner: CliRunner, tmp_path: Path) -> None:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path)
        result = runner.invoke(app, ["plan", "--fail", "NSM3", "--json"])
    assert result.exit_code == 1, result.stderr  # Disc Loading is impossible
    doc = json.loads(result.stdout)
    jsonschema.validate(doc, schema_of("plan"))
    statuses = {s["name"]: s["status"] for s in doc["schemas"]}
    assert statuses["object_repositioning"] == "solved"
    assert statuses["disc_loading"] == "unsolvable-proven"


@pytest.mark.planner
@pytest.mark.parametrize(("fail", "code"), [([], 0), (["--fail", "NSM3"], 1)])
def test_plan_switch_output_matches_schema(
    runner: CliRunner, tmp_path: Path, fail: list[str], code: int
) -> None:
    args = ["plan", "--switch-to", "disc_loading", "--only", "object_repositioning", "--json"]
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path)
        result = runner.invoke(app, [*args, *fail])
    assert result.exit_code == code, result.stderr
    doc = json.loads(result.stdout)
    jsonschema.validate(doc, schema_of("plan"))
    assert [s["name"] for s in doc["schemas"]] == ["disc_loading"]
    assert doc["switch"]["from"] == "object_repositioning"
