"""The file checks answer a clean document from its plain data alone, as the tree walks do.

The loader may build a document's positioned tree only when there is something to report:
``kind_of_plain``, ``structure_valid``, ``clean_values`` and ``repeated_edges`` say "nothing
to report" from the plain data, and ``kind_of``, ``structure_problems``, ``value_problems``
and ``duplicate_edges`` (which need the tree, for positions) say what. Each pair must agree.
"""

from __future__ import annotations

from pathlib import Path

from conftest import examples
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_values_fast import NUMBERS, PARAMETERS, _library

from rosreconf.errors import InvalidInputError
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.structure import (
    DocumentKind,
    kind_of,
    kind_of_plain,
    structure_problems,
    structure_valid,
)
from rosreconf.formats.values import clean_values, duplicate_edges, repeated_edges, value_problems

REPO = Path(__file__).resolve().parent.parent
YAML_FILES = sorted(
    [*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml"), *REPO.glob("tests/**/*.yaml")]
)


def _read(data: bytes) -> tuple[ys.YNode | None, ys.Plain] | None:
    try:
        return ys.parse_plain(data, "f.yaml")
    except InvalidInputError:
        return None


def test_every_file_gets_the_same_kind_and_verdict_from_its_plain_data() -> None:
    checked = 0
    for path in YAML_FILES:
        read = _read(path.read_bytes())
        if read is None:
            continue
        tree, plain = read
        kind, _ = kind_of(tree, path.name)
        assert kind_of_plain(plain) is kind, path
        if kind is None or tree is None:
            continue
        valid = structure_valid(kind, plain)
        assert valid == (list(structure_problems(tree, kind, plain)) == []), path
        if valid and kind is DocumentKind.LIBRARY and isinstance(tree, ys.YMapping):
            assert clean_values(plain) == (value_problems(tree, plain) == []), path
        if valid and kind is DocumentKind.SCHEMA and isinstance(tree, ys.YMapping):
            assert repeated_edges(plain) == bool(duplicate_edges(tree)), path
        checked += 1
    assert checked > 20


@settings(max_examples=examples(200))
@given(
    value=st.sampled_from(
        [
            "rosreconf/component-library",
            "'rosreconf/component-library'",
            '"rosreconf/interoperability-schema"',
            "rosreconf/component-library ",
            "Rosreconf/component-library",
            "1",
            "null",
            "[rosreconf/component-library]",
            "",
        ]
    ),
    top=st.sampled_from(["format: {}\n", "- format: {}\n", "name: x\nformat: {}\n"]),
)
def test_the_format_is_read_alike_from_plain_data_and_from_the_tree(value: str, top: str) -> None:
    read = _read(top.format(value).encode())
    assert read is not None
    tree, plain = read
    assert kind_of_plain(plain) is kind_of(tree, "f.yaml")[0]


@settings(max_examples=examples(200))
@given(
    components=st.lists(
        st.tuples(st.sampled_from(NUMBERS), st.sampled_from(NUMBERS), st.sampled_from(PARAMETERS)),
        min_size=1,
        max_size=4,
    )
)
@example(components=[("0.5", "1", "1"), ("0.5", "1e13", "1")])
def test_clean_values_says_clean_exactly_when_the_walk_finds_nothing(
    components: list[tuple[str, str, str]],
) -> None:
    read = _read(_library(components).encode())
    assert read is not None
    tree, plain = read
    assert isinstance(tree, ys.YMapping)
    if not structure_valid(DocumentKind.LIBRARY, plain):
        return  # value checks run on structurally valid libraries only
    assert clean_values(plain) == (value_problems(tree) == [])


@settings(max_examples=examples(200))
@given(
    edges=st.lists(
        st.tuples(st.sampled_from("abc"), st.lists(st.sampled_from("abc"), min_size=1, max_size=3)),
        max_size=4,
    )
)
@example(edges=[("a", ["b"]), ("a", ["b"])])
@example(edges=[("a", ["b", "c"]), ("b", ["a"])])
def test_repeated_edges_says_no_exactly_when_no_pair_repeats(
    edges: list[tuple[str, list[str]]],
) -> None:
    lines = ["edges:"]
    for consumer, providers in edges:
        lines.append(f"  - {{consumer: {consumer}, providers: [{', '.join(providers)}]}}")
    read = _read(("\n".join(lines) + "\n").encode() if edges else b"edges: []\n")
    assert read is not None
    tree, plain = read
    assert isinstance(tree, ys.YMapping)
    assert repeated_edges(plain) == bool(duplicate_edges(tree))
