"""analyse and whatif on many candidates for one role: the fast paths give the slow answers.

The fast paths (counting's marginals, Monte Carlo witnesses solved over one of each group of
interchangeable components) are what lets a 10,000-candidate role finish like counting; here
they are held to listing every configuration and to one count per failure state.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from manylib import write_many

from rosreconf.analysis import library as library_analysis
from rosreconf.analysis import whatif
from rosreconf.analysis.library import analyse
from rosreconf.analysis.marginals import marginals
from rosreconf.analysis.reliability import Twins, exact_probability, grouped_exact, most_reliable
from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.solve.solver import ClingoEngine

MID = 300
"""Perception candidates of the mid-sized library: every configuration can still be listed."""


def _many(tmp_path: Path, n: int) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    write_many(tmp_path, n)
    loaded = load_paths([tmp_path / "libraries", tmp_path / "schemas"])
    return loaded.library, loaded.schemas[0]


def test_analyse_on_many_candidates_equals_listing_every_configuration(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    library, schema = _many(tmp_path, MID)
    inst = compile_instance(library, schema)
    listed = list(ClingoEngine().configurations(inst))
    configs = [frozenset(c.components) for c in listed]
    result = analyse(library, schema)
    assert result.valid == len(listed) > 0
    for u, red in enumerate(result.redundancy):
        used = {c.assignment[u][1] for c in listed}
        assert red.usable == tuple(c for c in red.candidates if c in used)
    assert result.single_points_of_failure == sorted(frozenset.intersection(*configs))
    unmet = {f"PER_C{i}" for i in range(MID) if (i // 3) % 4 == 3}  # require sen_c
    assert {u.component for u in result.unusable} == unmet
    p = {c.name: c.failure_probability or 0.0 for c in library}
    exact = exact_probability(configs, p)
    assert result.reliability is not None
    assert result.reliability.probability == pytest.approx(exact, abs=1e-12)
    # The path a huge library takes (nothing listed): the same answers, and an interval
    # around the exact probability.
    monkeypatch.setattr(library_analysis, "EXACT_LIMIT", 0)
    sampled = analyse(library, schema, samples=4_000, seed=3)
    assert sampled.redundancy == result.redundancy
    assert sampled.single_points_of_failure == result.single_points_of_failure
    assert sampled.reliability is not None
    assert sampled.reliability.method.startswith("Monte Carlo")
    assert sampled.reliability.low <= exact <= sampled.reliability.high


def test_reliability_over_groups_of_interchangeable_components_is_the_listed_exact(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Too many configurations to list, few group configurations: still exact, and equal."""
    library, schema = _many(tmp_path, MID)
    configs = [
        frozenset(c.components)
        for c in ClingoEngine().configurations(compile_instance(library, schema))
    ]
    p = {c.name: c.failure_probability or 0.0 for c in library}
    limit = 200
    assert len(configs) > limit
    monkeypatch.setattr(library_analysis, "EXACT_LIMIT", limit)
    result = analyse(library, schema)
    assert result.reliability is not None
    assert "groups of interchangeable components" in result.reliability.method
    assert result.reliability.probability == pytest.approx(exact_probability(configs, p), abs=1e-12)
    failed = frozenset({"SEN_C0", "CTL_C2"})  # under failures too
    left = [c for c in configs if not c & failed]
    grouped = grouped_exact(library, schema, failed, p, limit)
    assert grouped is not None
    assert grouped[0] == pytest.approx(exact_probability(left, p), abs=1e-12)


def test_marginals_equal_per_candidate_counts_of_the_listing(tmp_path: Path) -> None:
    library, schema = _many(tmp_path, 60)
    failed = {"SEN_C2", "CTL_C1"}
    inst = compile_instance(library, schema, failed)
    marg = marginals(inst)
    expected = [dict.fromkeys((c.name for c in dom), 0) for dom in inst.domains]
    for config in ClingoEngine().configurations(inst):
        for u, (_, comp) in enumerate(config.assignment):
            expected[u][comp] += 1
    assert marg.per_role == expected
    assert marg.total == count(inst) == sum(expected[0].values())


def test_twins_decide_failure_states_as_the_whole_library_does(tmp_path: Path) -> None:
    """Solving over one of each group of alike components loses no surviving state."""
    library, schema = _many(tmp_path, 40)
    twins = Twins(library, schema)
    assert len(twins.groups) < len(library)
    p = {c.name: c.failure_probability or 0.0 for c in library}
    few = [c.name for c in library if not c.name.startswith("PER")]
    per = [c.name for c in library if c.name.startswith("PER")]
    rng = random.Random(7)
    outcomes = set()
    for _ in range(60):
        state = frozenset(rng.sample(few, rng.randint(0, 4)) + rng.sample(per, rng.randint(0, 30)))
        found = most_reliable(twins.survivors(state, p), schema, state, p)
        alive = count(compile_instance(library, schema, state)) > 0
        assert (found is not None) == alive, sorted(state)
        if found is not None:
            assert not found & state
        outcomes.add(alive)
    assert outcomes == {True, False}  # both kinds of state were tried


def test_whatif_one_failure_on_many_candidates_equals_one_count_per_component(
    tmp_path: Path,
) -> None:
    library, schema = _many(tmp_path, 80)
    report = whatif.analyse(library, schema, 1)
    for c in library:
        alive = count(compile_instance(library, schema, {c.name})) > 0
        key = frozenset({c.name})
        if key in report.outcomes:
            assert report.outcomes[key].survives == alive, c.name
        else:  # not relevant: in no configuration, so its failure changes nothing
            assert c.name not in report.relevant and alive
    base = count(compile_instance(library, schema))
    holding = {
        c
        for cfg in ClingoEngine().configurations(compile_instance(library, schema))
        for c in cfg.components
    }
    assert set(report.relevant) == holding and base > 0
    assert report.critical == [
        c for c in report.relevant if not count(compile_instance(library, schema, {c}))
    ]
