"""Quote text that came over the wire (a status text, an HTTP reason phrase, a node name).

Shared by both middlewares and the reports: such text may carry escape sequences that retitle
or clear a terminal, or reorder what it shows, so messages quote it only through ``printable``.
"""

from __future__ import annotations

_SHOWN_CHARS = 200
"""How much of a text from the wire an error message quotes."""


def printable(text: str, limit: int = _SHOWN_CHARS) -> str:
    """Return ``text`` fit for a terminal: control and other unprintable characters escaped.

    Anything that came over the wire (a status text, an HTTP reason phrase, a name) may carry
    escape sequences that retitle or clear a terminal, or reorder what it shows; messages
    quote it only through this function, cut to ``limit`` characters.
    """
    shown = "".join(
        c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in text
    )
    return shown if len(shown) <= limit else shown[: limit - 3] + "..."
