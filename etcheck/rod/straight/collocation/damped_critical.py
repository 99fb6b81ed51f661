"""Critical load and critical spin of the *damped* straight rod from static pencils alone.

Dimensionless (scalings of eq. (36) of arXiv:0810.3668). With Kelvin-Voigt damping
gamma > 0 the linearisation about the straight rod has the form
M q'' + (G + gamma D) q' + K q = 0 with M > 0, G skew (Coriolis), D > 0
(complete: it is the bending/torsion stiffness) and K symmetric; by the
Kelvin-Tait-Chetaev theorem the number of unstable eigenvalues equals the
number of negative eigenvalues of K (docs/model.md, section 8,
"Why the paper's Hopf results are in doubt"). K is the lambda = 0 operator A0, affine in B, omega^2 and T
(:class:`~etcheck.rod.straight.collocation.spectral.StraightFamily`), so along any of those axes
stability changes only where A0 is singular: at the real roots of a linear
pencil. With K positive definite at B = omega = 0 (T above the first
compressive load), the straight rod is stable exactly while

    omega < omega_c0(T)          (first omega root at B = 0)  and
    B     < B_c(omega, T)        (first B root at the operating spin),

and the critical spin at the operating load is the first omega root at
(B, T) when B < B_c(0, T). No eigenvalue scan and no bisection: each value
is one small pencil per resolution (``StraightFamily.pencil_roots``), located
exactly (to the discretisation error, which the two-resolution agreement
estimates). This is what makes
parametric sweeps cheap; :mod:`etcheck.rod.straight.collocation.spectral` is the general
(also undamped) scan that it must agree with, and a test checks it does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import check_resolution, roundoff_floor
from etcheck.rod.straight.analytic import critical_loads, static_roots
from etcheck.rod.straight.collocation.spectral import DOUBLE, family_bytes, straight_family
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import fits

__all__ = [
    "DRAFT_LADDER",
    "LADDER",
    "critical_from_roots",
    "damped_critical",
    "DampedCritical",
    "first_root",
    "PencilRoot",
]

#: Chebyshev resolutions tried in turn until two resolutions agree.
LADDER = (16, 24, 32, 48, 64, 96, 128)
#: The ladder of a draft (tolerance 1e-6): one coarser rung first, N = 12 checked at 20 (its pencils cost
#: half those of 16 and 24), where the scene's roots have converged that far.
DRAFT_LADDER = (12, *LADDER)
#: Below this two-resolution disagreement an error that no longer falls by a factor 3 from one rung of
#: the ladder to the next is round-off (e.g. a load root near the unloaded critical spin, where it falls
#: like a square root): the ladder stops there and reports the root with that estimate, unconverged.
_STALL_BELOW = 1e-6


@dataclass(frozen=True)
class PencilRoot:
    """The smallest positive root of the static pencil along one axis (dimensionless).

    ``value`` is B, T or omega (not omega^2); inf when the pencil has no
    positive root; ``error`` the relative two-resolution disagreement;
    ``N`` the resolution that met the tolerance (or the last one tried).
    ``model`` says whether it came from the chi roots (rung 0) or the pencil.
    """

    axis: str
    value: float
    error: float
    N: int
    converged: bool
    model: str


def _smallest_positive(params: RodParameters, axis: str, N: int, sign: float = 1.0) -> float:
    r = straight_family(params, N).pencil_roots(axis, params.B, params.omega, params.T)
    r = np.abs(r[sign * r > 0])
    if not r.size:
        return math.inf
    root = float(np.min(r))
    if params.R == 1.0:  # a double root: the mean of its split pair is accurate to round-off, either one to sqrt(eps)
        root = float(np.mean(r[r <= root * (1.0 + DOUBLE)]))
    return math.sqrt(root) if axis == "omega" else root


def first_root(params: RodParameters, axis: str, tol: float = 1e-8, sign: float = 1.0,
               ladder: tuple[int, ...] = LADDER, floor: float = 0.0) -> PencilRoot:
    """Smallest root of A0 on ``axis`` ("B", "omega", "T", "ray") on the side ``sign``.

    The other parameters are fixed at ``params``; the axis value in params is
    ignored (the pencil is A0 at axis = 0 plus axis times its derivative).
    "ray" scales load and spin squared together: the root t has A0(t B,
    sqrt(t) omega, T) singular, so with damping the rod is stable iff t > 1.
    At omega = T = 0 the B root is beta_1^3 sqrt(R) / f from chi (rung 0; its closed form for other ends).
    The error is relative to max(|root|, floor): a root that tends to zero
    (a critical load as the spin nears the critical spin of the unloaded rod)
    is converged when it is small against ``floor``. Memoised: in a sweep
    the roots at zero spin or zero load are shared by many points.
    """
    if axis != "ray":
        params = params.with_(**{axis: 0.0})
    return _first_root(params, axis, tol, sign, tuple(ladder), floor)


@lru_cache(maxsize=512)
def _first_root(params: RodParameters, axis: str, tol: float, sign: float, ladder: tuple[int, ...],
                floor: float) -> PencilRoot:
    if axis == "ray" and params.omega == 0 and params.B > 0:
        load = _first_root(params.with_(B=0.0), "B", tol, sign, ladder, floor)
        return PencilRoot("ray", load.value / params.B, load.error, load.N, load.converged, load.model)
    if axis == "B" and sign > 0 and params.omega == 0 and params.T == 0:
        root = static_roots(params.ends, 1)[0]
        return PencilRoot("B", float(critical_loads(params.R, params.f, 1, params.ends)[0]), 3.0 * root.error, 0,
                          True, "rung 0 (chi roots)" if params.ends.is_welded else "rung 0 (closed form)")
    # the ladder ends at the finest rung whose families fit the memory budget (the first one is always tried)
    fitting = [n for n in ladder if fits(family_bytes(check_resolution(n)))] or list(ladder[:1])
    model = "rung 1 (static pencil)" if len(fitting) == len(ladder) else \
        f"rung 1 (static pencil; N = {fitting[-1]} is the finest resolution within the memory budget)"
    err, value, N = math.inf, math.nan, ladder[0]
    for N in fitting:
        a = _smallest_positive(params, axis, N, sign)
        b = _smallest_positive(params, axis, check_resolution(N), sign)
        if math.isinf(a) and math.isinf(b):
            return PencilRoot(axis, math.inf, 0.0, N, True, model)
        value, last = b, err
        err = abs(a - b) / max(abs(b), floor, 1e-300) if math.isfinite(a) and math.isfinite(b) else math.inf
        if err <= tol or (err < _STALL_BELOW and err > 0.3 * last):
            break  # met, or stalled at round-off: finer grids would not improve it (an ill-conditioned root)
    return PencilRoot(axis, sign * value, err, N, err <= tol, model if err > tol else "rung 1 (static pencil)")


@dataclass(frozen=True)
class DampedCritical:
    """Stability of the damped straight rod at one operating point (dimensionless).

    ``critical_load``: first B at the operating omega and T (0 when the rod
    is already unstable at B = 0); ``critical_spin``: first omega at the
    operating B and T (0 when statically buckled), both with their errors
    relative to their values (judged against the tolerance relative to 1 %
    of the load at rest or of the spin at rest, whichever is larger: see
    :func:`first_root`); ``stable``: the operating point itself;
    ``spin_at_rest``: first omega at B = 0 (above it the unloaded rod
    whirls, and no load is safe).
    """

    critical_load: PencilRoot
    critical_spin: PencilRoot
    spin_at_rest: PencilRoot
    stable: bool
    converged: bool
    message: str


@single_blas_thread
def damped_critical(params: RodParameters, tol: float = 1e-8, ladder: tuple[int, ...] = LADDER,
                    spin: bool = True) -> DampedCritical:
    """Critical load, critical spin and stability of the damped straight rod.

    Requires gamma > 0 (Kelvin-Tait-Chetaev; undamped rods can flutter and
    need :func:`etcheck.rod.straight.collocation.spectral.critical_load`). Exact pencil roots,
    see the module docstring. Errors are relative to the root or to 1 % of
    its value at zero spin (load) or zero load (spin), whichever is larger.
    ``spin=False`` skips the critical spin at the operating load (NaN).
    """
    if not params.gamma > 0:
        raise ValueError("damped_critical needs gamma > 0 (Kelvin-Tait-Chetaev); use the spectral scan")

    def root(p, axis, tol, sign=1.0, floor=0.0):
        return first_root(p, axis, tol, sign=sign, ladder=ladder, floor=floor)

    return critical_from_roots(params, tol, spin, root)


def critical_from_roots(params: RodParameters, tol: float, spin: bool, root) -> DampedCritical:
    """The damped straight rod's critical values from a first-root finder (dimensionless).

    ``root(params, axis, tol, sign=1.0, floor=0.0) -> PencilRoot`` is the
    smallest root of the static operator on ``axis`` (this module's pencils,
    or the exact determinant of :mod:`etcheck.rod.straight.exact.roots`): one
    orchestration for both routes (compressive limit, spin at rest, static
    load, load at the operating spin, spin at the operating load).
    """
    p = params
    if p.T < 0:
        comp = root(p.with_(B=0.0, omega=0.0), "T", tol, sign=-1.0)
        if not comp.converged:
            return _failed(comp, "the compressive limit did not converge")
        if p.T <= comp.value:
            zero = PencilRoot("B", 0.0, 0.0, comp.N, True, comp.model)
            return DampedCritical(zero, PencilRoot("omega", 0.0, 0.0, comp.N, True, comp.model), zero, False, True,
                                  f"the end compression exceeds the Euler limit T = {comp.value:.6g}")
    rest = root(p.with_(B=0.0), "omega", tol)  # spin that destabilises the unloaded rod
    if math.isnan(rest.value):
        return _failed(rest, "the critical spin of the unloaded rod was not found")
    static = root(p.with_(omega=0.0), "B", tol)
    if math.isnan(static.value):
        return _failed(static, "the static critical load was not found")
    if p.omega == 0:
        load = static
    elif p.omega >= rest.value:
        load = PencilRoot("B", 0.0, 0.0, rest.N, True, rest.model)
    else:
        load = _near_end(root(p, "B", tol, floor=_floor(static)), rest.value**2, p.omega**2, _floor(static), tol)
    if not spin:
        crit = PencilRoot("omega", math.nan, math.nan, 0, True, "not asked")
    elif p.B >= static.value:
        crit = PencilRoot("omega", 0.0, 0.0, static.N, True, static.model)
    else:
        crit = _near_end(root(p, "omega", tol, floor=_floor(rest)), static.value, p.B, _floor(rest), tol)
    load = _relative_to_value(load, _floor(static))
    crit = _relative_to_value(crit, _floor(rest))
    # a root that missed tol (round-off of an ill-conditioned root) is still returned with its estimate:
    # the caller decides whether it is good enough to report
    converged = load.converged and crit.converged and rest.converged and static.converged
    stable = p.omega < rest.value and p.B < load.value
    msg = "converged" if converged else "; ".join(
        f"{what} not converged{_at(r)} (error estimate {r.error:.1e} > {tol:.0e})"
        for what, r in (("the critical load", load), ("the critical spin", crit), ("the critical spin at rest", rest),
                        ("the static critical load", static)) if not r.converged)
    return DampedCritical(load, crit, rest, bool(stable), converged, msg)


#: Relative round-off of the exact determinant's roots, and the least of the static pencil's, as measured
#: against independent solvers on the scenes of the tests: 1e-14 .. 1e-13. A pencil's grows with its resolution
#: as an eigenvalue's does (:func:`~etcheck.rod.core.spectrum.roundoff_floor`, 32 N^2 eps: 1.6e-11 at N = 48).
_ROUND_OFF = 1e-13


def _near_end(r: PencilRoot, end: float, at: float, floor: float, tol: float) -> PencilRoot:
    """The error of a root that vanishes like a square root at the end of its line, bounded below by
    its round-off.

    The load root at spin omega falls like sqrt(omega_c0^2 - omega^2) as omega nears the unloaded rod's
    critical spin omega_c0 (the static points are symmetric in B), and the spin root at load B like
    sqrt(B_c0 - B): a relative round-off eta of the operator moves the root by eta end / (2 (end - at))
    relative, which two resolutions, each at round-off, need not show. eta is that of the resolution the value
    came from (the pair's finer one; the exact determinant's for N = 0): SET 8e-6 below its static load, the
    spin root at N = 48 was 2.8e-7 off, against 1.1e-7 stated with eta = 1e-13 there. ``end``, ``at``:
    omega_c0^2 and omega^2, or B_c0 and B; the error stays relative to max(value, floor) (see :func:`first_root`).
    """
    if not (0 < r.value < math.inf) or end <= at:
        return r
    eta = max(_ROUND_OFF, roundoff_floor(check_resolution(r.N))) if r.N else _ROUND_OFF
    rounding = eta * end / (2.0 * (end - at)) * r.value / max(r.value, floor)
    if rounding <= r.error:
        return r
    return PencilRoot(r.axis, r.value, rounding, r.N, r.converged and rounding <= tol, r.model)


def _floor(end: PencilRoot) -> float:
    """1 % of the root at the end of a line (zero load or zero spin), the floor its errors are judged relative to;
    0 (relative to the root itself) where that end has no root (e.g. no spin destabilises the unloaded taut rod)."""
    return 1e-2 * end.value if math.isfinite(end.value) else 0.0


def _relative_to_value(r: PencilRoot, floor: float) -> PencilRoot:
    """The root with its error relative to its value (it was judged relative to max(value, floor)), as
    the margins need it: a root far below the floor has an error far above the one it was judged by."""
    if not (0 < r.value < math.inf) or r.value >= floor or not math.isfinite(r.error):
        return r
    return replace(r, error=r.error * floor / r.value)


def _at(root: PencilRoot) -> str:
    return f" at N = {root.N}" if root.N else ""


def _failed(root: PencilRoot, why: str) -> DampedCritical:
    nan = PencilRoot(root.axis, math.nan, root.error, root.N, False, root.model)
    return DampedCritical(nan, nan, root, False, False, f"{why}{_at(root)} (error estimate {root.error:.1e})")
