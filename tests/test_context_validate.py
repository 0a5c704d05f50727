"""Context declarations and ``when`` conditions: every error with its exact position.

Each case edits one line of the SUAVE-like example (docs/examples/suave) and runs the CLI
(``validate``; ``enumerate`` refuses the same file): the message, file:line:column and exit
code are pinned, and no traceback is ever shown.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app

REPO = Path(__file__).resolve().parent.parent
EXAMPLE = REPO / "docs" / "examples" / "suave"
LIBRARY = (EXAMPLE / "library.yaml").read_text(encoding="utf-8")
SCHEMA = EXAMPLE / "schema.yaml"

VIS = "when: {visibility: {at_least: 3.25}}"  # spiral_high's line
BAT = "field: percentage}"  # the battery declaration's line


def _line(text: str, needle: str) -> int:
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def _run(runner: CliRunner, tmp_path: Path, old: str, new: str, verb: str = "validate"):
    assert old in LIBRARY
    text = LIBRARY.replace(old, new, 1)
    lib = tmp_path / "lib.yaml"
    lib.write_text(text, encoding="utf-8")
    result = runner.invoke(app, [verb, "-l", str(lib), "-s", str(SCHEMA)])
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "Traceback" not in result.stdout + result.stderr
    return result, text, str(lib)


CASES = [
    (
        VIS,
        "when: {visibilty: {at_least: 3.25}}",
        "when: {visibilty",
        12,
        "error: spiral_high has a condition on 'visibilty', which is not a context of the "
        "library (did you mean 'visibility'? declare it under context: ({name, topic, type, "
        "field}), or fix the name)",
    ),
    (
        VIS,
        "when: {visibility: {at_least: 3.25, at_most: 3.0}}",
        "at_most: 3.0",
        35,
        "error: spiral_high's condition on visibility can never hold: at_least 3.25 is above "
        "at_most 3.0 (swap the bounds, or fix one)",
    ),
    (
        VIS,
        "when: {visibility: {at_least: high}}",
        "at_least: high",
        35,
        "error: 'components[0].when.visibility.at_least' must be a number, not text 'high'",
    ),
    (
        VIS,
        "when: {visibility: {at_most: true}}",
        "at_most: true",
        34,
        "error: 'components[0].when.visibility.at_most' must be a number, not boolean 'true'",
    ),
    (
        VIS,
        "when: {visibility: {equals: clear}}",
        "equals: clear",
        24,
        "error: spiral_high compares visibility as a string, but std_msgs/msg/Float64's field "
        "'data' holds a number (bound a number with at_least/at_most; compare a boolean or "
        "string with equals)",
    ),
    (
        BAT,
        "field: percent}",
        "field: percent}",
        87,
        "error: context 'battery': sensor_msgs/msg/BatteryState has no field 'percent' (did "
        "you mean 'percentage'?",
    ),
    (
        BAT,
        "field: status.stat}",
        "field: status.stat}",
        87,
        "error: context 'battery': sensor_msgs/msg/BatteryState has no field 'status.stat'",
    ),
    (
        "type: sensor_msgs/msg/BatteryState, field: percentage}",
        "type: sensor_msgs/msg/NavSatFix, field: status.servic}",
        "field: status.servic}",
        84,
        "error: context 'battery': sensor_msgs/msg/NavSatFix has no field 'status.servic' "
        "(did you mean 'status.service'?",
    ),
]


IDS = [
    "unknown-name",
    "at-least-above-at-most",
    "text-bound",
    "boolean-bound",
    "equals-on-a-number",
    "unknown-field",
    "unknown-nested-field",
    "unknown-nested-field-near",
]


@pytest.mark.parametrize("old, new, needle, column, message", CASES, ids=IDS)
def test_each_error_is_said_at_its_position(
    runner: CliRunner, tmp_path: Path, old: str, new: str, needle: str, column: int, message: str
) -> None:
    result, text, lib = _run(runner, tmp_path, old, new)
    assert result.exit_code == 1, result.stdout
    at = f"{lib}:{_line(text, needle)}:{column}: "
    said = [line for line in result.stdout.splitlines() if line.startswith(at)]
    assert said and said[0].startswith(at + message), result.stdout
    refused, _, _ = _run(runner, tmp_path, old, new, "enumerate")  # every command refuses it
    assert refused.exit_code != 0 and at + message in refused.stderr + refused.stdout


def test_a_nested_field_of_a_known_type_is_accepted(runner: CliRunner, tmp_path: Path) -> None:
    new = "type: sensor_msgs/msg/NavSatFix, field: status.service}"
    result, _, _ = _run(
        runner, tmp_path, "type: sensor_msgs/msg/BatteryState, field: percentage}", new
    )
    assert result.exit_code == 0, result.stdout


def test_an_unknown_type_is_taken_on_trust(runner: CliRunner, tmp_path: Path) -> None:
    new = "type: suave_msgs/msg/Visibility, field: reading.value}"
    result, _, _ = _run(runner, tmp_path, "type: std_msgs/msg/Float64, field: data}", new)
    assert result.exit_code == 0, result.stdout


def test_a_context_declared_twice(runner: CliRunner, tmp_path: Path) -> None:
    dup = "  - {name: battery, topic: /battery2, type: std_msgs/msg/Float64, field: data}\n"
    result, text, lib = _run(runner, tmp_path, "components:\n", dup + "components:\n")
    first = _line(text, "topic: /battery_state")
    at = f"{lib}:{_line(text, 'topic: /battery2')}:5: "
    assert f"{at}error: context 'battery' is declared twice (first at {lib}:{first}:5)" in (
        result.stdout
    )


def test_bounds_with_equals_is_refused(runner: CliRunner, tmp_path: Path) -> None:
    result, text, lib = _run(
        runner, tmp_path, VIS, "when: {visibility: {at_least: 1.0, equals: x}}"
    )
    at = f"{lib}:{_line(text, 'equals: x')}:35: "
    assert at + "error: 'components[0].when.visibility.at_least': {} is not allowed" in (
        result.stdout
    )
    assert result.exit_code == 1


def test_the_example_is_valid(runner: CliRunner) -> None:
    result = runner.invoke(
        app, ["validate", "-l", str(EXAMPLE / "library.yaml"), "-s", str(SCHEMA)]
    )
    assert result.exit_code == 0 and "0 error(s), 0 warning(s)" in result.stdout
