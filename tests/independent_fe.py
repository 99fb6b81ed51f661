"""An independent discretisation of the straight tether with profiles, for tests (not used by etcheck):
Hermite cubic finite elements (Galerkin, weak form) on a geometrically graded mesh.

The weak form of the bending equations (docs/model.md, section 10), with test functions du, dv that
vanish with the welded ends' conditions:

    int [ lambda^2 (u du + P R u' du') + lambda (gamma (R/f) u'' du'' - 2 omega v du)
          + (R/f) u'' du'' + T tau u' du' + P R omega^2 u' du' - omega^2 u du - B b v' du ] ds = 0
    int [ lambda^2 (v dv + P v' dv') + lambda (gamma (1/f) v'' dv'' + 2 omega u dv)
          + (1/f) v'' dv'' + T tau v' dv' + P omega^2 v' dv' - omega^2 v dv + B b u' dv ] ds = 0

Each element carries (w, w') at its two nodes (C1 cubics); the integrals are 5-point Gauss. Nothing is
shared with etcheck's collocation but the profiles' values at the quadrature points. The eigenvalues come
from dense QZ (small meshes) or shift-invert ARPACK on the companion pencil.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, eigs, splu

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(5)


def graded_nodes(layer: float, elements: int, ratio: float = 1.25) -> np.ndarray:
    """Nodes on [0, 1]: a uniform middle of ``elements`` elements, and towards each end element sizes
    shrinking by ``ratio`` down to layer / 4."""
    h = 1.0 / elements
    ends = []
    size = h
    while size > layer / 4:
        size /= ratio
        ends.append(size)
    ends = ends[::-1]
    left = np.concatenate([[0.0], np.cumsum(ends)])
    middle_lo, middle_hi = left[-1], 1.0 - left[-1]
    n_mid = max(2, int(math.ceil((middle_hi - middle_lo) / h)))
    middle = np.linspace(middle_lo, middle_hi, n_mid + 1)
    right = 1.0 - left[::-1]
    return np.unique(np.concatenate([left, middle, right]))


def _shape(xi: np.ndarray, h: float):
    """Hermite cubic shape functions on an element of length h at local xi in [0, 1]: values, first and second
    derivatives in s (4 functions: w0, w0', w1, w1')."""
    H = np.stack([1 - 3 * xi**2 + 2 * xi**3, h * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, h * (-xi**2 + xi**3)])
    D1 = np.stack([-6 * xi + 6 * xi**2, h * (1 - 4 * xi + 3 * xi**2), 6 * xi - 6 * xi**2, h * (-2 * xi + 3 * xi**2)]) / h
    D2 = np.stack([-6 + 12 * xi, h * (-4 + 6 * xi), 6 - 12 * xi, h * (-2 + 6 * xi)]) / h**2
    return H, D1, D2


def matrices(params, current, tension, nodes: np.ndarray):
    """(K0, KB, C, M) sparse, on the free DOFs (welded ends): the QEP is
    (K0 + B KB) + lambda C + lambda^2 M, with (u, u', v, v') at every node (T and omega from params)."""
    p = params
    n_nodes = nodes.size
    ndof = 4 * n_nodes
    blocks = {k: ([], [], []) for k in ("K0", "KB", "C", "M")}

    def put(name, rows, cols, V):
        r, c, v = blocks[name]
        r.append(rows.ravel())
        c.append(cols.ravel())
        v.append(V.ravel())

    xg = 0.5 * (_GAUSS_X + 1.0)
    wg = 0.5 * _GAUSS_W
    for e in range(n_nodes - 1):
        a, b = nodes[e], nodes[e + 1]
        h = b - a
        s = a + h * xg
        H, D1, D2 = _shape(xg, h)
        w = wg * h
        tau = tension(s)
        bb = current(s)
        du = np.array([4 * e, 4 * e + 1, 4 * e + 4, 4 * e + 5])
        dv = du + 2
        for own, other, c4, pc, sign in ((du, dv, p.R / p.f, p.P * p.R, 1.0), (dv, du, 1.0 / p.f, p.P, -1.0)):
            rows, cols = np.meshgrid(own, own, indexing="ij")
            stiff = c4 * (D2 * w) @ D2.T + p.T * (D1 * (w * tau)) @ D1.T + pc * p.omega**2 * (D1 * w) @ D1.T \
                - p.omega**2 * (H * w) @ H.T
            put("K0", rows, cols, stiff)
            put("C", rows, cols, p.gamma * c4 * (D2 * w) @ D2.T)
            put("M", rows, cols, (H * w) @ H.T + pc * (D1 * w) @ D1.T)
            rows2, cols2 = np.meshgrid(own, other, indexing="ij")
            put("KB", rows2, cols2, -sign * (H * (w * bb)) @ D1.T)  # -B b v' du in u's row, +B b u' dv in v's
            put("C", rows2, cols2, -sign * 2.0 * p.omega * (H * w) @ H.T)
    fixed = np.array([0, 1, 2, 3, ndof - 4, ndof - 3, ndof - 2, ndof - 1])
    free = np.setdiff1d(np.arange(ndof), fixed)
    out = []
    for name in ("K0", "KB", "C", "M"):
        r, c, v = blocks[name]
        A = sp.csc_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))), shape=(ndof, ndof))
        out.append(A[free][:, free].tocsc())
    return out


def eigenvalues(K0, KB, C, M, B: float, k: int = 24, sigma: float = 0.0123) -> np.ndarray:
    """The k eigenvalues of the QEP at load B nearest sigma (ARPACK, shift-invert companion)."""
    K = (K0 + B * KB).tocsc()
    n = K.shape[0]
    lu = splu((K + sigma * C + sigma**2 * M).tocsc())
    S = (C + sigma * M).tocsr()
    Mr = M.tocsr()

    def mv(z):
        w1 = -lu.solve(Mr @ z[n:] + S @ z[:n])
        return np.concatenate([w1, z[:n] + sigma * w1])

    op = LinearOperator((2 * n, 2 * n), matvec=mv, dtype=float)
    theta = eigs(op, k=k, which="LM", ncv=max(3 * k, 30), tol=1e-13, v0=np.ones(2 * n), return_eigenvectors=False)
    return sigma + 1.0 / theta


def dense_eigenvalues(K0, KB, C, M, B: float) -> np.ndarray:
    """Every eigenvalue of the QEP at load B (QZ of the companion; small meshes only)."""
    K = (K0 + B * KB).toarray()
    n = K.shape[0]
    Z, Id = np.zeros((n, n)), np.eye(n)
    L = np.block([[Z, Id], [-K, -C.toarray()]])
    Mm = np.block([[Id, Z], [Z, M.toarray()]])
    return sla.eig(L, Mm, right=False)


def critical_load(params, current, tension, nodes, B_hi: float, n_scan: int = 40, rtol: float = 1e-9,
                  k: int = 24, sigma: float = 0.0123) -> float:
    """The first B in (0, B_hi] where some eigenvalue has Re lambda > 1e-8 |lambda| (scan, then bisection)."""
    mats = matrices(params, current, tension, nodes)

    def unstable(B):
        lam = eigenvalues(*mats, B, k=k, sigma=sigma)
        return bool(np.any(lam.real > 1e-8 * np.maximum(np.abs(lam), 1.0)))

    prev = 0.0
    for B in np.linspace(0.0, B_hi, n_scan + 1)[1:]:
        if unstable(B):
            a, b = prev, B
            while b - a > rtol * b:
                c = 0.5 * (a + b)
                a, b = (a, c) if unstable(c) else (c, b)
            return 0.5 * (a + b)
        prev = B
    return math.nan
