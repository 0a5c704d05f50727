"""The JSON Schemas' verdicts written as code agree with jsonschema on damaged documents.

``rosreconf.formats.schemacode`` writes each published JSON Schema as plain Python
(``structure.fast_validator``); a document it accepts is never shown to jsonschema, so a
wrong "valid" would let a broken file through. These tests damage valid documents anywhere
in their tree (every keyword of both Schemas: names, labels, types, QoS, parameters,
dynamics, simulation blocks) and compare the two verdicts, and check that the writer refuses
what it cannot write.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.errors import InvalidInputError
from rosreconf.formats import schemacode
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.structure import DocumentKind, fast_validator, json_schema, kind_of

REPO = Path(__file__).resolve().parent.parent


def _valid_documents(kind: DocumentKind) -> list[Any]:
    """Return every document of ``kind`` in the repository that jsonschema accepts."""
    found = []
    paths = [*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml")]
    paths += (REPO / "tests" / "cases").rglob("*.yaml")
    for path in sorted(paths):
        try:
            tree, plain = ys.parse_plain(path.read_bytes(), path.name)
        except InvalidInputError:
            continue
        if kind_of(tree, path.name)[0] is not kind:
            continue
        if jsonschema.Draft202012Validator(json_schema(kind)).is_valid(plain):
            found.append(plain)
    return found


LIBRARIES = _valid_documents(DocumentKind.LIBRARY)
SCHEMAS = _valid_documents(DocumentKind.SCHEMA)

KEYS = [
    "name", "abstraction", "provides", "requires", "topic", "service", "type", "qos", "any_of",
    "depth", "deadline", "reliability", "ros", "package", "executable", "parameters",
    "substitution", "metrics", "cost", "dynamics", "transfer_function", "state_space", "num",
    "den", "A", "delay", "needs", "schemas", "roles", "edges", "providers", "consumer",
    "interfaces", "optional", "nominal", "simulation", "loops", "forward", "plant", "duration",
    "requirements", "overshoot", "format", "version", "extra",
]  # fmt: skip
"""Keys a damaged mapping may gain: the Schemas' own (right or wrong place) and one unknown."""

SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.sampled_from([0, 1, -1, 2, 2**40, 0.0, 1.0, 0.5, -0.5, 1.5, math.inf, math.nan]),
    st.integers(),
    st.floats(),
    st.sampled_from(
        ["a", "A_1", "1a", "a\n", "", "a b", "/a/b", "a//b", "a/B", "a/B/c", "$(find x)", "x.y-1"]
    ),
    st.sampled_from(["reliable", "volatile", "automatic", "best_effort", "sensor_msgs/Image"]),
    st.sampled_from(["rosreconf/component-library", "rosreconf/interoperability-schema"]),
    st.text(max_size=4),
)
VALUES = st.recursive(
    SCALARS,
    lambda inner: st.one_of(
        st.lists(inner, max_size=3),
        st.dictionaries(st.sampled_from(KEYS), inner, max_size=3),
    ),
    max_leaves=6,
)


def _parts(doc: Any) -> Iterator[Any]:
    """Yield every value in ``doc``, itself included (parents before children)."""
    yield doc
    children = doc.values() if isinstance(doc, dict) else doc if isinstance(doc, list) else ()
    for child in children:
        yield from _parts(child)


@st.composite
def _like(draw: st.DrawFn, old: Any) -> Any:
    """Return a value a little different from ``old``: a text edited, a number moved."""
    if isinstance(old, str):
        edit = draw(st.sampled_from(["1", "/", "//", "-", " ", "\n", "_", "$(", "x/Y", ".", ""]))
        where = draw(st.integers(0, len(old)))
        return draw(st.sampled_from([old[:where] + edit + old[where:], edit, old + edit]))
    if isinstance(old, bool) or old is None:
        return draw(SCALARS)
    if isinstance(old, int | float):
        return draw(st.sampled_from([-old, old + 1, old - 1, str(old), True, None, 0, 1.0, -1, 2]))
    return draw(VALUES)


@st.composite
def _damaged(draw: st.DrawFn, documents: list[Any]) -> Any:
    """Return one of ``documents`` with one to three edits anywhere in its tree.

    Most edits are small (a text or number changed a little, a key dropped or added with a
    value that key has elsewhere in the document, a list item dropped or repeated) so that
    many damaged documents are wrong in one small way, or still valid, rather than plainly
    wrong at the top.
    """
    doc = copy.deepcopy(draw(st.sampled_from(documents)))
    seen: dict[str, list[Any]] = {}
    for part in _parts(doc):
        if isinstance(part, dict):
            for key, value in part.items():
                seen.setdefault(key, []).append(value)
    for _ in range(draw(st.integers(1, 3))):
        parts = list(_parts(doc))
        how = draw(st.integers(0, 9))
        if how < 5:  # change one value a little
            holders: list[tuple[Any, Any]] = [
                (p, k) for p in parts if isinstance(p, dict) for k in p
            ]
            holders += [(p, i) for p in parts if isinstance(p, list) for i in range(len(p))]
            holder, at = draw(st.sampled_from(holders))
            holder[at] = draw(_like(holder[at]))
            continue
        dicts = [p for p in parts if isinstance(p, dict)]
        lists = [p for p in parts if isinstance(p, list)]
        if how < 8 and dicts:
            mapping = draw(st.sampled_from(dicts))
            key = draw(st.sampled_from(sorted(seen) + KEYS))
            if key in mapping and how == 5:
                del mapping[key]
            elif key in seen and how < 7:
                mapping[key] = copy.deepcopy(draw(st.sampled_from(seen[key])))
            else:
                mapping[key] = draw(st.one_of(SCALARS, VALUES))
        elif lists:
            node = draw(st.sampled_from(lists))
            if node and how == 8:
                node.append(copy.deepcopy(node[draw(st.integers(0, len(node) - 1))]))
            elif node and how == 9:
                del node[draw(st.integers(0, len(node) - 1))]
            else:
                node.append(draw(st.one_of(SCALARS, VALUES)))
    return doc


def _agree(kind: DocumentKind, doc: Any) -> None:
    reference = jsonschema.Draft202012Validator(json_schema(kind)).is_valid(doc)
    assert fast_validator(kind)(doc) is reference


def test_there_are_documents_to_damage() -> None:
    assert len(LIBRARIES) >= 3
    assert len(SCHEMAS) >= 4


@settings(max_examples=examples(400))
@given(doc=_damaged(LIBRARIES))
def test_verdicts_agree_on_damaged_libraries(doc: Any) -> None:
    _agree(DocumentKind.LIBRARY, doc)


@settings(max_examples=examples(300))
@given(doc=_damaged(SCHEMAS))
def test_verdicts_agree_on_damaged_interoperability_schemas(doc: Any) -> None:
    _agree(DocumentKind.SCHEMA, doc)


_BOTH = {
    "transfer_function": {"num": [1], "den": [1]},
    "state_space": {"A": [[1]], "B": [[1]], "C": [[1]], "D": [[1]]},
}


def _component(**fields: Any) -> dict[str, Any]:
    return {
        "format": "rosreconf/component-library",
        "version": 1,
        "name": "lib",
        "components": [{"name": "C", "abstraction": "a", **fields}],
    }


@pytest.mark.parametrize(
    "doc",
    [
        {**_component(), "version": True},  # JSON Schema: true is not 1
        {**_component(), "version": 1.0},  # ... but 1.0 is
        _component(name="a\n"),  # Python's re.search: '$' matches before a final newline
        _component(failure_probability=math.nan),  # NaN is a number, and never < 0
        _component(failure_probability=True),
        _component(needs=["b", "b"]),
        _component(needs=["b", "c"]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"depth": 1.0}}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"depth": 1.5}}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"deadline": None}}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"deadline": 0}}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"reliability": "x"}}]),
        _component(requires=[{"any_of": [{"topic": "t", "type": "a/B"}]}]),
        _component(ros={"package": "p", "executable": "e", "parameters": {"1x": 1}}),
        _component(
            ros={"package": "p", "executable": "e", "parameters": {"k": {"substitution": ""}}}
        ),
        _component(ros={"package": "p", "executable": "e", "remappings": {"/a": "b//c"}}),
        _component(metrics={"cost": "1"}),
        _component(metrics={"bad-name": 1}),
        _component(failure_probability=-0.1),
        _component(failure_probability=1.5),
        _component(provides=[{"topic": "t", "service": "s", "type": "a/B"}]),
        _component(provides=[{"type": "a/B"}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"depth": -1}}]),
        _component(provides=[{"topic": "t", "type": "a/B", "qos": {"durability": "x"}}]),
        _component(dynamics={"transfer_function": {"num": [1], "den": [1]}, "delay": -1}),
        _component(dynamics=_BOTH),
        _component(dynamics={"transfer_function": {"num": [], "den": [1]}}),
    ],
)
def test_verdicts_agree_on_the_edges_of_each_library_keyword(doc: Any) -> None:
    _agree(DocumentKind.LIBRARY, doc)


def _schema(**fields: Any) -> dict[str, Any]:
    return {
        "format": "rosreconf/interoperability-schema",
        "version": 1,
        "name": "s",
        "skill": "k",
        "environment": "e",
        "roles": [{"name": "a", "abstraction": "x"}, {"name": "b", "abstraction": "y"}],
        **fields,
    }


_LOOP = {"name": "l", "forward": ["a"], "plant": {"transfer_function": {"num": [1], "den": [1]}}}


@pytest.mark.parametrize(
    "doc",
    [
        _schema(),
        _schema(roles=[]),
        _schema(edges=[{"consumer": "a", "providers": ["b", "b"]}]),
        _schema(edges=[{"consumer": "a", "providers": []}]),
        _schema(edges=[{"consumer": "a", "providers": ["b"], "interfaces": ["t", "t"]}]),
        _schema(edges=[{"consumer": "a", "providers": ["b"], "optional": 1}]),
        _schema(nominal={"a": "C", "b": "1D"}),
        _schema(simulation={"loops": [_LOOP], "duration": 1.0}),
        _schema(simulation={"loops": [_LOOP], "duration": 0}),
        _schema(simulation={"loops": [_LOOP], "duration": 1, "reference": -1}),
        _schema(simulation={"loops": [{**_LOOP, "forward": ["a", "a"]}], "duration": 1}),
        _schema(simulation={"loops": [{**_LOOP, "plant": {"delay": 1}}], "duration": 1}),
        _schema(simulation={"loops": [{**_LOOP, "plant": _BOTH}], "duration": 1}),
        _schema(simulation={"loops": [], "duration": 1}),
        _schema(simulation={"loops": [_LOOP], "duration": 1, "requirements": {"overshoot": -1}}),
    ],
)
def test_verdicts_agree_on_the_edges_of_each_schema_keyword(doc: Any) -> None:
    _agree(DocumentKind.SCHEMA, doc)


def test_a_name_remembered_as_matching_does_not_hide_a_later_bad_one() -> None:
    # The code remembers texts that matched a pattern; a text that did not is never
    # remembered, and is refused every time.
    validate = fast_validator(DocumentKind.LIBRARY)
    good, bad = _component(), _component()
    bad["components"].append({"name": "C2", "abstraction": "1a"})
    for _ in range(2):
        assert validate(good)
        assert not validate(bad)


@pytest.mark.parametrize(
    "schema",
    [
        {"type": "object", "patternProperties": {"^a": {}}},  # a keyword not written
        {"$ref": "https://example.com/other.json"},
        {"const": [1]},
        {"enum": ["a", 1]},
        {"type": "array", "items": {"type": "number"}, "uniqueItems": True},
        {"minimum": 0},  # on a value of unknown type
        {"type": "decimal"},
        {"$defs": {"a": {"$ref": "#/$defs/a"}}, "$ref": "#/$defs/a"},
    ],
)
def test_what_cannot_be_written_is_refused_when_writing(schema: Any) -> None:
    with pytest.raises(schemacode.Unsupported):
        schemacode.verdict_code(schema)


def test_annotations_change_nothing() -> None:
    plain = {"type": "string", "pattern": "^a+$"}
    described = {**plain, "description": "d", "x-hint": "h", "title": "t"}
    assert schemacode.verdict_code(plain) == schemacode.verdict_code(described)
