"""The M-solution's loop simulation against closed forms, Routh-Hurwitz and scipy."""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor

import control
import numpy as np
import pytest
import scipy.signal
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rosreconf.analysis.performance import (
    SAMPLES,
    SETTLING_BAND,
    LoopResult,
    LoopSpec,
    dominates,
    meets,
    pareto_front,
    simulate_all,
    simulate_loop,
    step_curve,
    worst,
)
from rosreconf.model.dynamics import PerformanceRequirements, TransferFunction

PROPS = settings(max_examples=50, deadline=None, derandomize=True)


def gain(k: float) -> TransferFunction:
    return TransferFunction((k,), (1.0,))


@pytest.mark.parametrize(
    ("k", "tau", "kp"), [(2.0, 0.5, 3.0), (1.0, 2.0, 0.5), (5.0, 0.1, 10.0), (0.3, 4.0, 1.0)]
)
def test_first_order_loop_meets_its_closed_forms(k: float, tau: float, kp: float) -> None:
    """K/(tau s + 1) under gain Kp: e_ss = 1/(1 + K Kp), t_s = tau ln(50)/(1 + K Kp)."""
    settling = tau * math.log(1 / SETTLING_BAND) / (1 + k * kp)
    duration = 5 * settling
    spec = LoopSpec((gain(kp),), TransferFunction((k,), (tau, 1.0)), (), 2.0, duration)
    result = simulate_loop(spec)
    assert result.stable
    assert result.steady_state_error == pytest.approx(1 / (1 + k * kp), rel=1e-9)
    assert result.final_value == pytest.approx(2.0 * k * kp / (1 + k * kp), rel=1e-9)
    assert result.overshoot == pytest.approx(0.0, abs=1e-6)
    # step_info reports the first sample after the last one outside the band.
    step = duration / (SAMPLES - 1)
    assert result.settling_time is not None
    assert settling - 1e-9 <= result.settling_time <= settling + step + 1e-9


@pytest.mark.parametrize("k", [0.5, 3.0, 5.9, 6.1, 8.0, 30.0])
def test_third_order_loop_with_integrator_goes_unstable_past_routh_hurwitz_gain(k: float) -> None:
    """K/(s (s + 1)(s + 2)): s^3 + 3 s^2 + 2 s + K is Hurwitz exactly when 0 < K < 3 * 2."""
    spec = LoopSpec((gain(k),), TransferFunction((1.0,), (1.0, 3.0, 2.0, 0.0)), (), 1.0, 200.0)
    result = simulate_loop(spec)
    assert result.stable is (k < 6.0)
    if result.stable:
        # The integrator removes the steady-state error of a step.
        assert result.steady_state_error == pytest.approx(0.0, abs=1e-9)
    else:
        assert result == LoopResult(False, None, None, None, None)
        assert not meets(PerformanceRequirements(), result)


def routh_stable(poly: np.ndarray) -> bool:
    """Decide Hurwitz stability from the Routh array's first column (no roots computed)."""
    p = np.trim_zeros(np.asarray(poly, dtype=float), "f")
    n = len(p) - 1
    if n == 0:
        return True
    rows = [p[0::2].copy(), p[1::2].copy()]
    width = len(rows[0])
    rows = [np.pad(r, (0, width - len(r))) for r in rows]
    for _ in range(n - 1):
        a, b = rows[-2], rows[-1]
        if b[0] == 0:
            return False
        nxt = np.zeros(width)
        for j in range(width - 1):
            nxt[j] = (b[0] * a[j + 1] - a[0] * b[j + 1]) / b[0]
        rows.append(nxt)
    first = [r[0] for r in rows]
    return all(x > 0 for x in first) or all(x < 0 for x in first)


coefficient = st.floats(0.1, 5.0).map(lambda x: round(x, 3))


@st.composite
def blocks(draw: st.DrawFn, max_order: int = 2) -> TransferFunction:
    order = draw(st.integers(0, max_order))
    den = (1.0, *draw(st.lists(coefficient, min_size=order, max_size=order)))
    num = tuple(draw(st.lists(coefficient, min_size=1, max_size=order + 1)))
    sign = draw(st.sampled_from([1.0, 1.0, -1.0]))
    return TransferFunction(tuple(sign * x for x in num), den)


@st.composite
def loops(draw: st.DrawFn) -> LoopSpec:
    forward = tuple(draw(st.lists(blocks(), min_size=1, max_size=2)))
    plant = draw(blocks(max_order=3))
    feedback = tuple(draw(st.lists(blocks(max_order=1), max_size=1)))
    return LoopSpec(forward, plant, feedback, draw(st.sampled_from([1.0, 0.5, 3.0])), 30.0)


def polynomial_closed_loop(spec: LoopSpec) -> tuple[np.ndarray, np.ndarray]:
    """Return num/den of F P / (1 + F P H) by plain polynomial arithmetic (numpy)."""
    nf, df = np.array([1.0]), np.array([1.0])
    for b in (*spec.forward, spec.plant):
        nf, df = np.polymul(nf, b.num), np.polymul(df, b.den)
    nh, dh = np.array([1.0]), np.array([1.0])
    for b in spec.feedback:
        nh, dh = np.polymul(nh, b.num), np.polymul(dh, b.den)
    return np.polymul(nf, dh), np.polyadd(np.polymul(df, dh), np.polymul(nf, nh))


@PROPS
@given(spec=loops())
def test_random_loops_agree_with_routh_hurwitz_and_scipy(spec: LoopSpec) -> None:
    num, den = polynomial_closed_loop(spec)
    den = np.trim_zeros(den, "f")
    assume(len(den) > 0 and len(np.trim_zeros(num, "f")) <= len(den))  # well-posed
    # Stay clear of the stability boundary, where no two methods need to agree.
    assume(np.min(np.abs(np.real(np.roots(den))), initial=1.0) > 1e-3)
    result = simulate_loop(spec)
    assert result.stable is routh_stable(den)
    if not result.stable:
        return
    dc = np.polyval(num, 0.0) / np.polyval(den, 0.0)
    assume(abs(dc) > 1e-6)
    assert result.final_value == pytest.approx(spec.reference * dc, rel=1e-6, abs=1e-9)
    assert result.steady_state_error == pytest.approx(abs(1 - dc), rel=1e-6, abs=1e-9)
    t, y = step_curve(spec)
    _, y_scipy = scipy.signal.step((num, den), T=t)
    assert np.allclose(y, spec.reference * y_scipy, atol=1e-6 * max(1.0, np.max(np.abs(y))))
    final = spec.reference * dc
    y_ref = spec.reference * y_scipy
    if not np.any(np.sign(final) * (y_ref - 0.9 * final) >= 0):
        # Never within 10 % of the final value: neither settled nor overshot.
        assert (result.settling_time, result.overshoot) == (None, 0.0)
        return
    info = control.step_info(y_ref, t, yfinal=final)
    assert result.overshoot == pytest.approx(info["Overshoot"], rel=1e-3, abs=1e-3)
    expected = info["SettlingTime"]
    if math.isnan(expected):
        assert result.settling_time is None
    else:
        assert result.settling_time == pytest.approx(expected, abs=2 * spec.duration / SAMPLES)


@PROPS
@given(spec=loops())
def test_random_loops_agree_with_python_control_directly(spec: LoopSpec) -> None:
    blocks_ = [control.tf(list(b.num), list(b.den)) for b in spec.forward]
    forward = blocks_[0]
    for b in blocks_[1:]:
        forward = forward * b
    forward = forward * control.tf(list(spec.plant.num), list(spec.plant.den))
    feedback = control.tf([1.0], [1.0])
    for b in spec.feedback:
        feedback = feedback * control.tf(list(b.num), list(b.den))
    num, den = polynomial_closed_loop(spec)
    assume(len(np.trim_zeros(num, "f")) <= len(np.trim_zeros(den, "f")) > 0)  # well-posed
    loop = control.feedback(forward, feedback)
    poles = loop.poles()
    assume(np.min(np.abs(np.real(poles)), initial=1.0) > 1e-3)
    result = simulate_loop(spec)
    assert result.stable is bool(np.all(np.real(poles) < 0))
    t = np.linspace(0, spec.duration, SAMPLES)
    if result.stable and abs(loop.dcgain()) > 1e-6:
        y = control.step_response(loop, t).outputs
        assume(np.any(np.sign(loop.dcgain()) * (y - 0.9 * loop.dcgain()) >= 0))
        info = control.step_info(loop, T=t)
        assert result.steady_state_error == pytest.approx(abs(1 - info["SteadyStateValue"]))
        assert result.overshoot == pytest.approx(info["Overshoot"], rel=1e-6, abs=1e-6)


def exact_delayed_first_order(
    k: float, tau: float, kp: float, delay: float, t: np.ndarray
) -> np.ndarray:
    """Simulate K e^(-delay s)/(tau s + 1) under gain Kp exactly by the method of steps.

    With a step h that divides the delay, the delayed input is a known sample; between
    samples it is held (zero-order hold), for which the first-order update is exact. The
    only error is the hold's, O(h).
    """
    h = 1e-4
    n = round(t[-1] / h)
    m = round(delay / h)
    a = math.exp(-h / tau)
    y = np.zeros(n + 1)
    u = np.zeros(n + 1)
    for i in range(n):
        u[i] = kp * (1.0 - y[i])
        y[i + 1] = a * y[i] + (1 - a) * k * (u[i - m] if i >= m else 0.0)
    return np.interp(t, np.arange(n + 1) * h, y)


@pytest.mark.parametrize("delay", [0.05, 0.2])
def test_pade_delay_stays_close_to_the_exact_delayed_loop(delay: float) -> None:
    """The Pade stand-in for dead time errs by under 2 % of the final value (docs say so)."""
    k, tau, kp = 1.0, 1.0, 2.0
    spec = LoopSpec((gain(kp),), TransferFunction((k,), (tau, 1.0), delay), (), 1.0, 10.0)
    t, y = step_curve(spec)
    exact = exact_delayed_first_order(k, tau, kp, delay, t)
    final = k * kp / (1 + k * kp)
    assert np.max(np.abs(y - exact)) < 0.02 * final
    result = simulate_loop(spec)
    info = control.step_info(exact, t, yfinal=final)
    assert result.settling_time == pytest.approx(info["SettlingTime"], abs=2 * 10.0 / SAMPLES)
    assert result.overshoot == pytest.approx(info["Overshoot"], abs=0.05)


def test_equal_loops_are_simulated_once_and_a_pool_gives_the_same_answers() -> None:
    specs = [
        LoopSpec((gain(kp),), TransferFunction((1.0,), (tau, 1.0)), (), 1.0, 5.0)
        for kp in (1.0, 2.0, 4.0)
        for tau in (0.5, 1.0)
    ]
    simulated: list[int] = []
    local = simulate_all(specs * 3, progress=simulated.append)
    assert sum(simulated) == len(specs) == len(local)
    again: list[int] = []
    simulate_all(specs, cache=local, progress=again.append)
    assert again == []
    with ProcessPoolExecutor(max_workers=2) as pool:
        pooled = simulate_all(specs, executor=pool, chunk_size=2)
    assert pooled == local


def test_an_ill_posed_loop_is_reported_unstable() -> None:
    """-s/(s + 1) in unity feedback: 1 + L(s) -> 0 as s -> inf (an algebraic loop)."""
    spec = LoopSpec((gain(-1.0),), TransferFunction((1.0, 0.0), (1.0, 1.0)), (), 1.0, 1.0)
    assert not simulate_loop(spec).stable
    assert np.isnan(step_curve(spec)[1]).all()


def test_requirements_and_worst_figures() -> None:
    fast = LoopResult(True, 1.0, 0.01, 5.0, 0.99)
    slow = LoopResult(True, 3.0, 0.0, 0.0, 1.0)
    unsettled = LoopResult(True, None, 0.0, 40.0, 1.0)
    unstable = LoopResult(False, None, None, None, None)
    req = PerformanceRequirements(settling_time=2.0, overshoot=10.0)
    assert meets(req, fast)
    assert not meets(req, slow)
    assert not meets(req, unsettled)
    assert not meets(req, unstable)
    assert worst([fast, slow]) == {
        "settling_time": 3.0,
        "steady_state_error": 0.01,
        "overshoot": 5.0,
    }
    assert worst([fast, unstable])["steady_state_error"] == math.inf


figures = st.lists(st.tuples(*[st.integers(0, 4).map(float)] * 3), max_size=25)


@PROPS
@given(points=figures)
def test_pareto_front_is_what_brute_force_says(points: list[tuple[float, ...]]) -> None:
    expected = [
        i
        for i, p in enumerate(points)
        if not any(dominates(q, p) for j, q in enumerate(points) if j != i)
    ]
    assert pareto_front(points) == expected
    for i in expected:
        for j in range(len(points)):
            assert not (
                all(a <= b for a, b in zip(points[j], points[i], strict=True))
                and points[j] != points[i]
            )
