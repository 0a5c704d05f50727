"""Shared fixtures: the CLI runner with a pinned console width, and the case folders."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner


@pytest.fixture
def runner() -> CliRunner:
    """Return a CLI runner; stdout and stderr are kept apart so JSON can be parsed."""
    return CliRunner(env={"COLUMNS": "200", "NO_COLOR": "1"})
