"""Files a hostile or careless user writes, through every command that reads files (issue 30).

Each runs as a real process: the user must see one ``file:line:column`` error and exit 1, and
no Python traceback, whichever command read the file.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent

READING = [
    ["validate"],
    ["enumerate"],
    ["analyse"],
    ["graph", "-o", "out"],
    ["launch", "--ros2", "-o", "out.launch.py"],
    ["render-pddl", "-o", "out"],
    ["plan", "--fail", "NSM3"],
    ["whatif"],
    ["simulate"],
    ["watch"],
]
"""Every command that reads a library, with the options it needs to get as far as reading."""


def _run(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    cmd = [sys.executable, "-m", "rosreconf", *args]
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=60)


def _one_error(done: subprocess.CompletedProcess[str], where: str, words: str) -> None:
    """Assert exit 1, no traceback, and exactly one error line, at ``where``, saying ``words``."""
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert "Traceback" not in output, output
    errors = [line for line in output.splitlines() if ": error: " in line]
    assert len(errors) == 1, output
    assert errors[0].startswith(where), errors
    assert words in errors[0], errors


@pytest.mark.parametrize("command", READING, ids=lambda c: c[0])
def test_a_mapping_as_a_mapping_key_is_one_error_in_every_command(
    tmp_path: Path, command: list[str]
) -> None:
    """``? {a: [b]}`` (11 bytes): a mapping key that is a mapping; once a traceback in each."""
    (tmp_path / "hostile.yaml").write_bytes(b"? {a: [b]}\n")
    done = _run([*command, "--library", "hostile.yaml"], tmp_path)
    _one_error(done, "hostile.yaml:1:3: error: ", "a mapping key must be a plain value")
    assert not (tmp_path / "out.launch.py").exists()


TYPO = "{service: visual_perception, type: r?obot_arm_msgs/VisualPerception}"
OK = "{service: visual_perception, type: robot_arm_msgs/VisualPerception}"
WHERE = {
    "provides": ("provides[0]", f"provides: [{TYPO}]"),
    "requires": ("requires[0]", f"requires: [{TYPO}]"),
    "any_of": ("requires[0].any_of[1]", f"requires: [{{any_of: [{OK}, {TYPO}]}}]"),
}
"""The same typo in a type, as a provision, a requirement and a requirement's option."""


@pytest.mark.parametrize("where", WHERE)
def test_a_typo_in_a_type_is_that_types_problem_wherever_it_is_written(
    tmp_path: Path, where: str
) -> None:
    """Inside a requirement or an ``any_of`` option, as under ``provides``: the type's problem,
    at the type's column, in the same words. A requirement once got "missing required key
    'any_of'" at the item (the alternative it was not written as)."""
    path, entry = WHERE[where]
    line = f"    {entry}\n"
    (tmp_path / "lib.yaml").write_text(
        "format: rosreconf/component-library\nversion: 1\nname: lib\ncomponents:\n"
        f"  - name: A\n    abstraction: a\n{line}"
    )
    column = line.index("r?obot") + 1
    for command in (["validate", "lib.yaml"], ["enumerate", "--library", "lib.yaml"]):
        done = _run(command, tmp_path)
        _one_error(
            done,
            f"lib.yaml:7:{column}: error: 'components[0].{path}.type' text "
            "'r?obot_arm_msgs/VisualPerception' is not valid (a ROS type written package/Type",
            "",
        )


ESCAPES = "\x1b[2J\x1b]0;owned\x07\u202e"
"""Clear the screen, retitle the terminal, ring the bell, reverse the text that follows."""


def test_escape_sequences_in_a_path_are_shown_never_sent_to_the_terminal(tmp_path: Path) -> None:
    bad = tmp_path / f"lib{ESCAPES}.yaml"
    bad.write_text("components: [\n")
    shown = f"lib{ESCAPES.encode('unicode_escape').decode()}.yaml"
    for args, stream in (
        (["validate", "-l", str(bad)], "stdout"),  # the report's file:line:column line
        (["enumerate", "-l", str(bad)], "stderr"),  # the same problem, as an error
        (["validate", "-l", str(tmp_path / f"gone{ESCAPES}.yaml")], "stderr"),
        (["graph", "-o", str(tmp_path / f"no{ESCAPES}" / "g.dot")], "stderr"),
    ):
        done = _run(args, tmp_path)
        out = getattr(done, stream)
        assert done.returncode in (1, 2), (args, done.returncode, done.stderr)
        assert not any(c in done.stdout + done.stderr for c in "\x1b\x07\u202e"), (args, out)
        assert "\\x1b[2J" in out and "\\x07" in out and "\\u202e" in out, (args, out)
    assert shown in _run(["validate", "-l", str(bad)], tmp_path).stdout
