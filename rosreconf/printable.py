"""Quote text for a terminal: a path, a name, or text that came over the wire.

Such text may carry escape sequences that retitle or clear a terminal, or reorder what it
shows: a file name is any bytes but ``/`` and NUL, a node name or a status text comes from
another process. Everything rosreconf shows a person goes through one of these two functions
(the CLI's consoles and its text reports call ``terminal_text``; messages that quote a text
from the wire cut it with ``printable``), so no escape reaches a terminal.
"""

from __future__ import annotations

_SHOWN_CHARS = 200
"""How much of a text from the wire an error message quotes."""

_KEPT = frozenset("\n\t")
"""The control characters a message may carry itself (its own lines and indents)."""


def _escaped(char: str) -> str:
    """Return ``char`` as Python writes it in a string literal (``\\x1b``, ``\\u202e``)."""
    return char.encode("unicode_escape").decode("ascii")


def terminal_text(text: str) -> str:
    """Return ``text`` with every unprintable character but line breaks and tabs escaped.

    Escape sequences (ESC), the bell, C1 controls and bidirectional overrides in a path or a
    name are shown as ``\\x1b``, ``\\x07``, ``\\u202e``: visible, and harmless.
    """
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() or c in _KEPT else _escaped(c) for c in text)


def printable(text: str, limit: int = _SHOWN_CHARS) -> str:
    """Return ``text`` fit for a terminal on one line, cut to ``limit`` characters.

    Anything that came over the wire (a status text, an HTTP reason phrase, a name) may carry
    escape sequences, and line breaks that would forge a line of its own; messages quote it
    only through this function.
    """
    shown = "".join(c if c.isprintable() else _escaped(c) for c in text)
    return shown if len(shown) <= limit else shown[: limit - 3] + "..."
