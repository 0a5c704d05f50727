"""Report ``rosreconf redundancy``: Theorem 10's r, exact and approximate, as text or JSON."""

from __future__ import annotations

from dataclasses import asdict
from typing import Protocol

from rosreconf import jsonout
from rosreconf.analysis.redundancy import RedundancyAnswer
from rosreconf.render.reports import Output

NOTE = (
    "p is read as a component's probability of FAILURE: Theorem 10's formula only makes "
    "sense that way (the paper's text calls it availability)."
)


class RedundancyReporter(Protocol):
    """Render one redundancy answer."""

    def render(self, a: RedundancyAnswer) -> str:
        """Return the whole report."""
        ...


class TextReporter:
    """The needed r, the exact real root, the paper's approximation and its error."""

    def render(self, a: RedundancyAnswer) -> str:
        """Return the table and the note on reading p."""
        return (
            f"Theorem 10 with p = {a.p:g} (failure), N = {a.n}, q = {a.q:g}\n"
            f"  redundancy needed r        {a.r_needed}   ((1 - p^r)^N = {a.achieved:.6f} >= q)\n"
            f"  exact real root            {a.r_exact:.6f}   (of (1 - p^r)^N = q)\n"
            f"  paper's approximation      {a.r_approx:.6f}   "
            f"(log(-log q)/log p - log N/log p)\n"
            f"  approximation error        {a.error:+.6f}   ({a.relative_error:+.3%})\n"
            f"note: {NOTE}\n"
        )


class JsonReporter:
    """Every field of the answer, and the note, as one JSON document."""

    def render(self, a: RedundancyAnswer) -> str:
        """Return the JSON document."""
        return jsonout.dumps({**asdict(a), "note": NOTE}, indent=2) + "\n"


REPORTERS: dict[Output, RedundancyReporter] = {
    Output.TEXT: TextReporter(),
    Output.JSON: JsonReporter(),
}
