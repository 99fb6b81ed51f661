"""Resolution studies of the rung-1 spectrum (dimensionless).

:func:`accuracy_table` times one single-resolution solve per N (BLAS pinned to
one thread) and compares against a high-resolution reference: the lowest k
eigenvalue pairs of eqs. (82)-(85) of arXiv:0810.3668 and the first static load of
the straight rod (the first real root B > 0 of the lambda = 0 pencil,
eq. (91) generalised to omega, T != 0).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from ..numerics.eigen import match_spectra
from .base_state import straight
from .linear import linear_operator
from .parameters import RodParameters
from .spectrum import ERROR_FLOOR, lowest_eigenvalues, select_pairs
from .stability import _family

__all__ = ["AccuracyRow", "accuracy_table"]


@dataclass(frozen=True)
class AccuracyRow:
    """One resolution: N, seconds per solve (operator build + eigen-solve),
    max error of the lowest k pairs (relative, absolute below |lambda| = 0.1),
    relative error of the first static load B_c."""

    N: int
    solve_time: float
    eig_error: float
    load_error: float


def _first_load(params: RodParameters, N: int) -> float:
    r = _family(params, N).pencil_roots("B", params.B, params.omega, params.T)
    r = r[r > 1e-12]
    return float(r[0]) if r.size else float("nan")


def accuracy_table(params: RodParameters, Ns=(8, 12, 16, 24, 32, 48, 64), k: int = 10,
                   N_ref: int = 96, repeats: int = 3) -> list[AccuracyRow]:
    """Rows (N, solve time [s], eigenvalue error, B_c error) against N = N_ref.

    Timing: best of ``repeats`` runs of linear_operator + shift-invert solve
    for 2k + 8 eigenvalues, time.perf_counter, one BLAS thread.
    """
    base = straight(params)
    nev = 2 * k + 8
    rows = []
    with threadpool_limits(limits=1):
        ref = lowest_eigenvalues(params, base, N_ref, nev)
        want = ref[select_pairs(ref, k)]
        B_ref = _first_load(params, N_ref)
        for N in Ns:
            best = np.inf
            for _ in range(repeats):
                t0 = time.perf_counter()
                lam = lowest_eigenvalues(params, base, N, nev, operator=linear_operator(params, base, N))
                best = min(best, time.perf_counter() - t0)
            m = match_spectra(want, lam, accept=np.inf, floor=ERROR_FLOOR)
            err = float(np.max(m.errors)) if m.values.size == want.size else float("inf")
            B_N = _first_load(params, N)
            rows.append(AccuracyRow(N, best, err, abs(B_N - B_ref) / abs(B_ref)))
    return rows
