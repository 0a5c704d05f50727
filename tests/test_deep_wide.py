"""Deep and wide system graphs (issue 22): a long chain, a wide fan-in, a hub with many consumers.

``analyse`` raised RecursionError on a chain of 500 roles and on a fan-in of 2,000 providers
(the exact reliability expanded one component per Python frame), and took minutes on a hub
with 10,000 consumers (quadratic steps in the elimination). Each shape's answers are known in
closed form (``tests/shapes.py``): every role has two interchangeable candidates, so every
substitution is valid, no component is a single point of failure, and the schema survives
exactly when each role keeps one working candidate. Speed is in ``make bench``, not here.
"""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import pytest
from shapes import write_chain, write_fan_in, write_hub
from typer.testing import CliRunner

from rosreconf.analysis.reliability import exact_probability
from rosreconf.cli.app import app
from rosreconf.solve.factors import elimination_order


def _p(j: int) -> float:
    return 0.01 * (1 + j % 5)  # as tests/shapes.py writes them


def _analyse(folder: Path) -> dict[str, object]:
    result = CliRunner().invoke(
        app,
        ["analyse", "--json", "-l", str(folder / "libraries"), "-s", str(folder / "schemas")],
    )
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    [schema] = doc["schemas"]
    assert isinstance(schema, dict)
    return schema


@pytest.mark.parametrize(
    ("shape", "roles"),
    [(write_chain, 600), (write_fan_in, 300), (write_hub, 300)],
    ids=["chain_of_600_roles", "fan_in_of_300_providers", "hub_with_300_consumers"],
)
def test_analyse_on_a_deep_or_wide_schema_gives_the_closed_form(
    tmp_path: Path, shape: object, roles: int
) -> None:
    """Was RecursionError for the chain and the fan-in (a chain of 500 roles was enough)."""
    assert callable(shape)
    shape(tmp_path, roles)
    schema = _analyse(tmp_path)
    n = roles + (0 if shape is write_chain else 1)
    assert schema["valid"] == schema["substitutions"] == 2**n
    assert schema["single_points_of_failure"] == []
    reliability = schema["reliability"]
    assert isinstance(reliability, dict)
    survive = (1 - _p(0) * _p(1)) ** n  # each role: not both candidates failed
    assert reliability["probability"] == pytest.approx(survive, rel=1e-9)


def test_exact_probability_of_one_configuration_of_5000_components_is_the_product() -> None:
    """Was RecursionError: the expansion went one Python frame per component."""
    rng = random.Random(1)
    p = {f"c{i}": rng.uniform(0.0, 1e-3) for i in range(5000)}
    expected = math.prod(1 - q for q in p.values())
    assert exact_probability([frozenset(p)], p) == pytest.approx(expected, rel=1e-9)
    # two disjoint configurations 600 deep: P = 1 - (1 - a)(1 - b), by inclusion-exclusion
    half = [frozenset(f"c{i}" for i in range(k, 1200, 2)) for k in (0, 1)]
    a, b = (math.prod(1 - p[c] for c in h) for h in half)
    assert exact_probability(half, p) == pytest.approx(1 - (1 - a) * (1 - b), rel=1e-9)


def _reference_order(scopes: list[tuple[int, ...]], n: int) -> list[int]:
    """The elimination order by its definition: fewest neighbours, then the least index."""
    adjacent = [set[int]() for _ in range(n)]
    for scope in scopes:
        for v in scope:
            adjacent[v].update(set(scope) - {v})
    left = set(range(n))
    order = []
    while left:
        var = min(left, key=lambda v: (len(adjacent[v]), v))
        left.discard(var)
        order.append(var)
        for a in adjacent[var]:
            adjacent[a].discard(var)
            adjacent[a].update(adjacent[var] - {a})
    return order


def test_elimination_order_of_random_graphs_and_a_hub_is_the_definition() -> None:
    rng = random.Random(7)
    for _ in range(200):
        n = rng.randint(1, 30)
        scopes = [
            tuple(rng.sample(range(n), rng.randint(1, min(3, n))))
            for _ in range(rng.randint(0, 40))
        ]
        assert elimination_order(scopes, n) == _reference_order(scopes, n)
    hub: list[tuple[int, ...]] = [(0, i) for i in range(1, 300)]
    assert elimination_order(hub, 300) == _reference_order(hub, 300)
