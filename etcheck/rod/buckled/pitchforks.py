"""The straight rod's pitchforks in each symmetry class (dimensionless; Sec. VII A, eq. (91) of
arXiv:0810.3668 generalised to omega, T != 0): the loads where the primary branches bifurcate,
as real roots of the class-restricted static pencil with two-resolution errors, and the lift-off
spin at which a branch's pitchfork reaches B = 0 (it no longer bifurcates).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.numerics.eigen import pencil_eigenvalues
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled.symmetry import symmetry_bases, symmetry_class
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import check_resolution
from etcheck.runtime.blas import single_blas_thread

__all__ = [
    "class_loads",
    "liftoff_estimate",
    "liftoff_spin",
    "LiftoffSpin",
    "pitchfork_loads",
    "pitchfork_spins",
    "PitchforkLoads",
    "real_eigenvalues",
    "real_roots",
    "straight_pencil",
]


def straight_pencil(params: RodParameters, N: int, which: str, axis: str = "B"):
    """Restricted A0 = A + x C of the straight rod, x = B or omega^2 (others from params)."""
    b = symmetry_bases(params, N, which)
    if axis == "B":
        p0, p1 = params.with_(B=0.0), params.with_(B=1.0)
    else:
        p0, p1 = params.with_(omega=0.0), params.with_(omega=1.0)
    A0 = eq.jacobian(p0, eq.straight_state(p0, N))
    A1 = eq.jacobian(p1, eq.straight_state(p1, N)) - A0
    return b.L_plus @ A0 @ b.V_plus, b.L_plus @ A1 @ b.V_plus, b


def real_roots(A: np.ndarray, C: np.ndarray) -> np.ndarray:
    """The real x with A + x C singular, sorted, solved through the columns C reaches (:func:`pencil_eigenvalues`;
    the Lorentz load reaches a sixth of them: cheaper than QZ of the whole restricted pencil, the same roots to
    1e-12 relative, SET at omega = 0 - 0.6, T = 0 - 0.5, N = 32 and 48)."""
    return real_eigenvalues(pencil_eigenvalues(A, C))


def real_eigenvalues(x: np.ndarray) -> np.ndarray:
    """The real ones among eigenvalues x (imaginary part below 1e-7 of their size), sorted."""
    return np.sort(x[np.abs(x.imag) <= 1e-7 * np.maximum(np.abs(x), 1e-12)].real)


@single_blas_thread
def class_loads(params: RodParameters, which: str, N: int = 32, n: int = 3) -> np.ndarray:
    """The n smallest B > 0 where the straight rod has a pitchfork inside the class
    ``which`` ("b1"/"S1", "b2"/"S2") at params.omega, params.T (dimensionless; exact
    real eigenvalues of the restricted linear pencil in B at resolution N)."""
    A, C, _ = straight_pencil(params, N, which, "B")
    r = real_roots(A, C)
    return r[r > 1e-12][:n]


#: relative rounding floor of the error estimates of pitchfork loads and lift-off spins: the
#: restricted pencils carry differentiation matrices of norm ~N^2, so their eigenvalues agree between
#: resolutions only to ~1e-12 relative once converged (measured up to N = 64 on the test scenes)
ROUNDING = 1e-11


@dataclass(frozen=True)
class PitchforkLoads:
    """The n smallest pitchfork loads B > 0 of the straight rod in one symmetry class,
    with their discretisation errors (dimensionless).

    ``loads`` at the finer resolution ``N_check``; ``errors``: the change
    |B(N) - B(N_check)| of the coarser value (each fine root paired with the
    nearest coarse one), floored at ROUNDING |B|. The collocation converges
    spectrally, so the change of the coarser value bounds the error of the
    finer one (checked against N = 64 over a set of scenes in the tests);
    it overestimates it by the ratio of the two resolutions' errors.
    """

    which: str
    N: int
    N_check: int
    loads: np.ndarray
    errors: np.ndarray


def _paired_errors(fine: np.ndarray, coarse: np.ndarray) -> np.ndarray:
    if coarse.size == 0:
        return np.full(fine.shape, math.inf)
    d = np.min(np.abs(fine[:, None] - coarse[None, :]), axis=1)
    return np.maximum(d, ROUNDING * np.abs(fine))


@single_blas_thread
def pitchfork_loads(params: RodParameters, which: str, N: int = 32, n: int = 3,
                    N_check: int | None = None) -> PitchforkLoads:
    """:func:`class_loads` at N and N_check (default N + max(8, N // 2)), as a
    :class:`PitchforkLoads` (value at the finer resolution, error the change of
    the coarser one). Dimensionless."""
    Nc = check_resolution(N) if N_check is None else int(N_check)
    fine = class_loads(params, which, max(int(N), Nc), n)
    coarse = class_loads(params, which, min(int(N), Nc), n + 2)
    return PitchforkLoads(symmetry_class(which), int(N), Nc, fine, _paired_errors(fine, coarse))


# --- lift-off ----------------------------------------------------------------------------


@dataclass(frozen=True)
class LiftoffSpin:
    """Lift-off spin of a primary branch with its discretisation error (dimensionless).

    ``omega`` at the finer resolution ``N_check`` (the root of the restricted
    omega^2 pencil of the straight rod at B = 0 nearest the value tracked at
    N); ``error`` the change of the N value, floored at ROUNDING omega (as
    :class:`PitchforkLoads`); NaN for both when the branch does not lift off
    below omega_max.
    """

    omega: float
    error: float
    N: int
    N_check: int
    omega_coarse: float = math.nan  # the value at the coarser resolution


def pitchfork_spins(params: RodParameters, which: str, N: int) -> np.ndarray:
    """Spins omega > 0 at which the straight rod has a pitchfork at B = 0 inside the class."""
    A, C, _ = straight_pencil(params.with_(B=0.0, omega=0.0), N, which, "omega")
    om2 = real_roots(A, C)
    return np.sqrt(om2[om2 > 0])


@single_blas_thread
def liftoff_estimate(params: RodParameters, which: str = "b1", k: int = 1, N: int = 24,
                     N_check: int | None = None, omega_max: float = 4.0) -> LiftoffSpin:
    """:func:`liftoff_spin` at N (tracked from omega = 0, which identifies the
    branch) and its root at N_check (default N + max(8, N // 2)): a
    :class:`LiftoffSpin`. Dimensionless."""
    Nc = check_resolution(N) if N_check is None else int(N_check)
    w = liftoff_spin(params, which, k, N, omega_max)
    if not math.isfinite(w):
        return LiftoffSpin(math.nan, math.nan, int(N), Nc)
    roots = pitchfork_spins(params, symmetry_class(which), Nc)
    if roots.size == 0:
        return LiftoffSpin(w, math.inf, int(N), Nc, w)
    wc = float(roots[np.argmin(np.abs(roots - w))])
    return LiftoffSpin(wc, max(abs(wc - w), ROUNDING * wc), int(N), Nc, w)


@single_blas_thread
def liftoff_spin(params: RodParameters, which: str = "b1", k: int = 1, N: int = 24, omega_max: float = 4.0,
                 d_omega: float = 0.05) -> float:
    """Spin at which the pitchfork of the k-th primary branch of class ``which`` reaches B = 0.

    Linear theory of the straight rod (dimensionless): the pitchfork load of the
    class-restricted pencil (exact lambda = 0 problem) is followed from its
    omega = 0 value (the k-th root) as omega grows; where it reaches B = 0 the
    branch no longer bifurcates from the straight rod (it has merged with its
    mirror image at -B and lifted off, Sec. VII B). The value is the root of the
    restricted omega^2 pencil at B = 0 inside the last bracket. Returns nan if
    it does not happen below ``omega_max``.
    """
    base = params.with_(B=0.0, omega=0.0)
    # the restricted Jacobian of the straight rod is affine in B and in omega^2 (no cross term: the Lorentz
    # and centrifugal loads add), so the pencil at any spin is A + omega^2 W + B C, assembled once
    # (solved through the columns the Lorentz load reaches: real_roots)
    A, C, _ = straight_pencil(base, N, which, "B")
    W = straight_pencil(base, N, which, "omega")[1]

    def loads(w: float, n: int) -> np.ndarray:
        r = real_roots(A + w**2 * W, C)
        return r[r > 1e-12][:n]

    roots0 = loads(0.0, k)
    if roots0.size < k:
        raise ValueError("not enough pitchforks at omega = 0")
    cur = float(roots0[k - 1])
    w = 0.0
    slope = 0.0
    while w < omega_max:
        w2 = w + d_omega
        r = loads(w2, 50)
        guess = cur + slope * d_omega
        if r.size == 0 or np.min(np.abs(r - guess)) > max(0.25 * cur, 0.02) or (cur < 0.5 * roots0[k - 1] and
                                                                                np.min(r) > 2 * cur):
            # the tracked pitchfork has left B > 0: refine at B = 0 in omega^2
            om = pitchfork_spins(base, symmetry_class(which), N)
            inside = om[(om > w - 1e-9) & (om <= w2 + 1e-9)]
            if inside.size == 0:
                cand = om[np.argmin(np.abs(om - w2))]
                return float(cand)
            return float(inside[0])
        new = float(r[np.argmin(np.abs(r - guess))])
        slope = (new - cur) / d_omega
        cur, w = new, w2
    return math.nan
