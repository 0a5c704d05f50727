"""Simulate a configuration's control loops and judge them: the paper's M-solution (Section 4).

The S-solution decides whether components *connect*; this module decides whether the
connected loop *performs*. Each loop of a schema's ``simulation`` block is a classic unity
reference, negative-feedback loop (the paper's Fig. 2)::

    reference --(+)--> forward[0] --> ... --> forward[-1] --> plant --+--> y
                (-)                                                    |
                 +---- feedback[-1] <-- ... <-- feedback[0] <----------+

so the closed loop from the reference to the plant output ``y`` is
``F P / (1 + F P H)`` with ``F`` the product of the forward blocks and ``H`` the product of
the feedback blocks. ``rosreconf.analysis.lti`` closes it, finds its poles, simulates its
step response and reads the step figures as python-control does (``control.feedback``,
``control.step_info`` with its 2 % band), without importing python-control.

Dead time is replaced by a Pade approximant of order ``lti.PADE_ORDER`` (as ``control.pade``):
a rational transfer function keeps the loop finite-dimensional, so stability is read from
closed-loop poles. The price is a small error near the delay itself (docs/simulation.md
gives the measured figures; tests/test_performance.py checks them against an exact
simulation of a delayed loop).

Everything a worker needs is plain, hashable, picklable data (``LoopSpec``), so that equal
loops are simulated once (``simulate_all`` keys its cache on the spec's content) and the same
units of work run in a local process pool or on a Dask cluster unchanged.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass

from rosreconf.analysis.lti import (
    Array,
    feedback,
    is_stable,
    series,
    step_figures,
    step_response,
)
from rosreconf.analysis.numeric import np
from rosreconf.analysis.results import Results
from rosreconf.errors import RosreconfError
from rosreconf.model.dynamics import METRICS, PerformanceRequirements, TransferFunction

SETTLING_BAND = 0.02
"""The settling band, relative to the final value (python-control's default, 2 %)."""

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


def closed_loop(spec: LoopSpec) -> tuple[Array, Array] | None:
    """Return (num, den) of the closed loop from the reference to the plant output.

    The forward path (forward blocks, then the plant) and the feedback path are each one
    transfer function; negative feedback closes the loop (``lti.feedback``). Returns None when
    the loop is ill-posed: proper blocks with direct feed-through can make ``1 + F P H``
    vanish at infinite frequency (an algebraic loop), leaving no proper closed loop to
    simulate. Such a loop is reported unstable.
    """
    num, den = feedback(series((*spec.forward, spec.plant)), series(spec.feedback))
    return (num, den) if len(den) > 0 and len(num) <= len(den) else None


def time_points(spec: LoopSpec) -> Array:
    """Return the evenly spaced instants at which the step response is simulated."""
    return np.linspace(0.0, spec.duration, SAMPLES)


def step_curve(spec: LoopSpec) -> tuple[Array, Array]:
    """Return (time, output) of the loop's response to its reference step (for plots).

    An ill-posed loop has no response; its output is NaN throughout (plots leave it out).
    """
    t = time_points(spec)
    loop = closed_loop(spec)
    if loop is None:
        return t, np.full_like(t, np.nan)
    return t, spec.reference * step_response(*loop, t)


def simulate_loop(spec: LoopSpec) -> LoopResult:
    """Simulate one loop's step response and read its figures.

    Stability comes from the closed-loop poles; the final value from the DC gain (exact for
    a stable loop, whatever the duration); settling time and overshoot as python-control's
    ``step_info`` reads them over the simulated horizon, relative to that final value.
    """
    with np.errstate(all="ignore"):
        loop = closed_loop(spec)
        if loop is not None and not np.all(np.isfinite(loop[1])):
            raise _beyond_floats(spec)
        if loop is None or not is_stable(np.roots(loop[1])):
            return LoopResult(False, None, None, None, None)
        num, den = loop
        gain = float(np.polyval(num, 0.0) / np.polyval(den, 0.0))  # the DC gain, T(0)
        final = spec.reference * gain
        error = abs(1.0 - gain)
        if not math.isfinite(final) or abs(gain) < 1e-12:
            return LoopResult(True, None, error if math.isfinite(error) else None, None, final)
        t = time_points(spec)
        try:
            y = spec.reference * step_response(num, den, t)
        except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
            raise _beyond_floats(spec) from exc
    if not np.all(np.isfinite(y)):
        raise _beyond_floats(spec)
    settling, overshoot = step_figures(t, y, final, SETTLING_BAND)
    return LoopResult(True, settling, error, overshoot, final)


def _beyond_floats(spec: LoopSpec) -> RosreconfError:
    """Say that a stable loop's step response overflowed: its blocks multiply beyond a float.

    Each block passed validation's ranges (``formats.simchecks``), but a loop multiplies its
    blocks' coefficients: three gains of 1e12 make a loop gain of 1e36, whose matrix
    exponential overflows. Reported rather than given a figure that would be wrong.
    """
    blocks = "; ".join(str(b) for b in (*spec.forward, spec.plant, *spec.feedback))
    return RosreconfError(
        f"a control loop cannot be simulated in floating point: its blocks ({blocks}) "
        "multiply to coefficients a float cannot hold apart (keep the product of a loop's "
        "gains, and its fastest and slowest time constants, within the ranges of "
        "docs/simulation.md)"
    )


@functools.cache
def single_threaded_blas() -> None:
    """Make this process's BLAS use one thread (once per process; threadpoolctl).

    A loop's matrices are 5 to 30 states wide. For such sizes a multithreaded BLAS only
    adds synchronisation: on a busy two-core machine a 9x9 matrix exponential took 32 ms
    with OpenBLAS's threads and 0.2 ms with one. Parallelism comes from the worker
    processes instead (``--workers``, ``--cluster``), and every process computes the same
    way (Dask workers run single-threaded BLAS by default too). Usually there is nothing
    left to limit: ``numeric`` loads numpy's OpenBLAS with one thread. This covers the
    rest: numpy imported before rosreconf, a thread count the user chose, a Dask worker.
    tests/test_lti.py checks every loaded BLAS ends at one thread in each case.
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
    results: Results[list[LoopResult]] = Results()
    futures = {results.watch(executor.submit(simulate_chunk, chunk)): chunk for chunk in chunks}
    while results.pending:
        future, simulated = results.next()
        chunk = futures[future]
        cache.update(zip(chunk, simulated, strict=True))
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
