"""Rung 3: the damping map of b1 (Fig. 19 of arXiv:0810.3668): over the (B, omega) plane under
the secondary-pitchfork curve, the damping ratio of the least-damped mode of b1 for several
Kelvin-Voigt dampings gamma, each mode checked at two resolutions. Dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from etcheck.jsonable import jsonable
from etcheck.numerics.eigen import match_spectra
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled import pitchforks
from etcheck.rod.buckled.secondary import b1_in_B, first_break
from etcheck.rod.buckled.spectra import damped_operator, operator_eigenvalues
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import (
    ERROR_FLOOR,
    check_resolution,
    damping_cluster,
)
from etcheck.runtime.blas import single_blas_thread

#: The damping values of Fig. 19 (Sec. VII B), outside to inside.
HOPF_GAMMAS = (0.01, 0.013, 0.016, 0.02, 0.022)
#: Two-resolution acceptance of a mode in :func:`damping_map` (relative, absolute below 0.1).
MAP_ACCEPT = 1e-2

__all__ = ["HOPF_GAMMAS", "MAP_ACCEPT", "DampingMap", "damping_map"]


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
        return jsonable({k: getattr(self, k) for k in (
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
    lift = pitchforks.liftoff_spin(params.with_(gamma=0.0), "b1", 1, N=N) if liftoff is None else liftoff
    t_eq = time.perf_counter() - t0
    t_sp = 0.0
    for iw, w in enumerate(omega_grid):
        t0 = time.perf_counter()
        pw = params.with_(omega=float(w), gamma=0.0)
        loads = pitchforks.class_loads(pw, "S1", N, n=1)
        pf = float(loads[0]) if (loads.size and (not math.isfinite(lift) or w < lift)) else -math.inf
        primary[iw] = pf
        lower = max(pf + margin, float(B_grid.min()) - 0.05) if math.isfinite(pf) else float(B_grid.min()) - 0.05
        up, down = b1_in_B(params, float(w), N, B_ref, max(float(B_grid.max()) + B_above, B_ref + 0.1),
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
