"""rosreconf's loop arithmetic against python-control and scipy, step by step.

``rosreconf.analysis.lti`` repeats what python-control computes (so that ``simulate`` need not
import it); here each step is held to the real python-control or scipy: the Pade approximant,
the canonical realisation, ``step_info``'s settling time and overshoot, and the step
response of high-order loops against python-control's block-wise state-space interconnection,
which never forms the loop's badly scaled characteristic polynomial.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from typing import Any

import control
import numpy as np
import pytest
import scipy.linalg
import scipy.signal
from hypothesis import given, settings
from hypothesis import strategies as st

from rosreconf.analysis import lti, matfuncs
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


# --- matfuncs: the matrix exponential and the balancing, held to scipy.linalg -------------
#
# ``step_response`` discretises every loop with ``matfuncs.expm`` of its balanced augmented
# matrix; scipy.linalg is not imported at run time (issue 12). scipy stays the reference.
# Tolerances: the two compute the same Pade approximant with the same degree and squarings,
# in a different rounding order (numpy's solve for scipy's transposed LAPACK solve), so
# they agree to a few dozen units in the last place times the norm that the squarings
# amplify. Measured: 2e-16 relative for norms <= 1, 5e-14 x the 1-norm up to 1000, 2e-15 on
# the bundled loops; each bound below is 10 to 20 times that.

EPS = float(np.finfo(float).eps)


def expm_error(a: np.ndarray) -> float:
    """Return max |ours - scipy's| / max |scipy's| for ``expm(a)``."""
    ours, theirs = matfuncs.expm(a), scipy.linalg.expm(a)
    assert ours.shape == theirs.shape and np.all(np.isfinite(ours))
    return float(np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs)))


def norm1(a: np.ndarray) -> float:
    return float(np.abs(a).sum(axis=0).max())


def random_matrices(seed: int, low: float, high: float) -> list[np.ndarray]:
    """Return random n x n matrices (n = 2..24) with 1-norms drawn from [low, high]."""
    rng = np.random.default_rng(seed)
    out = []
    for n in range(2, 25):
        for _ in range(6):
            a = rng.standard_normal((n, n))
            out.append(a * rng.uniform(low, high) / norm1(a))
    return out


def test_expm_of_small_norm_matrices_is_scipys_to_a_few_ulps() -> None:
    for a in random_matrices(1, 1e-6, 1.0):
        assert expm_error(a) < 4e-15, a


@pytest.mark.parametrize(("low", "high"), [(1.0, 30.0), (30.0, 1000.0)])
def test_expm_of_larger_norms_is_scipys_to_rounding_times_the_norm(low: float, high: float) -> None:
    for a in random_matrices(2, low, high):
        assert expm_error(a) < 5e-13 * norm1(a), a


def bundled_loop_matrices() -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Return (companion A, B, sample time) of every distinct loop of the bundled example."""
    from rosreconf.analysis.performance import time_points
    from rosreconf.analysis.simulate import Cache, simulate_schema
    from rosreconf.formats.loader import load_bundled

    loaded = load_bundled()
    cache: Cache = {}
    for schema in loaded.schemas:
        if schema.simulation is not None:
            simulate_schema(loaded.library, schema, cache=cache)
    out = []
    for spec in cache:
        loop = closed_loop(spec)
        if loop is None:
            continue
        a, b, _, _ = lti.realise(*loop)
        t = time_points(spec)
        if len(b):
            out.append((a, b, float(t[1] - t[0])))
    return out


def augmented(a: np.ndarray, b: np.ndarray, dt: float) -> np.ndarray:
    n = len(b)
    out = np.zeros((n + 1, n + 1))
    out[:n, :n], out[:n, n] = a, b
    return out * dt


def test_expm_and_balance_on_the_bundled_loops_are_scipys() -> None:
    loops = bundled_loop_matrices()
    assert len(loops) >= 10 and max(len(b) for _, b, _ in loops) >= 8
    for a, b, dt in loops:
        scale = matfuncs.balance(a)
        balanced, (ref_scale, _) = scipy.linalg.matrix_balance(a, permute=False, separate=True)
        assert np.array_equal(scale, ref_scale)
        assert np.array_equal(a / scale[:, None] * scale[None, :], balanced)
        assert expm_error(augmented(balanced, b / scale, dt)) < 2e-14


def test_expm_of_an_unbalanced_companion_is_no_worse_than_scipys() -> None:
    """Badly scaled input: both err (hence the balancing), ours by no more than scipy's.

    The truth is the balanced exponential scaled back: balancing is a similarity by powers
    of two, so ``D e^(D^-1 A D) D^-1`` is exact to the balanced exponential's few ulps.
    """
    worse = 0
    for a, b, dt in bundled_loop_matrices():
        scale = matfuncs.balance(a)
        full = np.concatenate([scale, [scale[-1]]])  # the input column is not rescaled
        held = augmented(a, b, dt)
        balanced = held / full[:, None] * full[None, :]
        truth = matfuncs.expm(balanced) * full[:, None] / full[None, :]
        with np.errstate(over="ignore", invalid="ignore"):
            ours = np.max(np.abs(matfuncs.expm(held) - truth)) / np.max(np.abs(truth))
            theirs = np.max(np.abs(scipy.linalg.expm(held) - truth)) / np.max(np.abs(truth))
        if not theirs < 1e-12:  # a loop whose scaling matters
            worse += 1
            assert ours < 10 * theirs or not np.isfinite(theirs)
    assert worse >= 1  # the case balancing is for does occur in the example


def test_expm_of_ill_scaled_matrices_matches_the_exact_similarity() -> None:
    """``D A D^-1`` with D powers of two from 2^-26 to 2^26: the truth is ``D e^A D^-1``."""
    rng = np.random.default_rng(3)
    for n in (2, 5, 9, 16):
        for norm in (0.5, 5.0, 50.0):
            a = rng.standard_normal((n, n))
            a *= norm / norm1(a)
            d = 2.0 ** rng.integers(-26, 27, n).astype(float)
            scaled = a * d[:, None] / d[None, :]
            truth = scipy.linalg.expm(a) * d[:, None] / d[None, :]
            ours = matfuncs.expm(scaled) / (d[:, None] / d[None, :])
            theirs = scipy.linalg.expm(scaled) / (d[:, None] / d[None, :])
            base = np.max(np.abs(scipy.linalg.expm(a)))
            ref = truth / (d[:, None] / d[None, :])
            assert np.max(np.abs(ours - ref)) / base <= max(
                10 * np.max(np.abs(theirs - ref)) / base, 1e-13 * max(1.0, norm)
            )


def test_expm_of_stiff_and_large_norm_matrices() -> None:
    # A stiff loop: poles at -1, -1e3 and -1e5 in companion form, sampled at 10 ms.
    a, _, _, _ = lti.realise(np.array([1.0]), np.poly([-1.0, -1e3, -1e5]))
    scale = matfuncs.balance(a)
    stiff = a / scale[:, None] * scale[None, :] * 0.01
    assert expm_error(stiff) < 5e-13 * norm1(stiff)
    # A fast rotation: e^A is a rotation by 1000 rad, entries of norm 1, norm(A) = 1000.
    rotation = np.array([[0.0, 1000.0], [-1000.0, 0.0]])
    assert expm_error(rotation) < 5e-13 * 1000
    assert np.allclose(
        matfuncs.expm(rotation),
        [[np.cos(1e3), np.sin(1e3)], [-np.sin(1e3), np.cos(1e3)]],
        atol=1e-11,
    )
    # A strongly damped stable matrix of norm 2000: a tiny, nonzero exponential.
    rng = np.random.default_rng(4)
    damped = -2000.0 * np.eye(6) + 10.0 * rng.standard_normal((6, 6))
    ours, theirs = matfuncs.expm(damped * 0.3), scipy.linalg.expm(damped * 0.3)
    assert np.max(np.abs(ours - theirs)) <= 5e-13 * norm1(damped) * np.max(np.abs(theirs))


def test_expm_special_shapes() -> None:
    zero = np.zeros((4, 4))
    assert np.array_equal(matfuncs.expm(zero), np.eye(4))
    one = np.array([[-2.5]])
    assert np.array_equal(matfuncs.expm(one), np.exp(one))
    assert np.array_equal(matfuncs.expm(one), scipy.linalg.expm(one))
    diagonal = np.diag([-3.0, 0.0, 1e-9, 4.0])
    assert np.array_equal(matfuncs.expm(diagonal), scipy.linalg.expm(diagonal))
    # Nilpotent: the series stops, e^N = I + N + N^2/2 + ... + N^5/5!.
    rng = np.random.default_rng(5)
    nilpotent = np.triu(rng.standard_normal((6, 6)) * 3.0, k=1)
    series, term = np.eye(6), np.eye(6)
    for k in range(1, 6):
        term = term @ nilpotent / k
        series = series + term
    assert np.max(np.abs(matfuncs.expm(nilpotent) - series)) < 1e-13 * np.max(np.abs(series))
    assert expm_error(nilpotent) < 1e-13


@pytest.mark.parametrize("lower", [False, True])
def test_expm_of_triangular_matrices_recomputes_the_diagonal_as_scipy(lower: bool) -> None:
    """With squarings, a triangular input takes Al-Mohy and Higham's Code Fragment 2.1."""
    rng = np.random.default_rng(6)
    squared = 0
    for n in (2, 3, 7, 12):
        for spread in (1.0, 40.0, 400.0):
            a = np.triu(rng.standard_normal((n, n)) * spread / 4)
            np.fill_diagonal(a, -rng.uniform(0.0, spread, n))
            a = a.T if lower else a
            ours = matfuncs.expm(a)
            assert np.array_equal(ours, np.tril(ours) if lower else np.triu(ours))
            if matfuncs._pade_structure(a)[1] > 0:  # squared: the diagonal is exact
                squared += 1
                assert np.array_equal(np.diag(ours), np.exp(np.diag(a)))
            assert expm_error(a) < 5e-13 * max(1.0, norm1(a))
    assert squared >= 6


def balancing_cases() -> list[np.ndarray]:
    rng = np.random.default_rng(7)
    cases = [np.zeros((3, 3)), np.array([[5.0]]), np.array([[1.0, 1e6], [1e-6, 1.0]])]
    for n in range(2, 16):
        a = rng.standard_normal((n, n))
        cases.append(a)
        d = 10.0 ** rng.uniform(-12, 12, n)
        cases.append(a * d[:, None] / d[None, :])
        holey = a.copy()
        holey[rng.integers(n), :] = 0.0  # a zero row: that index is left alone
        holey[:, rng.integers(n)] = 0.0
        cases.append(holey)
        coefficients = 10.0 ** rng.uniform(-3, 25, n)
        companion, _, _, _ = lti.realise(np.array([1.0]), np.concatenate([[1.0], coefficients]))
        cases.append(companion)
    return cases


def test_balance_is_lapacks_gebal_without_permutation_bit_for_bit() -> None:
    for a in balancing_cases():
        scale = matfuncs.balance(a)
        balanced, (ref_scale, _) = scipy.linalg.matrix_balance(a, permute=False, separate=True)
        assert np.array_equal(scale, ref_scale), a
        assert np.all(np.log2(scale) == np.round(np.log2(scale)))  # powers of two
        assert np.array_equal(a / scale[:, None] * scale[None, :], balanced)


def test_balance_refuses_nan_as_scipy_does() -> None:
    bad = np.array([[1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(ValueError, match="NaN or infinite"):
        matfuncs.balance(bad)
    with pytest.raises(ValueError):
        scipy.linalg.matrix_balance(bad, permute=False, separate=True)


THREADS_PROBE = """
import json, os, sys
if sys.argv[1] == "numpy-first":
    import numpy
from threadpoolctl import threadpool_info
from rosreconf.analysis.performance import LoopSpec, simulate_chunk
from rosreconf.model.dynamics import TransferFunction
loaded = [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]
spec = LoopSpec((TransferFunction((2.0,), (0.5, 1.0)),), TransferFunction((1.0,), (1.0, 1.0)), ())
simulate_chunk([spec])
print(json.dumps({
    "loaded": loaded,
    "after": [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"],
    "threads": len(os.listdir("/proc/self/task")),
    "variable": os.environ.get("OPENBLAS_NUM_THREADS"),
    "scipy": "scipy" in sys.modules,
}))
"""


def blas_probe(order: str, threads: str | None) -> dict[str, Any]:
    """Run THREADS_PROBE in a fresh interpreter with ``OPENBLAS_NUM_THREADS`` as given."""
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    if threads is not None:
        env["OPENBLAS_NUM_THREADS"] = threads
    done = subprocess.run(
        [sys.executable, "-c", THREADS_PROBE, order],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
        env=env,
    )
    report: dict[str, Any] = json.loads(done.stdout)
    assert report["loaded"], "no BLAS loaded: the probe would prove nothing"
    assert not report["scipy"]
    assert report["after"] == [1] * len(report["after"])  # simulating: one thread, always
    return report


def test_the_simulation_loads_numpys_openblas_on_one_thread() -> None:
    """Imported first, the simulation starts OpenBLAS with no worker thread at all.

    That saves the threads' start-up (30 to 60 ms of CPU per process); the variable that
    does it is gone again, so planners and ROS nodes started later do not inherit it.
    """
    report = blas_probe("rosreconf-first", None)
    assert report["loaded"] == [1]
    assert report["threads"] == 1  # the interpreter's own thread only
    assert report["variable"] is None


def test_numpy_loaded_first_or_a_chosen_count_is_still_limited_while_simulating() -> None:
    """numpy imported before rosreconf, or the user's own thread count: threadpoolctl limits.

    ``blas_probe`` checks one thread while simulating; here OpenBLAS started with more
    (OpenBLAS caps a count at the number of cores).
    """
    cores = os.cpu_count() or 1
    first = blas_probe("numpy-first", None)
    assert first["loaded"] == [cores]  # the default: one thread per core
    chosen = blas_probe("rosreconf-first", "2")
    assert chosen["loaded"] == [min(2, cores)] and chosen["variable"] == "2"  # it stands
