"""Independent reference computations for tests (not used by etcheck itself).

The straight rod at lambda = 0 has constant coefficients, so its static
problem is solved exactly by a matrix exponential (shooting) instead of
Chebyshev collocation: the straight-rod equations of docs/model.md, section 6, at lambda = 0,

    (R/f) u'''' - (T + P R w^2) u'' - w^2 u - B v' = 0
    (1/f) v'''' - (T + P   w^2) v'' - w^2 v + B u' = 0,  u = u' = v = v' = 0 at 0, 1.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
from scipy.optimize import brentq

#: working precision of the shooting: the fundamental matrix grows like
#: exp(sqrt(f T)) and its 4x4 minor cancels, so doubles are not enough
mp.mp.dps = 50


def static_determinant(B, P, R, f, omega=0.0, T=0.0):
    """det of the 4x4 clamped shooting matrix (sign changes at simple static points).

    Under strong tension the matrix exponential is taken in 50-digit
    arithmetic (mpmath); elsewhere doubles suffice.
    """
    if f * abs(T) / R < 50:
        return _determinant_double(B, P, R, f, omega, T)
    # entries grow like exp(sqrt(f T / R)) and the minor cancels: carry that many digits and more
    with mp.workdps(50 + int(np.sqrt(f * abs(T) / R))):
        A = _system(mp.zeros(8, 8), *(mp.mpf(x) for x in (B, P, R, f, omega, T)))
        Phi = mp.expm(A)
        free = [2, 3, 6, 7]
        rows = [0, 1, 4, 5]
        M = mp.matrix([[Phi[r, c] for c in free] for r in rows])
        d = mp.det(M)
        return float(mp.sign(d)) * float(min(abs(d), mp.mpf("1e300")))  # the sign is what the tests use


def first_static_load(P, R, f, omega=0.0, T=0.0, B_max=5.0, n=2000):
    """Smallest B > 0 where the straight rod has a static (divergence) point.

    Needs a sign change: only for split (simple) points, i.e. R != 1 with
    omega != 0 or T != 0.
    """
    return _first_root(lambda b: static_determinant(b, P, R, f, omega, T), B_max, n)


def first_static_spin(P, R, f, B=0.0, T=0.0, w_max=3.0, n=3000):
    """Smallest omega > 0 with a static point at load B (sign change needed)."""
    return _first_root(lambda w: static_determinant(B, P, R, f, w, T), w_max, n)


def _first_root(g, x_max, n):
    grid = np.linspace(1e-9, x_max, n)
    d = np.array([g(x) for x in grid])
    i = np.nonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)[0]
    if i.size == 0:
        return None
    return brentq(g, grid[i[0]], grid[i[0] + 1], xtol=1e-15, rtol=1e-14)


def chi_mp(b):
    """chi(beta), eq. char_welded, transcribed from the paper (mpmath)."""
    s3 = mp.sqrt(3)
    return (
        2 * mp.cos(b)
        + mp.cos(2 * b)
        - 2 * (mp.cos(b / 2) + mp.cos(3 * b / 2)) * mp.cosh(s3 * b / 2)
        + (2 - mp.cos(b)) * mp.cosh(s3 * b)
        - s3 * mp.sin(b) * mp.sinh(s3 * b)
        - 2 * s3 * (mp.sin(b / 2) - mp.sin(3 * b / 2)) * mp.sinh(s3 * b / 2)
    )


def chi_scaled_mp(b):
    return chi_mp(b) * mp.exp(-mp.sqrt(3) * b)


_ROOT_CACHE: dict[int, float] = {}


def beta_ref(k: int) -> float:
    """k-th double zero of chi: a zero of d/dbeta [chi e^{-sqrt3 beta}] (mpmath)."""
    if k not in _ROOT_CACHE:
        guess = mp.pi / 3 + 2 * mp.pi * k
        root = mp.findroot(lambda b: mp.diff(chi_scaled_mp, b), guess, tol=mp.mpf(10) ** -30)
        assert abs(chi_scaled_mp(root)) < mp.mpf(10) ** -25  # a zero of chi itself, too
        _ROOT_CACHE[k] = float(root)
    return _ROOT_CACHE[k]


def _determinant_double(B, P, R, f, omega, T):
    from scipy.linalg import expm

    Phi = expm(_system(np.zeros((8, 8)), B, P, R, f, omega, T))
    M = Phi[np.ix_([0, 1, 4, 5], [2, 3, 6, 7])]
    return np.linalg.det(M / np.max(np.abs(M)))


def _system(A, B, P, R, f, omega, T):
    """Fill the 8x8 first-order matrix of (u, u', u'', u''', v, v', v'', v''') = y."""
    for i in (0, 1, 2, 4, 5, 6):
        A[i, i + 1] = 1
    A[3, 2] = f / R * (T + P * R * omega**2)  # row of the fourth derivative of u
    A[3, 0] = f / R * omega**2
    A[3, 5] = f / R * B
    A[7, 6] = f * (T + P * omega**2)  # row of the fourth derivative of v
    A[7, 4] = f * omega**2
    A[7, 1] = -f * B
    return A
