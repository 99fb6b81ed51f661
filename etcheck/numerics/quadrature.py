"""Many integrals against the standard normal density at once, adaptively, accurate far into the tails.

    I_i = int_{-cap}^{cap} f_i(z) phi(z) dz,   f_i >= 0, given as ln f_i (dimensionless)

Globally adaptive Gauss-Kronrod (the 15-point Kronrod rule with its embedded
7-point Gauss rule, QUADPACK's qk15): every integral starts from ``panels``
equal panels; each round evaluates the new panels of every unfinished integral
in one vectorised call, and bisects the panels whose error estimate |K15 - G7|
exceeds their share of rtol x I_i. The integrand is handled in logarithms,
scaled by its largest value seen, so that an integral of 1e-300 keeps its
relative accuracy. |K15 - G7| is the error of the 7-point rule, an upper
estimate of the error of the 15-point value returned (which is exact for
polynomials of degree 22 on each panel). The integrand may carry its own
pointwise error bound e_i(z) >= 0 (ln e_i, e.g. from its own evaluation),
integrated alongside with the same positive weights; panels are not refined
below it (an integral is done when its quadrature error is below rtol x I_i
plus its own error). Beyond +-cap the
integrals are cut: the integrands used here are probabilities (<= 1), so the
cut is at most 2 Phi(-cap) (``truncation``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["NormalIntegrals", "normal_integrals", "CAP"]

#: Half-width of the integration range in standard-normal coordinates: 2 Phi(-8.3) = 1.0e-16.
CAP = 8.3
_XK = np.array([-0.991455371120812639206854697526329, -0.949107912342758524526189684047851,
                -0.864864423359769072789712788640926, -0.741531185599394439863864773280788,
                -0.586087235467691130294144845693013, -0.405845151377397166906606412076961,
                -0.207784955007898467600689403773245, 0.0, 0.207784955007898467600689403773245,
                0.405845151377397166906606412076961, 0.586087235467691130294144845693013,
                0.741531185599394439863864773280788, 0.864864423359769072789712788640926,
                0.949107912342758524526189684047851, 0.991455371120812639206854697526329])
_WK = np.array([0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                0.204432940075298892414161999234649, 0.209482141084727828012999174891714,
                0.204432940075298892414161999234649, 0.190350578064785409913256402421014,
                0.169004726639267902826583426598550, 0.140653259715525918745189590510238,
                0.104790010322250183839876322541518, 0.063092092629978553290700663189204,
                0.022935322010529224963732008058970])
#: The 7-point Gauss weights on the odd Kronrod nodes (1, 3, 5, 7, 9, 11, 13).
_WG = np.zeros(15)
_WG[1::2] = [0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
             0.381830050505118944950369775488975, 0.417959183673469387755102040816327,
             0.381830050505118944950369775488975, 0.279705391489276667901467771423780,
             0.129484966168869693270611432679082]
_LOG_SQRT_2PI = 0.5 * math.log(2 * math.pi)


@dataclass(frozen=True)
class NormalIntegrals:
    """The integrals of :func:`normal_integrals`: ``log_value`` ln I_i (-inf where I_i = 0); relative error
    estimates of the quadrature (``quadrature``) and of the integrand's own error (``own``); ``truncation`` the
    absolute cut 2 Phi(-cap) (for integrands <= 1); ``converged`` per integral; ``evaluations`` in all;
    ``peak``: the node where f_i phi is largest."""

    log_value: np.ndarray
    quadrature: np.ndarray
    own: np.ndarray
    truncation: float
    converged: np.ndarray
    evaluations: int
    peak: np.ndarray


def normal_integrals(log_f: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]], n: int,
                     rtol: float = 1e-10, cap: float = CAP, panels: int = 8, max_panels: int = 4000,
                     below: float = 0.0) -> NormalIntegrals:
    """I_i = int_{-cap}^{cap} f_i(z) phi(z) dz for i < n, each to the relative error ``rtol`` (module docstring).

    ``log_f(i, z)`` takes equally long arrays of integral indices and points and returns (ln f_i(z), ln e_i(z)),
    the integrand and its own pointwise error bound (-inf where exact). An integral whose panels reach
    ``max_panels`` stops there, not converged, with its error estimate. An integral whose value plus error
    estimate is below ``below`` is done (converged: what is asked of it is that bound).
    """
    edges = np.linspace(-cap, cap, panels + 1)
    owner = np.repeat(np.arange(n), panels)
    a, b = np.tile(edges[:-1], n), np.tile(edges[1:], n)
    store = _Panels(np.empty(0, int), np.empty(0), np.empty(0), np.empty((0, 15)), np.empty((0, 15)))
    done = np.zeros(n, dtype=bool)
    evaluations = 0
    while True:
        lf, le = _evaluate(log_f, owner, a, b)
        evaluations += lf.size
        store = store.extend(owner, a, b, lf, le)
        value, err, own, count = store.sums(n)
        small = value + err + own < below * np.exp(-store.shift)
        ok = (err <= rtol * value + own) | (value == 0) | small  # no finer than the integrand's own error
        done = done | ok | (count >= max_panels)
        split = ~done[store.owner] & (store.err > rtol * value[store.owner] / count[store.owner])
        if not split.any():
            break
        mid = 0.5 * (store.a[split] + store.b[split])
        owner = np.concatenate([store.owner[split]] * 2)
        a, b = np.concatenate([store.a[split], mid]), np.concatenate([mid, store.b[split]])
        store = store.drop(split)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_value = np.log(value) + store.shift
        rel = np.where(value > 0, err / value, 0.0)
        rel_own = np.where(value > 0, own / value, 0.0)
    trunc = 2.0 * 0.5 * math.erfc(cap / math.sqrt(2.0))
    converged = (err <= rtol * value + own) | (value == 0) | (value + err + own < below * np.exp(-store.shift))
    return NormalIntegrals(log_value, rel, rel_own, trunc, converged, evaluations, store.peaks(n))


def _evaluate(log_f, owner: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """ln(f phi) and ln(e phi) at the 15 Kronrod nodes of every panel (rows)."""
    z = 0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * _XK[None, :]
    lf, le = log_f(np.repeat(owner, 15), z.ravel())
    log_phi = -0.5 * z**2 - _LOG_SQRT_2PI
    shape = z.shape
    return np.asarray(lf, float).reshape(shape) + log_phi, np.asarray(le, float).reshape(shape) + log_phi


@dataclass
class _Panels:
    """The panels kept so far (integral, ends, ln values at the nodes) and, per integral, the scale shift."""

    owner: np.ndarray
    a: np.ndarray
    b: np.ndarray
    lf: np.ndarray
    le: np.ndarray
    shift: np.ndarray | None = None
    err: np.ndarray | None = None

    def extend(self, owner, a, b, lf, le) -> _Panels:
        return _Panels(np.concatenate([self.owner, owner]), np.concatenate([self.a, a]), np.concatenate([self.b, b]),
                       np.concatenate([self.lf, lf]), np.concatenate([self.le, le]))

    def peaks(self, n: int) -> np.ndarray:
        """Per integral, the node where ln(f phi) is largest."""
        z = 0.5 * (self.a + self.b)[:, None] + 0.5 * (self.b - self.a)[:, None] * _XK[None, :]
        out = np.zeros(n)
        for i in range(n):
            rows = self.owner == i
            if rows.any():
                out[i] = z[rows].ravel()[np.argmax(self.lf[rows].ravel())]
        return out

    def drop(self, mask: np.ndarray) -> _Panels:
        keep = ~mask
        return _Panels(self.owner[keep], self.a[keep], self.b[keep], self.lf[keep], self.le[keep])

    def sums(self, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Per integral (scaled by exp(-shift)): K15 value, |K15 - G7| error, own error, number of panels; sets
        each panel's error ``err`` (same scale)."""
        top = np.max(np.maximum(self.lf, self.le), axis=1)
        shift = np.full(n, -np.inf)
        np.maximum.at(shift, self.owner, top)
        shift = np.where(np.isfinite(shift), shift, 0.0)
        self.shift = shift
        half = 0.5 * (self.b - self.a)
        f = np.exp(self.lf - shift[self.owner][:, None])
        k = half * (f @ _WK)
        # QUADPACK's estimate (qk15): |K15 - G7| scaled by the variation of f over the panel, to the power 3/2
        asc = half * (np.abs(f - (k / (2 * half))[:, None]) @ _WK)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(asc > 0, 200.0 * np.abs(k - half * (f @ _WG)) / asc, 0.0)
        self.err = asc * np.minimum(1.0, ratio**1.5)
        own = half * (np.exp(self.le - shift[self.owner][:, None]) @ _WK)
        value, err, own_sum = (np.bincount(self.owner, w, minlength=n) for w in (k, self.err, own))
        return value, err, own_sum, np.bincount(self.owner, minlength=n)
