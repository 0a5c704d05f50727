"""Decide a watcher's new configuration after failures, and say why, step by step.

The fewest-change valid configuration without the failed components
(``rosreconf.solve.running.nearest_valid``, an exact optimum), passed over when it fails the
schema's performance requirements (``rosreconf.analysis.simulate.choose``), with the
narrative of every change (``rosreconf.planning.narrative``). Every decision goes to the
``say`` callback (``replanned``, ``why``, ``passed-over``, ``no-configuration``); acting on it
is the watcher's.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.wiring import rewiring
from rosreconf.planning.narrative import explain_replan, ruled_out_wording
from rosreconf.solve.running import nearest_valid
from rosreconf.solve.search import Budget
from rosreconf.solve.solver import why_not

Say = Callable[..., None]
Change = tuple[str, str, str]
"""One role's change: (role, old component, new component; "" for an empty optional role).

Old and new are the same component for a kept one that restarts to be rewired (the wiring
model, ``rosreconf.model.wiring``): it counts as a change."""


def replan(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Configuration,
    failed: frozenset[str],
    say: Say,
    budget: Budget | None = None,
    ruled: Mapping[str, str] | None = None,
) -> tuple[Configuration, list[Change]] | None:
    """Return the new configuration and its changes, or None when there is none (said).

    ``budget`` bounds the search for one that meets the performance requirements when the
    fewest-change configuration does not (``rosreconf.analysis.choice``). ``ruled``: the
    components of ``failed`` that context ruled out, with why: the explanation gives that
    reason where it would say "has failed" (``planning.narrative.ruled_out_wording``).
    """
    new = nearest_valid(library, schema, failed, current)
    why = why_not(library, schema, failed) if new is None else ""
    fewest = "the fewest possible (exact optimum)"
    if new is not None and schema.simulation is not None:
        nearest = new
        new, why = _performing(library, schema, current, new, failed, say, budget)
        if new is not None and new != nearest:
            fewest = "the fewest among the configurations that meet the performance requirements"
    if new is None:
        say(
            "no-configuration",
            f"no valid configuration without {', '.join(sorted(failed))}: {why}",
            failed=sorted(failed),
        )
        return None
    old = current.mapping
    changes = changes_between(library, schema, current, new)
    say(
        "replanned",
        f"replanned without {', '.join(sorted(failed))}: "
        f"{len(changes)} change(s), {fewest}: {changes_text(changes)}",
        failed=sorted(failed),
        configuration=new.shown,
        changes=changes_data(changes),
    )
    # best_configuration is the exact optimum of the change count, so it is the fewest by
    # proof; passing len(changes) as "fewest" would only compare a number with itself.
    lines = explain_replan(library, schema, failed, old, new)
    for line in ruled_out_wording(lines, ruled or {}):
        say("why", line)
    return new, changes


def changes_between(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    old: Configuration,
    new: Configuration,
) -> list[Change]:
    """Return the changes from ``old`` to ``new``: each role whose component changes, and
    each kept component that restarts to be rewired (its providers changed).
    """
    before = old.mapping
    rewired = rewiring(library, schema, before, new.mapping)
    return [
        (r, before.get(r, ""), c)
        for r, c in new.assignment
        if before.get(r, "") != c or r in rewired
    ]


def changes_text(changes: list[Change]) -> str:
    """Return the changes as the log says them: ``role: A -> B`` or ``role: restart A``."""
    return "; ".join(
        f"{r}: restart {b} (rewired)" if a == b else f"{r}: {a or '(empty)'} -> {b or '(empty)'}"
        for r, a, b in changes
    )


def changes_data(changes: list[Change]) -> list[dict[str, object]]:
    """Return the changes as the JSON log gives them."""
    return [
        {"role": r, "from": a or None, "to": b or None, "restart": a == b} for r, a, b in changes
    ]


def _performing(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    current: Configuration,
    fewest: Configuration,
    failed: frozenset[str],
    say: Say,
    budget: Budget | None,
) -> tuple[Configuration | None, str]:
    """Return the configuration that meets the schema's performance requirements.

    Says so when the fewest-change configuration was passed over for failing them.
    """
    from rosreconf.analysis.choice import SearchExhausted, choose, shortfall  # imports numpy

    try:
        choice = choose(library, schema, fewest, current.mapping, {}, failed, budget=budget)
    except SearchExhausted as exc:
        return None, str(exc)
    if choice.passed_over is not None and choice.passed_over_performance is not None:
        say(
            "passed-over",
            "the fewest-change configuration fails the performance requirements "
            f"({shortfall(schema, choice.passed_over_performance)}): passed over",
            configuration=choice.passed_over.shown,
        )
    if choice.configuration is None:
        return None, (
            "every valid configuration fails the schema's performance requirements "
            f"({choice.tried} simulated to prove it)"
        )
    return choice.configuration, ""
