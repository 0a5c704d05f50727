"""Decide which configuration runs now, and which should run after failures: ONE rule.

Every command that needs "the configuration that runs now" (``plan`` and ``render-pddl``
start from it, ``graph`` and ``launch`` draw and start it, ``inspect`` and ``watch`` check and
keep it) asks ``running_configuration``; the rule lives here and in docs/architecture.md
("Which configuration runs now"), nowhere else:

1. a configuration given by the user (``--configuration`` / ``--current``) for that schema;
2. else the schema's declared ``nominal`` configuration (the one its authors run);
3. else, when the user gave ``--objective`` weights, the best configuration by them;
4. else the first valid configuration, the one ``rosreconf enumerate`` lists as number 1
   (deterministic: roles in schema order, candidates in library order).

Why: a ROS engineer runs what the schema says it runs; without that, what a weighted
objective prefers is what they would launch; with no preference either, the first listed
configuration is the one they can see and reproduce (an optimum under an empty objective
would be an arbitrary tie).

After failures (``--fail``, or a node dying under ``watch``) the configuration that should run
is the running one when it is still valid, else the valid configuration nearest to it (fewest
changed roles, then the objective: the paper's minimal reconfiguration), ``nearest_valid``.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path

from rosreconf.errors import RosreconfError, UsageError
from rosreconf.formats.configfile import read_configurations
from rosreconf.formats.selection import Selection
from rosreconf.model import ComponentLibrary, Configuration, InteroperabilitySchema
from rosreconf.model.validity import violations
from rosreconf.model.wiring import RestartTable, Wire, restart_table
from rosreconf.solve.objective import Objective
from rosreconf.solve.solver import best_configuration, configurations, why_not


def declared_nominal(schema: InteroperabilitySchema) -> Configuration | None:
    """Return the schema's declared nominal configuration, or None when it declares none."""
    roles = schema.graph.roles  # an optional role the nominal leaves out is empty
    if not schema.nominal or any(r.name not in schema.nominal for r in roles if not r.optional):
        return None
    return Configuration.of(schema.name, schema.nominal, schema.graph.roles)


def running_configuration(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    weights: Mapping[str, float] | None = None,
) -> Configuration | None:
    """Return what runs now, before any failure, by the module's rule (steps 2-4).

    None when the schema has no valid configuration at all.
    """
    nominal = declared_nominal(schema)
    if nominal is not None:
        return nominal
    if weights:
        return best_configuration(library, schema, Objective(weights=dict(weights)))
    return next(configurations(library, schema, limit=1), None)


def nearest_valid(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    failed: Collection[str],
    running: Configuration,
    weights: Mapping[str, float] | None = None,
) -> Configuration | None:
    """Return ``running`` if still valid under ``failed``, else the valid one nearest to it.

    Nearest means fewest changes, then the weighted metric sum (the paper's minimal
    reconfiguration); a change is a role that changes component, or a kept component
    restarted because what it is wired to changes (``rosreconf.model.wiring``). None when
    no valid configuration is left.
    """
    if not violations(running, library, schema, failed):
        return running
    objective = change_objective(library, schema, running.mapping, weights)
    return best_configuration(library, schema, objective, failed)


def change_objective(
    library: ComponentLibrary,
    schema: InteroperabilitySchema,
    running: Mapping[str, str],
    weights: Mapping[str, float] | None = None,
    wired: Mapping[str, frozenset[Wire]] | None = None,
) -> Objective:
    """Return the objective of a reconfiguration away from ``running``: fewest changes.

    Each role that changes component costs one, and so does each kept component that must
    restart to be rewired (the wiring model); then the weighted metric sum. ``wired``: role
    -> what its running component is wired to now, when that is not its wiring under
    ``schema`` (a task switch: it runs under another schema's edges,
    ``rosreconf.model.switching.carried_wiring``); None: its wiring under ``schema``.
    """
    table = restart_table(library, schema, running)
    if wired is not None:
        table = RestartTable(dict(wired), table.offers)
    return Objective(current=dict(running), weights=dict(weights or {}), restarts=table)


def should_run(
    library: ComponentLibrary, schema: InteroperabilitySchema, failed: Collection[str]
) -> Configuration:
    """Return the configuration that should run under ``failed``: the running one, or nearest.

    Raises:
        RosreconfError: no valid configuration is left (exit 1), with the reason why.
    """
    running = running_configuration(library, schema)
    config = None if running is None else nearest_valid(library, schema, failed, running)
    if config is None:
        raise RosreconfError(
            f"{schema.display_name} has no configuration: {why_not(library, schema, failed)}"
        )
    return config


def running_mappings(
    sel: Selection, path: Path | None, weights: Mapping[str, float]
) -> dict[str, dict[str, str]]:
    """Return per selected schema what runs now: from the file at ``path``, else by the rule.

    A schema with no configuration at all gets an empty mapping (nothing runs).
    """
    given = read_configurations(path) if path is not None else {}
    out: dict[str, dict[str, str]] = {}
    for s in sel.schemas:
        if given.get(s.name):
            out[s.name] = dict(given[s.name])
        else:
            config = running_configuration(sel.library, s, weights)
            out[s.name] = config.mapping if config is not None else {}
    return out


@dataclass(frozen=True)
class Target:
    """The configuration of one schema that a command works on.

    Attributes:
        schema: the schema.
        configuration: the configuration to draw, start or check.
        before: the declared nominal configuration, when there is one and it differs.
    """

    schema: InteroperabilitySchema
    configuration: Configuration
    before: Configuration | None


def targets(sel: Selection, configuration_file: Path | None) -> list[Target]:
    """Return the configuration of every selected schema (from the file, or by the rule).

    With a file, only the selected schemas the file names are returned; a configuration that
    is not valid for any reason other than a failed component is an error. Failed components
    stay in it (pictures draw them red). Without a file, ``should_run`` decides.

    Raises:
        UsageError: the file names no selected schema.
        RosreconfError: a configuration is not valid, or a schema has none (exit 1).
    """
    given = read_configurations(configuration_file) if configuration_file else None
    out: list[Target] = []
    for s in sel.schemas:
        if given is not None and s.name not in given:
            continue
        if given is not None:
            config = checked(sel, s, given[s.name], configuration_file)
        else:
            config = should_run(sel.library, s, sel.failed)
        nominal = declared_nominal(s)
        out.append(Target(s, config, nominal if nominal not in (None, config) else None))
    if not out:
        names = ", ".join(sorted(given or {})) or "none"
        raise UsageError(
            f"{configuration_file}: names no selected schema (it has: {names}; selected: "
            f"{', '.join(s.name for s in sel.schemas)})"
        )
    return out


def one_target(sel: Selection, configuration_file: Path | None) -> Target:
    """Return the one schema's running configuration that ``inspect`` and ``watch`` check.

    The schema is the only one selected, or the only selected one the file names. Without a
    file, the rule of this module decides (failures are the watcher's to handle, so they do
    not move it).

    Raises:
        UsageError: no single schema is named.
        RosreconfError: the configuration leaves a role empty, is not valid, or the schema
            has none (exit 1).
    """
    given = read_configurations(configuration_file) if configuration_file else {}
    names = [s.name for s in sel.schemas if not given or s.name in given]
    if len(names) != 1:
        choices = ", ".join(names) or "none"
        raise UsageError(f"name one schema with --only (schemas to choose from: {choices})")
    schema = next(s for s in sel.schemas if s.name == names[0])
    if schema.name in given:
        config = checked(sel, schema, given[schema.name], configuration_file)
    else:
        running = running_configuration(sel.library, schema)
        if running is None:
            why = why_not(sel.library, schema)
            raise RosreconfError(f"{schema.display_name} has no configuration: {why}")
        config = checked(sel, schema, running.mapping, Path(f"nominal of {schema.source}"))
    nominal = declared_nominal(schema)
    return Target(schema, config, nominal if nominal not in (None, config) else None)


def checked(
    sel: Selection, s: InteroperabilitySchema, mapping: Mapping[str, str], source: Path | None
) -> Configuration:
    """Return ``mapping`` as a configuration of ``s`` if it fills every role and is valid.

    A failed component does not count against it (pictures draw it red; watch replaces it).

    Raises:
        RosreconfError: a role is empty or a rule of validity is broken (exit 1).
    """
    roles = {r.name for r in s.graph.roles if not r.optional}  # optional: may stay empty
    missing = sorted(roles - set(mapping))
    if missing:
        raise RosreconfError(f"{source}: {s.name}: roles not filled: {', '.join(missing)}")
    config = Configuration.of(s.name, mapping, s.graph.roles)
    problems = [v for v in violations(config, sel.library, s, sel.failed) if v.code != "failed"]
    if problems:
        reasons = "; ".join(str(v) for v in problems)
        raise RosreconfError(f"{source}: {s.name}: not a valid configuration: {reasons}")
    return config
