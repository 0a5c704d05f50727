"""Simulate a configuration's control loops and judge them: the paper's M-solution (Section 4).

The S-solution decides whether components *connect*; this module decides whether the
connected loop *performs*. Each loop of a schema's ``simulation`` block is a classic unity
reference, negative-feedback loop (the paper's Fig. 2)::

    reference --(+)--> forward[0] --> ... --> forward[-1] --> plant --+--> y
                (-)                                                    |
                 +---- feedback[-1] <-- ... <-- feedback[0] <----------+

so the closed loop from the reference to the plant output ``y`` is
``F P / (1 + F P H)`` with ``F`` the product of the forward blocks and ``H`` the product of
the feedback blocks. python-control builds it (``control.feedback``), finds its poles,
simulates its step response and reads the step figures (``control.step_info``, 2 % band).

Dead time is replaced by a Pade approximant of order ``PADE_ORDER`` (``control.pade``): a
rational transfer function keeps the loop finite-dimensional, so stability is read from
closed-loop poles and python-control can simulate it. The price is a small error near the
delay itself (docs/simulation.md gives the measured figures; tests/test_performance.py checks
them against an exact simulation of a delayed loop).

Everything a worker needs is plain, hashable, picklable data (``LoopSpec``), so that equal
loops are simulated once (``simulate_all`` keys its cache on the spec's content) and the same
units of work run in a local process pool or on a Dask cluster unchanged.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass
from typing import Any

import control
import numpy as np
import scipy.linalg

from rosreconf.model.dynamics import METRICS, PerformanceRequirements, TransferFunction

SETTLING_BAND = 0.02
"""The settling band, relative to the final value (python-control's default, 2 %)."""

PADE_ORDER = 5
"""Order of the Pade approximant that stands in for dead time (numerator and denominator)."""

SAMPLES = 1001
"""Points of the simulated step response, evenly spaced over the schema's ``duration``."""


@dataclass(frozen=True)
class LoopSpec:
    """One loop to simulate: its blocks in order, the plant, the reference step and horizon.

    Two specs with equal content are the same simulation, which is what the cache relies on.

    Attributes:
        forward: the blocks from the error signal to the plant input, in order.
        plant: the environment model.
        feedback: the blocks from the plant output back to the comparison, in order.
        reference: the size of the reference step.
        duration: how long to simulate, seconds.
    """

    forward: tuple[TransferFunction, ...]
    plant: TransferFunction
    feedback: tuple[TransferFunction, ...]
    reference: float = 1.0
    duration: float = 10.0


@dataclass(frozen=True)
class LoopResult:
    """How one loop performs: the figures of its step response.

    Attributes:
        stable: every closed-loop pole has a negative real part.
        settling_time: seconds until the output stays within the 2 % band around its final
            value; None when unstable, when it has not settled within the duration, or when
            the final value is 0 (no relative band exists).
        steady_state_error: ``|1 - y_final / reference|``, ``y_final`` from the DC gain; None
            when unstable.
        overshoot: percent above the final value (python-control's ``step_info``); None when
            unstable or when the final value is 0.
        final_value: the output's final value (reference times the DC gain); None when
            unstable.
    """

    stable: bool
    settling_time: float | None
    steady_state_error: float | None
    overshoot: float | None
    final_value: float | None

    def figure(self, metric: str) -> float:
        """Return ``metric`` for comparisons: +inf when undefined (unstable, not settled)."""
        value: float | None = getattr(self, metric)
        return math.inf if value is None else value


def to_control(tf: TransferFunction) -> control.TransferFunction:
    """Return ``tf`` as python-control's transfer function, dead time by Pade approximant."""
    num, den = _polynomials((tf,))
    return control.tf(num, den)


@functools.lru_cache(maxsize=256)
def _pade(delay: float) -> tuple[np.ndarray[Any, Any], np.ndarray[Any, Any]]:
    num, den = control.pade(delay, PADE_ORDER)
    return np.asarray(num, dtype=float), np.asarray(den, dtype=float)


def _polynomials(
    blocks: Iterable[TransferFunction],
) -> tuple[np.ndarray[Any, Any], np.ndarray[Any, Any]]:
    """Return the numerator and denominator of the blocks in series (dead time by Pade).

    Plain polynomial products (numpy) rather than python-control's transfer-function
    products: the same arithmetic, without building an object per factor, which made
    assembling a loop cost more than simulating it.
    """
    num, den = np.array([1.0]), np.array([1.0])
    for block in blocks:
        num, den = np.polymul(num, block.num), np.polymul(den, block.den)
        if block.delay > 0:
            pade_num, pade_den = _pade(block.delay)
            num, den = np.polymul(num, pade_num), np.polymul(den, pade_den)
    return num, den


def closed_loop(spec: LoopSpec) -> control.TransferFunction | None:
    """Return the closed loop from the reference to the plant output (negative feedback).

    The forward path (forward blocks, then the plant) and the feedback path are each one
    transfer function; ``control.feedback`` closes the loop. Returns None when the loop is
    ill-posed: proper blocks with direct feed-through can make ``1 + F P H`` vanish at
    infinite frequency (an algebraic loop), leaving no proper closed loop to simulate. Such a
    loop is reported unstable.
    """
    forward = control.tf(*_polynomials((*spec.forward, spec.plant)))
    feedback = control.tf(*_polynomials(spec.feedback))
    try:
        sys = control.feedback(forward, feedback, sign=-1)
    except ValueError:  # python-control: "zero denominator"
        return None
    num = np.trim_zeros(np.atleast_1d(sys.num[0][0]), "f")
    den = np.trim_zeros(np.atleast_1d(sys.den[0][0]), "f")
    return sys if len(den) > 0 and len(num) <= len(den) else None


def is_stable(poles: Sequence[complex] | np.ndarray[Any, Any]) -> bool:
    """Tell whether every pole lies strictly in the left half-plane (a stable loop)."""
    return bool(np.all(np.real(poles) < 0))


def time_points(spec: LoopSpec) -> np.ndarray[Any, Any]:
    """Return the evenly spaced instants at which the step response is simulated."""
    return np.linspace(0.0, spec.duration, SAMPLES)


def step_curve(spec: LoopSpec) -> tuple[np.ndarray[Any, Any], np.ndarray[Any, Any]]:
    """Return (time, output) of the loop's response to its reference step (for plots).

    An ill-posed loop has no response; its output is NaN throughout (plots leave it out).
    """
    t = time_points(spec)
    sys = closed_loop(spec)
    if sys is None:
        return t, np.full_like(t, np.nan)
    return t, spec.reference * step_response(sys, t)


BLOCK = 32
"""Samples computed per step of the blocked recursion in ``step_response``."""


def step_response(sys: control.TransferFunction, t: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    """Return the unit-step response of ``sys`` at the evenly spaced instants ``t``.

    python-control gives the state-space form; a zero-order hold discretises it (as
    ``control.c2d`` does), which is exact for a step input at the sample instants. The
    recursion ``x[k+1] = Ad x[k] + Bd`` is then run ``BLOCK`` samples at a time:
    ``x[s+j] = Ad^j x[s] + (Ad^(j-1) + ... + I) Bd``, with the powers computed once, so
    that a thousand samples take a few dozen array operations instead of a thousand Python
    steps (``control.step_response`` runs one Python step per sample, which took most of a
    loop's time). tests/test_performance.py holds the curves to scipy's and
    python-control's.
    """
    ss = control.ss(sys)
    n = ss.nstates
    # Zero-order hold: expm([[A, B], [0, 0]] dt) = [[Ad, Bd], [0, 1]] (what control.c2d
    # computes, without building a system object, which cost ten times the exponential).
    augmented = np.zeros((n + 1, n + 1))
    augmented[:n, :n] = np.asarray(ss.A, dtype=float)
    augmented[:n, n] = np.asarray(ss.B, dtype=float)[:, 0]
    held = scipy.linalg.expm(augmented * float(t[1] - t[0]))
    a, b = held[:n, :n], held[:n, n]
    c = np.asarray(ss.C, dtype=float)[0]
    feedthrough = float(np.asarray(ss.D, dtype=float)[0, 0])
    y = np.empty(len(t))
    with np.errstate(over="ignore", invalid="ignore"):  # unstable curves (plots) may blow up
        powers = np.empty((BLOCK, n, n))
        sums = np.empty((BLOCK, n))
        powers[0], sums[0] = np.eye(n), 0.0
        for j in range(1, BLOCK):
            powers[j] = a @ powers[j - 1]
            sums[j] = a @ sums[j - 1] + b
        step_a = a @ powers[-1]
        step_b = a @ sums[-1] + b
        c_powers = np.einsum("i,jik->jk", c, powers)  # row j: c Ad^j
        c_sums = sums @ c + feedthrough
        x = np.zeros(n)
        for start in range(0, len(t), BLOCK):
            block = c_powers @ x + c_sums
            y[start : start + BLOCK] = block[: len(t) - start]
            x = step_a @ x + step_b
    return y


def simulate_loop(spec: LoopSpec) -> LoopResult:
    """Simulate one loop's step response and read its figures.

    Stability comes from the closed-loop poles; the final value from the DC gain (exact for
    a stable loop, whatever the duration); settling time and overshoot from python-control's
    ``step_info`` over the simulated horizon, relative to that final value.
    """
    sys = closed_loop(spec)
    if sys is None or not is_stable(sys.poles()):
        return LoopResult(False, None, None, None, None)
    gain = float(np.real(sys.dcgain()))
    final = spec.reference * gain
    error = abs(1.0 - gain)
    if not math.isfinite(final) or abs(gain) < 1e-12:
        return LoopResult(True, None, error if math.isfinite(error) else None, None, final)
    t = time_points(spec)
    y = spec.reference * step_response(sys, t)
    settling, overshoot = step_figures(t, y, final)
    return LoopResult(True, settling, error, overshoot, final)


def step_figures(
    t: np.ndarray[Any, Any], y: np.ndarray[Any, Any], final: float
) -> tuple[float | None, float | None]:
    """Return (settling time, overshoot %) of a step response by python-control's step_info.

    ``step_info`` fails when the output never reaches 90 % of its final value (it looks for
    a rise time); such a response has not settled within the horizon and has not overshot.
    """
    if not np.any(np.sign(final) * (y - 0.9 * final) >= 0):
        return None, 0.0
    info = control.step_info(y, t, yfinal=final, SettlingTimeThreshold=SETTLING_BAND)
    settling = float(info["SettlingTime"])
    overshoot = float(info["Overshoot"])
    return (
        settling if math.isfinite(settling) else None,
        overshoot if math.isfinite(overshoot) else None,
    )


@functools.cache
def single_threaded_blas() -> None:
    """Make this process's BLAS use one thread (once per process; threadpoolctl).

    A loop's matrices are 5 to 30 states wide. For such sizes a multithreaded BLAS only
    adds synchronisation: on a busy two-core machine a 9x9 matrix exponential took 32 ms
    with OpenBLAS's threads and 0.2 ms with one. Parallelism comes from the worker
    processes instead (``--workers``, ``--cluster``), and every process computes the same
    way (Dask workers run single-threaded BLAS by default too).
    """
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


def simulate_chunk(specs: Sequence[LoopSpec]) -> list[LoopResult]:
    """Simulate every loop of ``specs`` (a unit of work for a process pool or a Dask worker)."""
    single_threaded_blas()
    return [simulate_loop(spec) for spec in specs]


Progress = Callable[[int], None]
"""Called with the number of loops just simulated (for a progress display)."""


def simulate_all(
    specs: Iterable[LoopSpec],
    cache: dict[LoopSpec, LoopResult] | None = None,
    executor: Executor | None = None,
    chunk_size: int = 4,
    progress: Progress | None = None,
) -> dict[LoopSpec, LoopResult]:
    """Simulate each distinct loop of ``specs`` once; return the cache, spec -> result.

    Loops already in ``cache`` are not simulated again. With an ``executor`` (a process
    pool, or a Dask client's ``get_executor()``) the distinct loops go out in chunks of
    ``chunk_size``; the results are the same as in-process, only sooner.
    """
    cache = {} if cache is None else cache
    pending = list(dict.fromkeys(s for s in specs if s not in cache))
    chunks = [tuple(pending[i : i + chunk_size]) for i in range(0, len(pending), chunk_size)]
    if executor is None or len(chunks) < 2:
        for chunk in chunks:
            cache.update(zip(chunk, simulate_chunk(chunk), strict=True))
            if progress:
                progress(len(chunk))
        return cache
    futures = {executor.submit(simulate_chunk, chunk): chunk for chunk in chunks}
    for future in as_completed(futures):
        chunk = futures[future]
        cache.update(zip(chunk, future.result(), strict=True))
        if progress:
            progress(len(chunk))
    return cache


def meets(requirements: PerformanceRequirements, result: LoopResult) -> bool:
    """Tell whether a loop meets every requirement (an unstable loop meets none)."""
    if not result.stable:
        return False
    return all(result.figure(m) <= limit for m, limit in requirements.limits().items())


def worst(results: Iterable[LoopResult]) -> dict[str, float]:
    """Return metric -> the worst figure over ``results`` (+inf when any is undefined)."""
    listed = list(results)
    return {m: max((r.figure(m) for r in listed), default=0.0) for m in METRICS}


def dominates(a: Sequence[float], b: Sequence[float]) -> bool:
    """Tell whether ``a`` is at least as good as ``b`` everywhere and better somewhere."""
    return all(x <= y for x, y in zip(a, b, strict=True)) and any(
        x < y for x, y in zip(a, b, strict=True)
    )


def pareto_front(points: Sequence[Sequence[float]]) -> list[int]:
    """Return the indices of the points no other point dominates (lower is better), in order.

    Sorting by the figures first means a point can only be dominated by one before it, and
    only points already on the front need checking: O(n f) for a front of f points.
    """
    order = sorted(range(len(points)), key=lambda i: (tuple(points[i]), i))
    front: list[int] = []
    for i in order:
        if not any(dominates(points[j], points[i]) for j in front):
            front.append(i)
    return sorted(front)


def rank_key(meets: bool, figures: Mapping[str, float]) -> tuple[bool, float, float, float]:
    """Return the key that ranks configurations: meeting the requirements first.

    Then faster settling, smaller steady-state error and smaller overshoot, in that order:
    the paper names settling time first among the measures (Section 5).
    """
    return (
        not meets,
        figures["settling_time"],
        figures["steady_state_error"],
        figures["overshoot"],
    )
