"""Branches of whirling relative equilibria: start, continue, switch (dimensionless).

Rod-specific layer over :mod:`etcheck.numerics.continuation` and
:mod:`etcheck.rod.buckled.equilibria` (Secs. V A and VII of arXiv:0810.3668; docs/model.md, section 7, "Symmetry
of the welded problem").

The symmetries are :mod:`etcheck.rod.buckled.symmetry`; the straight rod's pitchforks and lift-off spins
:mod:`etcheck.rod.buckled.pitchforks`.

Labels. "b1" is the Fix(S1) branch from BP1 (x(s) = x(1-s), y(s) = -y(1-s)),
whose pitchfork load decreases with spin and reaches B = 0 at the spin where
the weak-axis whirl mode goes static (omega -> sqrt(R) for P -> 0); "b2" is
the Fix(S2) branch from BP1 (x odd, y even about s = 1/2; stiff-axis mode,
lift-off at omega -> 1 for P -> 0). This matches the paper's b1 (B = 0.595 at
measure_1 = 0.04, stable up to the secondary pitchfork, first to lift off).
For k >= 2 the same rule is used: b(2k-1) is the Fix(S1) branch from BP_k
and b(2k) the Fix(S2) one. This agrees with the paper's statement that the
connecting branch (b12, b34, ...) comes out of a secondary pitchfork on the
first branch of the pair: on the SET data b3 (Fix(S1)) carries one at
B = 13.46 and b4 has none below B = 28 (inferred; the paper's figures are not
available).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.numerics.continuation import (
    ContinuationOptions,
    ContinuationResult,
    SpecialPoint,
    continuation,
    correct,
    correct_at,
    illinois_update,
    signed_smallness,
    switch_branch,
    weights,
)
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.buckled.pitchforks import real_roots, straight_pencil
from etcheck.rod.buckled.symmetry import symmetry_bases, symmetry_class
from etcheck.rod.core.linear import NFIELDS
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import check_resolution
from etcheck.runtime.blas import single_blas_thread

__all__ = [
    "Branch",
    "BranchStart",
    "class_starts",
    "connecting_branch",
    "continue_branch",
    "locate",
    "primary_branches",
    "resolution_check",
    "ResolutionCheck",
    "RodBranchPoint",
    "state_at",
    "trivial_branch_points",
]


# --- continuation problems -------------------------------------------------------------


class _RodProblem:
    """F(u, p) = 0 for the equilibrium BVP in one parameter, optionally restricted to Fix(S)."""

    def __init__(self, params: RodParameters, parameter: str, N: int, which: str | None = None):
        if parameter not in eq.PARAMETERS:
            raise ValueError(f"parameter must be one of {eq.PARAMETERS}, got {parameter!r}")
        self.params, self.parameter, self.N = params, parameter, int(N)
        self.which = None if which is None else symmetry_class(which)
        self.bases = None if which is None else symmetry_bases(params, N, which)
        self._last = None

    def at(self, p: float) -> RodParameters:
        return self.params.with_(**{self.parameter: float(p)})

    def _full(self, u, p):
        key = (id(u), p)
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        pp = self.at(p)
        J = eq.jacobian(pp, u)
        Jp = eq.parameter_derivative(pp, u, self.parameter)
        self._last = (key, (J, Jp), u)
        return J, Jp

    def residual(self, u, p):
        r = eq.residual(self.at(p), u)
        return r if self.bases is None else self.bases.L_plus @ r

    def jacobian(self, u, p):
        J, Jp = self._full(u, p)
        if self.bases is None:
            return J, Jp
        b = self.bases
        return b.L_plus @ J @ b.V_plus, b.L_plus @ Jp

    def retract(self, u, du):
        full = du if self.bases is None else self.bases.V_plus @ du
        return eq.retract(u, full, u.params)

    def tests(self, u, p, Ju):
        # R = 1: rotations about e3 are a continuous symmetry whose generator lies in the antisymmetric space,
        # so the restricted antisymmetric Jacobian is singular at every buckled state: no break test there
        if self.bases is None or self.at(p).R == 1.0:
            return {}
        J, _ = self._full(u, p)
        b = self.bases
        return {"break": signed_smallness(b.L_minus @ J @ b.V_minus)}


# --- results -----------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class BranchStart:
    """A pitchfork of the straight rod inside one symmetry class (dimensionless).

    ``load``: B_k in that class at the given omega, T (the generalised
    eigenvalue of the restricted pencil, exact at resolution N); ``kernel``:
    restricted kernel vector (unit 2-norm); ``direction``: the same in full
    update coordinates; ``singular_values``: the two smallest singular values
    of the full A0(B_k) (both ~0 at omega = T = 0: the double pitchfork).
    """

    name: str
    which: str
    k: int
    params: RodParameters
    N: int
    load: float
    kernel: np.ndarray
    direction: np.ndarray
    singular_values: tuple


@dataclass(frozen=True, eq=False)
class RodBranchPoint:
    """A special point on a branch: kind ("fold", "bp", "break" = symmetry-breaking
    branch point), parameter value (the bracketed root of its test function,
    :class:`~etcheck.numerics.continuation.SpecialPoint`), bracket in the
    parameter (the converged branch points on either side of the root), the
    state there (the nearer bracket end) and its measure_1; ``converged``:
    the bracket shrank to ``LOCATE_WIDTH`` in arclength (else ``reason``)."""

    kind: str
    value: float
    bracket: tuple
    state: eq.Equilibrium
    measure1: float
    raw: SpecialPoint
    converged: bool = True
    reason: str = ""


@dataclass(frozen=True, eq=False)
class Branch:
    """A continued branch of relative equilibria (dimensionless).

    ``values``: the continuation parameter ``parameter`` at each point;
    ``measure1``, ``measure2``, ``max_deflection``: measures (paper captions of
    Figs. 5 and 6); ``states``: the
    :class:`~etcheck.rod.buckled.equilibria.Equilibrium` at each point; ``special``:
    folds and branch points located on it; ``time``: wall seconds; ``N``:
    resolution; ``which``: symmetry class it was restricted to (None: full
    space); ``residual``: largest residual max-norm over the points.
    """

    name: str
    parameter: str
    params: RodParameters
    N: int
    which: str | None
    values: np.ndarray
    measure1: np.ndarray
    measure2: np.ndarray
    max_deflection: np.ndarray
    states: tuple
    special: tuple
    time: float
    reason: str
    residual: float
    result: ContinuationResult
    problem: object

    def summary(self) -> dict:
        """Plain, JSON-serialisable data of the branch (no states)."""
        return _summary(self)


def _summary(branch: Branch) -> dict:
    return {
        "name": branch.name, "parameter": branch.parameter, "N": branch.N, "symmetry": branch.which,
        "values": branch.values.tolist(), "measure1": branch.measure1.tolist(),
        "measure2": branch.measure2.tolist(), "max_deflection": branch.max_deflection.tolist(),
        "special": [{"kind": q.kind, "value": q.value, "bracket": list(q.bracket), "measure1": q.measure1,
                     "converged": q.converged, "reason": q.reason} for q in branch.special],
        "time": branch.time, "reason": branch.reason, "residual": branch.residual,
    }


def _stamp(problem: _RodProblem, pt) -> eq.Equilibrium:
    """The point's state carrying its own parameters and residual."""
    u = pt.u
    return eq.Equilibrium(problem.at(pt.p), u.x, u.D, u.F, u.M, float(pt.residual), int(pt.newton),
                          bool(pt.residual < 1e-9))


def _branch(name, problem: _RodProblem, res: ContinuationResult) -> Branch:
    states = tuple(_stamp(problem, pt) for pt in res.points)
    ms = [eq.measures(s) for s in states]
    special = []
    for sp in res.special:
        st = _stamp(problem, sp.point)
        special.append(RodBranchPoint(sp.kind, sp.p, tuple(sorted(sp.p_bracket)), st, eq.measure1(st), sp,
                                      sp.converged, sp.reason))
    return Branch(
        name=name, parameter=problem.parameter, params=problem.params, N=problem.N, which=problem.which,
        values=res.p, measure1=np.array([m.measure1 for m in ms]), measure2=np.array([m.measure2 for m in ms]),
        max_deflection=np.array([m.max_deflection for m in ms]), states=states, special=tuple(special),
        time=res.time, reason=res.description,
        residual=max((pt.residual for pt in res.points), default=math.nan), result=res, problem=problem,
    )


@single_blas_thread
def primary_branches(params: RodParameters, k: int = 1, N: int = 40) -> tuple[BranchStart, BranchStart]:
    """The two branch starts at the k-th pitchfork of the straight rod (dimensionless).

    One in Fix(S1) and one in Fix(S2) ("b1" and "b2" for k = 1: the first
    pitchfork of each class; past a branch's lift-off spin, see
    :func:`liftoff_spin`, the first pitchfork of its class belongs to a
    higher branch); each with its
    exact load at resolution N (restricted pencil), restricted kernel and full
    kernel direction. At omega = T = 0 both loads equal beta_k^3 sqrt(R)/f
    (eq. (91)); spin or tension (R != 1) splits them.
    """
    return class_starts(params, "S1", (k,), N)[0], class_starts(params, "S2", (k,), N)[0]


@single_blas_thread
def class_starts(params: RodParameters, which: str, ks: tuple[int, ...], N: int = 40) -> tuple[BranchStart, ...]:
    """The branch starts at the k-th pitchforks (k in ``ks``) of the straight rod inside one symmetry class
    (as :func:`primary_branches`; one restricted pencil for all of them). Dimensionless."""
    which = symmetry_class(which)
    A, C, b = straight_pencil(params, N, which, "B")
    roots = real_roots(A, C)
    roots = roots[roots > 1e-12]
    out = []
    for k in ks:
        if roots.size < k:
            raise ValueError(f"class {which} has only {roots.size} pitchforks with B > 0 at {params}")
        Bk = float(roots[k - 1])
        _, sv, vh = np.linalg.svd(A + Bk * C)
        c = vh[-1]
        v = b.V_plus @ c
        n1 = N + 1
        xy = v[: 2 * n1]
        if xy[np.argmax(np.abs(xy))] < 0:
            c, v = -c, -v
        pk = params.with_(B=Bk)
        full = np.linalg.svd(eq.jacobian(pk, eq.straight_state(pk, N)), compute_uv=False)
        name = f"b{2 * k - 1}" if which == "S1" else f"b{2 * k}"
        out.append(BranchStart(name, which, k, pk, N, Bk, c, v, (float(full[-1]), float(full[-2]))))
    return tuple(out)


# --- continuation -----------------------------------------------------------------------


def _options(ds, ds_max, p_range, max_points, extra_stop=None, stop_on: tuple = ()) -> ContinuationOptions:
    lo, hi = p_range
    return ContinuationOptions(ds=ds, ds_min=1e-7, ds_max=ds_max, p_min=lo, p_max=hi, max_points=max_points,
                               tol=1e-10, stop=extra_stop, stop_on=tuple(stop_on))


def _stop_fn(max_measure1: float | None):
    if max_measure1 is None:
        return None
    return lambda u, p: eq.measure1(u) > max_measure1


@single_blas_thread
def continue_branch(params: RodParameters, start, parameter: str = "B", stop: tuple = (-math.inf, math.inf),
                    N: int | None = None, ds: float = 0.02, ds_max: float = 0.3, max_points: int = 400,
                    max_measure1: float | None = None, amplitude: float = 0.02,
                    direction: float = 1.0, which: str | None = None, stop_on: tuple = ()) -> Branch:
    """Continue a branch of relative equilibria in ``parameter`` (B, omega, T or R).

    ``start`` is a :class:`BranchStart` (leave the straight rod at its
    pitchfork, restricted to its symmetry class; the step ``amplitude`` is in
    the weighted arclength norm), a :class:`Branch` (continue from its last
    point, same symmetry restriction, in ``parameter``) or an
    :class:`~etcheck.rod.buckled.equilibria.Equilibrium` (a regular solution at its
    own parameters; ``which`` = "S1"/"S2"/"b1"/"b2" restricts to that
    symmetry class, None continues in the full space). ``direction`` = +1/-1
    orients the first tangent along +/- the parameter. ``stop`` = (p_min, p_max)
    bounds the parameter, ``max_measure1`` stops when measure_1 exceeds it,
    ``stop_on`` (kinds, e.g. ("break",)) at the first located special point
    of those kinds. Dimensionless. Returns a :class:`Branch` with located folds ("fold"),
    restricted branch points ("bp") and symmetry-breaking branch points
    ("break").
    """
    opts = _options(ds, ds_max, stop, max_points, _stop_fn(max_measure1), stop_on)
    if isinstance(start, BranchStart):
        if parameter != "B":
            raise ValueError("a branch starts at a pitchfork in B; continue it in another parameter afterwards")
        NN = start.N if N is None else int(N)
        if NN != start.N:
            start = _restart(start, NN)
        prob = _RodProblem(start.params, "B", NN, start.which)
        u0 = eq.straight_state(start.params, NN)
        d = np.append(start.kernel, 0.0)
        res = switch_branch(prob, u0, start.load, d, opts, amplitude=amplitude)
        return _branch(start.name, prob, res)
    if isinstance(start, Branch):
        u0, which, name = start.states[-1], start.which, start.name
    elif isinstance(start, eq.Equilibrium):
        u0, name = start, f"from {which or 'full'} state"
    else:
        raise TypeError(f"start must be a BranchStart, a Branch or an Equilibrium, got {type(start).__name__}")
    p_here = u0.params
    NN = u0.N if N is None else int(N)
    if NN != u0.N:
        u0 = eq.resample_state(u0, NN).with_params(p_here)
    prob = _RodProblem(p_here, parameter, NN, which)
    p0 = getattr(p_here, parameter)
    r0 = float(np.max(np.abs(prob.residual(u0, p0))))
    if r0 > 1e-8:
        raise ValueError(f"the start state is not an equilibrium at its parameters (residual {r0:.1e}); "
                         "solve it first (solve_equilibrium)")
    Ju, Jp = prob.jacobian(u0, p0)
    # initial tangent: Ju du = -Jp dp with dp = direction (a regular point is assumed)
    du = np.linalg.solve(Ju, -Jp * direction)
    res = continuation(prob, u0, p0, np.append(du, direction), opts, first_residual=r0)
    return _branch(name, prob, res)


def _restart(start: BranchStart, N: int) -> BranchStart:
    for s in primary_branches(start.params, start.k, N):
        if s.which == start.which:
            return s
    raise RuntimeError("unreachable")


@single_blas_thread
def connecting_branch(branch: Branch, bp: RodBranchPoint | None = None, ds: float = 0.02, ds_max: float = 0.3,
                      stop: tuple = (-math.inf, math.inf), max_points: int = 400,
                      min_measure1: float | None = 0.02, sign: float = 1.0, stop_at_bp: bool = True) -> Branch:
    """Switch at a symmetry-breaking branch point of a primary branch onto the
    connecting branch (b12 from b1, b34 from b3, ...) and continue it in the
    full space (dimensionless).

    ``bp`` defaults to the first "break" point of ``branch``. The new branch
    leaves along the kernel of the Jacobian restricted to the -1 eigenspace of
    the branch's symmetry (a pure symmetry-breaking direction, parameter
    tangent 0); ``sign`` picks one of the mirror pair: +1 the one along which
    measure_2 grows from the branch point, -1 its mirror image. Stops when
    measure_1 drops below ``min_measure1`` (at omega = T = 0
    the branch heads into the degenerate pitchfork of the straight rod, where
    the full Jacobian becomes doubly singular), when it leaves ``stop``, or,
    with ``stop_at_bp``, at the first branch point it meets: with spin, b12
    runs from b1's secondary pitchfork to a secondary pitchfork on b2 (where
    it would otherwise turn back along its mirror image and cycle).
    """
    if bp is None:
        breaks = [q for q in branch.special if q.kind == "break"]
        if not breaks:
            raise ValueError(f"branch {branch.name} has no symmetry-breaking branch point")
        bp = breaks[0]
    b = symmetry_bases(branch.params, branch.N, branch.which)
    u = bp.state
    p = bp.value
    full = _RodProblem(branch.params, branch.parameter, branch.N, None)
    J, _ = full._full(u, p)
    _, _, vh = np.linalg.svd(b.L_minus @ J @ b.V_minus)
    v = sign * _toward_positive_measure2(u, b.V_minus @ vh[-1])
    stop_fn = None if min_measure1 is None else (lambda uu, pp: eq.measure1(uu) < min_measure1)
    opts = ContinuationOptions(ds=ds, ds_min=1e-7, ds_max=ds_max, p_min=stop[0], p_max=stop[1],
                               max_points=max_points, tol=1e-10, stop=stop_fn,
                               stop_on=("bp",) if stop_at_bp else ())
    res = switch_branch(full, u, p, np.append(v, 0.0), opts, amplitude=ds)
    odd = branch.name[1:] if branch.name.startswith("b") and branch.name[1:].isdigit() else None
    name = f"b{odd}{int(odd) + 1}" if odd is not None else branch.name + "-connecting"
    return _branch(name, full, res)


def _toward_positive_measure2(u: eq.Equilibrium, v: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """The kernel direction v (unit 2-norm) oriented so that measure_2 grows along it: an SVD returns either sign,
    and which one follows from the round-off of the matrix (one of the mirror pair of connecting branches,
    :func:`connecting_branch`'s ``sign``, would otherwise be taken at random). Where measure_2 does not change to
    first order, the largest component is made positive."""
    dm = eq.measures(eq.retract(u, h * v)).measure2 - eq.measures(eq.retract(u, -h * v)).measure2
    if abs(dm) > 1e-6 * h:
        return v if dm > 0 else -v
    return v if v[np.argmax(np.abs(v))] > 0 else -v


@single_blas_thread
def locate(branch: Branch, fn, target: float, tol: float = 1e-12) -> tuple[float, eq.Equilibrium]:
    """Parameter value and state where fn(state) = target on ``branch`` (first crossing).

    fn is a scalar function of an Equilibrium (e.g. :func:`equilibria.measure1`);
    the crossing is bracketed by consecutive points and refined by the secant
    method on the arclength, each trial corrected onto the branch.
    """
    vals = np.array([fn(s) - target for s in branch.states])
    idx = np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) <= 0)[0]
    if idx.size == 0:
        raise ValueError(f"{target} not crossed on branch {branch.name} (range {vals.min() + target:.4g} .. "
                         f"{vals.max() + target:.4g})")
    i = int(idx[0])
    pts = branch.result.points
    a, bpt = pts[i], pts[i + 1]
    m = a.tau.size - 1
    W = weights(m, ContinuationOptions())
    prob = branch.problem
    lo, hi = 0.0, bpt.s - a.s
    flo, fhi, last = vals[i], vals[i + 1], 0
    best = (bpt.p, bpt.u)
    for _ in range(60):
        sig = hi - fhi * (hi - lo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
        if not lo < sig < hi:
            sig = 0.5 * (lo + hi)
        u, p, rn, it, ok = correct(prob, a.u, a.p, a.tau, sig, W, 1e-11, 12)
        if not ok:
            raise RuntimeError("corrector failed while locating")
        u = eq.Equilibrium(prob.at(p), u.x, u.D, u.F, u.M, rn, it, True)
        fq = fn(u) - target
        best = (p, u)
        if abs(fq) < tol:
            break
        lo, hi, flo, fhi, last = illinois_update(sig, fq, lo, hi, flo, fhi, last)
        if hi - lo < 1e-14:
            break
    return float(best[0]), best[1]


@single_blas_thread
def state_at(branch: Branch, value: float, tol: float = 1e-11) -> eq.Equilibrium:
    """The state of ``branch`` where its parameter equals ``value`` (first crossing; dimensionless).

    Predicted along the tangent of the nearer of the two bracketing points and
    corrected by Newton at the fixed parameter (same symmetry restriction):
    one short solve instead of the secant search of :func:`locate`, which it
    falls back to where the tangent has no parameter component (a fold).
    """
    vals = np.asarray(branch.values) - value
    idx = np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) <= 0)[0]
    if idx.size == 0:
        raise ValueError(f"{branch.parameter} = {value} not reached on branch {branch.name} "
                         f"({branch.values.min():.6g} .. {branch.values.max():.6g})")
    i = int(idx[0])
    pts = branch.result.points
    a = pts[i] if abs(vals[i]) <= abs(vals[i + 1]) else pts[i + 1]
    prob = branch.problem
    tp = float(a.tau[-1])
    if abs(tp) > 1e-3:
        u = prob.retract(a.u, (value - a.p) / tp * a.tau[:-1])
        u, _, rn, it, ok = correct_at(prob, u, float(value), tol, 12)
        if ok:
            return eq.Equilibrium(prob.at(value), u.x, u.D, u.F, u.M, rn, it, True)
    return locate(branch, lambda s: getattr(s.params, branch.parameter), value)[1]


@single_blas_thread
def trivial_branch_points(params: RodParameters, which: str | None, B_max: float, N: int = 32, dB: float = 0.05):
    """Continue the straight rod in B inside Fix(``which``) and return the located
    branch points (sign changes of the restricted bordered determinant) below B_max.

    Dimensionless. Demonstrates that the pitchforks are simple in each class;
    with ``which=None`` (full space) the determinant only touches zero at a
    double pitchfork (omega = T = 0) and nothing is found there.
    """
    prob = _RodProblem(params, "B", N, which)
    u0 = eq.straight_state(params.with_(B=0.0), N)
    m = prob.bases.V_plus.shape[1] if prob.bases is not None else NFIELDS * (N + 1)
    tau = np.zeros(m + 1)
    tau[-1] = 1.0
    opts = ContinuationOptions(ds=dB, ds_min=1e-9, ds_max=dB, p_min=-1.0, p_max=B_max, max_points=100000,
                               tol=1e-10, locate_tol=1e-13, weight_p=0.5)
    res = continuation(prob, u0, 0.0, tau, opts)
    return [sp.p for sp in res.special if sp.kind == "bp"], res


@dataclass(frozen=True)
class ResolutionCheck:
    """Two-resolution check of a branch (dimensionless).

    Each checked point is re-solved at ``N_check`` with the same parameters
    (Newton at fixed parameter, same symmetry restriction); ``measure1_error``
    and ``deflection_error`` are the largest differences of measure_1 and of
    the max deflection, ``residual`` the largest residual at N_check,
    ``checked``/``skipped`` how many points were (not) re-solved (a point next
    to a branch point or fold, where the Jacobian is singular, is skipped).
    """

    N: int
    N_check: int
    measure1_error: float
    deflection_error: float
    residual: float
    checked: int
    skipped: int


@single_blas_thread
def resolution_check(branch: Branch, N_check: int | None = None, stride: int = 4) -> ResolutionCheck:
    """Re-solve every ``stride``-th point of ``branch`` (and its last) at N_check
    (default N + max(8, N // 2)) and compare the measures (dimensionless)."""
    M = check_resolution(branch.N) if N_check is None else int(N_check)
    prob = _RodProblem(branch.params, branch.parameter, M, branch.which)
    idx = sorted(set(range(1, len(branch.states), stride)) | {len(branch.states) - 1})
    e1 = e2 = res = 0.0
    checked = skipped = 0
    for i in idx:
        st = branch.states[i]
        p = float(branch.values[i])
        u, _, rn, _, ok = correct_at(prob, eq.resample_state(st, M), p, 1e-11, 12)
        if not ok:
            skipped += 1
            continue
        checked += 1
        ms = eq.measures(u)
        e1 = max(e1, abs(ms.measure1 - branch.measure1[i]))
        e2 = max(e2, abs(ms.max_deflection - branch.max_deflection[i]))
        res = max(res, rn)
    return ResolutionCheck(branch.N, M, e1, e2, res, checked, skipped)
