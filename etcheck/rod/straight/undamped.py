"""Rung 1u: the undamped straight tether from its exact dynamic characteristic function.

Without damping (gamma = 0) the linearisation about the straight rod (paper
Sec. 6.1, eq. (86) with F = +T e3; docs/model.md, section 6) is gyroscopic,
M q'' + G q' + K q = 0 with G skew: it loses stability by divergence (a pair
lambda = +-i Omega through 0) or by flutter (two imaginary pairs collide and
leave the axis), and it can regain it (stable windows). With normal modes
(u, v) exp(lambda t) the bending equations (f-scaling of eq. (36), rotating
frame, u along the weak axis e1) are

    (R/f) u'''' - (a + P R lambda^2) u'' + (lambda^2 - omega^2) u - 2 omega lambda v - B v' = 0
    (1/f) v'''' - (b + P   lambda^2) v'' + (lambda^2 - omega^2) v + 2 omega lambda u + B u' = 0
    u = u' = v = v' = 0 at s = 0 and s = 1,   a = T + P R omega^2,  b = T + P omega^2

(torsion decouples and is neutrally stable; for omega = T = 0, f = 1 this is
eq. (87)). Constant coefficients: exponents k are the roots of the degree-8
polynomial p(k) = Pu(k) Pv(k) + q(k)^2 with q = B k + 2 omega lambda, and
the clamped determinant is known exactly, as for lambda = 0 in
:mod:`etcheck.rod.straight.exact` (same scaled state, same D = det G
exp(-sigma), G the map from y(0) to the boundary values).

**A real function of mu = -lambda^2.** det G is real for every real mu: for
mu < 0 (lambda real) the equations are real; for mu > 0 (lambda = i Omega)
the map (u, v)(s) -> (conj u(1 - s), -conj v(1 - s)) takes solutions to
solutions and gives conj(det G) det Phi(1) = det G with det Phi(1) = exp(sum
k) = 1 (p has no k^7 term). The map (u, v)(s) -> (u(1 - s), -v(1 - s)),
lambda -> -lambda makes D even in lambda. So

    E(mu) = D(lambda = sqrt(-mu))

is real-analytic in mu and in (B, omega, T), and its real roots are the
real eigenvalues mu of the gyroscopic pencil: mu > 0 an oscillation
Omega = sqrt(mu), mu < 0 a real pair (divergence). The rod is stable iff
every root mu is real and positive (the spectrum is Hamiltonian). Complex
roots mu come in conjugate pairs: flutter.

**Counting.** The real roots below a cut mu_cut are counted exactly (sign
changes, close pairs split by minimising |E|); no real root lies below the
Rayleigh bound mu_lo of K / M (for real lambda the eigenvector is real and
its Coriolis term vanishes). At omega = 0 the problem is self-adjoint (K q
= mu M q): every root is real, so the number of roots below mu_cut there
is the total; along a line from omega = 0 the number of complex pairs is
(total - real roots) / 2, the total changing only when a real root crosses
mu_cut (detected, with its direction). A flutter point is a fold of the
real roots, E = dE/dmu = 0: it is located by Brent's method on the value of
E at its local extremum in mu (smooth and with a simple zero at the fold),
a divergence point by a root of E(0) = D_static.

**Exact basis.** det W (initial data of the basis (q, Pu) exp(k s)) is
det C V(k), C the 8 x 8 coefficient matrix of q k^m, Pu k^m (m < 4), a
Sylvester-type matrix: det C = (R/f)^3 Res(q, Pu), Res(q, Pu) = B^4 Pu(-2
omega lambda / B). Where the exponential basis does not apply (coincident
exponents, B = 0 with omega lambda = 0) the ordered-Schur route of
:mod:`etcheck.rod.straight.exact` takes over; it is also the second
formulation behind every error estimate.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from etcheck.numerics.blas import single_blas_thread
from etcheck.numerics.optimize import bracketed_roots, brentq, find_root, minimize_scalar
from etcheck.numerics.parallel import can_split, split_map
from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.straight import exact as _ex
from etcheck.rod.straight.exact import _assemble, _log_vandermonde, _schur, _smoothing
from etcheck.rod.straight.mode_band import cut, mode_count
from etcheck.rod.straight.spectral import CriticalKind, CriticalPoint, stable_windows
from etcheck.rod.straight.undamped_isotropic import _characteristic_plus

__all__ = ["MODEL", "characteristic_mu", "Crossing", "StabilityLine", "stability_line", "UndampedCritical",
           "undamped_critical", "has_real_pair"]

#: Model string of every value from this module.
MODEL = "rung 1 (exact undamped determinant)"

_EPS = np.finfo(float).eps
_BC_REAL = np.array([0, 1, 4, 5])
#: Relative gap between two exponents below which the exponential basis is not used.
_CONFLUENT = 1e-4


def _lam(mu: np.ndarray) -> np.ndarray:
    """lambda with lambda^2 = -mu (either branch: D is even in lambda)."""
    return np.sqrt(-np.asarray(mu, dtype=complex))


def _coefficients(P, R, f, B, omega, T, lam):
    """Coefficient arrays of the u and v symbols: (a + P R lambda^2, b + P lambda^2, lambda^2 - omega^2, 2 omega lambda)."""
    l2 = lam * lam
    w2 = omega * omega
    return T + P * R * w2 + P * R * l2, T + P * w2 + P * l2, l2 - w2, 2 * omega * lam


def _wavenumbers(R, f, B, alpha, beta, c0, c1, factor):
    """Continuous wavenumber scales (ku, kv) of the u and v exponents (>= 1), smooth in every
    coefficient (a kink in a scale would put a kink into D, which is normalised in them)."""
    B = np.abs(B)
    kb = (f * B / math.sqrt(R)) ** (1.0 / 3.0)
    c1sq = np.sqrt(np.abs(c1) ** 4 + 1.0)  # |c1|^2, smoothed where lambda = 0
    kc = (f * np.sqrt(c1sq) * (B + 1.0) / math.sqrt(R)) ** 0.2
    a2, b2, c02 = np.abs(alpha) ** 2, np.abs(beta) ** 2, np.abs(c0) ** 2
    ku = 1.0 + (1.0 + f * f * a2 / R**2) ** 0.25 + (1.0 + f * f * c02 / R**2) ** 0.125 + kb + kc
    kv = 1.0 + (1.0 + f * f * b2) ** 0.25 + (1.0 + f * f * c02) ** 0.125 + kb + kc
    return factor * ku, factor * kv


def _companion(R, f, B, alpha, beta, c0, c1, ku, kv) -> np.ndarray:
    """8 x 8 first-order matrix of the scaled state (u, u'/ku, .., v, v'/kv, ..) at one point."""
    A = np.zeros((8, 8), dtype=complex)
    A[0, 1] = A[1, 2] = A[2, 3] = ku
    A[4, 5] = A[5, 6] = A[6, 7] = kv
    A[3, 0] = -f * c0 / (R * ku**3)
    A[3, 2] = f * alpha / (R * ku)
    A[3, 4] = f * c1 / (R * ku**3)
    A[3, 5] = f * B * kv / (R * ku**3)
    A[7, 4] = -f * c0 / kv**3
    A[7, 6] = f * beta / kv
    A[7, 0] = -f * c1 / kv**3
    A[7, 1] = -f * B * ku / kv**3
    return A


def _exponents(c: np.ndarray) -> np.ndarray:
    """Roots k of the degree-8 rows c (highest first).

    Rows come in runs along a grid (the mu grid of a line, sample after sample), where the roots move little
    from one row to the next: every :data:`_STRIDE`-th row is solved by :func:`_exponents_qr`, each row
    between starts from the roots of the row before it and takes Newton steps, and keeps them only when they
    are certified: eight roots, pairwise apart by more than :data:`_CONFLUENT` of their size, each with a
    backward error below 1e-13 (eight distinct roots of a degree-8 polynomial are all of them). Uncertified rows
    are solved by :func:`_exponents_qr` at once (the next row starts from them), and so is every row of a short
    run (fewer than :data:`_QR_BELOW`). E on the lines of SET 237 -> ~190 ms CPU; the same roots to round-off."""
    n = c.shape[0]
    if n < _QR_BELOW:
        return _exponents_qr(c)
    k = np.empty((n, 8), dtype=complex)
    anchor = np.arange(0, n, _STRIDE)
    k[anchor] = _exponents_qr(c[anchor])
    for offset in range(1, _STRIDE):  # each row from the row before it
        idx = anchor[anchor + offset < n] + offset
        with np.errstate(all="ignore"):
            z, good = _newton(c[idx], k[idx - 1])
        k[idx] = z
        if not good.all():
            bad = idx[~good]
            k[bad] = _exponents_qr(c[bad])
    return k


#: The 28 pairs (i < j) of the eight exponents.
_PAIRS = np.triu_indices(8, 1)
#: Every how many rows :func:`_exponents` solves one by QR (the rows between follow from it by Newton; 4 -> 8
#: with uncertified rows re-solved at once: 58 -> 50 ms on the 8228 rows of SET's spin line).
_STRIDE = 8
#: Fewer rows than this are all solved by QR: below it the Newton sweeps cost more in numpy's per-call overhead
#: than they save (measured on a spin line of SET: 65 rows 2.0 -> 1.3 ms, 121 rows 4.0 -> 3.0 ms; equal at ~200).
_QR_BELOW = 192


def _horner(c: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """p(z) and p'(z) for the degree-8 rows c (n, 9), highest first, at z (n, m).

    The rows of :func:`_exponential` have no z^7, z^5, z^3 terms: p(z) = Q(z^2) + c_7 z with Q of degree 4,
    so p'(z) = 2 z Q'(z^2) + c_7: Horner in w = z^2, half the products of a general degree-8 Horner."""
    c0, c2, c4, c6, c7, c8 = (c[:, j:j + 1] for j in (0, 2, 4, 6, 7, 8))
    w = z * z
    p = (((c0 * w + c2) * w + c4) * w + c6) * w + c8 + c7 * z
    q = 2.0 * z * (((4.0 * c0 * w + 3.0 * c2) * w + 2.0 * c4) * w + c6) + c7
    return p, q


def _size(c: np.ndarray, z: np.ndarray) -> np.ndarray:
    """sum_j |c_j| |z|^(8-j) for the rows of :func:`_horner` (the scale of p(z)'s rounding errors)."""
    a = np.abs(c)
    r = np.abs(z)
    w = r * r
    return (((a[:, :1] * w + a[:, 2:3]) * w + a[:, 4:5]) * w + a[:, 6:7]) * w + a[:, 8:9] + a[:, 7:8] * r


def _newton(c: np.ndarray, z: np.ndarray, steps: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on each of the eight roots of the rows c (n, 9) from z (n, 8); (roots, certified)."""
    z = z.astype(complex)
    for _ in range(steps):
        p, q = _horner(c, z)
        step = p / q
        z = z - np.where(np.isfinite(step), step, 0.0)
        if np.all(np.abs(step) <= 1e-14 * np.abs(z)):
            break
    # certificate: backward error of each root, and eight distinct roots
    az = np.abs(z)
    p, _ = _horner(c, z)
    size = _size(c, z)
    i, j = _PAIRS
    gap = np.min(np.abs(z[:, i] - z[:, j]) / np.maximum(az[:, i], az[:, j]), axis=1)
    good = np.all(np.abs(p) <= 1e-13 * size, axis=1) & (gap > _CONFLUENT) & np.all(np.isfinite(z), axis=1)
    return z, good


def _exponents_qr(c: np.ndarray) -> np.ndarray:
    """Roots k of the degree-8 rows c (highest first). p(i z) is a real polynomial in z for
    lambda imaginary and p(k) is real for lambda real, so the roots come from a real companion
    matrix (4x cheaper than a complex one), then Newton steps on p (as :func:`_roots`)."""
    n = c.shape[0]
    powers = 1j ** np.arange(8, -1, -1)
    rot = np.abs(c[:, 7].imag) > np.abs(c[:, 7].real)  # lambda imaginary: the k^1 coefficient is imaginary
    d = np.where(rot[:, None], c * powers, c).real
    C = np.zeros((n, 8, 8))
    C[:, 0, :] = -d[:, 1:] / d[:, :1]
    C[:, np.arange(1, 8), np.arange(7)] = 1.0
    z = np.linalg.eigvals(C)
    k = np.where(rot[:, None], 1j * z, z)
    for _ in range(2):
        p, q = _horner(c, k)
        step = np.where(q != 0, p / np.where(q != 0, q, 1.0), 0.0)
        k = k - np.where(np.isfinite(step), step, 0.0)
    return k


def _exponential(R, f, B, alpha, beta, c0, c1, ku, kv, shift=0):
    """D by the exponential basis for arrays (n,); NaN where it does not apply."""
    n = B.size
    lu, lv = R / f, 1.0 / f
    # p(k) = Pu Pv + q^2, Pu = lu k^4 - alpha k^2 + c0, Pv = lv k^4 - beta k^2 + c0, q = B k + c1: no k^7, k^5,
    # k^3 terms (which :func:`_horner` relies on)
    c = np.stack([np.full(n, lu * lv, dtype=complex), np.zeros(n, dtype=complex), -(lu * beta + lv * alpha),
                  np.zeros(n, dtype=complex), alpha * beta + c0 * (lu + lv), np.zeros(n, dtype=complex),
                  -c0 * (alpha + beta) + B**2, 2 * B * c1, c0**2 + c1**2], axis=1)
    with np.errstate(all="ignore"):
        k = _exponents(c)
        ak = np.abs(k)
        i, j = _PAIRS
        d = k[:, j] - k[:, i]
        ok = (np.all(np.abs(d) >= _CONFLUENT * np.maximum(ak[:, i], ak[:, j]), axis=1)
              & np.all(np.isfinite(k), axis=1))
        k2 = k * k
        Pu = lu * k2 * k2 - alpha[:, None] * k2 + c0[:, None]
        Pv = lv * k2 * k2 - beta[:, None] * k2 + c0[:, None]
        q = B[:, None] * k + c1[:, None]
        # Res(q, Pu) = B^4 Pu(-c1 / B), written to stay finite at B = 0
        res = lu * c1**4 - alpha * c1**2 * B**2 + c0 * B**4
        second = np.abs(Pv) > np.abs(Pu)  # (Pv, -q) = (Pv / q) (q, Pu) is the better null vector
        u = np.where(second, Pv, q)
        v = np.where(second, -q, Pu)
        ratio = np.where(np.abs(q) >= np.abs(Pu), Pv / q, -q / Pu)
        log_lam = np.sum(np.where(second, np.log(ratio), 0.0), axis=1)
        logW = 3 * math.log(lu) + np.log(res) + _log_vandermonde(k, d) + log_lam - 6 * np.log(ku) - 6 * np.log(kv)
        V = np.stack([u, u * k / ku[:, None], v, v * k / kv[:, None]], axis=1)
        good = np.abs(res) > 1e-12 * (lu * np.abs(c1) ** 4 + np.abs(alpha) * np.abs(c1) ** 2 * B**2
                                      + np.abs(c0) * B**4 + 1e-300)
        ok &= good & np.all(np.isfinite(V), axis=(1, 2)) & np.isfinite(logW)
        k = np.where(ok[:, None], k, 1.0 + np.arange(8))
        V = np.where(ok[:, None, None], V, 1.0)
        logW = np.where(ok, logW, 0.0)
        value, _ = _assemble(k, V, logW, shift)
        value = value * _smoothing(k)
    return np.where(ok & np.isfinite(value), value, np.nan)


#: Evaluations by the ordered-Schur route (a Python loop, ~1 ms each) that one line may spend where the
#: exponential basis does not apply (near-coincident exponents: R near 1 with large rotary inertia P);
#: past it the line gives up (ArithmeticError) and the check takes the spectral scans instead.
SCHUR_BUDGET = 3000
#: Most mu samples per point of a line. The grid follows the modes below the cut (5 per mode); long, taut,
#: thin tethers with large P spun far up have ~1e4-1e5 of them: the stable spin windows are then sought only
#: up to the first static spin, and a line that still needs more gives up (ArithmeticError).
MAX_GRID = 6000
#: Points at which E at the cut is sampled between two samples of a line to count the roots that pass it.
CUT_SAMPLES = 33


def characteristic_mu(params: RodParameters, mu, B=None, omega=None, T=None, route: str = "auto",
                      factor: float = 1.0, shift: int = 0, schur_budget: float = math.inf) -> np.ndarray:
    """E(mu; B, omega, T): the real characteristic function of the undamped straight rod.

    ``mu`` = -lambda^2 (array); B, omega, T default to the parameters' values
    and broadcast with mu. ``route``: "auto" (exponential basis, Schur where
    it does not apply), "exponential" (NaN where it does not apply) or
    "schur"; ``factor``, ``shift``: other wavenumber scales and split (a
    second formulation); ``schur_budget``: the most points that may take the
    Schur route (ArithmeticError past it). Dimensionless, real; zero exactly
    at the eigenvalues lambda = +-sqrt(-mu).
    """
    return _characteristic(params, mu, B, omega, T, route, factor, shift, schur_budget)[0]


def _characteristic(params: RodParameters, mu, B=None, omega=None, T=None, route: str = "auto",
                    factor: float = 1.0, shift: int = 0, schur_budget: float = math.inf) -> tuple[np.ndarray, int]:
    """:func:`characteristic_mu` and the number of points that took the Schur route."""
    B = params.B if B is None else B
    omega = params.omega if omega is None else omega
    T = params.T if T is None else T
    mu, B, omega, T = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (mu, B, omega, T)))
    shape = mu.shape
    mu, B, omega, T = (x.ravel() for x in (mu, B, omega, T))
    lam = _lam(mu)
    alpha, beta, c0, c1 = _coefficients(params.P, params.R, params.f, B, omega, T, lam)
    ku, kv = _wavenumbers(params.R, params.f, B, alpha, beta, c0, c1, factor)
    out = np.full(mu.size, np.nan, dtype=complex)
    if route != "schur":
        out = _exponential(params.R, params.f, B + 0j, alpha, beta, c0, c1, ku, kv, shift)
        rest = np.nonzero(~np.isfinite(out) & (B == 0) & (omega == 0))[0]
        if rest.size:  # u and v uncoupled: the basis of the coupled problem degenerates (q = 0)
            out[rest] = _uncoupled(params, mu[rest], T[rest], factor, shift)
    if route != "exponential":
        slow = np.nonzero(~np.isfinite(out))[0]
        if slow.size > schur_budget:
            raise ArithmeticError(f"the exponential basis does not apply at {slow.size} points (near-coincident "
                                  f"exponents) and the Schur route's budget is spent")
        for i in slow:
            A = _companion(params.R, params.f, B[i], alpha[i], beta[i], c0[i], c1[i], ku[i], kv[i])
            out[i] = _schur(A, _BC_REAL, shift).value * _smoothing(np.linalg.eigvals(A))
    return out.real.reshape(shape), int(slow.size) if route != "exponential" else 0


def _uncoupled(params: RodParameters, mu: np.ndarray, T: np.ndarray, factor: float, shift: int) -> np.ndarray:
    """E at B = omega = 0 up to a positive factor: the product of the determinants of the two clamped
    Rayleigh beams (c4 w^(4) - (T - pc mu) w'' - mu w = 0 for u and v). Where a beam's exponential basis does not
    apply (mu = 0: the double exponent 0) its own Schur route, in the same scaled state, so that the positive
    factor stays continuous along mu (the coupled Schur route there has another: a jump of two decades at
    mu = 0 looked like two dips of |E| on a line under compression and was taken for a double root)."""
    out = np.ones(mu.size, dtype=complex)
    for c4, pc in ((params.R / params.f, params.P * params.R), (1.0 / params.f, params.P)):
        c2 = T - pc * mu
        kap = factor * (1.0 + (1.0 + (c2 / c4) ** 2) ** 0.25 + (1.0 + (mu / c4) ** 2) ** 0.125)
        value = np.full(mu.size, np.nan, dtype=complex)
        for group in (mu == 0, mu != 0):
            if np.any(group):
                v, _, m = _ex._isotropic_batch(c4, c2[group] + 0j, mu[group] + 0j, np.zeros(int(group.sum())),
                                               kap[group], shift, small=False)
                value[group] = v * _smoothing(m)
        for i in np.nonzero(~np.isfinite(value))[0]:
            A = _ex._isotropic_companion(c4, c2[i], mu[i], 0.0, kap[i])
            value[i] = _ex._isotropic_schur(c4, c2[i], mu[i], 0.0, kap[i], shift).value * _smoothing(np.linalg.eigvals(A))
        out *= value
    return out


# --- the real roots in mu at one point of a line -------------------------------------------


def _rayleigh_floor(params: RodParameters, B_max: float, omega_max: float, T_min: float) -> float:
    """A lower bound of K / M over the line (no real root mu lies below it).

    For |u|^2 + |v|^2 = 1 (M >= 1 there), t = max(-T, 0) and the load's term B int (v u' - u v') = -2 B int u v':
    K >= (R/f) |u''|^2 + (1/f) |v''|^2 - t (|u'|^2 + |v'|^2) - omega^2 - 2 |B| |u| |v'|, and with
    |v'|^2 <= |v| |v''| the last term is at least -2 |B| |u| |v|^(1/2) |v''|^(1/2) >= -c |B| |v''|^(1/2),
    c = 2 max (1 - s)^(1/2) s^(1/4) = 2 (2/3)^(1/2) (1/3)^(1/4) = 1.2408 (at |v|^2 = s = 1/3):
    minimised over X = |v''| and Y = |u''| in closed form or on a grid. Under tension T > 0 the
    term T (|u'|^2 + |v'|^2) >= T pi^2 (|u|^2 + |v|^2) (u, v vanish at both ends) is added. (The load's term was
    once taken as |B| |u| |v'|: for R = 0.01 at ten times the static load the lowest real root, -73.1, lay
    below that floor, -64.6, and outside the line.)"""
    R, f = params.R, params.f
    t = max(-T_min, 0.0)
    c = 2.0 * math.sqrt(2.0 / 3.0) * (1.0 / 3.0) ** 0.25
    X = np.geomspace(1e-6, 1e6, 2001) * (1.0 + f * (abs(B_max) + t)) ** (2.0 / 3.0)
    m_v = float(np.min(X**2 / f - t * X - c * abs(B_max) * np.sqrt(X)))
    m_u = -t**2 * f / (4 * R)
    bound = -omega_max**2 + m_u + m_v + max(T_min, 0.0) * math.pi**2
    return 0.0 if bound > 0 else 1.1 * bound - 1e-6  # 0: no real root below 0, no real pair of eigenvalues


#: A lower bound of int w''^2 / int w^2 over clamped w (w = w' = 0 at both ends): beta^4 of the first clamped beam
#: mode (cos(beta) cosh(beta) = 1), rounded down.
_CLAMPED_BENDING = F_CLAMPED * (1.0 - 1e-12)


def _stiffness_positive(params: RodParameters, B, omega) -> np.ndarray:
    """Where a proof finds the stiffness K positive definite at (B, omega) (arrays; T, P, R, f from params):
    True there, False where none is found.

    For unit |q| = (|u|^2 + |v|^2)^(1/2), U = |u|, V = |v|, x = |v''| / V and y = |u''| / U (both >= beta^2,
    :data:`_CLAMPED_BENDING` = beta^4), |w'|^2 >= pi^2 |w|^2 (w = 0 at both ends), |w'|^2 = -(w, w'') <= x |w|^2
    and the load's term 2 B int u' v >= -2 |B| U |v'| >= -2 |B| U V x^(1/2):
    q^T K q >= A U^2 + C(x) V^2 - 2 |B| x^(1/2) U V, with A = min over y of (R/f) y^2 + a_u (pi^2 or y) - omega^2
    and C(x) = x^2 / f + a_v (pi^2 or x) - omega^2 (pi^2 for a >= 0, else x), a_u = T + P R omega^2,
    a_v = T + P omega^2. That 2 x 2 form is positive for every x >= beta^2 iff A > 0 and A C(x) - B^2 x > 0 there
    (a convex quadratic in x: its least value at the vertex or at beta^2). K > 0 with M > 0 and G skew: every
    eigenvalue lies on the imaginary axis (Lagrange), so every root mu of E is real and positive (no real pair, no
    complex pair). Exact at B = 0, T = P = 0 (the weak beam's first clamped mode: omega^2 = beta^4 R / f); looser
    with load and compression. A relative margin of 1e-9 keeps round-off out of the proof."""
    B, omega = np.broadcast_arrays(np.abs(np.asarray(B, dtype=float)), np.asarray(omega, dtype=float))
    w2 = omega**2
    b2 = math.sqrt(_CLAMPED_BENDING)
    cu, cv = params.R / params.f, 1.0 / params.f
    au, av = params.T + params.P * params.R * w2, params.T + params.P * w2
    yu = np.maximum(b2, -au / (2.0 * cu))
    A = np.where(au >= 0.0, cu * _CLAMPED_BENDING + au * math.pi**2, cu * yu**2 + au * yu) - w2
    A_scale = cu * _CLAMPED_BENDING + np.abs(au) * (math.pi**2 + yu) + w2
    s, t = np.minimum(av, 0.0), np.maximum(av, 0.0) * math.pi**2 - w2  # C(x) = cv x^2 + s x + t
    good = A > 1e-9 * A_scale
    with np.errstate(all="ignore"):
        x = np.maximum(b2, (B**2 - A * s) / (2.0 * A * cv))
        h = A * cv * x**2 + (A * s - B**2) * x + A * t
        h_scale = A * cv * x**2 + np.abs(A * s - B**2) * x + np.abs(A * t)
    return good & (h > 1e-9 * h_scale)


def _definite(params: RodParameters) -> bool:
    """:func:`_stiffness_positive` at params."""
    return bool(_stiffness_positive(params, params.B, params.omega))


@dataclass(frozen=True)
class _Sample:
    """Real roots of E(.; p) at one point p of a line: their approximate positions (sorted),
    the counts below and above mu = 0 (all counted above for a line in Omega) and the signs of E at the
    cuts."""

    p: float
    roots: tuple[float, ...]
    n_neg: int
    n_pos: int
    top: tuple[float, ...]


def _positive_grid(params: RodParameters, ends: list[RodParameters], density: float) -> tuple[float, np.ndarray]:
    """(mu_cut, grid on (0, mu_cut] uniform in the Weyl mode count) of a line whose ends are ``ends``."""
    mu_cut = cut(params, ends)
    fine = np.concatenate([[0.0], np.geomspace(1e-9 * mu_cut, mu_cut, 4000)])
    count = mode_count(params, fine, params.T)
    n = max(int(math.ceil(density * count[-1])), 16)
    return mu_cut, np.interp(np.linspace(0.0, count[-1], n + 1), count, fine)[1:]


def _sign_roots(mu: np.ndarray, E: np.ndarray) -> list[float]:
    """The roots of E on the grid mu where it changes sign (secant between the two samples) or is zero."""
    s = np.sign(E)
    j = np.nonzero(s[:-1] * s[1:] < 0)[0]
    return (mu[j] + (mu[j + 1] - mu[j]) * E[j] / (E[j] - E[j + 1])).tolist() + mu[s == 0].tolist()


def _dips(i: int, mu: np.ndarray, E: np.ndarray) -> list[tuple]:
    """The candidates of :func:`_close_pairs` in row i: the samples of E on the grid mu where |E| has a local
    minimum without a change of sign."""
    s = np.sign(E)
    aE = np.abs(E)
    j = np.nonzero((s[:-2] == s[1:-1]) & (s[1:-1] == s[2:]) & (aE[1:-1] < aE[:-2]) & (aE[1:-1] < aE[2:]))[0] + 1
    return [(i, mu[k - 1], mu[k + 1], s[k], max(aE[k - 1], aE[k + 1]), 1.0, E[k - 1], E[k + 1]) for k in j]


def _close_pairs(evaluate, ps: np.ndarray, cand: list) -> list[tuple[int, list[float]]]:
    """Close pairs of roots of E = evaluate(p, mu) at the dips of |E| between grid points: each dip is zoomed in
    (9 points, 8 levels, all dips in one evaluation per level) until E changes sign (two
    roots), the dip clearly stays off zero (parabola through its three lowest points), or it
    touches zero (a double root). ``cand``: (row, ends of the dip, sign of E there, scale of E, last
    parabola's minimum over the lowest sample, E at the ends and, past the first level, at the middle, which is
    the last level's lowest sample): E is evaluated only at the points it is not known at."""
    found = []
    t = np.linspace(0.0, 1.0, 9)
    for level in range(8):
        if not cand:
            break
        a = np.array([c[1] for c in cand])
        b = np.array([c[2] for c in cand])
        x = a[:, None] + (b - a)[:, None] * t[None, :]
        x[:, -1] = b
        E = np.empty(x.shape)
        E[:, 0], E[:, -1] = [c[6] for c in cand], [c[7] for c in cand]
        new = np.array([1, 2, 3, 5, 6, 7] if level else range(1, 8))
        if level:
            E[:, 4] = [c[8] for c in cand]
        E[:, new] = evaluate(np.array([ps[c[0]] for c in cand])[:, None], x[:, new])
        nxt = []
        for c, xi, Ei in zip(cand, x, E):
            i, sg, size = c[0], c[3], c[4]
            flips = np.nonzero(np.sign(Ei[:-1]) != np.sign(Ei[1:]))[0]
            if flips.size >= 2:  # each root where the secant crosses zero (a midpoint could put a root
                # just above mu = 0 below it, and count it with the real pairs, when E is tiny at a node)
                j = flips[[0, -1]]
                found.append((i, (xi[j] + (xi[j + 1] - xi[j]) * Ei[j] / (Ei[j] - Ei[j + 1])).tolist()))
                continue
            m = int(np.argmin(np.abs(Ei[1:-1]))) + 1
            e0, e1, e2 = sg * Ei[m - 1], sg * Ei[m], sg * Ei[m + 1]
            curv = e0 - 2 * e1 + e2
            low = e1 - (e2 - e0) ** 2 / (8 * curv) if curv > 0 else e1
            if abs(Ei[m]) <= 1e3 * _EPS * size:
                found.append((i, [xi[m], xi[m]]))  # touching to rounding: a double root
            elif low < 0.5 * e1 or level < 2:  # the parabola is rough on the first levels
                nxt.append((i, xi[m - 1], xi[m + 1], sg, size, low / e1, Ei[m - 1], Ei[m + 1], Ei[m]))
        cand = nxt
    # after 8 levels (4^8 finer) the parabola through the lowest samples still has its minimum at zero
    # or below it: E falls like the square of the distance, a double root or a pair closer than the
    # samples (R = 1 at omega = 0: E is a square; R near 1 under tension: the u and v string modes)
    return found + [(c[0], [0.5 * (c[1] + c[2])] * 2) for c in cand if c[5] <= 1e-3]


def _pair_brackets(evaluate, ps: np.ndarray, dips: list) -> tuple[list[tuple[int, float, float]], list[tuple[int, float]]]:
    """The close pairs at ``dips`` (:func:`_close_pairs`) as brackets of single roots: (row, lo, hi) from each
    dip's end to the pair's middle, where E has the other sign; and the pairs that touch (a double root), (row, mu)."""
    split, touching = [], []
    for row, (r1, r2) in _close_pairs(evaluate, ps, dips):
        a, b = next(((c[1], c[2]) for c in dips if c[0] == row and c[1] <= r1 and r2 <= c[2]), (r1, r2))
        if r1 == r2:
            touching.append((row, r1))
        elif a < r1 < r2 < b:
            m = 0.5 * (r1 + r2)
            split += [(row, a, m), (row, m, b)]
    return split, touching


class _Line:
    """E along one axis ("B" or "omega"; T, P, R, f from params) on a fixed mu grid.

    ``signed``: the roots below 0 are real pairs of eigenvalues (unstable); ``cuts``: (index in the grid,
    side) of each end of the counted interval (+1: roots are counted below it, -1: above it)."""

    signed = True

    def __init__(self, params: RodParameters, axis: str, lo: float, hi: float, route: str = "auto",
                 factor: float = 1.0, shift: int = 0, density: float = 5.0):
        self.params, self.axis, self.route, self.factor, self.shift = params, axis, route, factor, shift
        ends = [params.with_(**{axis: x}) for x in (lo, hi)]
        B_max = max(abs(e.B) for e in ends)
        w_max = max(abs(e.omega) for e in ends)
        self.mu_lo = _rayleigh_floor(params, B_max, w_max, params.T)
        self.mu_cut, pos = _positive_grid(params, ends, density)
        # negative side: uniform in sqrt(-mu); positive side: uniform in the Weyl mode count
        neg = -np.linspace(math.sqrt(-self.mu_lo), 0.0, 48, endpoint=False) ** 2
        above = self.mu_cut + (pos[-1] - pos[-2]) * np.arange(1, 4)  # past the cut: dips next to it are seen
        self.mu = np.unique(np.concatenate([neg, [0.0], pos, [self.mu_cut], above]))
        self.cuts = ((int(np.nonzero(self.mu == self.mu_cut)[0][0]), 1),)
        self.evaluations = 0
        self.schur_left = SCHUR_BUDGET

    def frequency(self, x: float) -> float:
        """Omega at the root x of the line's variable."""
        return math.sqrt(abs(x))

    def alternative(self, lo: float, hi: float) -> _Line:
        """The second formulation: the Schur route while the exponents span less than 4 decades
        (its error is eps times the largest), else other scales and another split."""
        if _separation(self.params, self.axis, hi) < 1e4:
            return type(self)(self.params, self.axis, lo, hi, route="schur")
        return type(self)(self.params, self.axis, lo, hi, factor=1.37, shift=1)

    def _values(self, p: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, int]:
        return _characteristic(self.params, x, **{self.axis: p}, route=self.route, factor=self.factor,
                               shift=self.shift, schur_budget=self.schur_left)

    def E(self, p, mu) -> np.ndarray:
        """E at (axis = p, mu), broadcast."""
        p, mu = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(mu, dtype=float))
        self.evaluations += p.size
        out, slow = self._values(p, mu)
        if self.route == "auto":
            self.schur_left -= slow
        return out

    def samples(self, ps) -> list[_Sample]:
        """The real roots of E on the mu grid at each p of ps (one vectorised evaluation, then
        the close pairs of all rows refined together). Where the stiffness is proven positive
        (:func:`_stiffness_positive`: every root real and positive) only the grid from mu = 0 up is sampled
        (SET's spin line to omega = 2: 37 % of its samples; the load line at its operating spin: 26 %)."""
        ps = np.atleast_1d(np.asarray(ps, dtype=float))
        start = np.zeros(ps.size, dtype=int)
        if self.signed and self.mu[0] < 0.0:
            B, omega = (ps, self.params.omega) if self.axis == "B" else (self.params.B, ps)
            start[_stiffness_positive(self.params, B, omega)] = int(np.searchsorted(self.mu, 0.0))
        rows = np.full((ps.size, self.mu.size), np.nan)
        for first in np.unique(start):
            at = start == first
            rows[at, first:] = self.E(ps[at, None], self.mu[None, first:])
        if not all(np.all(np.isfinite(row[k:])) for row, k in zip(rows, start)):
            raise ArithmeticError(f"characteristic function not finite on the {self.axis} line")
        roots: list[list[float]] = []
        cand = []
        for i, (row, k) in enumerate(zip(rows, start)):
            E, mu = row[k:], self.mu[k:]
            roots.append(_sign_roots(mu, E))
            cand += _dips(i, mu, E)
        for i, pair in _close_pairs(self.E, ps, cand):
            roots[i] += pair
        out = []
        for p, r, E in zip(ps, roots, rows):
            r = np.sort(np.asarray(r, dtype=float))
            r = r[(r < self.mu_cut) & (r > self.mu_lo)]
            neg = int(np.sum(r < 0)) if self.signed else 0
            out.append(_Sample(float(p), tuple(r.tolist()), neg, r.size - neg,
                               tuple(float(E[i]) for i, _ in self.cuts)))
        return out

    def rechecked(self, poor: _Sample, rich: _Sample) -> _Sample:
        """``poor`` with the pair of real roots that ``rich`` (a neighbouring sample) has and ``poor`` lacks, where a
        fine scan at poor.p finds it, else ``poor``: the u and v roots of a nearly round wire come in pairs closer
        than the grid's samples, and a pair between two samples with no dip at either looked like a fold, two real
        roots turned into a complex pair (R = 0.97 spun at 2.6: a flutter load 0.772 where the collocation spectrum
        first grows past 0.775). The scan: 257 points and the grid's own between the grid points next outside the
        pair's neighbours in ``rich`` (so that poor's roots there, each between two grid points, are counted alike),
        with its dips."""
        r = rich.roots
        if len(r) != len(poor.roots) + 2:
            return poor
        j = _vanishing_pair(rich, poor)
        mu = self.mu
        ia = max(int(np.searchsorted(mu, r[j - 1])) - 1, 0) if j > 0 else 0
        ib = min(int(np.searchsorted(mu, r[j + 2])), mu.size - 1) if j + 2 < len(r) else mu.size - 1
        lo, hi = mu[ia], min(mu[ib], self.mu_cut)
        if self.signed:  # E is only C^1 at mu = 0 (a grid point): each side on its own
            lo, hi = (max(lo, 0.0), hi) if r[j] > 0 else (lo, min(hi, 0.0))
        x = np.union1d(np.linspace(lo, hi, 257), mu[(mu >= lo) & (mu <= hi)])
        E = self.E(np.full(x.size, poor.p), x)
        found = _sign_roots(x, E)
        for _, pair in _close_pairs(self.E, np.array([poor.p]), _dips(0, x, E)):
            found += pair
        old = [v for v in poor.roots if lo <= v <= hi]
        if len(found) < len(old) + 2:
            return poor
        roots = np.sort(np.array([v for v in poor.roots if not lo <= v <= hi] + found))
        neg = int(np.sum(roots < 0)) if self.signed else 0
        return replace(poor, roots=tuple(roots.tolist()), n_neg=neg, n_pos=roots.size - neg)

    # --- bookkeeping along the line ----------------------------------------------------------

    def cut_crossing(self, a: _Sample, b: _Sample, samples: int = CUT_SAMPLES) -> int:
        """Change of the number of counted roots from a to b that comes through the cuts (each root that
        entered +1, each that left -1). E at a cut is sampled on ``samples`` points between a and b: the
        high modes move together with the load or spin, and two of them can pass a cut between two samples
        of the line, leaving the sign of E there unchanged: those show as a dip of |E| and are split as the
        samples' close pairs are."""
        return int(self.cut_crossings([a, b], samples)[0])

    def cut_crossings(self, smp: list[_Sample], samples: int = CUT_SAMPLES) -> np.ndarray:
        """:meth:`cut_crossing` from each sample to the next, E at each cut in one evaluation for all."""
        ps = np.array([np.linspace(a.p, b.p, samples) for a, b in zip(smp[:-1], smp[1:])])
        out = np.zeros(len(smp) - 1, dtype=int)
        for k, (i, side) in enumerate(self.cuts):
            x = self.mu[i]
            top = self.E(ps.ravel(), np.full(ps.size, x)).reshape(ps.shape)
            top[:, 0] = [a.top[k] for a in smp[:-1]]
            top[:, -1] = [b.top[k] for b in smp[1:]]
            r, j = np.nonzero(np.sign(top[:, :-1]) * np.sign(top[:, 1:]) < 0)
            lo, hi, rows = list(ps[r, j]), list(ps[r, j + 1]), list(r)
            # two roots through the cut between two points (the dense high modes of a fast spin: 209 roots
            # below the cut at omega = 17 of a taut tether, where they went uncounted and a stability change
            # with no root on the move could not be isolated): a dip of |E|, each root of the pair bracketed by
            # the dip's ends and the pair's middle
            dips = [c for row in range(ps.shape[0]) for c in _dips(row, ps[row], top[row])]
            split, _ = _pair_brackets(lambda _, t, x=x: self.E(t, np.full(t.shape, x)), np.zeros(ps.shape[0]), dips)
            for row, a, b in split:  # a touching pair passes nothing
                lo, hi, rows = lo + [a], hi + [b], rows + [row]
            np.add.at(out, np.asarray(rows, dtype=int),
                      self._through_cut(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float), x, side))
        return out

    def _through_cut(self, pa: np.ndarray, pb: np.ndarray, x: float, side: int) -> np.ndarray:
        """For each root of E at the cut x between pa and pb (arrays): +1 if it enters the counted side as p goes
        from pa to pb, else -1 (side +1: counted below x, -1: above). All roots at once
        (:func:`~etcheck.numerics.optimize.bracketed_roots`, one evaluation of E per pass for all), then the
        sign of dmu/dp = -E_p / E_mu there by central differences."""
        if pa.size == 0:
            return np.zeros(0, dtype=int)
        n = pa.size
        at = np.full(n, x)
        pc = bracketed_roots(lambda p: self.E(p, at), np.minimum(pa, pb), np.maximum(pa, pb))
        hp = 1e-6 * np.maximum(np.abs(pb - pa), 1e-12)
        hm = 1e-6 * abs(x)
        e = self.E(np.concatenate([pc - hp, pc + hp, pc, pc]),
                   np.concatenate([at, at, at - hm, at + hm])).reshape(4, n)
        dx_dp = -((e[1] - e[0]) / (2 * hp)) / ((e[3] - e[2]) / (2 * hm))
        return np.where(dx_dp * np.sign(pb - pa) * side > 0, -1, 1)

    # --- a fold of the real roots: flutter ----------------------------------------------------

    def extremum(self, p: float, mu0: float, sg: float, lo: float, hi: float) -> tuple[float, float]:
        """(mu, sg E) at the local minimum of sg E(., p) next to mu0 in (lo, hi): Newton's method on
        dE/dmu with central differences, bounded minimisation where the curvature has the wrong sign."""
        h = 1e-5 * (hi - lo)
        m = mu0
        for _ in range(40):
            e = sg * self.E(p, np.array([m - h, m, m + h]))
            d1, d2 = (e[2] - e[0]) / (2 * h), (e[2] - 2 * e[1] + e[0]) / h**2
            if not d2 > 0:
                res = minimize_scalar(lambda x: sg * self.E(p, x).item(), bounds=(lo, hi), method="bounded",
                                      options={"xatol": 1e-10 * (hi - lo)})
                return float(res.x), float(res.fun)
            new = min(max(m - d1 / d2, lo + h), hi - h)
            if abs(new - m) <= 1e-9 * (hi - lo):
                m = new
                break
            m = new
        return m, sg * self.E(p, m).item()


class _IsoLine(_Line):
    """D+ of :mod:`etcheck.rod.straight.undamped_isotropic` (R = 1) along one axis on a fixed grid in Omega over
    [-Omega_cut, Omega_cut] (Omega_cut^2 the mu cut of :class:`_Line`): the rod is stable iff every root of
    D+ is real, so every root counts alike (a real pair of eigenvalues is a complex pair Omega = +-i sigma
    here) and roots enter or leave through both cuts."""

    signed = False

    def __init__(self, params: RodParameters, axis: str, lo: float, hi: float, route: str = "auto",
                 factor: float = 1.0, shift: int = 0, density: float = 5.0):
        self.params, self.axis, self.route, self.factor, self.shift = params, axis, route, factor, shift
        mu_cut, pos = _positive_grid(params, [params.with_(**{axis: x}) for x in (lo, hi)], density)
        om = np.sqrt(pos)
        cut = om[-1]
        above = cut + (om[-1] - om[-2]) * np.arange(1, 4)
        self.mu = np.concatenate([-above[::-1], -om[::-1], [0.0], om, above])
        self.mu_lo, self.mu_cut = -cut, cut
        self.cuts = ((3, -1), (self.mu.size - 4, 1))
        self.evaluations = 0
        self.schur_left = SCHUR_BUDGET

    def frequency(self, x: float) -> float:
        return abs(x)

    def alternative(self, lo: float, hi: float) -> _Line:
        """The second formulation: the Schur route (4 x 4, exponents of a scalar problem), or other scales and
        another split where they span more than 4 decades."""
        p = self.params.with_(**{self.axis: hi})
        span = (1.0 + abs(p.T + p.P * p.omega**2) * p.f) ** 0.5 + (abs(p.B) * p.f) ** (1 / 3) + self.mu_cut ** 0.5
        if span < 1e4:
            return _IsoLine(self.params, self.axis, lo, hi, route="schur")
        return _IsoLine(self.params, self.axis, lo, hi, factor=1.37, shift=1)

    def _values(self, p: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, int]:
        return _characteristic_plus(self.params, x, **{self.axis: p}, route=self.route, factor=self.factor,
                                    shift=self.shift, schur_budget=self.schur_left)


# --- stability along a line --------------------------------------------------------------------


@dataclass(frozen=True)
class Crossing:
    """A change of stability of the undamped straight rod along a line (dimensionless).

    ``value``: the axis value (B or omega); ``error``: absolute error
    estimate (the distance to the same point from a second formulation of
    E, doubled, plus the root-finder tolerance); ``kind``: "divergence" (a
    root mu through 0) or "flutter" (a fold of two real roots, a Krein
    collision at Omega = sqrt(mu), or its reverse); ``frequency``: Omega
    at the point (0 for divergence); ``to_unstable``: the side past it.
    """

    value: float
    error: float
    kind: str
    frequency: float
    to_unstable: bool
    bracket: tuple[float, float]


@dataclass(frozen=True)
class StabilityLine:
    """Stability of the undamped straight rod on [lo, hi] along ``axis`` (dimensionless).

    ``unstable_at_start``: the state at lo; ``crossings``: every located
    change, in order; ``windows``: the stable intervals (a window reaching
    hi ends at hi); ``pairs_at_hi``: complex pairs of roots mu at hi (to
    anchor a crossing line there); ``evaluations``: characteristic-function
    evaluations spent. Changes closer together than the sample spacing (hi - lo) /
    (samples - 1) can be missed in pairs (a window or an unstable gap
    narrower than that), as in a scan.
    """

    axis: str
    lo: float
    hi: float
    unstable_at_start: bool
    crossings: tuple[Crossing, ...]
    windows: tuple[tuple[float, float], ...]
    pairs_at_hi: int
    evaluations: int

    def unstable_at(self, x: float) -> bool:
        """The state at x in [lo, hi] (at a crossing: the side past it)."""
        state = self.unstable_at_start
        for c in self.crossings:
            if x >= c.value:
                state = c.to_unstable
        return state


def _pairs(s: _Sample, N: int) -> int:
    twice = N - s.n_neg - s.n_pos
    if twice < 0 or twice % 2:
        raise ArithmeticError(f"inconsistent root count at {s.p:.9g}: {N} roots in all, "
                              f"{s.n_neg + s.n_pos} real")
    return twice // 2


def _unstable(s: _Sample, N: int) -> bool:
    return s.n_neg > 0 or _pairs(s, N) > 0


def _separation(params: RodParameters, axis: str, x: float) -> float:
    p = params.with_(**{axis: x})
    ku, kv = _wavenumbers(p.R, p.f, np.array([p.B]), *_coefficients(p.P, p.R, p.f, p.B, p.omega, p.T, 0.0), 1.0)
    return float(max(ku[0], kv[0]) / max(2 * math.pi, 1.0))


def _static_crossing(params: RodParameters, axis: str, a: float, b: float, rtol: float) -> tuple[float, float] | None:
    """Root of D_static (= E(0)) in (a, b) along axis, and its absolute error (two formulations);
    None without a sign change."""
    base = params.with_(**{axis: 0.0})
    fn, mult = _ex._function(base, axis, 1.0)
    g = _ex._Counter(fn)
    ga, gb = g.many(np.array([a, b]))
    if np.sign(ga) == np.sign(gb):
        return None  # an even number of static points in (a, b): bisect further
    x = brentq(g, a, b, xtol=1e-300, rtol=rtol, maxiter=200)
    route = _ex._route_at(base, axis, x, mult)
    g2 = _ex._Counter(_ex._alternative(base, axis, 1.0, x, route))
    x2 = _ex._second_opinion(g2, x, rtol)
    return x, (2.0 * (abs(x - x2) + 2 * rtol * abs(x)) if math.isfinite(x2) else math.inf)


def _vanishing_pair(rich: _Sample, poor: _Sample) -> int:
    """Index j of the adjacent pair (j, j + 1) of rich's roots that poor lacks."""
    r, q = np.asarray(rich.roots), np.asarray(poor.roots)
    best, jbest = math.inf, 0
    for j in range(len(r) - 1):
        rest = np.delete(r, [j, j + 1])
        if rest.size != q.size:
            continue
        cost = float(np.sum(np.abs(rest - q))) + 1e-3 * (r[j + 1] - r[j])
        if cost < best:
            best, jbest = cost, j
    return jbest


def _fold_point(line: _Line, a: _Sample, b: _Sample, rtol: float) -> tuple[float, float, tuple]:
    """The fold (E = dE/dmu = 0) between samples a and b: Brent on the extremum value."""
    rich, poor = (a, b) if len(a.roots) > len(b.roots) else (b, a)
    j = _vanishing_pair(rich, poor)
    r = rich.roots
    lo = 0.5 * (r[j - 1] + r[j]) if j > 0 else line.mu_lo
    hi = 0.5 * (r[j + 1] + r[j + 2]) if j + 2 < len(r) else line.mu_cut
    if line.signed:  # E is only C^1 at mu = 0
        lo, hi = (max(lo, 0.0), hi) if r[j] > 0 else (lo, min(hi, 0.0))
    mu0 = 0.5 * (r[j] + r[j + 1])
    sg = -float(np.sign(line.E(rich.p, mu0).item()))  # sg E: negative between the pair, positive past the fold
    state = [mu0]

    def e(p: float) -> float:
        m, v = line.extremum(p, state[0], sg, lo, hi)
        state[0] = m
        return v

    p = brentq(e, a.p, b.p, xtol=1e-300, rtol=rtol, maxiter=200)
    return p, state[0], (sg, lo, hi)


def _fold_crossing(line: _Line, a: _Sample, b: _Sample, rtol: float) -> tuple[float, float, float]:
    """(value, absolute error, mu) of a fold between a and b, with a second formulation."""
    p, mu, (sg, lo, hi) = _fold_point(line, a, b, rtol)
    alt = line.alternative(min(a.p, b.p), max(a.p, b.p))
    state = [mu]

    def e2(x: float) -> float:
        m, v = alt.extremum(x, state[0], sg, lo, hi)
        state[0] = m
        return v

    d = 1e-13 * max(abs(p), 1e-300)
    x2 = math.nan
    for _ in range(12):
        pa, pb = max(p - d, min(a.p, b.p)), min(p + d, max(a.p, b.p))
        ea, eb = e2(pa), e2(pb)
        if ea * eb <= 0:  # a sign change (False where the second formulation gives no value: widen)
            try:
                x2 = brentq(e2, pa, pb, xtol=max(1e-2 * d, 4 * _EPS * abs(p)), rtol=rtol, maxiter=200)
                break
            except ValueError:  # the tracked extremum jumped to another one between calls: widen
                state[0] = mu
        d *= 10.0
    line.evaluations += alt.evaluations
    err = 2.0 * (abs(p - x2) + 2 * rtol * abs(p)) if math.isfinite(x2) else math.inf
    return p, err, mu


#: Bisections of a fold's bracket before Brent's method (the extremum must stay in its window).
_SHRINK = 5
#: Relative width below which a fold that Brent's method cannot follow is taken as located by bisection of the
#: root counts (its error is the width).
_PINNED = 1e-12


def _locate(line: _Line, a: _Sample, Na: int, b: _Sample, Nb: int, rtol: float, depth: int = 0) -> Crossing:
    """The change of stability between samples a and b (bisecting until it is a single event)."""
    ca, cb = _pairs(a, Na), _pairs(b, Nb)
    dneg, dpos, dc = b.n_neg - a.n_neg, b.n_pos - a.n_pos, cb - ca
    to_unstable = _unstable(b, Nb)
    bracket = (a.p, b.p)
    static = None
    if dc == 0 and dneg == -dpos and 0 < abs(dneg) <= 2:
        static = _static_crossing(line.params, line.axis, min(a.p, b.p), max(a.p, b.p), rtol)
    if static is not None:
        return Crossing(*static, CriticalKind.DIVERGENCE, 0.0, to_unstable, bracket)
    fold = abs(dc) == 1 and ((dneg == -2 * dc and dpos == 0) or (dpos == -2 * dc and dneg == 0))
    if fold and depth >= _SHRINK:
        try:
            x, err, mu = _fold_crossing(line, a, b, rtol)
            return Crossing(x, err, CriticalKind.FLUTTER, line.frequency(mu), to_unstable, bracket)
        except ValueError:  # the extremum followed by Brent's method jumped to another one: a narrower bracket
            if abs(b.p - a.p) <= _PINNED * max(abs(a.p), abs(b.p)):  # located by the root counts alone
                rich = a if len(a.roots) > len(b.roots) else b
                j = _vanishing_pair(rich, b if rich is a else a)
                mu = 0.5 * (rich.roots[j] + rich.roots[j + 1])
                return Crossing(0.5 * (a.p + b.p), abs(b.p - a.p), CriticalKind.FLUTTER, line.frequency(mu),
                                to_unstable, bracket)
    if depth > 60:
        raise ArithmeticError(f"could not isolate the change of stability in [{a.p:.12g}, {b.p:.12g}]")
    m = line.samples([0.5 * (a.p + b.p)])[0]
    m = line.rechecked(line.rechecked(m, a), b)
    Nm = Na + line.cut_crossing(a, m)
    if _unstable(m, Nm) != _unstable(a, Na):
        return _locate(line, a, Na, m, Nm, rtol, depth + 1)
    return _locate(line, m, Nm, b, Nb, rtol, depth + 1)


def stability_line(params: RodParameters, axis: str, lo: float, hi: float, anchor: float | None = None,
                   pairs: int = 0, samples: int = 25, rtol: float = 4 * _EPS) -> StabilityLine:
    """Every change of stability of the undamped straight rod on [lo, hi] along ``axis``.

    ``axis``: "B" or "omega" (the other values, T, P, R, f from params;
    gamma is ignored: undamped). ``anchor``: a point of the line where the
    number of complex pairs of roots mu (flutter pairs) is known,
    ``pairs`` (default: lo with none, true at omega = 0 where the problem is
    self-adjoint). Samples the real roots of E on ``samples`` equally
    spaced points, follows the total number of roots below the cut, and
    locates each change of stability between samples exactly: a divergence
    point as a root of E(0) = D_static, a flutter point as the zero of the
    extremum value of E (a fold, E = dE/dmu = 0). For R = 1 the line follows D+ of
    :mod:`etcheck.rod.straight.undamped_isotropic` instead (``pairs``: complex pairs of its roots Omega). Dimensionless.
    """
    if axis not in ("B", "omega"):
        raise ValueError(f"axis must be 'B' or 'omega', got {axis!r}")
    if not hi > lo:
        raise ValueError("the line needs hi > lo")
    anchor = lo if anchor is None else float(anchor)
    return _stability_line(params.with_(gamma=0.0, **{axis: 0.0}), axis, float(lo), float(hi), anchor, int(pairs),
                           int(samples), float(rtol))


@lru_cache(maxsize=256)
def _stability_line(params: RodParameters, axis: str, lo: float, hi: float, anchor: float, pairs: int, samples: int,
                    rtol: float) -> StabilityLine:
    """:func:`stability_line` on params with the axis value and gamma zeroed (neither enters): memoised, as in a
    sweep the spin line at the operating load is the same for every spin of a length."""
    # every static point of the line with a sample just either side: an interval bounded by two static
    # points (between the critical speeds) is never narrower than the sampling
    static = _static_roots(params, axis, hi)
    static = static[static > lo]
    near = np.concatenate([static * (1 - 1e-6), static * (1 + 1e-6)])
    ps = np.unique(np.concatenate([np.linspace(lo, hi, samples), [anchor], near[(near > lo) & (near < hi)]]))
    line = (_IsoLine if params.R == 1.0 else _Line)(params, axis, lo, hi)
    if line.mu.size > MAX_GRID * (2 if params.R == 1.0 else 1):
        raise ArithmeticError(f"the {axis} line to {hi:.6g} needs {line.mu.size} mu samples per point (more than "
                              f"{MAX_GRID}: too many modes below its cut)")
    smp = line.samples(ps)
    ia = int(np.nonzero(ps == anchor)[0][0])
    N = [0] * len(smp)
    N[ia] = smp[ia].n_neg + smp[ia].n_pos + 2 * pairs
    through = line.cut_crossings(smp)  # from each sample to the next
    for i in range(ia + 1, len(smp)):
        N[i] = N[i - 1] + int(through[i - 1])
    for i in range(ia - 1, -1, -1):
        N[i] = N[i + 1] - int(through[i])
    for i in range(len(smp) - 1):  # a pair of real roots that one sample has and the next lacks: looked for again
        smp[i + 1] = line.rechecked(smp[i + 1], smp[i])
        smp[i] = line.rechecked(smp[i], smp[i + 1])
    flags = [_unstable(s, n) for s, n in zip(smp, N)]
    crossings = [_locate(line, smp[i], N[i], smp[i + 1], N[i + 1], rtol)
                 for i in range(len(smp) - 1) if flags[i] != flags[i + 1]]
    windows = stable_windows(crossings, lo, hi, bool(flags[0]))
    return StabilityLine(axis, float(lo), float(hi), bool(flags[0]), tuple(crossings), tuple(windows),
                         _pairs(smp[-1], N[-1]), line.evaluations)


# --- critical values at an operating point -------------------------------------------------------


@dataclass(frozen=True)
class UndampedCritical:
    """Critical values of the undamped straight rod at one operating point (dimensionless).

    ``critical_load``: first loss of stability as B grows from 0 at the
    operating omega and T; ``critical_spin``: as omega grows from 0 at the
    operating B and T (both :class:`~etcheck.rod.straight.spectral.CriticalPoint`,
    absolute errors, N = 0: no grid); ``windows``: the stable spin
    intervals at the operating load up to ``scanned_to``; ``stable``: the
    operating point itself; ``evaluations``: characteristic-function
    evaluations spent.
    """

    critical_load: CriticalPoint
    critical_spin: CriticalPoint
    windows: tuple[tuple[float, float], ...]
    scanned_to: float
    stable: bool
    evaluations: int

    @property
    def converged(self) -> bool:
        return self.critical_load.converged and self.critical_spin.converged


def _static_roots(params: RodParameters, axis: str, upto: float, n: int = 400) -> np.ndarray:
    """The static points (roots of D_static) on axis in (0, upto] that change its sign on a grid of n,
    each refined by Brent's method to 1e-9 (sample positions of the lines, not critical values). Read-only."""
    return _static_roots_of(params.with_(gamma=0.0, **{axis: 0.0}), axis, float(upto), int(n))


@lru_cache(maxsize=256)
def _static_roots_of(params: RodParameters, axis: str, upto: float, n: int) -> np.ndarray:
    fn, _ = _ex._function(params, axis, 1.0)
    x = np.linspace(0.0, upto, n + 1)[1:]
    g = fn(x)
    i = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]
    lo, hi = list(x[i]), list(x[i + 1])
    # a close pair between two samples (R near 1: the u and v modes' static points, 0.43 apart at B = 318 of a taut
    # tether, its 400 samples 0.8 apart) shows as a dip of |D|: split as the lines split theirs, each root then
    # bracketed by the dip's ends and the pair's middle, where D has the other sign
    split, touching = _pair_brackets(lambda _, t: fn(t.ravel()).reshape(t.shape), np.zeros(1), _dips(0, x, g))
    lo += [a for _, a, _ in split]
    hi += [b for _, _, b in split]
    # all brackets at once (Chandrupatla, one evaluation of fn per step on the unfinished ones)
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    out = find_root(fn, (lo, hi), tolerances={"xrtol": 1e-9}).x if lo.size else np.zeros(0)
    out = np.sort(np.concatenate([out, [r for _, r in touching]]))
    out.setflags(write=False)
    return out


def _spin_hi(r: np.ndarray) -> float:
    """End of the spin line (as the spectral scan's default) from the static spins r of the rod:
    max(2, 1.25 x the second)."""
    return float(max(2.0, 1.25 * r[1])) if r.size >= 2 else 2.0


def _point(line: StabilityLine, tol: float) -> CriticalPoint:
    """The first loss of stability on a line as a CriticalPoint (value, kind, absolute error)."""
    axis, lo, hi = line.axis, line.lo, line.hi
    if line.unstable_at_start:
        return CriticalPoint(axis, lo, CriticalKind.UNSTABLE_AT_START, (lo, lo), 0.0, True,
                             f"already unstable at {axis} = {lo:g} ({MODEL})", 0)
    first = next((c for c in line.crossings if c.to_unstable), None)
    if first is None:
        return CriticalPoint(axis, math.nan, CriticalKind.NONE_FOUND, (lo, hi), math.nan, False,
                             f"stable on the scanned range {axis} in [{lo:g}, {hi:g}] ({MODEL})", 0)
    conv = bool(math.isfinite(first.error) and first.error <= tol * max(abs(first.value), 1e-3))
    at = f" at Omega = {first.frequency:.9g}" if first.kind == CriticalKind.FLUTTER else ""
    msg = (f"first instability at {axis} = {first.value:.12g} ({first.kind}{at}; {MODEL}); "
           f"error estimate {first.error:.2e} (two formulations)")
    return CriticalPoint(axis, first.value, first.kind, (first.value, first.value), first.error, conv, msg, 0)


@single_blas_thread
def undamped_critical(params: RodParameters, tol: float = 1e-8, windows: bool = True,
                      spin: bool = True) -> UndampedCritical:
    """Critical load, critical spin, stable spin windows and stability of the undamped straight rod.

    Dimensionless; gamma is ignored (undamped). Three lines of
    :func:`stability_line`: the spin line of the unloaded rod up to the
    operating spin (it anchors the next one: complex pairs at (0, omega)),
    the load line at the operating spin from 0 to just past its first
    static point (stable before it means unstable past it: a root mu goes
    negative), and the spin line at the operating load from 0 (self-adjoint
    there) to max(2, 1.25 x its second static point, 1.1 x the operating
    spin) with ``windows``, else to just past its first static point and
    the operating spin. Same shapes as the spectral scans of
    :mod:`etcheck.rod.straight.spectral` (critical_load, scan_line); errors are
    absolute, from a second formulation of E; ``tol`` is relative.
    ``spin=False`` (with B > 0) skips the spin line at the operating load: the critical spin is not asked
    (NaN) and the operating point is judged on the load line (stable iff below its first instability).
    """
    p = params.with_(gamma=0.0)
    if p.R == 1.0:
        return _isotropic(p, tol, windows, spin)
    if not spin and p.B > 0:
        return _load_only(p, tol)
    # the spin line and what the load line needs are independent: on two cores a forked helper follows the load
    # line meanwhile (pure work; in a sweep worker or on one core only where it is needed, after the spin line)
    jobs = [lambda: _spin_line(p, _spin_end(p, windows), windows), lambda: _load_part(p)]
    (spin_line, why), *ahead = split_map(lambda job: job(), jobs) if can_split() else [jobs[0]()]
    if spin_line is None:  # no spin: the load decides (self-adjoint); the critical spin is not answered
        return _without_spin(p, tol, why)
    stable, spent = _operating_stable(p, spin_line)
    evaluations = spin_line.evaluations + spent
    load_part = ahead[0] if ahead else _load_part(p)
    if isinstance(load_part, Exception):
        raise load_part
    if load_part is None:  # the unloaded rod already has a real pair at this spin
        load = CriticalPoint("B", 0.0, CriticalKind.UNSTABLE_AT_START, (0.0, 0.0), 0.0, True,
                             f"already unstable at B = 0: a real pair of eigenvalues ({MODEL})", 0)
        return UndampedCritical(load, _point(spin_line, tol), spin_line.windows, spin_line.hi, stable, evaluations)
    static, followed = load_part
    if followed is None:  # not gyroscopic (w = 0): K q = mu M q, stable exactly below the first static load
        return UndampedCritical(_point(_static_line(static), tol), _point(spin_line, tol), spin_line.windows,
                                spin_line.hi, stable, evaluations + static.evaluations)
    load_line, spent = followed
    return UndampedCritical(_point(load_line, tol), _point(spin_line, tol), spin_line.windows, spin_line.hi, stable,
                            evaluations + spent)


def _spin_end(p: RodParameters, windows: bool) -> float:
    """End of the spin line at the operating load (R < 1): just past the first static spin, or with ``windows``
    as far as :func:`_spin_hi` unless that would cost more than :data:`MAX_GRID` samples per point."""
    if windows:  # most lines end at 2: then the line's own scan of its static spins tells (memoised for it)
        near = _static_roots(p, "omega", 2.0)
        if near.size >= 2 and 1.25 * near[1] <= 2.0 and _Line(p, "omega", 0.0, 2.0).mu.size <= MAX_GRID:
            return 2.0
    first = _static_roots(p, "omega", max(8.0 * _ex._root_scale(p, "omega", 1.0), 4.0))
    short = max(1.02 * first[0] if first.size else 2.0, 1e-3)  # stable at rest: unstable past the first static spin
    if not windows:
        return short
    spin_hi = _spin_hi(first)
    # windows past the first static spin would cost too many samples: not sought
    return short if _Line(p, "omega", 0.0, spin_hi).mu.size > MAX_GRID else spin_hi


def _operating_stable(p: RodParameters, spin_line: StabilityLine) -> tuple[bool, int]:
    """Whether the operating point is stable, from the spin line at the operating load where it reaches the
    operating spin, else from the complex pairs there; and the evaluations that took beyond the line's."""
    if p.omega <= spin_line.hi:
        return not spin_line.unstable_at(p.omega), 0
    if has_real_pair(p):  # a real pair of eigenvalues: unstable whatever the complex ones do
        return False, 0
    pairs, real, spent = _complex_pairs(p)
    return pairs == 0 and not real, spent


def _load_part(p: RodParameters):
    """What :func:`undamped_critical` needs for the critical load, independent of the spin line: None when the
    unloaded rod has a real pair at the operating spin (unstable at B = 0), else (the first static load at B = 0,
    the load line with its evaluations, or None without spin); an error met on the way is returned, to be raised
    only where the result is used."""
    try:
        if p.omega > 0 and has_real_pair(p.with_(B=0.0)):
            return None
        static = _ex.exact_root(p.with_(B=0.0), "B")
        return static, (_load_line(p, static) if p.omega != 0 else None)
    except (ArithmeticError, ValueError) as exc:
        return exc


def _at_rest(p: RodParameters):
    """The first static load of the rod at rest (omega = 0, ExactRoot): for R = 1 the undamped rod is stable at
    every spin below it (:mod:`etcheck.rod.straight.undamped_isotropic`: a hyperbolic pencil)."""
    return _ex.exact_root(p.with_(B=0.0, omega=0.0), "B")


def _isotropic(p: RodParameters, tol: float, windows: bool, spin: bool) -> UndampedCritical:
    """:func:`undamped_critical` for R = 1 on the lines of D+ (roots that never touch), with the bound of
    :mod:`etcheck.rod.straight.undamped_isotropic`: below the static load at rest B_s the rod is stable at every spin,
    so only loads past B_s (and spins at such loads) are followed."""
    if p.T <= -4 * math.pi**2 / p.f:  # the clamped Euler load: K_B is not positive at B = 0
        raise ArithmeticError("R = 1 compressed past its clamped Euler load: the undamped isotropic lines need "
                              "a rod stable at rest")
    rest = _at_rest(p)
    below = p.B < rest.value
    w = p.omega
    if w == 0:
        static = rest
        load_line, spent = _static_line(static), static.evaluations
    else:
        scale = _ex._root_scale(p, "B", 1.0)
        roots = _static_roots(p, "B", 16 * scale)
        load_hi = 1.1 * roots[2] if roots.size >= 3 else 2.0 * roots[-1] if roots.size else 16 * scale
        # stable (every root real) up to B_s: the line starts short of it, where no two roots are close
        lo = 0.98 * rest.value
        load_line = replace(stability_line(p, "B", lo, max(load_hi, 1.25 * rest.value)), lo=0.0)
        early = [c for c in load_line.crossings if c.value + c.error < rest.value * (1 - 1e-12)]
        if early:  # the hyperbolic bound says otherwise: the line's root counts are wrong (a dense spectrum)
            raise ArithmeticError(f"a change of stability at B = {early[0].value:.12g}, below the static load at "
                                  f"rest {rest.value:.12g}, where none can be: the root counts are not resolved")
        spent = rest.evaluations + load_line.evaluations
    load = _point(load_line, tol)
    if below:
        stable = True
    elif w == 0:
        stable = False  # past the static load at rest: a real pair of eigenvalues
    elif p.B <= load_line.hi:
        stable = not load_line.unstable_at(p.B)
    else:
        stable = None
    if not spin and p.B > 0 and stable is not None:
        none = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, True,
                             "critical spin not asked", 0)
        return UndampedCritical(load, none, (), 0.0, stable, spent)
    first = _static_roots(p, "omega", max(8.0 * _ex._root_scale(p, "omega", 1.0), 4.0))
    spin_hi = max(_spin_hi(first), 1.1 * w)
    if below:  # stable at every spin: nothing to follow
        point = CriticalPoint("omega", math.nan, CriticalKind.NEVER, (0.0, spin_hi), math.nan, True,
                              "stable at every spin: below its static buckling load at rest no spin can destabilise an "
                              f"undamped isotropic tether (its gyroscopic pencil is hyperbolic; {MODEL})", 0)
        return UndampedCritical(load, point, ((0.0, spin_hi),), spin_hi, True, spent)
    pairs = int(_static_roots(p.with_(omega=0.0), "B", p.B).size)  # real pairs at rest: one per static load below B
    hi = spin_hi if windows else max(1.02 * w, 1e-3)
    spin_line = stability_line(p, "omega", 0.0, hi, pairs=pairs, samples=64 if windows else 25)
    if stable is None:
        stable = not spin_line.unstable_at(w)
    return UndampedCritical(load, _point(spin_line, tol), spin_line.windows, spin_line.hi, stable,
                            spent + spin_line.evaluations)


def _complex_pairs(params: RodParameters) -> tuple[int, bool, int]:
    """(complex pairs of roots mu at params, whether it has a real pair (a root mu < 0), evaluations spent):
    the spin line from omega = 0 (self-adjoint: every root real) without locating anything on it, only the
    real roots at both ends and the roots that pass its cut in between (E at the cut on as many points as a
    line of 25 samples has). None of it where the stiffness is proven positive (:func:`_stiffness_positive`:
    every root real and positive)."""
    if _definite(params):
        return 0, False, 0
    return _complex_pairs_of(params.with_(gamma=0.0))


@lru_cache(maxsize=256)
def _complex_pairs_of(params: RodParameters) -> tuple[int, bool, int]:
    line = _Line(params.with_(omega=0.0), "omega", 0.0, params.omega)
    if line.mu.size > MAX_GRID:
        raise ArithmeticError(f"the omega line to {params.omega:.6g} needs {line.mu.size} mu samples per point "
                              f"(more than {MAX_GRID}: too many modes below its cut)")
    a, b = line.samples([0.0, params.omega])
    N = a.n_neg + a.n_pos + line.cut_crossing(a, b, samples=24 * (CUT_SAMPLES - 1) + 1)
    return _pairs(b, N), b.n_neg > 0, line.evaluations


def _load_line(p: RodParameters, static) -> tuple[StabilityLine, int]:
    """The load line at the operating spin (w > 0) from 0 to just past its first static point (R = 1: past the
    third, double static points do not end stability), anchored by the complex pairs of the unloaded rod (:func:`_complex_pairs`); and the
    evaluations spent, ``static`` (the first static load at the operating spin) included."""
    pairs, _, spent = _complex_pairs(p.with_(B=0.0))
    if pairs:  # flutter without load: unstable from the start of the line, nothing to locate on it
        return StabilityLine("B", 0.0, 0.0, True, (), (), pairs, spent), spent + static.evaluations
    scale = _ex._root_scale(p, "B", 1.0)
    load_hi = max(1.02 * static.value, 1e-3 * scale) if math.isfinite(static.value) else 16 * scale
    if p.R == 1.0:  # double static points do not end stability: as far as the spectral scan's default
        roots = _static_roots(p, "B", 16 * scale)
        load_hi = 1.1 * roots[2] if roots.size >= 3 else 2.0 * roots[-1] if roots.size else load_hi
    line = stability_line(p, "B", 0.0, load_hi, pairs=pairs)
    return line, spent + line.evaluations + static.evaluations


def _load_only(p: RodParameters, tol: float) -> UndampedCritical:
    """The critical load alone (B > 0): the operating point is stable iff B lies below it."""
    none = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, True,
                         "critical spin not asked", 0)
    static = _ex.exact_root(p.with_(B=0.0), "B")
    if p.omega == 0:
        load = _point(_static_line(static), tol)
        return UndampedCritical(load, none, (), 0.0, p.B < load.value, static.evaluations)
    if has_real_pair(p.with_(B=0.0)):
        load = CriticalPoint("B", 0.0, CriticalKind.UNSTABLE_AT_START, (0.0, 0.0), 0.0, True,
                             f"already unstable at B = 0: a real pair of eigenvalues ({MODEL})", 0)
        return UndampedCritical(load, none, (), 0.0, False, 0)
    line, spent = _load_line(p, static)
    load = _point(line, tol)
    return UndampedCritical(load, none, (), 0.0, not line.unstable_at(p.B) if p.B <= line.hi else False, spent)


def _spin_line(p: RodParameters, spin_hi: float, windows: bool) -> tuple[StabilityLine | None, str]:
    """The spin line at the operating load from 0 to spin_hi (unstable from the start, not followed, when the
    rod has a real pair at rest and no windows are asked); (None, why) without spin where it cannot be drawn."""
    at_rest = p.with_(B=0.0, omega=0.0)  # stable at rest iff B is below its first static load (T >= 0)
    # below it, without compression, the stiffness is positive definite at rest: no real pair there (for real
    # lambda and real q, q^T (lambda^2 M + lambda G + K) q = lambda^2 q^T M q + q^T K q > 0)
    if not windows and (p.B >= _ex.exact_root(at_rest, "B").value or (p.T < 0 and has_real_pair(p.with_(omega=0.0)))):
        return StabilityLine("omega", 0.0, 0.0, True, (), (), 0, 0), ""
    try:
        return stability_line(p, "omega", 0.0, spin_hi, samples=64 if windows else 25), ""
    except ArithmeticError as exc:
        if p.omega != 0:
            raise
        return None, str(exc)


def _static_line(static) -> StabilityLine:
    """The load line of a rod without spin: stable exactly below its first static load."""
    crossings = () if math.isinf(static.value) else (
        Crossing(static.value, static.error * static.value, CriticalKind.DIVERGENCE, 0.0, True,
                 (static.value, static.value)),)
    return StabilityLine("B", 0.0, static.value, False, crossings, (), 0, static.evaluations)


def _without_spin(p: RodParameters, tol: float, why: str) -> UndampedCritical:
    """Critical load of a rod without spin (its first static load) when the spin line cannot be drawn:
    the critical spin is "not located", with the reason."""
    static = _ex.exact_root(p.with_(B=0.0), "B")
    spin = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, False,
                         f"critical spin not answered ({MODEL}): {why}", 0)
    return UndampedCritical(_point(_static_line(static), tol), spin, (), 0.0, not has_real_pair(p), static.evaluations)


def has_real_pair(params: RodParameters, n: int = 64) -> bool:
    """True when E has a real root mu < 0 at params (a real pair of eigenvalues: unstable), from sign
    changes on n points between the Rayleigh floor and 0 and close pairs at the dips of |E| between them (as a
    line's samples); False when none shows (not a proof). False by a proof
    where the stiffness is proven positive (:func:`_stiffness_positive`) and, for R = 1 (short of the
    clamped Euler compression), below the static load at rest (:mod:`etcheck.rod.straight.undamped_isotropic`)."""
    if _definite(params):
        return False
    if params.R == 1.0 and params.T > -4 * math.pi**2 / params.f and params.B < _at_rest(params).value:
        return False
    mu_lo = _rayleigh_floor(params, params.B, params.omega, params.T)
    mu = -np.linspace(math.sqrt(-mu_lo), 0.0, n + 1) ** 2
    ends = characteristic_mu(params, mu[[0, -1]])
    if np.sign(ends[0]) * np.sign(ends[1]) < 0:  # an odd number of roots between: the scan would see a change
        return True
    E = np.concatenate([ends[:1], characteristic_mu(params, mu[1:-1]), ends[1:]])
    if np.any(np.sign(E[:-1]) * np.sign(E[1:]) < 0):
        return True
    # a close pair between two samples (R near 1 past its first static load: the u and v modes) shows as a dip
    found = _close_pairs(lambda _, x: characteristic_mu(params, x), np.zeros(1), _dips(0, mu, E))
    return any(r[0] < 0 for _, r in found)
