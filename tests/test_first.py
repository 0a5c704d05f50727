"""The first configuration from counting's tables is clingo's first, and valid.

``optimum.first`` replaces clingo's grounding for ``enumerate --limit 1`` and ``--graph``;
enumeration order is defined (roles in schema order, candidates in library order), so the
two must return the very same configuration, and both the brute-force lexicographic least.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from randomlib import brute_force, problems

from rosreconf.formats.loader import load_paths
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.validity import is_valid
from rosreconf.solve.factors import TooHard
from rosreconf.solve.instance import Instance, compile_instance
from rosreconf.solve.optimum import first
from rosreconf.solve.solver import ClingoEngine, first_configuration
from rosreconf.synthetic import generate, write


def _lex_key(inst: Instance, assignment: dict[str, str]) -> list[int]:
    """Return a configuration's place in enumeration order (domain positions, role by role)."""
    out = []
    for role, dom in zip(inst.roles, inst.domains, strict=True):
        out.append([c.name for c in dom].index(assignment[role.name]))
    return out


@settings(max_examples=200, deadline=None)
@given(problem=problems(), data=st.data())
def test_first_is_clingos_first_and_the_least_valid_configuration(
    problem: tuple[ComponentLibrary, InteroperabilitySchema], data: st.DataObject
) -> None:
    library, schema = problem
    names = [c.name for c in library]
    failed = frozenset(data.draw(st.sets(st.sampled_from(names), max_size=1)))
    inst = compile_instance(library, schema, failed)
    ours = first(inst)
    reference = ClingoEngine().first(inst)
    configs = brute_force(library, schema, failed)
    assert ours == reference
    assert first_configuration(inst) == reference
    if not configs:
        assert ours is None
        return
    assert ours is not None and is_valid(ours, library, schema, failed)
    least = min(configs, key=lambda c: _lex_key(inst, dict(c.assignment)))
    assert ours == least


@pytest.mark.parametrize(("roles", "candidates"), [(20, 3), (60, 10)])
def test_first_equals_clingo_on_generated_libraries(
    roles: int, candidates: int, tmp_path: Path
) -> None:
    write(generate(roles, candidates, 0.2, seed=3), tmp_path)
    loaded = load_paths([tmp_path / "libraries", tmp_path / "schemas"])
    inst = compile_instance(loaded.library, loaded.schemas[0])
    ours = first(inst)
    assert ours is not None and ours == ClingoEngine().first(inst)
    assert is_valid(ours, loaded.library, loaded.schemas[0])


def test_first_configuration_falls_back_to_clingo_when_tables_are_too_big(tmp_path: Path) -> None:
    write(generate(20, 3, 0.2, seed=3), tmp_path)
    loaded = load_paths([tmp_path / "libraries", tmp_path / "schemas"])
    inst = compile_instance(loaded.library, loaded.schemas[0])
    with pytest.raises(TooHard):
        first(inst, max_rows=0)
    assert first_configuration(inst, max_rows=0) == ClingoEngine().first(inst)
