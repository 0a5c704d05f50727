"""Compute with single-input single-output linear models: the arithmetic under a loop's figures.

Closing a loop, finding its poles, realising it in state space, simulating its step response
and reading the step figures are a few polynomial and matrix operations on numpy arrays. They
follow python-control step for step (``control.pade``, ``control.feedback``, ``control.ss``
without slycot, which is scipy's ``tf2ss``, ``control.step_info``) and tests/test_lti.py holds
each to python-control and scipy. They are written out here rather than called because
importing python-control imports scipy.signal, scipy.stats and matplotlib.pyplot: two seconds
of CPU per process, more than simulating a few hundred distinct loops takes, in a command
whose whole-process time is its benchmark. Only numpy is imported: the matrix exponential
and the balancing are ``matfuncs``'s, written as scipy.linalg computes them, because
importing scipy.linalg costs ``plan`` over a quarter of its whole-process CPU.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable
from typing import Any

from rosreconf.analysis.matfuncs import balance, expm
from rosreconf.analysis.numeric import np
from rosreconf.model.dynamics import Dynamics, StateSpace, TransferFunction

Array = np.ndarray[Any, Any]

PADE_ORDER = 5
"""Order of the Pade approximant that stands in for dead time (numerator and denominator)."""

BLOCK = 32
"""Samples computed per step of the blocked recursion in ``step_response``."""


@functools.lru_cache(maxsize=256)
def pade(delay: float, order: int = PADE_ORDER) -> tuple[Array, Array]:
    """Return (num, den) of the Pade approximant of ``e^(-delay s)``, as ``control.pade``.

    The coefficients come from Golub and van Loan's ``Dpq`` accumulated term by term (the
    same recurrence, in the same order, as python-control), normalised so ``den[0] == 1``.
    """
    if delay == 0:
        return np.array([1.0]), np.array([1.0])
    num = [0.0] * (order + 1)
    den = [0.0] * (order + 1)
    num[-1] = den[-1] = 1.0
    cn = cd = 1.0
    for k in range(1, order + 1):
        cn *= -delay * (order - k + 1) / (order + order - k + 1) / k
        num[order - k] = cn
    for k in range(1, order + 1):
        cd *= delay * (order - k + 1) / (order + order - k + 1) / k
        den[order - k] = cd
    lead = den[0]
    return np.array([c / lead for c in num]), np.array([c / lead for c in den])


def transfer_function(model: Dynamics) -> TransferFunction:
    """Return ``model`` as a transfer function (a state-space model by ``ss2tf``)."""
    return ss2tf(model) if isinstance(model, StateSpace) else model


@functools.lru_cache(maxsize=1024)
def ss2tf(model: StateSpace) -> TransferFunction:
    """Return the transfer function ``C (sI - A)^-1 B + D`` of a SISO state-space model.

    As scipy's and python-control's ``ss2tf``: ``den = det(sI - A)``, and
    ``num = det(sI - A + B C) + (D - 1) den`` (the matrix determinant lemma), with the
    characteristic polynomials from ``np.poly``. The delay carries over. The shapes must
    have been checked (``formats.simchecks``): A n x n, B n x 1, C 1 x n, D 1 x 1.
    """
    a = np.array(model.a, dtype=float)
    b = np.array(model.b, dtype=float)[:, 0]
    c = np.array(model.c, dtype=float)[0]
    d = float(model.d[0][0])
    den = np.poly(a)
    num = np.poly(a - np.outer(b, c)) + (d - 1.0) * den
    return TransferFunction(tuple(float(x) for x in num), tuple(float(x) for x in den), model.delay)


def series(blocks: Iterable[TransferFunction]) -> tuple[Array, Array]:
    """Return the numerator and denominator of the blocks in series (dead time by Pade)."""
    num, den = np.array([1.0]), np.array([1.0])
    for block in blocks:
        num, den = np.convolve(num, block.num), np.convolve(den, block.den)
        if block.delay > 0:
            pade_num, pade_den = pade(block.delay)
            num, den = np.convolve(num, pade_num), np.convolve(den, pade_den)
    return num, den


def _add(p: Array, q: Array) -> Array:
    """Return the sum of two polynomials (highest power first), as ``np.polyadd``."""
    if len(p) < len(q):
        p, q = q, p
    out = np.array(p, dtype=float)
    out[len(p) - len(q) :] += q
    return out


def feedback(forward: tuple[Array, Array], back: tuple[Array, Array]) -> tuple[Array, Array]:
    """Return ``G / (1 + G H)`` of ``forward`` G and ``back`` H, as ``control.feedback``.

    ``(nG dH) / (dG dH + nG nH)``, leading zeros dropped. Either may come back empty: an
    all-zero denominator, which python-control refuses ("zero denominator").
    """
    (num_g, den_g), (num_h, den_h) = forward, back
    num = np.convolve(num_g, den_h)  # np.polymul's product, without its poly1d objects
    den = _add(np.convolve(den_g, den_h), np.convolve(num_g, num_h))
    return np.trim_zeros(np.atleast_1d(num), "f"), np.trim_zeros(np.atleast_1d(den), "f")


def is_stable(poles: Array) -> bool:
    """Tell whether every pole lies strictly in the left half-plane (a stable loop)."""
    return bool(np.all(np.real(poles) < 0))


def realise(num: Array, den: Array) -> tuple[Array, Array, Array, float]:
    """Return (A, B, C, D) of ``num/den`` in controllable canonical form, as scipy's tf2ss.

    ``A`` is ``n x n`` (``n`` = the order; 0 for a static gain), ``B`` and ``C`` vectors.
    The model must be proper (``len(num) <= len(den)``, ``den[0] != 0``).
    """
    lead = float(den[0])
    den = np.asarray(den, dtype=float) / lead
    padded = np.zeros(len(den))
    padded[len(den) - len(num) :] = np.asarray(num, dtype=float) / lead
    d = float(padded[0])
    n = len(den) - 1
    a = np.zeros((n, n))
    if n:
        a[0] = -den[1:]
        a[1:, :-1] = np.eye(n - 1)
    b = np.zeros(n)
    if n:
        b[0] = 1.0
    c = padded[1:] - d * den[1:]
    return a, b, c, d


def step_response(num: Array, den: Array, t: Array) -> Array:
    """Return the unit-step response of ``num/den`` at the evenly spaced instants ``t``.

    The canonical state-space form, balanced, is discretised with a zero-order hold (``expm`` of the
    augmented matrix, as ``control.c2d`` computes), which is exact for a step input at the
    sample instants. The recursion ``x[k+1] = Ad x[k] + Bd`` is then run ``BLOCK`` samples at
    a time: ``x[s+j] = Ad^j x[s] + (Ad^(j-1) + ... + I) Bd``, with the powers computed once,
    so a thousand samples take a few dozen array operations instead of a thousand Python
    steps. tests/test_lti.py holds the curves to scipy's and python-control's.
    """
    a, b, c, d = realise(num, den)
    n = len(b)
    y = np.empty(len(t))
    if n == 0:
        y.fill(d)
        return y
    # Balance first (a diagonal similarity by powers of two, exact in floating point): a
    # loop's companion matrix holds its characteristic polynomial's coefficients, 1e-3 to
    # 1e25 for a 14th-order loop with two Pade delays, and the exponential of it unbalanced
    # erred by 2.5e-3 of the output (tests/test_lti.py measures it against a block-wise
    # realisation, which agrees with the balanced one to 1e-13).
    scale = balance(a)
    a = a / scale[:, None] * scale[None, :]
    b, c = b / scale, c * scale
    augmented = np.zeros((n + 1, n + 1))
    augmented[:n, :n] = a
    augmented[:n, n] = b
    held = expm(augmented * float(t[1] - t[0]))
    ad, bd = held[:n, :n], held[:n, n]
    with np.errstate(over="ignore", invalid="ignore"):  # unstable curves (plots) may blow up
        powers = np.empty((BLOCK, n, n))
        sums = np.empty((BLOCK, n))
        powers[0], sums[0] = np.eye(n), 0.0
        for j in range(1, BLOCK):
            powers[j] = ad @ powers[j - 1]
            sums[j] = ad @ sums[j - 1] + bd
        step_a = ad @ powers[-1]
        step_b = ad @ sums[-1] + bd
        c_powers = np.einsum("i,jik->jk", c, powers)  # row j: c Ad^j
        c_sums = sums @ c + d
        x = np.zeros(n)
        for start in range(0, len(t), BLOCK):
            block = c_powers @ x + c_sums
            y[start : start + BLOCK] = block[: len(t) - start]
            x = step_a @ x + step_b
    return y


def step_figures(
    t: Array, y: Array, final: float, band: float
) -> tuple[float | None, float | None]:
    """Return (settling time, overshoot %) of a step response, as ``control.step_info``.

    The settling time is the first instant after the last sample outside ``band`` around
    ``final`` (None when the last sample is still outside); the overshoot is the percentage
    by which the output, signed as ``final``, exceeds ``final``. ``step_info`` refuses a
    response that never reaches 90 % of its final value (it looks for a rise time); such a
    response has not settled within the horizon and has not overshot: (None, 0.0). A curve
    that overflowed has no overshoot (None). ``final`` must be finite and nonzero.
    """
    sign = float(np.sign(final))
    if not np.any(sign * (y - 0.9 * final) >= 0):
        return None, 0.0
    outside = np.nonzero(np.abs(y / final - 1) >= band)[0]
    settled = 0 if outside.size == 0 else int(outside[-1]) + 1
    settling = float(t[settled]) if settled < len(t) else None
    peak = float((sign * y).max())
    excess = abs(peak) - abs(final)
    overshoot = abs(100.0 * excess / final) if excess > 0 else 0.0
    return settling, (overshoot if math.isfinite(overshoot) else None)
