"""The pseudo-arclength corrector of :mod:`etcheck.numerics.continuation` (generic, dimensionless): the
options of a continuation, its accepted points, the unit tangent with the branch-point test, Newton along the
arclength (:func:`correct`) and at a fixed parameter (:func:`correct_at`), and the test function
:func:`signed_smallness`. The method is described in :mod:`etcheck.numerics.continuation`."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla


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


def weights(m: int, opts: ContinuationOptions) -> np.ndarray:
    w = np.full(m + 1, (1.0 - opts.weight_p) / m)
    w[-1] = opts.weight_p
    return w


def bordered(Ju: np.ndarray, Jp: np.ndarray, row: np.ndarray) -> np.ndarray:
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


def tangent(problem, u, p, tau0: np.ndarray, W: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(tau, Ju, Jp, bp) at (u, p): the unit tangent tau (in the W-norm) oriented like tau0, the Jacobians, and the
    branch-point test bp, :func:`signed_smallness` of [[Ju, Jp], [tau]], from the LU of the tangent's bordered
    matrix A = [[Ju, Jp], [W tau0]] (the two differ in their last row only: the determinant changes by the factor
    1 + (tau - W tau0) . t, t = A^{-1} e_last, and the solve by Sherman-Morrison)."""
    Ju, Jp = problem.jacobian(u, p)
    A = bordered(Ju, Jp, W * tau0)
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
QUADRATIC = 10.0


def _settled(step: float, last: float, tol: float) -> bool:
    """Whether Newton converges quadratically enough that the update of size ``step`` just made (after one of
    size ``last``) is the last one the plain test (an update below ``tol``) needs: the next update, ~ step^2 /
    last^2 * step, below a tenth of the tolerance, and the update itself below QUADRATIC sqrt(tol) (the
    asymptotic regime). Never after the first update (``last`` infinite: no rate to go by)."""
    return math.isfinite(last) and step < QUADRATIC * math.sqrt(tol) and step < last and step**3 / last**2 < 0.1 * tol


def _exit(problem, u, p: float, it: int, step: float, last: float, tol: float,
          small: bool) -> tuple[float, int, bool] | None:
    """(residual norm, iterations, converged) where Newton stops after iteration ``it`` (an update of size
    ``step`` after one of ``last``), else None: on the plain test (``small``), the residual at the result decides;
    on the quadratic exit (:func:`_settled`), only a residual below ``tol`` stops it, and the count returned is
    the one the plain test would have reached, one more (the step control, next_step, reads the same numbers)."""
    if small:
        rn = float(np.max(np.abs(problem.residual(u, p))))
        return rn, it, rn < tol
    if _settled(step, last, tol):
        rn = float(np.max(np.abs(problem.residual(u, p))))
        if rn < tol:
            return rn, it + 1, True
    return None


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
            d = np.linalg.solve(bordered(Ju, Jp, row), -np.append(r, g))
        except (np.linalg.LinAlgError, ValueError):
            return u, p, math.inf, it, False
        if not np.all(np.isfinite(d)):
            return u, p, math.inf, it, False
        u = problem.retract(u, d[:m])
        xi = xi + d[:m]
        p = p + float(d[m])
        step = float(np.max(np.abs(d)))
        rn = float(np.max(np.abs(r)))
        done = _exit(problem, u, p, it, step, last, tol, step < tol and rn < 1e2 * tol)
        if done:
            return (u, p, *done)
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
        done = _exit(problem, u, p, it, step, last, tol, step < tol)
        if done:
            return (u, p, *done)
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


def make_point(problem, u, p, tau_prev, W, s, residual, newton, opts) -> Point:
    tau, Ju, Jp, bp = tangent(problem, u, p, tau_prev, W)
    tests = {}
    if opts.detect_bp:
        tests["bp"] = bp
    if opts.detect_folds:
        tests["fold"] = float(tau[-1])
    extra = getattr(problem, "tests", None)
    if extra is not None:
        tests.update(extra(u, p, Ju))
    return Point(u, float(p), tau, residual, newton, s, tests)
