"""Property: no input makes ``rosreconf validate`` crash, hang or write a file.

Arbitrary bytes, arbitrary YAML documents, and random damage to the real bundled library
must all end in exit 0, 1 or 2 with a report, never a traceback.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from rosreconf.cli.app import app

REPO = Path(__file__).resolve().parent.parent
LIBRARY = (REPO / "libraries" / "robot_arms.yaml").read_text(encoding="utf-8")
FUZZ = settings(
    max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)


def _validate(folder: Path, name: str, data: bytes) -> None:
    (folder / name).write_bytes(data)
    before = sorted(os.listdir(folder))
    result = CliRunner().invoke(app, ["validate", str(folder / name), "--format", "json"])
    assert result.exit_code in (0, 1, 2), result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(
        result.exception
    )
    assert "Traceback" not in result.output
    assert sorted(os.listdir(folder)) == before, "validate wrote a file"


@FUZZ
@given(data=st.binary(max_size=2048))
def test_arbitrary_bytes(tmp_path: Path, data: bytes) -> None:
    _validate(tmp_path, "bytes.yaml", data)


scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.floats(allow_nan=True),
    st.text(max_size=20),
    st.sampled_from(["no", "on", "0755", "1e3", "~", "NSM3", "rosreconf/component-library"]),
)
documents: st.SearchStrategy[Any] = st.recursive(
    scalars,
    lambda children: st.one_of(
        st.lists(children, max_size=5),
        st.dictionaries(
            st.sampled_from(
                [
                    "format",
                    "version",
                    "name",
                    "components",
                    "provides",
                    "requires",
                    "roles",
                    "edges",
                    "any_of",
                    "service",
                    "topic",
                    "type",
                    "abstraction",
                    "x",
                ]
            ),
            children,
            max_size=6,
        ),
    ),
    max_leaves=30,
)


@FUZZ
@given(doc=documents)
def test_arbitrary_yaml(tmp_path: Path, doc: Any) -> None:
    _validate(tmp_path, "doc.yaml", yaml.safe_dump(doc, allow_unicode=True).encode())


@FUZZ
@given(
    cut=st.integers(min_value=0, max_value=len(LIBRARY)),
    junk=st.text(max_size=12),
)
def test_damaged_real_library(tmp_path: Path, cut: int, junk: str) -> None:
    damaged = LIBRARY[:cut] + junk + LIBRARY[cut + len(junk) :]
    _validate(tmp_path, "robot_arms.yaml", damaged.encode("utf-8", errors="surrogatepass"))
