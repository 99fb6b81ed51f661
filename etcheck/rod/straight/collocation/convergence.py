"""Resolution studies of the rung-1 spectrum (dimensionless).

:func:`accuracy_table` solves once per N (BLAS pinned to one thread), timing
the solve, and compares against a reference resolution: the lowest k
eigenvalue pairs of eqs. (82)-(85) of arXiv:0810.3668 and the first static
load of the straight rod at the scene's spin and tension (the first real root
B > 0 of the lambda = 0 pencil, eq. (91) generalised to omega, T != 0).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from etcheck.numerics.eigen import match_spectra
from etcheck.rod.core.base_state import straight
from etcheck.rod.core.linear import linear_operator, static_operator
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import ERROR_FLOOR, lowest_eigenvalues, select_pairs
from etcheck.runtime.blas import one_blas_thread

__all__ = ["REFERENCES", "AccuracyRow", "reference_resolution", "accuracy_table", "first_load"]

#: Reference resolutions: the smallest at least 1.5 x the finest N compared is
#: used (the lowest pairs of the straight rod agree to ~1e-14 from N = 32 on, so
#: N = 48 is a round-off reference for N <= 32; a larger N only adds cost).
REFERENCES = (48, 64, 96, 128)


def reference_resolution(Ns) -> int:
    """The reference N of :func:`accuracy_table` for the resolutions Ns (48 for N <= 32, 96 for N <= 64)."""
    need = 1.5 * max(Ns, default=0)
    return next((n for n in REFERENCES if n >= need), int(math.ceil(need)))


@dataclass(frozen=True)
class AccuracyRow:
    """One resolution: N, seconds per solve (operator build + eigen-solve),
    max error of the lowest k pairs (relative, absolute below |lambda| = 0.1),
    relative error of the first static load B_c."""

    N: int
    solve_time: float
    eig_error: float
    load_error: float


def first_load(params: RodParameters, N: int) -> float:
    """The smallest load root B > 0 of A0 at the scene's spin and tension, resolution N (nan if none, or where the
    unloaded operator K is singular to working precision: no root is read through it).

    A0(B) = K + B AB with AB nonzero on 2N rows (the load term of eq. (71)):
    B = -1/mu for the eigenvalues mu of AB[rows] K^-1 I[:, rows] (one LU of K,
    a 2N x 2N eigenvalue solve).
    """
    base = straight(params)
    K = static_operator(params.with_(B=0.0), base, N)
    AB = static_operator(params.with_(B=1.0), base, N) - K
    rows = np.nonzero(np.any(AB != 0.0, axis=1))[0]
    sel = np.zeros((K.shape[0], rows.size))
    sel[rows, np.arange(rows.size)] = 1.0
    with warnings.catch_warnings():
        warnings.simplefilter("error", sla.LinAlgWarning)
        try:
            X = sla.solve(K, sel, check_finite=False)
        except sla.LinAlgWarning:  # K (the unloaded rod at this spin and tension) is singular to working precision
            return math.nan
    mu = sla.eigvals(AB[rows] @ X, check_finite=False)
    mu = mu[np.abs(mu) > 0]
    B = -1.0 / mu
    B = B[(np.abs(B.imag) <= 1e-8 * np.abs(B)) & (B.real > 1e-12)].real
    return float(np.min(B)) if B.size else math.nan


def accuracy_table(params: RodParameters, Ns=(8, 12, 16, 24, 32), k: int = 10,
                   N_ref: int | None = None) -> list[AccuracyRow]:
    """Rows (N, solve time [s], eigenvalue error, B_c error) against N = N_ref.

    One solve per resolution: linear_operator + shift-invert solve for
    2k + 8 eigenvalues, timed with time.perf_counter on one BLAS thread (a
    single measurement), and the first static load from :func:`first_load`.
    ``N_ref`` defaults to :func:`reference_resolution` (Ns).
    """
    N_ref = reference_resolution(Ns) if N_ref is None else int(N_ref)
    base = straight(params)
    nev = 2 * k + 8
    rows = []
    # one after the other, after the reference: a solve timed while other work shares the cores (or as the
    # first of a process) reads several times slower, and the table is the scene's measured trade of time for accuracy
    with one_blas_thread():
        ref = lowest_eigenvalues(params, base, N_ref, nev)
        want = ref[select_pairs(ref, k)]
        B_ref = first_load(params, N_ref)
        for N in Ns:
            t0 = time.perf_counter()
            lam = lowest_eigenvalues(params, base, N, nev, operator=linear_operator(params, base, N))
            elapsed = time.perf_counter() - t0
            m = match_spectra(want, lam, accept=np.inf, floor=ERROR_FLOOR)
            err = float(np.max(m.errors)) if m.values.size == want.size else float("inf")
            rows.append(AccuracyRow(N, elapsed, err, abs(first_load(params, N) - B_ref) / abs(B_ref)))
    return rows
