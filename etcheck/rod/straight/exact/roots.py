"""Rung 1x: roots of the exact characteristic function of the straight tether along
load, spin, tension or a ray, with a second formulation for each root's error, and
the damped critical values from them (Kelvin-Tait-Chetaev: the damped straight rod
loses stability only where its static operator is singular; model.md section 8).
The function itself is :mod:`etcheck.rod.straight.exact.determinant`; the string limit
under strong tension closes the module. Dimensionless and pure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from etcheck.numerics.optimize import brentq, minimize_scalar
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.damped_critical import (
    LADDER,
    DampedCritical,
    PencilRoot,
    critical_from_roots,
    damped_critical,
)
from etcheck.rod.straight.exact.determinant import (
    is_isotropic,
    isotropic_batch_values,
    isotropic_evans,
    polynomial_roots,
    real_batch,
    real_evans,
    scales,
    tensions,
)
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import OverBudget

__all__ = [
    "AXES",
    "MODEL",
    "ExactRoot",
    "Counter",
    "alternative_function",
    "exact_root",
    "first_exact_root",
    "exact_critical",
    "pencil_or_exact",
    "root_function",
    "root_scale",
    "route_at",
    "second_opinion",
    "string_limit_load",
]

#: Model string of every root from this module.
MODEL = "rung 1x (exact determinant)"
#: Axes along which roots are searched (as in :func:`etcheck.rod.straight.collocation.damped_critical.first_root`).
AXES = ("B", "omega", "T", "ray")
_EPS = np.finfo(float).eps
#: beta_1 of the first double zero of chi (eq. (91)) to 7 digits: the scan's scale of the welded static load.
_BETA1 = 7.332130


# --- roots along an axis -----------------------------------------------------------------


@dataclass(frozen=True)
class ExactRoot:
    """A root of the exact characteristic function along one axis (dimensionless).

    ``value``: B, T, omega (not omega^2) or the ray parameter t; inf when
    none lies below the search limit. ``error``: relative error bound (the
    Brent tolerance plus the disagreement with a second formulation,
    doubled; relative to max(|value|, floor)). ``multiplicity``: 2 for the
    double zeros of the isotropic cases (R = 1, or omega = T = 0), 1 else.
    ``evaluations``: determinant evaluations spent; ``route``: the
    formulation that located it.
    """

    axis: str
    value: float
    error: float
    multiplicity: int
    evaluations: int
    route: str

    def pencil_root(self, tol: float) -> PencilRoot:
        """The same root as :class:`etcheck.rod.straight.collocation.damped_critical.PencilRoot` (N = 0: no grid)."""
        model = MODEL if self.multiplicity == 1 else f"{MODEL}, double root"
        return PencilRoot(self.axis, self.value, self.error, 0, bool(self.error <= tol), model)


def _axis_params(params: RodParameters, axis: str, x: float) -> RodParameters:
    if axis == "ray":
        return params.with_(B=x * params.B, omega=math.sqrt(max(x, 0.0)) * params.omega)
    return params.with_(**{axis: x})


def root_scale(params: RodParameters, axis: str, sign: float) -> float:
    """Expected size of the first root on ``axis`` (sets the scan step): the static
    load (rung 0) plus the string load 2 pi T; the Rayleigh quotient of the first
    bending mode for the spin; the Euler load for the tension (each for the rod's ends)."""
    P, R, f = params.P, params.R, params.f
    Tp = max(params.T, 0.0)
    ends = params.ends
    static = _BETA1**3 * math.sqrt(R) / f if ends.is_welded else float(critical_loads(R, f, 1, ends)[0])
    load = static + 2 * math.pi * Tp
    # first bending mode: int phi''^2 / int phi^2 = beta^4 (f when welded), int phi'^2 / int phi^2 (Ends.beam)
    slope = ends.beam.slope_quotient
    bending = R if ends.is_welded else R * ends.first_bending_root ** 4 / f
    spin = math.sqrt((bending + slope * Tp) / max(1.0 - slope * P * R, 0.05))
    if axis == "B":
        return load
    if axis == "omega":
        return spin
    if axis == "T":
        return ends.euler_load * R / f + abs(params.B) / (2 * math.pi) + params.omega**2 / math.pi**2
    if params.B == 0 and params.omega == 0:
        raise ValueError("the ray needs B != 0 or omega != 0")
    return 1.0 / (abs(params.B) / load + params.omega**2 / spin**2)


class Counter:
    """Vectorised function of the axis value with an evaluation count; scalar calls too."""

    def __init__(self, fn):
        self.fn, self.n = fn, 0

    def many(self, x: np.ndarray) -> np.ndarray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        self.n += x.size
        return self.fn(x)

    def __call__(self, x: float) -> float:
        return float(self.many(np.array([x]))[0])


def root_function(params: RodParameters, axis: str, sign: float, route: str = "auto", factor: float = 1.0,
              shift: int = 0):
    """The real, vectorised function of the (unsigned) axis value whose zeros are the
    roots, and the multiplicity of its zeros as roots of D."""
    moving = {"ray": ("B", "omega")}.get(axis, (axis,))
    iso = params.R == 1.0 or (params.omega == 0.0 and params.T == 0.0 and "omega" not in moving
                              and "T" not in moving)

    def args(x):
        t = sign * x
        if axis == "ray":
            return t * params.B, np.sqrt(np.maximum(t, 0.0)) * params.omega, np.full_like(t, params.T)
        vals = {"B": params.B, "omega": params.omega, "T": params.T}
        return tuple(t if name == axis else np.full_like(t, vals[name]) for name in ("B", "omega", "T"))

    def one(x, evans):
        B, w, T = args(x)
        return np.array([evans(params.with_(B=float(b), omega=float(o), T=float(t)), route, factor, shift).value.real
                         for b, o, t in zip(B, w, T)])

    if iso:
        if route == "auto":
            return (lambda x: isotropic_batch_values(params, *args(x), factor, shift)), 2
        return (lambda x: one(x, isotropic_evans)), 2
    if route == "auto":
        return (lambda x: real_batch(params, *args(x), factor, shift)), 1
    return (lambda x: one(x, real_evans)), 1


#: Samples per block of the scan (one vectorised evaluation) and per expected root.
_BLOCK = 16


def _scan(g: Counter, step: float, limit: float, rtol: float):
    """First zero of g on (0, limit]: a sign change, or a close pair found by
    minimising |g| at a local minimum of the samples. Returns (x, bracket) with x
    set for a touching zero, or None. First a block halving towards zero (step / 2 .. step / 2^16: a
    root much smaller than expected, e.g. the spin roots just below the static load, which come as a
    close pair there), then steps of ``step`` up to 64 steps, then geometric (1/16 of the current value)."""
    xs_prev = np.array([0.0])
    gs_prev = g.many(xs_prev)
    x = 0.0
    first = True
    while x < limit:
        if first:
            xs = step * 2.0 ** -np.arange(_BLOCK, 0, -1)
            first = False
        elif x < 64 * step:
            xs = x + step * np.arange(1, _BLOCK + 1)
        else:
            xs = x * (1.0 + 1.0 / 16) ** np.arange(1, _BLOCK + 1)
        gs = g.many(xs)
        X = np.concatenate([xs_prev[-2:], xs])
        G = np.concatenate([gs_prev[-2:], gs])
        for i in range(len(xs_prev[-2:]), len(X)):
            if G[i] == 0.0:
                return X[i], (X[i], X[i])
            if np.sign(G[i]) != np.sign(G[i - 1]):
                return None, (X[i - 1], X[i])
            if i >= 2 and abs(G[i - 1]) < abs(G[i - 2]) and abs(G[i - 1]) < abs(G[i]):
                sg = np.sign(G[i - 1])
                res = minimize_scalar(lambda t, sg=sg: sg * g(t), bounds=(X[i - 2], X[i]), method="bounded",
                                      options={"xatol": rtol * X[i]})
                if sg * res.fun <= 0.0:
                    return None, (X[i - 2], res.x)
                if abs(res.fun) <= 1e3 * _EPS * max(abs(G[i - 2]), abs(G[i])):  # touching zero
                    return res.x, (res.x, res.x)
        xs_prev, gs_prev, x = xs, gs, xs[-1]
    return None


def _refine(g, bracket: tuple[float, float], rtol: float) -> float:
    lo, hi = bracket
    if lo == hi:
        return lo
    return brentq(g, lo, hi, xtol=1e-300, rtol=rtol, maxiter=200)


def second_opinion(g2, x: float, rtol: float) -> float:
    """Root of a second formulation g2 next to x (bracket grown from 1e-13 relative);
    located to 1 % of the bracket, which is all an error estimate needs."""
    d = 1e-13 * max(abs(x), 1e-300)
    for _ in range(12):
        lo, hi = x - d, x + d
        glo, ghi = g2.many(np.array([lo, hi]))
        if np.sign(glo) != np.sign(ghi):
            return brentq(g2, lo, hi, xtol=max(1e-2 * d, 4 * _EPS * abs(x)), rtol=rtol, maxiter=200)
        d *= 10.0
    return math.nan


@single_blas_thread
def exact_root(params: RodParameters, axis: str, sign: float = 1.0, floor: float = 0.0,
               rtol: float = 4 * _EPS, limit: float = 1e3) -> ExactRoot:
    """Smallest root of the exact characteristic function on ``axis`` on the side ``sign``.

    ``axis``: "B", "omega", "T" or "ray" (t with D(t B, sqrt(t) omega, T)
    = 0), the others fixed at ``params`` (for B, omega, T the axis value in
    params is ignored). Scans from zero in vectorised blocks with a step of
    1/16 of the expected root (:func:`root_scale`), later 1/16 of the current
    value, up to ``limit`` times the expected root (inf beyond). A sign
    change is refined by Brent's method; a local minimum of |D| between
    samples is minimised to split a close pair of roots. The error is the
    Brent tolerance plus the distance to the root of a second formulation
    (the other route, or other scales and split), doubled, relative to
    max(|root|, floor).
    """
    if axis not in AXES:
        raise ValueError(f"axis must be one of {AXES}, got {axis!r}")
    if sign not in (1.0, -1.0):
        raise ValueError("sign must be +1 or -1")
    # neither the axis value nor gamma enters D: memoised on params without them (in a sweep the roots at zero
    # spin or zero load are shared by every point of a length)
    normal = params.with_(gamma=0.0) if axis == "ray" else params.with_(gamma=0.0, **{axis: 0.0})
    return _exact_root(normal, axis, float(sign), float(floor), float(rtol), float(limit))


@lru_cache(maxsize=512)
def _exact_root(params: RodParameters, axis: str, sign: float, floor: float, rtol: float, limit: float) -> ExactRoot:
    scale = root_scale(params, axis, sign)
    fn, mult = root_function(params, axis, sign)
    g = Counter(fn)
    found = _scan(g, scale / 16, limit * scale, 1e-10)
    if found is None:
        return ExactRoot(axis, sign * math.inf, 0.0, mult, g.n, "exponential")
    x, bracket = found
    if x is None:
        x = _refine(g, bracket, rtol)
    elif mult == 1:
        mult = 2  # a numerically touching zero of the generic function
    value = sign * x
    route = route_at(params, axis, value, mult)
    g2 = Counter(alternative_function(params, axis, sign, value, route))
    x2 = second_opinion(g2, x, rtol)
    err = 2.0 * (abs(x - x2) + 2 * rtol * abs(x)) if math.isfinite(x2) else math.inf
    return ExactRoot(axis, value, err / max(abs(x), floor, 1e-300), mult, g.n + g2.n, route)


def alternative_function(params: RodParameters, axis: str, sign: float, value: float, route: str):
    """A second formulation for the error estimate: the other route where it applies
    and is accurate (Schur only while the exponents span < 4 decades: its error is
    eps times the largest),
    else other scales (x 1.37) and another split tau (the exponential basis, Schur where it does not apply)."""
    other = "exponential" if route == "schur" else "schur"
    if other == "schur" and _separation(params, axis, value) > 1e4:
        other = None
    if other is not None:
        fn, _ = root_function(params, axis, sign, route=other)
        try:
            fn(np.array([abs(value)]))
            return fn
        except ValueError:
            pass
    # "auto": where the exponential basis stops applying next to the root (coincident exponents), Schur
    fn, _ = root_function(params, axis, sign, route="auto", factor=1.37, shift=1)
    return fn


def route_at(params: RodParameters, axis: str, x: float, mult: int) -> str:
    p = _axis_params(params, axis, x)
    if mult == 2 and is_isotropic(p):
        return isotropic_evans(p, "auto").route
    return real_evans(p, "auto").route


def _separation(params: RodParameters, axis: str, x: float) -> float:
    """Largest wavenumber scale over the smallest non-zero exponent at the root: the
    Schur route's absolute error on the exponents is eps times the former."""
    p = _axis_params(params, axis, x)
    a, b, w2 = tensions(p)
    c = np.array([[p.R / p.f**2, -(p.R * b + a) / p.f, a * b - w2 * (p.R + 1) / p.f, w2 * (a + b) + p.B**2, w2**2]])
    with np.errstate(all="ignore"):
        k = np.sqrt(np.abs(polynomial_roots(c[:, :4] if w2 == 0 else c)))
    k = k[np.isfinite(k) & (k > 0)]
    return max(scales(p)) / max(float(np.min(k)) if k.size else 1.0, 1e-300)


def first_exact_root(params: RodParameters, axis: str, tol: float = 1e-8, sign: float = 1.0,
                     floor: float = 0.0) -> PencilRoot:
    """:func:`exact_root` as a :class:`~etcheck.rod.straight.collocation.damped_critical.PencilRoot`
    (same semantics as :func:`etcheck.rod.straight.collocation.damped_critical.first_root`: value
    signed, inf when none, error relative to max(|value|, floor))."""
    return exact_root(params, axis, sign, floor).pencil_root(tol)


@single_blas_thread
def exact_critical(params: RodParameters, tol: float = 1e-8, spin: bool = True) -> DampedCritical:
    """Critical load, critical spin and stability of the damped straight rod, exactly.

    Same semantics as :func:`etcheck.rod.straight.collocation.damped_critical.damped_critical`
    (requires gamma > 0, Kelvin-Tait-Chetaev): the compressive limit when
    T < 0, the spin that destabilises the unloaded rod, the static load at
    zero spin, the critical load at the operating spin (0 beyond the spin
    at rest), the critical spin at the operating load (0 when statically
    buckled; NaN with ``spin=False``), stable iff omega < spin at rest and
    B < critical load. Errors relative to the root or to 1 % of its value at
    zero spin (load) or zero load (spin). Dimensionless.
    """
    if not params.gamma > 0:
        raise ValueError("exact_critical needs gamma > 0 (Kelvin-Tait-Chetaev); undamped rods can flutter")
    return critical_from_roots(params, tol, spin, first_exact_root)


def pencil_or_exact(params: RodParameters, tol: float = 1e-8, ladder: tuple[int, ...] = LADDER,
                    spin: bool = True) -> DampedCritical:
    """:func:`~etcheck.rod.straight.collocation.damped_critical.damped_critical` (the static pencils, milliseconds), and
    :func:`exact_critical` where a pencil root missed ``tol`` and the exact determinant meets it.

    Next to the end of its line (a critical load as the spin nears the unloaded rod's critical spin, a
    critical spin as the load nears the static load) a root falls like a square root and the pencil's
    round-off, 32 N^2 eps relative, is amplified by end / (2 (end - at)); the determinant's stays near eps
    (SET 8e-6 below its static load: the spin root 2.8e-7 off at N = 48, 1e-13 by the determinant).
    Same semantics as both; dimensionless. Where even the coarsest pencils would exceed the memory budget
    (:mod:`etcheck.runtime.memory`), the exact determinant alone (it builds no large matrix)."""
    try:
        d = damped_critical(params, tol, ladder, spin)
    except OverBudget:
        return exact_critical(params, tol, spin)
    if d.converged:
        return d
    e = exact_critical(params, tol, spin)
    return e if e.converged else d


# --- the string limit ----------------------------------------------------------------------


def string_limit_load(params: RodParameters, order: int = 1) -> float:
    """First critical load B of the straight tether under strong tension (dimensionless).

    As T f -> infinity both axes are strings held at their ends: with
    w = u + i v the outer problem is -T w'' + i B w' = 0, w(0) = w(1) = 0,
    whose first root is B = 2 pi T (I B0 = 2 pi T / L physically) whatever
    the attachment. Each end carries a boundary layer exp(-s / eps) of width
    eps_u = sqrt(R / (f a)) in u and eps_v = sqrt(1 / (f b)) in v
    (a = T + P R omega^2, b = T + P omega^2). Matched to the outer
    solution, a welded end (w = w' = 0) turns into u -/+ eps_u u' = 0,
    v -/+ eps_v v' = 0 (a pin at a distance eps inside it); a pinned end (w =
    w'' = 0) into w = eps^2 w'' (the layer's amplitude is eps^2 w''), which
    the outer helix meets at any beta as it meets w = 0: it does not move
    the root at any order in eps. With w = A + C exp(i beta s),
    beta = B / T = 2 pi + delta, the four conditions split at first order
    into (delta - 2 pi n eps_u) Im C = 0 and (delta - 2 pi n eps_v) Re C = 0,
    n the number of ends that hold the slope (welded): the double string root splits into
    beta = 2 pi (1 + n eps_u) (the mode whose ends bend about the weak
    axis, the first one) and 2 pi (1 + n eps_v). So

        order 0:  B = 2 pi T
        order 1:  B = 2 pi T (1 + n eps_u)                 error O(1 / (f T)) (pinned: order 0)
        order 2:  + 2 pi T [n^2 eps_u^2 + 2 pi^2 (1 + R) / (f T)
                            - omega^2 / (2 pi^2 T) + P (1 + R) omega^2 / (2 T)]

    The order-2 terms: the next term of the layer series (the n welded
    ends act as pins eps_u inside: 2 pi / (1 - n eps_u)), and the Rayleigh
    quotient of the outer helix w = 1 - exp(2 pi i s) (and i times it; the
    quotient is the same on both, so it does not split the pair): its bending
    stiffness averaged over u and v ((R + 1) / (2 f) times (2 pi)^2), and the
    spin (the whirling string B^2 = 4 pi^2 T^2 - 4 T omega^2, rotary inertia
    as the mean extra tension). For a thin tape (R << 1) with welded ends the
    order-2 bending term 2 pi^2 / (f T) exceeds the layer term
    2 sqrt(R / (f T)) until f T ~ pi^4 / R; with pinned ends it is the first
    correction. Error of order 2: O((f T)^-3/2). Requires T > 0.
    """
    if not params.T > 0:
        raise ValueError("the string limit needs tension T > 0")
    if order not in (0, 1, 2):
        raise ValueError("order must be 0, 1 or 2")
    T, R, f, P, w2 = params.T, params.R, params.f, params.P, params.omega**2
    a = T + P * R * w2
    n = sum(end.holds_slope for end in params.ends.conditions)
    layer = n * math.sqrt(R / (f * a))
    ratio = 1.0
    if order >= 1:
        ratio += layer
    if order >= 2:
        ratio += (layer**2 + 2 * math.pi**2 * (1 + R) / (f * T) - w2 / (2 * math.pi**2 * T)
                  + P * (1 + R) * w2 / (2 * T))
    return 2 * math.pi * T * ratio
