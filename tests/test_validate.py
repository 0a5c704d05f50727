"""``rosreconf validate`` on the bundled data and on every case folder under tests/cases."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.formats.yamlsource import MAX_BYTES

CASES = Path(__file__).parent / "cases"

VALID = sorted(p for p in (CASES / "valid").iterdir() if p.is_dir())
INVALID = sorted(p for p in (CASES / "invalid").iterdir() if p.is_dir())
REPO = Path(__file__).resolve().parent.parent


def _run(runner: CliRunner, where: Path, *args: str) -> tuple[int, str, str]:
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(where)
        result = runner.invoke(app, ["validate", *args])
    assert not isinstance(result.exception, Exception) or isinstance(
        result.exception, SystemExit
    ), result.exception
    return result.exit_code, result.stdout, result.stderr


def test_bundled_files_are_valid(runner: CliRunner, tmp_path: Path) -> None:
    code, out, _ = _run(runner, tmp_path)  # empty folder: falls back to the bundled example
    assert code == 0, out
    assert "7 file(s) valid: 0 error(s), 0 warning(s)" in out  # + nav_robot, map_navigation
    assert "bundled example" in out


def test_checkout_folders_are_valid(runner: CliRunner) -> None:
    code, out, _ = _run(runner, REPO)
    assert code == 0, out
    assert "using libraries/ and schemas/" in out


@pytest.mark.parametrize("case", VALID, ids=lambda p: p.name)
def test_valid_case(runner: CliRunner, case: Path) -> None:
    code, out, _ = _run(runner, case, ".")
    assert code == 0, out


REWRITE_PINS = os.environ.get("ROSRECONF_REWRITE_PINS", "") not in ("", "0")
"""Set ROSRECONF_REWRITE_PINS=1 to rewrite every ``expected.json`` from what ``validate``
reports now, after a deliberate change of messages or positions (then read the diff)."""


@pytest.mark.parametrize("case", INVALID, ids=lambda p: p.name)
def test_invalid_case_pins_message_and_position(runner: CliRunner, case: Path) -> None:
    """``validate . --format json`` in each invalid case is its pinned ``expected.json``."""
    code, out, _ = _run(runner, case, ".", "--format", "json")
    pinned = case / "expected.json"
    if REWRITE_PINS:
        pinned.write_text(out, encoding="utf-8")
    assert out == pinned.read_text(encoding="utf-8")
    assert json.loads(out)["valid"] is False
    assert code == 1


def test_json_report_is_one_document_with_positions(runner: CliRunner) -> None:
    code, out, _ = _run(runner, CASES / "invalid" / "unknown_key", ".", "--format", "json")
    doc = json.loads(out)
    assert code == 1 and doc["valid"] is False and doc["errors"] == 1
    [problem] = doc["problems"]
    assert (problem["file"], problem["line"], problem["column"]) == ("lib.yaml", 7, 5)
    assert problem["code"] == "unknown-key"
    assert "did you mean 'provides'?" in problem["hint"]


def test_github_annotations(runner: CliRunner) -> None:
    code, out, _ = _run(runner, CASES / "invalid" / "unknown_coupling", ".", "-f", "github")
    lines = out.splitlines()
    assert code == 1 and len(lines) == 2
    assert lines[0].startswith(
        "::error file=lib.yaml,line=9,col=13,title=rosreconf unknown-component::"
    )


def test_all_files_reported_in_one_run(runner: CliRunner, tmp_path: Path) -> None:
    for case in ("unknown_key", "alias", "syntax_error"):
        shutil.copy(CASES / "invalid" / case / "lib.yaml", tmp_path / f"{case}.yaml")
    code, out, _ = _run(runner, tmp_path, ".")
    files = {line.split(":")[0] for line in out.splitlines() if ".yaml:" in line}
    assert code == 1 and files == {"unknown_key.yaml", "alias.yaml", "syntax_error.yaml"}


def test_warning_fails_only_with_strict(runner: CliRunner, tmp_path: Path) -> None:
    lib = (CASES / "invalid" / "schema_errors" / "lib.yaml").read_text()
    (tmp_path / "lib.yaml").write_text(lib)
    (tmp_path / "task.yaml").write_text(
        "format: rosreconf/interoperability-schema\nversion: 1\nname: t\nskill: s\n"
        "environment: e\nroles:\n  - {name: camera, abstraction: camera}\n"
        "  - {name: vision, abstraction: perception}\n"
        "edges:\n  - {consumer: vision, providers: [camera]}\n"
    )
    assert _run(runner, tmp_path, ".")[0] == 0
    (tmp_path / "task.yaml").write_text(
        (tmp_path / "task.yaml")
        .read_text()
        .replace("perception}", "perception}\n  - {name: spare, abstraction: camera}")
        .replace("[camera]}", "[camera]}\n  - {consumer: vision, providers: [spare]}")
    )
    lib2 = (
        lib + "  - name: SONAR\n    abstraction: sonar\n    provides:\n"
        "      - {topic: range, type: sensor_msgs/Range}\n"
    )
    (tmp_path / "lib.yaml").write_text(lib2)
    code, out, _ = _run(runner, tmp_path, ".")
    assert code == 0 and "warning" in out
    assert _run(runner, tmp_path, ".", "--strict")[0] == 1


def test_missing_path_is_usage_error(runner: CliRunner, tmp_path: Path) -> None:
    code, _, err = _run(runner, tmp_path, "nope.yaml")
    assert code == 2
    assert "nope.yaml: no such file or folder" in err


def test_size_cap(runner: CliRunner, tmp_path: Path) -> None:
    size = MAX_BYTES + 10
    with (tmp_path / "big.yaml").open("wb") as f:
        f.truncate(size)  # sparse: costs no disk, and is not read whole
    code, out, _ = _run(runner, tmp_path, ".")
    assert code == 1
    assert f"big.yaml:1:1: error: file is {size} bytes, over the limit of {MAX_BYTES} bytes" in out


def _checkout_copy(tmp_path: Path) -> Path:
    for folder in ("libraries", "schemas"):
        shutil.copytree(REPO / folder, tmp_path / folder)
    return tmp_path


def _report(runner: CliRunner, where: Path, *args: str) -> Any:
    _, out, _ = _run(runner, where, ".", "--format", "json", *args)
    return json.loads(out)


def test_a_todo_mark_alone_is_reported_with_its_position(runner: CliRunner, tmp_path: Path) -> None:
    where = _checkout_copy(tmp_path)
    lib = where / "libraries" / "robot_arms.yaml"
    lines = lib.read_text(encoding="utf-8").splitlines(keepends=True)
    lines.insert(3, "# TODO: check the arm's joints\n")
    lib.write_text("".join(lines), encoding="utf-8")
    [todo] = _report(runner, where)["problems"]
    assert (todo["code"], todo["line"], todo["column"]) == ("todo", 4, 1)
    assert todo["file"] == "libraries/robot_arms.yaml"


def test_a_duplicate_edge_alone_is_reported_with_its_position(
    runner: CliRunner, tmp_path: Path
) -> None:
    where = _checkout_copy(tmp_path)
    schema = where / "schemas" / "object_repositioning.yaml"
    text = schema.read_text(encoding="utf-8")
    edge = "  - {consumer: perception, providers: [camera, gripper_sensor]}\n"
    assert edge in text
    line = text[: text.index(edge)].count("\n") + 2  # the line of the entry added below
    schema.write_text(
        text.replace(edge, edge + "  - {consumer: perception, providers: [camera]}\n")
    )
    [dup] = _report(runner, where, "--strict")["problems"]
    assert (dup["code"], dup["severity"]) == ("duplicate-edge", "warning")
    assert (dup["line"], dup["column"]) == (line, text.splitlines()[line - 2].index("camera") + 1)


def test_a_semantic_problem_across_clean_files_is_reported_with_positions(
    runner: CliRunner, tmp_path: Path
) -> None:
    # Every file is clean on its own; the problem shows only in the checks of the whole.
    where = _checkout_copy(tmp_path)
    shutil.copy(where / "libraries" / "robot_arms.yaml", where / "libraries" / "again.yaml")
    problems = _report(runner, where)["problems"]
    assert "duplicate-component" in {p["code"] for p in problems}
    assert all(p["line"] > 0 for p in problems)


def test_a_tab_before_a_comment_is_valid_yaml(runner: CliRunner, tmp_path: Path) -> None:
    # libyaml, the reader of record, reads it as YAML 1.2 does (PyYAML's pure parser refused it).
    where = _checkout_copy(tmp_path)
    lib = where / "libraries" / "robot_arms.yaml"
    text = lib.read_text(encoding="utf-8")
    lib.write_text(text.replace("version: 1\n", "version: 1\t# the format's version\n", 1))
    code, out, _ = _run(runner, where, ".")
    assert code == 0, out


def test_json_flag_is_format_json(runner: CliRunner) -> None:
    case = CASES / "invalid" / "unknown_key"
    assert _run(runner, case, ".", "--json") == _run(runner, case, ".", "--format", "json")
    assert json.loads(_run(runner, case, ".", "--json")[1])["errors"] == 1


def test_library_and_schema_options_read_what_paths_read(runner: CliRunner) -> None:
    lib, schema = "libraries/robot_arms.yaml", "schemas/object_repositioning.yaml"
    by_option = _run(runner, REPO, "-l", lib, "-s", schema, "--json")
    by_path = _run(runner, REPO, lib, schema, "--json")
    assert by_option == by_path
    assert json.loads(by_option[1])["files"] == [lib, schema]
    # -l alone: the schemas come from schemas/ here, as for every other command
    _, out, _ = _run(runner, REPO, "-l", lib, "--json")
    schemas = sorted(f"schemas/{p.name}" for p in REPO.glob("schemas/*.yaml"))
    assert json.loads(out)["files"] == [lib, *schemas]


def test_a_library_and_schema_without_any_configuration_get_a_warning_at_the_schema(
    runner: CliRunner,
) -> None:
    # The old validate said "valid: 0 error(s), 0 warning(s)" and only enumerate told.
    where = Path(__file__).parent / "data" / "no_configuration"
    code, out, _ = _run(runner, where)
    assert code == 0, out  # a warning: the files are well formed
    assert out.startswith(
        "schemas/arm.yaml:1:1: warning: schema 'arm' has no configuration over the library: "
        "Arm needs a sensor (role eye); every candidate is ruled out: "
    )
    assert "SPARE requires topic 'calibration'" in out
    assert "0 error(s), 1 warning(s)" in out
    assert _run(runner, where, "--strict")[0] == 1
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(where)
        enumerated = runner.invoke(app, ["enumerate"])
    why = enumerated.stdout.split("no configuration: ", 1)[1].strip()
    assert why in out  # enumerate's own explanation, word for word


def test_a_megabyte_name_is_quoted_short_with_its_length(runner: CliRunner, tmp_path: Path) -> None:
    # The old message echoed the whole 1 MB name.
    (tmp_path / "libraries").mkdir()
    name = "A b" * 350_000
    (tmp_path / "libraries" / "big.yaml").write_text(
        "format: rosreconf/component-library\nversion: 1\nname: big\ncomponents:\n"
        f'  - name: "{name}"\n    abstraction: sensor\n    failure_probability: 0.1\n'
    )
    code, out, _ = _run(runner, tmp_path, "libraries")
    assert code == 1
    assert len(out) < 1_000, out[:2_000]
    assert f"'{name[:120]}... (1,050,000 characters)'" in out


def test_the_summary_counts_the_files_that_hold_errors_not_every_file_read(
    runner: CliRunner, tmp_path: Path
) -> None:
    """One mistake in one library file of the bundled example's seven: "1 of 7", which said
    "7 file(s) invalid" before, as if every file were wrong."""
    for folder in ("libraries", "schemas"):
        shutil.copytree(REPO / folder, tmp_path / folder)
    files = sorted(tmp_path.rglob("*.yaml"))
    library = next(f for f in files if "failure_probability:" in f.read_text(encoding="utf-8"))
    text = library.read_text(encoding="utf-8")
    library.write_text(text.replace("failure_probability:", "failure_probabilty:", 1), "utf-8")
    code, out, _ = _run(runner, tmp_path, *(str(f) for f in files))
    assert code == 1, out
    assert out.splitlines()[-1].startswith(f"1 of {len(files)} file(s) invalid: 1 error(s)"), out
