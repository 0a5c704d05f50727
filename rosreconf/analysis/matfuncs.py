"""Exponentiate and balance small real matrices on numpy alone, as scipy.linalg does.

Discretising a loop (``lti.step_response``) needs two things from linear algebra: a
diagonal balancing of its companion matrix and the matrix exponential of the augmented
system. scipy.linalg offers both, but importing it costs about 0.3 s of CPU per process:
``plan --fail NSM3`` on the bundled example took 27 % more CPU with it and ``simulate`` 87 %
more (once per worker), to compute a handful of 5x5 to 30x30 matrices, and it computes the
same figures (docs/PERFORMANCE.md, "What stayed and why"). So both are written
out here on numpy, step for step as scipy 1.17 computes them, and tests/test_lti.py holds
them to ``scipy.linalg.expm`` and ``scipy.linalg.matrix_balance`` on random,
ill-conditioned, stiff, triangular, nilpotent and large-norm matrices.

What is reproduced exactly: the balancing (bit for bit: it only compares norms and
multiplies by powers of two), and the exponential's choice of Pade degree and number of
squarings (the same 1-norms of the same powers, formed in the same order). What is not:
scipy solves the final linear system with LAPACK on the transposed layout, numpy on the
matrix itself, so the exponentials agree to rounding (a few units in the last place, times
the norm the squarings amplify), not bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

from rosreconf.analysis.numeric import np

Array = np.ndarray[Any, Any]

THETA = (1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1, 2.097847961257068, 4.25)
"""Largest norms for which the degree 3, 5, 7, 9, 13 Pade approximants are accurate enough
(Al-Mohy and Higham 2009, Table 3.1; 4.25 for degree 13 as in their Algorithm 5.1)."""

BACKWARD = (
    1.1191048088221578e-11,
    1.1167770708198077e-06,
    4.9826124310493469e-01,
    6.5662862500000000e05,
    1.2573361865339437e19,
)
"""Coefficients of the backward-error bounds of degrees 3, 5, 7, 9, 13 (``c_m`` of
Al-Mohy and Higham 2009, eq. 5.1, divided by the unit roundoff), as scipy uses them."""

PADE = {
    3: (120.0, 60.0, 12.0, 1.0),
    5: (30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0),
    7: (17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0),
    9: (
        17643225600.0,
        8821612800.0,
        2075673600.0,
        302702400.0,
        30270240.0,
        2162160.0,
        110880.0,
        3960.0,
        90.0,
        1.0,
    ),
    13: (
        64764752532480000.0,
        32382376266240000.0,
        7771770303897600.0,
        1187353796428800.0,
        129060195264000.0,
        10559470521600.0,
        670442572800.0,
        33522128640.0,
        1323241920.0,
        40840800.0,
        960960.0,
        16380.0,
        182.0,
        1.0,
    ),
}
"""Coefficients ``b_0 .. b_m`` of the diagonal Pade approximants of ``e^x`` (Higham 2005)."""


def _norm(x: Array) -> float:
    """Return the 1-norm of ``x``: its largest absolute column sum."""
    return float(np.abs(x).sum(axis=0).max())


def _lm(spun: float, norm: float, coeff: float, degree: int) -> int:
    """Return the extra squarings the backward-error bound asks for (never negative)."""
    if spun == 0.0:
        return 0
    return max(0, math.ceil(math.log2(spun / norm / coeff) / (2 * degree)))


def _pade_structure(a: Array) -> tuple[int, int, list[Array]]:
    """Choose the Pade degree m and squarings s for ``a``; return them with the powers.

    Al-Mohy and Higham 2009, Algorithm 5.1, with exact norms of the powers (scipy does the
    same below n = 400; the loops here are far smaller) and the powers of ``|a|`` applied
    to a vector of ones for the bounds. The powers come back as [A, A^2, A^4, A^6, A^8]
    (A^8 only for degree 9), already scaled by 2^-s for degree 13.
    """
    abs_a = np.abs(a)
    work = abs_a @ np.ones(len(a))
    norm_a = float(work.max())
    a2 = a @ a
    a4 = a2 @ a2
    a6 = a2 @ a4
    d4 = _norm(a4) ** 0.25
    d6 = _norm(a6) ** (1.0 / 6.0)
    eta1 = max(d4, d6)

    def spin(times: int) -> float:
        nonlocal work
        for _ in range(times):
            work = abs_a @ work
        return float(work.max())

    # The vector is spun on whether or not a test needs it, so its powers stay in step.
    if _lm(spin(6), norm_a, BACKWARD[0], 3) == 0 and eta1 < THETA[0]:
        return 3, 0, [a, a2]
    if _lm(spin(4), norm_a, BACKWARD[1], 5) == 0 and eta1 < THETA[1]:
        return 5, 0, [a, a2, a4]
    a8 = a4 @ a4
    d8 = _norm(a8) ** 0.125
    eta2 = max(d6, d8)
    if _lm(spin(4), norm_a, BACKWARD[2], 7) == 0 and eta2 < THETA[2]:
        return 7, 0, [a, a2, a4, a6]
    if _lm(spin(4), norm_a, BACKWARD[3], 9) == 0 and eta2 < THETA[3]:
        return 9, 0, [a, a2, a4, a6, a8]
    d10 = _norm(a6 @ a4) ** 0.1
    eta4 = min(eta2, max(d8, d10))
    s = 0 if eta4 == 0.0 else max(0, math.ceil(math.log2(eta4 / THETA[4])))
    if s:
        abs_a = abs_a * 2.0**-s
        work = work * 2.0 ** (-19.0 * s)  # the vector has been spun 19 times
        norm_a *= 2.0**-s
    s += _lm(spin(8), norm_a, BACKWARD[4], 13)
    if s:
        a, a2, a4, a6 = a * 2.0**-s, a2 * 4.0**-s, a4 * 16.0**-s, a6 * 64.0**-s
    return 13, s, [a, a2, a4, a6]


def _pade(m: int, powers: list[Array]) -> Array:
    """Return the degree-m diagonal Pade approximant ``(V - U)^-1 (V + U)`` (Higham 2005).

    U holds the odd and V the even terms, evaluated as scipy's ``pade_UV_calc`` does
    (degree 13 with Paterson-Stockmeyer's splitting at A^6); ``I + 2 (V - U)^-1 U`` is
    the same quotient with one solve.
    """
    b = PADE[m]
    a, a2 = powers[0], powers[1]
    eye = np.eye(len(a))
    if m == 3:
        u = a @ a2 + b[1] * a
        v = b[2] * a2 + b[0] * eye
    elif m == 5:
        a4 = powers[2]
        u = a @ (a4 + b[3] * a2 + b[1] * eye)
        v = b[4] * a4 + b[2] * a2 + b[0] * eye
    elif m == 7:
        a4, a6 = powers[2], powers[3]
        u = a @ (a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
        v = b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
    elif m == 9:
        a4, a6, a8 = powers[2], powers[3], powers[4]
        u = a @ (a8 + b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye)
        v = b[8] * a8 + b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
    else:
        a4, a6 = powers[2], powers[3]
        inner = b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * eye
        outer = a6 + b[11] * a4 + b[9] * a2
        v = a6 @ (b[12] * a6 + b[10] * a4 + b[8] * a2) + (
            b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * eye
        )
        u = a @ (a6 @ outer + inner)
    result: Array = 2.0 * np.linalg.solve(v - u, u) + eye
    return result


def _exp_sinch(x: Array) -> Array:
    """Return ``(e^x[i+1] - e^x[i]) / (x[i+1] - x[i])`` (``e^x[i]`` where they are equal).

    Higham 2008, eq. (10.42): the superdiagonal of the exponential of a 2x2 triangular block.
    """
    exp_x = np.exp(x)
    out = np.diff(exp_x)
    step = np.diff(x)
    same = step == 0.0
    out[~same] /= step[~same]
    out[same] = exp_x[:-1][same]
    return out


def _bandwidth(a: Array) -> tuple[int, int]:
    """Return (lower, upper) bandwidth: how far below and above the diagonal a nonzero lies."""
    rows, cols = np.nonzero(a)
    if rows.size == 0:
        return 0, 0
    offset = cols - rows
    return max(0, int(-offset.min())), max(0, int(offset.max()))


def expm(a: Array) -> Array:
    """Return the matrix exponential of the square real matrix ``a``, as ``scipy.linalg.expm``.

    Scaling and squaring with a diagonal Pade approximant of degree 3 to 13 chosen from the
    norms of the powers of ``a`` (Al-Mohy and Higham, "A New Scaling and Squaring Algorithm
    for the Matrix Exponential", SIAM J. Matrix Anal. Appl. 31(3), 2009, Algorithm 5.1;
    Higham, "The Scaling and Squaring Method for the Matrix Exponential Revisited", SIAM J.
    Matrix Anal. Appl. 26(4), 2005). As scipy: a diagonal matrix is exponentiated entry by
    entry, and a triangular one recomputes its diagonal and first off-diagonal exactly at
    each squaring (Al-Mohy and Higham 2009, Code Fragment 2.1), which keeps stiff
    triangular blocks, such as a static gain's augmented matrix, accurate.
    """
    a = np.asarray(a, dtype=float)
    if a.shape == (1, 1):
        out: Array = np.exp(a)
        return out
    lower, upper = _bandwidth(a)
    if lower == 0 and upper == 0:
        return np.diag(np.exp(np.diag(a)))
    m, s, powers = _pade_structure(a)
    result = _pade(m, powers)
    if s and (lower == 0 or upper == 0):
        diag = np.diag(a)
        off = np.diag(a, k=-1 if upper == 0 else 1)
        np.fill_diagonal(result, np.exp(diag * 2.0**-s))
        for i in range(s - 1, -1, -1):
            result = result @ result
            np.fill_diagonal(result, np.exp(diag * 2.0**-i))
            band = result[1:, :-1] if upper == 0 else result[:-1, 1:]
            np.fill_diagonal(band, _exp_sinch(diag * 2.0**-i) * (off * 2.0**-i))
    else:
        for _ in range(s):
            result = result @ result
    if lower == 0:
        return np.triu(result)
    if upper == 0:
        return np.tril(result)
    return result


SCALE_FACTOR = 2.0
"""Balancing scales by powers of this radix, so the similarity is exact in floating point."""

CONVERGED = 0.95
"""A scaling is applied only if it cuts a row's plus its column's norm below this share."""


def balance(a: Array) -> Array:
    """Return the scaling ``d`` that balances ``a``: ``a / d[:, None] * d[None, :]``.

    LAPACK's ``dgebal`` with ``JOB = 'S'`` (scaling, no permutation), which is what
    ``scipy.linalg.matrix_balance(a, permute=False, separate=True)`` returns: the
    Parlett-Reinsch iteration ("Balancing a matrix for calculation of eigenvalues and
    eigenvectors", Numer. Math. 13, 1969) with 2-norms of rows and columns, scaling each
    row and column by powers of 2 until none would shrink their sum by 5 %. Powers of 2
    leave every entry exact, so the balanced matrix has the same exponential up to the
    same similarity, and the exponential of a badly scaled companion matrix becomes
    accurate (see ``lti.step_response``).
    """
    a = np.array(a, dtype=float)
    n = len(a)
    scale = np.ones(n)
    if not np.all(np.isfinite(a)):
        raise ValueError("cannot balance a matrix with NaN or infinite entries")
    tiny = np.finfo(float).tiny / np.finfo(float).eps  # LAPACK's SFMIN1 = safe min / precision
    huge = 1.0 / tiny
    tiny2 = tiny * SCALE_FACTOR
    huge2 = 1.0 / tiny2
    changed = True
    while changed:
        changed = False
        for i in range(n):
            c = math.hypot(*a[:, i])
            r = math.hypot(*a[i, :])
            ca = float(np.abs(a[:, i]).max())
            ra = float(np.abs(a[i, :]).max())
            if c == 0.0 or r == 0.0:
                continue
            g = r / SCALE_FACTOR
            f = 1.0
            total = c + r
            while c < g and max(f, c, ca) < huge2 and min(r, g, ra) > tiny2:
                f *= SCALE_FACTOR
                c *= SCALE_FACTOR
                ca *= SCALE_FACTOR
                r /= SCALE_FACTOR
                g /= SCALE_FACTOR
                ra /= SCALE_FACTOR
            g = c / SCALE_FACTOR
            while g >= r and max(r, ra) < huge2 and min(f, c, g, ca) > tiny2:
                f /= SCALE_FACTOR
                c /= SCALE_FACTOR
                g /= SCALE_FACTOR
                ca /= SCALE_FACTOR
                r *= SCALE_FACTOR
                ra *= SCALE_FACTOR
            if c + r >= CONVERGED * total:
                continue
            if f < 1.0 and scale[i] < 1.0 and f * scale[i] <= tiny:
                continue
            if f > 1.0 and scale[i] > 1.0 and scale[i] >= huge / f:
                continue
            scale[i] *= f
            changed = True
            a[i, :] *= 1.0 / f
            a[:, i] *= f
    return scale
