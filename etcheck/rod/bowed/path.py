"""The bowed tether's equilibrium path in the load B: pseudo-arclength continuation from the straight tether at
B = 0, its singular points (dimensionless, f-scaling).

The problem of :mod:`etcheck.rod.bowed.statics` (residual rows divided by
:func:`~etcheck.rod.bowed.statics.row_scale`, which moves no solution and no singular point) is continued in B
by :func:`etcheck.numerics.continuation.continuation`. Under a field across the chord the paper's pitchfork
(eq. (91)) is imperfect: the path leaves B = 0 bowed and is singular only at a fold (tau_B changes sign) or a
branch point of the path's static Jacobian. The continuation finds the points where det changes sign (folds and
simple branch points); an even crossing (the straight tether's double pitchforks, docs/model.md section 7) keeps
the sign, so the smallest singular value sigma of the Jacobian is followed too: each local minimum of sigma
along the path is refined by minimising sigma(B) between its neighbours (Brent, each state re-solved at fixed B)
and reported as a :class:`Dip`; a dip to round-off is a singular point (``kind`` "double"), a shallow one the
knee of the imperfect bifurcation (Southwell's picture).

With one current and the ends on the chord the load keeps a potential (docs/model.md, section 11): a singular
point of the path is where stability can change; with a current profile the load is circulatory and stability
is decided by the spectrum (:mod:`etcheck.rod.bowed.quantities`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from etcheck.errors import SolverError
from etcheck.numerics.continuation import ContinuationOptions, ContinuationResult, continuation
from etcheck.numerics.optimize import minimize_scalar
from etcheck.rod.bowed import statics
from etcheck.rod.bowed.field import CrossField
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.parameters import RodParameters

__all__ = ["KINK", "Dip", "SingularPoint", "BowedPath", "BowedProblem", "follow", "smallest_singular_value"]

#: A dip is a singular point when sigma there is below a hundredth of sigma at KINK times the location's tolerance
#: on either side: sigma has a kink at a zero (|B - B*| times its slope, so the ratio is ~1/KINK) and is flat at a
#: smooth minimum above zero (ratio ~1).
KINK = 1e4


class BowedProblem:
    """F(u, B) = 0 for :func:`etcheck.numerics.continuation.continuation`: the scaled residual of
    :mod:`etcheck.rod.bowed.statics` at the load B, its Jacobian and the load derivative."""

    def __init__(self, params: RodParameters, field: CrossField, N: int):
        statics.check_problem(params, int(N))
        self.params, self.field, self.N = params, field, int(N)
        self.scale = statics.row_scale(params, self.N)

    def at(self, B: float) -> RodParameters:
        return self.params.with_(B=float(B))

    def residual(self, u, p):
        return statics.residual(self.at(p), self.field, u) / self.scale

    def jacobian(self, u, p):
        pp = self.at(p)
        J = statics.jacobian(pp, self.field, u) / self.scale[:, None]
        return J, statics.load_derivative(pp, self.field, u) / self.scale

    def retract(self, u, du):
        return eq.retract(u, du, u.params)


def smallest_singular_value(problem: BowedProblem, state: eq.Equilibrium, B: float) -> float:
    """The smallest singular value of the scaled static Jacobian at (state, B)."""
    J, _ = problem.jacobian(state, B)
    return float(sla.svdvals(J, check_finite=False)[-1])


@dataclass(frozen=True, eq=False)
class Dip:
    """A local minimum of the smallest singular value along the path: the load ``B``, ``sigma`` (relative to
    sigma at B = 0), the state there; ``singular``: sigma has a kink there, a zero (:data:`KINK`)."""

    B: float
    sigma: float
    state: eq.Equilibrium
    singular: bool


@dataclass(frozen=True, eq=False)
class SingularPoint:
    """A singular point of the path: ``kind`` "fold", "bp" (det changes sign) or "double" (a dip of sigma to
    round-off), the load ``B`` and the state there."""

    kind: str
    B: float
    state: eq.Equilibrium


@dataclass(frozen=True, eq=False)
class BowedPath:
    """The continued path: ``loads`` B and ``states`` at the accepted points, ``sigma`` the smallest singular
    value of the scaled Jacobian at each (relative to B = 0), ``dips`` and ``singular`` points, why it stopped
    (``reason``), the raw continuation ``result``."""

    params: RodParameters
    field: CrossField
    N: int
    loads: np.ndarray
    states: tuple
    sigma: np.ndarray
    dips: tuple
    singular: tuple
    reason: str
    result: ContinuationResult


def _refine_dip(problem: BowedProblem, pts: list, i: int, sigma0: float) -> Dip:
    """Minimise sigma(B) between the neighbours of the accepted point i (a regular stretch of the path)."""
    lo, hi = sorted((pts[i - 1].p, pts[i + 1].p))
    near = {}

    def sig(B: float) -> float:
        start = min(pts[i - 1:i + 2], key=lambda q: abs(q.p - B)).u  # the nearest accepted state
        try:
            near[B] = statics.solve(problem.at(B), problem.field, start)
        except SolverError:
            return np.inf
        return smallest_singular_value(problem, near[B], B) / sigma0

    xatol = 1e-10 * max(1.0, hi)
    res = minimize_scalar(sig, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    B = float(res.x)
    value = sig(B)
    h = KINK * xatol
    beside = min(sig(B - h), sig(B + h))
    return Dip(B=B, sigma=value, state=near.get(B, pts[i].u), singular=value < 0.01 * beside)


def _dips(problem: BowedProblem, pts: list, sigma: np.ndarray, sigma0: float) -> list[Dip]:
    """The refined local minima of ``sigma`` (relative to ``sigma0``, its absolute value at B = 0)."""
    out = []
    for i in range(1, len(pts) - 1):
        monotone = pts[i - 1].tau[-1] * pts[i + 1].tau[-1] > 0  # no fold between the neighbours
        if sigma[i] < sigma[i - 1] and sigma[i] <= sigma[i + 1] and monotone:
            out.append(_refine_dip(problem, pts, i, sigma0))
    return out


def follow(params: RodParameters, field: CrossField, B_max: float, N: int = 24, ds: float = 0.02,
           step: float = 0.02, max_points: int = 400) -> BowedPath:
    """Continue the equilibrium from the straight tether at B = 0 (end tension ``params.T``) up to ``B_max``.

    Returns the :class:`BowedPath` with its dips and singular points (module docstring). ``ds`` is the first
    arclength step (the continuation's weighted norm), ``step`` B_max the longest: the dips of sigma near an
    imperfect pitchfork are as narrow as the imperfection, and a longer step can stride over one."""
    problem = BowedProblem(params, field, N)
    start = eq.straight_state(params.with_(B=0.0), N)
    tau0 = np.zeros(12 * (N + 1) + 1)
    tau0[-1] = 1.0
    opts = ContinuationOptions(ds=ds, ds_max=max(ds, step * B_max), p_min=-1e-12, p_max=B_max,
                               max_points=max_points, tol=1e-10)
    result = continuation(problem, start, 0.0, tau0, opts)
    pts = result.points
    sigma_abs = np.array([smallest_singular_value(problem, q.u, q.p) for q in pts])
    sigma = sigma_abs / sigma_abs[0]
    dips = _dips(problem, pts, sigma, float(sigma_abs[0]))
    singular = [SingularPoint(sp.kind, float(sp.p), sp.point.u) for sp in result.special]
    singular += [SingularPoint("double", d.B, d.state) for d in dips if d.singular
                 and not any(abs(d.B - s.B) <= 1e-6 * max(1.0, d.B) for s in singular)]
    singular.sort(key=lambda s: s.B)
    return BowedPath(params=params, field=field, N=N, loads=result.p, states=tuple(q.u for q in pts),
                     sigma=sigma, dips=tuple(dips), singular=tuple(singular), reason=result.description,
                     result=result)
