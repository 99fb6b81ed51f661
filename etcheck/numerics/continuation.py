"""Pseudo-arclength continuation of F(u, p) = 0 (generic, rod-agnostic, dimensionless).

The problem is an object with

* ``residual(u, p) -> r``            shape (m,)
* ``jacobian(u, p) -> (Ju, Jp)``     shapes (m, m) and (m,): derivatives with
  respect to the chart coordinates du of ``retract`` and to p;
* ``retract(u, du) -> u'``           move u by du (u + du for vector spaces;
  a manifold update, e.g. a rotation, otherwise). u is opaque to this module;
* optionally ``tests(u, p, Ju) -> dict[str, float]``: scalar test functions
  whose sign changes mark special points (e.g. a symmetry-breaking branch
  point), evaluated at every accepted point.

Method (Keller's pseudo-arclength; Allgower & Georg, *Introduction to
Numerical Continuation Methods*, ch. 2-3, 8):

* predictor u = retract(u0, ds tau_u + ds^2/2 kappa_u), p = p0 + ds tau_p +
  ds^2/2 kappa_p along the unit tangent, kappa the curvature of the branch
  from the tangents of the last two accepted points (0 at the first step);
* corrector: Newton on (F(u, p) = 0, <tau, (xi, p - p0)>_W = ds), xi the
  accumulated chart displacement, with the bordered matrix
  [[Ju, Jp], [W tau]]; the next tangent solves [[Ju, Jp], [W tau0]] tau = e
  (orientation kept);
* adaptive step: grow after fast convergence (or after the plain count of
  four Newton solves where the tangent has turned by less than a sixth of the
  largest accepted turn: the branch is nearly straight), halve after slow
  convergence; reject and halve a step that failed, turned too far, or needed
  seven or more Newton solves (it may have landed on a neighbouring branch;
  its retry at half the length is accepted however many it needs);
* folds: sign change of tau_p; simple branch points: sign change of
  det([[Ju, Jp], [tau]]) (a fold does not change it); user tests: sign
  change of the test function. Every special point is a bracketed root: the
  secant (Illinois) method on the arclength between the two bracketing
  points, each trial point corrected onto the branch and rejected if it
  jumped to a crossing branch; the root is interpolated between the two
  converged ends of the final bracket and flagged ``converged`` only when
  that bracket is narrower than ``LOCATE_WIDTH`` (never the nearest step).
* branch switching: :func:`switch_branch` starts the continuation from a
  branch point along a given kernel direction (the caller supplies it, e.g.
  the kernel of the Jacobian restricted to a symmetry class).

Options are an immutable :class:`ContinuationOptions` checked at construction
(as BifurcationKit's ContinuationPar).
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from enum import StrEnum
from functools import partial

import numpy as np
import scipy.linalg as sla

__all__ = [
    "ContinuationOptions",
    "Point",
    "SpecialPoint",
    "ContinuationResult",
    "StopReason",
    "continuation",
    "switch_branch",
    "correct",
    "correct_at",
    "signed_smallness",
]


@dataclass(frozen=True)
class ContinuationOptions:
    """Options of :func:`continuation` (all dimensionless).

    ds: first step; ds_min/ds_max: step limits; p_min/p_max: stop when p leaves
    [p_min, p_max] (the last point is placed on the bound); max_points: stop
    after that many accepted points; tol: Newton tolerance on max|F| and on
    the max-norm of the update; max_newton: corrector iterations;
    max_angle: largest accepted turn of the tangent per step (radians);
    weight_p: weight of the parameter in the arclength norm (the state part
    has weight (1 - weight_p)/m per component, so both are O(1));
    locate_tol: arclength tolerance when locating special points;
    detect_folds / detect_bp: switch the built-in tests on or off.
    stop: optional predicate stop(u, p) -> bool checked at each point;
    stop_on: kinds of special points ("bp", "fold", a test name) at which the
    continuation ends once the point is located (e.g. a connecting branch
    that has reached another branch).
    """

    ds: float = 0.05
    ds_min: float = 1e-6
    ds_max: float = 0.5
    p_min: float = -math.inf
    p_max: float = math.inf
    max_points: int = 500
    tol: float = 1e-10
    max_newton: int = 8
    max_angle: float = 0.3
    weight_p: float = 0.5
    locate_tol: float = 1e-10
    detect_folds: bool = True
    detect_bp: bool = True
    stop: Callable | None = None
    stop_on: tuple = ()

    def __post_init__(self) -> None:
        if not (0 < self.ds_min <= abs(self.ds) <= self.ds_max):
            raise ValueError(f"need 0 < ds_min <= |ds| <= ds_max, got {self.ds_min}, {self.ds}, {self.ds_max}")
        if not self.p_min < self.p_max:
            raise ValueError(f"need p_min < p_max, got {self.p_min}, {self.p_max}")
        if self.max_points < 1 or self.max_newton < 1:
            raise ValueError("max_points and max_newton must be >= 1")
        if not 0 < self.weight_p < 1:
            raise ValueError(f"weight_p must lie in (0, 1), got {self.weight_p}")
        if self.tol <= 0 or self.locate_tol <= 0 or self.max_angle <= 0:
            raise ValueError("tol, locate_tol and max_angle must be > 0")


@dataclass(frozen=True, eq=False)
class Point:
    """An accepted point: state u, parameter p, unit tangent (tau_u, tau_p),
    residual norm, Newton iterations, arclength s from the start, test values."""

    u: object
    p: float
    tau: np.ndarray
    residual: float
    newton: int
    s: float
    tests: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False)
class SpecialPoint:
    """A located special point: kind ("fold", "bp" or a user test name), the
    converged point of the final bracket nearest the root (``point``), the
    index i of the branch point before it, the arclength bracket (s_lo, s_hi)
    it was located in, and the test value at ``point``.

    ``p``: the located parameter value, the root of the test function
    interpolated linearly inside the final bracket (whose ends are both
    converged points of the branch on either side of the sign change);
    ``p_bracket``: the parameter at the two ends (the root lies between);
    ``converged``: the bracket shrank below ``LOCATE_WIDTH`` in arclength
    (else ``reason`` says why it stopped and the bracket is all that is known).
    """

    kind: str
    point: Point
    index: int
    bracket: tuple
    value: float
    p: float = math.nan
    p_bracket: tuple = (math.nan, math.nan)
    converged: bool = True
    reason: str = ""


class StopReason(StrEnum):
    """Why a continuation ended (the values are what results files show)."""

    MAX_POINTS = "max_points"
    STEP_UNDERFLOW = "step size underflow"
    PARAMETER_BOUND = "parameter bound"
    STOP_CONDITION = "stop condition"
    SPECIAL_POINT = "special point"  # one of ContinuationOptions.stop_on was located
    SWITCH_FAILED = "branch switch failed"


@dataclass(frozen=True, eq=False)
class ContinuationResult:
    """Accepted points, located special points, why it stopped, wall time [s], and
    the kind of special point it stopped at (``stop_kind``, "" unless
    ``reason`` is SPECIAL_POINT)."""

    points: list
    special: list
    reason: StopReason
    time: float
    stop_kind: str = ""

    @property
    def description(self) -> str:
        """The stop reason in words, e.g. "parameter bound" or "special point (bp)"."""
        return f"{self.reason} ({self.stop_kind})" if self.reason is StopReason.SPECIAL_POINT else str(self.reason)

    @property
    def p(self) -> np.ndarray:
        return np.array([q.p for q in self.points])


def weights(m: int, opts: ContinuationOptions) -> np.ndarray:
    w = np.full(m + 1, (1.0 - opts.weight_p) / m)
    w[-1] = opts.weight_p
    return w


def _bordered(Ju: np.ndarray, Jp: np.ndarray, row: np.ndarray) -> np.ndarray:
    m = Ju.shape[0]
    A = np.empty((m + 1, m + 1))
    A[:m, :m] = Ju
    A[:m, m] = Jp
    A[m] = row
    return A


def _lu(A: np.ndarray) -> tuple[tuple, float]:
    """LU factors of A and the sign of det A."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)
        lu, piv = sla.lu_factor(A, check_finite=False)
    return (lu, piv), float(np.prod(np.sign(np.diag(lu))) * (-1.0) ** int(np.sum(piv != np.arange(piv.size))))


def _tangent(problem, u, p, tau0: np.ndarray, W: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(tau, Ju, Jp, bp) at (u, p): the unit tangent tau (in the W-norm) oriented like tau0, the Jacobians, and the
    branch-point test bp, :func:`signed_smallness` of [[Ju, Jp], [tau]], from the LU of the tangent's bordered
    matrix A = [[Ju, Jp], [W tau0]] (the two differ in their last row only: the determinant changes by the factor
    1 + (tau - W tau0) . t, t = A^{-1} e_last, and the solve by Sherman-Morrison)."""
    Ju, Jp = problem.jacobian(u, p)
    A = _bordered(Ju, Jp, W * tau0)
    lu, sign = _lu(A)
    e = np.zeros(A.shape[0])
    e[-1] = 1.0
    t = sla.lu_solve(lu, e, check_finite=False)
    if not np.all(np.isfinite(t)):
        raise np.linalg.LinAlgError("singular bordered matrix: no tangent")
    tau = t / math.sqrt(float(np.sum(W * t * t)))
    dr = tau - A[-1]
    grow = 1.0 + float(dr @ t)
    y = sla.lu_solve(lu, _probe(e.size), check_finite=False)
    return tau, Ju, Jp, _smallness(sign * float(np.sign(grow)), y - t * (float(dr @ y) / grow))


#: Newton iterations with the residual below a tenth of the tolerance after which the corrector stops even
#: though its update has not shrunk below the tolerance (measured next to the branch points of the SET diagram:
#: residuals 1e-14 - 1e-13 while the parameter wanders by 1e-7 - 1e-6 from one iteration to the next, up to the
#: 40-iteration limit)
_CALM = 4
#: the quadratic-convergence exit of :func:`correct` and :func:`correct_at` (:func:`_settled`) is taken only for
#: updates below this times sqrt(tol) (the asymptotic regime; larger updates are followed to the plain test)
_QUADRATIC = 10.0


def _settled(step: float, last: float, tol: float) -> bool:
    """Whether Newton converges quadratically enough that the update of size ``step`` just made (after one of
    size ``last``) is the last one the plain test (an update below ``tol``) needs: the next update, ~ step^2 /
    last^2 * step, below a tenth of the tolerance, and the update itself below _QUADRATIC sqrt(tol) (the
    asymptotic regime). Never after the first update (``last`` infinite: no rate to go by)."""
    return math.isfinite(last) and step < _QUADRATIC * math.sqrt(tol) and step < last and step**3 / last**2 < 0.1 * tol


def correct(problem, u0, p0: float, tau0: np.ndarray, ds: float, W: np.ndarray, tol: float, max_newton: int,
            curvature: np.ndarray | None = None):
    """Predictor-corrector step of arclength ds from (u0, p0) along tau0 (and, given the branch's ``curvature``
    there, d tau / ds in the same coordinates, along the osculating parabola: the predictor's error is then of
    third order in ds instead of second).

    Returns (u, p, residual_norm, iterations, converged).
    """
    m = tau0.size - 1
    lead = ds * tau0 if curvature is None else ds * tau0 + 0.5 * ds * ds * curvature
    xi = lead[:m]
    u = problem.retract(u0, xi)
    p = p0 + float(lead[m])
    row = W * tau0
    rn = math.inf
    calm = 0  # consecutive iterations with the residual at round-off
    last = math.inf  # the previous update's size
    for it in range(1, max_newton + 1):
        r = problem.residual(u, p)
        g = float(row[:m] @ xi + row[m] * (p - p0) - ds)
        Ju, Jp = problem.jacobian(u, p)
        try:
            d = np.linalg.solve(_bordered(Ju, Jp, row), -np.append(r, g))
        except (np.linalg.LinAlgError, ValueError):
            return u, p, math.inf, it, False
        if not np.all(np.isfinite(d)):
            return u, p, math.inf, it, False
        u = problem.retract(u, d[:m])
        xi = xi + d[:m]
        p = p + float(d[m])
        step = float(np.max(np.abs(d)))
        rn = float(np.max(np.abs(r)))
        if step < tol and rn < 1e2 * tol:
            rn = float(np.max(np.abs(problem.residual(u, p))))
            return u, p, rn, it, rn < tol
        if _settled(step, last, tol):
            # the residual at the result decides; the count returned is the one the plain test (update < tol)
            # would have reached, one more: the step control (_next_step) reads the same numbers as before
            rn = float(np.max(np.abs(problem.residual(u, p))))
            if rn < tol:
                return u, p, rn, it + 1, True
        last = step
        if it >= 3 and rn > 1e3:
            break
        calm = calm + 1 if rn < 0.1 * tol else 0
        if calm >= _CALM:  # a solution; the update does not shrink because the bordered matrix is nearly
            break  # singular (next to a branch point): more iterations only wander along its near-null direction
    rn = float(np.max(np.abs(problem.residual(u, p))))
    return u, p, rn, max_newton, rn < tol


def correct_at(problem, u, p: float, tol: float, max_newton: int):
    """Newton at fixed parameter p (needs a regular Ju); returns like :func:`correct` (with its quadratic exit,
    :func:`_settled`)."""
    last = math.inf
    for it in range(1, max_newton + 1):
        r = problem.residual(u, p)
        Ju, _ = problem.jacobian(u, p)
        try:
            d = np.linalg.solve(Ju, -r)
        except (np.linalg.LinAlgError, ValueError):
            return u, p, math.inf, it, False
        u = problem.retract(u, d)
        step = float(np.max(np.abs(d)))
        if step < tol:
            rn = float(np.max(np.abs(problem.residual(u, p))))
            return u, p, rn, it, rn < tol
        if _settled(step, last, tol):
            rn = float(np.max(np.abs(problem.residual(u, p))))
            if rn < tol:
                return u, p, rn, it + 1, True
        last = step
    rn = float(np.max(np.abs(problem.residual(u, p))))
    return u, p, rn, max_newton, rn < tol


def _probe(n: int) -> np.ndarray:
    """The fixed vector e of :func:`signed_smallness`."""
    return np.cos(np.arange(n) * 0.7 + 0.3)


def _smallness(sign: float, y: np.ndarray) -> float:
    big = float(np.max(np.abs(y)))
    return float(sign / big) if np.isfinite(big) and big > 0 else 0.0


def signed_smallness(A: np.ndarray) -> float:
    """sign(det A) / max|A^{-1} e| for a fixed vector e (one LU).

    A continuous test function: zero exactly where A is singular, of the
    order of the smallest singular value near it, and it changes sign at a
    simple zero of det A (so the secant method locates it fast).
    """
    lu, sign = _lu(A)
    return _smallness(sign, sla.lu_solve(lu, _probe(A.shape[0]), check_finite=False))


def _make_point(problem, u, p, tau_prev, W, s, residual, newton, opts) -> Point:
    tau, Ju, Jp, bp = _tangent(problem, u, p, tau_prev, W)
    tests = {}
    if opts.detect_bp:
        tests["bp"] = bp
    if opts.detect_folds:
        tests["fold"] = float(tau[-1])
    extra = getattr(problem, "tests", None)
    if extra is not None:
        tests.update(extra(u, p, Ju))
    return Point(u, float(p), tau, residual, newton, s, tests)


def illinois_update(x: float, fx: float, lo: float, hi: float, flo: float, fhi: float, last: int = 0) -> tuple:
    """One bracket update of the Illinois (modified regula falsi) method: keep the
    sign change in [lo, hi]; when the same end is replaced twice in a row (``last``:
    -1 lo, +1 hi, 0 none), halve the value at the stale end. Returns
    (lo, hi, flo, fhi, replaced end)."""
    if (fx > 0) == (flo > 0):
        return x, hi, fx, (0.5 * fhi if last == -1 else fhi), -1
    return lo, x, (0.5 * flo if last == 1 else flo), fx, 1


#: a special point counts as located when its arclength bracket is narrower than this (weighted norm)
LOCATE_WIDTH = 1e-7
#: failed or jumped trials after which :func:`_locate` gives up
_MAX_FAILURES = 12


@dataclass
class _Bracket:
    """The current bracket of :func:`_locate`: arclength ends (from a), Illinois values,
    true test values and converged points at the ends."""

    lo: float
    hi: float
    flo: float
    fhi: float
    f0lo: float
    f0hi: float
    plo: Point
    phi: Point
    last: int = 0  # end replaced by the previous update: -1 lo, +1 hi

    def trial(self, failures: int) -> float:
        """Next arclength: Illinois secant, or after failed trials ever closer to the ends."""
        lo, hi = self.lo, self.hi
        if failures:
            frac = 0.5 ** (1 + (failures + 1) // 2)
            return lo + (frac if failures % 2 else 1.0 - frac) * (hi - lo)
        sig = hi - self.fhi * (hi - lo) / (self.fhi - self.flo) if self.fhi != self.flo else 0.5 * (lo + hi)
        return sig if lo < sig < hi else 0.5 * (lo + hi)

    def update(self, sig: float, q: Point, fq: float) -> None:
        if fq == 0.0:
            self.lo = self.hi = sig
            self.plo = self.phi = q
            self.f0lo = self.f0hi = 0.0
            return
        self.lo, self.hi, self.flo, self.fhi, self.last = illinois_update(sig, fq, self.lo, self.hi, self.flo,
                                                                          self.fhi, self.last)
        if self.last == -1:
            self.f0lo, self.plo = fq, q
        else:
            self.f0hi, self.phi = fq, q


def _trial_point(problem, br: _Bracket, s_a: float, sig: float, name: str, W, opts) -> Point | None:
    """The branch point at arclength sig inside the bracket, or None when the corrector
    failed or landed on a crossing branch (its tangent turned away too far)."""
    # predictor-corrector from the nearer converged bracket end along its own tangent: a short step
    # keeps the trial in the basin of this branch next to a branch point
    base, step = (br.plo, sig - br.lo) if sig - br.lo <= br.hi - sig else (br.phi, sig - br.hi)
    return _stepped(problem, base, step, name, float(np.sum(W * br.plo.tau * br.phi.tau)), W, opts)


def _stepped(problem, base: Point, step: float, name: str, cos_end: float, W, opts) -> Point | None:
    """The point of the branch a short pseudo-arclength step from the converged point ``base`` along its tangent
    (up to 40 Newton solves: next to a branch point the bordered matrix is nearly singular), or None when the
    corrector failed or the point left the branch: its tangent turned from base's by more than the larger of
    ``max_angle`` and the turn ``cos_end`` (a cosine) allows, plus slack, or it has no test ``name`` (it landed on
    a crossing branch)."""
    u, p, rn, it, ok = correct(problem, base.u, base.p, base.tau, step, W, opts.tol, max(40, opts.max_newton + 4))
    if not ok:
        return None
    q = _make_point(problem, u, p, base.tau, W, base.s + step, rn, it, opts)
    if float(np.sum(W * base.tau * q.tau)) < min(cos_end, math.cos(opts.max_angle)) - 0.2 or name not in q.tests:
        return None
    return q


def _locate(problem, a: Point, b: Point, name: str, W, opts, settled=None
            ) -> tuple[SpecialPoint, tuple[Point, Point]]:
    """Bracketed root of tests[name] between the accepted points a and b.

    Illinois (modified regula falsi: the value at an end kept twice in a row
    is halved, which keeps the convergence superlinear) on the arclength from
    a. Each trial is
    corrected onto the branch by a short pseudo-arclength step from the
    nearer converged end of the current bracket, along that end's tangent
    (up to 40 Newton iterations: next to a branch point the bordered matrix
    is nearly singular and Newton converges only linearly), and is kept only
    if its tangent has not turned away from that end's by more than the two
    ends' tangents differ (plus slack): next to a branch point a corrector
    can land on the crossing branch (e.g. the straight rod), whose test value
    says nothing about the root. A trial that fails or jumps is replaced by
    points ever closer to the converged ends. The root is interpolated
    linearly between the two converged bracket ends; the point is
    ``converged`` when the bracket is narrower than ``LOCATE_WIDTH``. Returns
    the point and the two ends of the final bracket.

    ``settled``: a function of the located point that returns the point to report instead (or None), asked
    each time the bracket is narrower than ``LOCATE_WIDTH``: the rest of the refinement (down to
    ``opts.locate_tol``) is not made once it answers (a branch point that is a fold, :func:`_fold_twin`).
    """
    fa, fb = a.tests[name], b.tests[name]
    br = _Bracket(0.0, b.s - a.s, fa, fb, fa, fb, a, b)
    failures = 0
    reason = ""
    for _ in range(100):
        if br.hi - br.lo <= opts.locate_tol:
            break
        sig = br.trial(failures)
        q = _trial_point(problem, br, a.s, sig, name, W, opts)
        if q is None:
            failures += 1
            if failures > _MAX_FAILURES:
                reason = (f"corrector failed or left the branch {failures} times; bracket width "
                          f"{br.hi - br.lo:.1e} > {LOCATE_WIDTH:.0e}")
                break
            continue
        failures = 0
        br.update(sig, q, q.tests[name])
        if br.lo == br.hi:
            break
        if settled is not None and br.hi - br.lo <= LOCATE_WIDTH:
            other = settled(_located(name, a, br, ""))
            if other is not None:
                return other, (br.plo, br.phi)
    return _located(name, a, br, reason), (br.plo, br.phi)


def _located(name: str, a: Point, br: _Bracket, reason: str) -> SpecialPoint:
    """The special point of a final bracket: root interpolated between its converged ends."""
    width = br.hi - br.lo
    t = br.f0lo / (br.f0lo - br.f0hi) if br.f0lo != br.f0hi else 0.5
    p_root = br.plo.p + t * (br.phi.p - br.plo.p)
    best = br.plo if abs(br.f0lo) <= abs(br.f0hi) else br.phi
    converged = width <= LOCATE_WIDTH
    if not converged and not reason:
        reason = f"bracket width {width:.1e} > {LOCATE_WIDTH:.0e} after the iteration limit"
    return SpecialPoint(name, best, -1, (a.s + br.lo, a.s + br.hi), float(best.tests[name]), float(p_root),
                        (float(br.plo.p), float(br.phi.p)), converged, reason)


def _clip_to_bounds(a: Point, ds: float, opts) -> tuple[float, float | None]:
    """Step from a, shortened so that the predictor does not cross a parameter bound
    (then also the bound it would reach)."""
    step, clipped = ds, None
    tp = float(a.tau[-1])
    for bound in (opts.p_max, opts.p_min):
        if tp != 0.0 and math.isfinite(bound) and (a.p + step * tp - bound) * (a.p - bound) < 0:
            step = (bound - a.p) / tp
            clipped = bound
    return step, clipped


def _place_on_bound(problem, a: Point, b: Point, step: float, W, opts) -> Point | None:
    """b moved back onto the parameter bound it overshot (None if that fails)."""
    bound = opts.p_max if b.p > opts.p_max else opts.p_min
    frac = (bound - a.p) / (b.p - a.p)
    try:
        u, p, rn, it, ok = correct(problem, a.u, a.p, a.tau, frac * step, W, opts.tol, opts.max_newton + 4)
        if ok:
            u, p, rn, it, ok = correct_at(problem, u, bound, opts.tol, opts.max_newton + 4)
    except ValueError:
        return None
    return _make_point(problem, u, p, a.tau, W, a.s + frac * step, rn, it, opts) if ok else None


def _advance(problem, a: Point, ds: float, W, opts, slow_ok: bool = False, curvature: np.ndarray | None = None
             ) -> tuple[Point | None, int, bool]:
    """One accepted step from a: (new point or None when rejected, Newton iterations,
    whether it lies on a parameter bound). ``slow_ok``: accept a step that took _SLOW or more Newton solves (the
    retry of one rejected for that: next to a branch point every step may be slow, and halving again would stall);
    ``curvature``: the branch's at a, for the predictor (:func:`correct`)."""
    step, clipped = _clip_to_bounds(a, ds, opts)
    try:
        u, p, rn, it, ok = correct(problem, a.u, a.p, a.tau, step, W, opts.tol, opts.max_newton, curvature)
        if ok and clipped is not None and abs(p - clipped) <= 0.1 * abs(step * float(a.tau[-1])):
            u, p, rn, it, ok = correct_at(problem, u, clipped, opts.tol, opts.max_newton + 4)
        else:
            clipped = None
    except ValueError:  # parameter left its admissible range
        return None, 0, False
    if not ok or (it >= _SLOW and not slow_ok and ds > opts.ds_min):
        return None, it, False
    b = _make_point(problem, u, p, a.tau, W, a.s + step, rn, it, opts)
    if _turn(a, b, W) > opts.max_angle and ds > opts.ds_min:
        return None, it, False
    if clipped is None and (b.p > opts.p_max or b.p < opts.p_min):
        placed = _place_on_bound(problem, a, b, step, W, opts)
        if placed is not None:
            return placed, it, True
    return b, it, clipped is not None


def _special_between(problem, a: Point, b: Point, index: int, W, opts) -> tuple[list, str]:
    """Special points located between consecutive points a and b (sign changes of their
    tests; folds first), and the first kind among them at which the continuation stops
    ("" if none)."""
    found, stop_kind, folds = [], "", []
    for name in sorted(a.tests, key=lambda k: k != "fold"):
        fa, fb = a.tests[name], b.tests.get(name)
        if fb is None or fa == 0.0 or (fa > 0) == (fb > 0):
            continue
        sp = _fold_twin(folds, name)
        if sp is None:
            twin = partial(_fold_twin, folds, name) if name == "bp" and folds else None
            lo, hi = _beside_fold(problem, a, b, folds, W, opts) if twin is not None else (a, b)
            sp, ends = _locate(problem, lo, hi, name, W, opts, settled=twin)
            if name == "fold" and sp.converged:
                folds.append((sp, ends))
            elif name == "bp":
                sp = _fold_twin(folds, name, sp) or sp
        found.append(replace(sp, index=index))
        if name in opts.stop_on and not stop_kind:
            stop_kind = name
    return found, stop_kind


def _beside_fold(problem, a: Point, b: Point, folds: list, W, opts) -> tuple[Point, Point]:
    """The bracket in which to locate a branch point whose test changes sign in the step a -> b in which a fold was
    located (a connecting branch ends so, at the pitchfork where it meets another branch).

    The fold's final bracket (lo, hi) does not contain the sign change (else the branch point is the fold,
    :func:`_fold_twin`), so it lies between a and lo or between hi and b. From the fold's end on that side, points
    1, 4, 13, 40, ... times ``LOCATE_WIDTH`` beyond it (each step three times the one before, from the point before,
    along its tangent: they stay on this branch) are corrected until the test changes sign; the bracket is the last
    two (or the last and a or b). Next to a branch point most trial points of a wide bracket land on the crossing
    branch, each rejected after up to 40 Newton solves (at the SET b12's end, omega = 0.25, the test is 1e-8 at the
    fold and changes sign 1.1e-6 from it): this bracket, grown from the fold, needs fewer trials than the step's.
    Returns (a, b) when no fold applies; when a point cannot be corrected, from the last one to a or b."""
    fa = a.tests["bp"]
    for _, (lo, hi) in folds:
        flo, fhi = lo.tests.get("bp"), hi.tests.get("bp")
        if not flo or not fhi or (flo > 0) != (fhi > 0):
            continue
        below = (fa > 0) != (flo > 0)  # the change lies between a and lo (else between hi and b)
        near, far = (lo, a) if below else (hi, b)
        side = -1.0 if below else 1.0
        width = LOCATE_WIDTH
        while abs(far.s - near.s) > 4.0 * width:
            q = _stepped(problem, near, side * width, "bp", 1.0, W, opts)
            if q is None:
                break
            if (q.tests["bp"] > 0) != (near.tests["bp"] > 0):
                return (q, near) if below else (near, q)
            near, width = q, 3.0 * width
        return (far, near) if below else (near, far)
    return a, b


def _fold_twin(folds: list, name: str, located: SpecialPoint | None = None) -> SpecialPoint | None:
    """The branch point as the fold it coincides with (None if it does not).

    A pitchfork reached along its bifurcating branch is a fold of that branch
    (the parameter is extremal there). Next to it the corrector of the
    determinant test keeps landing on the crossing branch and that test is
    nearly a step function, so its own bracket can end on two different
    branches (for the SET b1 met by its tension continuation: 3e-9 off in T,
    2e-8 in the straight tether's load, against 2e-11 from the fold). The fold
    test (the parameter component of the tangent) is smooth there. So a branch
    point found in the same step as a converged fold is that fold when the
    fold's final bracket also brackets the determinant's sign change (then it
    is not located at all) or, once located, when the two parameter values
    agree to twice the spread of the branch point's own parameter bracket; that is
    asked as soon as the branch point's bracket is narrower than ``LOCATE_WIDTH``
    (where it counts as located), and its refinement ends when the answer is yes.
    """
    if name != "bp":
        return None
    for f, (lo, hi) in folds:
        flo, fhi = lo.tests.get("bp"), hi.tests.get("bp")
        straddles = flo is not None and fhi is not None and (flo == 0.0 or fhi == 0.0 or (flo > 0) != (fhi > 0))
        spread = math.inf if located is None else abs(located.p_bracket[1] - located.p_bracket[0])
        near = located is not None and abs(f.p - located.p) <= 2.0 * spread + 1e-12
        if (located is None and straddles) or near:
            return replace(f, kind="bp", value=0.0)
    return None


#: Newton solves (as the plain test counts them, :func:`correct`) after which the next step grows; one more where
#: the tangent turned by less than ``max_angle`` / _STRAIGHT over the step; from _SHRINK on the next step is halved,
#: from _SLOW on the step is rejected (:func:`_advance`). The straight rule lets a nearly straight branch grow its
#: steps: on the SET connecting branch b12 at omega = 0.25 every step of 0.0225 converges in four solves while the
#: tangent turns by 0.007 rad (the same special points to 1e-9 with and without the rule). A step of eight solves
#: can have jumped to a neighbouring branch: b34 at omega = 0 (N = 28), measure1 0.044 -> 0.069, after a step of seven.
_FAST, _STRAIGHT, _SHRINK, _SLOW = 3, 6.0, 6, 7


def _next_step(ds: float, newton: int, turn: float, opts) -> float:
    """The step after one of length ds that took ``newton`` Newton solves and turned the tangent by ``turn``
    radians (W-norm): grown by half after fast convergence, halved after slow, else kept."""
    if newton <= _FAST or (newton == _FAST + 1 and turn < opts.max_angle / _STRAIGHT):
        return min(ds * 1.5, opts.ds_max)
    if newton >= _SHRINK:
        return max(ds * 0.5, opts.ds_min)
    return ds


def _curvature(pts: list) -> np.ndarray | None:
    """d tau / ds at the last accepted point, from the tangents of the last two (None for the first step). Assumes
    that the chart coordinates of two neighbouring points agree to first order: true in a vector space, and for
    rotations updated by left multiplication (their coordinates are space-frame angles, as the rod's)."""
    if len(pts) < 2 or pts[-1].s <= pts[-2].s:
        return None
    return (pts[-1].tau - pts[-2].tau) / (pts[-1].s - pts[-2].s)


def _turn(a: Point, b: Point, W: np.ndarray) -> float:
    """The angle between the tangents of a and b (W-norm, radians)."""
    return math.acos(max(-1.0, min(1.0, float(np.sum(W * a.tau * b.tau)))))


def continuation(problem, u0, p0: float, tau0: np.ndarray, opts: ContinuationOptions,
                 first_residual: float = 0.0) -> ContinuationResult:
    """Continue the solution branch through (u0, p0) (a solution) along tau0.

    tau0 (shape (m+1,)) gives the initial direction (it is replaced by the true
    tangent oriented like it). Returns every accepted point and the special
    points located between them, and why it stopped (:class:`StopReason`).
    """
    t_start = time.perf_counter()
    m = np.asarray(tau0).size - 1
    W = weights(m, opts)
    tau0 = np.asarray(tau0, dtype=float)
    tau0 = tau0 / math.sqrt(float(np.sum(W * tau0 * tau0)))
    pts = [_make_point(problem, u0, p0, tau0, W, 0.0, first_residual, 0, opts)]
    special: list[SpecialPoint] = []
    ds = abs(opts.ds)
    reason, kind = StopReason.MAX_POINTS, ""
    slow_ok = False  # the step is the retry of one rejected as slow
    while len(pts) < opts.max_points:
        a = pts[-1]
        b, it, on_bound = _advance(problem, a, ds, W, opts, slow_ok, _curvature(pts))
        if b is None:
            slow_ok = it >= _SLOW
            ds *= 0.5
            if ds < opts.ds_min:
                reason = StopReason.STEP_UNDERFLOW
                break
            continue
        slow_ok = False
        found, kind = _special_between(problem, a, b, len(pts) - 1, W, opts)
        special.extend(found)
        pts.append(b)
        stop = _stop_reason(b, on_bound, kind, opts)
        if stop is not None:
            reason = stop
            break
        ds = _next_step(ds, it, _turn(a, b, W), opts)
    return ContinuationResult(pts, special, reason, time.perf_counter() - t_start, kind)


def _stop_reason(b: Point, on_bound: bool, kind: str, opts) -> StopReason | None:
    if kind:
        return StopReason.SPECIAL_POINT
    if on_bound or b.p >= opts.p_max or b.p <= opts.p_min:
        return StopReason.PARAMETER_BOUND
    if opts.stop is not None and opts.stop(b.u, b.p):
        return StopReason.STOP_CONDITION
    return None


def switch_branch(problem, u_bp, p_bp: float, direction: np.ndarray, opts: ContinuationOptions,
                  amplitude: float | None = None) -> ContinuationResult:
    """Leave a branch point (u_bp, p_bp) along ``direction`` (shape (m+1,), chart
    coordinates plus parameter), e.g. (v, 0) for a pitchfork with kernel v.

    The first point is one corrected step of size ``amplitude`` (default
    opts.ds) along the direction; continuation then proceeds from it.
    """
    m = np.asarray(direction).size - 1
    W = weights(m, opts)
    d = np.asarray(direction, dtype=float)
    d = d / math.sqrt(float(np.sum(W * d * d)))
    ds = abs(amplitude if amplitude is not None else opts.ds)
    for _ in range(30):
        u, p, rn, it, ok = correct(problem, u_bp, p_bp, d, ds, W, opts.tol, opts.max_newton + 4)
        if ok:
            break
        ds *= 0.5
    else:
        return ContinuationResult([], [], StopReason.SWITCH_FAILED, 0.0)
    # tangent at the new point, oriented away from the branch point
    res = continuation(problem, u, p, d, opts, first_residual=rn)
    return res
