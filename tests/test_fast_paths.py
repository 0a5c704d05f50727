"""The fast paths (libyaml events, the JSON Schemas' verdicts as code) never change an answer.

rosreconf parses with libyaml and pre-validates with the JSON Schemas written as Python code
(``formats.schemacode``) for speed, falling back to PyYAML's pure parser and to jsonschema
for messages. These tests hold the fast and the
reference paths to identical trees, positions and verdicts. The fast YAML path exists twice,
a loop in C (the extension rosreconf.formats._yamlc) and the same loop in Python
(yamlfast._events): every comparison reads with all three readers, and also holds the two
fast loops to the same declines.
"""

from __future__ import annotations

import copy
import importlib
import re
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import yaml
from conftest import examples
from hypothesis import example, given, settings
from hypothesis import strategies as st

from rosreconf.errors import InvalidInputError
from rosreconf.formats import _yamlc, yamlfast
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.structure import (
    FAST_MODULES,
    DocumentKind,
    fast_validator,
    fast_validator_code,
    fast_validator_module,
    json_schema,
)
from rosreconf.formats.yamlfast import Declined, fast_read

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


READERS = ("c", "python", "pure")
"""The C loop over libyaml's events, the Python loop over PyYAML's, PyYAML's pure parser."""


def _use(reader: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Make ``yamlsource.parse_plain`` read with ``reader`` (one of ``READERS``)."""
    monkeypatch.setattr(ys, "FAST_LOADER", None if reader == "pure" else yaml.CSafeLoader)
    monkeypatch.setattr(yamlfast, "COMPILED_READ", _yamlc.read if reader == "c" else None)


def _parse(data: bytes, reader: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    _use(reader, monkeypatch)
    try:
        tree, plain = ys.parse_plain(data, "f.yaml")
    except Exception as exc:  # compare failures too: same problems, same positions
        return ("error", [str(p) for p in getattr(exc, "problems", [exc])])
    # The fast loop builds the plain data beside the tree: it must be the tree's (repr, so
    # that a NaN equals itself).
    assert repr(plain) == repr(ys.to_plain(tree))
    return _dump(tree)


def _fast(text: str, reader: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    """Return what ``fast_read`` gives with the C or the Python loop: a dump, or "declined"."""
    _use(reader, monkeypatch)
    got = fast_read(text, "f.yaml", yaml.CSafeLoader)
    if isinstance(got, Declined):
        return "declined"
    tree, plain = got
    return _dump(tree), repr(plain)


def _plain_only(text: str, reader: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    """Return what ``fast_read`` gives without positions: the plain data's repr, or "declined"."""
    _use(reader, monkeypatch)
    got = fast_read(text, "f.yaml", yaml.CSafeLoader, positions=False)
    if isinstance(got, Declined):
        return "declined"
    tree, plain = got
    assert tree is None  # no node was built
    return repr(plain)


def _readers_agree(data: bytes) -> None:
    """Assert that the three readers give one answer and the two fast loops one decline.

    Read without positions (the loader's first try), the two fast loops give the plain data
    they give with positions, and decline exactly where they decline with positions.
    """
    with pytest.MonkeyPatch.context() as mp:
        pure = _parse(data, "pure", mp)
        assert _parse(data, "c", mp) == pure
        assert _parse(data, "python", mp) == pure
        _use("c", mp)
        only = ys.parse_plain_only(data, "f.yaml")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            assert isinstance(only, Declined)
            return  # refused before any reader runs
        fast = _fast(text, "c", mp)
        assert _fast(text, "python", mp) == fast
        plain = "declined" if fast == "declined" else fast[1]
        assert _plain_only(text, "c", mp) == plain
        assert _plain_only(text, "python", mp) == plain
        # the loader's first try: declined wherever there is a problem or the pure reader reads
        assert ("declined" if isinstance(only, Declined) else repr(only)) == plain
        if isinstance(pure, tuple) and pure[0] == "error":
            assert isinstance(only, Declined)


def _three_searches(text: str) -> bool:
    """Return ``fast_path_safe``'s answer as the three searches its doc names give it."""
    return (
        "\t" not in text
        and "\ufeff" not in text
        and not yaml.reader.Reader.NON_PRINTABLE.search(text)
    )


@pytest.mark.parametrize("other", ["", "\u00e9", "\u2028", "\U0001f600"])
def test_the_text_check_is_the_three_searches_on_every_ascii_character(other: str) -> None:
    # ASCII text takes a shortcut (one pass over its bytes); with `other` it does not.
    for code in range(128):
        text = f"a: x{chr(code)}y{other}\n"
        assert yamlfast.fast_path_safe(text) == _three_searches(text), (code, other)


def test_libyaml_is_available() -> None:
    assert ys.FAST_LOADER is not None, "PyYAML without libyaml: parsing is 6x slower"


@pytest.mark.parametrize("path", YAML_FILES, ids=lambda p: str(p.relative_to(REPO)))
def test_parsers_agree_on_every_file(path: Path) -> None:
    _readers_agree(path.read_bytes())


# --- the two YAML parsers give the same answer on every text ------------------------------
#
# libyaml (the fast path) and PyYAML's pure parser differ in a few places (listed in
# rosreconf/formats/yamlsource.py); rosreconf takes the pure path wherever they might, so
# these tests compare rosreconf's answers with libyaml allowed and with libyaml switched off.
# Every counterexample ever found is pinned with @example; `make explore` searches with random
# seeds and 50 times the examples.

LIBRARY = (REPO / "libraries" / "robot_arms.yaml").read_text(encoding="utf-8")
BUNDLED = {
    p.name: p.read_text(encoding="utf-8")
    for p in sorted([*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml")])
}
EDIT_CHARACTERS = (
    "-?:,[]{}#&*!|>'\"%@`~=<\\/. \n\t\ra0_"  # YAML's indicators, blanks and a few plain ones
    "\ufeff\x85\u2028\u2029\u00e9\x00\x7f"  # BOM, Unicode line breaks, non-ASCII, refused ones
)

_PINNED_LINE = "      - {service: visual_perception, type: robot_arm_msgs/VisualPerception}"
R_OBOT = LIBRARY.index(_PINNED_LINE) + _PINNED_LINE.index("type: r") + len("type: r")
"""Where a '?' in robot_arms.yaml once made libyaml and PyYAML disagree (issue 10): found at
offset 14812, the `r` of `type: robot_arm_msgs/...` inside a flow mapping; found by content so
that the library can grow (the M-solution added dynamics above it) without moving the pin."""


E_LBOW = LIBRARY.index("remappings: {elbow/") + len("remappings: {e")
"""Where a '?' made libyaml accept `{e?lbow/dc_servo_command: ...}` as a flow mapping's key
while PyYAML refuses it (found by the derandomized damaged-file test, issue 12)."""

FOUND_AT = 14812
"""The offset where the first '?' disagreement was found (issue 10), kept as it was found:
robot_arms.yaml has changed since, so it now lands elsewhere, which is one more case."""


def test_pinned_positions_still_point_where_they_were_found() -> None:
    # The @example pins below are offsets into robot_arms.yaml: editing the file must not
    # quietly turn them into different (and pointless) cases.
    line = LIBRARY[LIBRARY.rindex("\n", 0, R_OBOT) + 1 : LIBRARY.index("\n", R_OBOT)]
    assert line == _PINNED_LINE
    assert LIBRARY[R_OBOT - 7 : R_OBOT] == "type: r"
    assert LIBRARY[E_LBOW - 2 : E_LBOW + 4] == "{elbow"
    assert len(LIBRARY) > FOUND_AT


@settings(max_examples=examples(200))
@given(cut=st.integers(0, len(LIBRARY)), junk=st.text(max_size=8))
@example(cut=FOUND_AT, junk="?")  # the original case, at its original offset (issue 10)
@example(cut=R_OBOT, junk="?")  # `type: r?obot_arm_msgs/...` in a flow mapping (issue 10)
@example(cut=E_LBOW, junk="?")  # `{e?lbow/...: ...}`: a '?' in a flow mapping's key (issue 12)
@example(cut=R_OBOT, junk="\t")  # a tab in a plain scalar (found with the fast path)
@example(cut=R_OBOT - 6, junk=" ")  # `type:  robot...`: extra space after ':' in a flow mapping
@example(cut=len(LIBRARY), junk="?")  # an explicit key with no value at the very end
@example(cut=0, junk="\ufeff")  # a byte order mark
def test_parsers_agree_on_damaged_files(cut: int, junk: str) -> None:
    _readers_agree((LIBRARY[:cut] + junk + LIBRARY[cut:]).encode("utf-8", errors="surrogatepass"))


@st.composite
def _one_character_edits(draw: st.DrawFn) -> tuple[str, int, str]:
    """Draw (bundled file, offset, character to insert or '' to delete the one there)."""
    name = draw(st.sampled_from(sorted(BUNDLED)))
    at = draw(st.integers(0, len(BUNDLED[name])))
    return name, at, draw(st.sampled_from(["", *EDIT_CHARACTERS]))


@settings(max_examples=examples(300))
@given(edit=_one_character_edits())
@example(edit=("robot_arms.yaml", R_OBOT, "?"))
@example(edit=("robot_arms.yaml", E_LBOW, "?"))
@example(edit=("robot_arms.yaml", R_OBOT - 1, ""))  # `type:robot_arm_msgs/...`
@example(edit=("robot_arms.yaml", len(LIBRARY) - 1, ""))  # no line break at the end
def test_parsers_agree_after_one_character_edits(edit: tuple[str, int, str]) -> None:
    name, at, char = edit
    text = BUNDLED[name]
    damaged = text[:at] + char + text[at + (0 if char else 1) :]
    _readers_agree(damaged.encode("utf-8"))


PIECES = [
    "a", "b", "1", ".", "\\", " ", "  ", "\n", "\n  ", "\n    ", ":", ": ", "?", "? ", "-",
    "- ", ",", "[", "]", "{", "}", "#", " #c", "&a", "*a", "!", "!!str", "!!str ", "|", "|-",
    "|2", ">", ">+", "'", "''", '"', '\\"', "%", "%YAML 1.1\n", "@", "`", "---", "...",
    "\n---\n", "\t", "\r\n", "\r", "\ufeff", "\x85", "\u2028", "\u00e9",
]  # fmt: skip
"""Pieces of YAML syntax; random strings of them reach every corner of both scanners."""


@settings(max_examples=examples(2000))
@given(pieces=st.lists(st.sampled_from(PIECES), min_size=1, max_size=16), end=st.booleans())
@example(pieces=["{", "a", ": ", "b", "?", "c", "}"], end=True)  # '?' inside a plain scalar
@example(pieces=["[", "a", " ", "?", "b", "]"], end=True)  # ... also after a space
@example(pieces=["{", "a", ": ", "}"], end=True)  # where an empty value in a flow mapping is
@example(pieces=["[", "a", ": ", "]"], end=True)  # ... and in a flow sequence's pair
@example(pieces=["{", "? ", "}"], end=True)  # ... and an empty explicit key
@example(pieces=["[", "!!str", ",", " ", "a", "]"], end=True)  # ',' in a tag in a flow sequence
@example(pieces=["a", ": ", "|", "#"], end=True)  # '#' right after a block scalar's header
@example(pieces=["? "], end=False)  # an empty value at the very end of the text
@example(pieces=["---"], end=False)  # ... an empty document
@example(pieces=["{", "a", ": ", "\ufeff", "a", ",", " ", "b", ": ", "c", "}"], end=True)  # BOM
@example(pieces=["a", ":", "\t", "b"], end=True)  # a tab separating tokens
def test_parsers_agree_on_small_documents(pieces: list[str], end: bool) -> None:
    _readers_agree(("".join(pieces) + ("\n" if end else "")).encode("utf-8"))


_ENDS = (yaml.CollectionEndEvent, yaml.DocumentEndEvent, yaml.StreamEndEvent)


def _events_differ(text: str) -> bool:
    """Tell whether raw libyaml and raw PyYAML events differ where rosreconf reads them."""

    def events(loader: Any) -> Any:
        try:
            return [
                (type(e).__name__, e.start_mark.line, e.start_mark.column,
                 getattr(e, "value", None), getattr(e, "tag", None),
                 getattr(e, "style", None) or None)  # plain: None from PyYAML, "" from libyaml
                for e in yaml.parse(text, Loader=loader)
                if not isinstance(e, _ENDS)  # rosreconf reads no position of these
            ]  # fmt: skip
        except yaml.YAMLError:
            return "error"

    return bool(events(yaml.CSafeLoader) != events(yaml.SafeLoader))


KNOWN_DIFFERENCES = {
    "question mark in a flow scalar": "{type: r?obot}\n",
    "question mark in a flow key": "{e?lbow: x}\n",
    "empty value in a flow mapping": "{a: }\n",
    "empty value at the very end": "? a",
    "comma in a tag in a flow sequence": "[!!str, a]\n",
    "comment right after a block scalar header": "a: |#\n  x\n",
    "byte order mark inside a line": "{a: \ufeffx, b: c}\n",
    "tab between tokens": "a:\tb\n",
}
"""One text for each way libyaml 0.2.5 and PyYAML 6 read the same text differently."""


@pytest.mark.parametrize("text", KNOWN_DIFFERENCES.values(), ids=KNOWN_DIFFERENCES.keys())
def test_each_known_difference_is_real_and_takes_the_pure_path(text: str) -> None:
    # Real: if a libyaml upgrade removes a difference, this says which rule may go.
    assert _events_differ(text)
    with pytest.MonkeyPatch.context() as mp:
        for reader in ("c", "python"):
            assert _fast(text, reader, mp) == "declined", reader
    _readers_agree(text.encode())


@pytest.mark.parametrize("at", [R_OBOT, E_LBOW], ids=["in-a-flow-mapping-value", "in-a-flow-key"])
def test_question_mark_in_a_flow_collection_is_the_syntax_error_at_the_question_mark(
    at: int,
) -> None:
    data = (LIBRARY[:at] + "?" + LIBRARY[at:]).encode()
    line = LIBRARY[:at].count("\n") + 1
    column = at - LIBRARY.rindex("\n", 0, at)
    with pytest.raises(InvalidInputError) as caught:
        ys.parse(data, "robot_arms.yaml")
    [problem] = caught.value.problems
    assert (problem.span.line, problem.span.column) == (line, column)
    assert "expected ',' or '}', but got '?'" in problem.message


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


@settings(max_examples=examples(300))
@given(doc=_mutations(PLAIN_LIBRARY))  # type: ignore[arg-type]
def test_validators_agree(doc: dict[str, Any]) -> None:
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    assert fast_validator(DocumentKind.LIBRARY)(doc) == reference


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
@pytest.mark.parametrize("reader", READERS)
def test_every_problem_is_refused_whichever_parser_reads_first(
    text: str, reader: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    if reader != "pure":
        assert _fast(text, reader, monkeypatch) == "declined"
    _use(reader, monkeypatch)
    with pytest.raises(ys.InvalidInputError):
        ys.parse(text.encode(), "f.yaml")


_INTERFACES: list[Any] = [
    {"topic": "t", "type": "a/B"},
    {"service": "s", "type": "a/B"},
    {"topic": "t", "service": "s", "type": "a/B"},  # both: exactly one is allowed
    {"type": "a/B"},  # neither
    {"any_of": [{"topic": "t", "type": "a/B"}, {"service": "s", "type": "a/B"}]},
    {"any_of": [{"topic": "t", "type": "a/B"}], "topic": "t"},  # any_of beside a key
    {"any_of": [{"topic": "t", "service": "s", "type": "a/B"}, {"topic": "u", "type": "a/B"}]},
    {"topic": "t", "type": "a/B", "any_of": []},
    "t",
]
_PARAMETERS: list[Any] = [
    1,
    "x",
    True,
    {"substitution": "$(find p)"},
    {"substitution": 1},
    [1],
    None,
]


@pytest.mark.parametrize("where", ["provides", "requires"])
@pytest.mark.parametrize("interface", _INTERFACES)
@pytest.mark.parametrize("parameter", _PARAMETERS[:1] + _PARAMETERS[3:5])
def test_validators_agree_on_every_one_of(where: str, interface: Any, parameter: Any) -> None:
    # The verdict code adds up a oneOf's branches (schemacode._branches), inlining the simple
    # ones: each oneOf of the library Schema, with values on both sides of every branch.
    doc = copy.deepcopy(PLAIN_LIBRARY)
    assert isinstance(doc, dict)
    component = doc["components"][0]
    component[where] = [interface]
    component["ros"] = {"package": "p", "executable": "e", "parameters": {"k": parameter}}
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    assert fast_validator(DocumentKind.LIBRARY)(doc) == reference


@pytest.mark.parametrize("parameter", _PARAMETERS)
def test_validators_agree_on_launch_parameters(parameter: Any) -> None:
    doc = copy.deepcopy(PLAIN_LIBRARY)
    assert isinstance(doc, dict)
    doc["components"][0]["ros"] = {
        "package": "p",
        "executable": "e",
        "parameters": {"k": parameter},
    }
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    assert fast_validator(DocumentKind.LIBRARY)(doc) == reference


@pytest.mark.parametrize("kind", list(DocumentKind))
def test_the_verdict_code_is_the_same_text_in_every_process(kind: DocumentKind) -> None:
    # Sets are written sorted, not in a hash order that changes per process: the shipped
    # module must not change each time scripts/fast_validators.py runs.
    code = fast_validator_code(kind)
    for literal in re.findall(r"frozenset\(\{([^}]*)\}\)", code):
        members = literal.split(", ")
        assert members == sorted(members)


@pytest.mark.parametrize("kind", list(DocumentKind))
def test_the_shipped_fast_validator_is_the_one_written_now(kind: DocumentKind) -> None:
    # rosreconf/formats/fastschema_*.py save writing and compiling the verdict code in
    # every process. After changing a JSON Schema: python scripts/fast_validators.py
    shipped = REPO / "rosreconf" / "formats" / f"{FAST_MODULES[kind]}.py"
    assert shipped.read_text(encoding="utf-8") == fast_validator_module(kind)
    fast_validator.cache_clear()
    validate = fast_validator(kind)
    assert validate is importlib.import_module(f"rosreconf.formats.{FAST_MODULES[kind]}").VALIDATE


def test_a_stale_shipped_validator_is_not_used(monkeypatch: pytest.MonkeyPatch) -> None:
    # A module written for another JSON Schema (SOURCE differs) must not decide verdicts.
    kind = DocumentKind.LIBRARY
    module = importlib.import_module(f"rosreconf.formats.{FAST_MODULES[kind]}")
    monkeypatch.setattr(module, "SOURCE", "written for another JSON Schema")
    fast_validator.cache_clear()
    try:
        validate = fast_validator(kind)
        assert validate is not module.VALIDATE
        assert validate(PLAIN_LIBRARY)
        assert not validate({**PLAIN_LIBRARY, "version": 2})
    finally:
        fast_validator.cache_clear()


SCHEMA_DOCS = [
    ys.to_plain(ys.parse(p.read_bytes(), p.name)) for p in sorted(REPO.glob("schemas/*.yaml"))
]


@settings(max_examples=examples(200))
@given(
    which=st.integers(0, len(SCHEMA_DOCS) - 1),
    key=st.sampled_from(["roles", "edges", "nominal", "simulation", "name", "extra"]),
    item=st.integers(0, 3),
    value=st.one_of(st.none(), st.integers(), st.text(max_size=4), st.lists(st.integers())),
)
def test_validators_agree_on_interoperability_schemas(
    which: int, key: str, item: int, value: Any
) -> None:
    # Verdicts on schemas too must stay jsonschema's.
    doc = copy.deepcopy(SCHEMA_DOCS[which])
    assert isinstance(doc, dict)
    target = doc.get(key)
    if isinstance(target, list) and target:  # damage one item of a list
        entry = target[item % len(target)]
        if isinstance(entry, dict) and entry:
            entry[sorted(entry)[item % len(entry)]] = value
        else:
            target[item % len(target)] = value
    else:
        doc[key] = value
    kind = DocumentKind.SCHEMA
    reference = jsonschema.Draft202012Validator(json_schema(kind)).is_valid(doc)
    assert fast_validator(kind)(doc) == reference


@pytest.mark.parametrize("doc", SCHEMA_DOCS)
def test_the_fast_validator_accepts_the_bundled_schemas(doc: Any) -> None:
    assert fast_validator(DocumentKind.SCHEMA)(doc)


_TF = {"num": [1.0], "den": [1.0, 1.0]}
_SS = {"A": [[-1.0]], "B": [[1.0]], "C": [[1.0]], "D": [[0.0]]}


@pytest.mark.parametrize(
    "dynamics",
    [
        {"transfer_function": _TF},
        {"state_space": _SS},
        {"transfer_function": _TF, "state_space": _SS},  # both: exactly one is allowed
        {"delay": 0.1},  # neither
        {"transfer_function": _TF, "delay": 0.1},
        {},
    ],
)
def test_validators_agree_on_dynamics(dynamics: dict[str, Any]) -> None:
    # dynamics is a oneOf of single required keys, added up like the interface's.
    doc = copy.deepcopy(PLAIN_LIBRARY)
    assert isinstance(doc, dict)
    doc["components"][0]["dynamics"] = dynamics
    reference = jsonschema.Draft202012Validator(json_schema(DocumentKind.LIBRARY)).is_valid(doc)
    assert reference == (("transfer_function" in dynamics) != ("state_space" in dynamics))
    assert fast_validator(DocumentKind.LIBRARY)(doc) == reference
