"""The test suite's own rules: deterministic property tests, missing tools fail, no skips.

`make test` must give the same verdict on every clean checkout, every time; these tests keep
the rules in tests/conftest.py from being undone quietly.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from pathlib import Path

import conftest
import pytest
from hypothesis import settings

TESTS = Path(__file__).resolve().parent


@pytest.fixture
def fresh_tool_checks() -> Iterator[None]:
    """Forget the cached tool checks before and after, so that each sees this test's PATH."""
    conftest._tool_present.cache_clear()
    yield
    conftest._tool_present.cache_clear()


def test_a_missing_tool_fails_the_test_and_never_skips_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fresh_tool_checks: None
) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))  # no dot, no roscore
    for marker in ("graphviz", "ros"):
        with pytest.raises(pytest.fail.Exception) as failed:
            conftest.require_tool(marker)
        assert "make system-deps" in str(failed.value)
        assert f"-m 'not {marker}'" in str(failed.value)


def test_installed_tools_pass_the_rule(fresh_tool_checks: None) -> None:
    for marker in conftest.TOOLS:
        conftest.require_tool(marker)  # `make test` installs them all


def test_every_tool_marker_is_registered_with_pytest(pytestconfig: pytest.Config) -> None:
    declared = {line.split(":")[0] for line in pytestconfig.getini("markers")}
    assert set(conftest.TOOLS) <= declared


def test_no_test_skips_itself() -> None:
    # Skipping hides a test that did not run; a missing tool fails through require_tool.
    banned = re.compile(r"pytest\.skip\(|importorskip|mark\.skip|skipif|pytest\.xfail|mark\.xfail")
    offenders = [
        f"{path.name}:{number}: {line.strip()}"
        for path in sorted(TESTS.rglob("*.py"))
        if path.name != Path(__file__).name
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if banned.search(line)
    ]
    assert offenders == []


def test_the_default_hypothesis_profile_is_deterministic() -> None:
    ci = settings.get_profile("ci")
    assert ci.derandomize and ci.database is None and ci.deadline is None
    if "HYPOTHESIS_PROFILE" not in os.environ:  # a plain `pytest`
        assert settings.default.derandomize and settings.default.database is None


def test_make_test_selects_the_deterministic_profile() -> None:
    makefile = (TESTS.parent / "Makefile").read_text(encoding="utf-8")
    [recipe] = re.findall(r"^pytest:.*\n\t(.*)$", makefile, flags=re.MULTILINE)
    assert "HYPOTHESIS_PROFILE=ci" in recipe
