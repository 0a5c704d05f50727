"""An optional role's empty choice, as the compiled tables and the solvers see it.

A configuration may leave an optional role empty (``rosreconf.model.EMPTY``; rule
``optional-role``). The solvers never see ``EMPTY``: ``compile_instance`` gives each optional
role one more candidate, its empty choice, so every encoding (clingo, counting, elimination,
the dense grids, PDDL) handles it as any other candidate, and configurations are translated
at the solvers' edges (``as_chosen`` out, ``as_candidate`` in).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from rosreconf.model import EMPTY, Component, ComponentLibrary, Role

EMPTY_PREFIX = "empty-"
"""How the compiled tables name an optional role's empty choice: ``empty-<role>``.

One candidate per optional role, never a component's name (model names hold no ``-``) and
never another role's, so no rule naming components (one role each, needs, excludes) can
mistake it for a component; it provides and requires nothing, every edge touching it is
realised, it fails never and costs nothing. Every solver sees it as one more candidate
(rule ``optional-role``); configurations leaving the solvers hold ``EMPTY`` instead."""


def empty_choice(role: str) -> str:
    """Return the compiled tables' name of optional role ``role``'s empty choice."""
    return EMPTY_PREFIX + role


def is_empty_choice(name: str) -> bool:
    """Tell whether a candidate's name is an optional role's empty choice (no component)."""
    return name.startswith(EMPTY_PREFIX)


def as_chosen(name: str) -> str:
    """Return a candidate's name as a configuration holds it (``EMPTY`` for an empty choice)."""
    return EMPTY if name.startswith(EMPTY_PREFIX) else name


def as_candidate(role: str, name: str) -> str:
    """Return what a configuration holds for ``role`` as the compiled tables' candidate name."""
    return empty_choice(role) if name == EMPTY else name


def with_empty_choices(
    library: ComponentLibrary, roles: Sequence[Role], domains: list[list[Component]]
) -> ComponentLibrary:
    """Append each optional role's empty choice to its domain, and return the library with them.

    The empty choice provides and requires nothing, fails never (probability 0) and has no
    metrics; the library returned holds it so that solvers look it up like any component.
    """
    empties = []
    for role, dom in zip(roles, domains, strict=True):
        if role.optional:
            empty = Component(empty_choice(role.name), role.abstraction, failure_probability=0.0)
            dom.append(empty)
            empties.append(empty)
    if not empties:
        return library
    return replace(library, components=library.components + tuple(empties))
