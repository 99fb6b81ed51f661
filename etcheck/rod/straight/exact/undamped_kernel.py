"""The exact dynamic characteristic function E(mu) of the undamped straight tether (rung 1u),
and the bounds that confine its real roots.

Without damping (gamma = 0) the linearisation about the straight rod (paper
Sec. VI A, eq. (86) with F = +T e3; docs/model.md, section 6) is gyroscopic,
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
the determinant with the ends' conditions (clamped as above, or u = u'' = v = v'' = 0 at a
pinned end, :mod:`etcheck.rod.core.ends`) is known exactly, as for lambda = 0 in
:mod:`etcheck.rod.straight.exact.roots` (same scaled state, same D = det G
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

**Exact basis.** det W (initial data of the basis (q, Pu) exp(k s)) is
det C V(k), C the 8 x 8 coefficient matrix of q k^m, Pu k^m (m < 4), a
Sylvester-type matrix: det C = (R/f)^3 Res(q, Pu), Res(q, Pu) = B^4 Pu(-2
omega lambda / B). Where the exponential basis does not apply (coincident
exponents, B = 0 with omega lambda = 0) the ordered-Schur route of
:mod:`etcheck.rod.straight.exact.roots` takes over; it is also the second
formulation behind every error estimate.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math

import numpy as np

from etcheck.rod.core.ends import ALL_WELDED, Ends
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.exact import determinant
from etcheck.rod.straight.exact.determinant import assemble, bc_real, end_values, log_vandermonde, schur, smoothing
from etcheck.runtime.memory import items_within

__all__ = [
    "MODEL",
    "characteristic_counted",
    "characteristic_mu",
    "coefficients",
    "horner",
    "rayleigh_floor",
    "rounding_scale",
    "stiffness_definite",
    "stiffness_positive",
    "wavenumbers",
]


#: Model string of every value from this module.
MODEL = "rung 1 (exact undamped determinant)"

_EPS = np.finfo(float).eps
#: Relative gap between two exponents below which the exponential basis is not used.
_CONFLUENT = 1e-4


def _lam(mu: np.ndarray) -> np.ndarray:
    """lambda with lambda^2 = -mu (either branch: D is even in lambda)."""
    return np.sqrt(-np.asarray(mu, dtype=complex))


def coefficients(P, R, f, B, omega, T, lam):
    """Coefficient arrays of the u and v symbols: (a + P R lambda^2, b + P lambda^2, lambda^2 - omega^2, 2 omega lambda)."""
    l2 = lam * lam
    w2 = omega * omega
    return T + P * R * w2 + P * R * l2, T + P * w2 + P * l2, l2 - w2, 2 * omega * lam


def wavenumbers(R, f, B, alpha, beta, c0, c1, factor):
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
    run (fewer than :data:`_QR_BELOW`). The same roots as QR of every row, to round-off, for less work."""
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
#: Every how many rows :func:`_exponents` solves one by QR (the rows between follow from it by Newton, uncertified
#: rows are re-solved by QR at once).
_STRIDE = 8
#: Fewer rows than this are all solved by QR: below it the Newton sweeps cost more in numpy's per-call overhead
#: than they save (on a spin line of SET the two cost the same near 200 rows).
_QR_BELOW = 192


def horner(c: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """p(z) and p'(z) for the degree-8 rows c (n, 9), highest first, at z (n, m).

    The rows of :func:`_exponential` have no z^7, z^5, z^3 terms: p(z) = Q(z^2) + c_7 z with Q of degree 4,
    so p'(z) = 2 z Q'(z^2) + c_7: Horner in w = z^2, half the products of a general degree-8 Horner."""
    c0, c2, c4, c6, c7, c8 = (c[:, j:j + 1] for j in (0, 2, 4, 6, 7, 8))
    w = z * z
    p = (((c0 * w + c2) * w + c4) * w + c6) * w + c8 + c7 * z
    q = 2.0 * z * (((4.0 * c0 * w + 3.0 * c2) * w + 2.0 * c4) * w + c6) + c7
    return p, q


def rounding_scale(c: np.ndarray, z: np.ndarray) -> np.ndarray:
    """sum_j |c_j| |z|^(8-j) for the rows of :func:`horner` (the scale of p(z)'s rounding errors)."""
    a = np.abs(c)
    r = np.abs(z)
    w = r * r
    return (((a[:, :1] * w + a[:, 2:3]) * w + a[:, 4:5]) * w + a[:, 6:7]) * w + a[:, 8:9] + a[:, 7:8] * r


def _newton(c: np.ndarray, z: np.ndarray, steps: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on each of the eight roots of the rows c (n, 9) from z (n, 8); (roots, certified)."""
    z = z.astype(complex)
    for _ in range(steps):
        p, q = horner(c, z)
        step = p / q
        z = z - np.where(np.isfinite(step), step, 0.0)
        if np.all(np.abs(step) <= 1e-14 * np.abs(z)):
            break
    # certificate: backward error of each root, and eight distinct roots
    az = np.abs(z)
    p, _ = horner(c, z)
    size = rounding_scale(c, z)
    i, j = _PAIRS
    gap = np.min(np.abs(z[:, i] - z[:, j]) / np.maximum(az[:, i], az[:, j]), axis=1)
    good = np.all(np.abs(p) <= 1e-13 * size, axis=1) & (gap > _CONFLUENT) & np.all(np.isfinite(z), axis=1)
    return z, good


def _exponents_qr(c: np.ndarray) -> np.ndarray:
    """Roots k of the degree-8 rows c (highest first). p(i z) is a real polynomial in z for
    lambda imaginary and p(k) is real for lambda real, so the roots come from a real companion
    matrix (a fraction of the work of a complex one), then Newton steps on p (as :func:`_roots`)."""
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
        p, q = horner(c, k)
        step = np.where(q != 0, p / np.where(q != 0, q, 1.0), 0.0)
        k = k - np.where(np.isfinite(step), step, 0.0)
    return k


#: bytes the exponential basis needs per point while it evaluates E (5.3 kB measured with tracemalloc)
POINT_BYTES = 6e3


def _exponential(R, f, B, alpha, beta, c0, c1, ku, kv, shift=0, ends: Ends = ALL_WELDED):
    """D by the exponential basis for arrays (n,); NaN where it does not apply."""
    n = B.size
    lu, lv = R / f, 1.0 / f
    # p(k) = Pu Pv + q^2, Pu = lu k^4 - alpha k^2 + c0, Pv = lv k^4 - beta k^2 + c0, q = B k + c1: no k^7, k^5,
    # k^3 terms (which :func:`horner` relies on)
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
        logW = 3 * math.log(lu) + np.log(res) + log_vandermonde(k, d) + log_lam - 6 * np.log(ku) - 6 * np.log(kv)
        V = end_values(u, v, k, ku, kv, ends)
        good = np.abs(res) > 1e-12 * (lu * np.abs(c1) ** 4 + np.abs(alpha) * np.abs(c1) ** 2 * B**2
                                      + np.abs(c0) * B**4 + 1e-300)
        ok &= good & np.all([np.all(np.isfinite(x), axis=(1, 2)) for x in V], axis=0) & np.isfinite(logW)
        k = np.where(ok[:, None], k, 1.0 + np.arange(8))
        V = tuple(np.where(ok[:, None, None], x, 1.0) for x in V)
        logW = np.where(ok, logW, 0.0)
        value, _ = assemble(k, V, logW, shift)
        value = value * smoothing(k)
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
    return characteristic_counted(params, mu, B, omega, T, route, factor, shift, schur_budget)[0]


def characteristic_counted(params: RodParameters, mu, B=None, omega=None, T=None, route: str = "auto",
                    factor: float = 1.0, shift: int = 0, schur_budget: float = math.inf) -> tuple[np.ndarray, int]:
    """:func:`characteristic_mu` and the number of points that took the Schur route."""
    B = params.B if B is None else B
    omega = params.omega if omega is None else omega
    T = params.T if T is None else T
    mu, B, omega, T = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (mu, B, omega, T)))
    shape = mu.shape
    mu, B, omega, T = (x.ravel() for x in (mu, B, omega, T))
    lam = _lam(mu)
    alpha, beta, c0, c1 = coefficients(params.P, params.R, params.f, B, omega, T, lam)
    ku, kv = wavenumbers(params.R, params.f, B, alpha, beta, c0, c1, factor)
    out = np.full(mu.size, np.nan, dtype=complex)
    if route != "schur":  # in blocks that fit a tenth of the memory budget (the same values, to round-off)
        step = items_within(POINT_BYTES, 0.1)
        for a in range(0, mu.size, step):
            k = slice(a, a + step)
            out[k] = _exponential(params.R, params.f, B[k] + 0j, alpha[k], beta[k], c0[k], c1[k], ku[k], kv[k],
                                  shift, params.ends)
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
            out[i] = schur(A, bc_real(params.ends), shift).value * smoothing(np.linalg.eigvals(A))
    return out.real.reshape(shape), int(slow.size) if route != "exponential" else 0


def _uncoupled(params: RodParameters, mu: np.ndarray, T: np.ndarray, factor: float, shift: int) -> np.ndarray:
    """E at B = omega = 0 up to a positive factor: the product of the determinants of the two Rayleigh beams
    (c4 w^(4) - (T - pc mu) w'' - mu w = 0 for u and v, held as the ends are). Where a beam's exponential basis
    does not apply (mu = 0: the double exponent 0) its own Schur route, in the same scaled state, so that the positive
    factor stays continuous along mu (the coupled Schur route there has another: a jump of two decades at
    mu = 0 would look like two dips of |E| on a line under compression and be taken for a double root)."""
    out = np.ones(mu.size, dtype=complex)
    for c4, pc in ((params.R / params.f, params.P * params.R), (1.0 / params.f, params.P)):
        c2 = T - pc * mu
        kap = factor * (1.0 + (1.0 + (c2 / c4) ** 2) ** 0.25 + (1.0 + (mu / c4) ** 2) ** 0.125)
        value = np.full(mu.size, np.nan, dtype=complex)
        for group in (mu == 0, mu != 0):
            if np.any(group):
                v, _, m = determinant.isotropic_batch(c4, c2[group] + 0j, mu[group] + 0j, np.zeros(int(group.sum())),
                                                      kap[group], shift, small=False, ends=params.ends)
                value[group] = v * smoothing(m)
        for i in np.nonzero(~np.isfinite(value))[0]:
            A = determinant.isotropic_companion(c4, c2[i], mu[i], 0.0, kap[i])
            value[i] = (determinant.isotropic_schur(c4, c2[i], mu[i], 0.0, kap[i], shift, params.ends).value
                        * smoothing(np.linalg.eigvals(A)))
        out *= value
    return out


# --- the real roots in mu at one point of a line -------------------------------------------


def rayleigh_floor(params: RodParameters, B_max: float, omega_max: float, T_min: float) -> float:
    """A lower bound of K / M over the line (no real root mu lies below it).

    For |u|^2 + |v|^2 = 1 (M >= 1 there), t = max(-T, 0) and the load's term B int (v u' - u v') = -2 B int u v':
    K >= (R/f) |u''|^2 + (1/f) |v''|^2 - t (|u'|^2 + |v'|^2) - omega^2 - 2 |B| |u| |v'|, and with
    |v'|^2 <= |v| |v''| the last term is at least -2 |B| |u| |v|^(1/2) |v''|^(1/2) >= -c |B| |v''|^(1/2),
    c = 2 max (1 - s)^(1/2) s^(1/4) = 2 (2/3)^(1/2) (1/3)^(1/4) = 1.2408 (at |v|^2 = s = 1/3):
    minimised over X = |v''| and Y = |u''| in closed form or on a grid. Under tension T > 0 the
    term T (|u'|^2 + |v'|^2) >= T pi^2 (|u|^2 + |v|^2) (u, v vanish at both ends) is added. (The factor 2 of the
    load's term matters: with |B| |u| |v'| alone, for R = 0.01 at ten times the static load the lowest real root,
    -73.1, would lie below the floor, -64.6, and outside the line.)"""
    R, f = params.R, params.f
    t = max(-T_min, 0.0)
    c = 2.0 * math.sqrt(2.0 / 3.0) * (1.0 / 3.0) ** 0.25
    X = np.geomspace(1e-6, 1e6, 2001) * (1.0 + f * (abs(B_max) + t)) ** (2.0 / 3.0)
    m_v = float(np.min(X**2 / f - t * X - c * abs(B_max) * np.sqrt(X)))
    m_u = -t**2 * f / (4 * R)
    bound = -omega_max**2 + m_u + m_v + max(T_min, 0.0) * math.pi**2
    return 0.0 if bound > 0 else 1.1 * bound - 1e-6  # 0: no real root below 0, no real pair of eigenvalues


def bending_floor(ends: Ends) -> float:
    """A lower bound of int w''^2 / int w^2 over w held at these ends (w = w' = 0 welded, w = 0 pinned): beta^4 of
    the first beam mode (cos(beta) cosh(beta) = 1 welded at both, tan(beta) = tanh(beta) at one, beta = pi
    pinned at both; :attr:`etcheck.rod.core.ends.Ends.first_bending_root`), rounded down."""
    return ends.first_bending_root ** 4 * (1.0 - 1e-12)


def stiffness_positive(params: RodParameters, B, omega) -> np.ndarray:
    """Where a proof finds the stiffness K positive definite at (B, omega) (arrays; T, P, R, f from params):
    True there, False where none is found.

    For unit |q| = (|u|^2 + |v|^2)^(1/2), U = |u|, V = |v|, x = |v''| / V and y = |u''| / U (both >= beta^2,
    :func:`bending_floor` = beta^4 of the ends), |w'|^2 >= pi^2 |w|^2 (w = 0 at both ends), |w'|^2 = -(w, w'') <= x |w|^2
    and the load's term 2 B int u' v >= -2 |B| U |v'| >= -2 |B| U V x^(1/2):
    q^T K q >= A U^2 + C(x) V^2 - 2 |B| x^(1/2) U V, with A = min over y of (R/f) y^2 + a_u (pi^2 or y) - omega^2
    and C(x) = x^2 / f + a_v (pi^2 or x) - omega^2 (pi^2 for a >= 0, else x), a_u = T + P R omega^2,
    a_v = T + P omega^2. That 2 x 2 form is positive for every x >= beta^2 iff A > 0 and A C(x) - B^2 x > 0 there
    (a convex quadratic in x: its least value at the vertex or at beta^2). K > 0 with M > 0 and G skew: every
    eigenvalue lies on the imaginary axis (Lagrange), so every root mu of E is real and positive (no real pair, no
    complex pair). Exact at B = 0, T = P = 0 (the weak beam's first mode: omega^2 = beta^4 R / f); looser
    with load and compression. A relative margin of 1e-9 keeps round-off out of the proof."""
    B, omega = np.broadcast_arrays(np.abs(np.asarray(B, dtype=float)), np.asarray(omega, dtype=float))
    w2 = omega**2
    floor = bending_floor(params.ends)
    b2 = math.sqrt(floor)
    cu, cv = params.R / params.f, 1.0 / params.f
    au, av = params.T + params.P * params.R * w2, params.T + params.P * w2
    yu = np.maximum(b2, -au / (2.0 * cu))
    A = np.where(au >= 0.0, cu * floor + au * math.pi**2, cu * yu**2 + au * yu) - w2
    A_scale = cu * floor + np.abs(au) * (math.pi**2 + yu) + w2
    s, t = np.minimum(av, 0.0), np.maximum(av, 0.0) * math.pi**2 - w2  # C(x) = cv x^2 + s x + t
    good = A > 1e-9 * A_scale
    with np.errstate(all="ignore"):
        x = np.maximum(b2, (B**2 - A * s) / (2.0 * A * cv))
        h = A * cv * x**2 + (A * s - B**2) * x + A * t
        h_scale = A * cv * x**2 + np.abs(A * s - B**2) * x + np.abs(A * t)
    return good & (h > 1e-9 * h_scale)


def stiffness_definite(params: RodParameters) -> bool:
    """:func:`stiffness_positive` at params."""
    return bool(stiffness_positive(params, params.B, params.omega))
