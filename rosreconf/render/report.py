"""Turn problems in user files into text, JSON or GitHub annotations.

Reporters share one interface so the CLI's ``--format`` choices come from ``REPORTERS``
(check-jsonschema's pattern). A reporter returns the whole text; the CLI decides where it
goes, so library code never prints.
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from typing import Protocol

from rosreconf import jsonout
from rosreconf.errors import Problem, Severity
from rosreconf.printable import terminal_text


class OutputFormat(enum.StrEnum):
    """The formats ``rosreconf validate --format`` offers."""

    TEXT = "text"
    JSON = "json"
    GITHUB = "github"


def problem_dict(p: Problem) -> dict[str, object]:
    """Return one problem as the JSON object documented in docs/json.md."""
    return {
        "file": p.span.file,
        "line": p.span.line,
        "column": p.span.column,
        "severity": p.severity.value,
        "code": p.code,
        "message": p.message,
        "hint": p.hint,
    }


class Reporter(Protocol):
    """Render the outcome of validating ``files``."""

    def render(self, files: Sequence[str], problems: Sequence[Problem], note: str) -> str:
        """Return the report text (ends with a newline when not empty)."""
        ...


def _counts(problems: Sequence[Problem]) -> tuple[int, int]:
    errors = sum(p.severity is Severity.ERROR for p in problems)
    return errors, len(problems) - errors


class TextReporter:
    """One ``file:line:column: severity: message (hint)`` line per problem, then a summary."""

    def render(self, files: Sequence[str], problems: Sequence[Problem], note: str) -> str:
        """Return the problems and a one-line summary."""
        lines = [terminal_text(str(p)) for p in problems]  # a path may hold any byte
        errors, warnings = _counts(problems)
        if errors:  # name how many files hold the errors, not how many were read
            bad = {p.span.file for p in problems if p.severity is Severity.ERROR}
            verdict = f"{min(len(bad), len(files)) or 1} of {len(files)} file(s) invalid"
        else:
            verdict = f"{len(files)} file(s) valid"
        lines.append(
            f"{verdict}: {errors} error(s), {warnings} warning(s)" + (f" [{note}]" if note else "")
        )
        return "\n".join(lines) + "\n"


class JsonReporter:
    """One JSON document: verdict, files, counts and every problem."""

    def render(self, files: Sequence[str], problems: Sequence[Problem], note: str) -> str:
        """Return the JSON document."""
        errors, warnings = _counts(problems)
        doc = {
            "valid": errors == 0,
            "files": list(files),
            "errors": errors,
            "warnings": warnings,
            "note": note,
            "problems": [problem_dict(p) for p in problems],
        }
        return jsonout.dumps(doc, indent=2) + "\n"


def _escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(text: str) -> str:
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


class GithubReporter:
    """GitHub Actions workflow commands: ``::error file=F,line=L,col=C::message``."""

    def render(self, files: Sequence[str], problems: Sequence[Problem], note: str) -> str:
        """Return one annotation per problem."""
        lines = []
        for p in problems:
            level = "error" if p.severity is Severity.ERROR else "warning"
            message = p.message + (f" ({p.hint})" if p.hint else "")
            lines.append(
                f"::{level} file={_escape_property(p.span.file)},line={p.span.line},"
                f"col={p.span.column},title=rosreconf {p.code}::{_escape_data(message)}"
            )
        return "".join(line + "\n" for line in lines)


REPORTERS: dict[OutputFormat, Reporter] = {
    OutputFormat.TEXT: TextReporter(),
    OutputFormat.JSON: JsonReporter(),
    OutputFormat.GITHUB: GithubReporter(),
}
