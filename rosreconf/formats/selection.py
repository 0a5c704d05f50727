"""Load and check the input of a command: files, ``--fail`` and ``--only`` names.

Every command picks its files the same way (``loader.load_checked``) and checks ``--fail``
and ``--only`` names the same way, so their answers are always about the same library and
schemas.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from rosreconf.errors import UsageError
from rosreconf.formats.contextargs import context_values, ruled_out, unset_names
from rosreconf.formats.loader import Loaded, load_checked
from rosreconf.model import ComponentLibrary, InteroperabilitySchema
from rosreconf.model.context import ContextValue, RuledOut


@dataclass(frozen=True)
class Selection:
    """The checked input of a solving command.

    Attributes:
        loaded: what was loaded (files, note).
        library: L, all library files joined.
        schemas: the schemas to work on, in file order.
        failed: the components treated as unusable: ``--fail``'s as given (validated
            against L), then those context rules out (``ruled_out``), each once.
        context: the context values given (``--context``).
        ruled_out: the components whose ``when`` conditions fail under ``context``, with why.
        ignored: context names some condition uses but ``--context`` did not give, taken to
            hold (``--ignore-context``).
        fail_given: ``--fail``'s components alone (``analyse``'s thresholds vary context
            and keep these failed throughout).
    """

    loaded: Loaded
    library: ComponentLibrary
    schemas: tuple[InteroperabilitySchema, ...]
    failed: tuple[str, ...]
    context: Mapping[str, ContextValue] = field(default_factory=dict)
    ruled_out: tuple[RuledOut, ...] = ()
    ignored: tuple[str, ...] = ()
    fail_given: tuple[str, ...] = ()

    @property
    def has_context(self) -> bool:
        """Tell whether the library declares context or conditions (reports then say it)."""
        return bool(self.library.context or self.context or self.ruled_out or self.ignored)


def select(
    libraries: Sequence[Path] | None,
    schemas: Sequence[Path] | None,
    failed: Sequence[str] | None = None,
    only: Sequence[str] | None = None,
    context: Sequence[str] | None = None,
    *,
    ignore_context: bool = False,
) -> Selection:
    """Load and check the input, validate ``--fail`` and ``--only`` names, apply ``--context``.

    ``context`` None is a command that does not apply context: every component is usable
    whatever its conditions (``--context`` not given is ``[]``: conditions then need values).

    Raises:
        InvalidInputError: the files have errors.
        UsageError: an unknown component or schema name was given, a ``--context`` item is
            malformed, or a condition is on a context value not given (and not
            ``ignore_context``).
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
    given = tuple(dict.fromkeys(failed or []))
    if context is None:  # a command that does not apply context (launch, graph, watch...)
        return Selection(loaded, library, tuple(chosen), given, fail_given=given)
    values = context_values(library, context)
    out = ruled_out(library, values, ignore_unset=ignore_context)
    unusable = tuple(dict.fromkeys([*given, *(r.component for r in out)]))
    ignored = unset_names(library, values)
    return Selection(loaded, library, tuple(chosen), unusable, values, out, ignored, given)


def _did_you_mean(name: str, choices: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, choices, n=1)
    return f" (did you mean {close[0]}?)" if close else ""
