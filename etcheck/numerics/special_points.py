"""Special points of a continuation (generic, dimensionless): folds, branch points and user tests located as
bracketed roots of their test functions between two accepted points (Illinois on the arclength, each trial
corrected onto the branch), and a branch point that is a fold reported as that fold. The method is described
in :mod:`etcheck.numerics.continuation`."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from etcheck.numerics.corrector import Point, correct, make_point


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
#: failed or jumped trials after which :func:`locate` gives up
_MAX_FAILURES = 12


@dataclass
class _Bracket:
    """The current bracket of :func:`locate`: arclength ends (from a), Illinois values,
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


def trial_point(problem, br: _Bracket, s_a: float, sig: float, name: str, W, opts) -> Point | None:
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
    q = make_point(problem, u, p, base.tau, W, base.s + step, rn, it, opts)
    if float(np.sum(W * base.tau * q.tau)) < min(cos_end, math.cos(opts.max_angle)) - 0.2 or name not in q.tests:
        return None
    return q


def locate(problem, a: Point, b: Point, name: str, W, opts, settled=None
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
        q = trial_point(problem, br, a.s, sig, name, W, opts)
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


def special_between(problem, a: Point, b: Point, index: int, W, opts) -> tuple[list, str]:
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
            lo, hi = beside_fold(problem, a, b, folds, W, opts) if twin is not None else (a, b)
            sp, ends = locate(problem, lo, hi, name, W, opts, settled=twin)
            if name == "fold" and sp.converged:
                folds.append((sp, ends))
            elif name == "bp":
                sp = _fold_twin(folds, name, sp) or sp
        found.append(replace(sp, index=index))
        if name in opts.stop_on and not stop_kind:
            stop_kind = name
    return found, stop_kind


def beside_fold(problem, a: Point, b: Point, folds: list, W, opts) -> tuple[Point, Point]:
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
