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
  beyond DDS's 32-bit ``long`` (``number_problems``, ``clean_numbers``); the ranges a
  simulation computes correctly within are ``simchecks``'s, on the built model.

These checks run on the positioned tree, before model objects are built, so every problem
has the value's ``file:line:column`` and nothing downstream ever sees such a value.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator

from rosreconf.errors import Problem, Severity
from rosreconf.formats import yamlsource as ys
from rosreconf.model import Span

MAX_METRIC = 1e12
"""Largest metric value: sums over 10,000 components stay exact in a float, and costs in PDDL."""

INT32 = (-(2**31), 2**31 - 1)
"""The integers a ROS 1 parameter can hold (XML-RPC ``i4``)."""

DDS_LONG = 2**31 - 1
"""Largest QoS history depth and Duration_t seconds (deadline, lease): DDS's ``long`` is int32,
and rmw's ``size_t`` depth reaches DDS as one (rmw_fastrtps, rmw_cyclonedds)."""

QOS_LIMITS = {"depth": DDS_LONG, "deadline": DDS_LONG, "lease_duration": DDS_LONG}
"""The QoS numbers and their largest value (seconds for the durations)."""

SUBSTITUTION = "$("
"""What starts a roslaunch / ROS 2 launch substitution."""


def value_problems(tree: ys.YMapping, plain: ys.Plain = None) -> list[Problem]:
    """Return the problems of a structurally valid component library's numbers and launch values.

    ``plain`` is the tree as plain data when the reader built it (``parse_plain``): a
    component whose plain values ``_clean`` passes has no problem to report, and only the
    others are walked in the positioned tree, for their positions. A caller holding only
    the plain data asks ``clean_values`` first, and builds the tree only when it says no.
    """
    problems: list[Problem] = []
    components = _items(tree.items.get("components"))
    fast = plain.get("components") if isinstance(plain, dict) else None
    if not (isinstance(fast, list) and len(fast) == len(components)):
        fast = [None] * len(components)
    for n, (component, values) in enumerate(zip(components, fast, strict=True)):
        if isinstance(values, dict) and _clean(values):
            continue
        fields = component.items if isinstance(component, ys.YMapping) else {}
        fp = fields.get("failure_probability")
        if isinstance(fp, ys.YScalar):
            problems.extend(_number(fp, "failure_probability", 0.0, 1.0))
        metrics = fields.get("metrics")
        if isinstance(metrics, ys.YMapping):
            for key, value in metrics.items.items():
                if isinstance(value, ys.YScalar):
                    problems.extend(_number(value, f"metric '{key}'", 0.0, MAX_METRIC))
        ros = fields.get("ros")
        params = ros.items.get("parameters") if isinstance(ros, ys.YMapping) else None
        if isinstance(params, ys.YMapping):
            for key, value in params.items.items():
                problems.extend(_parameter(key, value))
        problems.extend(_huge(fields.get("dynamics"), f"components[{n}].dynamics"))
        problems.extend(_qos_numbers(fields))
    return problems


def clean_values(plain: ys.Plain) -> bool:
    """Tell whether ``value_problems`` has nothing to report, from the plain data alone.

    For a structurally valid library (the JSON Schema passed); no positioned tree is
    needed to say yes, only to report a problem when the answer is no.
    """
    components = plain.get("components") if isinstance(plain, dict) else None
    if not isinstance(components, list):
        return False
    clean = _clean
    return all([type(c) is dict and clean(c) for c in components])


_NUMBERS = (int, float)
"""The exact types of a YAML number (``bool`` is not one: the Schema reports it)."""


def _clean(component: dict[str, ys.Plain]) -> bool:
    """Tell whether a component's plain values give ``value_problems`` nothing to report.

    The same tests as ``_number`` and ``_parameter`` on plain values, without building
    problems: a comparison with NaN is false, so NaN is never clean. A large library's
    components are almost all clean, and need no walk through their positioned tree. A
    plain int or float is tested inline; anything else goes through ``_within``.
    """
    fp = component.get("failure_probability")
    if fp is not None:
        if type(fp) in _NUMBERS:
            if not 0.0 <= fp <= 1.0:  # type: ignore[operator]
                return False
        elif not _within(fp, 1.0):
            return False
    metrics = component.get("metrics")
    if isinstance(metrics, dict):
        for value in metrics.values():
            if type(value) in _NUMBERS:
                if not 0.0 <= value <= MAX_METRIC:  # type: ignore[operator]
                    return False
            elif not _within(value, MAX_METRIC):
                return False
    dynamics = component.get("dynamics")
    if dynamics is not None and not clean_numbers(dynamics):
        return False
    for key in ("provides", "requires"):  # QoS numbers; most interfaces have neither key
        entries = component.get(key)
        if type(entries) is list:
            for entry in entries:
                has = type(entry) is dict and ("qos" in entry or "any_of" in entry)
                if has and not _clean_interface(entry):  # type: ignore[arg-type]
                    return False
    ros = component.get("ros")
    if ros is None:
        return True
    params = ros.get("parameters") if isinstance(ros, dict) else None
    if isinstance(params, dict):
        for value in params.values():
            if isinstance(value, str) and SUBSTITUTION in value:
                return False
            if isinstance(value, float) and not math.isfinite(value):
                return False
            integer = isinstance(value, int) and not isinstance(value, bool)
            if integer and not INT32[0] <= value <= INT32[1]:  # type: ignore[operator]
                return False
    return True


def schema_value_problems(tree: ys.YMapping) -> list[Problem]:
    """Return the problems of a schema's numbers that no model could hold (``number_problems``).

    The simulation block's numbers (reference, duration, requirements, the plants) become
    floats when the schema is built; an integer too large for one is refused here, at its
    position, before it can stop the build.
    """
    return list(_huge(tree.items.get("simulation"), "simulation"))


def clean_numbers(plain: ys.Plain) -> bool:
    """Tell whether ``plain`` (a subtree as plain data) holds no integer too large for a float."""
    if type(plain) is int:
        return -FLOAT_MAX <= plain <= FLOAT_MAX
    if isinstance(plain, dict):
        return all(clean_numbers(v) for v in plain.values())
    if isinstance(plain, list):
        return all(clean_numbers(v) for v in plain)
    return True


FLOAT_MAX = sys.float_info.max
"""The largest float: an integer beyond it cannot become one (``OverflowError``)."""


def _huge(node: ys.YNode | None, where: str) -> Iterator[Problem]:
    """Refuse every integer under ``node`` too large for a float, at its position."""
    if isinstance(node, ys.YMapping):
        for key, value in node.items.items():
            yield from _huge(value, f"{where}.{key}")
    elif isinstance(node, ys.YSequence):
        for i, value in enumerate(node.items):
            yield from _huge(value, f"{where}[{i}]")
    elif isinstance(node, ys.YScalar) and type(node.value) is int and abs(node.value) > FLOAT_MAX:
        yield Problem(
            node.span,
            f"'{where}' is {_shown(node.raw)}, too large to compute with",
            "write a number within the ranges docs/simulation.md gives (at most 1e12)",
            code="not-finite",
        )


def _interfaces(fields: dict[str, ys.YNode]) -> Iterator[ys.YMapping]:
    """Yield the interface mappings a component provides and requires (any_of's too)."""
    for key in ("provides", "requires"):
        for entry in _items(fields.get(key)):
            if isinstance(entry, ys.YMapping):
                yield entry
                for option in _items(entry.items.get("any_of")):
                    if isinstance(option, ys.YMapping):
                        yield option


def _qos_numbers(fields: dict[str, ys.YNode]) -> Iterator[Problem]:
    """Refuse QoS depths and durations beyond DDS's 32-bit ``long`` (``QOS_LIMITS``)."""
    for interface in _interfaces(fields):
        qos = interface.items.get("qos")
        if not isinstance(qos, ys.YMapping):
            continue
        for key, high in QOS_LIMITS.items():
            node = qos.items.get(key)
            if not isinstance(node, ys.YScalar) or not isinstance(node.value, int | float):
                continue
            if isinstance(node.value, bool) or not node.value > high:
                continue  # NaN, and what the Schema refuses, are reported elsewhere
            unit = "" if key == "depth" else " s"
            yield Problem(
                node.span,
                f"QoS {key} is {_shown(node.raw)}, more than DDS can carry ({high}{unit}, a "
                "32-bit 'long')",
                "give a depth of at most 2147483647 (0 keeps all)"
                if key == "depth"
                else "give at most 2147483647 seconds, or null for none",
                code="out-of-range",
            )


def _clean_interface(entry: dict[str, ys.Plain]) -> bool:
    """Tell whether ``_qos_numbers`` has nothing to report on one interface (any_of's too)."""
    options = entry.get("any_of")
    items = [entry, *options] if isinstance(options, list) else [entry]
    return all(_clean_profile(item) for item in items)


def _clean_profile(interface: ys.Plain) -> bool:
    """Tell whether an interface's ``qos`` holds no number over ``QOS_LIMITS``."""
    qos = interface.get("qos") if isinstance(interface, dict) else None
    if not isinstance(qos, dict):
        return True
    for name, high in QOS_LIMITS.items():
        value = qos.get(name)
        if type(value) in _NUMBERS and value > high:  # type: ignore[operator]
            return False
    return True


def _within(value: ys.Plain, high: float) -> bool:
    """Tell whether ``_number`` accepts ``value`` in [0, ``high``] (anything not a number too)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return True
    return 0.0 <= value <= high


def _items(node: ys.YNode | None) -> list[ys.YNode]:
    return node.items if isinstance(node, ys.YSequence) else []


def _number(node: ys.YScalar, what: str, low: float, high: float) -> Iterator[Problem]:
    """Refuse a non-finite number, one too large for a float, or one outside [low, high]."""
    value = node.value
    if isinstance(value, bool) or not isinstance(value, int | float):
        return  # the JSON Schema reports the type
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        how = "too large to compute with" if isinstance(value, int) else "not a finite number"
        yield Problem(
            node.span,
            f"{what} is {_shown(node.raw)}, {how}",
            f"give a number between {low:g} and {high:g}",
            code="not-finite",
        )
    elif not low <= number <= high:
        yield Problem(
            node.span,
            f"{what} is {_shown(node.raw)}, outside [{low:g}, {high:g}]",
            f"give a number between {low:g} and {high:g}",
            code="out-of-range",
        )


def _parameter(key: str, node: ys.YNode) -> Iterator[Problem]:
    """Refuse unmarked substitutions, non-finite floats and integers ROS 1 cannot carry."""
    if isinstance(node, ys.YMapping):
        return  # {substitution: "..."}: marked by the user (its shape is the Schema's job)
    if not isinstance(node, ys.YScalar):
        return
    value = node.value
    if isinstance(value, str) and SUBSTITUTION in value:
        yield Problem(
            node.span,
            f"parameter '{key}' contains '$(', which roslaunch would evaluate as a "
            "substitution ($(eval ...) runs Python, $(env ...) reads the environment)",
            f'if it is meant as one, mark it: {key}: {{substitution: "{value}"}}; '
            "otherwise remove the '$('",
            code="launch-substitution",
        )
    elif isinstance(value, float) and not math.isfinite(value):
        yield Problem(
            node.span,
            f"parameter '{key}' is {node.raw}, not a finite number",
            "give a finite number",
            code="not-finite",
        )
    elif (
        isinstance(value, int) and not isinstance(value, bool) and not INT32[0] <= value <= INT32[1]
    ):
        yield Problem(
            node.span,
            f"parameter '{key}' is {_shown(node.raw)}, outside the 32-bit integers ROS 1 can carry",
            "write it as a float (with a '.') or as a quoted string",
            code="out-of-range",
        )


def _shown(raw: str) -> str:
    """Quote a number as written, shortened when it is very long (a 401-digit integer)."""
    return raw if len(raw) <= 24 else f"{raw[:12]}...{raw[-4:]} ({len(raw)} characters)"


def repeated_edges(plain: ys.Plain) -> bool:
    """Tell whether ``duplicate_edges`` may find a pair listed twice, from the plain data.

    False (nothing to report) needs no positioned tree: a schema's tree is needed only
    to say where a repeated pair is. True when some value is not a text (the structure
    check's to report) or a pair repeats.
    """
    edges = plain.get("edges", []) if isinstance(plain, dict) else None
    if not isinstance(edges, list):
        return True
    pairs: set[tuple[str, str]] = set()
    count = 0
    for entry in edges:
        if not isinstance(entry, dict):
            return True
        consumer, providers = entry.get("consumer"), entry.get("providers", [])
        if type(consumer) is not str or not isinstance(providers, list):
            return True
        for provider in providers:
            if type(provider) is not str:
                return True
            pairs.add((consumer, provider))
        count += len(providers)
    return len(pairs) != count


def duplicate_edges(tree: ys.YMapping) -> list[Problem]:
    """Warn about a consumer-provider pair listed twice in a schema's edges.

    The loader merges them (the entry without an ``interfaces`` restriction wins), which may
    not be what the author meant: one of the two entries is ignored, silently until now.
    """
    seen: dict[tuple[str, str], Span] = {}
    problems: list[Problem] = []
    for entry in _items(tree.items.get("edges")):
        fields = entry.items if isinstance(entry, ys.YMapping) else {}
        consumer = fields.get("consumer")
        if not isinstance(consumer, ys.YScalar):
            continue
        for provider in _items(fields.get("providers")):
            if not isinstance(provider, ys.YScalar):
                continue
            key = (consumer.raw, provider.raw)
            if key in seen:
                problems.append(
                    Problem(
                        provider.span,
                        f"edge {provider.raw} -> {consumer.raw} is listed again (first at "
                        f"{seen[key]}); the two entries are merged and the one without "
                        "'interfaces' wins",
                        "list each consumer-provider pair once",
                        code="duplicate-edge",
                        severity=Severity.WARNING,
                    )
                )
            else:
                seen[key] = provider.span
    return problems
