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

Three modules: this one follows a branch (step control, parameter bounds, stopping, branch switching); the
corrector, the tangent and the options are in :mod:`etcheck.numerics.corrector`; the location of special
points between two accepted points in :mod:`etcheck.numerics.special_points`. The names a caller needs are
importable from here.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from etcheck.numerics.corrector import (
    ContinuationOptions,
    Point,
    correct,
    correct_at,
    make_point,
    signed_smallness,
    weights,
)
from etcheck.numerics.special_points import LOCATE_WIDTH, SpecialPoint, illinois_update, special_between

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
    "illinois_update",
    "weights",
    "LOCATE_WIDTH",
]


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
    return make_point(problem, u, p, a.tau, W, a.s + frac * step, rn, it, opts) if ok else None


def advance(problem, a: Point, ds: float, W, opts, slow_ok: bool = False, curvature: np.ndarray | None = None
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
    b = make_point(problem, u, p, a.tau, W, a.s + step, rn, it, opts)
    if _turn(a, b, W) > opts.max_angle and ds > opts.ds_min:
        return None, it, False
    if clipped is None and (b.p > opts.p_max or b.p < opts.p_min):
        placed = _place_on_bound(problem, a, b, step, W, opts)
        if placed is not None:
            return placed, it, True
    return b, it, clipped is not None


#: Newton solves (as the plain test counts them, :func:`correct`) after which the next step grows; one more where
#: the tangent turned by less than ``max_angle`` / _STRAIGHT over the step; from _SHRINK on the next step is halved,
#: from _SLOW on the step is rejected (:func:`advance`). The straight rule lets a nearly straight branch grow its
#: steps: on the SET connecting branch b12 at omega = 0.25 every step of 0.0225 converges in four solves while the
#: tangent turns by 0.007 rad (the same special points to 1e-9 with and without the rule). A step of eight solves
#: can have jumped to a neighbouring branch: b34 at omega = 0 (N = 28), measure1 0.044 -> 0.069, after a step of seven.
_FAST, _STRAIGHT, _SHRINK, _SLOW = 3, 6.0, 6, 7


def next_step(ds: float, newton: int, turn: float, opts) -> float:
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
    pts = [make_point(problem, u0, p0, tau0, W, 0.0, first_residual, 0, opts)]
    special: list[SpecialPoint] = []
    ds = abs(opts.ds)
    reason, kind = StopReason.MAX_POINTS, ""
    slow_ok = False  # the step is the retry of one rejected as slow
    while len(pts) < opts.max_points:
        a = pts[-1]
        b, it, on_bound = advance(problem, a, ds, W, opts, slow_ok, _curvature(pts))
        if b is None:
            slow_ok = it >= _SLOW
            ds *= 0.5
            if ds < opts.ds_min:
                reason = StopReason.STEP_UNDERFLOW
                break
            continue
        slow_ok = False
        found, kind = special_between(problem, a, b, len(pts) - 1, W, opts)
        special.extend(found)
        pts.append(b)
        stop = _stop_reason(b, on_bound, kind, opts)
        if stop is not None:
            reason = stop
            break
        ds = next_step(ds, it, _turn(a, b, W), opts)
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
