"""Rung 3: stability of buckled, whirling relative equilibria (dimensionless).

The O(delta) linearisation of Sec. V B of arXiv:0810.3668 (eqs. (71)-(75),
boundary conditions (76)-(81); Appendix A with the errata of docs/errata.md) about
a non-trivial base state is :func:`etcheck.rod.core.linear.linear_operator` with an
:class:`~etcheck.rod.buckled.equilibria.Equilibrium` as the base; this module follows
its least-|lambda| eigenvalues along branches, locates the secondary
(symmetry-breaking) pitchfork of b1 as a curve B*(omega) (Secs. VII A, VIII), looks
for Hopf points (Sec. VII B, Fig. 19) and maps the damping margin.

**Structure (checked, not assumed; :func:`structure_check`).** In the
rotating frame the discretised linearisation is
A0 + lambda A1 + lambda^2 A2 with A1 = G + gamma D: every term linear in
lambda is either gyroscopic (Coriolis, rotary-inertia gyroscopic coupling) or
Kelvin-Voigt damping (the factor (1 + gamma lambda) of eq. (74)),
so A1 is affine in gamma, and dropping A1 leaves the non-gyroscopic undamped
problem K q + M q'' = 0 whose eigenvalues mu = lambda^2 are real when K is
symmetric (M > 0). Then (Kelvin-Tait-Chetaev, complete damping) the number of
eigenvalues with Re lambda > 0 for every gamma > 0 equals the number of
negative eigenvalues of K, i.e. the number of mu > 0; stability of an
equilibrium can only change where A0 is singular (a static bifurcation: the
primary and secondary pitchforks), never in a Hopf bifurcation. The solver
checks this independently (:func:`find_hopf` bisects on the complex modes).

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

from etcheck.errors import SolverError
from etcheck.numerics.blas import single_blas_thread
from etcheck.numerics.chebyshev import clenshaw_curtis_weights
from etcheck.numerics.eigen import match_spectra
from etcheck.numerics.optimize import linear_sum_assignment
from etcheck.numerics.parallel import split_map
from etcheck.rod.buckled import branches as br
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import NFIELDS, collocation, linear_operator, stiffness_diag
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import (
    ERROR_FLOOR,
    SIGMA,
    check_resolution,
    damping_cluster,
    nearest_eigenvalues,
    prefers_dense,
)
from etcheck.rod.straight.spectral import THRESHOLD

__all__ = [
    "HOPF_GAMMAS",
    "MAP_ACCEPT",
    "LABELS",
    "BranchSpectra",
    "PitchforkPoint",
    "PitchforkCurve",
    "HopfPoint",
    "HopfScan",
    "StructureCheck",
    "DampingMap",
    "DampedOperator",
    "damped_operator",
    "operator_eigenvalues",
    "b1_spin_branch",
    "mode_energies",
    "branch_spectra",
    "b1_state",
    "first_break",
    "secondary_pitchfork",
    "secondary_pitchfork_curve",
    "find_hopf",
    "structure_check",
    "stiffness_index",
    "damping_map",
]

#: The damping values of Fig. 19 (Sec. VII B), outside to inside.
HOPF_GAMMAS = (0.01, 0.013, 0.016, 0.02, 0.022)
#: Two-resolution acceptance of a mode in :func:`damping_map` (relative, absolute below 0.1).
MAP_ACCEPT = 1e-2
#: Mode labels, in the order of the energy fractions.
LABELS = ("bend-d1", "bend-d2", "torsion")


def _jsonable(x):
    if isinstance(x, np.ndarray):
        if np.iscomplexobj(x):
            return {"real": _jsonable(x.real), "imag": _jsonable(x.imag)}
        return [_jsonable(v) for v in x] if x.ndim > 1 else [None if (isinstance(v, float) and not math.isfinite(v))
                                                             else v for v in x.tolist()]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.bool_,)):
        return bool(x)
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    return x


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
    that meets the 1e-13 tolerance: 17 ms at N = 32 and 38 ms at N = 48 (one
    core, a buckled SET state), against ~0.3 s for dense QZ of the companion;
    eliminating the lambda-free unknowns (phi, m) first halves the companion,
    but its QR costs as much as it saves (11 + 7 ms at N = 32, 30 + 10 ms at
    N = 48). The stiffness index uses the linear pencil in mu = lambda^2
    instead (:func:`_static_problem`)."""
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


def _rep(lam: np.ndarray) -> np.ndarray:
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
        return _jsonable({
            "name": self.name, "parameter": self.parameter, "gamma": self.gamma, "k": self.k, "N": self.N,
            "N_check": self.N_check, "values": self.values, "eigenvalues": self.eigenvalues,
            "labels": self.labels.tolist(), "energy": self.energy.tolist(), "errors": self.errors,
            "state_errors": self.state_errors, "max_real": self.max_real, "max_real_error": self.max_real_error,
            "stable": self.stable.tolist(), "decided": self.decided.tolist(), "index": self.index.tolist(),
            "crossings": [list(c) for c in self.crossings], "time": self.time,
        })


def _point_spectrum(state, gamma: float, nev: int, N: int, vectors: bool, op: DampedOperator | None = None):
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
    lam, V = _point_spectrum(st_g, gamma, nev, N, True, op)
    lam_M = _point_spectrum(st_g, gamma, nev, M, False)
    lam_S = None
    if check:
        try:
            lam_S = _point_spectrum(eq.solve_equilibrium(p, st_g, M), gamma, nev, M, False)
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
        rep = _rep(lam)
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


# --- b1 states and the secondary pitchfork curve -----------------------------------------


@dataclass(frozen=True)
class PitchforkPoint:
    """Secondary pitchfork of b1 at spin omega (dimensionless).

    Located as the symmetry-breaking branch point of the Fix(S1) continuation
    of b1 in B (a bracketed root of the restricted test function) at two
    resolutions: ``B`` is the value at the finer one, max(``N``,
    ``N_check``), ``B_check`` the value at the other; ``error`` = |B -
    B_check|: the change of the coarser value, which bounds the error of the
    finer one (the collocation converges spectrally; checked against a much
    finer resolution in the tests). NaN when N_check = N (one resolution).
    ``measure1`` of the state there (finer resolution)."""

    omega: float
    B: float
    B_check: float
    error: float
    N: int
    N_check: int
    measure1: float
    time: float


@dataclass(frozen=True)
class PitchforkCurve:
    """The curve B*(omega) of secondary pitchforks of b1 (Secs. VII A, VIII; Fig. 19)."""

    points: tuple

    @property
    def omega(self) -> np.ndarray:
        return np.array([p.omega for p in self.points])

    @property
    def B(self) -> np.ndarray:
        return np.array([p.B for p in self.points])

    @property
    def error(self) -> np.ndarray:
        return np.array([p.error for p in self.points])

    def at(self, omega: float) -> float:
        """B*(omega) by linear interpolation in the table."""
        return float(np.interp(omega, self.omega, self.B))

    def as_dict(self) -> dict:
        return _jsonable({"omega": self.omega, "B": self.B, "error": self.error,
                          "points": [p.__dict__ for p in self.points]})


def _b1_reference(params: RodParameters, B_ref: float, N: int):
    """State on b1 at (B_ref, omega = 0) (Fix(S1) continuation from BP1)."""
    p0 = params.with_(omega=0.0, gamma=0.0, T=params.T)
    start = br.primary_branches(p0, 1, N)[0]
    b = br.continue_branch(p0, start, stop=(0.0, B_ref + 0.2), ds=0.05)
    return br.state_at(b, B_ref)


_OMEGA_BRANCH_CACHE: dict = {}


@dataclass(frozen=True, eq=False)
class _Single:
    """A one-state stand-in for an omega branch that stays at omega = 0."""

    state: eq.Equilibrium

    @property
    def states(self) -> tuple:
        return (self.state,)

    @property
    def values(self) -> np.ndarray:
        return np.array([0.0])


def b1_spin_branch(params: RodParameters, B_ref: float, omega_max: float, N: int = 32):
    """b1 at fixed B = B_ref continued in omega from 0 to omega_max inside Fix(S1)
    (Figs. 17 and 18 use B_ref = 1.2):
    BP1 -> (B_ref, 0) in B, then in omega. A :class:`~etcheck.rod.buckled.branches.Branch`
    (parameter "omega"); cached per (P, R, Gamma, f, T, B_ref, N). Dimensionless."""
    key = (params.P, params.R, params.Gamma, params.f, params.T, B_ref, N)
    got = _OMEGA_BRANCH_CACHE.get(key)
    if got is not None and got.values[-1] >= omega_max - 1e-12:
        return got
    ref = _b1_reference(params, B_ref, N)
    if omega_max <= 0:
        return _Single(ref)
    bw = br.continue_branch(ref.params, ref, parameter="omega", stop=(-1e-9, max(omega_max, 1e-3) + 1e-9),
                            which="S1", ds=0.05, ds_max=0.25)
    if len(_OMEGA_BRANCH_CACHE) > 8:
        _OMEGA_BRANCH_CACHE.clear()
    _OMEGA_BRANCH_CACHE[key] = bw
    return bw


def _spin_state(params: RodParameters, B_ref: float, omega: float, N: int) -> eq.Equilibrium:
    """b1 at exactly (B_ref, omega): Newton at that spin from the omega branch
    (:func:`~etcheck.rod.buckled.branches.state_at`), then in the full space at the exact parameters."""
    bw = b1_spin_branch(params, B_ref, omega, N)
    if omega == 0:
        return bw.states[0]
    st = br.state_at(bw, omega)
    return eq.solve_equilibrium(st.params.with_(omega=float(omega), B=float(B_ref)), st)


@single_blas_thread
def b1_state(params: RodParameters, B: float, omega: float, N: int = 32, B_ref: float = 1.2) -> eq.Equilibrium:
    """The b1 equilibrium (Fix(S1), Sec. VII) at (B, omega), reached by continuation:
    BP1 -> (B_ref, 0) in B, -> (B_ref, omega) in omega, then Newton at (B, omega)
    from there if B != B_ref (no fold of b1 in B lies between, Sec. VII B).
    Dimensionless; raises SolverError if Newton fails."""
    st = _spin_state(params, B_ref, omega, N)
    if B == B_ref:
        return st
    b = br.continue_branch(st.params, st, parameter="B", stop=(min(B, B_ref) - 1e-9, max(B, B_ref) + 1e-9),
                           which="S1", ds=0.05, ds_max=0.2, direction=1.0 if B > B_ref else -1.0)
    st = br.state_at(b, B)
    return eq.solve_equilibrium(st.params.with_(B=float(B)), st)


_UP_CACHE: dict = {}


def _b1_up(params: RodParameters, omega: float, N: int, B_ref: float, B_max: float):
    """b1 at fixed omega continued in B upward from B_ref to its first secondary pitchfork (or
    B_max); cached per (P, R, Gamma, f, T, omega, N, B_ref), a cached branch serving every B_max
    it reached (the damping map and the B*(omega) curve continue the same b1)."""
    key = (params.P, params.R, params.Gamma, params.f, params.T, float(omega), int(N), float(B_ref))
    got = _UP_CACHE.get(key)
    if got is not None and (got.reason == "special point (break)" or got.values[-1] >= B_max):
        return got
    st = _spin_state(params, B_ref, omega, N)
    up = br.continue_branch(st.params, st, parameter="B", stop=(B_ref - 1e-9, B_max), which="S1", ds=0.05,
                            ds_max=0.25, stop_on=("break",))
    if len(_UP_CACHE) > 64:
        _UP_CACHE.clear()
    _UP_CACHE[key] = up
    return up


def _b1_in_B(params: RodParameters, omega: float, N: int, B_ref: float, B_max: float, lower: float | None = None):
    """b1 at fixed omega continued in B upward from B_ref to its first secondary pitchfork
    (or B_max; :func:`_b1_up`), and downward to ``lower``."""
    up = _b1_up(params, omega, N, B_ref, B_max)
    st = up.states[0]
    down = None
    if lower is not None and lower < B_ref:
        down = br.continue_branch(st.params, st, parameter="B", stop=(lower, B_ref + 1e-9), which="S1", ds=0.05,
                                  ds_max=0.25, direction=-1.0)
    return up, down


def first_break(branch, above: float = -math.inf) -> br.RodBranchPoint | None:
    """The first symmetry-breaking branch point ("break") of ``branch`` with B > ``above``
    (None if there is none); raises :class:`~etcheck.errors.SolverError` when it was
    bracketed but not located (bracket wider than ``LOCATE_WIDTH``)."""
    brk = next((q for q in branch.special if q.kind == "break" and q.value > above), None)
    if brk is not None and not brk.converged:
        raise SolverError(f"secondary pitchfork of {branch.name} at N = {branch.N} not located: {brk.reason} "
                          f"(bracketed in B = [{brk.bracket[0]:.10g}, {brk.bracket[1]:.10g}])")
    return brk


def _b1_direct(params: RodParameters, N: int, B_max: float):
    """b1 from its pitchfork at the scene's omega and T, continued in B up to its first secondary
    pitchfork (or B_max; Fix(S1))."""
    start = next(s for s in br.primary_branches(params.with_(B=0.0), 1, N) if s.which == "S1")
    return br.continue_branch(params, start, stop=(0.0, B_max), N=N, stop_on=("break",))


def _b1_near(branch, N: int, B_first: float, B_ref: float | None = None):
    """b1 at resolution N from its state on ``branch`` (b1 at the other resolution) last below 0.9 B_first,
    resampled and re-solved at N, continued in B to 5 % past B_first (Fix(S1)): the branch point there
    without following b1 again from its pitchfork (``B_ref`` None) or from (B_ref, omega), which it does when
    the branch has no such state."""
    below = [s for s in branch.states if s.params.B < 0.9 * B_first]
    if not below:
        if B_ref is None:
            return _b1_direct(branch.params, N, B_first * (1.0 + 0.05))
        return _b1_in_B(branch.params, branch.params.omega, N, B_ref, B_first * (1.0 + 0.05))[0]
    start = eq.solve_equilibrium(below[-1].params, below[-1], N)
    return br.continue_branch(start.params, start, stop=(0.0, B_first * (1.0 + 0.05)), N=N, which="S1", ds=0.05,
                              ds_max=0.25, stop_on=("break",))


@single_blas_thread
def secondary_pitchfork(params: RodParameters, omega: float, N: int = 32, N_check: int | None = None,
                        B_ref: float = 1.2, B_max: float = 20.0, branch=None) -> PitchforkPoint:
    """Secondary (symmetry-breaking) pitchfork of b1 at spin omega (Secs. VII A, VIII).

    The one implementation of B* (the check's margin, the B*(omega) curve of
    the damping map and the benchmarks all come here). b1 is continued inside
    Fix(S1) in B, either from (B_ref, omega) reached through spin (works past
    b1's lift-off) or, when ``branch`` is given (b1 at this omega from its
    pitchfork, as the check's diagram continues it), from its pitchfork at
    the same omega at the other resolution; the first zero of the Jacobian
    restricted to the -1 eigenspace of S1 (kind "break") is located as a
    bracketed root (:func:`first_break`). Done at N and N_check (default
    check_resolution(N)); see :class:`PitchforkPoint` (value at the finer
    resolution, error = the change of the coarser one). Raises ValueError
    when no secondary pitchfork lies below B_max, SolverError when it is not
    located. Dimensionless.
    """
    t0 = time.perf_counter()
    Nc = check_resolution(N) if N_check is None else int(N_check)
    if branch is not None and (branch.parameter != "B" or branch.which != "S1"
                               or branch.params.omega != omega or branch.N != int(N)):
        raise ValueError("branch must be b1 (Fix(S1)) continued in B at the given omega and resolution N")
    got, first = {}, branch
    for n in sorted({int(N), Nc}, key=lambda k: k != (branch.N if branch is not None else int(N))):
        if first is not None and n == first.N:
            brk = first_break(first, above=-math.inf if branch is not None else B_ref)
        elif first is not None:  # the other resolution: from the first one's state just below its B*
            brk = first_break(_b1_near(first, n, got[first.N][0], B_ref if branch is None else None))
        else:
            first, _ = _b1_in_B(params, omega, n, B_ref, B_max)
            brk = first_break(first, above=B_ref)
        if brk is None:
            lo = 0.0 if branch is not None else B_ref
            hi = branch.values.max() if branch is not None and n == branch.N else B_max
            raise ValueError(f"no secondary pitchfork of b1 between B = {lo:g} and {hi:g} at omega = {omega} "
                             f"(N = {n})")
        got[n] = (float(brk.value), float(brk.measure1))
    fine, coarse = max(got), min(got)
    err = abs(got[fine][0] - got[coarse][0]) if fine != coarse else math.nan
    return PitchforkPoint(float(omega), got[fine][0], got[coarse][0], err, int(N), Nc, got[fine][1],
                          time.perf_counter() - t0)


@single_blas_thread
def secondary_pitchfork_curve(params: RodParameters, omegas, N: int = 32, N_check: int | None = None,
                              B_ref: float = 1.2, B_max: float = 20.0) -> PitchforkCurve:
    """B*(omega) of b1 at each omega of ``omegas`` (each point located exactly, two
    resolutions; :func:`secondary_pitchfork`). Dimensionless."""
    omegas = [float(w) for w in omegas]
    # one omega continuation serves every omega (the check resolution starts from these states: none there);
    # made here, before the spins are shared with a forked helper (two cores)
    b1_spin_branch(params, B_ref, max(omegas), int(N))
    return PitchforkCurve(tuple(split_map(lambda w: secondary_pitchfork(params, w, N, N_check, B_ref, B_max), omegas)))


# --- Hopf ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class HopfPoint:
    """A complex pair crossing Re lambda = 0: parameter bracket, eigenvalue there."""

    parameter: str
    value: float
    bracket: tuple
    eigenvalue: complex
    direction: str  # "destabilising" or "stabilising"


@dataclass(frozen=True)
class HopfScan:
    """Result of :func:`find_hopf` on one branch at one gamma (dimensionless).

    ``max_real_complex`` (n,): max Re lambda over the complex modes (Im > 1e-6)
    among the computed eigenvalues at N, ``error`` (n,): its change at
    M = check_resolution(N); ``max_real_complex_check`` (n,): the value at M;
    ``points``: located crossings (empty when there are none).
    """

    gamma: float
    parameter: str
    values: np.ndarray
    max_real_complex: np.ndarray
    max_real_complex_check: np.ndarray
    error: np.ndarray
    points: tuple
    N: int
    N_check: int
    time: float

    def as_dict(self) -> dict:
        return _jsonable({"gamma": self.gamma, "parameter": self.parameter, "values": self.values,
                          "max_real_complex": self.max_real_complex,
                          "max_real_complex_check": self.max_real_complex_check, "error": self.error,
                          "points": [{"value": p.value, "bracket": list(p.bracket),
                                      "eigenvalue": [p.eigenvalue.real, p.eigenvalue.imag],
                                      "direction": p.direction} for p in self.points],
                          "N": self.N, "N_check": self.N_check, "time": self.time})


def _complex_max(lam: np.ndarray):
    c = lam[np.abs(lam.imag) > 1e-6]
    if not c.size:
        return math.nan, complex("nan")
    j = int(np.argmax(c.real))
    return float(c.real[j]), complex(c[j])


@single_blas_thread
def find_hopf(branch, gamma: float, k: int = 6, N: int | None = None, tol: float = 1e-7) -> HopfScan:
    """Hopf points of the complex modes along ``branch`` at damping gamma.

    The max real part over the complex eigenvalues (the 2k + 8 nearest the
    shift) is evaluated at every branch point at N and M; every sign change
    between neighbours is bisected on the parameter (state re-solved by
    Newton from the nearer neighbour) to ``tol``. Dimensionless.
    """
    t0 = time.perf_counter()
    states = tuple(branch.states)
    parameter = branch.parameter
    N0 = states[0].N if N is None else int(N)
    M = check_resolution(N0)
    nev = 2 * k + 8

    def evaluate(st, n):
        p = st.params.with_(gamma=gamma)
        return _complex_max(_point_spectrum(st.with_params(p), gamma, nev, n, False))

    vals = np.array([getattr(s.params, parameter) for s in states])
    f = np.array([evaluate(s, N0)[0] for s in states])
    fM = np.array([evaluate(s, M)[0] for s in states])
    pts = []
    for i in range(len(states) - 1):
        if not (np.isfinite(f[i]) and np.isfinite(f[i + 1])) or f[i] * f[i + 1] > 0:
            continue
        lo, hi, flo = vals[i], vals[i + 1], f[i]
        st_lo = states[i]
        lam_at = complex("nan")
        while abs(hi - lo) > tol:
            mid = 0.5 * (lo + hi)
            st = eq.solve_equilibrium(st_lo.params.with_(**{parameter: mid}), st_lo)
            fm, lam_at = evaluate(st, N0)
            if fm * flo > 0:
                lo, flo, st_lo = mid, fm, st
            else:
                hi = mid
        pts.append(HopfPoint(parameter, 0.5 * (lo + hi), (lo, hi), lam_at,
                             "destabilising" if f[i] < 0 else "stabilising"))
    return HopfScan(float(gamma), parameter, vals, f, fM, np.abs(f - fM), tuple(pts), N0, M,
                    time.perf_counter() - t0)


# --- structure ------------------------------------------------------------------------------


def _static_problem(op: DampedOperator, nev: int) -> np.ndarray:
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
def _count_index(lam0: np.ndarray) -> int:
    real = np.abs(lam0.imag) <= 1e-8 * np.maximum(np.abs(lam0), 1.0)
    return int(np.count_nonzero(real & (lam0.real > 1e-9)))


def stiffness_index(op: DampedOperator, nev: int = 20) -> int:
    """Number of negative eigenvalues of the stiffness K (rotating frame, centrifugal
    terms included) about the operator's base state: the number of real lambda > 0
    of K q + lambda^2 M q = 0 (each mu = lambda^2 > 0 gives one), among the nev
    nearest the shift (the negative directions of K are the softest modes).
    Dimensionless."""
    return _count_index(_static_problem(op, nev))


@dataclass(frozen=True)
class StructureCheck:
    """Structural checks of the linearisation about one equilibrium (dimensionless).

    ``hamiltonian_defect``: at gamma = 0, max over the inner half of the
    computed eigenvalues of the distance from -lambda to the nearest computed
    eigenvalue, relative (absolute below 0.1): 0 up to discretisation error
    when the undamped spectrum is Hamiltonian (lambda, -lambda, conj);
    ``max_real_undamped``: max |Re lambda| of those when none is real-unstable
    (0: purely imaginary); ``stiffness_asymmetry``: max |Im mu| / |mu| over
    the lowest mu = lambda^2 of A0 + mu A2 (A1 = 0: no gyroscopic, no damping
    terms) -- real mu (to discretisation error) means K symmetric relative to
    M; ``index``: number of mu > 0 (negative eigenvalues of K);
    ``unstable_damped``: number of eigenvalues with Re lambda > 0 for each
    gamma in ``gammas`` (Kelvin-Tait-Chetaev: equal to ``index``);
    ``A0_smallest_singular``: smallest singular value of A0 / largest.
    """

    N: int
    hamiltonian_defect: float
    max_real_undamped: float
    stiffness_asymmetry: float
    index: int
    gammas: tuple
    unstable_damped: tuple
    A0_smallest_singular: float

    @property
    def kelvin_tait_chetaev(self) -> bool:
        return all(u == self.index for u in self.unstable_damped)


@single_blas_thread
def structure_check(state, N: int | None = None, k: int = 8, gammas=(0.01, 0.04375)) -> StructureCheck:
    """Check the structure M q'' + (G + gamma D) q' + K q = 0 of the linearisation
    about ``state`` (eqs. (71)-(75)): see :class:`StructureCheck`.
    Dimensionless."""
    N0 = state.N if N is None else int(N)
    op = damped_operator(state.params, state, N0)
    nev = 2 * k + 8
    lam = operator_eigenvalues(op, 0.0, nev, False)
    order = np.argsort(np.abs(lam))
    inner = lam[order[: max(2, lam.size // 2)]]
    d = np.abs(-inner[:, None] - lam[None, :]).min(axis=1) / np.maximum(np.abs(inner), ERROR_FLOOR)
    ham = float(np.max(d))
    mr = float(np.max(np.abs(inner.real)))
    # non-gyroscopic, undamped: (A0 + mu A2) q = 0, mu = lambda^2 -> eigenvalues of the QEP with A1 = 0
    lam0 = _static_problem(op, nev)
    mu = lam0**2
    mu_low = mu[np.argsort(np.abs(mu))][: max(2, mu.size // 2)]
    asym = float(np.max(np.abs(mu_low.imag) / np.maximum(np.abs(mu_low), 1e-300)))
    index = _count_index(lam0)  # each mu > 0 appears as the pair +-sqrt(mu)
    unstable = []
    for g in gammas:
        lg = operator_eigenvalues(op, g, nev, False)
        unstable.append(int(np.count_nonzero(lg.real > THRESHOLD)))
    sv = np.linalg.svd(op.A0, compute_uv=False)
    return StructureCheck(N0, ham, mr, asym, index, tuple(gammas), tuple(unstable), float(sv[-1] / sv[0]))


# --- damping map ----------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class DampingMap:
    """Damping margin of b1 over a (B, omega) grid under the secondary pitchfork.

    Arrays of shape (n_gamma, n_omega, n_B) (NaN where b1 does not exist
    there, i.e. below its primary pitchfork, or lies above the secondary
    pitchfork B*(omega)): ``max_real`` (max Re lambda of the least-damped
    resolved mode), ``decay`` = -max_real, ``zeta`` = -Re/|lambda| of that
    mode, ``log_decrement`` = -2 pi Re/Im (inf for a real mode),
    ``frequency`` = Im of it, ``error``: two-resolution change of max_real.
    ``curve``: the secondary pitchfork B*(omega) at the grid's omegas (located
    exactly at resolution N); ``inside`` (n_omega, n_B) bool: where b1 was
    computed; ``measure1`` (n_omega, n_B). ``timing``: seconds for the
    equilibria and for the spectra (all gammas).
    """

    B: np.ndarray
    omega: np.ndarray
    gammas: tuple
    N: int
    N_check: int
    max_real: np.ndarray
    decay: np.ndarray
    zeta: np.ndarray
    log_decrement: np.ndarray
    frequency: np.ndarray
    error: np.ndarray
    inside: np.ndarray
    measure1: np.ndarray
    curve_B: np.ndarray
    primary_B: np.ndarray
    timing: dict

    def as_dict(self) -> dict:
        return _jsonable({k: getattr(self, k) for k in (
            "B", "omega", "gammas", "N", "N_check", "max_real", "decay", "zeta", "log_decrement", "frequency",
            "error", "inside", "measure1", "curve_B", "primary_B", "timing")} | {"gammas": list(self.gammas)})


def _least_damped(lam: np.ndarray, lam_M: np.ndarray, gamma: float):
    """(Re, Im, error) of the least-damped resolved mode (both resolutions agree to
    ``MAP_ACCEPT``; looser than the spectrum's 1e-3 so that the static mode next to
    a secondary pitchfork, whose tiny eigenvalue inherits the base state's
    discretisation error, is not dropped)."""
    m = match_spectra(lam, lam_M, accept=MAP_ACCEPT, floor=ERROR_FLOOR)
    keep = ~damping_cluster(m.values, gamma)
    v, partner = m.values[keep], m.partner[keep]
    if not v.size:
        return math.nan, math.nan, math.nan
    j = int(np.argmax(v.real))
    mr_M = float(np.max(lam_M[~damping_cluster(lam_M, gamma)].real))
    # the error of Re lambda is at least the change of that mode's own real part between the resolutions: the
    # largest real part at M can belong to another mode, and under a tiny damping the real parts are
    # discretisation error (1.1e-5 stated from max Re alone, 1.3e-5 true at gamma = 1e-9)
    own = abs(float(v[j].real) - float(lam_M[int(partner[j])].real))
    return float(v[j].real), float(abs(v[j].imag)), max(abs(float(v[j].real) - mr_M), own)


@single_blas_thread
def damping_map(params: RodParameters, B_grid, omega_grid, gammas=HOPF_GAMMAS, N: int = 24, k: int = 6,
                B_ref: float = 1.2, margin: float = 1e-3, B_above: float = 1.0,
                liftoff: float | None = None) -> DampingMap:
    """Decay rate, damping ratio and logarithmic decrement of the least-damped
    mode of b1 over the grid B_grid x omega_grid, for each gamma (Sec. VII B,
    Fig. 19; dimensionless, rates in units of omega_c).

    For each omega, b1 is reached at (B_ref, omega) (:func:`b1_state`) and
    continued in B up to its secondary pitchfork (located: the curve) and down
    to its primary pitchfork (or min(B_grid) after lift-off); each grid B
    strictly inside (by ``margin``) is solved by Newton from the nearest
    continuation point (b1 is continued to max(B_grid) + ``B_above``; a
    secondary pitchfork beyond that is not located and ``curve_B`` is inf
    there). The equilibria and operators are built once and reused
    for every gamma (A1 is affine in gamma); eigenvalues at N and
    M = check_resolution(N) (only modes agreeing to ``MAP_ACCEPT`` count).
    ``liftoff``: b1's lift-off spin at N (:func:`~etcheck.rod.buckled.branches.liftoff_spin`) when already known
    (a map computed spin by spin).
    """
    B_grid = np.asarray(B_grid, dtype=float)
    omega_grid = np.asarray(omega_grid, dtype=float)
    gammas = tuple(float(g) for g in gammas)
    M = check_resolution(N)
    nev = 2 * k + 8
    shape = (len(gammas), omega_grid.size, B_grid.size)
    maxre = np.full(shape, np.nan)
    freq = np.full(shape, np.nan)
    err = np.full(shape, np.nan)
    inside = np.zeros(shape[1:], dtype=bool)
    m1 = np.full(shape[1:], np.nan)
    curve = np.full(omega_grid.size, np.nan)
    primary = np.full(omega_grid.size, np.nan)
    t0 = time.perf_counter()
    lift = br.liftoff_spin(params.with_(gamma=0.0), "b1", 1, N=N) if liftoff is None else liftoff
    t_eq = time.perf_counter() - t0
    t_sp = 0.0
    for iw, w in enumerate(omega_grid):
        t0 = time.perf_counter()
        pw = params.with_(omega=float(w), gamma=0.0)
        loads = br.class_loads(pw, "S1", N, n=1)
        pf = float(loads[0]) if (loads.size and (not math.isfinite(lift) or w < lift)) else -math.inf
        primary[iw] = pf
        lower = max(pf + margin, float(B_grid.min()) - 0.05) if math.isfinite(pf) else float(B_grid.min()) - 0.05
        up, down = _b1_in_B(params, float(w), N, B_ref, max(float(B_grid.max()) + B_above, B_ref + 0.1),
                            lower=lower)
        brk = first_break(up, above=B_ref)
        curve[iw] = brk.value if brk is not None else math.inf
        pool = list(up.states) + (list(down.states) if down is not None else [])
        pool_B = np.array([s.params.B for s in pool])
        pool_m = np.array([eq.measure1(s) for s in pool])
        t_eq += time.perf_counter() - t0
        for ib, B in enumerate(B_grid):
            if not (pf + margin < B < curve[iw] - margin):
                continue
            t0 = time.perf_counter()
            # nearest point of the same (buckled) branch: prefer non-trivial ones
            cand = np.argsort(np.abs(pool_B - B) - 1e3 * (pool_m > 1e-6))
            guess = pool[int(cand[0])]
            try:
                st = eq.solve_equilibrium(pw.with_(B=float(B)), guess)
            except Exception:  # noqa: BLE001 - recorded as outside
                t_eq += time.perf_counter() - t0
                continue
            mm = eq.measure1(st)
            if mm < 1e-6:  # fell onto the straight rod
                t_eq += time.perf_counter() - t0
                continue
            inside[iw, ib] = True
            m1[iw, ib] = mm
            t_eq += time.perf_counter() - t0
            t0 = time.perf_counter()
            opN = damped_operator(pw.with_(B=float(B)), st, N)
            opM = damped_operator(pw.with_(B=float(B)), st, M)
            for ig, g in enumerate(gammas):
                lam = operator_eigenvalues(opN, g, nev, False)
                lam_M = operator_eigenvalues(opM, g, nev, False)
                re, im, e = _least_damped(lam, lam_M, g)
                maxre[ig, iw, ib], freq[ig, iw, ib], err[ig, iw, ib] = re, im, e
            t_sp += time.perf_counter() - t0
    decay = -maxre
    mod = np.hypot(maxre, freq)
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(mod > 0, -maxre / mod, np.nan)
        logdec = np.where(freq > 1e-9, -2.0 * np.pi * maxre / freq, np.where(np.isfinite(maxre), np.inf, np.nan))
    return DampingMap(B_grid, omega_grid, gammas, N, M, maxre, decay, zeta, logdec, freq, err, inside, m1, curve,
                      primary, {"equilibria_s": t_eq, "spectra_s": t_sp, "points": int(inside.sum())})
