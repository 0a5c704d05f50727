"""``whatif`` on the paper's example, and against brute force on a generated library."""

from __future__ import annotations

import itertools
import json
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.analysis.whatif import analyse, sweep
from rosreconf.cli.app import app
from rosreconf.formats.loader import load_bundled, load_paths
from rosreconf.model import Configuration
from rosreconf.model.validity import is_valid
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.synthetic import generate, write


def test_paper_example_critical_parts(
    runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)  # no libraries/ here: the bundled example
    with_cwd = runner.invoke(app, ["whatif", "--json"])
    assert with_cwd.exit_code == 0, with_cwd.output
    doc = {s["name"]: s for s in json.loads(with_cwd.stdout)["schemas"]}
    disc = set(doc["disc_loading"]["critical"])
    assert {f"NSM{i}" for i in range(1, 6)} | {f"NFB2{i}" for i in range(1, 5)} | {"NREA"} <= disc
    assert doc["object_repositioning"]["critical"] == ["NREA"]
    pairs = [set(p) for p in doc["object_repositioning"]["critical_pairs"]]
    assert {"NCA1", "NCA2"} in pairs
    assert {"NDC1", "NSM1"} in pairs


def test_matches_brute_force_on_generated_library(tmp_path: Path) -> None:
    write(generate(12, 3, 0.5, seed=5), tmp_path)
    loaded = load_paths([tmp_path / "libraries", tmp_path / "schemas"])
    library, schema = loaded.library, loaded.schemas[0]
    with ProcessPoolExecutor(max_workers=2) as pool:
        report = analyse(library, schema, 2, pool, chunk_size=4)
    names = [c.name for c in library]
    assert report.listed_all  # few enough sets to list them all
    decided = {frozenset(o.failed): o for o in report.listed}
    for k in (1, 2):
        alive = 0
        for failed in itertools.combinations(names, k):
            n = count(compile_instance(library, schema, failed))
            alive += n > 0
            key = frozenset(failed)
            if key in decided:
                outcome = decided[key]
                assert outcome.survives == (n > 0), failed
                if outcome.configuration:
                    roles = [r.name for r in schema.graph.roles]
                    mapping = dict(zip(roles, outcome.configuration, strict=True))
                    config = Configuration.of(schema.name, mapping, schema.graph.roles)
                    assert is_valid(config, library, schema, failed)
        assert report.survived(k) == (alive, len(list(itertools.combinations(names, k))))


def test_bundled_in_process_without_pool() -> None:
    loaded = load_bundled()
    schema = next(s for s in loaded.schemas if s.name == "object_repositioning")
    report = analyse(loaded.library, schema, 1)
    assert report.critical == ["NREA"]


def test_sweep_runs_every_schema_on_one_pool_and_reports_progress_per_schema() -> None:
    loaded = load_bundled()
    calls: list[tuple[str, int]] = []
    reports = sweep(
        loaded.library,
        loaded.schemas,
        2,
        workers=2,
        progress=lambda schema, decided: calls.append((schema.name, decided)),
    )
    assert [r.schema for r in reports] == [s.name for s in loaded.schemas]
    starts = [name for name, decided in calls if decided == 0]
    assert starts[: len(loaded.schemas)] == [s.name for s in loaded.schemas]
    for schema, report in zip(loaded.schemas, reports, strict=True):
        alone = analyse(loaded.library, schema, 2)  # in process, no pool
        assert [(o.failed, o.survives) for o in report.listed] == [
            (o.failed, o.survives) for o in alone.listed
        ]
        told = [decided for name, decided in calls if name == schema.name]
        assert told[0] == 0  # the schema's start, before any set is decided
        # Every failure set but the empty one is told once, whether pruned or solved.
        assert sum(told) == len(report.listed) - 1
