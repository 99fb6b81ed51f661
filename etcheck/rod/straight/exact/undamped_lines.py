"""Stability of the undamped straight tether along a line of load B or spin omega (rung 1u):
the real roots of E(mu) (:mod:`etcheck.rod.straight.exact.undamped_kernel`) followed along the line,
and every divergence and flutter point on it located exactly.

**Counting.** The real roots below a cut mu_cut are counted exactly (sign
changes, close pairs split by minimising |E|); no real root lies below the
Rayleigh bound mu_lo of K / M (for real lambda the eigenvector is real and
its Coriolis term vanishes). At omega = 0 the problem is self-adjoint (K q
= mu M q): every root is real, so the number of roots below mu_cut there
is the total; along a line from omega = 0 the number of complex pairs is
(total - real roots) / 2, the total changing only when a real root crosses
mu_cut (detected, with its direction). A flutter point is a fold of the
real roots, E = dE/dmu = 0: it is located by Brent's method on the value of
E at its local extremum in mu (smooth and with a simple zero at the fold),
a divergence point by a root of E(0) = D_static.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from etcheck.numerics.optimize import bracketed_roots, brentq, find_root, minimize_scalar
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.spectral import CriticalKind, stable_windows
from etcheck.rod.straight.exact import roots as exact
from etcheck.rod.straight.exact.mode_band import cut, mode_count
from etcheck.rod.straight.exact.undamped_isotropic import characteristic_plus_counted
from etcheck.rod.straight.exact.undamped_kernel import (
    CUT_SAMPLES,
    MAX_GRID,
    SCHUR_BUDGET,
    characteristic_counted,
    coefficients,
    rayleigh_floor,
    stiffness_positive,
    wavenumbers,
)

_EPS = np.finfo(float).eps

__all__ = [
    "close_pairs",
    "Crossing",
    "dips",
    "Line",
    "pair_count",
    "stability_line",
    "StabilityLine",
    "static_roots",
]


@dataclass(frozen=True)
class _Sample:
    """Real roots of E(.; p) at one point p of a line: their approximate positions (sorted),
    the counts below and above mu = 0 (all counted above for a line in Omega) and the signs of E at the
    cuts."""

    p: float
    roots: tuple[float, ...]
    n_neg: int
    n_pos: int
    top: tuple[float, ...]


def _positive_grid(params: RodParameters, ends: list[RodParameters], density: float) -> tuple[float, np.ndarray]:
    """(mu_cut, grid on (0, mu_cut] uniform in the Weyl mode count) of a line whose ends are ``ends``."""
    mu_cut = cut(params, ends)
    fine = np.concatenate([[0.0], np.geomspace(1e-9 * mu_cut, mu_cut, 4000)])
    count = mode_count(params, fine, params.T)
    n = max(int(math.ceil(density * count[-1])), 16)
    return mu_cut, np.interp(np.linspace(0.0, count[-1], n + 1), count, fine)[1:]


def _sign_roots(mu: np.ndarray, E: np.ndarray) -> list[float]:
    """The roots of E on the grid mu where it changes sign (secant between the two samples) or is zero."""
    s = np.sign(E)
    j = np.nonzero(s[:-1] * s[1:] < 0)[0]
    return (mu[j] + (mu[j + 1] - mu[j]) * E[j] / (E[j] - E[j + 1])).tolist() + mu[s == 0].tolist()


def dips(i: int, mu: np.ndarray, E: np.ndarray) -> list[tuple]:
    """The candidates of :func:`close_pairs` in row i: the samples of E on the grid mu where |E| has a local
    minimum without a change of sign."""
    s = np.sign(E)
    aE = np.abs(E)
    j = np.nonzero((s[:-2] == s[1:-1]) & (s[1:-1] == s[2:]) & (aE[1:-1] < aE[:-2]) & (aE[1:-1] < aE[2:]))[0] + 1
    return [(i, mu[k - 1], mu[k + 1], s[k], max(aE[k - 1], aE[k + 1]), 1.0, E[k - 1], E[k + 1]) for k in j]


def close_pairs(evaluate, ps: np.ndarray, cand: list) -> list[tuple[int, list[float]]]:
    """Close pairs of roots of E = evaluate(p, mu) at the dips of |E| between grid points: each dip is zoomed in
    (9 points, 8 levels, all dips in one evaluation per level) until E changes sign (two
    roots), the dip clearly stays off zero (parabola through its three lowest points), or it
    touches zero (a double root). ``cand``: (row, ends of the dip, sign of E there, scale of E, last
    parabola's minimum over the lowest sample, E at the ends and, past the first level, at the middle, which is
    the last level's lowest sample): E is evaluated only at the points it is not known at."""
    found = []
    t = np.linspace(0.0, 1.0, 9)
    for level in range(8):
        if not cand:
            break
        a = np.array([c[1] for c in cand])
        b = np.array([c[2] for c in cand])
        x = a[:, None] + (b - a)[:, None] * t[None, :]
        x[:, -1] = b
        E = np.empty(x.shape)
        E[:, 0], E[:, -1] = [c[6] for c in cand], [c[7] for c in cand]
        new = np.array([1, 2, 3, 5, 6, 7] if level else range(1, 8))
        if level:
            E[:, 4] = [c[8] for c in cand]
        E[:, new] = evaluate(np.array([ps[c[0]] for c in cand])[:, None], x[:, new])
        nxt = []
        for c, xi, Ei in zip(cand, x, E):
            i, sg, size = c[0], c[3], c[4]
            flips = np.nonzero(np.sign(Ei[:-1]) != np.sign(Ei[1:]))[0]
            if flips.size >= 2:  # each root where the secant crosses zero (a midpoint could put a root
                # just above mu = 0 below it, and count it with the real pairs, when E is tiny at a node)
                j = flips[[0, -1]]
                found.append((i, (xi[j] + (xi[j + 1] - xi[j]) * Ei[j] / (Ei[j] - Ei[j + 1])).tolist()))
                continue
            m = int(np.argmin(np.abs(Ei[1:-1]))) + 1
            e0, e1, e2 = sg * Ei[m - 1], sg * Ei[m], sg * Ei[m + 1]
            curv = e0 - 2 * e1 + e2
            low = e1 - (e2 - e0) ** 2 / (8 * curv) if curv > 0 else e1
            if abs(Ei[m]) <= 1e3 * _EPS * size:
                found.append((i, [xi[m], xi[m]]))  # touching to rounding: a double root
            elif low < 0.5 * e1 or level < 2:  # the parabola is rough on the first levels
                nxt.append((i, xi[m - 1], xi[m + 1], sg, size, low / e1, Ei[m - 1], Ei[m + 1], Ei[m]))
        cand = nxt
    # after 8 levels (4^8 finer) the parabola through the lowest samples still has its minimum at zero
    # or below it: E falls like the square of the distance, a double root or a pair closer than the
    # samples (R = 1 at omega = 0: E is a square; R near 1 under tension: the u and v string modes)
    return found + [(c[0], [0.5 * (c[1] + c[2])] * 2) for c in cand if c[5] <= 1e-3]


def _pair_brackets(evaluate, ps: np.ndarray, dips: list) -> tuple[list[tuple[int, float, float]], list[tuple[int, float]]]:
    """The close pairs at ``dips`` (:func:`close_pairs`) as brackets of single roots: (row, lo, hi) from each
    dip's end to the pair's middle, where E has the other sign; and the pairs that touch (a double root), (row, mu)."""
    split, touching = [], []
    for row, (r1, r2) in close_pairs(evaluate, ps, dips):
        a, b = next(((c[1], c[2]) for c in dips if c[0] == row and c[1] <= r1 and r2 <= c[2]), (r1, r2))
        if r1 == r2:
            touching.append((row, r1))
        elif a < r1 < r2 < b:
            m = 0.5 * (r1 + r2)
            split += [(row, a, m), (row, m, b)]
    return split, touching


class Line:
    """E along one axis ("B" or "omega"; T, P, R, f from params) on a fixed mu grid.

    ``signed``: the roots below 0 are real pairs of eigenvalues (unstable); ``cuts``: (index in the grid,
    side) of each end of the counted interval (+1: roots are counted below it, -1: above it)."""

    signed = True

    def __init__(self, params: RodParameters, axis: str, lo: float, hi: float, route: str = "auto",
                 factor: float = 1.0, shift: int = 0, density: float = 5.0):
        self.params, self.axis, self.route, self.factor, self.shift = params, axis, route, factor, shift
        ends = [params.with_(**{axis: x}) for x in (lo, hi)]
        B_max = max(abs(e.B) for e in ends)
        w_max = max(abs(e.omega) for e in ends)
        self.mu_lo = rayleigh_floor(params, B_max, w_max, params.T)
        self.mu_cut, pos = _positive_grid(params, ends, density)
        # negative side: uniform in sqrt(-mu); positive side: uniform in the Weyl mode count
        neg = -np.linspace(math.sqrt(-self.mu_lo), 0.0, 48, endpoint=False) ** 2
        above = self.mu_cut + (pos[-1] - pos[-2]) * np.arange(1, 4)  # past the cut: dips next to it are seen
        self.mu = np.unique(np.concatenate([neg, [0.0], pos, [self.mu_cut], above]))
        self.cuts = ((int(np.nonzero(self.mu == self.mu_cut)[0][0]), 1),)
        self.evaluations = 0
        self.schur_left = SCHUR_BUDGET

    def frequency(self, x: float) -> float:
        """Omega at the root x of the line's variable."""
        return math.sqrt(abs(x))

    def alternative(self, lo: float, hi: float) -> Line:
        """The second formulation: the Schur route while the exponents span less than 4 decades
        (its error is eps times the largest), else other scales and another split."""
        if _separation(self.params, self.axis, hi) < 1e4:
            return type(self)(self.params, self.axis, lo, hi, route="schur")
        return type(self)(self.params, self.axis, lo, hi, factor=1.37, shift=1)

    def _values(self, p: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, int]:
        return characteristic_counted(self.params, x, **{self.axis: p}, route=self.route, factor=self.factor,
                               shift=self.shift, schur_budget=self.schur_left)

    def E(self, p, mu) -> np.ndarray:
        """E at (axis = p, mu), broadcast."""
        p, mu = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(mu, dtype=float))
        self.evaluations += p.size
        out, slow = self._values(p, mu)
        if self.route == "auto":
            self.schur_left -= slow
        return out

    def samples(self, ps) -> list[_Sample]:
        """The real roots of E on the mu grid at each p of ps (one vectorised evaluation, then
        the close pairs of all rows refined together). Where the stiffness is proven positive
        (:func:`stiffness_positive`: every root real and positive) only the grid from mu = 0 up is sampled."""
        ps = np.atleast_1d(np.asarray(ps, dtype=float))
        start = np.zeros(ps.size, dtype=int)
        if self.signed and self.mu[0] < 0.0:
            B, omega = (ps, self.params.omega) if self.axis == "B" else (self.params.B, ps)
            start[stiffness_positive(self.params, B, omega)] = int(np.searchsorted(self.mu, 0.0))
        rows = np.full((ps.size, self.mu.size), np.nan)
        for first in np.unique(start):
            at = start == first
            rows[at, first:] = self.E(ps[at, None], self.mu[None, first:])
        if not all(np.all(np.isfinite(row[k:])) for row, k in zip(rows, start)):
            raise ArithmeticError(f"characteristic function not finite on the {self.axis} line")
        roots: list[list[float]] = []
        cand = []
        for i, (row, k) in enumerate(zip(rows, start)):
            E, mu = row[k:], self.mu[k:]
            roots.append(_sign_roots(mu, E))
            cand += dips(i, mu, E)
        for i, pair in close_pairs(self.E, ps, cand):
            roots[i] += pair
        out = []
        for p, r, E in zip(ps, roots, rows):
            r = np.sort(np.asarray(r, dtype=float))
            r = r[(r < self.mu_cut) & (r > self.mu_lo)]
            neg = int(np.sum(r < 0)) if self.signed else 0
            out.append(_Sample(float(p), tuple(r.tolist()), neg, r.size - neg,
                               tuple(float(E[i]) for i, _ in self.cuts)))
        return out

    def rechecked(self, poor: _Sample, rich: _Sample) -> _Sample:
        """``poor`` with the pair of real roots that ``rich`` (a neighbouring sample) has and ``poor`` lacks, where a
        fine scan at poor.p finds it, else ``poor``: the u and v roots of a nearly round wire come in pairs closer
        than the grid's samples, and a pair between two samples with no dip at either would look like a fold, two real
        roots turned into a complex pair (R = 0.97 spun at 2.6: a flutter load 0.772 where the collocation spectrum
        first grows past 0.775). The scan: 257 points and the grid's own between the grid points next outside the
        pair's neighbours in ``rich`` (so that poor's roots there, each between two grid points, are counted alike),
        with its dips."""
        r = rich.roots
        if len(r) != len(poor.roots) + 2:
            return poor
        j = _vanishing_pair(rich, poor)
        mu = self.mu
        ia = max(int(np.searchsorted(mu, r[j - 1])) - 1, 0) if j > 0 else 0
        ib = min(int(np.searchsorted(mu, r[j + 2])), mu.size - 1) if j + 2 < len(r) else mu.size - 1
        lo, hi = mu[ia], min(mu[ib], self.mu_cut)
        if self.signed:  # E is only C^1 at mu = 0 (a grid point): each side on its own
            lo, hi = (max(lo, 0.0), hi) if r[j] > 0 else (lo, min(hi, 0.0))
        x = np.union1d(np.linspace(lo, hi, 257), mu[(mu >= lo) & (mu <= hi)])
        E = self.E(np.full(x.size, poor.p), x)
        found = _sign_roots(x, E)
        for _, pair in close_pairs(self.E, np.array([poor.p]), dips(0, x, E)):
            found += pair
        old = [v for v in poor.roots if lo <= v <= hi]
        if len(found) < len(old) + 2:
            return poor
        roots = np.sort(np.array([v for v in poor.roots if not lo <= v <= hi] + found))
        neg = int(np.sum(roots < 0)) if self.signed else 0
        return replace(poor, roots=tuple(roots.tolist()), n_neg=neg, n_pos=roots.size - neg)

    # --- bookkeeping along the line ----------------------------------------------------------

    def cut_crossing(self, a: _Sample, b: _Sample, samples: int = CUT_SAMPLES) -> int:
        """Change of the number of counted roots from a to b that comes through the cuts (each root that
        entered +1, each that left -1). E at a cut is sampled on ``samples`` points between a and b: the
        high modes move together with the load or spin, and two of them can pass a cut between two samples
        of the line, leaving the sign of E there unchanged: those show as a dip of |E| and are split as the
        samples' close pairs are."""
        return int(self.cut_crossings([a, b], samples)[0])

    def cut_crossings(self, smp: list[_Sample], samples: int = CUT_SAMPLES) -> np.ndarray:
        """:meth:`cut_crossing` from each sample to the next, E at each cut in one evaluation for all."""
        ps = np.array([np.linspace(a.p, b.p, samples) for a, b in zip(smp[:-1], smp[1:])])
        out = np.zeros(len(smp) - 1, dtype=int)
        for k, (i, side) in enumerate(self.cuts):
            x = self.mu[i]
            top = self.E(ps.ravel(), np.full(ps.size, x)).reshape(ps.shape)
            top[:, 0] = [a.top[k] for a in smp[:-1]]
            top[:, -1] = [b.top[k] for b in smp[1:]]
            r, j = np.nonzero(np.sign(top[:, :-1]) * np.sign(top[:, 1:]) < 0)
            lo, hi, rows = list(ps[r, j]), list(ps[r, j + 1]), list(r)
            # two roots through the cut between two points (the dense high modes of a fast spin: 209 roots
            # below the cut at omega = 17 of a taut tether; left uncounted, they leave a stability change
            # with no root on the move that cannot be isolated): a dip of |E|, each root of the pair bracketed by
            # the dip's ends and the pair's middle
            candidates = [c for row in range(ps.shape[0]) for c in dips(row, ps[row], top[row])]
            split, _ = _pair_brackets(lambda _, t, x=x: self.E(t, np.full(t.shape, x)), np.zeros(ps.shape[0]), candidates)
            for row, a, b in split:  # a touching pair passes nothing
                lo, hi, rows = lo + [a], hi + [b], rows + [row]
            np.add.at(out, np.asarray(rows, dtype=int),
                      self._through_cut(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float), x, side))
        return out

    def _through_cut(self, pa: np.ndarray, pb: np.ndarray, x: float, side: int) -> np.ndarray:
        """For each root of E at the cut x between pa and pb (arrays): +1 if it enters the counted side as p goes
        from pa to pb, else -1 (side +1: counted below x, -1: above). All roots at once
        (:func:`~etcheck.numerics.optimize.bracketed_roots`, one evaluation of E per pass for all), then the
        sign of dmu/dp = -E_p / E_mu there by central differences."""
        if pa.size == 0:
            return np.zeros(0, dtype=int)
        n = pa.size
        at = np.full(n, x)
        pc = bracketed_roots(lambda p: self.E(p, at), np.minimum(pa, pb), np.maximum(pa, pb))
        hp = 1e-6 * np.maximum(np.abs(pb - pa), 1e-12)
        hm = 1e-6 * abs(x)
        e = self.E(np.concatenate([pc - hp, pc + hp, pc, pc]),
                   np.concatenate([at, at, at - hm, at + hm])).reshape(4, n)
        dx_dp = -((e[1] - e[0]) / (2 * hp)) / ((e[3] - e[2]) / (2 * hm))
        return np.where(dx_dp * np.sign(pb - pa) * side > 0, -1, 1)

    # --- a fold of the real roots: flutter ----------------------------------------------------

    def extremum(self, p: float, mu0: float, sg: float, lo: float, hi: float) -> tuple[float, float]:
        """(mu, sg E) at the local minimum of sg E(., p) next to mu0 in (lo, hi): Newton's method on
        dE/dmu with central differences, bounded minimisation where the curvature has the wrong sign."""
        h = 1e-5 * (hi - lo)
        m = mu0
        for _ in range(40):
            e = sg * self.E(p, np.array([m - h, m, m + h]))
            d1, d2 = (e[2] - e[0]) / (2 * h), (e[2] - 2 * e[1] + e[0]) / h**2
            if not d2 > 0:
                res = minimize_scalar(lambda x: sg * self.E(p, x).item(), bounds=(lo, hi), method="bounded",
                                      options={"xatol": 1e-10 * (hi - lo)})
                return float(res.x), float(res.fun)
            new = min(max(m - d1 / d2, lo + h), hi - h)
            if abs(new - m) <= 1e-9 * (hi - lo):
                m = new
                break
            m = new
        return m, sg * self.E(p, m).item()


class _IsoLine(Line):
    """D+ of :mod:`etcheck.rod.straight.exact.undamped_isotropic` (R = 1) along one axis on a fixed grid in Omega over
    [-Omega_cut, Omega_cut] (Omega_cut^2 the mu cut of :class:`Line`): the rod is stable iff every root of
    D+ is real, so every root counts alike (a real pair of eigenvalues is a complex pair Omega = +-i sigma
    here) and roots enter or leave through both cuts."""

    signed = False

    def __init__(self, params: RodParameters, axis: str, lo: float, hi: float, route: str = "auto",
                 factor: float = 1.0, shift: int = 0, density: float = 5.0):
        self.params, self.axis, self.route, self.factor, self.shift = params, axis, route, factor, shift
        mu_cut, pos = _positive_grid(params, [params.with_(**{axis: x}) for x in (lo, hi)], density)
        om = np.sqrt(pos)
        cut = om[-1]
        above = cut + (om[-1] - om[-2]) * np.arange(1, 4)
        self.mu = np.concatenate([-above[::-1], -om[::-1], [0.0], om, above])
        self.mu_lo, self.mu_cut = -cut, cut
        self.cuts = ((3, -1), (self.mu.size - 4, 1))
        self.evaluations = 0
        self.schur_left = SCHUR_BUDGET

    def frequency(self, x: float) -> float:
        return abs(x)

    def alternative(self, lo: float, hi: float) -> Line:
        """The second formulation: the Schur route (4 x 4, exponents of a scalar problem), or other scales and
        another split where they span more than 4 decades."""
        p = self.params.with_(**{self.axis: hi})
        span = (1.0 + abs(p.T + p.P * p.omega**2) * p.f) ** 0.5 + (abs(p.B) * p.f) ** (1 / 3) + self.mu_cut ** 0.5
        if span < 1e4:
            return _IsoLine(self.params, self.axis, lo, hi, route="schur")
        return _IsoLine(self.params, self.axis, lo, hi, factor=1.37, shift=1)

    def _values(self, p: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, int]:
        return characteristic_plus_counted(self.params, x, **{self.axis: p}, route=self.route, factor=self.factor,
                                    shift=self.shift, schur_budget=self.schur_left)


# --- stability along a line --------------------------------------------------------------------


@dataclass(frozen=True)
class Crossing:
    """A change of stability of the undamped straight rod along a line (dimensionless).

    ``value``: the axis value (B or omega); ``error``: absolute error
    estimate (the distance to the same point from a second formulation of
    E, doubled, plus the root-finder tolerance); ``kind``: "divergence" (a
    root mu through 0) or "flutter" (a fold of two real roots, a Krein
    collision at Omega = sqrt(mu), or its reverse); ``frequency``: Omega
    at the point (0 for divergence); ``to_unstable``: the side past it.
    """

    value: float
    error: float
    kind: str
    frequency: float
    to_unstable: bool
    bracket: tuple[float, float]


@dataclass(frozen=True)
class StabilityLine:
    """Stability of the undamped straight rod on [lo, hi] along ``axis`` (dimensionless).

    ``unstable_at_start``: the state at lo; ``crossings``: every located
    change, in order; ``windows``: the stable intervals (a window reaching
    hi ends at hi); ``pairs_at_hi``: complex pairs of roots mu at hi (to
    anchor a crossing line there); ``evaluations``: characteristic-function
    evaluations spent. Changes closer together than the sample spacing (hi - lo) /
    (samples - 1) can be missed in pairs (a window or an unstable gap
    narrower than that), as in a scan.
    """

    axis: str
    lo: float
    hi: float
    unstable_at_start: bool
    crossings: tuple[Crossing, ...]
    windows: tuple[tuple[float, float], ...]
    pairs_at_hi: int
    evaluations: int

    def unstable_at(self, x: float) -> bool:
        """The state at x in [lo, hi] (at a crossing: the side past it)."""
        state = self.unstable_at_start
        for c in self.crossings:
            if x >= c.value:
                state = c.to_unstable
        return state


def pair_count(s: _Sample, N: int) -> int:
    twice = N - s.n_neg - s.n_pos
    if twice < 0 or twice % 2:
        raise ArithmeticError(f"inconsistent root count at {s.p:.9g}: {N} roots in all, "
                              f"{s.n_neg + s.n_pos} real")
    return twice // 2


def _unstable(s: _Sample, N: int) -> bool:
    return s.n_neg > 0 or pair_count(s, N) > 0


def _separation(params: RodParameters, axis: str, x: float) -> float:
    p = params.with_(**{axis: x})
    ku, kv = wavenumbers(p.R, p.f, np.array([p.B]), *coefficients(p.P, p.R, p.f, p.B, p.omega, p.T, 0.0), 1.0)
    return float(max(ku[0], kv[0]) / max(2 * math.pi, 1.0))


def _static_crossing(params: RodParameters, axis: str, a: float, b: float, rtol: float) -> tuple[float, float] | None:
    """Root of D_static (= E(0)) in (a, b) along axis, and its absolute error (two formulations);
    None without a sign change."""
    base = params.with_(**{axis: 0.0})
    fn, mult = exact.root_function(base, axis, 1.0)
    g = exact.Counter(fn)
    ga, gb = g.many(np.array([a, b]))
    if np.sign(ga) == np.sign(gb):
        return None  # an even number of static points in (a, b): bisect further
    x = brentq(g, a, b, xtol=1e-300, rtol=rtol, maxiter=200)
    route = exact.route_at(base, axis, x, mult)
    g2 = exact.Counter(exact.alternative_function(base, axis, 1.0, x, route))
    x2 = exact.second_opinion(g2, x, rtol)
    return x, (2.0 * (abs(x - x2) + 2 * rtol * abs(x)) if math.isfinite(x2) else math.inf)


def _vanishing_pair(rich: _Sample, poor: _Sample) -> int:
    """Index j of the adjacent pair (j, j + 1) of rich's roots that poor lacks."""
    r, q = np.asarray(rich.roots), np.asarray(poor.roots)
    best, jbest = math.inf, 0
    for j in range(len(r) - 1):
        rest = np.delete(r, [j, j + 1])
        if rest.size != q.size:
            continue
        cost = float(np.sum(np.abs(rest - q))) + 1e-3 * (r[j + 1] - r[j])
        if cost < best:
            best, jbest = cost, j
    return jbest


def _fold_point(line: Line, a: _Sample, b: _Sample, rtol: float) -> tuple[float, float, tuple]:
    """The fold (E = dE/dmu = 0) between samples a and b: Brent on the extremum value."""
    rich, poor = (a, b) if len(a.roots) > len(b.roots) else (b, a)
    j = _vanishing_pair(rich, poor)
    r = rich.roots
    lo = 0.5 * (r[j - 1] + r[j]) if j > 0 else line.mu_lo
    hi = 0.5 * (r[j + 1] + r[j + 2]) if j + 2 < len(r) else line.mu_cut
    if line.signed:  # E is only C^1 at mu = 0
        lo, hi = (max(lo, 0.0), hi) if r[j] > 0 else (lo, min(hi, 0.0))
    mu0 = 0.5 * (r[j] + r[j + 1])
    sg = -float(np.sign(line.E(rich.p, mu0).item()))  # sg E: negative between the pair, positive past the fold
    state = [mu0]

    def e(p: float) -> float:
        m, v = line.extremum(p, state[0], sg, lo, hi)
        state[0] = m
        return v

    p = brentq(e, a.p, b.p, xtol=1e-300, rtol=rtol, maxiter=200)
    return p, state[0], (sg, lo, hi)


def _fold_crossing(line: Line, a: _Sample, b: _Sample, rtol: float) -> tuple[float, float, float]:
    """(value, absolute error, mu) of a fold between a and b, with a second formulation."""
    p, mu, (sg, lo, hi) = _fold_point(line, a, b, rtol)
    alt = line.alternative(min(a.p, b.p), max(a.p, b.p))
    state = [mu]

    def e2(x: float) -> float:
        m, v = alt.extremum(x, state[0], sg, lo, hi)
        state[0] = m
        return v

    d = 1e-13 * max(abs(p), 1e-300)
    x2 = math.nan
    for _ in range(12):
        pa, pb = max(p - d, min(a.p, b.p)), min(p + d, max(a.p, b.p))
        ea, eb = e2(pa), e2(pb)
        if ea * eb <= 0:  # a sign change (False where the second formulation gives no value: widen)
            try:
                x2 = brentq(e2, pa, pb, xtol=max(1e-2 * d, 4 * _EPS * abs(p)), rtol=rtol, maxiter=200)
                break
            except ValueError:  # the tracked extremum jumped to another one between calls: widen
                state[0] = mu
        d *= 10.0
    line.evaluations += alt.evaluations
    err = 2.0 * (abs(p - x2) + 2 * rtol * abs(p)) if math.isfinite(x2) else math.inf
    return p, err, mu


#: Bisections of a fold's bracket before Brent's method (the extremum must stay in its window).
_SHRINK = 5
#: Relative width below which a fold that Brent's method cannot follow is taken as located by bisection of the
#: root counts (its error is the width).
_PINNED = 1e-12


def _locate(line: Line, a: _Sample, Na: int, b: _Sample, Nb: int, rtol: float, depth: int = 0) -> Crossing:
    """The change of stability between samples a and b (bisecting until it is a single event)."""
    ca, cb = pair_count(a, Na), pair_count(b, Nb)
    dneg, dpos, dc = b.n_neg - a.n_neg, b.n_pos - a.n_pos, cb - ca
    to_unstable = _unstable(b, Nb)
    bracket = (a.p, b.p)
    static = None
    if dc == 0 and dneg == -dpos and 0 < abs(dneg) <= 2:
        static = _static_crossing(line.params, line.axis, min(a.p, b.p), max(a.p, b.p), rtol)
    if static is not None:
        return Crossing(*static, CriticalKind.DIVERGENCE, 0.0, to_unstable, bracket)
    fold = abs(dc) == 1 and ((dneg == -2 * dc and dpos == 0) or (dpos == -2 * dc and dneg == 0))
    if fold and depth >= _SHRINK:
        try:
            x, err, mu = _fold_crossing(line, a, b, rtol)
            return Crossing(x, err, CriticalKind.FLUTTER, line.frequency(mu), to_unstable, bracket)
        except ValueError:  # the extremum followed by Brent's method jumped to another one: a narrower bracket
            if abs(b.p - a.p) <= _PINNED * max(abs(a.p), abs(b.p)):  # located by the root counts alone
                rich = a if len(a.roots) > len(b.roots) else b
                j = _vanishing_pair(rich, b if rich is a else a)
                mu = 0.5 * (rich.roots[j] + rich.roots[j + 1])
                return Crossing(0.5 * (a.p + b.p), abs(b.p - a.p), CriticalKind.FLUTTER, line.frequency(mu),
                                to_unstable, bracket)
    if depth > 60:
        raise ArithmeticError(f"could not isolate the change of stability in [{a.p:.12g}, {b.p:.12g}]")
    m = line.samples([0.5 * (a.p + b.p)])[0]
    m = line.rechecked(line.rechecked(m, a), b)
    Nm = Na + line.cut_crossing(a, m)
    if _unstable(m, Nm) != _unstable(a, Na):
        return _locate(line, a, Na, m, Nm, rtol, depth + 1)
    return _locate(line, m, Nm, b, Nb, rtol, depth + 1)


def stability_line(params: RodParameters, axis: str, lo: float, hi: float, anchor: float | None = None,
                   pairs: int = 0, samples: int = 25, rtol: float = 4 * _EPS) -> StabilityLine:
    """Every change of stability of the undamped straight rod on [lo, hi] along ``axis``.

    ``axis``: "B" or "omega" (the other values, T, P, R, f from params;
    gamma is ignored: undamped). ``anchor``: a point of the line where the
    number of complex pairs of roots mu (flutter pairs) is known,
    ``pairs`` (default: lo with none, true at omega = 0 where the problem is
    self-adjoint). Samples the real roots of E on ``samples`` equally
    spaced points, follows the total number of roots below the cut, and
    locates each change of stability between samples exactly: a divergence
    point as a root of E(0) = D_static, a flutter point as the zero of the
    extremum value of E (a fold, E = dE/dmu = 0). For R = 1 the line follows D+ of
    :mod:`etcheck.rod.straight.exact.undamped_isotropic` instead (``pairs``: complex pairs of its roots Omega). Dimensionless.
    """
    if axis not in ("B", "omega"):
        raise ValueError(f"axis must be 'B' or 'omega', got {axis!r}")
    if not hi > lo:
        raise ValueError("the line needs hi > lo")
    anchor = lo if anchor is None else float(anchor)
    return _stability_line(params.with_(gamma=0.0, **{axis: 0.0}), axis, float(lo), float(hi), anchor, int(pairs),
                           int(samples), float(rtol))


@lru_cache(maxsize=256)
def _stability_line(params: RodParameters, axis: str, lo: float, hi: float, anchor: float, pairs: int, samples: int,
                    rtol: float) -> StabilityLine:
    """:func:`stability_line` on params with the axis value and gamma zeroed (neither enters): memoised, as in a
    sweep the spin line at the operating load is the same for every spin of a length."""
    # every static point of the line with a sample just either side: an interval bounded by two static
    # points (between the critical speeds) is never narrower than the sampling
    static = static_roots(params, axis, hi)
    static = static[static > lo]
    near = np.concatenate([static * (1 - 1e-6), static * (1 + 1e-6)])
    ps = np.unique(np.concatenate([np.linspace(lo, hi, samples), [anchor], near[(near > lo) & (near < hi)]]))
    line = (_IsoLine if params.R == 1.0 else Line)(params, axis, lo, hi)
    if line.mu.size > MAX_GRID * (2 if params.R == 1.0 else 1):
        raise ArithmeticError(f"the {axis} line to {hi:.6g} needs {line.mu.size} mu samples per point (more than "
                              f"{MAX_GRID}: too many modes below its cut)")
    smp = line.samples(ps)
    ia = int(np.nonzero(ps == anchor)[0][0])
    N = [0] * len(smp)
    N[ia] = smp[ia].n_neg + smp[ia].n_pos + 2 * pairs
    through = line.cut_crossings(smp)  # from each sample to the next
    for i in range(ia + 1, len(smp)):
        N[i] = N[i - 1] + int(through[i - 1])
    for i in range(ia - 1, -1, -1):
        N[i] = N[i + 1] - int(through[i])
    for i in range(len(smp) - 1):  # a pair of real roots that one sample has and the next lacks: looked for again
        smp[i + 1] = line.rechecked(smp[i + 1], smp[i])
        smp[i] = line.rechecked(smp[i], smp[i + 1])
    flags = [_unstable(s, n) for s, n in zip(smp, N)]
    crossings = [_locate(line, smp[i], N[i], smp[i + 1], N[i + 1], rtol)
                 for i in range(len(smp) - 1) if flags[i] != flags[i + 1]]
    windows = stable_windows(crossings, lo, hi, bool(flags[0]))
    return StabilityLine(axis, float(lo), float(hi), bool(flags[0]), tuple(crossings), tuple(windows),
                         pair_count(smp[-1], N[-1]), line.evaluations)


def static_roots(params: RodParameters, axis: str, upto: float, n: int = 400) -> np.ndarray:
    """The static points (roots of D_static) on axis in (0, upto] that change its sign on a grid of n,
    each refined by Brent's method to 1e-9 (sample positions of the lines, not critical values). Read-only."""
    return _static_roots_of(params.with_(gamma=0.0, **{axis: 0.0}), axis, float(upto), int(n))


@lru_cache(maxsize=256)
def _static_roots_of(params: RodParameters, axis: str, upto: float, n: int) -> np.ndarray:
    fn, _ = exact.root_function(params, axis, 1.0)
    x = np.linspace(0.0, upto, n + 1)[1:]
    g = fn(x)
    i = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]
    lo, hi = list(x[i]), list(x[i + 1])
    # a close pair between two samples (R near 1: the u and v modes' static points, 0.43 apart at B = 318 of a taut
    # tether, its 400 samples 0.8 apart) shows as a dip of |D|: split as the lines split theirs, each root then
    # bracketed by the dip's ends and the pair's middle, where D has the other sign
    split, touching = _pair_brackets(lambda _, t: fn(t.ravel()).reshape(t.shape), np.zeros(1), dips(0, x, g))
    lo += [a for _, a, _ in split]
    hi += [b for _, _, b in split]
    # all brackets at once (Chandrupatla, one evaluation of fn per step on the unfinished ones)
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    out = find_root(fn, (lo, hi), tolerances={"xrtol": 1e-9}).x if lo.size else np.zeros(0)
    out = np.sort(np.concatenate([out, [r for _, r in touching]]))
    out.setflags(write=False)
    return out
