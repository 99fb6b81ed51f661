"""Spectrum of the linearised whirling rod, with error estimates (dimensionless).

Solves the quadratic eigenproblem (A0 + lambda A1 + lambda^2 A2) Y = 0 of
:func:`etcheck.rod.core.linear.linear_operator` (Sec. VI of
arXiv:0810.3668, eqs. (82)-(85) inserted in (71)-(75)) for the
eigenvalues of least modulus. Unstable if any Re lambda > 0.

**Eigen-strategy: shift-invert ARPACK on the full 12(N+1) system**, (b) one
LU of Q(sigma), size 12(N+1), rather than (a) QR-eliminating phi, m and dense
QZ of the 2 x 6(N+1) companion. For the few eigenvalues nearest 0 that a check
wants, (b) is the cheaper at every resolution used (N >= 16), its cost grows
~N^2 instead of N^3, and it never forms the infinite eigenvalues (singular A2:
theta = 1/(lambda - sigma) = 0 for them). The shift sigma is a small real
number (``SIGMA``), not 0, so the LU exists at divergence points where
lambda = 0 is an eigenvalue. (a) is kept in
:mod:`etcheck.numerics.eigen` (``eliminate_static`` + ``qep_dense``) and is
used as an independent check in the tests.

**Which eigenvalues.** The ``k`` least-|lambda| *pairs*: the 2k eigenvalues
of least modulus (a conjugate pair is never split), reported once per complex
conjugate pair (Im lambda > 0) and with both members when real; sorted by
|lambda|. With Kelvin-Voigt damping the spectrum accumulates at -1/gamma; if
that point is among the wanted eigenvalues, they are resolution-dependent and
``converged`` is False.

**Error control.** Each solve is done at two resolutions N < M (M = N +
max(8, N // 2)); fine eigenvalues are paired one-to-one with coarse ones
(:func:`etcheck.numerics.eigen.match_spectra`) and each reported value is the
fine one with error estimate |lambda_N - lambda_M| / max(|lambda_M|, 0.1)
(relative, absolute below |lambda| = 0.1). Values without a partner within
1e-3 are dropped as spurious/unresolved. With ``N=None`` the resolution is
raised along ``LADDER`` until all wanted eigenvalues agree to ``tol``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from etcheck.numerics.chebyshev import lobatto_weights, resample_matrix
from etcheck.numerics.eigen import eliminate_static, match_spectra, qep_dense, qep_shift_invert
from etcheck.rod.core.base_state import BaseState, straight
from etcheck.rod.core.linear import NFIELDS, collocation, linear_operator
from etcheck.rod.core.parameters import RodParameters
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import BASELINE, WORKSPACE, describe, fits, matrix_bytes, require
from etcheck.runtime.timelimit import predicted_past

__all__ = [
    "SIGMA",
    "LADDER",
    "ERROR_FLOOR",
    "Spectrum",
    "lowest_eigenvalues",
    "nearest_eigenvalues",
    "prefers_dense",
    "damping_cluster",
    "spectrum",
    "spectrum_from",
    "select_pairs",
    "check_resolution",
    "solve_bytes",
]

#: Real shift of the shift-invert (small, irrational-looking, not an eigenvalue
#: at divergence points).
SIGMA = 0.01234567
#: Damping gamma from which eigenvalues are always computed densely (the
#: Kelvin-Voigt cluster at -1/gamma then lies among the lowest modes).
DENSE_GAMMA = 0.05
#: Resolutions tried in turn when N is None.
LADDER = (16, 24, 32, 48, 64, 96, 128)
#: |lambda| below which errors are absolute rather than relative.
ERROR_FLOOR = 0.1
#: Pairs whose two-resolution distance exceeds this are treated as spurious.
ACCEPT = 1e-3
#: Round-off floor of an eigenvalue's error estimate, times N^2 eps at the finer resolution N: where both
#: resolutions sit at round-off their distance can understate the error (5x measured at R = 1, T-bar = 30,
#: undamped: 3.5e-12 stated at N = 64, 1.8e-11 against N = 96); 32 N^2 eps is 2.9e-11 at N = 64.
ROUNDOFF = 32.0


def roundoff_floor(N: int) -> float:
    """The least relative error an eigenvalue at resolution N is stated with: ROUNDOFF N^2 eps."""
    return ROUNDOFF * N**2 * float(np.finfo(float).eps)


def check_resolution(N: int) -> int:
    """The companion resolution M used to check resolution N."""
    return N + max(8, N // 2)


@dataclass(frozen=True)
class Spectrum:
    """Least-|lambda| eigenvalues of the linearisation (dimensionless growth rates/frequencies).

    ``eigenvalues``: one per complex-conjugate pair (Im > 0), both members of
    real pairs, sorted by |lambda|; ``errors``: two-resolution estimates
    (relative, absolute below |lambda| = 0.1); ``N`` the resolution reported,
    ``N_check`` the one compared against. ``modes`` (with_modes=True): complex
    array (n_eig, len(mode_s), 6) of (xi1, xi2, xi3, a1, a2, a3) on the
    uniform grid ``mode_s``, scaled so that the largest displacement
    component is 1 (the largest rotation for pure torsion modes).
    """

    eigenvalues: np.ndarray
    errors: np.ndarray
    N: int
    N_check: int
    converged: bool
    message: str
    tol: float
    mode_s: np.ndarray | None = field(default=None, repr=False)
    modes: np.ndarray | None = field(default=None, repr=False)

    @property
    def max_real(self) -> float:
        """max Re lambda over the reported eigenvalues (the growth rate)."""
        return float(np.max(self.eigenvalues.real)) if self.eigenvalues.size else float("nan")

    @property
    def stable(self) -> bool:
        """True when no reported eigenvalue has positive real part (threshold 1e-9)."""
        return self.max_real <= 1e-9


def damping_cluster(lam: np.ndarray, gamma: float) -> np.ndarray:
    """Mask of eigenvalues in the Kelvin-Voigt accumulation cluster (dimensionless).

    With damping gamma > 0 every stiffness term carries a factor (1 + gamma
    lambda), so the high modes pile up on the real axis just left of
    lambda = -1/gamma (the material relaxation rate). These eigenvalues decay
    at least as fast as 1/gamma, cannot cause instability, and are not
    resolved individually by any finite N; they are excluded from the
    reported spectrum and from its convergence test.
    """
    lam = np.asarray(lam, dtype=complex)
    if gamma <= 0:
        return np.zeros(lam.shape, dtype=bool)
    edge = -1.0 / gamma
    return (lam.real <= edge * (1.0 - 1e-6)) & (np.abs(lam.imag) <= 1e-3 / gamma)


def lowest_eigenvalues(params: RodParameters, base: BaseState | None, N: int, nev: int,
                       vectors: bool = False, operator=None):
    """The nev eigenvalues nearest SIGMA at resolution N, outside the damping cluster."""
    if base is None:
        base = straight(params)
    A0, A1, A2 = operator if operator is not None else linear_operator(params, base, N)
    return nearest_eigenvalues(A0, A1, A2, nev, params.gamma, vectors, dense=prefers_dense(params, nev))


def prefers_dense(params: RodParameters, nev: int) -> bool:
    """Whether the Kelvin-Voigt cluster at -1/gamma may lie among the nev
    eigenvalues nearest the shift (then ARPACK converges slowly or not at all
    on its (near-)degenerate members and dense QZ is used instead).

    Estimated from the unperturbed bending and torsion frequencies (Sec. VI B,
    rung 0) plus the spin: dense when 1/gamma < 1.5 x the (nev/2)-th of them.
    """
    if params.gamma <= 0:
        return False
    if params.gamma >= DENSE_GAMMA:
        return True
    scale = _frequency_scale(params.P, params.R, params.Gamma, params.f, nev // 2, params.ends)
    return 1.0 / params.gamma < 1.5 * scale + 2 * abs(params.omega)


@lru_cache(maxsize=64)
def _frequency_scale(P: float, R: float, Gamma: float, f: float, n: int, ends: tuple[str, str]) -> float:
    from etcheck.rod.straight.analytic import bending_frequencies, torsion_frequencies

    mu = np.concatenate(
        [
            bending_frequencies(P, R, f, n, "weak", ends),
            bending_frequencies(P, R, f, n, "stiff", ends),
            torsion_frequencies(P, Gamma, f, n, ends),
        ]
    )
    return float(np.sort(mu)[n - 1])


def nearest_eigenvalues(A0, A1, A2, nev: int, gamma: float, vectors: bool = False, past_cluster: bool = True,
                        dense: bool = False, reduced: bool = False):
    """The nev eigenvalues of the QEP nearest SIGMA (dimensionless).

    With ``past_cluster`` the Kelvin-Voigt cluster near -1/gamma
    (:func:`damping_cluster`) is removed and the nev nearest eigenvalues
    outside it are returned. By default shift-invert ARPACK, asking for more
    until nev lie outside the cluster. When the cluster lies among the wanted
    eigenvalues (``dense``, see :func:`prefers_dense`) ARPACK converges slowly
    on its degenerate members: then all eigenvalues are computed densely (QZ
    after eliminating the lambda-free unknowns phi, m; several times
    slower). ``reduced``: phi, m are already eliminated (no vectors then).
    """
    if dense:
        lam, V = (qep_dense(A0, A1, A2), None) if reduced else _dense(A0, A1, A2, vectors)
        keep = ~damping_cluster(lam, gamma) if past_cluster else np.ones(lam.size, dtype=bool)
        idx = np.nonzero(keep)[0]
        idx = idx[np.argsort(np.abs(lam[idx] - SIGMA), kind="stable")][:nev]
        return (lam[idx], V[:, idx]) if vectors else lam[idx]
    want, top = nev, 2 * A0.shape[0] - 2
    while True:
        out = qep_shift_invert(A0, A1, A2, k=want, sigma=SIGMA, vectors=vectors)
        lam = out[0] if vectors else out
        if not past_cluster:
            return out
        keep = ~damping_cluster(lam, gamma)
        if keep.sum() >= nev or keep.all() or want >= top:
            break
        want = min(2 * want + int(np.count_nonzero(~keep)), top)
    idx = np.nonzero(keep)[0][:nev]
    return (lam[idx], out[1][:, idx]) if vectors else lam[idx]


def _dense(A0, A1, A2, vectors: bool):
    """All finite eigenvalues (and QEP eigenvectors) by QZ on the reduced problem."""
    n = A0.shape[0] // NFIELDS
    el = eliminate_static(A0, A1, A2, np.arange(6 * n, NFIELDS * n))
    if not vectors:
        return qep_dense(el.B0, el.B1, el.B2), None
    lam, Y = qep_dense(el.B0, el.B1, el.B2, vectors=True)
    V = np.column_stack([el.recover(z, Y[:, i]) for i, z in enumerate(lam)]) if lam.size else np.zeros((A0.shape[0], 0))
    return lam, V


def _is_real(lam: np.ndarray) -> np.ndarray:
    return np.abs(lam.imag) <= 1e-12 * np.maximum(np.abs(lam), 1.0)


def select_pairs(lam: np.ndarray, k: int) -> np.ndarray:
    """Indices of the k least-|lambda| pairs, one per conjugate pair (Im > 0), real ones all.

    Takes the 2k eigenvalues of least modulus, never splitting a conjugate
    pair, and keeps the members with Im >= 0 (both members of real pairs).
    """
    lam = np.asarray(lam, dtype=complex)
    order = np.argsort(np.abs(lam), kind="stable")
    chosen = []
    count = 0
    for i in order:
        if count >= 2 * k:
            break
        chosen.append(i)
        count += 1
    # Complete a conjugate pair cut at the boundary.
    if chosen:
        last = lam[chosen[-1]]
        if not _is_real(np.array([last]))[0]:
            partner = np.argmin(np.abs(lam - np.conj(last)) + np.where(np.isin(np.arange(lam.size), chosen), np.inf, 0.0))
            if np.isfinite(np.abs(lam[partner] - np.conj(last))) and np.abs(lam[partner] - np.conj(last)) <= 1e-8 * max(abs(last), 1.0):
                chosen.append(int(partner))
    chosen = np.array(chosen, dtype=int)
    real = _is_real(lam[chosen])
    keep = chosen[real | (lam[chosen].imag > 0)]
    keep = keep[np.lexsort((-lam[keep].imag, np.abs(lam[keep])))]
    return keep


def _with_unstable(lam: np.ndarray, want: np.ndarray) -> np.ndarray:
    """``want`` and every other computed eigenvalue with Re lambda > 1e-9 (Im >= 0): a growing mode is always
    reported. With heavy damping the overdamped modes pile up towards -1/gamma and can outnumber the pairs
    between 0 and a mode that grows faster than 1/gamma, which the least-|lambda| pairs would then miss."""
    extra = np.nonzero((lam.real > 1e-9) & (lam.imag >= 0))[0]
    return np.concatenate([want, np.setdiff1d(extra, want)]).astype(int)


def _normalise_modes(Y: np.ndarray, N: int, s_plot: np.ndarray) -> np.ndarray:
    col = collocation(N)
    P = resample_matrix(col.s, s_plot, lobatto_weights(N))
    fields = Y.T.reshape(Y.shape[1], NFIELDS, N + 1)[:, :6, :]  # (n_eig, 6, N+1)
    vals = np.einsum("pj,ecj->epc", P, fields)  # (n_eig, ns, 6)
    out = np.empty_like(vals)
    for i, v in enumerate(vals):
        # scale by the largest displacement; by the largest rotation for
        # (pure torsion) modes without displacement
        part = v[:, :3] if np.max(np.abs(v[:, :3])) >= 1e-6 * np.max(np.abs(v[:, 3:])) else v[:, 3:]
        idx = np.unravel_index(np.argmax(np.abs(part)), part.shape)
        out[i] = v / part[idx]
    return out


@single_blas_thread
def spectrum(params: RodParameters, base: BaseState | None = None, k: int = 10, N: int | None = None,
             tol: float = 1e-8, with_modes: bool = False, n_mode_points: int = 101,
             N_max: int = 128, deadline: float | None = None) -> Spectrum:
    """The k least-|lambda| eigenvalue pairs with two-resolution error estimates.

    Dimensionless eigenvalues lambda of eqs. (82)-(85) (growth rate
    Re lambda, angular frequency Im lambda, in units of omega_c). ``base=None``
    is the straight rod :func:`etcheck.rod.core.base_state.straight`. With
    ``N=None`` the resolution climbs ``LADDER`` (up to N_max) until every
    wanted eigenvalue agrees between N and its check resolution to ``tol``;
    with N given, N and check_resolution(N) are used and ``converged`` says
    whether ``tol`` was met. Each error estimate is the distance to the partner at the check resolution,
    at least :func:`roundoff_floor` of the finer resolution. A base state known at a resolution of its own (a
    buckled state, ``base.N``) starts the ladder there: below it the operator samples the state's interpolant,
    and the solves of the climb cannot agree with the finer ones. The climb stops early, unconverged and saying
    why, at the finest resolution within the memory budget (:mod:`etcheck.runtime.memory`) and before a
    resolution predicted to end past ``deadline`` (a ``time.perf_counter()`` value; its cost from the last
    solve's, as N^3).
    """
    if base is None:
        base = straight(params)
    nev = 2 * k + 8
    dense = prefers_dense(params, nev)
    pairs, short = _within_memory(_pairs(base, N, N_max), dense)
    cache: dict[int, tuple] = {}
    seconds: dict[int, float] = {}

    def solve(n: int, vec: bool):
        if n not in cache or (vec and cache[n][1] is None):
            t0 = time.perf_counter()
            out = lowest_eigenvalues(params, base, n, nev, vectors=vec)
            seconds[n] = time.perf_counter() - t0
            cache[n] = out if vec else (out, None)
        return cache[n]

    result = None
    resolved_before = -1
    for n_c, n_f in pairs:
        if result is not None and predicted_past(deadline, _predicted(seconds, n_c, n_f)):
            short = f"N = {n_f} would take about {_predicted(seconds, n_c, n_f):.2g} s, past the time budget"
            break
        lam_c, _ = solve(n_c, False)
        lam_f, V_f = solve(n_f, with_modes)
        result = (n_c, n_f, lam_f, V_f, *_judged(lam_c, lam_f, k, n_f, tol))
        converged, ok = result[-1], result[-2]
        # done when every wanted value is resolved, or when the resolved set no
        # longer grows with N (the rest is discretisation junk, not modes)
        if converged and (np.all(ok) or np.count_nonzero(ok) == resolved_before):
            short = None
            break
        resolved_before = int(np.count_nonzero(ok)) if converged else -1
    out = _spectrum(*result, tol, with_modes, n_mode_points)
    if short is not None and not out.converged:
        out = replace(out, message=f"{out.message}; {short}: the ladder stopped before it")
    return out


def _pairs(base: BaseState, N: int | None, N_max: int) -> list[tuple[int, int]]:
    """The (coarse, fine) resolutions :func:`spectrum` climbs through."""
    if N is not None:
        return [(int(N), check_resolution(int(N)))]
    N_min = int(getattr(base, "N", 0))  # the resolution the base state is known at (none: analytic)
    ladder = [n for n in LADDER if N_min <= n <= N_max] or [max(N_min, min(N_max, LADDER[-1]))]
    return list(zip(ladder[:-1], ladder[1:])) or [(ladder[0], check_resolution(ladder[0]))]


def _within_memory(pairs: list[tuple[int, int]], dense: bool) -> tuple[list[tuple[int, int]], str | None]:
    """The pairs up to the finest within the memory budget (OverBudget where not even the first fits), and what
    the next would need (None: all fit)."""
    fitting = [pair for pair in pairs if fits(solve_bytes(pair[1], dense))] or pairs[:1]
    require(f"the spectrum at N = {fitting[0][1]}", solve_bytes(fitting[0][1], dense))
    if len(fitting) == len(pairs):
        return pairs, None
    n = pairs[len(fitting)][1]
    return fitting, f"N = {n} would need {describe(BASELINE + solve_bytes(n, dense))} of memory, past the budget"


def _predicted(seconds: dict[int, float], n_c: int, n_f: int) -> float:
    """Seconds of the solves at n_c and n_f not done yet, from the finest one done (cost as N^3)."""
    last = max(seconds)
    return sum(seconds[last] * (n / last) ** 3 for n in (n_c, n_f) if n not in seconds)


#: one solve at resolution N in 12(N+1)-square float64 matrices: the operator and the dense QZ of its reduced
#: companion form (10.3-10.6 measured with tracemalloc from N = 12 to 48), or the operator, the LU of the
#: shift-invert and ARPACK's vectors (6.5-8.4 from N = 16 to 96)
SOLVE_DENSE, SOLVE_SHIFT = 11, 9


def solve_bytes(N: int, dense: bool) -> float:
    """Bytes of one eigenvalue solve of the linearisation at resolution N (dense QZ or shift-invert)."""
    return matrix_bytes(NFIELDS * (int(N) + 1), count=SOLVE_DENSE if dense else SOLVE_SHIFT) + WORKSPACE


def spectrum_from(lam_c: np.ndarray, lam_f: np.ndarray, N: int, N_check: int, k: int, tol: float
                  ) -> Spectrum | None:
    """What :func:`spectrum` (no modes, N not given) returns for a base state known at resolution N, given the
    nev = 2k + 8 eigenvalues nearest the shift at N (``lam_c``) and at N_check (``lam_f``), when that is the first
    pair of its ladder (N on LADDER, N_check the next rung) and it would stop there (every wanted value resolved
    to ``tol``); None where it would not (then call it). For spectra already computed, e.g. along a branch's
    eigenvalue paths."""
    rungs = [n for n in LADDER if n >= N]
    if len(rungs) < 2 or rungs[:2] != [N, N_check]:
        return None
    judged = _judged(lam_c, lam_f, k, N_check, tol)
    converged, ok = judged[-1], judged[-2]
    if not (converged and np.all(ok)):
        return None
    return _spectrum(int(N), int(N_check), lam_f, None, *judged, tol, False, 0)


def _judged(lam_c: np.ndarray, lam_f: np.ndarray, k: int, n_f: int, tol: float):
    """(want, errs, ok, converged) of one pair of resolutions in :func:`spectrum`: the wanted eigenvalues at the
    finer one, their errors, which of them are resolved, and whether the pair meets ``tol``."""
    want = _with_unstable(lam_f, select_pairs(lam_f, k))
    # Error estimate of every wanted value: distance to its partner.
    m = match_spectra(lam_f, lam_c, accept=np.inf, floor=ERROR_FLOOR)
    err_all = np.full(lam_f.size, np.inf)
    err_all[m.index] = np.maximum(m.errors, roundoff_floor(n_f))
    errs = err_all[want]
    ok = errs <= ACCEPT
    # Unmatched eigenvalues count as spurious only beyond every matched one
    # (discretisation junk at large |lambda|); one inside the resolved range
    # means the resolution is not yet enough.
    size = np.abs(lam_f[want])
    gap = bool(np.any(~ok & (size <= np.max(size[ok], initial=0.0))))
    converged = bool(np.any(ok) and np.all(errs[ok] <= tol) and not gap)
    return want, errs, ok, converged


def _spectrum(n_c: int, n_f: int, lam_f: np.ndarray, V_f, want, errs, ok, converged: bool, tol: float,
              with_modes: bool, n_mode_points: int) -> Spectrum:
    dropped = int(np.count_nonzero(~ok))
    idx = want[ok]
    msg_parts = []
    if converged:
        msg_parts.append(f"{idx.size} eigenvalues agree to {tol:g} between N={n_c} and N={n_f}")
    else:
        worst = float(np.max(errs[ok])) if np.any(ok) else float("nan")
        msg_parts.append(f"not converged to {tol:g}: worst two-resolution error {worst:.2e} (N={n_c} vs {n_f})")
    if dropped:
        msg_parts.append(f"{dropped} unresolved/spurious eigenvalue(s) dropped")
    mode_s = modes = None
    if with_modes:
        mode_s = np.linspace(0.0, 1.0, n_mode_points)
        modes = _normalise_modes(V_f[:, idx], n_f, mode_s)
    return Spectrum(
        eigenvalues=lam_f[idx],
        errors=errs[ok],
        N=n_f,
        N_check=n_c,
        converged=converged,
        message="; ".join(msg_parts),
        tol=tol,
        mode_s=mode_s,
        modes=modes,
    )
