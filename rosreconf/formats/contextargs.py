"""Read ``--context NAME=VALUE`` options against a library's context declarations.

A value is read as the library's conditions on its name compare it: a number for bounds
(``at_least``, ``at_most``), ``true``/``false`` for a boolean ``equals``, the text itself for
a string ``equals``. Then ``ruled_out`` says which components the values rule out and why;
``formats.selection`` merges them with ``--fail``'s, so every solver treats a ruled-out
component exactly as a failed one.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping, Sequence

from rosreconf.errors import UsageError
from rosreconf.model import ComponentLibrary
from rosreconf.model.context import ContextValue, RuledOut, rule_out, unset

_BOOLEANS = {"true": True, "false": False}


def context_values(library: ComponentLibrary, items: Sequence[str]) -> dict[str, ContextValue]:
    """Parse ``NAME=VALUE`` items (later ones win) into context values.

    Raises:
        UsageError: an item is not ``NAME=VALUE``, names no declared context, or its value
            is not what the library's conditions compare it as.
    """
    declared = [v.name for v in library.context]
    kinds = {w.name: w for c in library for w in c.when}
    values: dict[str, ContextValue] = {}
    for item in items:
        name, sep, text = (part.strip() for part in item.partition("="))
        if not sep or not name or not text:
            raise UsageError(f"--context {item}: write NAME=VALUE, e.g. visibility=2.0")
        if name not in declared:
            close = difflib.get_close_matches(name, declared, n=1)
            known = f" (did you mean {close[0]}?)" if close else ""
            if not close:
                known = f" (declared: {', '.join(declared)})" if declared else ""
            raise UsageError(f"--context {item}: the library declares no context '{name}'{known}")
        cond = kinds.get(name)
        if cond is not None and isinstance(cond.equals, bool):
            if text.lower() not in _BOOLEANS:
                raise UsageError(f"--context {item}: {name} is a boolean: write true or false")
            values[name] = _BOOLEANS[text.lower()]
        elif cond is not None and isinstance(cond.equals, str):
            values[name] = text
        else:
            values[name] = _number(item, name, text)
    return values


def _number(item: str, name: str, text: str) -> float:
    try:
        number = float(text)
    except ValueError:
        number = math.nan
    if not math.isfinite(number):
        raise UsageError(f"--context {item}: {name} is a number: write e.g. {name}=2.0")
    return number


def ruled_out(
    library: ComponentLibrary,
    values: Mapping[str, ContextValue],
    *,
    ignore_unset: bool,
) -> tuple[RuledOut, ...]:
    """Return the components ``values`` rule out, with why.

    Raises:
        UsageError: a condition is on a context value not given, and ``ignore_unset`` is
            false (a component must not be thought usable by forgetting a value).
    """
    missing = unset(library, values)
    if missing and not ignore_unset:
        name, user = next(iter(missing.items()))
        more = f" (and {', '.join(sorted(set(missing) - {name}))})" if len(missing) > 1 else ""
        raise UsageError(
            f"{user} is usable only under a condition on context '{name}'{more}, which was "
            f"not given: add --context {name}=VALUE, or --ignore-context to take conditions "
            "on values not given to hold"
        )
    return rule_out(library, values)


def unset_names(library: ComponentLibrary, values: Mapping[str, ContextValue]) -> tuple[str, ...]:
    """Return the context names some condition uses that ``values`` does not give, sorted."""
    return tuple(sorted(unset(library, values)))
