"""Clean files load without positions; anything to report loads again, with positions.

The loader reads every file as plain data first (no tree, no span) and builds the model
from it; at the first thing to report it loads every file again the positioned way
(``loader.load_reported``). These tests hold the two builds to equal models on every
bundled, test and generated library, prove that a clean load takes the plain path (its
spans are NOWHERE), and that every invalid case reports exactly what the positioned load
reported before the plain path existed (``expected.json``, written by ``rosreconf validate
--format json`` on main before this change).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app
from rosreconf.errors import Severity
from rosreconf.formats import loader
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.build import NeedsPositions, build_library, build_schema
from rosreconf.formats.generate import generate, write
from rosreconf.formats.loader import Loaded, load_paths, load_reported, load_selection
from rosreconf.formats.selection import select
from rosreconf.model import NOWHERE, Component, InteroperabilitySchema
from rosreconf.render.report import REPORTERS, OutputFormat

REPO = Path(__file__).resolve().parent.parent
CASES = REPO / "tests" / "cases"
INVALID = sorted(p for p in (CASES / "invalid").iterdir() if p.is_dir())
VALID = sorted(p for p in (CASES / "valid").iterdir() if p.is_dir())
CHECKOUT = [REPO / "libraries", REPO / "schemas"]
YAML_FILES = sorted(
    [*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml"), *CASES.rglob("*.yaml")]
)


def _component_fields(c: Component) -> tuple[object, ...]:
    """Return every field of a component that its equality compares, one by one."""
    return (
        c.name,
        c.abstraction,
        sorted(c.provides),
        [(r.options, str(r)) for r in c.requires],
        c.failure_probability,
        sorted(c.needs),
        sorted(c.excludes),
        sorted(c.schemas),
        c.launch,
        dict(c.launch.parameters) if c.launch else None,
        [type(v).__name__ for v in c.launch.parameters.values()] if c.launch else None,
        dict(c.metrics),
        dict(c.qos),
        c.dynamics,
        c.description,
    )


def _schema_fields(s: InteroperabilitySchema) -> tuple[object, ...]:
    return (
        s.name,
        s.title,
        s.graph.roles,
        [(r.name, r.abstraction, r.description) for r in s.graph.roles],
        s.graph.edges,
        s.skill,
        s.environment,
        dict(s.nominal),
        s.simulation,
        s.source,
    )


def _assert_same_model(positioned: Loaded, plain: Loaded) -> None:
    """Assert the two loads built equal models, field by field, and the plain one no span."""
    assert plain.files == positioned.files
    assert plain.libraries == positioned.libraries
    assert plain.schemas == positioned.schemas
    for a, b in zip(positioned.libraries, plain.libraries, strict=True):
        assert (a.name, a.description, a.source) == (b.name, b.description, b.source)
        assert [_component_fields(c) for c in a] == [_component_fields(c) for c in b]
        for c in b:
            assert c.span == NOWHERE and not c.where
            assert all(r.span == NOWHERE for r in c.requires)
    for s, t in zip(positioned.schemas, plain.schemas, strict=True):
        assert _schema_fields(s) == _schema_fields(t)
        assert t.span == NOWHERE and not t.where
        assert all(r.span == NOWHERE for r in t.graph.roles)
        assert all(e.span == NOWHERE for e in t.graph.edges)
    # the positioned load has them: the comparison above is not of two empty position sets
    assert all(c.span != NOWHERE for lib in positioned.libraries for c in lib)


@pytest.mark.parametrize(
    "folders",
    [CHECKOUT, *([case] for case in VALID)],
    ids=["checkout", *(f"valid/{case.name}" for case in VALID)],
)
def test_plain_and_positioned_builds_give_equal_models(folders: list[Path]) -> None:
    _assert_same_model(load_paths(folders), load_paths(folders, positions=False))


@pytest.mark.parametrize(
    ("roles", "candidates", "dynamics"),
    [(40, 3, False), (60, 10, True), (13, 1, True)],
)
def test_generated_libraries_build_the_same_either_way(
    tmp_path: Path, roles: int, candidates: int, dynamics: bool
) -> None:
    write(generate(roles, candidates, 0.3, seed=roles, dynamics=dynamics), tmp_path)
    plain = load_paths([tmp_path], positions=False)
    _assert_same_model(load_paths([tmp_path]), plain)
    if dynamics:  # the dynamics and the simulation block were built from plain data too
        assert any(c.dynamics is not None for lib in plain.libraries for c in lib)
        assert all(s.simulation is not None for s in plain.schemas)


def test_the_bundled_example_builds_the_same_either_way() -> None:
    _assert_same_model(loader.load_bundled(), loader.load_bundled(positions=False))


@pytest.fixture
def positioned(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Spy on the positioned reader: the files it reads, in order (a clean load reads none)."""
    files: list[str] = []
    real = ys.parse_plain

    def spy(data: bytes, file: str) -> object:
        files.append(file)
        return real(data, file)

    monkeypatch.setattr(ys, "parse_plain", spy)
    return files


def test_a_clean_load_takes_the_plain_path_and_reads_once(
    monkeypatch: pytest.MonkeyPatch, positioned: list[str]
) -> None:
    # A spy on the positioned reader: a clean load never calls it, and what the commands
    # get (select, through load_checked) has no position at all.
    monkeypatch.chdir(REPO)
    chosen = select(None, None)
    assert not positioned
    assert all(c.span == NOWHERE and not c.where for c in chosen.library)
    assert all(s.span == NOWHERE for s in chosen.schemas)
    loaded, problems = load_reported(lambda p: load_selection([], positions=p))
    assert not problems and not positioned
    assert loaded.files == load_selection([]).files


def test_warnings_alone_cost_the_solvers_no_second_load(positioned: list[str]) -> None:
    # The checkout's libraries with one schema: every mobile-robot component's abstraction is
    # unused, a warning each. validate reports them, with positions (a second, positioned
    # load); the solvers drop warnings, so load_checked keeps the plain load.
    one_schema = [REPO / "schemas" / "disc_loading.yaml"]
    _, reported = load_reported(
        lambda p: loader.load_split([REPO / "libraries"], one_schema, positions=p)
    )
    assert reported and all(p.severity is Severity.WARNING for p in reported)
    assert all(p.span.line > 0 for p in reported)
    positioned.clear()  # that was validate's positioned load; now the solvers' load
    loaded = loader.load_checked([REPO / "libraries"], one_schema)
    assert not positioned
    assert [s.name for s in loaded.schemas] == ["disc_loading"]
    assert all(c.span == NOWHERE for c in loaded.library)


@pytest.mark.parametrize("case", INVALID, ids=lambda p: p.name)
def test_an_invalid_case_is_loaded_again_with_positions(case: Path) -> None:
    loaded, problems = load_reported(lambda p: load_paths([case], positions=p))
    assert problems
    assert all(p.span.line > 0 for p in problems)  # none at NOWHERE
    assert all(c.span != NOWHERE for lib in loaded.libraries for c in lib)


def _reports_agree(runner: CliRunner, where: Path, strict: bool = False) -> Any:
    """Assert ``validate . --format json`` in ``where`` is what the positioned load reports.

    Returns the report, parsed.
    """
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(where)
        args = ["validate", ".", "--format", "json", *(["--strict"] if strict else [])]
        result = runner.invoke(app, args)
        only = load_paths([Path()])
        problems = sorted([*only.problems, *loader.check_loaded(only)])
    assert result.stdout == REPORTERS[OutputFormat.JSON].render(only.files, problems, only.note)
    return json.loads(result.stdout)


@pytest.mark.parametrize("case", INVALID, ids=lambda p: p.name)
def test_validate_json_is_what_it_was_before_the_plain_path(runner: CliRunner, case: Path) -> None:
    report = _reports_agree(runner, case)
    assert report["valid"] is False
    assert json.dumps(report, indent=2) + "\n" == (case / "expected.json").read_text("utf-8")


def _checkout_copy(tmp_path: Path) -> Path:
    for folder in CHECKOUT:
        shutil.copytree(folder, tmp_path / folder.name)
    return tmp_path


def test_a_todo_mark_alone_is_reported_with_its_position(runner: CliRunner, tmp_path: Path) -> None:
    # A warning, not an error: the plain load would have succeeded, yet the mark is reported
    # from the positioned load, at its line.
    where = _checkout_copy(tmp_path)
    lib = where / "libraries" / "robot_arms.yaml"
    lines = lib.read_text(encoding="utf-8").splitlines(keepends=True)
    lines.insert(3, "# TODO: check the arm's joints\n")
    lib.write_text("".join(lines), encoding="utf-8")
    report = _reports_agree(runner, where)
    [todo] = report["problems"]
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
    schema.write_text(
        text.replace(edge, edge + "  - {consumer: perception, providers: [camera]}\n")
    )
    report = _reports_agree(runner, where, strict=True)
    [dup] = report["problems"]
    assert (dup["code"], dup["severity"]) == ("duplicate-edge", "warning") and dup["line"] > 0


def test_a_semantic_problem_across_clean_files_is_reported_with_positions(
    runner: CliRunner, tmp_path: Path
) -> None:
    # Every file is clean on its own (the plain pass builds them all); the problem shows
    # only in the semantic checks of the whole, which then sends everything back to be
    # loaded with positions.
    where = _checkout_copy(tmp_path)
    shutil.copy(where / "libraries" / "robot_arms.yaml", where / "libraries" / "again.yaml")
    report = _reports_agree(runner, where)
    codes = {p["code"] for p in report["problems"]}
    assert "duplicate-component" in codes
    assert all(p["line"] > 0 for p in report["problems"])


def test_the_builder_does_not_guess_the_text_of_a_number() -> None:
    # Plain data has the float 1.0 where the tree keeps "1.0" as written: a name built from
    # plain data would be "1.0" or "1" by guess. The builder asks for the tree instead.
    text = (REPO / "libraries" / "robot_arms.yaml").read_bytes()
    plain: Any = ys.parse_plain_only(text, "robot_arms.yaml")
    assert isinstance(plain, dict)
    plain["components"][0]["name"] = 1.0
    with pytest.raises(NeedsPositions):
        build_library(plain, "robot_arms.yaml")
    schema: Any = ys.parse_plain_only((REPO / "schemas" / "disc_loading.yaml").read_bytes(), "s")
    assert isinstance(schema, dict)
    schema["roles"][0]["abstraction"] = True
    with pytest.raises(NeedsPositions):
        build_schema(schema, "s")


@pytest.mark.parametrize(
    "data",
    [b"\xff\xfe", b"a: 1\n", b"format: 1\n", b"format: rosreconf/component-library\n"],
    ids=["not-utf8", "no-format", "numeric-format", "structure"],
)
def test_every_file_problem_sends_the_load_back(tmp_path: Path, data: bytes) -> None:
    (tmp_path / "lib.yaml").write_bytes(data)
    with pytest.raises(NeedsPositions):
        load_paths([tmp_path], positions=False)
