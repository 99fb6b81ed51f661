"""The symmetries of the welded problem (dimensionless; Secs. V A and VII of arXiv:0810.3668,
docs/model.md section 7): the involutions S1, S2, their action on a state and on updates, and
bases of their fixed-point and antisymmetric spaces.

Symmetry. The welded problem is equivariant under the involutions

    S_Q: x(s) -> Q x(1-s) + (x3(0) + x3(1)) e3,  D(s) -> Q D(1-s) Q,
         F(s) -> -Q F(1-s),  M(s) -> -Q M(1-s),

with Q = diag(1, -1, -1) (``"S1"``: s -> 1-s and a half-turn about e1) or
Q = diag(-1, 1, -1) (``"S2"``: half-turn about e2), for every B, omega, T, R
(Lorentz, centrifugal and rotary-inertia terms all commute with Q; the
sliding-end position z0 = x3(0) is kept). Their linear action S on an update
(xi, a, phi, m) is xi(s) -> Q xi(1-s) + (xi3(0) + xi3(1)) e3,
a(s) -> Q a(1-s), phi(s) -> -Q phi(1-s), m(s) -> -Q m(1-s) (an exact
involution, :func:`symmetry_matrix`); on the residual rows it acts by a
constant matrix S_row = J S J^{-1}, computed once per N at a regular straight
state (equivariance J S = S_row J is checked at another state and, in the
tests, on a buckled one). Each doubly degenerate pitchfork of the straight rod is simple
inside Fix(S1) and inside Fix(S2): the primary branches are continued with
Newton restricted to the fixed-point space (square restricted Jacobian
L_+ J V_+, with V_+ / L_+ orthonormal bases of the +1 eigenspaces of S and
S_row^T), which also keeps them exactly symmetric. Symmetry-breaking
(secondary) branch points on a primary branch are zeros of the Jacobian
restricted to the -1 eigenspace, L_- J V_-; they are detected by the sign
change of a continuous test function (sign det times a smallest-singular-value
estimate) and the connecting branch (b12) is followed in the full space from
the kernel of L_- J V_-.

"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sparse
from scipy.sparse.csgraph import connected_components

from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import NFIELDS
from etcheck.rod.core.parameters import RodParameters

__all__ = [
    "BRANCH_CLASS",
    "SYMMETRIES",
    "null_bases_2x2",
    "null_basis",
    "reflect",
    "symmetry_bases",
    "symmetry_class",
    "symmetry_matrix",
    "SymmetryBases",
]


SYMMETRIES = {"S1": np.array([1.0, -1.0, -1.0]), "S2": np.array([-1.0, 1.0, -1.0])}
#: symmetry class of the paper's primary branches from BP1
BRANCH_CLASS = {"b1": "S1", "b2": "S2"}


def symmetry_class(which: str) -> str:
    which = BRANCH_CLASS.get(which, which)
    if which not in SYMMETRIES:
        raise ValueError(f"unknown branch/symmetry {which!r}; use 'b1', 'b2', 'S1' or 'S2'")
    return which


# --- symmetry --------------------------------------------------------------------------


@lru_cache(maxsize=16)
def symmetry_matrix(N: int, which: str) -> np.ndarray:
    """Linear action S of the involution ``which`` on updates (xi, a, phi, m), shape (n, n).

    n = 12 (N+1), ``linear.VARIABLES`` ordering; S @ S = I exactly.
    """
    q = SYMMETRIES[symmetry_class(which)]
    n1 = N + 1
    S = np.zeros((NFIELDS * n1, NFIELDS * n1))
    signs = np.concatenate([q, q, -q, -q])
    j = np.arange(n1)
    for c in range(NFIELDS):
        S[c * n1 + j, c * n1 + (N - j)] = signs[c]
    z = 2 * n1  # xi3 block: xi3~(s) = -xi3(1-s) + xi3(0) + xi3(1)
    S[z + j, z] += 1.0
    S[z + j, z + N] += 1.0
    S.setflags(write=False)
    return S


def reflect(state: eq.Equilibrium, which: str) -> eq.Equilibrium:
    """The image S(state) of an equilibrium under the involution ``which`` (dimensionless)."""
    Q = np.diag(SYMMETRIES[symmetry_class(which)])
    x = state.x[::-1] @ Q
    x[:, 2] += state.x[0, 2] + state.x[-1, 2]
    D = np.einsum("ab,nbc,cd->nad", Q, state.D[::-1], Q)
    return eq.Equilibrium(state.params, x, D, -state.F[::-1] @ Q, -state.M[::-1] @ Q)


@dataclass(frozen=True, eq=False)
class SymmetryBases:
    """Orthonormal bases of the +/-1 eigenspaces of S (columns of V) and of S_row^T (rows of L).

    V and L are sparse (``scipy.sparse``): S and S_row are block diagonal with
    blocks of one or two unknowns (rows) except the axial-displacement block
    (the tension row), and each basis is built block by block, so that the
    restricted Jacobians L J V cost two sparse-dense products instead of two
    dense matrix products.

    ``equivariance`` is ||J S - S_row J|| / ||J|| at a second (curved-free)
    check state: rounding level when the row action is state independent.
    """

    which: str
    N: int
    S: np.ndarray
    S_row: np.ndarray
    V_plus: np.ndarray
    V_minus: np.ndarray
    L_plus: np.ndarray
    L_minus: np.ndarray
    equivariance: float


def _components(A: np.ndarray) -> list[np.ndarray]:
    """Index sets of the diagonal blocks of A (connected components of the pattern of A + A^T)."""
    pattern = sparse.csr_array((A != 0) | (A.T != 0))
    n, labels = connected_components(pattern, directed=False)
    order = np.argsort(labels, kind="stable")
    return np.split(order, np.cumsum(np.bincount(labels, minlength=n))[:-1])


def _eigenspace(A: np.ndarray, sign: float, blocks: list[np.ndarray]) -> sparse.csc_array:
    """Orthonormal basis (columns) of ker(A - sign I) for A block diagonal on ``blocks``:
    per block its kernel as scipy.linalg.null_space finds it (rcond 1e-9), so the basis is as sparse as A's
    blocks. Most blocks are 2 x 2 (the signed permutation s -> 1 - s pairs the collocation points): their
    kernels are written out, all at once (:func:`null_bases_2x2`); the few others by one small SVD each."""
    kernels: list = [None] * len(blocks)
    for size in sorted({b.size for b in blocks}):
        which = [i for i, b in enumerate(blocks) if b.size == size]
        idx = np.stack([blocks[i] for i in which])
        Ms = A[idx[:, :, None], idx[:, None, :]] - sign * np.eye(size)
        if size == 2:
            for i, Z in zip(which, null_bases_2x2(Ms)):
                kernels[i] = Z
            continue
        for i, M in zip(which, Ms):
            kernels[i] = null_basis(M)
    rows, cols, vals, k = [], [], [], 0
    for idx, Z in zip(blocks, kernels):
        Z[np.abs(Z) < 1e-15] = 0.0
        r, c = np.nonzero(Z)
        rows.append(idx[r])
        cols.append(c + k)
        vals.append(Z[r, c])
        k += Z.shape[1]
    return sparse.csc_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(A.shape[0], k))


def null_basis(M: np.ndarray) -> np.ndarray:
    """Orthonormal basis (columns) of ker M: the right singular vectors of singular values at or below 1e-9 of
    the largest (as scipy.linalg.null_space)."""
    _, sv, vh = sla.svd(M, lapack_driver="gesvd", check_finite=False)
    rank = int(np.sum(sv > 1e-9 * sv.max(initial=0.0)))
    return vh[rank:].T.conj()


def null_bases_2x2(Ms: np.ndarray) -> list[np.ndarray]:
    """:func:`null_basis` of each 2 x 2 matrix of the stack Ms (m, 2, 2) at once: the singular values from the
    Frobenius norm and the determinant (s_max^2 + s_min^2 = |M|_F^2, s_max s_min = |det M|); a matrix of rank 1
    has the unit vector orthogonal to its larger row as its kernel, one of rank 2 none; the zero matrix (kernel:
    the plane) by the SVD."""
    fro2 = np.einsum("mij,mij->m", Ms, Ms)
    det = Ms[:, 0, 0] * Ms[:, 1, 1] - Ms[:, 0, 1] * Ms[:, 1, 0]
    s_max = np.sqrt(0.5 * (fro2 + np.sqrt(np.maximum(fro2**2 - 4.0 * det**2, 0.0))))
    with np.errstate(divide="ignore", invalid="ignore"):
        s_min = np.abs(det) / s_max
    rows = np.where((np.abs(Ms[:, 0]).sum(axis=1) >= np.abs(Ms[:, 1]).sum(axis=1))[:, None], Ms[:, 0], Ms[:, 1])
    v = np.stack([-rows[:, 1], rows[:, 0]], axis=1)
    v /= np.linalg.norm(v, axis=1, keepdims=True).clip(min=1e-300)
    out = []
    for M, smax, smin, vk in zip(Ms, s_max, s_min, v):
        if smax == 0.0:
            out.append(null_basis(M))
        elif smin > 1e-9 * smax:
            out.append(np.zeros((2, 0)))
        else:
            out.append(vk[:, None])
    return out


@lru_cache(maxsize=16)
def _bases(N: int, which: str, P: float, R: float, Gamma: float, f: float) -> SymmetryBases:
    S = symmetry_matrix(N, which)
    p = RodParameters(P=P, R=R, Gamma=Gamma, f=f, B=0.37 * 7.33**3 * math.sqrt(R) / f, omega=0.3, T=0.1)
    J0 = eq.jacobian(p, eq.straight_state(p, N))
    # S_row = J0 S J0^{-1}: a signed permutation on the collocation rows (t_k -> t_{N-1-k}) and on the
    # boundary rows, except the sliding-end tension row F3(0) - T, which maps to F3(1) - T = that row plus
    # the quadrature of the F3' rows; entries below rounding are the zeros of that structure
    S_row = np.linalg.solve(J0.T, (J0 @ S).T).T
    S_row[np.abs(S_row) < 1e-12 * np.max(np.abs(S_row))] = 0.0
    S_row.setflags(write=False)
    p2 = p.with_(B=0.9 * p.B, omega=0.7, T=-0.05)
    J2 = eq.jacobian(p2, eq.straight_state(p2, N))
    equiv = float(np.max(np.abs(J2 @ S - S_row @ J2)) / np.max(np.abs(J2)))
    n = S.shape[0]
    cols, rows = _components(S), _components(S_row)
    Vp, Vm = _eigenspace(S, 1.0, cols), _eigenspace(S, -1.0, cols)
    Lp, Lm = _eigenspace(S_row.T, 1.0, rows), _eigenspace(S_row.T, -1.0, rows)
    if Vp.shape[1] != Lp.shape[1] or Vm.shape[1] != Lm.shape[1] or Vp.shape[1] + Vm.shape[1] != n:
        raise RuntimeError(f"symmetry bases inconsistent: {Vp.shape}, {Vm.shape}, {Lp.shape}, {Lm.shape}")
    return SymmetryBases(which, N, S, S_row, Vp, Vm, Lp.T.tocsr(), Lm.T.tocsr(), equiv)


def symmetry_bases(params: RodParameters, N: int, which: str) -> SymmetryBases:
    """Cached :class:`SymmetryBases` for resolution N (depend on P, R, Gamma, f only through
    the check state; the eigenspaces themselves are parameter independent)."""
    return _bases(int(N), symmetry_class(which), params.P, params.R, params.Gamma, params.f)
