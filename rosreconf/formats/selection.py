"""Load and check the input of a command: files, ``--fail`` and ``--only`` names.

Every command picks its files the same way (``loader.load_checked``) and checks ``--fail``
and ``--only`` names the same way, so their answers are always about the same library and
schemas.
"""

from __future__ import annotations

import difflib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.formats.loader import Loaded, load_checked
from rosreconf.model import ComponentLibrary, InteroperabilitySchema


@dataclass(frozen=True)
class Selection:
    """The checked input of a solving command.

    Attributes:
        loaded: what was loaded (files, note).
        library: L, all library files joined.
        schemas: the schemas to work on, in file order.
        failed: the failed components, as given (validated against L).
    """

    loaded: Loaded
    library: ComponentLibrary
    schemas: tuple[InteroperabilitySchema, ...]
    failed: tuple[str, ...]


def select(
    libraries: Sequence[Path] | None,
    schemas: Sequence[Path] | None,
    failed: Sequence[str] | None = None,
    only: Sequence[str] | None = None,
) -> Selection:
    """Load and check the input, and validate ``--fail`` and ``--only`` names.

    Raises:
        InvalidInputError: the files have errors.
        UsageError: an unknown component or schema name was given.
    """
    loaded = load_checked(libraries or [], schemas or [])
    library = loaded.library
    if not library.components:
        raise UsageError("no component library was given or found")
    if not loaded.schemas:
        raise UsageError("no interoperability schema was given or found")
    names = [c.name for c in library]
    for name in failed or []:
        if name not in library:
            raise UsageError(f"--fail {name}: no such component{_did_you_mean(name, names)}")
    chosen = list(loaded.schemas)
    if only:
        known = [s.name for s in chosen]
        for name in only:
            if name not in known:
                raise UsageError(f"--only {name}: no such schema{_did_you_mean(name, known)}")
        chosen = [s for s in chosen if s.name in only]
    return Selection(loaded, library, tuple(chosen), tuple(dict.fromkeys(failed or [])))


def _did_you_mean(name: str, choices: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, choices, n=1)
    return f" (did you mean {close[0]}?)" if close else ""
