"""Rung 3: Hopf search along a branch (Sec. VII B, Fig. 19 of arXiv:0810.3668): the real part of
the least-damped complex mode followed along the branch and bisected where it changes sign, at
two resolutions. With complete Kelvin-Voigt damping none is expected
(:mod:`etcheck.rod.buckled.structure`); the search checks it. Dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from etcheck.jsonable import jsonable
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled.spectra import point_spectrum
from etcheck.rod.core.spectrum import (
    check_resolution,
)
from etcheck.runtime.blas import single_blas_thread

__all__ = ["HopfPoint", "HopfScan", "find_hopf"]


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
        return jsonable({"gamma": self.gamma, "parameter": self.parameter, "values": self.values,
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
        return _complex_max(point_spectrum(st.with_params(p), gamma, nev, n, False))

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
