"""whatif decides failures of components with a working twin without a solve per failure.

``whatif -k 1`` on a hub of 10^4 consumers took over 300 s (issue 22): every consumer is in
the first configuration, so every single failure went to clingo. A failed component whose
role has an interchangeable candidate (``rosreconf.solve.swaps``) is now swapped for it. The
answers are held here to the independent references: one clingo solve per failure set
(``whatif.evaluate_chunk``, the path every set took before) and a count per failure set, and every
configuration given is checked valid under its failures by ``validity.is_valid``.
"""

from __future__ import annotations

import itertools
from pathlib import Path

from shapes import write_hub

from rosreconf.analysis.whatif import (
    Chunk,
    Outcome,
    SchemaReport,
    analyse,
    evaluate_chunk,
    make_task,
)
from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.validity import is_valid
from rosreconf.solve.counting import count
from rosreconf.solve.instance import compile_instance
from rosreconf.synthetic import generate, write


def _load(folder: Path) -> tuple[ComponentLibrary, InteroperabilitySchema]:
    loaded = load_paths([folder / "libraries", folder / "schemas"])
    return loaded.library, loaded.schemas[0]


def _valid(outcome: Outcome, library: ComponentLibrary, schema: InteroperabilitySchema) -> bool:
    assert outcome.configuration is not None
    roles = schema.graph.roles
    mapping = dict(zip((r.name for r in roles), outcome.configuration, strict=True))
    config = Configuration.of(schema.name, mapping, roles)
    return is_valid(config, library, schema, outcome.failed)


def _decided(report: SchemaReport) -> dict[frozenset[str], Outcome]:
    assert report.listed_all
    return {frozenset(o.failed): o for o in report.listed}


def test_whatif_k1_on_a_hub_of_120_consumers_equals_one_solve_per_failure(
    tmp_path: Path,
) -> None:
    """Case: whatif -k 1 on a hub of 10^4 consumers, one clingo solve per failure (>300 s)."""
    library, schema = _load(write_hub(tmp_path, 120))
    report = analyse(library, schema, 1)
    # the reference: one clingo solve per failure (one grounding for all)
    sets = tuple((c.name,) for c in library)
    solved = evaluate_chunk(Chunk(make_task(library, schema), sets))
    decided = _decided(report)
    assert len(decided) == 1 + len(library)  # every component is in some configuration
    for reference in solved:
        outcome = decided[frozenset(reference.failed)]
        assert outcome.survives == reference.survives, reference.failed
        assert _valid(outcome, library, schema), reference.failed
    assert report.critical == []
    assert report.survived(1) == (len(library), len(library))


def test_whatif_k2_on_a_hub_with_two_twins_per_role_equals_a_count_per_pair(
    tmp_path: Path,
) -> None:
    """The pairs that take both twins of a role kill it: the solver must still find them."""
    library, schema = _load(write_hub(tmp_path, 20))
    report = analyse(library, schema, 2)
    decided = _decided(report)
    names = [c.name for c in library]
    dead = []
    for failed in itertools.combinations(names, 2):
        alive = count(compile_instance(library, schema, failed)) > 0
        outcome = decided[frozenset(failed)]
        assert outcome.survives == alive, failed
        if alive:
            assert _valid(outcome, library, schema), failed
        else:
            dead.append(failed)
    assert report.critical_pairs == dead
    assert dead == [(f"{r}_C0", f"{r}_C1") for r in ["HUB", *(f"C{i}" for i in range(20))]]


def test_whatif_k2_with_three_twins_per_role_swaps_in_the_third(tmp_path: Path) -> None:
    library, schema = _load(write_hub(tmp_path, 12, k=3))
    report = analyse(library, schema, 2)
    decided = _decided(report)
    for failed in itertools.combinations([c.name for c in library], 2):
        outcome = decided[frozenset(failed)]
        assert outcome.survives, failed  # a third candidate is left in every role
        assert _valid(outcome, library, schema), failed
    assert report.critical == [] and report.critical_pairs == []


def test_whatif_k2_on_a_generated_library_with_twins_and_couplings_equals_a_count_per_set(
    tmp_path: Path,
) -> None:
    """Generated roles mix twins with candidates of other interfaces, and couplings."""
    write(generate(14, 4, 0.4, seed=11), tmp_path)
    library, schema = _load(tmp_path)
    report = analyse(library, schema, 2)
    decided = _decided(report)
    names = [c.name for c in library]
    for k in (1, 2):
        alive = 0
        for failed in itertools.combinations(names, k):
            survives = count(compile_instance(library, schema, failed)) > 0
            alive += survives
            outcome = decided.get(frozenset(failed))
            if outcome is not None:  # sets over relevant components only are listed
                assert outcome.survives == survives, failed
                if survives:
                    assert _valid(outcome, library, schema), failed
        assert report.survived(k) == (alive, len(list(itertools.combinations(names, k))))


def test_whatif_configurations_do_not_depend_on_which_sets_a_worker_solved_before(
    tmp_path: Path,
) -> None:
    """A worker keeps its ground program between chunks: each set's answer stays its own."""
    write(generate(14, 4, 0.4, seed=11), tmp_path)
    library, schema = _load(tmp_path)
    task = make_task(library, schema)
    names = [c.name for c in library]
    sets = tuple(itertools.combinations(names, 2))
    forward = evaluate_chunk(Chunk(task, sets))
    backward = evaluate_chunk(Chunk(task, sets[::-1]))[::-1]
    alone = [evaluate_chunk(Chunk(make_task(library, schema), (s,)))[0] for s in sets[:40]]
    assert [o.configuration for o in forward] == [o.configuration for o in backward]
    assert [o.configuration for o in forward[:40]] == [o.configuration for o in alone]
    assert any(o.survives for o in forward) and any(not o.survives for o in forward)
