"""The bundled example data, JSON Schemas and templates work from an installed wheel."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Build the wheel and install it (without dependencies) into a private target folder."""
    out = tmp_path_factory.mktemp("wheel")
    # Build from a clean copy: a developer's build/ or .venv must not leak into the wheel.
    source = out / "source"
    skip = shutil.ignore_patterns(
        ".venv",
        "build",
        "dist",
        ".git",
        "*.egg-info",
        "__pycache__",
        ".*_cache",
        ".hypothesis",
    )
    shutil.copytree(REPO, source, ignore=skip)
    build = [sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps"]
    build += ["--no-build-isolation", "-w", str(out / "dist"), str(source)]
    subprocess.run(build, check=True, cwd=out, capture_output=True)
    [wheel] = (out / "dist").glob("rosreconf-*.whl")
    target = out / "site"
    with zipfile.ZipFile(wheel) as zf:
        names = zf.namelist()
        zf.extractall(target)
    for expected in (
        "rosreconf/libraries/robot_arms.yaml",
        "rosreconf/schemas/object_repositioning.yaml",
        "rosreconf/data/component-library.schema.json",
        "rosreconf/data/output-enumerate.schema.json",
        "rosreconf/templates/domain.pddl.j2",
        "rosreconf/templates/problem.pddl.j2",
    ):
        assert expected in names
    # Every package of the checkout ships: a missing one would still import here through the
    # editable install's finder, so only this list shows it.
    for package in REPO.joinpath("rosreconf").rglob("__init__.py"):
        assert package.relative_to(REPO).as_posix() in names
    # Pure Python: nothing compiled, so one wheel serves every platform.
    assert wheel.name.endswith("-py3-none-any.whl")
    assert not [n for n in names if n.endswith((".so", ".pyd", ".c"))]
    return target


def _run(installed: Path, where: Path, *argv: str) -> subprocess.CompletedProcess[str]:
    """Run Python with only the installed wheel's rosreconf importable from ``where``."""
    env = {**os.environ, "PYTHONPATH": str(installed)}
    return subprocess.run(
        [sys.executable, *argv], cwd=where, env=env, capture_output=True, text=True, check=False
    )


def test_installed_wheel_runs_on_bundled_example(installed: Path, tmp_path: Path) -> None:
    result = _run(
        installed, tmp_path, "-m", "rosreconf", "enumerate", "--json", "--only", "disc_loading"
    )
    assert result.returncode == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["files"][0].startswith("<bundled>/")
    assert doc["schemas"][0]["count"] == 2
    probe = _run(installed, tmp_path, "-c", "import rosreconf.resources as r; print(r.__file__)")
    assert probe.stdout.startswith(str(installed))  # the wheel's copy, not the checkout's


def test_installed_wheel_renders_pddl_from_its_templates(installed: Path, tmp_path: Path) -> None:
    out = tmp_path / "pddl"
    result = _run(
        installed,
        tmp_path,
        "-m",
        "rosreconf",
        "render-pddl",
        "--only",
        "disc_loading",
        "-o",
        str(out),
    )
    assert result.returncode == 0, result.stderr
    domain = (out / "disc_loading" / "domain.pddl").read_text(encoding="utf-8")
    assert "(define (domain" in domain and "choose-elbow_joint-nsm3" in domain


def test_installed_wheel_reads_yaml_with_positions(installed: Path, tmp_path: Path) -> None:
    code = (
        "import json\n"
        "from rosreconf.formats import yamlsource\n"
        "tree, plain = yamlsource.read(b'a: [1, {b: no}]\\n', 'f.yaml')\n"
        "inner = tree.lookup(['a', 1, 'b'])\n"
        "print(json.dumps({'file': yamlsource.__file__, 'plain': plain,\n"
        "                  'at': list(tree.span(inner))}))\n"
    )
    result = _run(installed, tmp_path, "-c", code)
    assert result.returncode == 0, result.stderr
    probe = json.loads(result.stdout)
    assert probe["file"].startswith(str(installed))  # the wheel's reader, not the checkout's
    assert probe["plain"] == {"a": [1, {"b": "no"}]}  # YAML 1.2: 'no' is text
    assert probe["at"] == ["f.yaml", 1, 12]
