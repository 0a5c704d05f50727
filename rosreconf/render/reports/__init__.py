"""Text and JSON reports of the verbs' results: one module per verb, one interface per module.

check-jsonschema's pattern: a verb's reporters share one interface (``render(result) -> str``)
and the CLI picks one from the module's ``REPORTERS`` dict by ``Output``; the CLI writes the
text where it belongs. Reporters never print, so the same result can be written as text, as
one JSON document (schemas in ``rosreconf/data/output-*.schema.json``) or tested directly.
"""

from __future__ import annotations

import enum


class Output(enum.StrEnum):
    """The report kinds of a verb: text for people, one JSON document for programs."""

    TEXT = "text"
    JSON = "json"

    @classmethod
    def of(cls, as_json: bool) -> Output:
        """Return the kind a ``--json`` flag asks for."""
        return cls.JSON if as_json else cls.TEXT
