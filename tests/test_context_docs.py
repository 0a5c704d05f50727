"""docs/context.md's console examples are what the commands print now."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from typer.testing import CliRunner

from rosreconf.cli.app import app

REPO = Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"```console\n(.*?)```", re.S)


def examples() -> list[tuple[list[str], str]]:
    """Return each console block's command (without ``rosreconf``) and the output shown."""
    out = []
    for block in BLOCK.findall((REPO / "docs" / "context.md").read_text(encoding="utf-8")):
        lines = block.splitlines()
        command = lines.pop(0).removeprefix("$ ")
        while command.endswith("\\"):
            command = command[:-1] + lines.pop(0).strip()
        out.append((shlex.split(command)[1:], "\n".join(lines) + "\n"))
    return out


@pytest.mark.parametrize("args, shown", examples(), ids=lambda v: str(v)[:30])
def test_the_example_prints_what_the_page_shows(
    runner: CliRunner, args: list[str], shown: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(REPO)
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.stderr
    if shown.startswith("...\n"):  # the page shows the end only
        assert result.stdout.rstrip("\n").endswith(shown[4:].rstrip("\n"))
    else:
        assert result.stdout.rstrip("\n") == shown.rstrip("\n")
