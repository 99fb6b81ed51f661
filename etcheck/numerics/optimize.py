"""The scipy.optimize functions etcheck calls, loaded on their first call.

Importing scipy.optimize costs about 0.3 s (it loads linear programming,
scipy.fft and scipy.special); a draft check and a JSON report need none of
it, or only in a rare branch. These forwarders take the same arguments and
return the same objects as scipy's. :func:`bisect_brackets` refines many
brackets at once where a fine scan has already found them.
"""

from __future__ import annotations

import numpy as np

__all__ = ["brentq", "minimize_scalar", "find_root", "linear_sum_assignment", "bisect_brackets"]


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


def bisect_brackets(f, a, b) -> np.ndarray:
    """The roots of the vectorised ``f`` in the brackets [a_i, b_i] (f changes sign across each), by bisection of
    all brackets at once to the last bit (at most ~60 evaluations of ``f`` on the array of midpoints)."""
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)
    fa, fb = np.asarray(f(a), dtype=float), np.asarray(f(b), dtype=float)
    if np.any(np.sign(fa) * np.sign(fb) > 0):
        raise ValueError("f does not change sign across every bracket")
    a, b = np.where(fb == 0, b, a), np.where(fa == 0, a, b)  # a root at an end: that end
    for _ in range(1100):  # each pass halves the bracket (or stops it): 2 x 1074 passes reach any float
        m = 0.5 * (a + b)
        open_ = (m != a) & (m != b)
        if not open_.any():
            break
        fm = np.asarray(f(m), dtype=float)
        left = np.sign(fm) * np.sign(fa) <= 0  # the root lies in [a, m] (or is m)
        b = np.where(open_ & left, m, b)
        a, fa = np.where(open_ & ~left, m, a), np.where(open_ & ~left, fm, fa)
        exact = open_ & (fm == 0)
        a, b = np.where(exact, m, a), np.where(exact, m, b)
    return 0.5 * (a + b)
