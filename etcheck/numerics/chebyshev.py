"""Chebyshev spectral tools on the unit interval [0, 1] (generic, dimensionless).

Everything here is plain polynomial interpolation on s in [0, 1]:

* :func:`lobatto_nodes`      second-kind Chebyshev (Chebyshev-Lobatto) points
  ``s_j = (1 - cos(pi j / N)) / 2``, j = 0..N, ascending, endpoints included;
* :func:`first_kind_nodes`   first-kind Chebyshev (Gauss) points
  ``t_k = (1 - cos(pi (2k + 1) / (2n))) / 2``, k = 0..n-1 (interior only);
* :func:`barycentric_weights`  barycentric weights of any node set;
* :func:`diff_matrix`        the collocation differentiation matrix on the nodes;
* :func:`resample_matrix`    barycentric interpolation from the nodes to any
  other points (the "resampling" matrix of Driscoll & Hale's rectangular
  collocation);
* :func:`clenshaw_curtis_weights`  quadrature weights on the Lobatto points
  (exact for polynomials of degree <= N).

No rod knowledge lives here. References: Trefethen, *Spectral Methods in
MATLAB* (2000), ch. 6 and 12; Berrut & Trefethen, SIAM Review 46 (2004);
Driscoll & Hale, IMA J. Numer. Anal. 36 (2016) "Rectangular spectral
collocation".
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "lobatto_nodes",
    "first_kind_nodes",
    "barycentric_weights",
    "lobatto_weights",
    "first_kind_weights",
    "diff_matrix",
    "resample_matrix",
    "clenshaw_curtis_weights",
]


def lobatto_nodes(N: int) -> np.ndarray:
    """N+1 Chebyshev-Lobatto points on [0, 1], ascending (s_0 = 0, s_N = 1).

    Uses the sine form ``(1 + sin(pi (2j - N) / (2N))) / 2`` so the points are
    exactly symmetric about 1/2.
    """
    if N < 1:
        raise ValueError(f"N must be >= 1, got {N}")
    j = np.arange(N + 1)
    return 0.5 * (1.0 + np.sin(np.pi * (2 * j - N) / (2.0 * N)))


def first_kind_nodes(n: int) -> np.ndarray:
    """n first-kind Chebyshev points on (0, 1), ascending (no endpoints)."""
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    k = np.arange(n)
    return 0.5 * (1.0 + np.sin(np.pi * (2 * k - n + 1) / (2.0 * n)))


def lobatto_weights(N: int) -> np.ndarray:
    """Barycentric weights of the N+1 Lobatto points (closed form, scaled)."""
    w = (-1.0) ** np.arange(N + 1)
    w[0] *= 0.5
    w[-1] *= 0.5
    return w


def first_kind_weights(n: int) -> np.ndarray:
    """Barycentric weights of the n first-kind points in ascending order."""
    k = np.arange(n)
    # For x_k = -cos((2k+1) pi / (2n)) (ascending) the weights are
    # (-1)^k sin((2k+1) pi / (2n)) up to a common factor.
    return (-1.0) ** k * np.sin((2 * k + 1) * np.pi / (2.0 * n))


def barycentric_weights(x: np.ndarray) -> np.ndarray:
    """Barycentric weights 1 / prod_{k != j} (x_j - x_k), normalised to max 1.

    Generic (any distinct nodes); prefer the closed forms for Chebyshev points.
    """
    x = np.asarray(x, dtype=float)
    diff = x[:, None] - x[None, :]
    np.fill_diagonal(diff, 1.0)
    # Work with logs to avoid overflow for many points.
    sign = np.prod(np.sign(diff), axis=1)
    logabs = -np.sum(np.log(np.abs(diff)), axis=1)
    w = sign * np.exp(logabs - logabs.max())
    return w


def diff_matrix(x: np.ndarray, w: np.ndarray | None = None) -> np.ndarray:
    """Differentiation matrix D on nodes x (D @ f(x) = f'(x) for polynomials).

    Off-diagonal ``D_ij = (w_j / w_i) / (x_i - x_j)``; diagonal by the
    negative-sum trick (rows annihilate constants exactly).
    """
    x = np.asarray(x, dtype=float)
    if w is None:
        w = barycentric_weights(x)
    dx = x[:, None] - x[None, :]
    np.fill_diagonal(dx, 1.0)
    D = (w[None, :] / w[:, None]) / dx
    np.fill_diagonal(D, 0.0)
    D[np.diag_indices_from(D)] = -D.sum(axis=1)
    return D


def resample_matrix(x: np.ndarray, y: np.ndarray, w: np.ndarray | None = None) -> np.ndarray:
    """Barycentric interpolation matrix P with P @ f(x) = p(y).

    p is the polynomial interpolant of degree len(x) - 1 through (x, f(x));
    ``P_ij = (w_j / (y_i - x_j)) / sum_k w_k / (y_i - x_k)`` (second, "true"
    barycentric formula), with exact rows where y_i coincides with a node.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if w is None:
        w = barycentric_weights(x)
    dy = y[:, None] - x[None, :]
    hit = dy == 0.0
    dy = np.where(hit, 1.0, dy)
    C = w[None, :] / dy
    P = C / C.sum(axis=1, keepdims=True)
    rows = np.any(hit, axis=1)
    if np.any(rows):
        P[rows] = hit[rows].astype(float)
    return P


def clenshaw_curtis_weights(N: int) -> np.ndarray:
    """Clenshaw-Curtis weights on the N+1 Lobatto points of [0, 1].

    ``sum(w * f(lobatto_nodes(N)))`` integrates f over [0, 1], exactly for
    polynomials of degree <= N (Trefethen, SMM, ``clencurt``).
    """
    if N < 1:
        raise ValueError(f"N must be >= 1, got {N}")
    theta = np.pi * np.arange(N + 1) / N
    w = np.zeros(N + 1)
    ii = np.arange(1, N)
    v = np.ones(N - 1)
    if N % 2 == 0:
        w[0] = w[N] = 1.0 / (N**2 - 1)
        for k in range(1, N // 2):
            v -= 2.0 * np.cos(2 * k * theta[ii]) / (4 * k**2 - 1)
        v -= np.cos(N * theta[ii]) / (N**2 - 1)
    else:
        w[0] = w[N] = 1.0 / N**2
        for k in range(1, (N - 1) // 2 + 1):
            v -= 2.0 * np.cos(2 * k * theta[ii]) / (4 * k**2 - 1)
    w[ii] = 2.0 * v / N
    # Nodes cos(theta) run from +1 to -1; ours ascend from 0 to 1 (symmetric
    # weights, so the order does not matter), and [0, 1] halves the length.
    return 0.5 * w[::-1]
