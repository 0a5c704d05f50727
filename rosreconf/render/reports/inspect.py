"""Report ``rosreconf inspect``: whether the live system conforms, and every difference."""

from __future__ import annotations

from typing import Protocol

from rosreconf import jsonout
from rosreconf.model import InteroperabilitySchema
from rosreconf.printable import printable
from rosreconf.render.reports import Output
from rosreconf.ros.conformance import Conformance


class InspectReporter(Protocol):
    """Render one comparison of a live graph with a schema's configuration."""

    def render(self, result: Conformance, schema: InteroperabilitySchema) -> str:
        """Return the whole report."""
        ...


class TextReporter:
    """A verdict line naming the master and the schema, one line per finding, the standbys."""

    def render(self, result: Conformance, schema: InteroperabilitySchema) -> str:
        """Return the verdict and the findings."""
        head = "conforms to" if result.ok else "does NOT conform to"
        where = printable(result.live.master_uri)
        lines = [f"{where}: the live system {head} the {schema.display_name} configuration\n"]
        # Names come from the network: nothing in them may drive the terminal.
        lines += [f"  {f.code}: {printable(f.message, 10_000)}\n" for f in result.findings]
        if result.standby:  # not findings: the library's managed nodes held out of service
            lines.append("standby (managed nodes of the library, out of service):\n")
            lines += [
                f"  {printable(s.node)} ({', '.join(s.components)}): {s.state}\n"
                for s in result.standby
            ]
        return "".join(lines)


class JsonReporter:
    """``Conformance.to_dict`` as one JSON document (output-inspect.schema.json)."""

    def render(self, result: Conformance, schema: InteroperabilitySchema) -> str:
        """Return the JSON document."""
        return jsonout.dumps(result.to_dict(), indent=2) + "\n"


REPORTERS: dict[Output, InspectReporter] = {
    Output.TEXT: TextReporter(),
    Output.JSON: JsonReporter(),
}
