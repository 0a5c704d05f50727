"""The fast paths (libyaml events, fastjsonschema) never change an answer.

rosreconf parses with libyaml and pre-validates with fastjsonschema for speed, falling back
to PyYAML's pure parser and to jsonschema for messages. These tests hold the fast and the
reference paths to identical trees, positions and verdicts.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import fastjsonschema
import jsonschema
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.formats import yamlsource as ys
from rosreconf.formats.structure import DocumentKind, fast_validator, json_schema

REPO = Path(__file__).resolve().parent.parent
YAML_FILES = sorted(
    [
        *REPO.glob("libraries/*.yaml"),
        *REPO.glob("schemas/*.yaml"),
        *list((REPO / "tests" / "cases").rglob("*.yaml")),
    ]
)


def _dump(node: ys.YNode | None) -> Any:
    """Return the tree with every value and every position, for comparison."""
    if node is None:
        return None
    if isinstance(node, ys.YScalar):
        return ("s", node.span, node.value, node.raw, node.plain)
    if isinstance(node, ys.YMapping):
        return ("m", node.span, [(k, node.key_spans[k], _dump(v)) for k, v in node.items.items()])
    assert isinstance(node, ys.YSequence)
    return ("l", node.span, [_dump(v) for v in node.items])


def _parse(data: bytes, fast: bool, monkeypatch: pytest.MonkeyPatch) -> Any:
    monkeypatch.setattr(ys, "FAST_LOADER", ys.FAST_LOADER if fast else None)
    try:
        return _dump(ys.parse(data, "f.yaml"))
    except Exception as exc:  # compare failures too: same problems, same positions
        return ("error", [str(p) for p in getattr(exc, "problems", [exc])])


def test_libyaml_is_available() -> None:
    assert ys.FAST_LOADER is not None, "PyYAML without libyaml: parsing is 6x slower"


@pytest.mark.parametrize("path", YAML_FILES, ids=lambda p: str(p.relative_to(REPO)))
def test_parsers_agree_on_every_file(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    data = path.read_bytes()
    assert _parse(data, True, monkeypatch) == _parse(data, False, monkeypatch)


LIBRARY = (REPO / "libraries" / "robot_arms.yaml").read_text(encoding="utf-8")


@settings(max_examples=200, deadline=None)
@given(cut=st.integers(0, len(LIBRARY)), junk=st.text(max_size=8))
def test_parsers_agree_on_damaged_files(cut: int, junk: str) -> None:
    data = (LIBRARY[:cut] + junk + LIBRARY[cut:]).encode("utf-8", errors="surrogatepass")
    with pytest.MonkeyPatch.context() as mp:
        assert _parse(data, True, mp) == _parse(data, False, mp)


def _mutations(doc: dict[str, Any]) -> st.SearchStrategy[dict[str, Any]]:
    values = st.one_of(
        st.none(),
        st.booleans(),
        st.integers(),
        st.floats(allow_nan=False),
        st.text(max_size=6),
        st.lists(st.text(max_size=4), max_size=2),
        st.dictionaries(st.text(max_size=4), st.text(max_size=4), max_size=2),
    )

    @st.composite
    def mutate(draw: st.DrawFn) -> dict[str, Any]:
        out = copy.deepcopy(doc)
        for _ in range(draw(st.integers(1, 3))):
            comp = draw(st.sampled_from(out["components"]))
            key = draw(st.sampled_from([*comp.keys(), "extra"]))
            if draw(st.booleans()) and key in comp:
                del comp[key]
            else:
                comp[key] = draw(values)
        return out

    return mutate()


PLAIN_LIBRARY = ys.to_plain(ys.parse(LIBRARY.encode(), "l"))


@settings(max_examples=300, deadline=None)
@given(doc=_mutations(PLAIN_LIBRARY))  # type: ignore[arg-type]
def test_validators_agree(doc: dict[str, Any]) -> None:
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    try:
        fast_validator(DocumentKind.LIBRARY)(doc)
        fast = True
    except fastjsonschema.JsonSchemaException:
        fast = False
    assert fast == reference


@pytest.mark.parametrize(
    "path",
    sorted([*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml")]),
    ids=lambda p: p.name,
)
def test_clean_files_take_the_one_loop_fast_tree(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A valid file is built by ``_fast_tree`` (not read twice), into the reference tree."""
    text = path.read_text(encoding="utf-8")
    fast = ys._fast_tree(text, "f.yaml")
    assert fast is not ys._UNCLEAN
    assert _dump(fast) == _parse(text.encode(), False, monkeypatch)


@pytest.mark.parametrize(
    "text",
    [
        "a: 1\na: 2\n",  # duplicate key
        "a: &x 1\nb: *x\n",  # anchor and alias
        "a: !!int 1\n",  # a tag
        "? [a]\n: 1\n",  # a complex key
        "a: 1\n---\nb: 2\n",  # two documents
        "a: [1\n",  # a syntax error
        "a:" + " [" * 40 + "]" * 40 + "\n",  # too deep
    ],
)
def test_fast_tree_hands_every_problem_to_the_full_reader(text: str) -> None:
    assert ys._fast_tree(text, "f.yaml") is ys._UNCLEAN
    with pytest.raises(ys.InvalidInputError):
        ys.parse(text.encode(), "f.yaml")
