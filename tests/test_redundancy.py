"""Theorem 10: exact answer, the paper's approximation, and the asymptotics."""

from __future__ import annotations

import itertools
import math

import pytest
from typer.testing import CliRunner

from rosreconf.analysis.redundancy import redundancy, survival
from rosreconf.cli.app import app
from rosreconf.errors import UsageError


@pytest.mark.parametrize(("p", "n", "q"), [(0.05, 100, 0.999), (0.3, 10, 0.9), (0.01, 5000, 0.99)])
def test_smallest_integer_and_root(p: float, n: int, q: float) -> None:
    a = redundancy(p, n, q)
    assert survival(p, a.r_needed, n) >= q
    assert a.r_needed == 1 or survival(p, a.r_needed - 1, n) < q
    assert math.isclose(survival(p, a.r_exact, n), q, rel_tol=1e-9)
    assert math.isclose(a.error, a.r_approx - a.r_exact)


def test_grows_like_log_n_for_fixed_q() -> None:
    p, q = 0.1, 0.99
    ns = [10**k for k in range(1, 8)]
    rs = [redundancy(p, n, q).r_exact for n in ns]
    slopes = [(b - a) / math.log(10) for a, b in itertools.pairwise(rs)]
    # r ~ log N / (-log p): the slope against log N tends to 1 / -log p.
    assert math.isclose(slopes[-1], 1 / -math.log(p), rel_tol=1e-3)
    assert all(b > a for a, b in itertools.pairwise(rs))


def test_grows_like_log_log_inverse_q_for_fixed_n() -> None:
    p, n = 0.1, 50
    qs = [1 - 10.0**-k for k in range(2, 13)]
    rs = [redundancy(p, n, q).r_exact for q in qs]
    ll = [-math.log(math.log(1 / q)) for q in qs]
    ratio = [(rs[i + 1] - rs[i]) / (ll[i + 1] - ll[i]) for i in range(len(qs) - 1)]
    assert math.isclose(ratio[-1], 1 / -math.log(p), rel_tol=1e-3)


def test_approximation_error_shrinks_as_q_goes_to_one() -> None:
    errors = [abs(redundancy(0.2, 20, 1 - 10.0**-k).relative_error) for k in (1, 3, 6)]
    assert errors[0] > errors[1] > errors[2]


@pytest.mark.parametrize(("p", "q"), [(0.0, 0.9), (1.0, 0.9), (1.5, 0.9), (0.1, 1.0), (0.1, 0.0)])
def test_rejects_out_of_range(p: float, q: float) -> None:
    with pytest.raises(UsageError):
        redundancy(p, 10, q)


def test_cli_exit_codes(runner: CliRunner) -> None:
    ok = runner.invoke(app, ["redundancy", "--p", "0.05", "--n", "100", "--q", "0.999"])
    assert ok.exit_code == 0 and "redundancy needed r        4" in ok.stdout
    bad = runner.invoke(app, ["redundancy", "--p", "2", "--n", "100", "--q", "0.999"])
    assert bad.exit_code == 2 and "strictly between 0 and 1" in bad.stderr
