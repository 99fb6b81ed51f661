"""The scipy.optimize functions etcheck calls, loaded on their first call.

Importing scipy.optimize costs about 0.3 s (it loads linear programming,
scipy.fft and scipy.special); a draft check and a JSON report need none of
it, or only in a rare branch. These forwarders take the same arguments and
return the same objects as scipy's. :func:`bracketed_roots` refines many
brackets at once where a fine scan has already found them.
"""

from __future__ import annotations

import numpy as np

__all__ = ["brentq", "minimize_scalar", "find_root", "linear_sum_assignment", "bracketed_roots"]


def brentq(f, a, b, **kwargs):
    """:func:`scipy.optimize.brentq`."""
    from scipy.optimize import brentq as impl

    return impl(f, a, b, **kwargs)


def minimize_scalar(fun, **kwargs):
    """:func:`scipy.optimize.minimize_scalar`."""
    from scipy.optimize import minimize_scalar as impl

    return impl(fun, **kwargs)


def find_root(f, init, **kwargs):
    """:func:`scipy.optimize.elementwise.find_root`."""
    from scipy.optimize.elementwise import find_root as impl

    return impl(f, init, **kwargs)


def linear_sum_assignment(cost):
    """:func:`scipy.optimize.linear_sum_assignment` (minimum cost; row indices ascending).

    Where every row's cheapest column is a different column (every column's cheapest row, for more rows than
    columns), that pairing is returned without scipy: no assignment costs less than the sum of those minima,
    so it is optimal. Two spectra of one problem at two resolutions pair this way unless eigenvalues cluster.
    """
    cost = np.asarray(cost, dtype=float)
    if cost.ndim == 2 and cost.size and np.all(np.isfinite(cost)):
        n, m = cost.shape
        if n <= m:
            cols = np.argmin(cost, axis=1)
            if np.unique(cols).size == n:
                return np.arange(n), cols
        else:
            rows = np.argmin(cost, axis=0)
            if np.unique(rows).size == m:
                order = np.argsort(rows)
                return rows[order], np.arange(m)[order]
    from scipy.optimize import linear_sum_assignment as impl

    return impl(cost)


def bracketed_roots(f, a, b) -> np.ndarray:
    """The roots of the vectorised ``f`` in the brackets [a_i, b_i] (a_i < b_i, f changes sign across each), all
    brackets at once, each to within 2 ulp: the Illinois variant of false position (superlinear: ~10 evaluations
    of ``f`` on an array from a scan's brackets, against ~45 bisections), bisection where a false-position point
    falls outside its bracket and after 60 passes."""
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)
    fa, fb = np.asarray(f(a), dtype=float), np.asarray(f(b), dtype=float)
    if np.any(np.sign(fa) * np.sign(fb) > 0):
        raise ValueError("f does not change sign across every bracket")
    a, b = np.where(fb == 0, b, a), np.where(fa == 0, a, b)  # a root at an end: that end
    kept = np.zeros(a.shape, dtype=int)  # the end kept by the last pass: -1 a, +1 b
    eps = np.finfo(float).eps
    for n in range(1200):  # past 60 passes only bisections: 2 x 1074 halvings reach any float
        open_ = (b - a) > 4 * eps * np.maximum(np.abs(a), np.abs(b))
        if not open_.any():
            break
        m = 0.5 * (a + b)
        with np.errstate(all="ignore"):
            c = (a * fb - b * fa) / (fb - fa) if n < 60 else m
        c = np.where((c > a) & (c < b), c, m)
        fc = np.asarray(f(c), dtype=float)
        left = open_ & (np.sign(fc) * np.sign(fa) <= 0)  # the root lies in [a, c]: a is kept
        right = open_ & ~left
        # Illinois: an end kept twice in a row counts half, so that false position moves it too
        fa = np.where(left & (kept == -1), 0.5 * fa, fa)
        fb = np.where(right & (kept == 1), 0.5 * fb, fb)
        b, fb = np.where(left, c, b), np.where(left, fc, fb)
        a, fa = np.where(right, c, a), np.where(right, fc, fa)
        kept = np.where(left, -1, np.where(right, 1, kept))
        exact = open_ & (fc == 0)
        a, b = np.where(exact, c, a), np.where(exact, c, b)
    return 0.5 * (a + b)
