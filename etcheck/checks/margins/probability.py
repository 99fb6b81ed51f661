"""The probability that a margin falls below the required margin, with a stated error or interval.

The uncertain inputs are independent; each is one standard-normal coordinate
(:mod:`etcheck.checks.margins.limit_state`, which also integrates one coordinate
exactly by conditioning: the power input that moves the margin most, else
the solved input with the largest elasticity times spread; the sampling
switches to the one the FORM design point leans on most). What remains, D
coordinates, is

* **D = 0**: nothing: the answer is one conditional probability, in closed
  form or at one root of the margin along the input (``exact``);
* **D = 1, or D = 2 when no more than one of them needs the margin solved
  again** (the rest enter as exact powers): adaptive Gauss-Kronrod quadrature
  against the normal density (:func:`etcheck.numerics.quadrature.normal_integrals`),
  nested for D = 2, to a relative error RTOL = 1e-8 (``quadrature``); along
  one solved input the margin is interpolated at 17, 33, 65 Chebyshev points
  where P settles to SURROGATE_RTOL = 1e-6 there. The stated error adds the
  quadrature's estimate, the margins' own errors carried through, the cut of
  the integration range at +-8.3 standard deviations (1e-16 absolute per
  coordinate), the root tolerance and the interpolation's last change;
* **otherwise**: randomised quasi-Monte Carlo, with defensive importance
  sampling at the design point where FORM puts the probability at or below
  0.1 (:mod:`etcheck.checks.margins.sampling`; ``sampling``): the 95 % interval of 32
  replicates with a Student t quantile; the number of points is fixed
  beforehand by budgets of margin evaluations (BUDGET) and of their seconds
  (SECONDS, at the time per evaluation measured first).

At or below SMALL = 1e-4, FORM and SORM (Breitung) are computed as a
cross-check. A probability whose upper end (value + error, or the interval's
upper end) lies below FLOOR = 1e-9 is reported as the bound "P < 1e-9": below
what the inputs' distributions mean, and below what the sampling resolves.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from etcheck.checks.margins.limit_state import Coordinate, LimitState, NotAnswered
from etcheck.checks.margins.margin_model import MarginModel
from etcheck.checks.margins.sampling import REPLICATES, SMALL_FORM, design_point, sample
from etcheck.checks.margins.sensitivity import MarginSensitivity
from etcheck.checks.results.sections import CrossCheck, Probability
from etcheck.input.uncertainty import Uncertainty
from etcheck.numerics.quadrature import CAP, normal_integrals

#: Probabilities whose upper end lies below this are reported as the bound P < FLOOR.
FLOOR = 1e-9
#: At and below this, FORM and SORM are computed as a cross-check.
SMALL = 1e-4
#: Target relative error of the quadrature.
RTOL = 1e-8
#: Chebyshev-Lobatto degrees of the interpolated margin along one shape input (nested), and the stated relative
#: error at which it is used (the margins are solved at the quadrature points where it does not reach it).
SURROGATE_POINTS = (16, 32, 64)
SURROGATE_RTOL = 1e-6
_TRUNCATION = math.erfc(8.3 / math.sqrt(2))  # 2 Phi(-8.3): the cut of one integration range
#: Default budgets of sampling where each sample needs the check's route: margin evaluations, and seconds of them.
BUDGET = 4096
SECONDS = 5.0
#: Points per replicate for sampling a closed-form margin (32 x 2^15: ~1e6 points, about a second).
CLOSED_POINTS = 2**15
EXACT, QUADRATURE, SAMPLING, NOT_ANSWERED = "exact", "quadrature", "sampling", "not answered"


def failure_probability(model: MarginModel, kind: str, unc: Uncertainty, sens: MarginSensitivity | None = None,
                        seed: int = 20240615, budget: int = BUDGET, method: str | None = None,
                        points: int | None = None, seconds: float | None = SECONDS) -> Probability:
    """P(margin ``kind`` < required) over the uncertain inputs ``unc`` (module docstring).

    ``sens``: the margin's elasticities (they choose the input to condition on
    when every input needs the margin solved again); ``seed``: of the
    sampling; ``budget``: margin evaluations the sampling may spend;
    ``method``: force "sampling" (tests of the interval), else chosen;
    ``points``: sampled points per replicate (default: from the budgets, or
    CLOSED_POINTS for a closed form); ``seconds``: a time budget for the
    sampled margins (None: ``budget`` alone decides; the points then do not
    depend on the machine).
    """
    started = time.perf_counter()
    base = dict(margin=kind, required=model.required, model=model.name)
    inert = model.inert(kind, unc.names)
    moving = [d for d in unc.inputs if d.input not in inert]
    powers = model.powers(kind)
    shape = tuple(d.input for d in moving if d.input not in powers)
    why = model.unanswered(kind, shape)
    if why:
        return _not_answered(base, why, moving, inert, started)
    ls = _limit_state(model, kind, moving, powers, sens)
    info = dict(base, inputs=tuple(d.input for d in moving), inert=tuple(d.input for d in unc.inputs
                                                                           if d.input in inert))
    try:
        if ls is None:  # nothing moves it
            m = model.margin(model.values(), kind)
            p = float(m.value < model.required)
            return Probability(**info, value=p, bound=None, low=p, high=p, error=0.0, method=EXACT,
                               how="exact: no uncertain input moves this margin", evaluations=1, points=0,
                               conditioned_on=None, elapsed_s=time.perf_counter() - started)
        chosen = method or _method(ls)
        corner = None if chosen == SAMPLING and method else _adverse_corner(ls, sens)
        if corner is not None:
            return replace(corner, **info, elapsed_s=time.perf_counter() - started)
        out = _sampled(ls, info, seed, budget, points, seconds) if chosen == SAMPLING else _integrated(ls, info)
    except NotAnswered as exc:
        return _not_answered(base, f"a sample's margin was not answered by the check's route: {exc}", moving, inert,
                             started)
    return _finish(out, ls, started)


def _not_answered(base: dict, why: str, moving, inert, started: float) -> Probability:
    return Probability(**base, value=None, bound=None, low=None, high=None, error=None, method=NOT_ANSWERED,
                       how=why, evaluations=0, points=0, conditioned_on=None,
                       inputs=tuple(d.input for d in moving), inert=tuple(inert), elapsed_s=time.perf_counter() - started)


def _limit_state(model: MarginModel, kind: str, moving, powers: dict[str, float],
                 sens: MarginSensitivity | None) -> LimitState | None:
    """The coordinates (lognormal power inputs merged), the one conditioned on and the order of the rest:
    inputs whose margin must be solved again outermost (one solve serves a whole inner integral)."""
    if not moving:
        return None
    coords, merged = [], []
    for d in moving:
        a = powers.get(d.input)
        if a is not None and d.shape == "lognormal" and d.mass() == 1.0:
            merged.append((d.input, a * d.b))
        else:
            coords.append(Coordinate(d.input, d, a, 0.0, model.nominal.get(d.input, 1.0)))
    if merged:
        sigma = math.sqrt(sum(s * s for _, s in merged))
        coords.append(Coordinate(" and ".join(n for n, _ in merged) + (" (lognormal, one term)" if len(merged) > 1
                                                                         else ""), None, None, sigma))
    coords.sort(key=lambda c: not c.shape)  # shape coordinates first: outermost in the nesting
    closed = [i for i, c in enumerate(coords) if not c.shape]
    if closed:
        cond = max(closed, key=lambda i: coords[i].spread)
        return LimitState(model, kind, coords, cond)
    # an elasticity that is not a finite number (the margin jumps at the mission's values: a tether at its critical
    # spin) says nothing of the direction: the margins at z = -+0.5 decide it
    els = {e.input: e.value for e in sens.elasticities if e.value is not None and math.isfinite(e.value)} if sens else {}
    cond = max(range(len(coords)), key=lambda i: abs(els.get(coords[i].name, 0.0)) * coords[i].dist.log_spread())
    ls = LimitState(model, kind, coords, cond)
    e = els.get(coords[cond].name)
    ls.rising = ls.rises_along_cond() if not e else e > 0
    return ls


def _adverse_corner(ls: LimitState, sens: MarginSensitivity | None) -> Probability | None:
    """P < FLOOR at the cost of a few margins where the margin meets the required margin at the mission's values
    and with every input at CAP = 8.3 standard deviations on either side (on its adverse side for an exact power):
    taking the margin monotone in each input (as the conditioning does), failure needs an input beyond 8.3
    standard deviations, P <= n 2 Phi(-8.3) = n 1e-16. None where that does not hold, where more than 8 corners
    would be needed, or where every margin is a closed form (integrated exactly anyway)."""
    if sens is None or not any(c.shape for c in ls.coords):
        return None
    sides = []
    for c in ls.coords:
        if c.dist is None:  # the merged lognormal power inputs: ln m grows with z (term sigma z)
            sides.append((-CAP,))
        elif c.power is not None:  # an exact power: its adverse side is known
            sides.append((0.0,) if c.power == 0 else (-CAP if c.power > 0 else CAP,))
        else:  # a solved input: both sides (an elasticity's sign at the mission's values is no proof)
            sides.append((-CAP, CAP))
    corners = np.array(np.meshgrid(*sides)).reshape(len(sides), -1).T
    if len(corners) > 8:
        return None
    corners = np.vstack([np.zeros((1, len(sides))), corners])  # the mission's own values must pass too
    lnM, err = ls.log_margins(corners)
    worst = float(np.min(lnM + ls.power_sum(corners) - np.abs(err)))
    if not worst >= ls.log_required:
        return None
    n = len(ls.coords)
    return Probability("", 0.0, None, FLOOR, None, None, None, EXACT,
                       f"exact bound: the margin meets the required margin at the mission's values and with every "
                       f"input at 8.3 standard deviations on either side ({len(corners)} margin evaluations); "
                       f"taking it monotone in each input, P <= {n} x 1e-16",
                       ls.evaluations, len(corners), None, (), (), "",
                       note=f"below {FLOOR:g}: reported as a bound")


def _method(ls: LimitState) -> str:
    """Quadrature where at most one outer coordinate needs the margin solved again (and D <= 2; with a root
    found per point only D <= 1), sampling otherwise."""
    D = len(ls.outer)
    shape_outer = sum(ls.coords[i].shape for i in ls.outer)
    root = ls.coords[ls.cond].shape
    if D == 0 or D == 1 or (D == 2 and shape_outer <= 1 and not root):
        return QUADRATURE
    return SAMPLING


def _integrated(ls: LimitState, info: dict) -> Probability:
    """D = 0: the conditional probability at the outer point; D = 1, 2: nested quadrature."""
    cond = ls.coords[ls.cond]
    how_cond = (f"{cond.name} integrated in closed form (the margin is an exact power of it)" if not cond.shape else
                f"{cond.name} integrated exactly at the root of margin = required along it (secant or Brent)")
    D = len(ls.outer)
    if D == 0:
        lp, le = ls.log_conditional(np.zeros((1, 0)))
        value, err = float(np.exp(lp[0])), float(np.exp(le[0]))
        return Probability(**info, value=value, bound=None, low=max(0.0, value - err), high=min(1.0, value + err),
                           error=err / value if value > 0 else None, method=EXACT,
                           how=f"exact: one input; {how_cond}", evaluations=ls.evaluations, points=1,
                           conditioned_on=cond.name)
    log_value, abs_err, evaluations, peak, N = _interpolated(ls)
    if N is None:
        log_value, abs_err, evaluations, peak = _nested(ls)
    value = math.exp(log_value)
    names = ", ".join(ls.coords[i].name for i in ls.outer)
    how = (f"quadrature: adaptive Gauss-Kronrod (15 points, nested {D}-D) over {names} in standard-normal "
           f"coordinates to a relative {RTOL:.0e}; {how_cond}")
    if N is not None:
        what = (f"the root along {cond.name}" if cond.shape else
                f"the margin along {next(c.name for c in ls.coords if c.shape)}")
        how += (f"; {what} interpolated at {N + 1} Chebyshev points over +-8.3 standard deviations (the change of "
                f"P from {N // 2 + 1} points added to the error stated)")
    return Probability(**info, value=value, bound=None, low=max(0.0, value - abs_err), high=min(1.0, value + abs_err),
                       error=abs_err / value if value > 0 else None, method=QUADRATURE, how=how,
                       evaluations=ls.evaluations, points=evaluations, conditioned_on=cond.name,
                       cross_check=_cross_check(ls, value, peak))


def _cross_check(ls: LimitState, value: float, start: np.ndarray | None = None) -> CrossCheck | None:
    """FORM and SORM for a small probability (from ``start``, e.g. where the integrand peaked)."""
    if not FLOOR <= value <= SMALL or not ls.outer:  # (a bound is not cross-checked)
        return None
    dp = design_point(ls, start)
    return CrossCheck(dp.beta, dp.form, dp.sorm) if dp.safe_origin and dp.found else None


def _interpolated(ls: LimitState) -> tuple[float, float, int, np.ndarray, int | None]:
    """With one shape coordinate, not the one conditioned on: ln M along it interpolated at 17, 33, 65
    Chebyshev-Lobatto points over +-CAP (nested: each level reuses the last's margins); with a shape coordinate
    conditioned on and one outer coordinate: the root along the former interpolated in the latter; until the
    stated error,
    with the change of P from the last level added (an estimate of the last level's error, and so a generous
    one of this level's), is below SURROGATE_RTOL x P. N None where that does not happen (or a margin is zero or
    unbounded at a point): the margin is then solved at every quadrature point."""
    shape = [c for c in ls.coords if c.shape]
    root = ls.coords[ls.cond].shape
    if (root and len(ls.outer) != 1) or (not root and len(shape) != 1):
        return 0.0, 0.0, 0, np.zeros(0), None
    last = None
    for N in SURROGATE_POINTS:
        if not ls.lobatto_solve(N):
            break
        ls.surrogate = N
        try:
            log_value, abs_err, count, peak = _nested(ls)
        finally:
            ls.surrogate = None
        value = math.exp(log_value)
        if last is not None and abs_err + abs(value - last) <= SURROGATE_RTOL * value + 2 * _TRUNCATION:
            return log_value, abs_err + abs(value - last), count, peak, N
        last = value
    return 0.0, 0.0, 0, np.zeros(0), None


def _nested(ls: LimitState) -> tuple[float, float, int, np.ndarray]:
    """ln P, its absolute error bound, the integrand evaluations and where the outermost integrand peaked
    (the others at 0), by nested quadrature over the outer coordinates (outermost first)."""
    outer = ls.outer
    count = [0]
    peaks = []

    def level(prefix: np.ndarray, depth: int):
        """ln of the integral over coordinates depth.. for every row of ``prefix`` (the coordinates before),
        and ln of its absolute error."""
        n = len(prefix)

        def log_f(i, z):
            Z = np.column_stack([prefix[i], z]) if prefix.shape[1] else z[:, None]
            if depth == len(outer) - 1:
                count[0] += len(z)
                return ls.log_conditional(Z)
            return level(Z, depth + 1)

        r = normal_integrals(log_f, n, rtol=RTOL, panels=_panels(ls, depth), below=0.1 * FLOOR if depth == 0 else 0.0)
        if depth == 0:
            peaks.append(r.peak[0])
        value = np.exp(r.log_value)
        err = (r.quadrature + r.own) * value + r.truncation
        with np.errstate(divide="ignore"):
            return r.log_value, np.log(err)

    log_value, log_err = level(np.zeros((1, 0)), 0)
    start = np.zeros(len(outer))
    start[0] = peaks[0]
    return float(log_value[0]), float(np.exp(log_err[0])), count[0], start


def _panels(ls: LimitState, depth: int) -> int:
    """Initial panels on [-8.3, 8.3]: 3 where each point costs a margin solve, 16 for closed forms."""
    return 3 if ls.coords[ls.outer[depth]].shape or ls.coords[ls.cond].shape else 16


def _sampled(ls: LimitState, info: dict, seed: int, budget: int, points: int | None,
             seconds: float | None) -> Probability:
    """Randomised QMC, half the points at the design point when FORM puts P at or below SMALL_FORM; the points
    per replicate fixed before sampling (``points``, else from the budgets)."""
    dp = design_point(ls)
    ls = _leaning(ls, dp)
    shifted = dp.safe_origin and dp.found and dp.form <= SMALL_FORM
    points = max(points or _points(ls, budget, seconds), 2 if shifted else 1)  # the mixture: half and half
    s = sample(ls, points, seed, dp.u[ls.outer] if shifted else None)
    names = ", ".join(ls.coords[i].name for i in ls.outer)
    cond = ls.coords[ls.cond]
    how = (f"sampling: randomised quasi-Monte Carlo, {REPLICATES} scrambled Sobol sequences of {points} points over "
           f"{names}" + (f", half of them around the design point (defensive importance sampling, FORM beta = "
                         f"{dp.beta:.3g})" if shifted else "") + "; 95 % interval from the replicates with a Student t "
           f"quantile ({REPLICATES - 1} degrees of freedom); {cond.name} integrated exactly")
    total = REPLICATES * points
    cross = CrossCheck(dp.beta, dp.form, dp.sorm) if dp.safe_origin and dp.found else None
    common = dict(info, method=SAMPLING, how=how, evaluations=ls.evaluations, points=total,
                  conditioned_on=cond.name, cross_check=cross)
    if s.value == 0:  # no point came near failing: the rule of three over the points drawn from the inputs' own law
        unshifted = total // 2 if shifted else total
        return Probability(**common, value=None, bound=min(1.0, 3.0 / unshifted), low=None, high=None, error=None,
                           note=f"no sampled point came near failing: P < 3/{unshifted} (the rule of three, 95 %)")
    low, high = max(0.0, s.value - s.half_width), min(1.0, s.value + s.half_width)
    return Probability(**common, value=s.value, bound=None, low=low, high=high, error=s.half_width / s.value)


def _leaning(ls: LimitState, dp) -> LimitState:
    """The limit state conditioned on the coordinate the design point leans on most (the largest |u*_i|: the
    failure there hinges on it, and integrating it exactly leaves the smoothest integrand to sample) where that
    is not the one chosen from the inputs' spreads at the mission's values and leans at least 1.5 times as far."""
    if not (dp.found and dp.safe_origin):
        return ls
    lean = np.abs(dp.u)
    best = int(np.argmax(lean))
    if best == ls.cond or lean[best] < 1.5 * lean[ls.cond]:
        return ls
    return ls.conditioned_on(best, rising=bool(dp.u[best] < 0))


def _points(ls: LimitState, budget: int, seconds: float | None) -> int:
    """Points per replicate: CLOSED_POINTS for a closed form; otherwise the largest power of two whose margin
    evaluations fit in what is left of ``budget`` and (if given) of ``seconds`` at the time per evaluation
    measured so far; at least one."""
    per_sample = _cost_per_sample(ls)
    if per_sample == 0:
        return CLOSED_POINTS
    spare = float(budget - ls.evaluations)
    if seconds is not None and ls.evaluations:
        spare = min(spare, seconds / (ls.seconds / ls.evaluations))
    n = spare / (REPLICATES * per_sample)
    return 2 ** max(0, int(math.floor(math.log2(n)))) if n >= 1 else 1


def _cost_per_sample(ls: LimitState) -> float:
    """Margin evaluations one sampled point costs: 0 for a closed form, 1 with a closed-form conditioning, the
    mean of the root searches so far otherwise."""
    if not any(c.shape for c in ls.coords):
        return 0
    if not ls.coords[ls.cond].shape:
        return 1
    return max(1.0, ls.evaluations / max(1, ls.roots_found))


def _finish(p: Probability, ls: LimitState, started: float) -> Probability:
    """The cross-check for small probabilities, the bound below FLOOR, notes and the time."""
    notes = []
    if ls.not_monotone:
        notes.append(f"the margin is not monotone along {ls.coords[ls.cond].name} over the points visited: the "
                     "conditional probability takes its first crossing")
    p = replace(p, evaluations=max(p.evaluations, ls.evaluations))
    top = p.high if p.high is not None else p.value
    if p.value is not None and top is not None and top < FLOOR:
        notes.append(f"below {FLOOR:g}: reported as a bound (the estimate {p.value:.3g})")
        p = replace(p, value=None, bound=FLOOR)
    return replace(p, note="; ".join(n for n in (p.note, *notes) if n), elapsed_s=time.perf_counter() - started)
