"""Theorem 10: how much redundancy keeps a system reconfigurable with probability q.

With N abstraction labels, each playable by r components that fail independently with
probability p, the system stays reconfigurable when every label keeps one working
component: probability (1 - p^r)^N. The paper solves (1 - p^r)^N = q for r exactly,

    r = log(1 - q^(1/N)) / log p,

and approximates it, using exp(log q / N) ~ 1 + log q / N, by

    r ~ log(-log q) / log p - log N / log p.

Note: the formula needs p to be a component's probability of *failure*; the paper's text
calls p(c) the probability of availability, under which the formula is meaningless
(1 - p^r would fall as r grows). rosreconf reads p as the failure probability.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rosreconf.errors import UsageError


@dataclass(frozen=True)
class RedundancyAnswer:
    """The redundancy Theorem 10 asks for, exact and approximate.

    Attributes:
        p: failure probability of one component.
        n: number of abstraction labels the system needs (N).
        q: required probability of reconfigurability.
        r_exact: the real root of (1 - p^r)^N = q.
        r_needed: the smallest integer r with (1 - p^r)^N >= q.
        achieved: (1 - p^r_needed)^N.
        r_approx: the paper's approximation.
        error: r_approx - r_exact.
        relative_error: error / r_exact.
    """

    p: float
    n: int
    q: float
    r_exact: float
    r_needed: int
    achieved: float
    r_approx: float
    error: float
    relative_error: float


def survival(p: float, r: int | float, n: int) -> float:
    """Return (1 - p^r)^N, the probability every label keeps a working component."""
    return math.exp(n * math.log1p(-(p**r)))


def redundancy(p: float, n: int, q: float) -> RedundancyAnswer:
    """Solve Theorem 10 for r, exactly and by the paper's approximation.

    Raises:
        UsageError: p or q outside (0, 1), or N below 1.
    """
    if not 0 < p < 1:
        raise UsageError(f"p = {p} must lie strictly between 0 and 1 (a failure probability)")
    if not 0 < q < 1:
        raise UsageError(f"q = {q} must lie strictly between 0 and 1 (a probability below 1)")
    if n < 1:
        raise UsageError(f"N = {n} must be at least 1")
    # 1 - q^(1/N) computed as -expm1(log q / N) to keep precision when q is close to 1.
    r_exact = math.log(-math.expm1(math.log(q) / n)) / math.log(p)
    r_needed = max(1, math.ceil(r_exact - 1e-12))
    while survival(p, r_needed, n) < q:
        r_needed += 1
    while r_needed > 1 and survival(p, r_needed - 1, n) >= q:
        r_needed -= 1
    r_approx = math.log(-math.log(q)) / math.log(p) - math.log(n) / math.log(p)
    error = r_approx - r_exact
    return RedundancyAnswer(
        p=p,
        n=n,
        q=q,
        r_exact=r_exact,
        r_needed=r_needed,
        achieved=survival(p, r_needed, n),
        r_approx=r_approx,
        error=error,
        relative_error=error / r_exact if r_exact else math.inf,
    )
