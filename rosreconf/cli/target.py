"""Decide which configuration ``graph --view ros`` draws and ``launch`` starts, the same way.

Both commands take either ``--configuration FILE`` (what runs, or should run) or the usual
selection options with ``--fail``. Without a file, a schema's configuration is its nominal
one when that is still valid under the failures; otherwise the valid configuration nearest
to the nominal one (fewest changed roles, ``rosreconf.solve.solver.best_configuration``: the
paper's minimal reconfiguration); without a nominal one, the first valid configuration.
The nominal configuration is also what a picture compares against (``before``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from rosreconf.cli.common import Selection
from rosreconf.errors import RosreconfError, UsageError
from rosreconf.formats.configfile import read_configurations
from rosreconf.model import Configuration, InteroperabilitySchema
from rosreconf.model.validity import violations
from rosreconf.solve.solver import Objective, best_configuration, configurations, why_not


@dataclass(frozen=True)
class Target:
    """The configuration of one schema that a command works on.

    Attributes:
        schema: the schema.
        configuration: the configuration to draw or start.
        before: the nominal configuration, when the schema declares one and it differs.
    """

    schema: InteroperabilitySchema
    configuration: Configuration
    before: Configuration | None


def targets(sel: Selection, configuration_file: Path | None) -> list[Target]:
    """Return the configuration of every selected schema (from the file, or chosen).

    With a file, only the selected schemas the file names are returned; a configuration that
    is not valid for any reason other than a failed component is an error. Failed components
    stay in it (pictures draw them red).

    Raises:
        UsageError: the file names no selected schema.
        RosreconfError: a configuration is not valid, or a schema has none (exit 1).
    """
    given = read_configurations(configuration_file) if configuration_file else None
    out: list[Target] = []
    for s in sel.schemas:
        if given is not None and s.name not in given:
            continue
        nominal = _nominal(s)
        if given is not None:
            config = checked(sel, s, given[s.name], configuration_file)
        else:
            config = _chosen(sel, s, nominal)
        before = nominal if nominal is not None and nominal != config else None
        out.append(Target(s, config, before))
    if not out:
        names = ", ".join(sorted(given or {})) or "none"
        raise UsageError(
            f"{configuration_file}: names no selected schema (it has: {names}; selected: "
            f"{', '.join(s.name for s in sel.schemas)})"
        )
    return out


def _nominal(s: InteroperabilitySchema) -> Configuration | None:
    if not s.nominal or any(r.name not in s.nominal for r in s.graph.roles):
        return None
    return Configuration.of(s.name, s.nominal, s.graph.roles)


def checked(
    sel: Selection, s: InteroperabilitySchema, mapping: Mapping[str, str], source: Path | None
) -> Configuration:
    """Return ``mapping`` as a configuration of ``s`` if it fills every role and is valid.

    A failed component does not count against it (pictures draw it red; watch replaces it).

    Raises:
        RosreconfError: a role is empty or a rule of validity is broken (exit 1).
    """
    roles = {r.name for r in s.graph.roles}
    missing = sorted(roles - set(mapping))
    if missing:
        raise RosreconfError(f"{source}: {s.name}: roles not filled: {', '.join(missing)}")
    config = Configuration.of(s.name, mapping, s.graph.roles)
    problems = [v for v in violations(config, sel.library, s, sel.failed) if v.code != "failed"]
    if problems:
        reasons = "; ".join(str(v) for v in problems)
        raise RosreconfError(f"{source}: {s.name}: not a valid configuration: {reasons}")
    return config


def _chosen(
    sel: Selection, s: InteroperabilitySchema, nominal: Configuration | None
) -> Configuration:
    if nominal is not None:
        if not violations(nominal, sel.library, s, sel.failed):
            return nominal
        config = best_configuration(sel.library, s, Objective(current=nominal.mapping), sel.failed)
    else:
        config = next(configurations(sel.library, s, sel.failed, limit=1), None)
    if config is None:
        raise RosreconfError(
            f"{s.display_name} has no configuration: {why_not(sel.library, s, sel.failed)}"
        )
    return config
