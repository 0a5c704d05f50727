"""The paper's Section 6 results, asserted from the CLI's JSON on the bundled example."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.loader import load_bundled

DC_CAM1 = [
    "NDC1",
    "NDC2",
    "NDC3",
    "NDC4",
    "NDC5",
    "NCA1",
    "NCO1",
    "NVP1",
    "NFB11",
    "NFB12",
    "NFB13",
    "NFB14",
    "NREA",
]
DC_CAM2 = [
    "NDC1",
    "NDC2",
    "NDC3",
    "NDC4",
    "NDC5",
    "NCA2",
    "NCO2",
    "NVP2",
    "NFB11",
    "NFB12",
    "NFB13",
    "NFB14",
    "NREA",
]
SM_CAM1 = [
    "NSM1",
    "NSM2",
    "NSM3",
    "NSM4",
    "NSM5",
    "NCA1",
    "NCO1",
    "NVP1",
    "NFB21",
    "NFB22",
    "NFB23",
    "NFB24",
    "NREA",
]
SM_CAM2 = [
    "NSM1",
    "NSM2",
    "NSM3",
    "NSM4",
    "NSM5",
    "NCA2",
    "NCO2",
    "NVP2",
    "NFB21",
    "NFB22",
    "NFB23",
    "NFB24",
    "NREA",
]
ARMS = ["--only", "object_repositioning", "--only", "disc_loading"]


def _json(runner: CliRunner, tmp_path: Path, *args: str) -> tuple[int, dict[str, Any]]:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path)  # no libraries/ here: the bundled example is used
        result = runner.invoke(app, [*args, "--json"])
    return result.exit_code, json.loads(result.stdout)


def _configs(doc: dict[str, Any]) -> dict[str, list[list[str]]]:
    return {s["name"]: [c["components"] for c in s["configurations"]] for s in doc["schemas"]}


def test_paper_four_plus_two(runner: CliRunner, tmp_path: Path) -> None:
    code, doc = _json(runner, tmp_path, "enumerate", *ARMS)
    assert code == 0
    assert _configs(doc) == {
        "object_repositioning": [DC_CAM1, DC_CAM2, SM_CAM1, SM_CAM2],
        "disc_loading": [SM_CAM1, SM_CAM2],
    }
    assert {s["name"]: s["count"] for s in doc["schemas"]} == {
        "object_repositioning": 4,
        "disc_loading": 2,
    }


def test_fail_nsm3_leaves_two_and_none_with_reason(runner: CliRunner, tmp_path: Path) -> None:
    code, doc = _json(runner, tmp_path, "enumerate", *ARMS, "--fail", "NSM3")
    assert code == 1
    by_name = {s["name"]: s for s in doc["schemas"]}
    assert [c["components"] for c in by_name["object_repositioning"]["configurations"]] == [
        DC_CAM1,
        DC_CAM2,
    ]
    dl = by_name["disc_loading"]
    assert dl["count"] == 0 and dl["configurations"] == []
    assert "elbow actuator" in dl["why_not"] and "NSM3 has failed" in dl["why_not"]
    assert "NDC3 may only serve in object_repositioning" in dl["why_not"]


def test_count_matches_listing_and_ros_graph_is_concrete(runner: CliRunner, tmp_path: Path) -> None:
    _, counted = _json(runner, tmp_path, "enumerate", "--count")
    _, listed = _json(runner, tmp_path, "enumerate")
    assert {s["name"]: s["count"] for s in counted["schemas"]} == {
        s["name"]: len(s["configurations"]) for s in listed["schemas"]
    }
    first = next(s for s in listed["schemas"] if s["name"] == "disc_loading")["configurations"][0]
    graph = first["ros_graph"]
    assert {n["id"] for n in graph["nodes"]} == set(SM_CAM1)
    services = {s["id"] for s in graph["services"]}
    assert "NSM3/elbow/digital_servo_command" in services and "NCA1/camera_image" in services
    edges = {(e["from"], e["to"]) for e in graph["edges"]}
    # Information flows provider -> service -> consumer.
    assert ("NCA1", "NCA1/camera_image") in edges and ("NCA1/camera_image", "NVP1") in edges


def test_limit_stops_early(runner: CliRunner, tmp_path: Path) -> None:
    _, doc = _json(runner, tmp_path, "enumerate", "--only", "indoor_navigation", "--limit", "3")
    [nav] = doc["schemas"]
    assert len(nav["configurations"]) == 3 and nav["limit_reached"] and nav["count"] is None


def test_unknown_failed_component_is_usage_error(runner: CliRunner, tmp_path: Path) -> None:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path)
        result = runner.invoke(app, ["enumerate", "--fail", "NSM9"])
    assert result.exit_code == 2
    assert "no such component (did you mean NSM5?)" in result.stderr


def test_analyse_paper_questions(runner: CliRunner, tmp_path: Path) -> None:
    code, doc = _json(runner, tmp_path, "analyse", *ARMS)
    assert code == 0
    by_name = {s["schema"]: s for s in doc["schemas"]}
    orep = by_name["object_repositioning"]
    assert orep["orthogonal"] is False and orep["valid"] == 4 and orep["substitutions"] == 2**12
    reasons = {(p["first"], p["second"]): p["reason"] for p in orep["incompatible"]}
    assert reasons[("NDC3", "NFB21")] == (
        "NFB21 requires elbow/digital_servo_command; NDC3 provides elbow/dc_servo_command"
    )
    assert orep["single_points_of_failure"] == ["NREA"]
    pairs = {tuple(p) for p in orep["critical_pairs"]}
    assert ("NCA1", "NCA2") in pairs and ("NDC1", "NSM1") in pairs
    dl = by_name["disc_loading"]
    assert set(dl["single_points_of_failure"]) == {
        "NREA",
        "NSM1",
        "NSM2",
        "NSM3",
        "NSM4",
        "NSM5",
        "NFB21",
        "NFB22",
        "NFB23",
        "NFB24",
    }
    assert dl["reliability"]["method"].startswith("exact")
    assert 0 < dl["reliability"]["probability"] < orep["reliability"]["probability"] < 1


def test_mobile_robot_is_not_orthogonal_because_of_sonar(runner: CliRunner, tmp_path: Path) -> None:
    _, doc = _json(runner, tmp_path, "analyse", "--only", "indoor_navigation")
    [nav] = doc["schemas"]
    assert not nav["orthogonal"]
    assert any("SONAR_RING provides sonar" in p["reason"] for p in nav["incompatible"])
    sensor = next(r for r in nav["redundancy"] if r["role"] == "range_sensor")
    assert len(sensor["candidates"]) == 3 and sensor["usable"] == ["HOKUYO_UST10", "SICK_TIM571"]


def test_astronomical_count_is_exact_and_printable(runner: CliRunner, tmp_path: Path) -> None:
    """A product over 400 independent roles of 3 candidates: 3**400, 191 digits (Theorem 9)."""
    lib = ["format: rosreconf/component-library", "version: 1", "name: wide", "components:"]
    roles = []
    for r in range(400):
        roles.append(f"  - {{name: r{r}, abstraction: a{r}}}")
        for k in range(3):
            lib.append(f"  - {{name: C{r}_{k}, abstraction: a{r}, provides: []}}")
    schema = [
        "format: rosreconf/interoperability-schema",
        "version: 1",
        "name: wide",
        "skill: s",
        "environment: e",
        "roles:",
        *roles,
    ]
    (tmp_path / "lib.yaml").write_text("\n".join(lib) + "\n")
    (tmp_path / "schema.yaml").write_text("\n".join(schema) + "\n")
    args = ["enumerate", "--count", "-l", str(tmp_path / "lib.yaml")]
    args += ["-s", str(tmp_path / "schema.yaml")]
    text = runner.invoke(app, args)
    assert text.exit_code == 0, text.output
    assert f"{3**400} configuration(s) (about 7.055e190, 191 digits)" in text.stdout
    doc = runner.invoke(app, [*args, "--json"])
    [schema_doc] = [s for s in json.loads(doc.stdout)["schemas"] if s["name"] == "wide"]
    assert schema_doc["count"] == 3**400 and schema_doc["count_text"] == str(3**400)


def test_best_is_the_least_weighted_sum_of_all_listed(runner: CliRunner, tmp_path: Path) -> None:
    _, listed = _json(runner, tmp_path, "enumerate")
    code, best = _json(runner, tmp_path, "enumerate", "--best", "--objective", "cost=1")
    assert code == 0
    cost = {c.name: c.metrics.get("cost", 0.0) for c in load_bundled().library}
    for every, one in zip(listed["schemas"], best["schemas"], strict=True):
        sums = [sum(cost[n] for n in c["components"]) for c in every["configurations"]]
        [chosen] = one["configurations"]
        assert one["optimum"]["weighted_sum"] == pytest.approx(min(sums))
        assert sum(cost[n] for n in chosen["components"]) == pytest.approx(min(sums))
        assert one["count"] is None and not one["limit_reached"]


@pytest.mark.parametrize(
    "args",
    [
        ["--best", "--count"],
        ["--best", "--limit", "2"],
        ["--objective", "cost=1"],
        ["--best", "--objective", "cost"],
    ],
)
def test_best_usage_errors_exit_2(runner: CliRunner, args: list[str]) -> None:
    result = runner.invoke(app, ["enumerate", *args])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
