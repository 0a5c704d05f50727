"""Refuse values that would be unsafe or meaningless where rosreconf writes them.

The JSON Schema checks types and ranges, but three kinds of value pass it and then do harm:

- numbers that are not finite: ``.nan`` passes ``minimum: 0`` (every comparison with NaN is
  false) and ends as a bare ``NaN`` in ``--json`` output, which is not JSON; ``.inf`` or a
  401-digit integer as a metric makes every sum infinite or cannot be turned into a float at
  all. Failure probabilities must lie in [0, 1] and metrics in [0, ``MAX_METRIC``];
- launch parameter values containing ``$(``: roslaunch and ROS 2 launch evaluate ``$(eval
  ...)``, ``$(env ...)`` and ``$(find ...)`` in every attribute, so a library file could run
  Python on the robot. A value that really is a substitution must be marked as one:
  ``name: {substitution: "$(find my_pkg)/config.yaml"}``;
- integer parameters outside what ROS 1 can carry (XML-RPC integers are 32-bit), and
  subnormal float parameters, which ROS 2's rcl reads as strings (``strtod`` underflows);
- integers too large for a float (a 401-digit coefficient) anywhere in a model's dynamics or
  a schema's simulation block, which could not even be built, and QoS depths and durations
  beyond DDS's 32-bit ``long``; the ranges a simulation computes correctly within are
  ``simchecks``'s, on the built model.

Each check runs once, on the plain data, after its JSON Schema check passed and before model
objects are built; only a value found wrong is looked up in the document's positions
(``positions.Positions``) for its ``file:line:column`` and its text as written.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator

from rosreconf.errors import Problem, Severity
from rosreconf.formats import nodes
from rosreconf.formats.nodes import NUMBER
from rosreconf.formats.positions import Place, Positions
from rosreconf.model import Span

MAX_METRIC = 1e12
"""Largest metric value: sums over 10,000 components stay exact in a float, and costs in PDDL."""

INT32 = (-(2**31), 2**31 - 1)
"""The integers a ROS 1 parameter can hold (XML-RPC ``i4``)."""

DDS_LONG = 2**31 - 1
"""The largest DDS ``long``: history depth and ``Duration_t`` seconds are 32-bit."""

QOS_LIMITS = {"depth": DDS_LONG, "deadline": DDS_LONG, "lease_duration": DDS_LONG}
"""The QoS numbers and their largest value (seconds for the durations)."""

FLOAT_MAX = sys.float_info.max
"""The largest float: an integer beyond it cannot become one (``OverflowError``)."""

SUBSTITUTION = "$("
"""What starts a roslaunch / ROS 2 launch substitution."""


def value_problems(tree: Positions, plain: nodes.Plain) -> list[Problem]:
    """Return the problems of a structurally valid library's numbers and launch values."""
    problems: list[Problem] = []
    components = plain.get("components") if isinstance(plain, dict) else None
    for i, component in enumerate(components if isinstance(components, list) else []):
        if not isinstance(component, dict):
            continue
        fp = component.get("failure_probability")
        if not _within(fp, 1.0):
            where = _at(tree, "components", i, "failure_probability")
            problems.append(_number(fp, 1.0, "failure_probability", where))
        metrics = component.get("metrics")
        for key, value in metrics.items() if isinstance(metrics, dict) else ():
            if not _within(value, MAX_METRIC):
                where = _at(tree, "components", i, "metrics", key)
                problems.append(_number(value, MAX_METRIC, f"metric '{key}'", where))
        ros = component.get("ros")
        params = ros.get("parameters") if isinstance(ros, dict) else None
        for key, value in params.items() if isinstance(params, dict) else ():
            problems.extend(_parameter(key, value, tree, i))
        if "dynamics" in component:
            problems.extend(_huge(component["dynamics"], tree, "components", i, "dynamics"))
        for key in ("provides", "requires"):
            entries = component.get(key)
            for j, entry in enumerate(entries if isinstance(entries, list) else ()):
                if isinstance(entry, dict) and ("qos" in entry or "any_of" in entry):
                    problems.extend(_qos(entry, tree, "components", i, key, j))
    return problems


def schema_value_problems(tree: Positions, plain: nodes.Plain) -> list[Problem]:
    """Return the integers of a schema's simulation block too large to become floats.

    Refused here, at their position, before they can stop the build.
    """
    simulation = plain.get("simulation") if isinstance(plain, dict) else None
    return list(_huge(simulation, tree, "simulation"))


def _at(tree: Positions, *path: str | int) -> tuple[Positions, Place]:
    """Return the value at ``path`` of the document, with the positions that place it."""
    return tree, tree.lookup(path)


def _span(at: tuple[Positions, Place]) -> Span:
    return at[0].span(at[1])


def _text(at: tuple[Positions, Place]) -> str:
    return at[0].text(at[1])


def _huge(plain: nodes.Plain, tree: Positions, *path: str | int) -> Iterator[Problem]:
    """Refuse every integer under ``plain`` (at ``path``) too large for a float."""
    if type(plain) is int and abs(plain) > FLOAT_MAX:
        node = _at(tree, *path)
        yield Problem(
            _span(node),
            f"'{nodes.path_text(path)}' is {_shown(_text(node))}, too large to compute with",
            "write a number within the ranges docs/simulation.md gives (at most 1e12)",
            code="not-finite",
        )
    elif isinstance(plain, dict):
        for key, child in plain.items():
            yield from _huge(child, tree, *path, key)
    elif isinstance(plain, list):
        for i, child in enumerate(plain):
            yield from _huge(child, tree, *path, i)


def _qos(interface: nodes.Plain, tree: Positions, *path: str | int) -> Iterator[Problem]:
    """Refuse an interface's (and its options') QoS numbers beyond DDS's 32-bit ``long``."""
    if not isinstance(interface, dict):
        return
    qos = interface.get("qos")
    for name, high in QOS_LIMITS.items() if isinstance(qos, dict) else ():
        value = qos.get(name)  # type: ignore[union-attr]
        if type(value) not in NUMBER or not value > high:  # type: ignore[operator]
            continue  # NaN, and what the Schema refuses, are reported elsewhere
        node = _at(tree, *path, "qos", name)
        unit = "" if name == "depth" else " s"
        yield Problem(
            _span(node),
            f"QoS {name} is {_shown(_text(node))}, more than DDS can carry "
            f"({high}{unit}, a 32-bit 'long')",
            "give a depth of at most 2147483647 (0 keeps all)"
            if name == "depth"
            else "give at most 2147483647 seconds, or null for none",
            code="out-of-range",
        )
    options = interface.get("any_of")
    for k, option in enumerate(options if isinstance(options, list) else ()):
        yield from _qos(option, tree, *path, "any_of", k)


def _within(value: nodes.Plain, high: float) -> bool:
    """Tell whether ``value`` is in [0, ``high``] (never NaN), or no number (the Schema's)."""
    return type(value) not in NUMBER or 0.0 <= value <= high  # type: ignore[operator]


def _number(value: nodes.Plain, high: float, what: str, node: tuple[Positions, Place]) -> Problem:
    """Return the problem of a number ``_within`` refused: not finite, or outside [0, high]."""
    try:
        finite = math.isfinite(float(value))  # type: ignore[arg-type]
    except OverflowError:
        finite = False
    how = "too large to compute with" if type(value) is int else "not a finite number"
    return Problem(
        _span(node),
        f"{what} is {_shown(_text(node))}, " + (f"outside [0, {high:g}]" if finite else how),
        f"give a number between 0 and {high:g}",
        code="out-of-range" if finite else "not-finite",
    )


def _parameter(key: str, value: nodes.Plain, tree: Positions, i: int) -> Iterator[Problem]:
    """Refuse unmarked substitutions, non-finite or subnormal floats, integers ROS 1 cannot carry.

    A mapping (``{substitution: "..."}``) is marked by the user; its shape is the Schema's job.
    """
    if isinstance(value, str) and SUBSTITUTION in value:
        yield Problem(
            _span(_at(tree, "components", i, "ros", "parameters", key)),
            f"parameter '{key}' contains '$(', which roslaunch would evaluate as a "
            "substitution ($(eval ...) runs Python, $(env ...) reads the environment)",
            f'if it is meant as one, mark it: {key}: {{substitution: "{value}"}}; '
            "otherwise remove the '$('",
            code="launch-substitution",
        )
    elif isinstance(value, float) and not math.isfinite(value):
        node = _at(tree, "components", i, "ros", "parameters", key)
        yield Problem(
            _span(node),
            f"parameter '{key}' is {_text(node)}, not a finite number",
            "give a finite number",
            code="not-finite",
        )
    elif isinstance(value, float) and value and abs(value) < sys.float_info.min:
        node = _at(tree, "components", i, "ros", "parameters", key)
        yield Problem(
            _span(node),
            f"parameter '{key}' is {_shown(_text(node))}, a subnormal number: ROS 2's "
            "rcl reads no spelling of it as a double (strtod reports an underflow), and the "
            "node would get a string",
            f"give 0 or a number of at least {sys.float_info.min!r} in size",
            code="out-of-range",
        )
    elif type(value) is int and not INT32[0] <= value <= INT32[1]:
        node = _at(tree, "components", i, "ros", "parameters", key)
        yield Problem(
            _span(node),
            f"parameter '{key}' is {_shown(_text(node))}, outside the 32-bit integers "
            "ROS 1 can carry",
            "write it as a float (with a '.') or as a quoted string",
            code="out-of-range",
        )


def _shown(raw: str) -> str:
    """Quote a number as written, shortened when it is very long (a 401-digit integer)."""
    return raw if len(raw) <= 24 else f"{raw[:12]}...{raw[-4:]} ({len(raw)} characters)"


def duplicate_edges(tree: Positions, plain: nodes.Plain) -> list[Problem]:
    """Warn about a consumer-provider pair listed twice in a schema's edges.

    The loader merges them (the entry without an ``interfaces`` restriction wins), which may
    not be what the author meant: one of the two entries is ignored, silently until now.
    ``plain`` is a structurally valid schema's plain data; ``tree`` gives the positions.
    """
    seen: dict[tuple[str, str], list[str | int]] = {}
    problems: list[Problem] = []
    edges = plain.get("edges", []) if isinstance(plain, dict) else []
    for i, entry in enumerate(edges if isinstance(edges, list) else []):
        if not isinstance(entry, dict):
            continue
        consumer = entry.get("consumer")
        providers = entry.get("providers", [])
        for j, provider in enumerate(providers if isinstance(providers, list) else []):
            key = (str(consumer), str(provider))
            at: list[str | int] = ["edges", i, "providers", j]
            if key not in seen:
                seen[key] = at
                continue
            first = tree.span(tree.lookup(seen[key]))
            problems.append(
                Problem(
                    tree.span(tree.lookup(at)),
                    f"edge {provider} -> {consumer} is listed again (first at "
                    f"{first}); the two entries are merged and the one without "
                    "'interfaces' wins",
                    "list each consumer-provider pair once",
                    code="duplicate-edge",
                    severity=Severity.WARNING,
                )
            )
    return problems
