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
- integer parameters outside what ROS 1 can carry (XML-RPC integers are 32-bit);
- integers too large for a float (a 401-digit coefficient) anywhere in a model's dynamics or
  a schema's simulation block, which could not even be built, and QoS depths and durations
  beyond DDS's 32-bit ``long`` (``clean_numbers``, ``schema_value_problems``); the ranges a
  simulation computes correctly within are ``simchecks``'s, on the built model.

These checks run on the plain data once its JSON Schema check passed, before model objects
are built; a value found wrong is looked up in the positioned tree (composed then, when the
loader read the file without one) for its ``file:line:column`` and its text as written, so
nothing downstream ever sees such a value.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator

from rosreconf.errors import Problem, Severity
from rosreconf.formats import nodes
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


def value_problems(tree: nodes.TreeOf, plain: nodes.Plain) -> list[Problem]:
    """Return the problems of a structurally valid component library's numbers and launch values.

    ``plain`` is the library's plain data and ``tree()`` the positioned tree it was read from,
    where each value found wrong is looked up (by its path) for its position and text.
    """
    problems: list[Problem] = []
    components = plain.get("components") if isinstance(plain, dict) else None
    for i, component in enumerate(components if isinstance(components, list) else []):
        if not isinstance(component, dict):
            continue

        def at(*path: str, i: int = i) -> nodes.Node | None:
            return nodes.lookup(tree(), ["components", i, *path])

        if not _within(component.get("failure_probability"), 1.0):
            problems.extend(_number(at("failure_probability"), "failure_probability", 0.0, 1.0))
        metrics = component.get("metrics")
        for key, value in metrics.items() if isinstance(metrics, dict) else ():
            if not _within(value, MAX_METRIC):
                problems.extend(_number(at("metrics", key), f"metric '{key}'", 0.0, MAX_METRIC))
        ros = component.get("ros")
        params = ros.get("parameters") if isinstance(ros, dict) else None
        for key, value in params.items() if isinstance(params, dict) else ():
            if not _fine_parameter(value):
                problems.extend(_parameter(key, at("ros", "parameters", key)))
        if not clean_numbers(component.get("dynamics")):
            problems.extend(_huge(at("dynamics"), f"components[{i}].dynamics"))
        if not _clean_qos(component):
            problems.extend(_qos_numbers(nodes.lookup(tree(), ["components", i])))
    return problems


def schema_value_problems(tree: nodes.Node, plain: nodes.Plain) -> list[Problem]:
    """Return the problems of a schema's numbers that no model could hold.

    The simulation block's numbers (reference, duration, requirements, the plants) become
    floats when the schema is built; an integer too large for one is refused here, at its
    position, before it can stop the build.
    """
    simulation = plain.get("simulation") if isinstance(plain, dict) else None
    if clean_numbers(simulation):
        return []
    return list(_huge(nodes.fields(tree).get("simulation"), "simulation"))


def clean_numbers(plain: nodes.Plain) -> bool:
    """Tell whether ``plain`` (a subtree as plain data) holds no integer too large for a float."""
    if type(plain) is int:
        return -FLOAT_MAX <= plain <= FLOAT_MAX
    if isinstance(plain, dict):
        return all(clean_numbers(v) for v in plain.values())
    if isinstance(plain, list):
        return all(clean_numbers(v) for v in plain)
    return True


def _huge(node: nodes.Node | None, where: str) -> Iterator[Problem]:
    """Refuse every integer under ``node`` too large for a float, at its position."""
    if type(node) is nodes.MappingNode:
        for key, child in nodes.fields(node).items():
            yield from _huge(child, f"{where}.{key}")
    elif type(node) is nodes.SequenceNode:
        for i, child in enumerate(nodes.seq_of(node)):
            yield from _huge(child, f"{where}[{i}]")
    elif type(node) is nodes.ScalarNode:
        value = nodes.value(node)
        if type(value) is int and abs(value) > FLOAT_MAX:
            yield Problem(
                nodes.span(node),
                f"'{where}' is {_shown(node.value)}, too large to compute with",
                "write a number within the ranges docs/simulation.md gives (at most 1e12)",
                code="not-finite",
            )


def _profiles(component: dict[str, nodes.Plain]) -> Iterator[dict[str, nodes.Plain]]:
    """Yield the interfaces (``any_of``'s options too) a component provides and requires."""
    for key in ("provides", "requires"):
        entries = component.get(key)
        for entry in entries if isinstance(entries, list) else ():
            if isinstance(entry, dict):
                yield entry
                options = entry.get("any_of")
                for option in options if isinstance(options, list) else ():
                    if isinstance(option, dict):
                        yield option


def _clean_qos(component: dict[str, nodes.Plain]) -> bool:
    """Tell whether ``_qos_numbers`` has nothing to report on a component's interfaces."""
    for interface in _profiles(component):
        qos = interface.get("qos")
        if isinstance(qos, dict):
            for name, high in QOS_LIMITS.items():
                value = qos.get(name)
                if type(value) in nodes.NUMBER and value > high:  # type: ignore[operator]
                    return False
    return True


def _qos_numbers(component: nodes.Node | None) -> Iterator[Problem]:
    """Refuse QoS depths and durations beyond DDS's 32-bit ``long`` (``QOS_LIMITS``)."""
    for key in ("provides", "requires"):
        for entry in nodes.seq_of(nodes.fields(component).get(key)):
            options = nodes.seq_of(nodes.fields(entry).get("any_of"))
            for interface in (entry, *options):
                qos = nodes.fields(interface).get("qos")
                for name, high in QOS_LIMITS.items():
                    node = nodes.fields(qos).get(name)
                    value = nodes.value(node)
                    if type(value) not in nodes.NUMBER or not value > high:  # type: ignore[operator]
                        continue  # NaN, and what the Schema refuses, are reported elsewhere
                    unit = "" if name == "depth" else " s"
                    yield Problem(
                        nodes.span(node),
                        f"QoS {name} is {_shown(nodes.text_of(node))}, more than DDS can carry "
                        f"({high}{unit}, a 32-bit 'long')",
                        "give a depth of at most 2147483647 (0 keeps all)"
                        if name == "depth"
                        else "give at most 2147483647 seconds, or null for none",
                        code="out-of-range",
                    )


def _within(value: nodes.Plain, high: float) -> bool:
    """Tell whether ``_number`` accepts ``value`` in [0, ``high``] (anything not a number too).

    A comparison with NaN is false, so NaN is never within.
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        return True
    return 0.0 <= value <= high


def _fine_parameter(value: nodes.Plain) -> bool:
    """Tell whether ``_parameter`` has nothing to say about a launch parameter's value."""
    if isinstance(value, str):
        return SUBSTITUTION not in value
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, int) and not isinstance(value, bool):
        return INT32[0] <= value <= INT32[1]
    return True


def _number(node: nodes.Node | None, what: str, low: float, high: float) -> Iterator[Problem]:
    """Refuse a non-finite number, one too large for a float, or one outside [low, high]."""
    if type(node) is not nodes.ScalarNode:
        return
    value = nodes.value(node)
    if isinstance(value, bool) or not isinstance(value, int | float):
        return  # the JSON Schema reports the type
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        how = "too large to compute with" if isinstance(value, int) else "not a finite number"
        yield Problem(
            nodes.span(node),
            f"{what} is {_shown(node.value)}, {how}",
            f"give a number between {low:g} and {high:g}",
            code="not-finite",
        )
    elif not low <= number <= high:
        yield Problem(
            nodes.span(node),
            f"{what} is {_shown(node.value)}, outside [{low:g}, {high:g}]",
            f"give a number between {low:g} and {high:g}",
            code="out-of-range",
        )


def _parameter(key: str, node: nodes.Node | None) -> Iterator[Problem]:
    """Refuse unmarked substitutions, non-finite floats and integers ROS 1 cannot carry."""
    if type(node) is not nodes.ScalarNode:
        return  # {substitution: "..."}: marked by the user (its shape is the Schema's job)
    value = nodes.value(node)
    if isinstance(value, str) and SUBSTITUTION in value:
        yield Problem(
            nodes.span(node),
            f"parameter '{key}' contains '$(', which roslaunch would evaluate as a "
            "substitution ($(eval ...) runs Python, $(env ...) reads the environment)",
            f'if it is meant as one, mark it: {key}: {{substitution: "{value}"}}; '
            "otherwise remove the '$('",
            code="launch-substitution",
        )
    elif isinstance(value, float) and not math.isfinite(value):
        yield Problem(
            nodes.span(node),
            f"parameter '{key}' is {node.value}, not a finite number",
            "give a finite number",
            code="not-finite",
        )
    elif (
        isinstance(value, int) and not isinstance(value, bool) and not INT32[0] <= value <= INT32[1]
    ):
        yield Problem(
            nodes.span(node),
            f"parameter '{key}' is {_shown(node.value)}, outside the 32-bit integers ROS 1 can "
            "carry",
            "write it as a float (with a '.') or as a quoted string",
            code="out-of-range",
        )


def _shown(raw: str) -> str:
    """Quote a number as written, shortened when it is very long (a 401-digit integer)."""
    return raw if len(raw) <= 24 else f"{raw[:12]}...{raw[-4:]} ({len(raw)} characters)"


def duplicate_edges(tree: nodes.Node, plain: nodes.Plain) -> list[Problem]:
    """Warn about a consumer-provider pair listed twice in a schema's edges.

    The loader merges them (the entry without an ``interfaces`` restriction wins), which may
    not be what the author meant: one of the two entries is ignored, silently until now.
    ``plain`` is a structurally valid schema's plain data; ``tree`` gives the positions.
    """
    seen: dict[tuple[str, str], tuple[int, int]] = {}
    problems: list[Problem] = []
    edges = plain.get("edges", []) if isinstance(plain, dict) else []
    for i, entry in enumerate(edges if isinstance(edges, list) else []):
        if not isinstance(entry, dict):
            continue
        consumer = entry.get("consumer")
        providers = entry.get("providers", [])
        for j, provider in enumerate(providers if isinstance(providers, list) else []):
            key = (str(consumer), str(provider))
            if key not in seen:
                seen[key] = (i, j)
                continue
            first = _provider_span(tree, *seen[key])
            problems.append(
                Problem(
                    _provider_span(tree, i, j),
                    f"edge {provider} -> {consumer} is listed again (first at "
                    f"{first}); the two entries are merged and the one without "
                    "'interfaces' wins",
                    "list each consumer-provider pair once",
                    code="duplicate-edge",
                    severity=Severity.WARNING,
                )
            )
    return problems


def _provider_span(tree: nodes.Node, edge: int, index: int) -> Span:
    node = nodes.lookup(tree, ["edges", edge, "providers", index])
    return nodes.span(node) if node is not None else nodes.span(tree)
