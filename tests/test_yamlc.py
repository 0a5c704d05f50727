"""The compiled YAML reader (rosreconf.formats._yamlc) is built, used, and safe.

tests/test_fast_paths.py holds its answers to the Python loop's and the pure reader's on
every text; these tests hold what is particular to C: it is what ``fast_read`` uses unless
``ROSRECONF_PURE_YAML`` says otherwise, reading never leaks memory (on accepted, declined and
failed reads alike), Python exceptions raised on the way propagate, the depth limit is the
one passed in, and bad arguments are refused without crashing. The extension is imported at
module level: without it this file fails, it never skips (make test builds it).
"""

from __future__ import annotations

import gc
import json
import os
import subprocess
import sys
import tracemalloc
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml

from rosreconf.formats import _yamlc, yamlfast
from rosreconf.formats import yamlsource as ys
from rosreconf.formats.generate import generate
from rosreconf.formats.yamltree import (
    MAX_DEPTH,
    Scalar,
    YMapping,
    YScalar,
    YSequence,
    resolve_plain,
    to_plain,
)
from rosreconf.model import Span

REPO = Path(__file__).resolve().parent.parent
BUNDLED = sorted([*REPO.glob("libraries/*.yaml"), *REPO.glob("schemas/*.yaml")])
HEADER_COMMENT = yamlfast._BLOCK_HEADER_THEN_COMMENT.match
LIBRARY = BUNDLED[0].read_text(encoding="utf-8")


def _read(
    text: str,
    *,
    max_depth: int = MAX_DEPTH,
    scalar: Any = YScalar,
    resolve: Callable[[str], Scalar] = resolve_plain,
    header_comment: Callable[[str, int], object] = HEADER_COMMENT,
    positions: bool = True,
) -> Any:
    """Call the extension as ``yamlfast.fast_read`` does, with any part replaced."""
    types = (Span, scalar, YMapping, YSequence) if positions else (None, None, None, None)
    return _yamlc.read(text, "f.yaml", max_depth, *types, resolve, header_comment)


def _plain(text: str, **changes: Any) -> Any:
    """Call the extension without positions (the loader's first try), with any part replaced."""
    return _read(text, positions=False, **changes)


def _python_loop(text: str) -> Any:
    """Return what the Python loop over PyYAML's events gives for ``text``."""
    saved = yamlfast.COMPILED_READ
    yamlfast.COMPILED_READ = None
    try:
        return yamlfast.fast_read(text, "f.yaml", yaml.CSafeLoader)
    finally:
        yamlfast.COMPILED_READ = saved


def _probe(env: dict[str, str]) -> dict[str, Any]:
    """Report, from a fresh process with ``env``, which loop ``fast_read`` uses."""
    code = (
        "import json\n"
        "from rosreconf.formats import _yamlc, yamlfast\n"
        "print(json.dumps({'compiled': yamlfast.COMPILED_READ is _yamlc.read,\n"
        "                  'python': yamlfast.COMPILED_READ is None,\n"
        "                  'file': _yamlc.__file__}))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    probe: dict[str, Any] = json.loads(result.stdout)
    return probe


def _env(**changes: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != yamlfast.PURE_ENV}
    return {**env, **changes}


def test_the_extension_is_built_and_is_what_fast_read_uses() -> None:
    probe = _probe(_env())
    assert probe["compiled"], "fast_read would use the Python loop: rebuild (make yamlc)"
    assert probe["file"].endswith(".so")


@pytest.mark.parametrize("value", ["1", "yes"])
def test_the_environment_variable_forces_the_python_loop(value: str) -> None:
    probe = _probe(_env(ROSRECONF_PURE_YAML=value))
    assert probe["python"] and not probe["compiled"]


@pytest.mark.parametrize("value", ["", "0"])
def test_the_environment_variable_off_keeps_the_compiled_loop(value: str) -> None:
    assert _probe(_env(ROSRECONF_PURE_YAML=value))["compiled"]


def test_parse_reads_through_the_compiled_loop(monkeypatch: pytest.MonkeyPatch) -> None:
    # A spy around the real reader: yamlsource.parse_plain goes through it, once per file,
    # and returns what it built.
    calls: list[Any] = []

    def spy(*args: Any) -> Any:
        calls.append(_yamlc.read(*args))
        return calls[-1]

    monkeypatch.setattr(yamlfast, "COMPILED_READ", spy)
    monkeypatch.setattr(ys, "FAST_LOADER", yaml.CSafeLoader)
    tree, plain = ys.parse_plain(LIBRARY.encode(), "lib.yaml")
    [(built_tree, built_plain)] = calls
    assert tree is built_tree and plain is built_plain


@pytest.mark.parametrize("path", BUNDLED, ids=lambda p: p.name)
def test_the_bundled_files_are_read_in_c_not_declined(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    got = _read(text)
    assert got is not None
    assert repr(got) == repr(_python_loop(text))
    tree, plain = got
    assert repr(plain) == repr(to_plain(tree))


def test_a_generated_library_reads_the_same_in_c_and_in_python() -> None:
    # rosreconf generate's libraries are what the C loop is for: many roles, flow mappings,
    # metrics (numbers resolved once per distinct text), dynamics.
    text = generate(60, 10, 0.2, 7).library
    got = _read(text)
    assert got is not None
    assert repr(got) == repr(_python_loop(text))


def _traced_growth(read: Callable[[], object], rounds: int) -> int:
    """Return the bytes still allocated after ``rounds`` more reads than a warm-up."""
    for _ in range(20):  # warm up: caches, free lists, interned strings
        read()
    gc.collect()
    tracemalloc.start()
    try:
        gc.collect()
        before = tracemalloc.get_traced_memory()[0]
        for _ in range(rounds):
            read()
        gc.collect()
        return tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()


class _FakeFailure(Exception):
    """Raised by the fake callables below: a fault the real parts never show."""


def _fake_failing_resolve(text: str) -> Scalar:
    if text == "fail":
        raise _FakeFailure(text)
    return resolve_plain(text)


def _raised(read: Callable[[], object]) -> object:
    """Call ``read``, which must raise ``_FakeFailure``; return the exception."""
    with pytest.raises(_FakeFailure) as caught:
        read()
    return caught.value


LEAK_CASES: dict[str, Callable[[], object]] = {
    "accepted": lambda: _read(LIBRARY),
    "declined, duplicate key deep inside": lambda: _read("a:\n  b: [1, {c: 2, c: 3}]\n"),
    "declined, too deep": lambda: _read("a: " + "[" * 40 + "]" * 40 + "\n"),
    "declined, libyaml's syntax error": lambda: _read("a: {b: [1, 2\nc: d\n"),
    "declined, block scalar header comment": lambda: _read("a: [1, 2]\nb: |#\n  x\n"),
    "declined, key waiting": lambda: _read("a:\n  b: {c: *x}\n"),
    "raised in the middle": lambda: _raised(
        lambda: _read("a:\n  b: [x, {c: fail}]\n", resolve=_fake_failing_resolve)
    ),
    "plain only, accepted": lambda: _plain(LIBRARY),
    "plain only, declined, duplicate key deep inside": lambda: _plain(
        "a:\n  b: [1, {c: 2, c: 3}]\n"
    ),
    "plain only, declined, too deep": lambda: _plain("a: " + "[" * 40 + "]" * 40 + "\n"),
    "plain only, declined, libyaml's syntax error": lambda: _plain("a: {b: [1, 2\nc: d\n"),
    "plain only, declined, key waiting": lambda: _plain("a:\n  b: {c: *x}\n"),
    "plain only, raised in the middle": lambda: _raised(
        lambda: _plain("a:\n  b: [x, {c: fail}]\n", resolve=_fake_failing_resolve)
    ),
}


@pytest.mark.parametrize("case", LEAK_CASES.values(), ids=LEAK_CASES.keys())
def test_reading_many_times_does_not_grow_memory(case: Callable[[], object]) -> None:
    # One leaked object per read (a Span, a key, an int: 28 bytes or more) would grow 200
    # reads by 5,600 bytes or more; a leaked tree by megabytes.
    growth = _traced_growth(case, 200)
    assert growth < 2000, f"{growth} bytes more after 200 reads"


def test_a_python_exception_propagates_from_resolve_plain() -> None:
    with pytest.raises(_FakeFailure, match="fail"):
        _read("a: [x, fail]\n", resolve=_fake_failing_resolve)


def test_a_memory_error_propagates_from_a_node_constructor() -> None:
    built = 0

    def fake_scalar_out_of_memory(*args: Any) -> YScalar:
        nonlocal built
        built += 1
        if built == 3:
            raise MemoryError
        return YScalar(*args)

    with pytest.raises(MemoryError):
        _read("a: 1\nb: [2, 3]\n", scalar=fake_scalar_out_of_memory)


def test_an_exception_from_the_header_check_propagates() -> None:
    def fake_failing_check(text: str, index: int) -> object:
        raise _FakeFailure(index)

    with pytest.raises(_FakeFailure):
        _read("a: |\n  x\n", header_comment=fake_failing_check)
    assert _read("a: 'x'\n", header_comment=fake_failing_check) is not None  # only for | and >


def test_the_header_check_is_asked_at_the_scalar_where_python_asks_it() -> None:
    asked: list[int] = []

    def spy(text: str, index: int) -> object:
        asked.append(index)
        return HEADER_COMMENT(text, index)

    text = "é: x\nb: |\n  y\nc: >-\n  z\n"
    assert _read(text, header_comment=spy) is not None
    assert [text[i] for i in asked] == ["|", ">"]  # character offsets, as PyYAML's marks


@pytest.mark.parametrize("depth", [0, 1, 2, 5, MAX_DEPTH])
def test_the_depth_limit_is_the_one_passed_in(depth: int) -> None:
    nested = "[" * depth + "]" * depth + "\n" if depth else "x\n"
    deeper = "[" * (depth + 1) + "]" * (depth + 1) + "\n"
    assert _read(nested, max_depth=depth) is not None
    assert _read(deeper, max_depth=depth) is None


def test_nesting_to_the_limit_reads_the_same_in_c_and_in_python() -> None:
    # Block collections, each one level deeper, up to MAX_DEPTH open at once.
    # k0 .. k29: 30 mappings, then a block sequence holding a flow one: 32.
    text = "".join("  " * i + f"k{i}:\n" for i in range(MAX_DEPTH - 2))
    text += "  " * (MAX_DEPTH - 2) + "- [leaf]\n"
    got = _read(text)
    assert got is not None
    assert repr(got) == repr(_python_loop(text))
    assert _read(text, max_depth=MAX_DEPTH - 1) is None


@pytest.mark.parametrize(
    ("args", "error"),
    [
        ((b"a: 1\n",), TypeError),  # bytes, not str
        (("a: 1\n", "f.yaml", -1), ValueError),  # a negative depth
        (("a: 1\n", "f.yaml", "32"), TypeError),  # a depth that is no int
        (("a: 1\n", "f.yaml", 32, dict), TypeError),  # a span type that is no tuple
    ],
)
def test_bad_arguments_are_refused(args: tuple[Any, ...], error: type[Exception]) -> None:
    full = ("a: 1\n", "f.yaml", MAX_DEPTH, Span, YScalar, YMapping, YSequence)
    full += (resolve_plain, HEADER_COMMENT)
    with pytest.raises(error):
        _yamlc.read(*args, *full[len(args) :])
    with pytest.raises(TypeError):
        _yamlc.read(*full[:8])  # type: ignore[call-arg]


def test_an_empty_text_is_no_tree() -> None:
    assert _read("") == (None, None)
    assert _read("# only a comment\n") == (None, None)
    assert _plain("") == (None, None)


@pytest.mark.parametrize("path", BUNDLED, ids=lambda p: p.name)
def test_without_positions_the_plain_data_is_the_same_and_no_node_is_made(path: Path) -> None:
    # A spy in place of every node type and Span: without positions none is ever called.
    def never(*args: Any) -> Any:
        raise AssertionError("a node was built without positions")

    text = path.read_text(encoding="utf-8")
    full = _read(text)
    with pytest.raises(AssertionError, match="a node was built"):
        _read(text, scalar=never)  # the spy works: with positions it is called
    plain = _plain(text, scalar=never)
    assert plain is not None and plain[0] is None
    assert repr(plain[1]) == repr(full[1])
    saved = yamlfast.COMPILED_READ
    yamlfast.COMPILED_READ = None
    try:  # the Python loop, its twin and reference, gives the same
        python = yamlfast.fast_read(text, "f.yaml", yaml.CSafeLoader, positions=False)
    finally:
        yamlfast.COMPILED_READ = saved
    assert repr(python) == repr(plain)


@pytest.mark.parametrize("depth", [0, 2, MAX_DEPTH])
def test_without_positions_the_depth_limit_is_the_same(depth: int) -> None:
    nested = "[" * depth + "]" * depth + "\n" if depth else "x\n"
    deeper = "[" * (depth + 1) + "]" * (depth + 1) + "\n"
    assert _plain(nested, max_depth=depth) is not None
    assert _plain(deeper, max_depth=depth) is None


def test_the_node_types_are_all_given_or_all_none() -> None:
    rest = (resolve_plain, HEADER_COMMENT)
    for mixed in [(None, YScalar, YMapping, YSequence), (Span, YScalar, None, YSequence)]:
        with pytest.raises(TypeError, match="all given or all None"):
            _yamlc.read("a: 1\n", "f.yaml", MAX_DEPTH, *mixed, *rest)
