"""Generic quadratic eigenvalue problems (QEP) and spectrum matching (dimensionless).

Problem: Q(lambda) y = (A0 + lambda A1 + lambda^2 A2) y = 0 with real square
A0, A1, A2; A2 (and A1) may be singular, which produces infinite eigenvalues.

Tools:

* :func:`companion`          first companion linearisation L - lambda M;
* :func:`eliminate_static`   QR elimination of unknowns that enter only A0
                             (reduced, smaller QEP + back-substitution;
                             :func:`factor_static`: the QR alone, to reduce
                             other matrices with it);
* :func:`qep_dense`          all finite eigenvalues by QZ on the linearisation;
* :func:`qep_shift_invert`   the k eigenvalues nearest a real shift sigma by
                             ARPACK on the shift-inverted companion, one LU
                             of Q(sigma) (real arithmetic);
* :func:`pencil_eigenvalues` the roots x of det(A0 + x n0) (low-rank n0: small
                             standard eigenproblem; else QZ);
* :func:`match_spectra`      two-resolution agreement filter with error
                             estimates (optimal assignment, so degenerate
                             clusters are paired one-to-one).

No rod knowledge lives here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.linalg as sla

from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import WORKSPACE, matrix_bytes, require

from .optimize import linear_sum_assignment

__all__ = [
    "companion",
    "StaticElimination",
    "StaticFactor",
    "eliminate_static",
    "factor_static",
    "qep_dense",
    "qep_shift_invert",
    "pencil_eigenvalues",
    "qep_newton",
    "Matched",
    "match_spectra",
    "relative_distance",
    "sparse_pencil_nearest",
    "sparse_qep_nearest",
]


def companion(A0: np.ndarray, A1: np.ndarray, A2: np.ndarray):
    """First companion form: z = (y, lambda y), (L - lambda M) z = 0.

    L = [[0, I], [-A0, -A1]],  M = [[I, 0], [0, A2]].
    """
    n = A0.shape[0]
    eye = np.eye(n)
    Z = np.zeros((n, n))
    L = np.block([[Z, eye], [-A0, -A1]])
    M = np.block([[eye, Z], [Z, A2]])
    return L, M


@dataclass(frozen=True)
class StaticFactor:
    """A0[:, drop] = Q [R; 0] (``qr``, ``tau``: LAPACK's Householder form of Q, never formed): see
    :func:`factor_static`. ``keep``: the other unknowns."""

    keep: np.ndarray
    drop: np.ndarray
    qr: np.ndarray
    tau: np.ndarray

    def reduce(self, *A: np.ndarray) -> list[np.ndarray]:
        """Q2^T A[:, keep] of each matrix (none may meet the dropped unknowns), in one application of Q to
        their non-zero columns (a parameter's derivative reaches few)."""
        sub = [a[:, self.keep] for a in A]
        cols = [np.flatnonzero(np.any(a != 0.0, axis=0)) for a in sub]
        Z = _qt(self.qr, self.tau, np.hstack([a[:, c] for a, c in zip(sub, cols)]))[self.drop.size:]
        out, j = [], 0
        for c in cols:
            o = np.zeros((Z.shape[0], self.keep.size))
            o[:, c] = Z[:, j:j + c.size]
            out.append(o)
            j += c.size
        return out

    def recover(self, A: tuple, lam: complex, y_keep: np.ndarray) -> np.ndarray:
        """Full eigenvector of the QEP ``A = (A0, A1, A2)`` from the reduced one at eigenvalue lam."""
        A0, A1, A2 = A
        k, r = self.keep, self.drop.size
        rhs = (A0[:, k] + lam * A1[:, k] + lam**2 * A2[:, k]) @ y_keep
        q1t = _qt(self.qr, self.tau, np.column_stack([rhs.real, rhs.imag]))[:r]
        y_drop = -sla.solve_triangular(np.triu(self.qr[:r, :r]), q1t[:, 0] + 1j * q1t[:, 1])
        y = np.zeros(A0.shape[0], dtype=np.result_type(y_keep, complex))
        y[k] = y_keep
        y[self.drop] = y_drop
        return y


def factor_static(A0: np.ndarray, drop) -> StaticFactor:
    """QR of the columns ``drop`` of A0 (full column rank required): the rows Q2^T A0 no longer involve them.

    Q stays in Householder form (LAPACK geqrf, applied by ormqr): forming it would cost several times the
    factorisation.
    """
    drop = np.asarray(drop)
    mask = np.ones(A0.shape[0], dtype=bool)
    mask[drop] = False
    (qr, tau), _ = sla.qr(A0[:, drop], mode="raw")
    r = drop.size
    if abs(qr[r - 1, r - 1]) <= 1e-13 * abs(qr[0, 0]):
        raise np.linalg.LinAlgError("static block is rank deficient")
    return StaticFactor(keep=np.nonzero(mask)[0], drop=drop, qr=qr, tau=tau)


@dataclass(frozen=True)
class StaticElimination:
    """Result of :func:`eliminate_static`: ``B0, B1, B2`` act on the kept unknowns ``factor.keep``; the
    eliminated unknowns follow from ``y_drop = -solve(R, Q1^T (A0 + lambda A1 + lambda^2 A2)[:, keep] y_keep)``
    (:meth:`recover`)."""

    B0: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    factor: StaticFactor
    A: tuple

    def recover(self, lam: complex, y_keep: np.ndarray) -> np.ndarray:
        """Full eigenvector from the reduced one at eigenvalue lam."""
        return self.factor.recover(self.A, lam, y_keep)


def eliminate_static(A0, A1, A2, drop) -> StaticElimination:
    """Eliminate unknowns whose columns appear only in A0 (lambda-free).

    With A0[:, drop] = Q [R; 0] (:func:`factor_static`) the rows Q2^T Q(lambda) of the QEP no longer involve
    the dropped unknowns, giving a square QEP of size n - len(drop) with the same finite eigenvalues.
    """
    drop = np.asarray(drop)
    if np.any(A1[:, drop]) or np.any(A2[:, drop]):
        raise ValueError("eliminated unknowns must not appear in A1 or A2")
    factor = factor_static(A0, drop)
    B0, B1, B2 = factor.reduce(A0, A1, A2)
    return StaticElimination(B0=B0, B1=B1, B2=B2, factor=factor, A=(A0, A1, A2))


def _qt(qr: np.ndarray, tau: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Q^T X for real X (n, m), Q given by LAPACK's Householder reflectors (qr, tau)."""
    X = np.asarray(X, dtype=float)
    cq, _, info = _ormqr("L", "T", qr, tau, X, max(1, 64 * X.shape[1]))
    if info != 0:
        raise np.linalg.LinAlgError(f"ormqr: info = {info}")
    return cq


def pencil_eigenvalues(A0: np.ndarray, n0: np.ndarray) -> np.ndarray:
    """The finite x with A0 + x n0 singular (real square A0, n0).

    Where A0 is regular: x = -1 / kappa for the non-zero eigenvalues kappa of (A0^-1 n0) on the columns n0
    reaches (the others give kappa = 0, infinite x): cheaper than QZ of the whole pencil, the more so the fewer
    columns n0 reaches. Where A0 is nearly singular (reciprocal condition below 1e-10: a root next to x = 0), QZ."""
    cols = np.flatnonzero(np.any(n0 != 0.0, axis=0))
    if 0 < cols.size:
        lu, piv, info = _getrf(A0)
        if info == 0:
            rcond, _ = _gecon(lu, float(np.max(np.sum(np.abs(A0), axis=0))))
            if rcond > 1e-10:
                K = _getrs(lu, piv, n0[:, cols])[0][cols]
                kappa = np.linalg.eigvals(K)
                big = np.abs(kappa) > 1e-13 * np.max(np.abs(kappa), initial=0.0)
                return -1.0 / kappa[big]
    alpha, beta = sla.eig(A0, -n0, right=False, homogeneous_eigvals=True, check_finite=False)
    ok = np.abs(beta) > 1e-13 * np.abs(alpha)
    return alpha[ok] / beta[ok]


_ormqr, _getrf, _getrs, _gecon = sla.get_lapack_funcs(("ormqr", "getrf", "getrs", "gecon"), dtype=np.float64)


#: dense QZ of a companion form of size m, in m-square float64 matrices: L and M, the copies QZ works on and its
#: workspace (6.0-6.2 measured with tracemalloc; two more for the complex eigenvectors)
QZ_MATRICES = 7


@single_blas_thread
def qep_dense(A0, A1, A2, vectors: bool = False, max_abs: float = np.inf):
    """All finite eigenvalues of the QEP by QZ on :func:`companion`.

    Infinite eigenvalues (beta = 0) and those with |lambda| > max_abs are
    dropped. Returns ``lam`` or ``(lam, Y)`` with Y[:, i] the top half of the
    companion eigenvector (the QEP eigenvector).
    """
    n = A0.shape[0]
    require(f"a dense eigenproblem of size {2 * n}", matrix_bytes(2 * n, count=QZ_MATRICES + 2 * vectors) + WORKSPACE)
    L, M = companion(A0, A1, A2)
    if vectors:
        ab, V = sla.eig(L, M, right=True, homogeneous_eigvals=True)
    else:
        ab = sla.eig(L, M, right=False, homogeneous_eigvals=True)
    alpha, beta = ab
    ok = np.abs(beta) > 1e-14 * np.abs(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = np.where(ok, alpha / np.where(ok, beta, 1.0), np.inf)
    ok &= np.isfinite(lam) & (np.abs(lam) <= max_abs)
    lam = lam[ok]
    if vectors:
        return lam, V[:n, ok]
    return lam


@lru_cache(maxsize=16)
def _start_vector(size: int) -> np.ndarray:
    """ARPACK's start vector: fixed, so that every run gives the same answer (its default start is random)."""
    v0 = np.random.default_rng(12345).uniform(-1.0, 1.0, size)
    v0.setflags(write=False)
    return v0


def qep_shift_invert(A0, A1, A2, k: int, sigma: float = 0.0, vectors: bool = False,
                     ncv: int | None = None, tol: float = 1e-13, maxiter: int | None = None):
    """The k eigenvalues of the QEP nearest the real shift sigma (ARPACK).

    Shift-invert of the companion pencil: theta = 1 / (lambda - sigma) are the
    largest eigenvalues of (L - sigma M)^{-1} M, applied with one dense LU of
    Q(sigma) = A0 + sigma A1 + sigma^2 A2:
    w1 = -Q(sigma)^{-1} (A2 z2 + (A1 + sigma A2) z1), w2 = z1 + sigma w1.
    Infinite eigenvalues map to theta = 0 and are never returned. sigma should
    not be an eigenvalue (a small non-zero real value works at divergence
    points where lambda = 0 is one).
    """
    n = A0.shape[0]
    Qs = A0 + sigma * A1 + sigma**2 * A2
    lu, piv = sla.lu_factor(Qs, overwrite_a=True, check_finite=False)  # Qs is ours: no copy
    # A2 z2 + (A1 + sigma A2) z1 through the rows and columns that A1, A2 reach (with damping, gyroscopic and
    # inertia terms in a few fields only: a third of the entries) in one product, and LAPACK's getrs called
    # directly (without the per-call overhead of scipy's lu_solve)
    rows = np.flatnonzero(A1.any(axis=1) | A2.any(axis=1))
    cols = np.flatnonzero(A1.any(axis=0) | A2.any(axis=0))
    ix = np.ix_(rows, cols)
    a2 = A2[ix]
    block = np.hstack([A1[ix] + sigma * a2, a2])
    cols = np.concatenate([cols, cols + n])

    def matvec(z):
        z = np.asarray(z).reshape(-1)
        b = np.zeros(n)
        b[rows] = block @ z[cols]
        w1 = _getrs(lu, piv, b, overwrite_b=True)[0]
        w1 *= -1.0
        return np.concatenate([w1, z[:n] + sigma * w1])

    # scipy.sparse.linalg here: a draft (static pencils only) never loads it
    from scipy.sparse.linalg import ArpackError, ArpackNoConvergence, LinearOperator, eigs

    op = LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=float)
    k = min(k, 2 * n - 2)
    if maxiter is None:
        maxiter = 500  # restarts; what did not converge by then is dropped, never invented
    if ncv is None:
        ncv = min(2 * n, max(3 * k, 20))  # a wider Krylov space: fewer restarts
    v0 = _start_vector(2 * n)
    try:
        out = eigs(op, k=k, which="LM", ncv=ncv, tol=tol, maxiter=maxiter, v0=v0, return_eigenvectors=vectors)
    except ArpackNoConvergence as err:  # keep what converged
        out = (err.eigenvalues, err.eigenvectors) if vectors else err.eigenvalues
    except ArpackError:  # a breakdown of the restarted iteration (rare): all eigenvalues by dense QZ instead
        dense = qep_dense(A0, A1, A2, vectors=vectors)
        lam = dense[0] if vectors else dense
        order = np.argsort(np.abs(lam - sigma), kind="stable")[:k]
        return (lam[order], dense[1][:, order]) if vectors else lam[order]
    if vectors:
        theta, V = out
    else:
        theta, V = out, None
    lam = sigma + 1.0 / theta
    order = np.argsort(np.abs(lam - sigma))
    lam = lam[order]
    if vectors:
        return lam, V[:n, order]
    return lam


def relative_distance(a: np.ndarray, b: np.ndarray, floor: float) -> np.ndarray:
    """|a - b| / max(|b|, floor): relative for |b| >= floor, scaled absolute below."""
    return np.abs(a - b) / np.maximum(np.abs(b), floor)


@dataclass(frozen=True)
class Matched:
    """Eigenvalues of the finer resolution that have a partner in the coarser one."""

    values: np.ndarray  # fine-resolution eigenvalues (kept), in input order
    errors: np.ndarray  # relative_distance(coarse partner, fine value)
    index: np.ndarray  # indices into the fine array
    partner: np.ndarray  # indices into the coarse array


def match_spectra(fine: np.ndarray, coarse: np.ndarray, accept: float = 1e-3,
                  floor: float = 0.1) -> Matched:
    """Pair two spectra of the same problem at two resolutions.

    Optimal one-to-one assignment (Hungarian) on the scaled distance
    |l_f - l_c| / max(|l_f|, floor); a fine eigenvalue is kept when its
    partner lies within ``accept`` (spurious/unresolved eigenvalues move with
    the resolution and are dropped). The error estimate of each kept value is
    that scaled distance.
    """
    fine = np.asarray(fine, dtype=complex)
    coarse = np.asarray(coarse, dtype=complex)
    if fine.size == 0 or coarse.size == 0:
        empty = np.zeros(0, dtype=int)
        return Matched(fine[:0], np.zeros(0), empty, empty)
    dist = np.abs(fine[:, None] - coarse[None, :]) / np.maximum(np.abs(fine), floor)[:, None]
    rows, cols = linear_sum_assignment(np.minimum(dist, 1e300))
    err = dist[rows, cols]
    ok = err <= accept
    order = np.argsort(rows[ok])
    rows, cols, err = rows[ok][order], cols[ok][order], err[ok][order]
    return Matched(values=fine[rows], errors=err, index=rows, partner=cols)


def sparse_qep_nearest(A0, A1, A2, k: int, sigma: complex = 0.0, vectors: bool = False, tol: float = 1e-13,
                       ncv: int | None = None, maxiter: int = 500, scale: float = 1.0, ordering: str = "COLAMD"):
    """The k eigenvalues of a sparse QEP nearest the shift sigma (real or complex), by ARPACK on the
    shift-inverted companion pencil with one sparse LU of Q(sigma) = A0 + sigma A1 + sigma^2 A2 (as
    :func:`qep_shift_invert`, whose dense LU this replaces). ``scale``: the size of the wanted eigenvalues,
    by which lambda is scaled before the companion is formed (its two halves, y and lambda y, then balance:
    without it the eigenvalues of a tether under a tension of 1e9 carry errors of 1e-5 of their size).
    ``ordering``: SuperLU's column ordering (``"NATURAL"`` for matrices already banded by blocks).
    Infinite eigenvalues are never returned. Returns ``lam`` sorted by distance to sigma, or ``(lam, Y)`` with
    the QEP eigenvectors in the columns of Y."""
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import ArpackNoConvergence, LinearOperator, eigs, splu

    if scale != 1.0:
        out = sparse_qep_nearest(A0, scale * A1, (scale * scale) * A2, k, sigma / scale, vectors, tol, ncv, maxiter,
                                 ordering=ordering)
        return (scale * out[0], out[1]) if vectors else scale * out
    n = A0.shape[0]
    cplx = np.iscomplexobj(sigma) and complex(sigma).imag != 0.0
    sigma = complex(sigma) if cplx else float(np.real(sigma))
    try:
        lu = splu(csc_matrix(A0 + sigma * A1 + (sigma * sigma) * A2), permc_spec=ordering)
    except RuntimeError:  # the shift is an eigenvalue to the last bit: one next to it
        sigma = sigma + 1e-10 * (1.0 + abs(sigma))
        lu = splu(csc_matrix(A0 + sigma * A1 + (sigma * sigma) * A2), permc_spec=ordering)
    S = (A1 + sigma * A2).tocsr()
    M2 = A2.tocsr()
    dtype = complex if cplx else float

    def matvec(z):
        z = np.asarray(z).reshape(-1)
        w1 = -lu.solve(np.asarray(M2 @ z[n:] + S @ z[:n], dtype=dtype))
        return np.concatenate([w1, z[:n] + sigma * w1])

    op = LinearOperator((2 * n, 2 * n), matvec=matvec, dtype=dtype)
    k = min(k, 2 * n - 2)
    ncv = ncv or min(2 * n, max(3 * k, 20))
    v0 = _start_vector(2 * n).astype(dtype)
    try:
        out = eigs(op, k=k, which="LM", ncv=ncv, tol=tol, maxiter=maxiter, v0=v0, return_eigenvectors=vectors)
    except ArpackNoConvergence as err:  # keep what converged
        out = (err.eigenvalues, err.eigenvectors) if vectors else err.eigenvalues
    theta, V = out if vectors else (out, None)
    lam = sigma + 1.0 / theta
    order = np.argsort(np.abs(lam - sigma), kind="stable")
    return (lam[order], V[:n, order]) if vectors else lam[order]


def sparse_pencil_nearest(A, N, k: int, shift: float = 0.0, ordering: str = "COLAMD") -> np.ndarray:
    """The k values x nearest ``shift`` where the sparse A + x N is singular (ARPACK on (A + shift N)^-1 N,
    whose eigenvalues are 1 / (shift - x); N may be singular: its infinite x are never returned).
    ``ordering``: SuperLU's column ordering."""
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import ArpackNoConvergence, LinearOperator, eigs, splu

    n = A.shape[0]
    lu = splu(csc_matrix(A + shift * N), permc_spec=ordering)
    Nr = N.tocsr()
    op = LinearOperator((n, n), matvec=lambda z: lu.solve(np.asarray(Nr @ np.asarray(z).reshape(-1), dtype=float)),
                        dtype=float)
    k = min(k, n - 2)
    try:
        theta = eigs(op, k=k, which="LM", ncv=min(n, max(3 * k, 20)), tol=1e-13, maxiter=500,
                     v0=_start_vector(n), return_eigenvectors=False)
    except ArpackNoConvergence as err:
        theta = err.eigenvalues
    theta = theta[theta != 0]
    return shift - 1.0 / theta


def qep_newton(A0, A1, A2, lam: complex, y: np.ndarray, tol: float = 1e-13, maxit: int = 8,
               ordering: str = "COLAMD") -> tuple[complex, np.ndarray, bool]:
    """One eigenpair of the sparse QEP (A0 + lambda A1 + lambda^2 A2) y = 0 from a nearby guess (lam, y), by
    nonlinear inverse iteration (Ruhe 1973): w = Q(lambda)^-1 Q'(lambda) y, lambda <- lambda - (c* y) / (c* w),
    y <- w / (c* w) with c the first guess; quadratic convergence near a simple eigenvalue. Returns
    (lambda, y, converged): converged when the step falls below ``tol`` |lambda| (else the last iterate)."""
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import splu

    c = np.conj(y) / np.vdot(y, y)
    y = y / np.dot(c, y)
    lam = complex(lam)
    last = math.inf
    for _ in range(maxit):
        try:
            lu = splu(csc_matrix(A0 + lam * A1 + (lam * lam) * A2, dtype=complex), permc_spec=ordering)
        except RuntimeError:  # exactly singular: lambda is an eigenvalue to the last bit
            return lam, y, True
        w = lu.solve(np.asarray((A1 + (2 * lam) * A2) @ y, dtype=complex))
        cw = np.dot(c, w)
        if cw == 0 or not np.isfinite(cw):
            return lam, y, False
        step = 1.0 / cw  # c* y = 1
        lam = lam - step
        y = w / cw
        if abs(step) <= tol * max(abs(lam), 1e-300):
            return lam, y, True
        if abs(step) > 0.25 * last and abs(step) <= 1e3 * tol * abs(lam):  # no longer quadratic: at round-off
            return lam, y, True
        last = abs(step)
    return lam, y, False
