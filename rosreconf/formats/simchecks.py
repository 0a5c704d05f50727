"""Check the M-solution's models: component dynamics and schemas' simulation blocks.

The JSON Schema holds their shape; what it cannot say is checked here, each problem at the
offending value: ``.inf`` and ``.nan``, all-zero denominators, improper models (not
realisable, and python-control cannot simulate them), state-space matrices that do not fit
one input and one output around a square A, loops naming unknown roles, and a role in both
the forward and the feedback path (it would sit twice in one loop).

It also holds every number to the range the simulation computes correctly in (docs/simulation.md,
"Ranges"): coefficients and matrix entries between ``MIN_MAGNITUDE`` and ``MAX_MAGNITUDE``
(or zero), no pole or zero faster than ``1 / MIN_TIME``, delays of 0 or between ``MIN_TIME``
and ``MAX_TIME``, durations between ``MIN_DURATION`` and ``MAX_TIME``, references up to
``MAX_MAGNITUDE``. A step response is sampled ``performance.SAMPLES`` times over the duration,
and a loop's polynomials multiply its blocks' coefficients: beyond these ranges a loop's
coefficients span more than a float's 16 digits can hold apart, and a time constant of 1e-18 s
read as "overshoot 100 %, not settled" where the truth is 12 % and 2.6 s (tests/test_simranges.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import TypeAlias

from rosreconf.errors import Problem
from rosreconf.model import Component, InteroperabilitySchema, Span, StateSpace, TransferFunction
from rosreconf.model.dynamics import Dynamics

MAX_MAGNITUDE = 1e12
"""Largest coefficient or matrix entry (a gain), and largest reference step."""

MIN_MAGNITUDE = 1e-12
"""Smallest non-zero coefficient or matrix entry."""

MIN_TIME = 1e-6
"""Shortest time constant (fastest pole or zero) and shortest non-zero delay, seconds."""

MAX_TIME = 1e6
"""Longest delay and longest simulated duration, seconds."""

MIN_DURATION = 1e-3
"""Shortest simulated duration, seconds."""

At: TypeAlias = Callable[[str], Span]
"""Where a value of a component or schema is written, by its ``where`` key."""


def component_problems(c: Component) -> Iterator[Problem]:
    """Yield the problems of ``c``'s dynamics (none when it has no dynamics)."""
    if c.dynamics is not None:
        yield from _model(c.dynamics, "dynamics", c.at, f"the dynamics of component '{c.name}'")


def schema_problems(s: InteroperabilitySchema) -> Iterator[Problem]:
    """Yield the problems of ``s``'s simulation block (none when it has none)."""
    sim = s.simulation
    if sim is None:
        return
    for key in ("reference", "duration"):
        value = getattr(sim, key)
        if not math.isfinite(value):
            yield _not_finite(s.at(f"simulation.{key}"), f"simulation {key}")
    yield from _horizon(sim.reference, sim.duration, s.at)
    for metric, value in sim.requirements.limits().items():
        if not math.isfinite(value):
            yield _not_finite(s.at(f"simulation.requirements.{metric}"), f"requirement {metric}")
    roles = {r.name for r in s.graph.roles}
    names: dict[str, int] = {}
    for i, loop in enumerate(sim.loops):
        key = f"simulation.loops.{i}"
        if loop.name in names:
            yield Problem(
                s.at(f"{key}.name"),
                f"duplicate loop name '{loop.name}' (first is loop {names[loop.name] + 1})",
                "give every loop of a schema a unique name",
                code="duplicate-loop",
            )
        names.setdefault(loop.name, i)
        for path in ("forward", "feedback"):
            for j, role in enumerate(getattr(loop, path)):
                if role not in roles:
                    yield Problem(
                        s.at(f"{key}.{path}.{j}"),
                        f"loop '{loop.name}' names role '{role}', which schema '{s.name}' "
                        "does not define",
                        "use one of the schema's roles: " + ", ".join(sorted(roles)),
                        code="unknown-loop-role",
                    )
        feedback = set(loop.feedback)
        for j, role in enumerate(loop.forward):
            if role in feedback:
                yield Problem(
                    s.at(f"{key}.forward.{j}"),
                    f"role '{role}' is in both the forward and the feedback path of loop "
                    f"'{loop.name}'",
                    "a role's component sits in one place of a loop: keep it in one path",
                    code="role-in-both-paths",
                )
        yield from _model(loop.plant, f"{key}.plant", s.at, f"the plant of loop '{loop.name}'")


def _model(model: Dynamics, key: str, at: At, what: str) -> Iterator[Problem]:
    """Yield the problems of a transfer function or a state-space model written at ``key``.

    ``at`` (a look-up in the file's tree) is asked only for a problem's position.
    """
    ss = isinstance(model, StateSpace)
    rows = (
        dict(zip("ABCD", (model.a, model.b, model.c, model.d), strict=True))
        if isinstance(model, StateSpace)
        else {"num": (model.num,), "den": (model.den,)}
    )
    cells = [
        (p, i, j, v) for p, m in rows.items() for i, row in enumerate(m) for j, v in enumerate(row)
    ]

    def cell(part: str, i: int, j: int) -> tuple[str, str]:
        """Return where a number is written and how a message names it."""
        if ss:
            return f"{key}.state_space.{part}.{i}.{j}", f"{part}[{i + 1}][{j + 1}] of {what}"
        return f"{key}.transfer_function.{part}.{j}", f"{part} coefficient {j + 1} of {what}"

    broken = [cell(p, i, j) for p, i, j, v in cells if not math.isfinite(v)]
    for where, label in broken:
        yield _not_finite(at(where), label)
    if not math.isfinite(model.delay):
        yield _not_finite(at(f"{key}.delay"), f"the delay of {what}")
    if broken or not math.isfinite(model.delay):
        return
    if isinstance(model, TransferFunction) and not any(model.den):
        yield Problem(
            at(f"{key}.transfer_function.den"),
            f"{what} has a denominator of zeros (it divides by zero)",
            "give at least one non-zero coefficient, e.g. den: [1.0]",
            code="zero-denominator",
        )
        return
    if model.delay != 0 and not MIN_TIME <= model.delay <= MAX_TIME:
        yield Problem(
            at(f"{key}.delay"),
            f"the delay of {what} is {model.delay:g} s, outside the {MIN_TIME:g} s to "
            f"{MAX_TIME:g} s (or 0) a simulation computes correctly with",
            f"write 0 for a delay shorter than {MIN_TIME:g} s; docs/simulation.md gives the ranges",
            code="out-of-range",
        )
    sized = True
    for part, i, j, value in cells:
        if value != 0 and not MIN_MAGNITUDE <= abs(value) <= MAX_MAGNITUDE:
            sized = False
            where, label = cell(part, i, j)
            yield Problem(
                at(where),
                f"{label} is {value:g}, outside the {MIN_MAGNITUDE:g} to {MAX_MAGNITUDE:g} (or 0) "
                "a simulation computes correctly with",
                ("" if ss else "num and den may be multiplied by one common factor; beyond that, ")
                + "the model is outside the ranges of docs/simulation.md",
                code="out-of-range",
            )
    if isinstance(model, StateSpace):
        if sized:
            rate = max((sum(abs(v) for v in row) for row in model.a), default=0.0)
            how = "poles (bounded by A's largest row sum) up to"
            yield from _fast(rate, at, f"{key}.state_space.A", what, how)
        yield from _shapes(model, f"{key}.state_space", at, what)
        return
    for part in ("num", "den") if sized else ():
        how = "a pole at" if part == "den" else "a zero at"
        yield from _fast(
            _rate(getattr(model, part)), at, f"{key}.transfer_function.{part}", what, how
        )
    num_order = _order(model.num)
    den_order = _order(model.den)
    if num_order > den_order:
        yield Problem(
            at(f"{key}.transfer_function.num"),
            f"{what} is improper: its numerator has order {num_order}, its denominator "
            f"order {den_order}",
            "a physical model's denominator has at least the numerator's order; add a fast "
            "pole (e.g. multiply den by (0.01 s + 1)) or drop leading numerator terms",
            code="improper-transfer-function",
        )


def _shapes(ss: StateSpace, key: str, at: At, what: str) -> Iterator[Problem]:
    """Refuse matrices that do not fit one input and one output around A (n x n, n its rows).

    Reported at the matrix (too many or too few rows) or at its first row of the wrong width.
    """
    n = len(ss.a)
    for part, matrix in zip("ABCD", (ss.a, ss.b, ss.c, ss.d), strict=True):
        rows, cols = {"A": (n, n), "B": (n, 1), "C": (1, n), "D": (1, 1)}[part]
        need = f"{part} must be {rows} x {cols}"
        why = "single input, single output" if part != "A" else "square"
        if len(matrix) != rows:
            yield Problem(
                at(f"{key}.{part}"),
                f"{what}: {part} has {len(matrix)} row(s), {need} ({why}; A is {n} x {n})",
                _shape_hint(part, rows, cols),
                code="state-space-shape",
            )
            continue
        for i, row in enumerate(matrix):
            if len(row) != cols:
                yield Problem(
                    at(f"{key}.{part}.{i}"),
                    f"{what}: row {i + 1} of {part} has {len(row)} number(s), {need} ({why}; "
                    f"A is {n} x {n})",
                    _shape_hint(part, rows, cols),
                    code="state-space-shape",
                )
                break


def _shape_hint(part: str, rows: int, cols: int) -> str:
    if part == "B" and cols == 1:
        example = ", ".join(["[0.0]"] * (rows - 1) + ["[1.0]"])
        return f"write B as {rows} row(s) of one number, e.g. [{example}] (one input)"
    if part == "C" and rows == 1:
        example = ", ".join(["1.0"] + ["0.0"] * (cols - 1))
        return f"write C as one row of {cols} number(s), e.g. [[{example}]] (one output)"
    if part == "D":
        return "write D as [[d]], the direct feed-through (one input, one output)"
    return f"write A as {rows} row(s) of {cols} number(s) each"


def _order(coefficients: tuple[float, ...]) -> int:
    """Return the polynomial's order once leading zeros are dropped (-1 for all zeros)."""
    for i, c in enumerate(coefficients):
        if c != 0:
            return len(coefficients) - 1 - i
    return -1


def _not_finite(span: Span, what: str) -> Problem:
    return Problem(
        span,
        f"{what} is not a finite number",
        "write a real number (YAML's .inf and .nan are not allowed here)",
        code="not-finite",
    )


def _rate(coefficients: tuple[float, ...]) -> float:
    """Return max_k |c_k / c_0|^(1/k): the polynomial's largest root lies in [rate / n, 2 rate].

    Fujiwara's bound (2 rate) above, Vieta's formulas below, leading zeros dropped; 0 for a
    constant. Pure arithmetic, so ``validate`` needs no numpy.
    """
    trimmed = coefficients[len(coefficients) - 1 - _order(coefficients) :]
    if len(trimmed) < 2:
        return 0.0
    lead = abs(trimmed[0])
    return max(float(abs(c / lead) ** (1.0 / k)) for k, c in enumerate(trimmed[1:], 1))


def _fast(rate: float, at: At, key: str, what: str, how: str) -> Iterator[Problem]:
    """Refuse a model whose fastest pole or zero is faster than ``1 / MIN_TIME`` rad/s."""
    if rate > 1.0 / MIN_TIME:
        yield Problem(
            at(key),
            f"{what} has {how} about {rate:.3g} rad/s, a time constant of about "
            f"{1.0 / rate:.3g} s, shorter than the {MIN_TIME:g} s a simulation resolves",
            f"model dynamics faster than {MIN_TIME:g} s as instantaneous (drop the factor: "
            "den [1e-9, 1] becomes [1])",
            code="out-of-range",
        )


def _horizon(reference: float, duration: float, at: At) -> Iterator[Problem]:
    """Refuse a duration outside [``MIN_DURATION``, ``MAX_TIME``] or a reference over the range."""
    if math.isfinite(duration) and not MIN_DURATION <= duration <= MAX_TIME:
        yield Problem(
            at("simulation.duration"),
            f"simulation duration is {duration:g} s, outside the {MIN_DURATION:g} s to "
            f"{MAX_TIME:g} s a simulation computes correctly with",
            f"simulate between {MIN_DURATION:g} s and {MAX_TIME:g} s (the response is sampled "
            "1001 times over it)",
            code="out-of-range",
        )
    if math.isfinite(reference) and reference > MAX_MAGNITUDE:
        yield Problem(
            at("simulation.reference"),
            f"simulation reference is {reference:g}, more than {MAX_MAGNITUDE:g}",
            f"give a reference step of at most {MAX_MAGNITUDE:g} (the figures are relative to it)",
            code="out-of-range",
        )
