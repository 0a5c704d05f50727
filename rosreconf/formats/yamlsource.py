"""Read YAML into a tree that remembers where every value was written.

PyYAML's ``safe_load`` forgets positions, follows YAML 1.1 (where ``no`` and ``on`` become
booleans), accepts duplicate keys silently and recurses once per nesting level. Users need
``file:line:column`` in every error, so this module builds its own tree from PyYAML's
event stream (which is produced by a non-recursive state machine) and applies the rules
rosreconf promises:

* safe by construction: no tags other than the standard string ones, nothing is constructed;
* duplicate keys are errors naming both lines;
* anchors and aliases are rejected (they hide structure and allow "billion laughs");
* input over ``MAX_BYTES`` and nesting deeper than ``MAX_DEPTH`` are errors, not crashes;
* plain scalars are resolved with YAML 1.2's core schema: only ``true``/``false`` are
  booleans, so ``no``, ``on`` and ``yes`` stay strings; the written text is always kept
  (``raw``) so a value such as ``0755`` can be reported exactly as the user wrote it.

Three modules do the work: ``yamltree`` (the tree and the YAML 1.2 resolver), ``yamlfast``
(one flat loop over libyaml's events for clean files, declining anything to report or that
libyaml might read differently; compiled in ``_yamlc.c`` when built) and ``yamlbuilder``
(PyYAML's pure parser, the reader of record, with every message). ``parse`` tries the
first and falls back to the second, so answers never depend on whether libyaml is installed.

``parse_plain_only`` is the loader's first try at every file: the plain data alone, built by
the fast reader without a node or a position (positions serve only to report problems), or
``DECLINED`` wherever the fast reader declines or anything else might need reporting; the
loader then reads again with ``parse_plain``, the positioned way.
"""

from __future__ import annotations

import gc

import yaml

from rosreconf.errors import InvalidInputError, Problem
from rosreconf.formats.yamlbuilder import offset_span, read_pure
from rosreconf.formats.yamlfast import DECLINED, Declined, fast_read
from rosreconf.formats.yamltree import (
    MAX_DEPTH,
    Plain,
    Scalar,
    YMapping,
    YNode,
    YScalar,
    YSequence,
    key_span,
    lookup,
    resolve_plain,
    to_plain,
    walk,
)
from rosreconf.model import Span

__all__ = [
    "DECLINED",
    "FAST_LOADER",
    "MAX_BYTES",
    "MAX_DEPTH",
    "Declined",
    "Plain",
    "Scalar",
    "YMapping",
    "YNode",
    "YScalar",
    "YSequence",
    "key_span",
    "lookup",
    "parse",
    "parse_plain",
    "parse_plain_only",
    "resolve_plain",
    "to_plain",
    "too_large",
    "walk",
]

MAX_BYTES = 64 * 1024 * 1024
"""Largest YAML file rosreconf reads: room for a 10,000-role, 10-candidate library (27 MB as
``rosreconf generate`` writes it); the loader reads no more than this of any file."""

FAST_LOADER: type[yaml.CSafeLoader] | None = (
    yaml.CSafeLoader if getattr(yaml, "__with_libyaml__", False) else None
)
"""libyaml's parser when PyYAML was built with it (the wheels are), else None."""


def too_large(file: str, size: int) -> Problem:
    """Return the problem of a file over ``MAX_BYTES`` (checked before reading it whole)."""
    return Problem(
        Span(file, 1, 1),
        f"file is {size} bytes, over the limit of {MAX_BYTES} bytes",
        "split the library into several files",
        code="too-large",
    )


def parse(data: bytes, file: str) -> YNode | None:
    """Parse one YAML document into a positioned tree; ``None`` for an empty file.

    Raises:
        InvalidInputError: with every structural problem found (the YAML syntax errors stop
            parsing at the first one, because nothing after it can be trusted).
    """
    return parse_plain(data, file)[0]


def parse_plain(data: bytes, file: str) -> tuple[YNode | None, Plain]:
    """Parse like ``parse`` and also return the tree as plain data (``to_plain``'s answer).

    The fast reader builds both in one pass over libyaml's events, which saves walking a
    large library's tree a second time for its JSON Schema check.

    Raises:
        InvalidInputError: as ``parse``.
    """
    if len(data) > MAX_BYTES:
        raise InvalidInputError([too_large(file, len(data))])
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        good = data[: exc.start].decode("utf-8", errors="replace")
        raise InvalidInputError(
            [
                Problem(
                    offset_span(file, good, len(good)),
                    "file is not valid UTF-8 text",
                    "save it as UTF-8",
                    code="encoding",
                )
            ]
        ) from None
    if FAST_LOADER is not None:
        # libyaml reads about six times faster. On any problem, and wherever libyaml might
        # read the text differently, the pure reader reads the file again (``yamlfast``).
        collecting = gc.isenabled()
        gc.disable()  # the tree only grows: collections would walk all of it, finding nothing
        try:
            fast = fast_read(text, file, FAST_LOADER)
        finally:
            if collecting:
                gc.enable()
        if not isinstance(fast, Declined):
            return fast
    tree = read_pure(text, file)
    return tree, to_plain(tree)


def parse_plain_only(data: bytes, file: str) -> Plain | Declined:
    """Return the plain data of a clean file, building no tree; else ``DECLINED``.

    Declined wherever ``parse_plain`` would report a problem or read with the pure reader
    (over the size limit, not UTF-8, no libyaml, anything ``fast_read`` declines), so that
    whatever is to be reported is read again, with positions, by ``parse_plain``. The caller
    pauses the cyclic garbage collector (``loader``): the data only grows here.
    """
    if FAST_LOADER is None or len(data) > MAX_BYTES:
        return DECLINED
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return DECLINED
    read = fast_read(text, file, FAST_LOADER, positions=False)
    return read if isinstance(read, Declined) else read[1]
