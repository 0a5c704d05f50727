"""Input that must be refused (issue 10 item 3), and outputs that must hold for any input.

Each test reproduces a reported defect through the real CLI: a crash, a silent acceptance or
output that is not JSON.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf import jsonout
from rosreconf.cli.app import app
from rosreconf.formats import yamlsource
from rosreconf.formats.loader import load_paths
from rosreconf.render.reports import enumerate as enumerate_report
from rosreconf.synthetic import generate, write

CASES = Path(__file__).parent / "cases"
REPO = Path(__file__).resolve().parent.parent


def _lib_with(tmp_path: Path, old: str, new: str) -> Path:
    """Copy the bundled mobile robot library and schemas with one text replaced."""
    (tmp_path / "libraries").mkdir()
    text = (REPO / "libraries" / "mobile_robot.yaml").read_text()
    assert old in text
    (tmp_path / "libraries" / "mobile_robot.yaml").write_text(text.replace(old, new, 1))
    shutil.copytree(REPO / "schemas", tmp_path / "schemas")
    for other in (REPO / "libraries").glob("*.yaml"):
        if other.name != "mobile_robot.yaml":
            shutil.copy(other, tmp_path / "libraries")
    return tmp_path


def test_a_nan_failure_probability_is_refused_and_json_stays_json(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(_lib_with(tmp_path, "failure_probability: 0.02", "failure_probability: .nan"))
    result = runner.invoke(app, ["validate"])
    assert result.exit_code == 1 and "not a finite number" in result.stdout
    result = runner.invoke(app, ["analyse", "--json"])
    assert result.exit_code == 1 and "NaN" not in result.stdout


def test_a_huge_metric_is_a_problem_not_a_crash(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(
        _lib_with(tmp_path, "metrics: {cost: 3.0}", "metrics: {cost: " + "9" * 401 + "}")
    )
    for command in (["validate"], ["enumerate", "--count"], ["analyse"]):
        result = runner.invoke(app, command)
        assert result.exit_code == 1, (command, result.output)
        assert result.exception is None or isinstance(result.exception, SystemExit)
        assert "mobile_robot.yaml:21:" in result.output
        assert "too large to compute with" in result.output


def test_an_integer_too_long_for_python_is_a_problem(tmp_path: Path) -> None:
    text = (CASES / "invalid" / "non_finite_numbers" / "lib.yaml").read_text()
    (tmp_path / "lib.yaml").write_text(text.replace("9" * 401, "9" * 5000))
    loaded = load_paths([tmp_path / "lib.yaml"])  # Python's int() refuses 4,301+ digits
    assert "lib.yaml:11:13" in str(loaded.problems[1])


@pytest.mark.parametrize("value", ["inf", "nan", "0", "1e9"])
def test_plan_timeout_is_range_checked(runner: CliRunner, value: str) -> None:
    result = runner.invoke(app, ["plan", "--fail", "NSM3", "--timeout", value])
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "--timeout" in result.stderr


@pytest.mark.parametrize("verb", ["plan", "watch", "whatif"])
@pytest.mark.parametrize("value", ["nan", "inf", "0"])
def test_search_time_must_be_a_finite_number_of_seconds(
    runner: CliRunner, verb: str, value: str
) -> None:
    """--search-time nan acted as about 0 seconds (issue 32, N7); it is refused like inf."""
    extra = {"plan": ["--fail", "NSM3"], "watch": ["--master", "http://127.0.0.1:9/"]}
    result = runner.invoke(app, [verb, *extra.get(verb, []), "--search-time", value])
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "--search-time" in result.stderr


def test_counts_of_any_size_print_in_text_and_json() -> None:
    """A 10,000-role library has counts of thousands of digits; Python refuses str() of an
    int over 4,300 digits unless told otherwise. Both outputs must print it in full."""
    count = 7 * 10**6000 + 3
    limit = sys.get_int_max_str_digits()
    try:
        sys.set_int_max_str_digits(4300)  # Python's default, as in a fresh process
        text = enumerate_report._summary(count, 0, None)
        sys.set_int_max_str_digits(4300)
        doc = jsonout.dumps({"count": count})
    finally:
        sys.set_int_max_str_digits(limit)
    digits = text.split()[0]
    assert len(digits) == 6001 and digits.startswith("7") and digits.endswith("3")
    assert "6001 digits" in text
    assert json.loads(doc, parse_int=str)["count"] == digits  # Python parses it back exactly


def test_a_file_over_the_limit_is_not_read_whole(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(yamlsource, "MAX_BYTES", 1000)
    big = tmp_path / "big.yaml"
    with big.open("wb") as f:
        f.truncate(200 * 1024 * 1024)  # sparse: 200 MB that cost no disk
    loaded = load_paths([big])
    assert [p.code for p in loaded.problems] == ["too-large"]
    assert f"file is {200 * 1024 * 1024} bytes" in loaded.problems[0].message


def _bytes_read() -> int:
    """Return the bytes this process has read through read() calls so far (Linux)."""
    for line in Path("/proc/self/io").read_text().splitlines():
        if line.startswith("rchar:"):
            return int(line.split()[1])
    raise AssertionError("/proc/self/io has no rchar line")


def test_the_size_is_checked_before_the_file_is_read(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A sparse 5 GB file costs at most the limit in reads: reading it whole would cost 5 GB."""
    monkeypatch.setattr(yamlsource, "MAX_BYTES", 1000)
    big = tmp_path / "big.yaml"
    size = 5 * 1024**3
    with big.open("wb") as f:
        f.truncate(size)  # sparse: no disk used, but read() would return 5 GB of zeros
    before = _bytes_read()
    loaded = load_paths([big])
    read = _bytes_read() - before
    assert [p.code for p in loaded.problems] == ["too-large"]
    assert f"file is {size} bytes" in loaded.problems[0].message
    assert read < 1024 * 1024, f"read {read} bytes of a {size}-byte file"


def test_generated_libraries_stay_loadable_at_the_loader_limit(tmp_path: Path) -> None:
    generated = generate(10_000, 10, 0.2, 0)
    assert len(generated.library.encode()) <= yamlsource.MAX_BYTES
    write(generated, tmp_path)


@pytest.mark.parametrize("kind", ["fifo", "device", "loop"])
def test_special_files_are_named(runner: CliRunner, tmp_path: Path, kind: str) -> None:
    path = tmp_path / "lib.yaml"
    if kind == "fifo":
        os.mkfifo(path)
        what = "is a FIFO"
    elif kind == "device":
        path = Path("/dev/zero")
        what = "is a character device"
    else:
        path.symlink_to(path)
        what = "is a symlink loop"
    result = runner.invoke(app, ["validate", str(path)])
    assert result.exit_code == 2 and what in result.stderr, result.output
    if kind != "device":  # inside a folder they are named too, not skipped
        result = runner.invoke(app, ["validate", str(tmp_path)])
        assert result.exit_code == 2 and what in result.stderr, result.output


def test_an_empty_folder_fails_validate(runner: CliRunner, tmp_path: Path) -> None:
    (tmp_path / "notes.txt").write_text("no yaml here")
    result = runner.invoke(app, ["validate", str(tmp_path)])
    assert result.exit_code == 2 and "has no .yaml or .yml files" in result.stderr


def test_a_marked_substitution_reaches_the_launch_file(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    folder = _lib_with(
        tmp_path,
        "parameters: {ip_address: 192.168.0.10, frame_id: laser}",
        'parameters: {ip_address: 192.168.0.10, frame_id: {substitution: "$(env FRAME)"}}',
    )
    monkeypatch.chdir(folder)
    assert runner.invoke(app, ["validate"]).exit_code == 0
    result = runner.invoke(app, ["launch", "--only", "indoor_navigation", "--ros1", "-o", "-"])
    assert result.exit_code == 0, result.output
    assert '<param name="frame_id" value="$(env FRAME)"' in result.stdout


def test_each_duplicate_key_names_the_line_of_its_first_even_after_another_bad_key(
    runner: CliRunner, tmp_path: Path
) -> None:
    lib = tmp_path / "lib.yaml"
    lib.write_text(
        "format: rosreconf/component-library\n"
        "name: a\n"
        "format: again\n"
        "? [complex]\n"
        ": x\n"
        "version: 1\n"
        "version: 2\n"
    )
    result = runner.invoke(app, ["validate", str(lib)])
    assert result.exit_code == 1
    said = [line.partition(" (")[0] for line in result.stdout.splitlines() if "error:" in line]
    assert said == [
        f"{lib}:3:1: error: duplicate key 'format'",
        f"{lib}:4:3: error: a mapping key must be a plain value, not a list or mapping",
        f"{lib}:7:1: error: duplicate key 'version'",
    ], result.stdout
    assert "'format' (first written at line 1)" in result.stdout
    assert "'version' (first written at line 6)" in result.stdout


def test_a_number_is_quoted_as_written_not_as_read(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(_lib_with(tmp_path, "failure_probability: 0.02", "failure_probability: 1.50"))
    result = runner.invoke(app, ["validate"])
    assert result.exit_code == 1
    assert "failure_probability' is number '1.50', which is out of range" in result.stdout


@pytest.mark.parametrize(
    "command",
    [
        ["enumerate", "--best", "--objective", "cots=1"],
        ["plan", "--fail", "NSM3", "--objective", "cots=1"],
        [
            "plan",
            "--switch-to",
            "disc_loading",
            "--only",
            "object_repositioning",
            "--objective",
            "cots=1",
        ],
        ["render-pddl", "-o", "{out}", "--fail", "NSM3", "--objective", "cots=1"],
        ["watch", "--only", "object_repositioning", "--prefer", "cots=1"],
    ],
)
def test_a_misspelt_metric_is_refused_not_weighed_zero(
    runner: CliRunner, tmp_path: Path, command: list[str]
) -> None:
    """A metric no component carries would weigh 0 everywhere: the choice would silently fall
    to the other rules. It is refused as ``simulate --pareto`` refuses one, naming the
    library's metrics (read here from the YAML itself), and nothing is written or started."""
    import yaml

    out = tmp_path / "pddl"
    argv = [arg.replace("{out}", str(out)) for arg in command]
    result = runner.invoke(app, argv)
    assert result.exit_code == 2, result.output
    flag = "--prefer" if "--prefer" in argv else "--objective"
    known = sorted(
        {
            metric
            for path in (REPO / "libraries").glob("*.yaml")
            for component in yaml.safe_load(path.read_text())["components"]
            for metric in component.get("metrics", {})
        }
    )
    assert known and "cots" not in known
    assert result.stderr.strip() == (
        f"rosreconf: error: {flag} cots=1: unknown metric 'cots' "
        f"(the library's: {', '.join(known)})"
    )
    assert not out.exists()  # render-pddl made no folder for a refused command


@pytest.mark.parametrize(
    "command",
    [
        ["snapshot", "--master", "http://127.0.0.1:1/", "--spin-time", "5"],
        ["inspect", "--snapshot", "{out}", "--only", "object_repositioning", "--spin-time", "5"],
        ["import", "--snapshot", "{out}", "-o", "-", "--spin-time", "5"],
    ],
)
def test_spin_time_is_for_a_ros2_read_only(
    runner: CliRunner, tmp_path: Path, command: list[str]
) -> None:
    """Only a ROS 2 read listens for discovery; elsewhere ``--spin-time`` would be ignored."""
    argv = [arg.replace("{out}", str(tmp_path / "saved.json")) for arg in command]
    result = runner.invoke(app, argv)
    assert result.exit_code == 2, result.output
    assert (
        result.stderr.strip() == "rosreconf: error: --spin-time is for --ros2 (ROS 2 over DDS) only"
    )
