"""Rung 3: the spectra of buckled, whirling relative equilibria along branches (dimensionless).

The O(delta) linearisation of Sec. V B of arXiv:0810.3668 (eqs. (71)-(75),
boundary conditions (76)-(81); Appendix A with the errata of docs/errata.md) about
a non-trivial base state is :func:`etcheck.rod.core.linear.linear_operator` with an
:class:`~etcheck.rod.buckled.equilibria.Equilibrium` as the base; this module forms it with its damping
separated (A1 = G + gamma D) and follows its least-|lambda| eigenvalues along branches, with labels.

**Errors.** Every eigenvalue carries (i) the operator error: the same base
state linearised at N and at M = ``check_resolution(N)``, partners paired by
distance; (ii) at every ``state_stride``-th point the base-state error: the
equilibrium re-solved (Newton) at resolution M and the spectrum recomputed at
M about it.

Mode labels. A mode's elastic energy is split into the parts stored in the
perturbed body curvatures kappa_j = a' . d_j0 (eq. (74)):
E_j = int K_j |kappa_j|^2 ds (Clenshaw-Curtis), K = (1, R, Gamma (1+R)/2)/f.
The label is the largest part: "bend-d1" (bending about d1, the stiff
bending stiffness EI1), "bend-d2" (about d2, EI2) or "torsion".
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import partial

import numpy as np
import scipy.linalg as sla
from scipy.sparse.linalg import ArpackNoConvergence, LinearOperator, eigs

from etcheck.jsonable import jsonable
from etcheck.numerics.chebyshev import clenshaw_curtis_weights
from etcheck.numerics.eigen import match_spectra
from etcheck.numerics.optimize import linear_sum_assignment
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import NFIELDS, collocation, linear_operator, stiffness_diag
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import (
    ERROR_FLOOR,
    SIGMA,
    check_resolution,
    nearest_eigenvalues,
    prefers_dense,
)
from etcheck.rod.straight.collocation.spectral import THRESHOLD
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.parallel import split_map

__all__ = [
    "LABELS",
    "branch_spectra",
    "BranchSpectra",
    "damped_operator",
    "DampedOperator",
    "mode_energies",
    "operator_eigenvalues",
    "pair_representatives",
    "point_spectrum",
    "real_positive_count",
    "static_problem",
    "stiffness_index",
]


#: Mode labels, in the order of the energy fractions.
LABELS = ("bend-d1", "bend-d2", "torsion")


# --- operators ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class DampedOperator:
    """The discretised linearisation split by its gamma dependence (dimensionless).

    A(lambda) = A0 + lambda A1(gamma) + lambda^2 A2, shapes (12(N+1), 12(N+1)):
    A1(gamma) is ``A1`` (built at gamma = 1) with its Kelvin-Voigt rows
    ``damped`` (eq. (74); no gyroscopic term there) times gamma, its other
    rows gyroscopic (Coriolis, rotary inertia). Base-state dependent only, so
    one build serves every gamma.
    """

    params: RodParameters
    N: int
    A0: np.ndarray
    A1: np.ndarray
    damped: slice
    A2: np.ndarray

    def at(self, gamma: float) -> tuple:
        """(A0, A1, A2) at damping gamma."""
        A1 = self.A1.copy()
        A1[self.damped] *= gamma
        return self.A0, A1, self.A2


def damped_operator(params: RodParameters, base, N: int) -> DampedOperator:
    """Build :class:`DampedOperator` about ``base`` at resolution N with one build of
    :func:`~etcheck.rod.core.linear.linear_operator` at gamma = 1: the Kelvin-Voigt term
    lambda gamma K kappa(q) sits only in the constitutive rows (ODE group 1, rows
    3N..6N; eq. (74)), where no gyroscopic term appears, so A1 splits by rows
    (checked against a gamma = 0 build in the tests)."""
    p0 = params.with_(gamma=0.0)
    A0, A1, A2 = linear_operator(p0.with_(gamma=1.0), base, N)
    return DampedOperator(p0, int(N), A0, A1, slice(3 * int(N), 6 * int(N)), A2)


def operator_eigenvalues(op: DampedOperator, gamma: float, nev: int, vectors: bool = False):
    """The nev eigenvalues of ``op`` at damping gamma nearest the small real shift
    (Kelvin-Voigt cluster excluded; dense QZ when the cluster is near, else
    shift-invert ARPACK; :func:`etcheck.rod.core.spectrum.nearest_eigenvalues`).
    Returns lam or (lam, Y) with Y the full QEP eigenvectors. Dimensionless.

    Which solver, and why: shift-invert ARPACK on the companion form (one
    dense LU of the 12(N+1) operator, ~60 products per solve) is the cheapest
    that meets the 1e-13 tolerance, an order of magnitude below dense QZ of the
    companion; eliminating the lambda-free unknowns (phi, m) first halves the
    companion, but its QR costs about as much as it saves. The stiffness index
    uses the linear pencil in mu = lambda^2 instead (:func:`static_problem`)."""
    p = op.params.with_(gamma=gamma)
    A0, A1, A2 = op.at(gamma)
    return nearest_eigenvalues(A0, A1, A2, nev, gamma, vectors=vectors, dense=prefers_dense(p, nev))


def mode_energies(base, Y: np.ndarray, N: int, params: RodParameters) -> np.ndarray:
    """Fractions of the elastic energy of modes Y (columns, length 12(N+1)) stored
    in the perturbed body curvatures kappa_j = a' . d_j0, j = 1, 2, 3
    (bending about d1, about d2, torsion; eq. (74)). Shape (n_modes, 3),
    rows sum to 1. Dimensionless."""
    col = collocation(N)
    Y = np.atleast_2d(np.asarray(Y).T).T
    n1 = N + 1
    a = Y.T.reshape(Y.shape[1], NFIELDS, n1)[:, 3:6, :]  # (m, 3, N+1)
    ap = np.einsum("jk,mck->mcj", col.D, a)  # a'
    D0 = base.D0(col.s)  # (N+1, 3, 3), column i = d_i
    kap = np.einsum("mcj,jci->mij", ap, D0)  # (m, 3 body, N+1)
    w = clenshaw_curtis_weights(N)
    K = stiffness_diag(params)
    E = np.einsum("mij,j->mi", np.abs(kap) ** 2, w) * K[None, :]
    tot = E.sum(axis=1, keepdims=True)
    return E / np.where(tot > 0, tot, 1.0)


def pair_representatives(lam: np.ndarray) -> np.ndarray:
    """Indices of one member per conjugate pair (Im >= 0; both members of real pairs)."""
    lam = np.asarray(lam)
    real = np.abs(lam.imag) <= 1e-10 * np.maximum(np.abs(lam), 1.0)
    return np.nonzero(real | (lam.imag > 0))[0]


def _unit(V: np.ndarray, N: int) -> np.ndarray:
    """(xi, a) part of the eigenvectors, normalised column-wise (for overlaps)."""
    W = np.asarray(V)[: 6 * (N + 1)]
    return W / np.linalg.norm(W, axis=0, keepdims=True)


def _max_real(lam: np.ndarray) -> float:
    return float(np.max(lam.real)) if lam.size else math.nan


def static_problem(op: DampedOperator, nev: int) -> np.ndarray:
    """Eigenvalues lambda of (A0 + lambda^2 A2) q = 0 (A1 = 0: no gyroscopic, no damping terms).

    Solved as the linear pencil A0 q = -mu A2 q in mu = lambda^2 (size 12(N+1),
    half the companion form of the QEP, and one mu per pair +-lambda): the
    nev // 2 mu nearest SIGMA^2 by shift-invert ARPACK (one dense LU of
    A0 + SIGMA^2 A2; infinite mu, from the lambda-free unknowns, map to 0 and
    are never returned). Returns both square roots +-sqrt(mu) of each, i.e. the
    nev lambda of least modulus, like the QEP would.
    """
    n = op.A0.shape[0]
    k = max(1, min(nev // 2, n - 2))
    s = SIGMA**2
    lu = sla.lu_factor(op.A0 + s * op.A2, check_finite=False)
    A2 = op.A2
    inv = LinearOperator((n, n), matvec=lambda z: sla.lu_solve(lu, A2 @ z, check_finite=False), dtype=float)
    try:
        theta = eigs(inv, k=k, which="LM", ncv=min(n, max(3 * k, 20)), tol=1e-13, maxiter=500,
                     return_eigenvectors=False)
    except ArpackNoConvergence as err:  # keep what converged
        theta = err.eigenvalues
    mu = s - 1.0 / theta.astype(complex)  # (A0 + s A2)^-1 A2 q = q / (s - mu)
    root = np.sqrt(mu)
    return np.concatenate([root, -root])
def real_positive_count(lam0: np.ndarray) -> int:
    real = np.abs(lam0.imag) <= 1e-8 * np.maximum(np.abs(lam0), 1.0)
    return int(np.count_nonzero(real & (lam0.real > 1e-9)))


def stiffness_index(op: DampedOperator, nev: int = 20) -> int:
    """Number of negative eigenvalues of the stiffness K (rotating frame, centrifugal
    terms included) about the operator's base state: the number of real lambda > 0
    of K q + lambda^2 M q = 0 (each mu = lambda^2 > 0 gives one), among the nev
    nearest the shift (the negative directions of K are the softest modes).
    Dimensionless."""
    return real_positive_count(static_problem(op, nev))


# --- eigenvalue paths along a branch -----------------------------------------------------


@dataclass(frozen=True, eq=False)
class BranchSpectra:
    """Least-|lambda| eigenvalue paths along a branch (dimensionless).

    ``values`` (n,): the branch parameter (``parameter``, "B" or "omega") at
    each point; ``eigenvalues`` (n, k) complex: k paths, one member per
    conjugate pair (Im >= 0), followed continuously from point to point by
    eigenvector overlap (Hungarian assignment on 1 - |<v_i, w_j>| plus the
    scaled eigenvalue distance); ``labels`` (n, k): "bend-d1"/"bend-d2"/
    "torsion"; ``energy`` (n, k, 3): energy fractions (:func:`mode_energies`);
    ``errors`` (n, k): operator error |lambda_N - lambda_M| / max(|lambda_M|, 0.1)
    (inf: no partner at M); ``state_errors`` (n, k): base-state error (same
    scaling; NaN where the state was not re-solved); ``max_real`` (n,): max
    Re lambda over all computed eigenvalues (2k + 8 nearest the shift,
    Kelvin-Voigt cluster excluded), ``max_real_error`` (n,) its two-resolution
    change; ``stable`` (n,): max_real <= THRESHOLD (1e-9 absolute; at
    gamma = 0 the threshold is relative, 1e-8 |lambda|, for the neutral
    spectrum); ``index`` (n,): number of negative eigenvalues of the stiffness K
    (:func:`stiffness_index`; Kelvin-Tait-Chetaev: the number of unstable
    eigenvalues for any gamma > 0; -1 where not asked for, see
    :func:`branch_spectra`); ``decided`` (n,): whether the flag is
    trustworthy: |max_real| > 2 max_real_error; at gamma = 0 the neutral
    spectrum's real parts are pure discretisation error (the collocation
    breaks the Hamiltonian symmetry at the level of its error), so there a
    point with index 0 is stable (Lagrange-Dirichlet, K > 0, whatever the
    gyroscopic terms) and decided, and one with index > 0 is decided only
    when |max_real| > 2 max_real_error;
    ``crossings``: (i, j_old, j_new) where path identity was ambiguous
    (overlap < 0.5); ``spectra`` (n,): per state the 2k + 8 eigenvalues nearest
    the shift at N and at N_check that the paths were picked from.
    """

    name: str
    parameter: str
    gamma: float
    k: int
    N: int
    N_check: int
    values: np.ndarray
    eigenvalues: np.ndarray
    labels: np.ndarray
    energy: np.ndarray
    errors: np.ndarray
    state_errors: np.ndarray
    max_real: np.ndarray
    max_real_error: np.ndarray
    stable: np.ndarray
    decided: np.ndarray
    index: np.ndarray
    crossings: tuple
    time: float
    states: tuple = field(default=(), repr=False)
    spectra: tuple = field(default=(), repr=False)

    @property
    def error(self) -> float:
        """Largest error estimate (operator and base state) over all paths and points."""
        e = np.concatenate([self.errors.ravel(), self.state_errors[np.isfinite(self.state_errors)].ravel()])
        return float(np.max(e)) if e.size else math.nan

    def as_dict(self) -> dict:
        """JSON-able data (no states)."""
        return jsonable({
            "name": self.name, "parameter": self.parameter, "gamma": self.gamma, "k": self.k, "N": self.N,
            "N_check": self.N_check, "values": self.values, "eigenvalues": self.eigenvalues,
            "labels": self.labels.tolist(), "energy": self.energy.tolist(), "errors": self.errors,
            "state_errors": self.state_errors, "max_real": self.max_real, "max_real_error": self.max_real_error,
            "stable": self.stable.tolist(), "decided": self.decided.tolist(), "index": self.index.tolist(),
            "crossings": [list(c) for c in self.crossings], "time": self.time,
        })


def point_spectrum(state, gamma: float, nev: int, N: int, vectors: bool, op: DampedOperator | None = None):
    op = damped_operator(state.params, state, N) if op is None else op
    return operator_eigenvalues(op, gamma, nev, vectors)


def _state_spectra(job: tuple, gamma: float, nev: int, N: int, M: int, stiffness: bool = True) -> tuple:
    """What :func:`branch_spectra` needs of one state, independent of the others: (lam, V) at N, lam at M,
    the stiffness index (-1 unless ``stiffness``) and, when the job asks for the check, lam of the state re-solved
    at M (None when it cannot be re-solved: a branch point)."""
    st, check = job
    p = st.params.with_(gamma=gamma)
    st_g = st.with_params(p) if st.params != p else st
    op = damped_operator(p, st_g, N)
    lam, V = point_spectrum(st_g, gamma, nev, N, True, op)
    lam_M = point_spectrum(st_g, gamma, nev, M, False)
    lam_S = None
    if check:
        try:
            lam_S = point_spectrum(eq.solve_equilibrium(p, st_g, M), gamma, nev, M, False)
        except Exception:  # noqa: BLE001 - a state that cannot be re-solved (branch point) stays unchecked
            pass
    return lam, V, lam_M, stiffness_index(op, nev) if stiffness else -1, lam_S


def _is_stable(lam: np.ndarray, gamma: float) -> bool:
    if lam.size == 0:
        return False
    thr = THRESHOLD if gamma > 0 else np.maximum(THRESHOLD, 1e-8 * np.abs(lam))
    return bool(np.all(lam.real <= thr))


@single_blas_thread
def branch_spectra(branch, gamma: float, k: int = 6, N: int | None = None, state_stride: int = 5,
                   name: str | None = None, stiffness: bool = True) -> BranchSpectra:
    """Eigenvalue paths of the k least-|lambda| pairs along ``branch`` at damping gamma.

    ``branch``: a :class:`~etcheck.rod.buckled.branches.Branch` (or any sequence of
    :class:`~etcheck.rod.buckled.equilibria.Equilibrium` with a common N, parameter
    taken from the branch or "B"). Linearisation eqs. (71)-(75)
    about each state at N (default: the state's N) and
    M = check_resolution(N); every ``state_stride``-th point (and the last)
    is re-solved at M for the base-state error (0 disables).
    ``stiffness=False`` leaves out the stiffness index of damped states (-1;
    a tenth of the cost, and the paths do not need it); undamped, it decides
    stability and is always computed. See :class:`BranchSpectra` for the
    fields. Dimensionless.
    """
    t0 = time.perf_counter()
    states = tuple(branch.states) if hasattr(branch, "states") else tuple(branch)
    parameter = getattr(branch, "parameter", "B")
    nm = name or getattr(branch, "name", "branch")
    N0 = states[0].N if N is None else int(N)
    M = check_resolution(N0)
    nev = 2 * k + 8
    n = len(states)
    lam_paths = np.full((n, k), np.nan + 0j)
    energy = np.full((n, k, 3), np.nan)
    errs = np.full((n, k), np.inf)
    serrs = np.full((n, k), np.nan)
    maxre = np.full(n, np.nan)
    maxre_err = np.full(n, np.nan)
    stable = np.zeros(n, dtype=bool)
    decided = np.zeros(n, dtype=bool)
    index = np.zeros(n, dtype=int)
    crossings = []
    prev_vec = prev_lam = None
    check_idx = set(range(0, n, state_stride)) | {n - 1} if state_stride else set()
    work = partial(_state_spectra, gamma=gamma, nev=nev, N=N0, M=M, stiffness=stiffness or gamma == 0)
    solved = split_map(work, [(st, i in check_idx) for i, st in enumerate(states)], min_items=8)
    for i, (st, (lam, V, lam_M, index[i], lam_S)) in enumerate(zip(states, solved)):
        p = st.params.with_(gamma=gamma)
        st_g = st.with_params(p) if st.params != p else st
        maxre[i] = _max_real(lam)
        maxre_err[i] = abs(_max_real(lam_M) - maxre[i]) if lam_M.size else math.inf
        stable[i] = _is_stable(lam, gamma)
        decided[i] = abs(maxre[i]) > 2.0 * maxre_err[i]
        if gamma == 0 and index[i] == 0:
            stable[i] = decided[i] = True
        rep = pair_representatives(lam)
        rep = rep[np.argsort(np.abs(lam[rep]), kind="stable")]
        cand_lam = lam[rep]
        cand_vec = _unit(V[:, rep], N0)
        if prev_vec is None:
            pick = np.full(k, -1)
            pick[: min(k, rep.size)] = np.arange(min(k, rep.size))
        else:
            ov = np.abs(prev_vec.conj().T @ cand_vec)  # (k, m)
            dist = np.abs(prev_lam[:, None] - cand_lam[None, :]) / np.maximum(np.abs(prev_lam), ERROR_FLOOR)[:, None]
            cost = (1.0 - ov) + 0.5 * np.minimum(dist, 10.0)
            cost = np.where(np.isfinite(cost), cost, 1e6)
            r, c = linear_sum_assignment(cost)
            pick = np.full(k, -1)
            pick[r] = c
            for j in r:
                if ov[j, pick[j]] < 0.5:
                    crossings.append((i, int(j), int(pick[j])))
        pick = np.asarray(pick)
        good = pick >= 0
        sel = rep[pick[good]]
        lam_paths[i, good] = lam[sel]
        energy[i, good] = mode_energies(st_g, V[:, sel], N0, p)
        m = match_spectra(lam[sel], lam_M, accept=np.inf, floor=ERROR_FLOOR)
        e = np.full(sel.size, np.inf)
        e[m.index] = m.errors
        errs[i, good] = e
        if lam_S is not None:
            ms = match_spectra(lam_M, lam_S, accept=np.inf, floor=ERROR_FLOOR)
            # base-state error of each path: its M-partner vs the re-solved state's spectrum
            eS = np.full(sel.size, np.nan)
            mm = match_spectra(lam[sel], lam_M, accept=np.inf, floor=ERROR_FLOOR)
            # ms pairs lam_M (index) with lam_S (partner); mm pairs the paths with lam_M
            err_of = dict(zip(ms.index.tolist(), ms.errors.tolist()))
            for a, b in zip(mm.index.tolist(), mm.partner.tolist()):
                eS[a] = err_of.get(b, np.inf)
            serrs[i, good] = eS
        prev_lam = np.where(good, lam_paths[i], prev_lam if prev_lam is not None else np.nan)
        pv = np.zeros((6 * (N0 + 1), k), dtype=complex) if prev_vec is None else prev_vec.copy()
        pv[:, good] = cand_vec[:, pick[good]]
        prev_vec = pv
    labels = np.array([[LABELS[int(np.argmax(energy[i, j]))] if np.all(np.isfinite(energy[i, j])) else ""
                        for j in range(k)] for i in range(n)])
    values = np.array([getattr(s.params, parameter) for s in states])
    return BranchSpectra(nm, parameter, float(gamma), k, N0, M, values, lam_paths, labels, energy, errs, serrs,
                         maxre, maxre_err, stable, decided, index, tuple(crossings), time.perf_counter() - t0, states,
                         tuple((lam, lam_M) for lam, _, lam_M, _, _ in solved))
