"""Report ``rosreconf enumerate`` as it goes: text lines, or one JSON document, streamed.

Both reporters share one interface, called per schema and per configuration as the solver
finds them, so memory stays flat however many configurations there are; each writes through
the ``write`` callable it is given (the CLI's stdout). The JSON document is
output-enumerate.schema.json.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from rosreconf import jsonout
from rosreconf.formats.selection import Selection
from rosreconf.model import EMPTY, Configuration, InteroperabilitySchema
from rosreconf.model.validity import graph_dict, ros_graph
from rosreconf.render.reports import Output
from rosreconf.render.reports.context import context_doc, context_text, reworded


class EnumerateReporter(Protocol):
    """Write the listing of the selected schemas, piece by piece."""

    def begin_schema(self, s: InteroperabilitySchema) -> None:
        """Start a schema's part."""
        ...

    def configuration(
        self, sel: Selection, s: InteroperabilitySchema, config: Configuration, n: int
    ) -> None:
        """Write the ``n``-th configuration of ``s``."""
        ...

    def end_schema(
        self,
        total: int | None,
        listed: int,
        *,
        limit_reached: bool,
        why: str | None,
        optimum: dict[str, object] | None = None,
    ) -> None:
        """Close a schema's part with its count (None: not counted) or why none.

        ``optimum`` (``--best``): the weights, weighted sum and engine of the one listed.
        """
        ...

    def close(self) -> None:
        """Finish the report."""
        ...


class TextReporter:
    """A heading per schema, one numbered line per configuration, a count or the why-not."""

    def __init__(self, sel: Selection, write: Callable[[str], None]) -> None:
        self.write = write
        self.sel = sel
        if sel.has_context:
            write(context_text(sel))

    def begin_schema(self, s: InteroperabilitySchema) -> None:
        """Write the schema's heading."""
        self.write(_heading(s))

    def configuration(
        self, sel: Selection, s: InteroperabilitySchema, config: Configuration, n: int
    ) -> None:
        """Write one numbered line of components."""
        self.write(f"  {n:>3}. {_row(config)}\n")

    def end_schema(
        self,
        total: int | None,
        listed: int,
        *,
        limit_reached: bool,
        why: str | None,
        optimum: dict[str, object] | None = None,
    ) -> None:
        """Write the count, the limit note, what the optimum is optimal for, or why none."""
        if optimum is not None:
            self.write(_optimum_line(optimum) + "\n")
            return
        self.write(_summary(total, listed, _why(why, self.sel)))

    def close(self) -> None:
        """Nothing to close in text."""


def _optimum_line(optimum: dict[str, object]) -> str:
    """Say what the listed configuration is optimal for, and who proved it."""
    weights = optimum["weights"]
    assert isinstance(weights, dict)
    goal = ", ".join(f"{m}={w:g}" for m, w in weights.items()) or "no metric"
    return (
        f"  optimal for {goal}: weighted sum {optimum['weighted_sum']:g} "
        f"(proven by {optimum['engine']})\n"
    )


def _why(why: str | None, sel: Selection) -> str | None:
    """Say why there is none with a ruled-out component's condition where the solver, which
    sees it as unusable, says "has failed" (as ``plan``'s report does)."""
    return None if why is None else reworded([why], sel)[0]


def _heading(s: InteroperabilitySchema) -> str:
    return f"{s.display_name} ({s.name}):\n"


def _summary(total: int | None, listed: int, why: str | None) -> str:
    if total is None:
        return f"  {listed} configuration(s) listed; stopped at --limit\n\n"
    if why:
        return f"  no configuration: {why}\n\n"
    jsonout.allow_big_ints()  # counts of 10,000-role libraries have thousands of digits
    digits = str(total)
    # Counts can have a thousand digits, far beyond a float: write the estimate from the digits.
    size = f" (about {digits[0]}.{digits[1:4]}e{len(digits) - 1}, {len(digits)} digits)"
    size = size if len(digits) > 15 else ""
    return f"  {total} configuration(s){size}\n\n"


class JsonReporter:
    """Write one JSON document incrementally, so memory stays flat however many there are."""

    def __init__(self, sel: Selection, write: Callable[[str], None]) -> None:
        self.write = write
        self.sel = sel
        self.first_schema = True
        self.first_config = True
        head: dict[str, object] = {
            "library": {"name": sel.library.name, "components": len(sel.library)},
            "files": sel.loaded.files,
            "note": sel.loaded.note,
            "failed": list(sel.failed),
        }
        if sel.has_context:
            head["context"] = context_doc(sel)
        self._w(jsonout.dumps(head)[:-1] + ', "schemas": [')

    def _w(self, text: str) -> None:
        self.write(text)

    def begin_schema(self, s: InteroperabilitySchema) -> None:
        sep = "" if self.first_schema else ", "
        self.first_schema = False
        self.first_config = True
        head = {"name": s.name, "title": s.display_name, "roles": [r.name for r in s.graph.roles]}
        self._w(sep + jsonout.dumps(head)[:-1] + ', "configurations": [')

    def configuration(
        self, sel: Selection, s: InteroperabilitySchema, config: Configuration, n: int
    ) -> None:
        sep = "" if self.first_config else ", "
        self.first_config = False
        doc = {
            "index": n,
            "assignment": config.shown,
            "components": list(config.components),
            "ros_graph": graph_dict(ros_graph(config, sel.library, s)),
        }
        self._w(sep + jsonout.dumps(doc))

    def end_schema(
        self,
        total: int | None,
        listed: int,
        *,
        limit_reached: bool,
        why: str | None,
        optimum: dict[str, object] | None = None,
    ) -> None:
        tail: dict[str, object] = {
            "count": total,
            "count_text": None if total is None else str(total),
            "limit_reached": limit_reached,
            "why_not": _why(why, self.sel),
        }
        if optimum is not None:  # --best: what the configuration is optimal for
            tail["optimum"] = optimum
        self._w("], " + jsonout.dumps(tail)[1:])

    def close(self) -> None:
        self._w("]}\n")


def _row(config: Configuration) -> str:
    """Return a configuration's components in role order, an empty optional role said so."""
    return ", ".join(c if c != EMPTY else f"({r} empty)" for r, c in config.assignment)


REPORTERS: dict[Output, Callable[[Selection, Callable[[str], None]], EnumerateReporter]] = {
    Output.TEXT: TextReporter,
    Output.JSON: JsonReporter,
}
"""The reporter classes by output kind; each is built with the selection and a writer."""
