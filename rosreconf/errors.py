"""The one error family of rosreconf, and the problems it reports about user files.

Library code raises these and never prints or exits; only ``rosreconf.cli.app`` turns them into
messages and exit codes. Problems in user files are *collected* (every file, every problem)
and raised together, because a user fixing a library wants the whole list in one run.
"""

from __future__ import annotations

import enum
import re
from collections.abc import Iterable
from dataclasses import dataclass

from rosreconf.model import Span


class ExitCode(enum.IntEnum):
    """The documented exit codes of every rosreconf command."""

    OK = 0
    FAILED = 1
    """The check failed: invalid input files, no configuration possible, non-conformant graph."""
    USAGE = 2
    """The command line was wrong: unknown option, missing file, bad value."""
    PLANNER = 3
    """An external program (planner, graphviz, roslaunch) is missing, failed or timed out, or
    rosreconf itself ran out of memory (or of disk for a document it spools)."""
    INTERRUPTED = 130
    """Stopped by Ctrl-C or SIGINT (128 + SIGINT, as the shell reports it)."""
    TERMINATED = 143
    """Stopped by SIGTERM (128 + SIGTERM); the programs and workers it ran are stopped too."""


class Severity(enum.StrEnum):
    """How bad a problem is: errors make a file invalid, warnings do not."""

    ERROR = "error"
    WARNING = "warning"


SHOWN_CHARACTERS = 120
"""The most characters of one user text (a name, a value) a message quotes; the rest is cut
and its length said, so that a 1 MB name gives a one-line message, not a megabyte."""
MESSAGE_CHARACTERS = 2000
"""The most characters of a whole message; a longer one keeps its start and its end."""
_QUOTED = re.compile(r"'([^'\n]*)'")
"""A quoted text; matched pair after pair from the left, so a gap between two quotes is never
taken for one."""


def clip(text: str, limit: int = SHOWN_CHARACTERS) -> str:
    """Shorten one user text for a message: its first ``limit`` characters and its length."""
    if len(text) <= limit:
        return text
    return f"{text[:limit]}... ({len(text):,} characters)"


def clip_message(message: str) -> str:
    """Shorten the user texts a message quotes ('...'), then the message itself if still long.

    The one place every message passes through (``Problem`` and ``RosreconfError``), so no
    reporter can echo a megabyte of a user's file.
    """
    message = _QUOTED.sub(lambda m: f"'{clip(m.group(1))}'", message)
    if len(message) <= MESSAGE_CHARACTERS:
        return message
    keep = MESSAGE_CHARACTERS // 2
    cut = len(message) - 2 * keep
    return f"{message[:keep]} ... [{cut:,} characters cut] ... {message[-keep:]}"


@dataclass(frozen=True, order=True)
class Problem:
    """One thing wrong in a user file, with where it is and how to fix it.

    Attributes:
        span: file, line and column of the offending value.
        message: what is wrong, in one sentence.
        hint: how to fix it (may be empty).
        code: a short stable identifier (``duplicate-key``) for tests and JSON consumers.
        severity: error or warning.
    """

    span: Span
    message: str
    hint: str = ""
    code: str = "invalid"
    severity: Severity = Severity.ERROR

    def __post_init__(self) -> None:
        object.__setattr__(self, "message", clip_message(self.message))
        object.__setattr__(self, "hint", clip_message(self.hint))

    def __str__(self) -> str:
        text = f"{self.span}: {self.severity}: {self.message}"
        return f"{text} ({self.hint})" if self.hint else text


class RosreconfError(Exception):
    """The base of every error rosreconf raises on purpose; carries its exit code."""

    exit_code: ExitCode = ExitCode.FAILED

    def __str__(self) -> str:
        return clip_message(super().__str__())


class InvalidInputError(RosreconfError):
    """User files are invalid; ``problems`` lists every problem found, sorted by position."""

    exit_code = ExitCode.FAILED

    def __init__(self, problems: Iterable[Problem]) -> None:
        self.problems = tuple(sorted(problems))
        first = str(self.problems[0]) if self.problems else "invalid input"
        more = len(self.problems) - 1
        super().__init__(first + (f" (and {more} more problem(s))" if more > 0 else ""))


class UsageError(RosreconfError):
    """The command line asked for something impossible (unknown component, missing file)."""

    exit_code = ExitCode.USAGE


class ExternalToolError(RosreconfError):
    """An external program is missing, failed, or ran out of time or memory."""

    exit_code = ExitCode.PLANNER


class UnsettledGraphError(ExternalToolError):
    """A read caught the graph half-announced: the source answers, and its nodes are changing.

    ROS 2: a participant announces endpoints its newest node list does not name yet (nodes
    being started or configured). Not a lost source: ``watch`` reads again on its next poll
    and says so only when it lasts (``rosreconf.ros.polling``); a one-off read fails with it.
    """


class OutOfResourcesError(RosreconfError):
    """The run needed more memory (or spool disk) than the machine or its limits allow.

    Exit 3, as an external program that ran out of memory: the input was not wrong (exit 1
    would say "the check failed") and the command line was not (exit 2).
    """

    exit_code = ExitCode.PLANNER
