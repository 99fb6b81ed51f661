"""Generic pencil and QEP tools of etcheck.numerics.eigen against dense references (scipy's QZ, explicit Q)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla

from etcheck.numerics.eigen import eliminate_static, factor_static, pencil_eigenvalues


def _qz_roots(A0: np.ndarray, n0: np.ndarray) -> np.ndarray:
    alpha, beta = sla.eig(A0, -n0, right=False, homogeneous_eigvals=True)
    ok = np.abs(beta) > 1e-13 * np.abs(alpha)
    return alpha[ok] / beta[ok]


def _same_roots(a: np.ndarray, b: np.ndarray, rtol: float) -> bool:
    """Every root of each set next to one of the other (conjugate pairs come in either order)."""
    d = np.abs(a[:, None] - b[None, :]) / np.maximum(np.abs(b), 1.0)[None, :]
    return a.size == b.size and bool(np.all(d.min(axis=1) <= rtol) and np.all(d.min(axis=0) <= rtol))


@pytest.mark.parametrize("reach", [5, 30, 60])  # columns n0 reaches: a few, half, all
def test_pencil_roots_agree_with_qz_whatever_columns_the_derivative_reaches(reach):
    rng = np.random.default_rng(reach)
    n = 60
    A0 = rng.standard_normal((n, n)) + 4.0 * np.eye(n)
    n0 = np.zeros((n, n))
    cols = rng.choice(n, reach, replace=False)
    n0[:, cols] = rng.standard_normal((n, reach))
    fast = pencil_eigenvalues(A0, n0)
    assert fast.size == reach  # n0 of rank `reach`: as many finite roots
    assert _same_roots(fast, _qz_roots(A0, n0), 1e-11)


def test_pencil_roots_next_to_zero_take_qz():
    # A0 singular to round-off: the root x = 0 of A0 + x n0 comes from QZ (the low-rank route needs A0 regular)
    rng = np.random.default_rng(7)
    n = 40
    U, _, Vt = np.linalg.svd(rng.standard_normal((n, n)))
    s = np.linspace(1.0, 2.0, n)
    s[-1] = 1e-15
    A0 = U @ np.diag(s) @ Vt
    n0 = rng.standard_normal((n, n))
    x = pencil_eigenvalues(A0, n0)
    assert np.min(np.abs(x)) < 1e-12
    assert _same_roots(x, _qz_roots(A0, n0), 1e-8)


def test_factor_static_reduces_like_an_explicit_q():
    rng = np.random.default_rng(3)
    n, r = 30, 12
    drop = np.arange(n - r, n)
    A0, A1, A2 = (rng.standard_normal((n, n)) for _ in range(3))
    A1[:, drop] = A2[:, drop] = 0.0
    sparse = np.zeros((n, n))
    sparse[:, [1, 4]] = rng.standard_normal((n, 2))  # a derivative that reaches two columns
    Q, _ = np.linalg.qr(A0[:, drop], mode="complete")
    keep = np.arange(n - r)
    factor = factor_static(A0, drop)
    for got, A in zip(factor.reduce(A0, A1, A2, sparse), (A0, A1, A2, sparse)):
        np.testing.assert_allclose(np.abs(got), np.abs(Q[:, r:].T @ A[:, keep]), atol=1e-12)  # Q2 up to signs
    el = eliminate_static(A0, A1, A2, drop)
    for got, ref in zip((el.B0, el.B1, el.B2), factor.reduce(A0, A1, A2)):
        np.testing.assert_array_equal(got, ref)
    assert not np.any(factor.reduce(sparse)[0][:, [0, 2, 3]])  # columns it does not reach stay exactly zero


def test_sparse_solvers_started_on_an_exact_eigenvalue_do_not_raise():
    """A tracked eigenvalue that lands on an eigenvalue to the last bit makes Q(lambda) exactly singular (SuperLU
    raises): inverse iteration has converged there; a shift on an eigenvalue is moved next to it."""
    import scipy.sparse as sp

    from etcheck.numerics.eigen import qep_newton, sparse_qep_nearest

    A0 = sp.diags([1.0, 4.0, 9.0, 16.0]).tocsc()
    A1 = sp.csc_matrix((4, 4))
    A2 = sp.identity(4, format="csc")
    lam, y, ok = qep_newton(A0, A1, A2, 1j, np.array([1.0, 0.1, 0.0, 0.0], dtype=complex))
    assert ok and lam == 1j
    near = sparse_qep_nearest(A0, A1, A2, k=2, sigma=-1.0)  # Q(-1) = A0 + A2 is regular
    assert np.allclose(np.sort(np.abs(near)), [1.0, 1.0])
    on = sparse_qep_nearest(A0, A1, A2, k=1, sigma=2j)  # Q(2i) = A0 - 4 A2 is exactly singular
    assert np.allclose(on, [2j])
