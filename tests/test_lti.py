"""rosreconf's loop arithmetic against python-control and scipy, step by step.

``rosreconf.analysis.lti`` repeats what python-control computes (so that ``simulate`` need not
import it); here each step is held to the real python-control or scipy: the Pade approximant,
the canonical realisation, ``step_info``'s settling time and overshoot, and the step
response of high-order loops against python-control's block-wise state-space interconnection,
which never forms the loop's badly scaled characteristic polynomial.
"""

from __future__ import annotations

import math

import control
import numpy as np
import pytest
import scipy.signal
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.analysis import lti
from rosreconf.analysis.performance import SAMPLES, SETTLING_BAND, LoopSpec, closed_loop
from rosreconf.model.dynamics import StateSpace, TransferFunction

PROPS = settings(max_examples=50, deadline=None, derandomize=True)


@pytest.mark.parametrize("delay", [0.0, 0.003, 0.05, 0.12, 1.0, 7.5])
@pytest.mark.parametrize("order", [1, 3, 5])
def test_pade_is_python_controls(delay: float, order: int) -> None:
    num, den = lti.pade(delay, order)
    ref_num, ref_den = control.pade(delay, order)
    assert np.array_equal(num, np.asarray(ref_num, dtype=float))
    assert np.array_equal(den, np.asarray(ref_den, dtype=float))


coefficient = st.floats(-5.0, 5.0).map(lambda x: round(x, 3))


@st.composite
def proper(draw: st.DrawFn) -> tuple[list[float], list[float]]:
    order = draw(st.integers(0, 6))
    den = [draw(st.floats(0.1, 5.0)), *draw(st.lists(coefficient, min_size=order, max_size=order))]
    num = draw(st.lists(coefficient, min_size=1, max_size=order + 1))
    return num, den


@pytest.mark.filterwarnings("ignore:Badly conditioned filter coefficients")  # scipy, on 0 s^n
@PROPS
@given(model=proper())
def test_realisation_is_scipys_tf2ss(model: tuple[list[float], list[float]]) -> None:
    num, den = model
    a, b, c, d = lti.realise(np.array(num), np.array(den))
    ref_a, ref_b, ref_c, ref_d = scipy.signal.tf2ss(num, den)
    if len(den) == 1:  # a static gain: scipy keeps one dummy state, rosreconf none
        assert a.shape == (0, 0) and d == pytest.approx(float(ref_d[0, 0]))
        return
    assert np.allclose(a, ref_a) and np.allclose(b, ref_b[:, 0])
    assert np.allclose(c, ref_c[0]) and d == pytest.approx(float(ref_d[0, 0]))


@st.composite
def curves(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, float]:
    """A damped second-order response (some overshoot, some not settled) and its final value."""
    zeta = draw(st.floats(0.05, 2.0))
    wn = draw(st.floats(0.2, 5.0))
    final = draw(st.sampled_from([1.0, -2.0, 0.5]))
    t = np.linspace(0.0, draw(st.floats(2.0, 20.0)), SAMPLES)
    _, y = scipy.signal.step(([wn * wn], [1.0, 2 * zeta * wn, wn * wn]), T=t)
    return t, final * y, final


@PROPS
@given(curve=curves())
def test_step_figures_are_python_controls_step_info(
    curve: tuple[np.ndarray, np.ndarray, float],
) -> None:
    t, y, final = curve
    settling, overshoot = lti.step_figures(t, y, final, SETTLING_BAND)
    if not np.any(np.sign(final) * (y - 0.9 * final) >= 0):
        assert (settling, overshoot) == (None, 0.0)  # step_info would fail: no rise time
        return
    info = control.step_info(y, t, yfinal=final, SettlingTimeThreshold=SETTLING_BAND)
    expected = info["SettlingTime"]
    assert settling == (None if math.isnan(expected) else expected)
    assert overshoot == info["Overshoot"]


def block(tf: TransferFunction) -> control.StateSpace:
    """Return one block as python-control's state space, dead time by its own Pade."""
    sys = control.ss(control.tf(list(tf.num), list(tf.den)))
    if tf.delay > 0:
        sys = sys * control.ss(control.tf(*control.pade(tf.delay, lti.PADE_ORDER)))
    return sys


def interconnected(spec: LoopSpec) -> control.StateSpace:
    """Return the closed loop built by python-control from each block's own realisation."""
    forward = block(spec.plant)
    for tf in reversed(spec.forward):
        forward = forward * block(tf)
    back = control.ss([], [], [], [[1.0]])
    for tf in spec.feedback:
        back = block(tf) * back
    return control.feedback(forward, back)


def slow(k: float, tau: float, delay: float = 0.0) -> TransferFunction:
    return TransferFunction((k,), (tau, 1.0), delay)


# Loops like the generated benchmark's and the arm's: a PI controller, lags, a plant, and
# sensors with dead time. Their characteristic polynomials reach order 15 with coefficients
# from 1e-5 to 1e32, where an unbalanced exponential of the companion matrix erred by a
# quarter of the output (a settling time of 0.12 s instead of 1.76 s).
HIGH_ORDER = [
    LoopSpec(
        (TransferFunction((2.286, 2.996), (1.0, 0.0)), slow(1.0, 0.149)),
        slow(1.0, 0.5),
        (slow(1.0, 0.015, 0.008), slow(1.0, 0.013, 0.003)),
    ),
    LoopSpec(
        (TransferFunction((0.8, 1.2), (1.0, 0.0)), slow(1.0, 0.05, 0.02)),
        TransferFunction((1.0,), (0.4, 1.0, 0.0)),
        (slow(1.0, 0.05, 0.12), slow(1.0, 0.02, 0.05)),
    ),
    LoopSpec((slow(3.0, 0.2), slow(1.0, 0.1)), slow(1.0, 1.0), (slow(1.0, 0.01, 0.01),)),
]


@pytest.mark.parametrize("spec", HIGH_ORDER)
def test_high_order_step_response_is_the_interconnected_loops(spec: LoopSpec) -> None:
    loop = closed_loop(spec)
    assert loop is not None
    num, den = loop
    assert len(den) > 8  # high order: the case that needed balancing
    t = np.linspace(0.0, spec.duration, SAMPLES)
    ours = lti.step_response(num, den, t)
    theirs = control.step_response(interconnected(spec), t).outputs
    assert np.max(np.abs(ours - theirs)) < 1e-9
    poles = np.sort_complex(np.roots(den))
    reference = np.sort_complex(interconnected(spec).poles())
    assert np.allclose(poles, reference, rtol=1e-6)


def test_unbalanced_companion_exponential_errs_on_such_loops() -> None:
    """The reason for balancing: without it the first loop's curve is wrong or overflows."""
    import scipy.linalg

    loop = closed_loop(HIGH_ORDER[0])
    assert loop is not None
    a, b, c, d = lti.realise(*loop)
    n = len(b)
    t = np.linspace(0.0, 10.0, SAMPLES)
    augmented = np.zeros((n + 1, n + 1))
    augmented[:n, :n], augmented[:n, n] = a, b
    held = scipy.linalg.expm(augmented * (t[1] - t[0]))
    x, y = np.zeros(n), []
    with np.errstate(over="ignore", invalid="ignore"):  # it may even overflow
        for _ in t:
            y.append(c @ x + d)
            x = held[:n, :n] @ x + held[:n, n]
    theirs = control.step_response(interconnected(HIGH_ORDER[0]), t).outputs
    assert not np.max(np.abs(np.array(y) - theirs)) < 1e-3  # wrong by more, or NaN


@st.composite
def state_spaces(draw: st.DrawFn) -> StateSpace:
    n = draw(st.integers(1, 4))
    entry = st.floats(-3.0, 3.0).map(lambda x: round(x, 2))
    a = tuple(tuple(draw(entry) for _ in range(n)) for _ in range(n))
    b = tuple((draw(entry),) for _ in range(n))
    c = (tuple(draw(entry) for _ in range(n)),)
    d = ((draw(entry),),)
    return StateSpace(a, b, c, d, draw(st.sampled_from([0.0, 0.1])))


@PROPS
@given(model=state_spaces())
def test_state_space_becomes_python_controls_ss2tf(model: StateSpace) -> None:
    """The same transfer function as control.ss2tf: equal frequency responses, same delay."""
    tf = lti.ss2tf(model)
    assert tf.delay == model.delay
    theirs = control.ss2tf(
        np.array(model.a), np.array(model.b), np.array(model.c), np.array(model.d)
    )
    assert len(tf.den) == len(model.a) + 1 and tf.den[0] == 1.0
    for s in (0.3j, 1.0 + 2.0j, 7.0j, -0.5 + 0.1j):
        ours = np.polyval(tf.num, s) / np.polyval(tf.den, s)
        ref = complex(theirs(s))
        assert ours == pytest.approx(ref, rel=1e-6, abs=1e-6)
    assert lti.transfer_function(model) == tf
    plain = TransferFunction((1.0,), (1.0, 1.0))
    assert lti.transfer_function(plain) is plain
