"""Correct answers in the corner cases (issue 10 item 5), through the real CLI."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.solve import counting

REPO = Path(__file__).resolve().parent.parent


def test_a_schema_without_configuration_has_no_single_points_of_failure_to_list(
    runner: CliRunner,
) -> None:
    result = runner.invoke(app, ["analyse", "--only", "disc_loading", "--fail", "NSM3"])
    assert "no configuration" in result.stdout, result.output
    assert "single points of failure: none" not in result.stdout
    assert "single points of failure: not applicable" in result.stdout


def test_redundancy_above_one_half_warns_and_shows_both_readings(runner: CliRunner) -> None:
    result = runner.invoke(app, ["redundancy", "--p", "0.95", "--n", "10", "--q", "0.99"])
    assert result.exit_code == 0, result.output
    assert "almost surely an availability" in result.stderr
    assert "r = 135" in result.stderr and "give --p 0.05" in result.stderr
    quiet = runner.invoke(app, ["redundancy", "--p", "0.05", "--n", "10", "--q", "0.99"])
    assert "warning" not in quiet.stderr


def test_load_with_both_options_ignores_the_default_folders(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "libraries").mkdir()
    (tmp_path / "libraries" / "broken.yaml").write_text("format: [unclosed\n")
    shutil.copytree(REPO / "libraries", tmp_path / "mine")
    shutil.copytree(REPO / "schemas", tmp_path / "myschemas")
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["enumerate", "--count", "-l", "mine", "-s", "myschemas"])
    assert result.exit_code == 0, result.output
    assert "broken.yaml" not in result.output


def test_count_says_when_it_falls_back_to_listing(
    runner: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(counting, "MAX_FACTOR_ROWS", 1)
    monkeypatch.setattr(counting.count, "__defaults__", (1,))
    result = runner.invoke(app, ["enumerate", "--count", "--only", "object_repositioning"])
    assert result.exit_code == 0, result.output
    assert "counted by listing every configuration" in result.stderr


def test_duplicate_edges_are_a_warning_in_validate(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    shutil.copytree(REPO / "libraries", tmp_path / "libraries")
    shutil.copytree(REPO / "schemas", tmp_path / "schemas")
    schema = tmp_path / "schemas" / "indoor_navigation.yaml"
    old = "  - {consumer: base, providers: [local_planner]}\n"
    text = schema.read_text()
    assert old in text
    schema.write_text(
        text.replace(
            old, old + "  - {consumer: base, providers: [local_planner], interfaces: [cmd_vel]}\n"
        )
    )
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["validate"])
    assert result.exit_code == 0, result.output
    assert "indoor_navigation.yaml:25:" in result.stdout
    assert "warning: edge local_planner -> base is listed again" in result.stdout
    assert runner.invoke(app, ["validate", "--strict"]).exit_code == 1
