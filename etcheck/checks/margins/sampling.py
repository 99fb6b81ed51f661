"""The design point (FORM, SORM) and randomised quasi-Monte Carlo with importance sampling, for the
probability of falling short when there are too many uncertain inputs to integrate deterministically.

Works on a :class:`~etcheck.checks.margins.limit_state.LimitState`: its conditional
probability P(fail | z) over the D outer standard-normal coordinates z (one
coordinate already integrated exactly), and its margin over all of them.

**Design point.** The limit state is g(u) = ln m(u) - ln required over all
standard-normal coordinates u (failure where g < 0). FORM's design point is
the point of g = 0 nearest the origin, found by the improved HL-RF iteration
(finite-difference gradients); beta = |u*|, P_FORM = Phi(-beta). SORM
(Breitung): P ~ Phi(-beta) prod (1 + beta kappa_i)^-1/2 with the principal
curvatures kappa_i of g = 0 at u*, from the central-difference Hessian of g
(step 1e-2). Both are asymptotic approximations, reported as a cross-check,
never as the answer; the outer part of u* is where the importance sampling
centres its shifted points.

**Sampling.** R = 32 independent replicates, each n points of scrambled
Sobol sequences (scipy.stats.qmc; seeds spawned from one seed by
numpy.random.SeedSequence), mapped to z = Phi^-1(u). Where FORM puts the
probability at or below SMALL_FORM = 0.1, half of each replicate's points are
shifted to the design point mu (defensive importance sampling: the points
fall where the failures are, and the even mixture with the unshifted half
bounds every weight phi(z) / q(z) by 2, so that a second failure region is
not lost); each point contributes P(fail | z) phi(z) / q(z), q the mixture
density (the balance heuristic). Every replicate mean is unbiased; the
estimate is their mean, its 95 % interval mean +- t_{0.975, R-1} s / sqrt(R)
(Student t with R - 1 degrees of freedom, s the replicates' standard
deviation). n is fixed before sampling (from the evaluation budget), never by
looking at the results, so no stopping rule biases the estimate or its
interval. 32 replicates rather than fewer with more points: the replicate
means of scrambled nets can be skewed (a rare point in a high stratum), and
the t interval holds its 95 % over them only with enough of them (measured on
closed-form cases: 0.89-0.92 with 16, 0.93-0.96 with 32).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.checks.margins.limit_state import LimitState, NotAnswered
from etcheck.numerics.quadrature import CAP

#: Replicates of the randomised QMC (the interval's degrees of freedom are one fewer).
REPLICATES = 32
#: FORM probability at and below which half the points are shifted to the design point.
SMALL_FORM = 0.1
#: Points per chunk of a closed-form replicate (bounds the memory: ~10 MB per outer coordinate).
_CHUNK = 2**16


@dataclass(frozen=True)
class DesignPoint:
    """FORM's design point: ``u`` (all coordinates; ``z`` the outer ones), ``beta`` (its distance from the
    origin), ``form`` = Phi(-beta), ``sorm`` (Breitung; None where a curvature makes it undefined or it was not
    computed), ``curvatures``; ``safe_origin``: the mission's values do not fall short (else FORM says nothing of
    a small probability); ``found``: the search reached the limit-state surface."""

    u: np.ndarray
    z: np.ndarray
    beta: float
    form: float
    sorm: float | None
    curvatures: tuple[float, ...]
    safe_origin: bool
    found: bool


def limit_state(ls: LimitState, U: np.ndarray) -> np.ndarray:
    """g(u) = ln m(u) - ln required over all coordinates (rows of U, each within +-CAP: beyond, P < 1e-16 and
    an input can reach the end of its range): failure where g < 0 (clipped to +-50)."""
    U = np.clip(np.atleast_2d(U), -CAP, CAP)
    lnM, _ = ls.log_margins(U)
    return np.clip(lnM + ls.power_sum(U) - ls.log_required, -50.0, 50.0)


def design_point(ls: LimitState, start: np.ndarray | None = None, sorm_up_to: int = 3) -> DesignPoint:
    """FORM by the improved Hasofer-Lind-Rackwitz-Fiessler iteration on g (finite-difference gradients, step
    1e-5; from ``start``, outer coordinates, else the origin), and SORM (Breitung) from the central-difference
    Hessian of g at the design point where g is a closed form or there are at most ``sorm_up_to``
    coordinates (module docstring)."""
    from scipy import special

    n = len(ls.coords)
    u = np.zeros(n)
    if start is not None:
        u[ls.outer] = start
    g0 = float(limit_state(ls, np.zeros((1, n)))[0])
    if g0 <= 0:  # the mission's values already fall short
        return DesignPoint(np.zeros(n), np.zeros(n - 1), math.nan, math.nan, None, (), False, True)
    try:
        u, grad, found = _hlrf(ls, u, g0)
    except NotAnswered:  # a margin on the way was not answered: no design point (the sampling does without)
        return DesignPoint(u, u[ls.outer], math.nan, math.nan, None, (), True, False)
    beta = float(np.linalg.norm(u))
    form = float(special.ndtr(-beta)) if found else 0.0
    curv: list[float] = []
    if found and (not any(c.shape for c in ls.coords) or n <= sorm_up_to):
        curv = _curvatures(ls, u)
    factors = [1.0 + beta * k for k in curv]
    sorm = form / math.sqrt(math.prod(factors)) if curv and all(f > 0 for f in factors) else None
    return DesignPoint(u, u[ls.outer], beta, form, sorm, tuple(curv), True, found)


def _gradient(ls: LimitState, u: np.ndarray, h: float = 1e-5) -> tuple[float, np.ndarray]:
    n = len(u)
    g = limit_state(ls, np.vstack([u, u + h * np.eye(n)]))
    return float(g[0]), (g[1:] - g[0]) / h


def _hlrf(ls: LimitState, u: np.ndarray, g0: float, steps: int = 40) -> tuple[np.ndarray, np.ndarray, bool]:
    """The design point by iHLRF: the HL-RF step, halved until the merit |u|^2 / 2 + c |g| falls (Zhang and
    Der Kiureghian's rule); (u, the gradient of g there, converged)."""
    g, grad = _gradient(ls, u)
    for _ in range(steps):
        norm = float(grad @ grad)
        if norm == 0 or not np.all(np.isfinite(grad)):
            return u, grad, False
        d = (grad @ u - g) / norm * grad - u
        c = 2.0 * max(1.0, float(np.linalg.norm(u)) / math.sqrt(norm))
        merit = 0.5 * float(u @ u) + c * abs(g)
        step, trial = 1.0, np.clip(u + d, -CAP, CAP)
        while step > 1e-4:
            trial = np.clip(u + step * d, -CAP, CAP)
            gt = float(limit_state(ls, trial[None, :])[0])
            if 0.5 * float(trial @ trial) + c * abs(gt) < merit:
                break
            step *= 0.5
        moved = float(np.linalg.norm(trial - u))
        u = trial
        g, grad = _gradient(ls, u)
        if moved < 1e-6 * max(1.0, float(np.linalg.norm(u))) and abs(g) < 1e-6 * g0 + 1e-9:
            return u, grad, True
    return u, grad, bool(abs(g) < 1e-4 * g0 + 1e-6)


def _curvatures(ls: LimitState, u: np.ndarray, h: float = 1e-2) -> list[float]:
    """Principal curvatures of g = 0 at u (positive: the surface curves away from the origin), from the
    central-difference gradient and Hessian of g."""
    n = len(u)
    E = np.eye(n)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    pts = [u] + [u + s * h * E[i] for i in range(n) for s in (1, -1)]
    pts += [u + h * (si * E[i] + sj * E[j]) for i, j in pairs for si, sj in ((1, 1), (1, -1), (-1, 1), (-1, -1))]
    f = limit_state(ls, np.array(pts))
    up, dn = f[1:1 + 2 * n:2], f[2:2 + 2 * n:2]
    H = np.diag((up - 2 * f[0] + dn) / h**2)
    for k, (i, j) in enumerate(pairs):
        pp, pm, mp, mm = f[1 + 2 * n + 4 * k:5 + 2 * n + 4 * k]
        H[i, j] = H[j, i] = (pp - pm - mp + mm) / (4 * h * h)
    grad = (up - dn) / (2 * h)
    normal = grad / np.linalg.norm(grad)
    Pt = np.eye(n) - np.outer(normal, normal)
    vals, vecs = np.linalg.eigh(Pt @ H @ Pt / np.linalg.norm(grad))
    tangent = np.abs(vecs.T @ normal) < 0.5  # drop the normal direction's zero
    return [float(v) for v in vals[tangent]]


@dataclass(frozen=True)
class Sampled:
    """The estimate, its 95 % half-width, the replicate means, points per replicate, the shift used."""

    value: float
    half_width: float
    replicates: np.ndarray
    points: int
    shift: np.ndarray


def sample(ls: LimitState, points: int, seed: int, shift: np.ndarray | None = None,
           replicates: int = REPLICATES) -> Sampled:
    """Randomised QMC of P(fail) = E[P(fail | z)] over the outer coordinates: ``replicates`` replicates of
    ``points`` points each, from scrambled Sobol sequences (module docstring); with a ``shift``, half of each
    replicate's points from N(0, I) and half from N(shift, I), weighted by the balance heuristic. The points of
    all replicates are evaluated together, in chunks (bounded memory; margins shared with a forked helper)."""
    from scipy import stats

    D = len(ls.outer)
    mu = None if shift is None else np.asarray(shift, float)
    if mu is not None and points % 2:
        raise ValueError("a shifted sample needs an even number of points per replicate (half from each density)")
    sums = np.zeros(replicates)
    for owner, z in _points_in_chunks(D, points, seed, replicates, mu):
        lp, _ = ls.log_conditional(z)
        if mu is not None:  # phi(z) / (phi(z) / 2 + phi(z - mu) / 2) = 2 / (1 + exp(z.mu - |mu|^2 / 2))
            lp = lp + math.log(2.0) - np.logaddexp(0.0, z @ mu - 0.5 * float(mu @ mu))
        sums += np.bincount(owner, np.exp(lp), minlength=replicates)
    means = sums / points
    value = float(np.mean(means))
    half = float(stats.t.ppf(0.975, replicates - 1) * np.std(means, ddof=1) / math.sqrt(replicates))
    return Sampled(value, half, means, points, np.zeros(D) if mu is None else mu)


def _points_in_chunks(D: int, points: int, seed: int, replicates: int, mu: np.ndarray | None):
    """(replicate of each row, z) in chunks of at most _CHUNK rows: every replicate's ``points`` scrambled
    Sobol points (one sequence per replicate; with mu, its first half as it is and its second half around mu:
    each half of a Sobol sequence of 2^k points is a net of its own)."""
    from scipy import special
    from scipy.stats import qmc

    halves = [(np.zeros(D), points)] if mu is None else [(np.zeros(D), points // 2), (mu, points // 2)]
    owner, rows, held = [], [], 0
    for r, child in enumerate(np.random.SeedSequence(seed).spawn(replicates)):
        engine = qmc.Sobol(D, scramble=True, seed=np.random.default_rng(child))
        for centre, n in halves:
            left = n
            while left > 0:
                k = min(left, _CHUNK)
                rows.append(centre + special.ndtri(engine.random(k)))
                owner.append(np.full(k, r))
                held, left = held + k, left - k
                if held >= _CHUNK:
                    yield np.concatenate(owner), np.vstack(rows)
                    owner, rows, held = [], [], 0
    if rows:
        yield np.concatenate(owner), np.vstack(rows)
