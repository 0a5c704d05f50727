"""The fast validator remembers valid interfaces and requirements: verdicts stay jsonschema's."""

from __future__ import annotations

import copy
from typing import Any

import fastjsonschema
import jsonschema
import pytest
from conftest import examples
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.formats import yamlsource as ys
from rosreconf.formats.schemamemo import content_key, remember_valid
from rosreconf.formats.structure import DocumentKind, fast_validator, json_schema
from rosreconf.resources import Bundle, bundled

LIBRARY = ys.to_plain(
    ys.parse(bundled(Bundle.LIBRARIES, "robot_arms.yaml").read_bytes(), "robot_arms.yaml")
)


def _verdicts(doc: Any) -> tuple[bool, bool]:
    """Return (fast validator's verdict, jsonschema's verdict) on a library document."""
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    try:
        fast_validator(DocumentKind.LIBRARY)(doc)
    except fastjsonschema.JsonSchemaException:
        return False, reference
    return True, reference


@pytest.mark.parametrize(
    ("one", "other"),
    [(True, 1), (1, 1.0), (True, 1.0), (1, "1"), (None, "null"), ([1], {"0": 1}), ([], {})],
)
def test_contents_python_calls_equal_have_different_keys(one: Any, other: Any) -> None:
    assert content_key(one) != content_key(other)
    assert content_key({"k": [one]}) != content_key({"k": [other]})


def test_equal_contents_have_equal_keys() -> None:
    a = {"topic": "t", "type": "a/B", "qos": {"depth": 1, "deadline": None}}
    assert content_key(a) == content_key(copy.deepcopy(a))


def test_a_value_no_yaml_reader_makes_is_checked_and_not_remembered() -> None:
    calls = []

    def validate(data: Any, *rest: Any) -> Any:
        calls.append(data)
        return data

    check = remember_valid(validate)
    for data in ({1: "x"}, {1: "x"}, {"s": {2, 3}}, {"s": {2, 3}}):
        check(data, {}, None)
    assert len(calls) == 4


def test_each_valid_content_is_checked_once_and_each_invalid_one_every_time() -> None:
    calls = []

    def validate(data: Any, *rest: Any) -> Any:
        calls.append(data)
        if data.get("topic") != "t":
            raise fastjsonschema.JsonSchemaValueException("bad")
        return data

    check = remember_valid(validate)
    for _ in range(3):
        assert check({"topic": "t"}, {}, None) == {"topic": "t"}
        with pytest.raises(fastjsonschema.JsonSchemaValueException):
            check({"topic": "u"}, {}, None)
    assert calls == [{"topic": "t"}, {"topic": "u"}, {"topic": "u"}, {"topic": "u"}]


@pytest.mark.parametrize("where", ["provides", "requires"])
def test_a_remembered_valid_interface_does_not_pass_a_python_equal_invalid_one(
    where: str,
) -> None:
    # depth 1 is valid, depth True is not, yet (("depth", 1),) == (("depth", True),) in Python.
    valid = {"topic": "t", "type": "a/B", "qos": {"depth": 1}}
    invalid = {"topic": "t", "type": "a/B", "qos": {"depth": True}}
    for interface, expected in ((valid, True), (invalid, False), (valid, True)):
        doc = copy.deepcopy(LIBRARY)
        assert isinstance(doc, dict)
        either = {"any_of": [interface, interface]}
        doc["components"][0][where] = [interface, either if where == "requires" else interface]
        assert _verdicts(doc) == (expected, expected)


def _interface(kind: str, label: Any, type_: Any, qos: Any, extra: str | None) -> Any:
    """Return an interface mapping, valid or nearly so (a wrong type, an extra key)."""
    interface: dict[str, Any] = {kind: label, "type": type_}
    if qos is not None:
        interface["qos"] = qos
    if extra is not None:
        interface[extra] = label
    return interface


_SCALARS = [1, True, 1.0, -1, 0, None, "reliable"]
_INTERFACES = st.builds(
    _interface,
    st.sampled_from(["topic", "service"]),
    st.sampled_from(["t", "u", "t", "u", "1", True, 1]),
    st.sampled_from(["a/B", "a/C", "a/B", "a/C", "B", True, 1.0]),
    st.one_of(
        st.none(),
        st.dictionaries(st.sampled_from(["depth", "reliability"]), st.sampled_from(_SCALARS)),
    ),
    st.sampled_from([None, None, None, "service", "any_of"]),
)
_REQUIREMENTS = st.one_of(
    _INTERFACES, st.builds(lambda i: {"any_of": i}, st.lists(_INTERFACES, max_size=3))
)


@settings(max_examples=examples(300))
@given(interfaces=st.lists(_REQUIREMENTS, min_size=1, max_size=6))
def test_verdicts_stay_jsonschemas_whatever_was_seen_before(interfaces: list[Any]) -> None:
    # Each interface is checked in a document of its own, after all those before it: what
    # the validator remembered from earlier documents must never change a verdict.
    for interface in interfaces:
        for where in ("provides", "requires"):
            doc = copy.deepcopy(LIBRARY)
            assert isinstance(doc, dict)
            doc["components"][1][where] = [interface, copy.deepcopy(interface)]
            fast, reference = _verdicts(doc)
            assert fast == reference
