"""Plain scalars resolve by YAML 1.2's core schema, whichever test decides them first.

``nodes.resolve_plain`` orders its tests for speed (names by their first character,
then numbers); these are the core schema's own examples (YAML 1.2.2, 10.3.2) and the
spellings YAML 1.1 read otherwise, so a reordering that changes an answer fails here.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rosreconf.formats.loader import load_paths, problems_of
from rosreconf.formats.nodes import Scalar, resolve_plain

CORE_SCHEMA: list[tuple[str, Scalar]] = [
    ("", None),
    ("~", None),
    ("null", None),
    ("Null", None),
    ("NULL", None),
    ("true", True),
    ("True", True),
    ("TRUE", True),
    ("false", False),
    ("FALSE", False),
    ("0", 0),
    ("-19", -19),
    ("+12", 12),
    ("0755", 755),  # YAML 1.1 read octal 493
    ("0o14", 12),
    ("0xC", 12),
    ("0x1f", 31),
    ("1.", 1.0),
    ("0.", 0.0),
    ("-0.0", -0.0),
    (".5", 0.5),
    ("+12e03", 12000.0),
    ("-2E+05", -200000.0),
    ("1e5", 100000.0),
    ("0.0416", 0.0416),
    (".inf", math.inf),
    ("-.Inf", -math.inf),
    ("+.INF", math.inf),
    ("no", "no"),  # YAML 1.1 booleans stay text
    ("yes", "yes"),
    ("on", "on"),
    ("off", "off"),
    ("y", "y"),
    ("nan", "nan"),
    ("inf", "inf"),
    ("1_000", "1_000"),  # YAML 1.1 and Python allow the underscores, YAML 1.2 does not
    ("0b101", "0b101"),
    ("0o8", "0o8"),
    ("0xG", "0xG"),
    ("1.2.3", "1.2.3"),
    ("+", "+"),
    ("-", "-"),
    (".", "."),
    ("1e", "1e"),
    ("- 1", "- 1"),
    ("12:30", "12:30"),  # YAML 1.1 read sexagesimal 750
    ("2001-12-14", "2001-12-14"),  # no timestamps
    ("~x", "~x"),
    ("nulls", "nulls"),
    ("truex", "truex"),
    ("SEN0_C0", "SEN0_C0"),
]


@pytest.mark.parametrize(("text", "value"), CORE_SCHEMA)
def test_core_schema(text: str, value: Scalar) -> None:
    got = resolve_plain(text)
    assert type(got) is type(value)
    assert got == value


@pytest.mark.parametrize("text", [".nan", ".NaN", ".NAN"])
def test_not_a_number(text: str) -> None:
    got = resolve_plain(text)
    assert isinstance(got, float) and math.isnan(got)


def test_an_integer_too_long_for_int_is_infinite() -> None:
    assert resolve_plain("9" * 5000) == math.inf
    assert resolve_plain("-" + "9" * 5000) == -math.inf


@pytest.mark.parametrize("spelling", ["1_000", "0b101", "+0x1F", "0O17", ".iNf", "1" * 4100])
def test_a_number_only_yaml_1_1_or_python_reads_so_is_refused_as_yaml_1_2_reads_it(
    tmp_path: Path, spelling: str
) -> None:
    """A metric written ``1_000`` is text in YAML 1.2: refused at its line, not read as 1000."""
    library = tmp_path / "lib.yaml"
    library.write_text(
        "format: rosreconf/component-library\nversion: 1\nname: lib\ncomponents:\n"
        "  - name: A\n    abstraction: a\n    metrics:\n"
        f"      cost: {spelling}\n"
    )
    problems = problems_of(load_paths([library]))
    expected = "not-finite" if spelling.startswith("1111") else "wrong-type"
    assert [(p.code, p.span.line, p.span.column) for p in problems] == [(expected, 8, 13)]


def _metric_library(tmp_path: Path, key: str) -> Path:
    library = tmp_path / "lib.yaml"
    library.write_text(
        "format: rosreconf/component-library\nversion: 1\nname: lib\ncomponents:\n"
        f"  - name: A\n    abstraction: a\n    metrics:\n      {key}: 5.0\n"
    )
    return library


@pytest.mark.parametrize("key", ["1", "0x1F"])
def test_a_key_yaml_reads_as_a_number_is_refused_at_its_line_as_written(
    tmp_path: Path, key: str
) -> None:
    """A metric named ``1`` is the text '1' to rosreconf, refused by the name pattern at 8:7."""
    problems = problems_of(load_paths([_metric_library(tmp_path, key)]))
    assert [(p.code, p.span.line, p.span.column) for p in problems] == [("bad-name", 8, 7)]


@pytest.mark.parametrize("key", ["true", "null", "no"])
def test_a_key_yaml_reads_as_a_boolean_or_null_is_a_name_as_written(
    tmp_path: Path, key: str
) -> None:
    """A metric named ``true`` or ``null`` is named so, as written (keys are never resolved)."""
    loaded = load_paths([_metric_library(tmp_path, key)])
    assert problems_of(loaded) == []
    assert dict(loaded.library.components[0].metrics) == {key: 5.0}
