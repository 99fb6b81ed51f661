"""The exact characteristic function of the straight tether (dimensionless): the
determinant kernel that the exact (damped) and undamped routes of rung 1 share.

The linearisation about the straight, untwisted rod (paper Sec. VI A, the
trivial solution eq. (86) with the tension sign of the boundary condition
eq. (25), F = +T e3) has constant coefficients. In the f-scaling of Sec. IV
(eq. (36)), rotating frame, u along the weak axis e1 (stiffness R/f), v along
e2 (stiffness 1/f), its static (lambda = 0) part is

    (R/f) u'''' - a u'' - omega^2 u - B v' = 0,   a = T + P R omega^2,
    (1/f) v'''' - b v'' - omega^2 v + B u' = 0,   b = T + P omega^2,
    u = u' = v = v' = 0 at s = 0 and s = 1

(rotary inertia acts as an extra tension P R omega^2, P omega^2 in the
rotating frame; torsion decouples). For omega = T = 0 and f = 1 this is the
lambda = 0 case of eq. (87). With Kelvin-Voigt damping the straight rod
loses stability only where this static operator is singular
(Kelvin-Tait-Chetaev, see :mod:`etcheck.rod.straight.collocation.damped_critical`), so its exact
characteristic function decides the damped straight rod without any
discretisation, down to boundary layers of width sqrt(R/(f T)) that a
Chebyshev grid cannot resolve.

**The characteristic function.** Write the ODE as y' = A y for the scaled
state y = (u, u'/ku, u''/ku^2, u'''/ku^3, v, v'/kv, v''/kv^2, v'''/kv^3)
(ku, kv continuous wavenumber scales of the u and v exponents). Let G be
the 8x8 map from y(0) to the clamped boundary values (u, u', v, v') at
s = 0 and s = 1 (at a pinned end (u, u'', v, v''): no bending moment;
``bc_real``, :mod:`etcheck.rod.core.ends`). det G is real and analytic in (B, omega, T); it grows like
exp(sigma), sigma = sum of the positive real parts of the exponents (the
eigenvalues of A). The function returned is

    D = det G * exp(-sigma),

real, with a sign that is continuous in the parameters (every basis and
scaling choice below cancels exactly), zero exactly where the clamped
problem has a kernel, and free of exponential growth: its size is a power
of the exponents (O(1) for moderate tension, 1e14 at T f = 1e12, R = 1e-7). Two routes compute it:

* **exponential basis** (default where it applies): the exponents are the
  roots of a quartic in k^2, polished by Newton's method to full relative
  accuracy; the basis solutions are the analytic null vectors times
  exp(k (s - s_k)), scaled at the end where each is small (s_k = 1 for
  Re k above a split tau, else 0). det G is det M / det W with M the scaled
  boundary matrix and det W the closed-form determinant of the initial
  data (a Vandermonde product in the exponents). This keeps full accuracy
  when the exponents span many decades (T f up to 1e12 with R = 1e-7:
  layer exponents 3e9 next to string exponents 2 pi): nothing is computed
  from a matrix whose norm is the largest exponent.
* **ordered real Schur** (fallback): A = Q T Q^T ordered so the exponents
  with Re k < tau come first; the other invariant subspace is Q [Y; I] with
  T11 Y - Y T22 = -T12 (so det of the two bases together is det Q = +-1),
  the first block is propagated from s = 0 with expm(T11), the second from
  s = 1 with expm(-T22). Robust where exponents coincide (k = 0 double at
  omega = 0, the Jordan block at B = omega = 0, equal u and v exponents at
  R = 1) because no eigenvectors are formed; its absolute error on the
  exponents is eps times the largest exponent, so it is used only where
  the exponential basis does not apply.

**Double roots.** For R = 1 (any omega, T) and for omega = T = 0 (any R) the
problem is isotropic: with w = u + i v (R = 1) or w = u + i v / sqrt(R)
(omega = T = 0) it is one complex equation c4 w'''' - c2 w'' - c0 w +
i c1 w' = 0, whose clamped determinant is real (the map w(s) ->
conj(w(1 - s)) preserves the problem; with one end of each the problem is
self-adjoint with self-adjoint conditions at each end, and the determinant is
real as well, to round-off) and has simple zeros; D is a positive
multiple of its square, so every zero of D is double (touching, no sign
change; the kernel is two-dimensional, Sec. VI A). Roots in these cases come
from the complex determinant. Elsewhere zeros are simple; close pairs (the
split double root at small T, omega or 1 - R, and the u and v string modes
near B = 2 pi T) are found by minimising |D| between samples.

Everything here is dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.linalg import lapack

from etcheck.rod.core.ends import ALL_WELDED, Ends
from etcheck.rod.core.parameters import RodParameters

__all__ = [
    "bc_complex",
    "bc_real",
    "Characteristic",
    "Evans",
    "assemble",
    "characteristic",
    "evaluate",
    "is_isotropic",
    "isotropic_batch",
    "isotropic_batch_values",
    "isotropic_characteristic",
    "isotropic_companion",
    "isotropic_evans",
    "isotropic_schur",
    "kernel_dimension",
    "log_vandermonde",
    "polynomial_roots",
    "real_batch",
    "real_evans",
    "scales",
    "schur",
    "smoothing",
    "tensions",
]


_EPS = np.finfo(float).eps
#: Relative gap between two exponents below which the exponential basis is not used.
_CONFLUENT = 1e-4
#: The same where the exponents span more than 4 decades (the Schur route is then the worse one).
_CONFLUENT_WIDE = 1e-12
#: |k| below which an exponent is treated as near zero (Schur route).
_SMALL_K = 1e-3


def bc_real(ends: Ends = ALL_WELDED) -> tuple[np.ndarray, np.ndarray]:
    """The boundary-value rows of the real scaled state held at each end (rows at s = 0, rows at s = 1): u, u',
    v, v' at a welded end, u, u'', v, v'' at a pinned one (no bending moment;
    :meth:`~etcheck.rod.core.ends.EndCondition.real_rows`)."""
    return ends.lower.real_rows(), ends.upper.real_rows()


def bc_complex(ends: Ends = ALL_WELDED) -> tuple[np.ndarray, np.ndarray]:
    """:func:`bc_real` of the complex state (w, w'/kap, ..): w, w' or w, w''."""
    return ends.lower.complex_rows(), ends.upper.complex_rows()


# --- coefficients and scales ---------------------------------------------------------


def tensions(params: RodParameters) -> tuple[float, float, float]:
    """(a, b, omega^2): effective tensions of the u and v equations and the spin term."""
    w2 = params.omega**2
    return params.T + params.P * params.R * w2, params.T + params.P * w2, w2


def scales(params: RodParameters, factor: float = 1.0) -> tuple[float, float]:
    """Continuous wavenumber scales (ku, kv) of the u and v exponents (>= 1)."""
    a, b, w2 = tensions(params)
    R, f = params.R, params.f
    kb = (f * abs(params.B) / math.sqrt(R)) ** (1.0 / 3.0)
    ku = 1.0 + math.sqrt(f * abs(a) / R) + (f * w2 / R) ** 0.25 + kb
    kv = 1.0 + math.sqrt(f * abs(b)) + (f * w2) ** 0.25 + kb
    return factor * ku, factor * kv


def _companion(params: RodParameters, ku: float, kv: float) -> np.ndarray:
    """8x8 first-order matrix of the scaled state (see the module docstring)."""
    a, b, w2 = tensions(params)
    R, f, B = params.R, params.f, params.B
    A = np.zeros((8, 8))
    A[0, 1] = A[1, 2] = A[2, 3] = ku
    A[4, 5] = A[5, 6] = A[6, 7] = kv
    A[3, 0] = f * w2 / (R * ku**3)
    A[3, 2] = f * a / (R * ku)
    A[3, 5] = f * B * kv / (R * ku**3)
    A[7, 4] = f * w2 / kv**3
    A[7, 6] = f * b / kv
    A[7, 1] = -f * B * ku / kv**3
    return A


def _split(re: np.ndarray, shift: int = 0) -> float:
    """Threshold tau between the exponents propagated from s = 0 (Re k < tau) and from
    s = 1: the middle of the widest gap (log scale) of the positive real parts in
    [0.25, 6], so no exponent sits near it and nothing grows by more than e^6."""
    pos = np.sort(re[(re > 0.25) & (re < 6.0)])
    pts = np.log(np.concatenate([[0.25], pos, [6.0]]))
    gaps = np.diff(pts)
    order = np.argsort(gaps)[::-1]
    i = order[min(shift, len(order) - 1)]
    return math.exp(0.5 * (pts[i] + pts[i + 1]))


# --- route 1: ordered Schur ------------------------------------------------------------


@dataclass(frozen=True)
class Evans:
    value: complex
    M: np.ndarray  # scaled boundary matrix (columns: the basis solutions)
    route: str


def schur(A: np.ndarray, bc, shift: int = 0) -> Evans:
    """D by the ordered Schur route; ``bc`` the boundary rows, a pair (s = 0, s = 1)."""
    b0, b1 = bc
    cplx = np.iscomplexobj(A)
    T, Q = sla.schur(A, output="complex" if cplx else "real")
    re = np.diag(T).real.copy()  # real parts (equal on the diagonal of a 2x2 block)
    tau = _split(re, shift)
    n = A.shape[0]
    select = (re < tau).astype(np.int32)
    if cplx:
        T, Q, _, m, _, _, info = lapack.ztrsen(select, T, Q, job="N")
    else:
        T, Q, _, _, m, _, _, info = lapack.dtrsen(select, T, Q, job="N")
    if info != 0:
        raise np.linalg.LinAlgError(f"Schur reordering failed (info = {info})")
    T11, T12, T22 = T[:m, :m], T[:m, m:], T[m:, m:]
    if 0 < m < n:
        trsyl = lapack.ztrsyl if cplx else lapack.dtrsyl
        Y, scale, info = trsyl(T11, T22, -T12, isgn=-1)
        if info < 0:
            raise np.linalg.LinAlgError(f"Sylvester solve failed (info = {info})")
        Y = Y / scale
    else:
        Y = np.zeros((m, n - m), dtype=T.dtype)
    Q1 = Q[:, :m]
    Q2 = Q1 @ Y + Q[:, m:]  # invariant subspace of the exponents with Re k >= tau
    P1 = Q1 @ sla.expm(T11) if m else Q1
    P2 = Q2 @ sla.expm(-T22) if m < n else Q2
    M = np.vstack([np.hstack([Q1[b0], P2[b0]]), np.hstack([P1[b1], Q2[b1]])])
    sigma = float(np.sum(np.maximum(re, 0.0)))
    value = np.linalg.det(M) * np.exp(np.trace(T22) - sigma) / np.linalg.det(Q)
    return Evans(complex(value), M, "schur")


# --- route 2: exponential basis --------------------------------------------------------


def polynomial_roots(c: np.ndarray) -> np.ndarray:
    """Roots of the polynomials with coefficient rows c (n, d+1), highest first: companion
    eigenvalues, then Newton steps (relative accuracy for well-separated roots)."""
    n, d = c.shape[0], c.shape[1] - 1
    C = np.zeros((n, d, d), dtype=complex)
    C[:, 0, :] = -c[:, 1:] / c[:, :1]
    C[:, np.arange(1, d), np.arange(d - 1)] = 1.0
    r = np.linalg.eigvals(C)
    dc = c[:, :-1] * np.arange(d, 0, -1)
    for _ in range(3):
        p = np.zeros_like(r) + c[:, :1]
        q = np.zeros_like(r) + dc[:, :1]
        for j in range(1, d + 1):
            p = p * r + c[:, j:j + 1]
            if j < d:
                q = q * r + dc[:, j:j + 1]
        step = np.where(q != 0, p / np.where(q != 0, q, 1.0), 0.0)
        r = r - np.where(np.isfinite(step), step, 0.0)
    return r


def _separated(k: np.ndarray, small: bool = True, wide=False) -> np.ndarray:
    """Rows of k (n, m) where no two exponents nearly coincide (and, with ``small``,
    none is near zero). Near-coincident exponents cost the exponential basis eps / gap
    (nearly parallel columns) and the Schur route eps x (largest / smallest exponent) / gap,
    so where the exponents span more than 4 decades (``wide``, per row) the exponential
    basis is kept down to relative gaps of ``_CONFLUENT_WIDE``."""
    d = np.abs(k[:, :, None] - k[:, None, :])
    ak = np.abs(k)
    scale = np.maximum(ak[:, :, None], ak[:, None, :])
    d[:, np.arange(k.shape[1]), np.arange(k.shape[1])] = np.inf
    gap = np.where(np.asarray(wide), _CONFLUENT_WIDE, _CONFLUENT)
    gap = np.broadcast_to(gap, (k.shape[0],))[:, None, None]
    ok = np.all(d >= gap * scale, axis=(1, 2)) & np.all(np.isfinite(k), axis=1)
    return ok & np.all(ak >= _SMALL_K, axis=1) if small else ok


def _spread(k: np.ndarray) -> np.ndarray:
    """Largest over smallest non-zero |exponent| of each row of k."""
    ak = np.abs(k)
    small = np.min(np.where(ak > 0, ak, np.inf), axis=1)
    return np.max(ak, axis=1) / small


def _polish_factored(kap: np.ndarray, lu: float, lv: float, a: np.ndarray, b: np.ndarray, w2: np.ndarray,
                     B: np.ndarray, static: bool) -> np.ndarray:
    """Newton steps on the roots kappa = k^2 of Pu Pv + B^2 kappa evaluated in factored form
    (Pu = lu kappa^2 - a kappa - w2, Pv = lv kappa^2 - b kappa - w2; divided by kappa when
    static). The expanded polynomial loses the u and v string roots when a and b nearly
    coincide (strong tension, small P omega^2): its coefficients cancel to eps relative to
    a b, so the pair is split only to sqrt(eps); each factor keeps its own root to eps."""
    a, b, w2, B2 = a[:, None], b[:, None], w2[:, None], (B**2)[:, None]
    for _ in range(3):
        if static:
            u1, v1 = lu * kap - a, lv * kap - b
            p = kap * u1 * v1 + B2
            dp = u1 * v1 + kap * (lu * v1 + lv * u1)
        else:
            Pu, Pv = lu * kap**2 - a * kap - w2, lv * kap**2 - b * kap - w2
            p = Pu * Pv + B2 * kap
            dp = (2 * lu * kap - a) * Pv + Pu * (2 * lv * kap - b) + B2
        step = np.where(dp != 0, p / np.where(dp != 0, dp, 1.0), 0.0)
        new = kap - np.where(np.isfinite(step), step, 0.0)
        better = np.abs(_factored(new, lu, lv, a, b, w2, B2, static)) <= np.abs(p)
        kap = np.where(better, new, kap)
    return kap


def _factored(kap, lu, lv, a, b, w2, B2, static):
    if static:
        return kap * (lu * kap - a) * (lv * kap - b) + B2
    return (lu * kap**2 - a * kap - w2) * (lv * kap**2 - b * kap - w2) + B2 * kap


def log_vandermonde(k: np.ndarray, d: np.ndarray | None = None) -> np.ndarray:
    """log prod_{i<j} (k_j - k_i) for each row of k (modulo 2 pi i), from the logs of products of 7
    differences at a time (a complex log costs ten multiplications; seven factors stay far inside the
    floating-point range for any exponents below 1e40 in size and above 1e-40 apart). ``d``: the differences
    k_j - k_i in the order of ``np.triu_indices``, where the caller has them already."""
    if d is None:
        i, j = np.triu_indices(k.shape[1], 1)
        d = k[:, j] - k[:, i]
    cols = d.shape[1]
    return sum(np.log(np.prod(d[:, a:a + 7], axis=1)) for a in range(0, cols, 7))


def smoothing(k: np.ndarray) -> np.ndarray:
    """exp(sigma - sigma_s): replaces sigma = sum max(Re k, 0) = sum |Re k| / 2 (the sum of all
    Re k is 0) of D by sigma_s = sum (Re k^4 + 1)^(1/4) / 2. Re k of a single exponent is not
    analytic: it leaves the imaginary axis like sqrt(distance) where two exponents meet there (and
    at lambda = 0, mu changing sign), so |Re k| puts a cusp into D; (x^4 + 1)^(1/4) = 1 + O(x^4)
    leaves D continuously differentiable. The factor lies in [exp(-m/2), 1] for m exponents: zeros and signs of D
    are unchanged."""
    x = k.real
    return np.exp(0.5 * np.sum(np.abs(x) - (x**4 + 1.0) ** 0.25, axis=-1))


def _splits(re: np.ndarray, shift: int = 0) -> np.ndarray:
    """:func:`_split` for each row of re (n, m)."""
    lo, hi = math.log(0.25), math.log(6.0)
    x = np.clip(np.log(np.where(re > 0, re, 0.25)), lo, hi)
    n = re.shape[0]
    pts = np.sort(np.hstack([np.full((n, 1), lo), x, np.full((n, 1), hi)]), axis=1)
    gaps = np.diff(pts, axis=1)
    i = np.argsort(-gaps, axis=1, kind="stable")[:, min(shift, gaps.shape[1] - 1)]
    rows = np.arange(n)
    return np.exp(0.5 * (pts[rows, i] + pts[rows, i + 1]))


def assemble(k: np.ndarray, V, logdet: np.ndarray, shift: int) -> tuple[np.ndarray, np.ndarray]:
    """D (n,) and the scaled boundary matrices M (n, 2 r, m) from exponents k (n, m),
    boundary rows V, a pair (V0, V1) of (n, r, m) (initial values of the basis solutions at the rows held at s = 0
    and at s = 1) and log det of the full initial-data matrix W (n,)."""
    V0, V1 = V
    norm = np.maximum(np.max(np.abs(V0), axis=1), np.max(np.abs(V1), axis=1))
    V0, V1 = V0 / norm[:, None, :], V1 / norm[:, None, :]
    logdet = logdet - np.sum(np.log(norm), axis=1)
    tau = _splits(k.real, shift)
    far = k.real >= tau[:, None]  # scaled at s = 1
    e0 = np.exp(np.where(far, -k, 0.0))
    e1 = np.exp(np.where(far, 0.0, k))
    M = np.concatenate([V0 * e0[:, None, :], V1 * e1[:, None, :]], axis=1)
    sigma = np.sum(np.maximum(k.real, 0.0), axis=1)
    value = np.linalg.det(M) * np.exp(np.sum(np.where(far, k, 0.0), axis=1) - sigma - logdet)
    return value, M


def _exponential_batch(P: float, R: float, f: float, B: np.ndarray, w2: np.ndarray, a: np.ndarray,
                       b: np.ndarray, ku: np.ndarray, kv: np.ndarray, shift: int = 0, ends: Ends = ALL_WELDED):
    """The exponential-basis route of the coupled real problem for arrays of (B, omega^2,
    a, b, ku, kv), all with omega = 0 or all with omega != 0. Returns (D, M); D is NaN
    where the route does not apply (B = 0, coincident or near-zero exponents)."""
    n = B.size
    static = bool(np.all(w2 == 0))
    # det [[(R/f) k^4 - a k^2 - w2, -B k], [B k, k^4/f - b k^2 - w2]] as a polynomial in k^2
    c = np.stack([np.full(n, R / f**2), -(R * b + a) / f, a * b - w2 * (R + 1) / f, w2 * (a + b) + B**2, w2**2],
                 axis=1)
    if static:
        c = c[:, :4]  # k^2 = 0 is a root: the constants u = 1, v = 1 solve the problem
    with np.errstate(all="ignore"):
        kap = _polish_factored(polynomial_roots(c), R / f, 1.0 / f, a, b, w2, B, static)
        r = np.sqrt(kap)
        k = np.concatenate([r, -r], axis=1)
        ok = _separated(k, small=False, wide=_spread(k) > 1e4) & (B != 0)
        Bc = B[:, None]
        Pu = R / f * k**4 - a[:, None] * k**2 - w2[:, None]
        Pv = k**4 / f - b[:, None] * k**2 - w2[:, None]
        second = np.abs(Pv) > np.abs(Pu)  # (Pv, -B k) is the better-conditioned null vector
        u = np.where(second, Pv, Bc * k)
        v = np.where(second, -Bc * k, Pu)
        # Near-zero exponents are harmless while their null vectors span (u, v) with
        # room to spare: at most two (none besides the constants at omega = 0), and
        # not parallel (near a Jordan block the basis degenerates: Schur instead).
        nsmall = np.sum(np.abs(k) < _SMALL_K, axis=1)
        ok &= nsmall <= (0 if static else 2)
        two = np.argsort(np.abs(k), axis=1)[:, :2]
        rows = np.arange(n)[:, None]
        phi = np.stack([u[rows, two], v[rows, two]], axis=2)  # (n, 2, 2)
        phi = phi / np.linalg.norm(phi, axis=2, keepdims=True)
        cos = np.abs(np.sum(np.conj(phi[:, 0]) * phi[:, 1], axis=1))
        ok &= (nsmall < 2) | (cos < 0.99)
        log_lam = np.sum(np.where(second, np.log(Pv / (Bc * k)), 0.0), axis=1)
        # closed-form det of the unscaled initial data with null vectors (B k, Pu(k))
        if static:
            logW = 3 * np.log(B + 0j) + 3 * math.log(R / f) + np.sum(2 * np.log(k), axis=1) + log_vandermonde(k)
        else:
            logW = np.log(B**4 * w2 + 0j) + 3 * math.log(R / f) + log_vandermonde(k)
        logW = logW + 1j * math.pi + log_lam - 6 * np.log(ku) - 6 * np.log(kv)
        V = end_values(u, v, k, ku, kv, ends)
        if static:
            const = np.zeros((n, 4, 2))
            const[:, 0, 0] = const[:, 2, 1] = 1.0
            V = tuple(np.concatenate([const, x], axis=2) for x in V)
            k = np.concatenate([np.zeros((n, 2)), k], axis=1)
        ok &= np.all([np.all(np.isfinite(x), axis=(1, 2)) for x in V], axis=0) & np.isfinite(logW)
        k = np.where(ok[:, None], k, 1.0 + np.arange(k.shape[1]))
        V = tuple(np.where(ok[:, None, None], x, 1.0) for x in V)
        logW = np.where(ok, logW, 0.0)
        value, M = assemble(k, V, logW, shift)
    return np.where(ok & np.isfinite(value), value, np.nan), M


def end_values(u: np.ndarray, v: np.ndarray, k: np.ndarray, ku: np.ndarray, kv: np.ndarray, ends: Ends) -> tuple:
    """The boundary values (n, 4, m) of the basis solutions (u, v) exp(k s) of the scaled state at s = 0, one array per
    end: u, u' / ku, v, v' / kv at a welded end, u, u'' / ku^2, v, v'' / kv^2 at a pinned one
    (:meth:`~etcheck.rod.core.ends.EndCondition.real_values`)."""
    return tuple(end.real_values(u, v, k, ku, kv) for end in ends.conditions)


def real_batch(params: RodParameters, B, omega, T, factor: float = 1.0, shift: int = 0) -> np.ndarray:
    """D at arrays of (B, omega, T): exponential basis, Schur where it does not apply."""
    B, omega, T = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (B, omega, T)))
    P, R, f = params.P, params.R, params.f
    w2 = omega**2
    a, b = T + P * R * w2, T + P * w2
    kb = (f * np.abs(B) / math.sqrt(R)) ** (1.0 / 3.0)
    ku = factor * (1.0 + np.sqrt(f * np.abs(a) / R) + (f * w2 / R) ** 0.25 + kb)
    kv = factor * (1.0 + np.sqrt(f * np.abs(b)) + (f * w2) ** 0.25 + kb)
    out = np.full(B.size, np.nan, dtype=complex)
    for group in (w2 == 0, w2 != 0):
        group = group & (B != 0)
        if np.any(group):
            out[group] = _exponential_batch(P, R, f, B[group], w2[group], a[group], b[group], ku[group], kv[group],
                                            shift, params.ends)[0]
    free = B == 0
    if np.any(free):
        out[free] = _decoupled_batch(R, f, w2[free], a[free], b[free], ku[free], kv[free], shift, params.ends)[0]
    for i in np.nonzero(~np.isfinite(out))[0]:
        p = params.with_(B=float(B[i]), omega=float(omega[i]), T=float(T[i]))
        out[i] = schur(_companion(p, ku[i], kv[i]), bc_real(params.ends), shift).value
    return out.real


def _decoupled_batch(R: float, f: float, w2: np.ndarray, a: np.ndarray, b: np.ndarray, ku: np.ndarray,
                     kv: np.ndarray, shift: int = 0, ends: Ends = ALL_WELDED):
    """B = 0: u and v decouple and D = D_u D_v, each the real determinant of a scalar
    clamped beam (the complex route with c1 = 0; the two boundary blocks are swapped
    pairwise, so no sign). Returns (D, M) with M block diagonal; NaN where it does
    not apply (the Jordan block at omega = 0)."""
    out, Ms = np.ones(w2.size, dtype=complex), []
    for c4, c2, kap in ((R / f, a, ku), (1.0 / f, b, kv)):
        n = w2.size
        value = np.full(n, np.nan, dtype=complex)
        M = np.full((n, 4, 4), np.nan, dtype=complex)
        for group in (w2 == 0, w2 != 0):
            if np.any(group):
                value[group], M[group], _ = isotropic_batch(c4, c2[group], w2[group],
                                                             np.zeros(int(group.sum())), kap[group], shift, ends=ends)
        out *= value
        Ms.append(M)
    M = np.zeros((w2.size, 8, 8), dtype=complex)
    M[:, np.ix_([0, 1, 4, 5], [0, 1, 2, 3])[0], np.ix_([0, 1, 4, 5], [0, 1, 2, 3])[1]] = Ms[0]
    M[:, np.ix_([2, 3, 6, 7], [4, 5, 6, 7])[0], np.ix_([2, 3, 6, 7], [4, 5, 6, 7])[1]] = Ms[1]
    return out, M


def _exponential(params: RodParameters, ku: float, kv: float, shift: int = 0) -> Evans | None:
    """The exponential-basis route at one point, or None where it does not apply."""
    a, b, w2 = tensions(params)
    one = lambda x: np.array([float(x)])  # noqa: E731
    if params.B == 0:
        value, M = _decoupled_batch(params.R, params.f, one(w2), one(a), one(b), one(ku), one(kv), shift,
                                    params.ends)
    else:
        value, M = _exponential_batch(params.P, params.R, params.f, one(params.B), one(w2), one(a), one(b), one(ku),
                                      one(kv), shift, params.ends)
    if not np.isfinite(value[0]):
        return None
    return Evans(complex(value[0]), M[0], "exponential")


# --- the isotropic (complex) problem ----------------------------------------------------


def is_isotropic(params: RodParameters) -> bool:
    """True where the linear static problem is isotropic (R = 1, or omega = T = 0):
    every zero of D is then double (Sec. VI A)."""
    return params.R == 1.0 or (params.omega == 0.0 and params.T == 0.0)


def isotropic_batch(c4: float, c2: np.ndarray, c0: np.ndarray, c1: np.ndarray, kap: np.ndarray, shift: int = 0,
                     small: bool = True, ends: Ends = ALL_WELDED):
    """Exponential-basis route of the complex problem for arrays (all c0 = 0 or all c0 != 0).
    Returns (D, M, m): D is NaN where the route does not apply, m the exponents (n, 4); ``small``: not
    where an exponent is near zero either."""
    n = c2.size
    static = bool(np.all(c0 == 0))
    c = np.stack([np.full(n, c4, dtype=complex), np.zeros(n), -c2 + 0j, 1j * c1, -c0 + 0j], axis=1)
    with np.errstate(all="ignore"):
        if static:  # m = 0 is a root (the constants): keep it exact
            m = polynomial_roots(c[:, :4])
            ok = _separated(m) & (c1 != 0)
            m = np.concatenate([np.zeros((n, 1)), m], axis=1)
        else:
            m = polynomial_roots(c)
            ok = _separated(m, small)
        ms = m / kap[:, None]
        V = tuple(end.complex_values(ms) for end in ends.conditions)
        logW = log_vandermonde(ms)
        ok &= np.isfinite(logW) & np.all([np.all(np.isfinite(x), axis=(1, 2)) for x in V], axis=0)
        m = np.where(ok[:, None], m, 1.0 + np.arange(4))
        V = tuple(np.where(ok[:, None, None], x, 1.0) for x in V)
        value, M = assemble(m, V, np.where(ok, logW, 0.0), shift)
    return np.where(ok & np.isfinite(value), value, np.nan), M, m


def _isotropic_arrays(params: RodParameters, B, omega, T, factor: float = 1.0):
    B, omega, T = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (B, omega, T)))
    if params.R == 1.0:
        c4, c2, c0, c1 = 1.0 / params.f, T + params.P * omega**2, omega**2, B
    elif np.all(omega == 0) and np.all(T == 0):
        c4, c2, c0, c1 = params.R / params.f, np.zeros_like(B), np.zeros_like(B), B * math.sqrt(params.R)
    else:
        raise ValueError("the problem is isotropic only for R = 1 or omega = T = 0")
    kap = factor * (1.0 + np.sqrt(np.abs(c2) / c4) + (np.abs(c0) / c4) ** 0.25 + (np.abs(c1) / c4) ** (1.0 / 3.0))
    return c4, c2, c0, c1, kap


def isotropic_companion(c4: float, c2: float, c0: float, c1: float, kap: float) -> np.ndarray:
    """4 x 4 first-order matrix of the scaled state (w, w'/kap, ..) of c4 w^(4) - c2 w'' + i c1 w' - c0 w = 0."""
    A = np.zeros((4, 4), dtype=complex)
    A[0, 1] = A[1, 2] = A[2, 3] = kap
    A[3, 0] = c0 / (c4 * kap**3)
    A[3, 1] = -1j * c1 / (c4 * kap**2)
    A[3, 2] = c2 / (c4 * kap)
    return A


def isotropic_schur(c4: float, c2: float, c0: float, c1: float, kap: float, shift: int = 0,
                    ends: Ends = ALL_WELDED) -> Evans:
    return schur(isotropic_companion(c4, c2, c0, c1, kap), bc_complex(ends), shift)


def isotropic_batch_values(params: RodParameters, B, omega, T, factor: float = 1.0, shift: int = 0) -> np.ndarray:
    """Real complex-problem determinant at arrays of (B, omega, T) (R = 1 or omega = T = 0)."""
    c4, c2, c0, c1, kap = _isotropic_arrays(params, B, omega, T, factor)
    out = np.full(c2.size, np.nan, dtype=complex)
    for group in (c0 == 0, c0 != 0):
        if np.any(group):
            out[group] = isotropic_batch(c4, c2[group], c0[group], c1[group], kap[group], shift, ends=params.ends)[0]
    for i in np.nonzero(~np.isfinite(out))[0]:
        out[i] = isotropic_schur(c4, c2[i], c0[i], c1[i], kap[i], shift, params.ends).value
    return out.real


def isotropic_evans(params: RodParameters, route: str, factor: float = 1.0, shift: int = 0) -> Evans:
    c4, c2, c0, c1, kap = _isotropic_arrays(params, params.B, params.omega, params.T, factor)
    if route != "schur":
        value, M, _ = isotropic_batch(c4, c2, c0, c1, kap, shift, ends=params.ends)
        if np.isfinite(value[0]):
            return Evans(complex(value[0]), M[0], "exponential")
        if route == "exponential":
            raise ValueError("the exponential basis does not apply here (coincident exponents)")
    return isotropic_schur(c4, c2[0], c0[0], c1[0], kap[0], shift, params.ends)


# --- public evaluation -----------------------------------------------------------------


@dataclass(frozen=True)
class Characteristic:
    """The exact characteristic function at one point (dimensionless).

    ``value``: D = det G exp(-sigma) (real, O(1), sign continuous in the
    parameters); ``imaginary``: |Im| of the computed value relative to its
    modulus (zero in exact arithmetic: a consistency check); ``route``:
    "exponential" or "schur"; ``singular_values``: of the column-normalised
    scaled boundary matrix, largest first (the kernel dimension is the
    number that vanish).
    """

    value: float
    imaginary: float
    route: str
    singular_values: tuple[float, ...]


def real_evans(params: RodParameters, route: str = "auto", factor: float = 1.0, shift: int = 0) -> Evans:
    ku, kv = scales(params, factor)
    if route != "schur":
        ev = _exponential(params, ku, kv, shift)
        if ev is not None and np.isfinite(ev.value):
            return ev
        if route == "exponential":
            raise ValueError("the exponential basis does not apply here (B = 0 or coincident exponents)")
    return schur(_companion(params, ku, kv), bc_real(params.ends), shift)


def _finish(ev: Evans) -> Characteristic:
    M = ev.M / np.maximum(np.max(np.abs(ev.M), axis=0), 1e-300)
    s = np.linalg.svd(M, compute_uv=False)
    mod = abs(ev.value)
    return Characteristic(float(ev.value.real), abs(ev.value.imag) / mod if mod > 0 else 0.0, ev.route,
                          tuple(float(x) for x in s))


def characteristic(params: RodParameters, route: str = "auto") -> float:
    """D(B, omega, T) at the parameters' load, spin and tension (dimensionless, real).

    ``route``: "auto" (exponential basis where it applies, else Schur),
    "exponential" or "schur". Zero exactly where the clamped static problem
    has a kernel; the sign is continuous in every parameter.
    """
    return float(real_evans(params, route).value.real)


def evaluate(params: RodParameters, route: str = "auto") -> Characteristic:
    """:func:`characteristic` with its diagnostics (route, imaginary residue, singular values)."""
    return _finish(real_evans(params, route))


def isotropic_characteristic(params: RodParameters, route: str = "auto") -> float:
    """Real clamped determinant of the isotropic complex problem (R = 1 or omega = T = 0).

    Simple zeros exactly at the (double) zeros of :func:`characteristic`;
    normalised like D (det exp(-sigma) of the complex boundary map).
    Dimensionless.
    """
    return float(isotropic_evans(params, route).value.real)


def kernel_dimension(params: RodParameters, rtol: float = 1e-7) -> int:
    """Dimension of the kernel of the clamped static problem at params (real solutions):
    the number of singular values of the scaled boundary matrix below rtol times the
    largest. Use it at a located root (1 for a simple zero, 2 for a double one)."""
    s = np.asarray(_finish(real_evans(params, "schur")).singular_values)
    return int(np.sum(s <= rtol * s[0]))
