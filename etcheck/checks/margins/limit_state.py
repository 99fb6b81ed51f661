"""P(margin < required) of one margin as an integral over independent standard-normal coordinates.

Each uncertain input x_j is a monotone function of one standard-normal
coordinate z_j (Phi(z_j) = F_j(x_j): :meth:`etcheck.input.uncertainty.Distribution.from_normal`,
exact into the far tails). The margin factors exactly
(:meth:`etcheck.checks.margins.margin_model.MarginModel.powers`):

    ln m(z) = ln M(z_shape) + sum_j a_j ln(x_j(z_j) / x_j0)

where M is computed by the check's route at the "shape" inputs and the
"power" inputs enter as exact powers (inputs that provably do not move the
margin are left out). Lognormal power inputs without bounds add up to one
normal term sigma z (sigma^2 = sum a_j^2 sigma_j^2), one coordinate.

**Conditioning.** One coordinate c is integrated exactly: given the others,
P(fail | z_rest) = Phi(+-zeta), zeta the value of z_c where the margin equals
the required margin: in closed form when c is a power input, at a root of the
margin along z_c when c is a shape input (the secant method from the root of
the nearest point solved before, else a bracket and Brent's method, to 1e-10
in z; the margin is taken monotone along c, which the search checks on the
points it visits). Which coordinate: :mod:`etcheck.checks.margins.probability`
chooses. Conditional probabilities are returned in logarithms (log Phi) so
that 1e-300 keeps its relative accuracy, with their own error: a relative
margin error eps moves ln m by eps, and the root by eps / |d ln m / dz|.

Margins at shape inputs are solved once per distinct point (remembered), a
batch of many shared with a forked helper (:func:`etcheck.runtime.parallel.split_map`).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from etcheck.checks.margins.margin_model import MarginModel
from etcheck.input.uncertainty import Distribution
from etcheck.numerics.chebyshev import lobatto_weights
from etcheck.numerics.optimize import brentq
from etcheck.numerics.quadrature import CAP
from etcheck.runtime.parallel import split_map

#: Absolute tolerance of a root in standard-normal coordinates (its effect on P: phi(zeta) x 1e-10).
ROOT_XTOL = 1e-10
#: Margin evaluations per batch above which they are shared with a forked helper (one core's worth: ~50 ms).
_PARALLEL_FROM = 8


class NotAnswered(Exception):
    """A margin at some sample could not be computed by the check's route (the message says why)."""


@dataclass(frozen=True)
class Coordinate:
    """One standard-normal coordinate: a shape input (``power`` None: the margin is re-evaluated), a power input
    (margin ∝ x^power exactly) or the merged lognormal power inputs (``sigma``: their term sigma z in ln m)."""

    name: str
    dist: Distribution | None
    power: float | None = None
    sigma: float = 0.0
    x0: float = 1.0  # the margin model's nominal value of the input (SI; 1 for bending_stiffness)

    @property
    def shape(self) -> bool:
        return self.dist is not None and self.power is None

    def value(self, z) -> np.ndarray:
        """The input's value (SI, or a factor for bending_stiffness) at z (shape coordinates)."""
        x = self.dist.from_normal(z)
        return x * self.x0 if self.dist.factor and self.name != "bending_stiffness" else x

    def term(self, z) -> np.ndarray:
        """Its term a ln(x / x0) of ln m at z (power coordinates)."""
        z = np.asarray(z, dtype=float)
        if self.dist is None:
            return self.sigma * z
        x = self.dist.from_normal(z)
        ratio = x if self.dist.factor else x / self.x0
        with np.errstate(divide="ignore"):
            return self.power * np.log(ratio)

    def z_at(self, t) -> np.ndarray:
        """z where the term equals t (vectorised; +-inf beyond the ends of the support)."""
        t = np.asarray(t, dtype=float)
        if self.dist is None:
            return t / self.sigma
        with np.errstate(over="ignore"):
            ratio = np.exp(t / self.power)
        return self.dist.to_normal(ratio if self.dist.factor else ratio * self.x0)

    @property
    def spread(self) -> float:
        """How far it moves ln m per unit z (about): |a| x the log spread of the input."""
        if self.dist is None:
            return self.sigma
        return abs(self.power or 0.0) * self.dist.log_spread()


@dataclass
class LimitState:
    """The margin ``kind`` of ``model`` against its required margin over the coordinates ``coords``;
    ``cond`` indexes the coordinate integrated exactly, the others (``outer``, in order) are integrated or
    sampled. ``rising``: for a shape conditioning coordinate, whether the margin grows with it.
    ``evaluations``: margin evaluations so far (each one solve of the check's route; ``seconds`` their wall
    time). ``surrogate``: a degree N: with one shape coordinate, ln M is then the polynomial interpolant of its
    values at the N + 1 Chebyshev-Lobatto points over +-CAP; with a shape coordinate conditioned on and one
    outer coordinate, the root along it is the interpolant of its roots there (:meth:`lobatto_solve`)."""

    model: MarginModel
    kind: str
    coords: list[Coordinate]
    cond: int
    rising: bool = True
    evaluations: int = 0
    seconds: float = 0.0
    not_monotone: bool = False
    surrogate: int | None = None
    _memo: dict = field(default_factory=dict)
    _roots: dict = field(default_factory=dict)
    _lobatto_roots: dict = field(default_factory=dict)
    _found: dict = field(default_factory=dict)

    @property
    def outer(self) -> list[int]:
        return [i for i in range(len(self.coords)) if i != self.cond]

    @property
    def roots_found(self) -> int:
        """Roots of the margin along the conditioning coordinate found so far."""
        return len(self._roots)

    @property
    def log_required(self) -> float:
        return math.log(self.model.required)

    # ------------------------------------------------------------------ the margin at shape inputs

    def _key(self, zrow: np.ndarray) -> tuple:
        return tuple(float(zrow[i]) for i, c in enumerate(self.coords) if c.shape)

    def _inputs(self, key: tuple) -> dict[str, float]:
        shape = [c for c in self.coords if c.shape]
        changes = {c.name: float(c.value(z)) for c, z in zip(shape, key)}
        return self.model.values(changes)

    def log_margins(self, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ln M and its relative error at the shape coordinates of every row of Z (full coordinates; power
        inputs at their nominal values), each distinct point computed once (remembered)."""
        if self.surrogate is not None:
            return self._interpolated(Z[:, next(i for i, c in enumerate(self.coords) if c.shape)], self.surrogate)
        return self._solved(Z)

    def _solved(self, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ln M and its relative error solved by the check's route at every row of Z (remembered)."""
        if not any(c.shape for c in self.coords):  # one margin for every row
            lnM, e = self._memo[()] if () in self._memo else self._remember([()])[()]
            return np.full(len(Z), lnM), np.full(len(Z), e)
        keys = [self._key(row) for row in Z]
        self._remember(list(dict.fromkeys(k for k in keys if k not in self._memo)))
        out = np.array([self._memo[k] for k in keys]).reshape(len(keys), 2)
        return out[:, 0], out[:, 1]

    def _remember(self, todo: list[tuple]) -> dict:
        """Solve the margin at the shape points ``todo`` (shared with a forked helper when there are many)."""
        if todo:
            started = time.perf_counter()
            got = split_map(self._one, todo) if len(todo) >= _PARALLEL_FROM else [self._one(k) for k in todo]
            self.seconds += time.perf_counter() - started
            self.evaluations += len(todo)
            for k, m in zip(todo, got):
                if not m.answered:
                    raise NotAnswered(m.why)
                self._memo[k] = (_log(m.value), m.error)
        return self._memo

    def lobatto_solve(self, N: int) -> bool:
        """At the N + 1 Chebyshev-Lobatto points over [-CAP, CAP] (those of N / 2 among them): with a power input
        conditioned on, ln M along the one shape coordinate; with a shape input conditioned on, its roots along
        the one outer coordinate. Whether all are finite (else no interpolant)."""
        from etcheck.numerics.chebyshev import lobatto_nodes

        if not self.coords[self.cond].shape:
            values, _ = self._solved(self._lobatto_rows(N))
            return bool(np.all(np.isfinite(values)))
        Z = np.zeros((N + 1, len(self.coords)))
        Z[:, self.outer[0]] = -CAP + 2 * CAP * lobatto_nodes(N)
        self._lobatto_roots[N] = found = self._root_rows(Z)
        return all(r.root is not None and math.isfinite(r.dz) for r in found)

    def _lobatto_rows(self, N: int) -> np.ndarray:
        from etcheck.numerics.chebyshev import lobatto_nodes

        Z = np.zeros((N + 1, len(self.coords)))
        Z[:, next(i for i, c in enumerate(self.coords) if c.shape)] = -CAP + 2 * CAP * lobatto_nodes(N)
        return Z

    def _interpolated(self, z: np.ndarray, N: int) -> tuple[np.ndarray, np.ndarray]:
        """ln M by the degree-N interpolant (the margins solved by :meth:`lobatto_margins`), and the largest error
        of those margins."""
        from etcheck.numerics.chebyshev import lobatto_nodes, resample_matrix

        values, err = self._solved(self._lobatto_rows(N))
        at = (np.asarray(z, float) + CAP) / (2 * CAP)
        return resample_matrix(lobatto_nodes(N), at, lobatto_weights(N)) @ values, np.full(len(at), np.max(err))

    def _one(self, key: tuple):
        return self.model.margin(self._inputs(key), self.kind)

    # ------------------------------------------------------------------ conditional probabilities

    def power_sum(self, Z: np.ndarray, skip: int | None = None) -> np.ndarray:
        """sum of the power terms of every row (full coordinates), leaving out coordinate ``skip``."""
        s = np.zeros(len(Z))
        for i, c in enumerate(self.coords):
            if not c.shape and i != skip:
                s = s + c.term(Z[:, i])
        return s

    def log_conditional(self, Zo: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ln P(fail | outer coordinates) for every row of Zo (columns in the order of ``outer``) and ln of its
        own error bound (from the margins' errors and the root tolerance)."""
        Z = np.zeros((len(Zo), len(self.coords)))
        Z[:, self.outer] = Zo
        if not self.coords[self.cond].shape:
            return self._closed_conditional(Z)
        if self.surrogate is not None:
            return self._interpolated_boundary(Zo[:, 0], self.surrogate)
        found = self._root_rows(Z)
        return np.array([r.log_p for r in found]), np.array([r.log_error for r in found])

    def _root_rows(self, Z: np.ndarray) -> list[_Root]:
        """The conditional probabilities at the roots of every row of Z (full coordinates), shared with a forked
        helper when there are many; what it learnt (roots, evaluations, seconds) is learnt here too."""
        rows = list(Z)
        evaluations, seconds = self.evaluations, self.seconds
        found = split_map(self._root_conditional, rows) if len(rows) >= _PARALLEL_FROM else \
            [self._root_conditional(r) for r in rows]
        self.evaluations = evaluations + sum(r.evaluations for r in found)  # those of a forked helper too
        self.seconds = seconds + sum(r.seconds for r in found)
        for r in found:
            self.not_monotone |= r.not_monotone
            self._found[r.key] = r
            if r.root is not None:
                self._roots[r.key] = (r.root, r.slope)
        return found

    def _interpolated_boundary(self, z: np.ndarray, N: int) -> tuple[np.ndarray, np.ndarray]:
        """ln P(fail | z) with the root along the conditioning coordinate interpolated in the one outer
        coordinate z (degree N, :meth:`lobatto_solve`), and ln of its error (the largest root error)."""
        from scipy import special

        from etcheck.numerics.chebyshev import lobatto_nodes, resample_matrix

        found = self._lobatto_roots[N]
        roots = np.array([r.root for r in found])
        zeta = resample_matrix(lobatto_nodes(N), (np.asarray(z, float) + CAP) / (2 * CAP), lobatto_weights(N)) @ roots
        dz = max(r.dz for r in found)
        with np.errstate(divide="ignore"):
            log_err = -0.5 * zeta**2 - 0.5 * math.log(2 * math.pi) + math.log(dz)
        return special.log_ndtr(zeta if self.rising else -zeta), log_err

    def _closed_conditional(self, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        from scipy import special

        c = self.coords[self.cond]
        lnM, err = self.log_margins(Z)
        t = self.log_required - lnM - self.power_sum(Z, skip=self.cond)
        sign = 1.0 if (c.power if c.dist is not None else 1.0) > 0 else -1.0

        def log_p(tt):
            with np.errstate(invalid="ignore"):
                return special.log_ndtr(sign * np.nan_to_num(c.z_at(tt), nan=-np.inf * sign))

        lp = log_p(t)
        moved = np.maximum(np.abs(np.exp(log_p(t + err)) - np.exp(lp)), np.abs(np.exp(log_p(t - err)) - np.exp(lp)))
        with np.errstate(divide="ignore"):
            return lp, np.log(moved)

    def _root_conditional(self, row: np.ndarray) -> _Root:
        """ln P(fail | row) at the root of the margin along the shape conditioning coordinate (secant from the
        nearest root found before, else a bracket and Brent's method), and ln of its error."""
        from scipy import special

        key = tuple(float(row[i]) for i in self.outer)
        if key in self._found:  # solved before (a quadrature's point, an interpolation node)
            return replace(self._found[key], evaluations=0, seconds=0.0)
        before, spent = self.evaluations, self.seconds
        c = self.cond
        rest = float(self.power_sum(row[None, :])[0])
        seen: list[tuple[float, float, float]] = []

        def g(z: float) -> float:
            r = row.copy()
            r[c] = z
            lnM, e = self.log_margins(r[None, :])
            val = float(np.clip(lnM[0] + rest - self.log_required, -1e3, 1e3))
            seen.append((z, val, float(e[0])))
            return val

        root = self._secant(g, key)
        if root is None:
            bracket = self._bracket(g, self._guess(key)[0])
            if bracket is None:  # no root inside +-CAP: failing everywhere or nowhere, to within Phi(-CAP)
                return _Root(key, 0.0 if seen[0][1] < 0 else -math.inf, math.log(0.5 * math.erfc(CAP / math.sqrt(2))),
                             self.evaluations - before, self.seconds - spent, _monotone(seen, self.rising))
            root = brentq(g, *bracket, xtol=ROOT_XTOL, rtol=4 * np.finfo(float).eps)
        slope = _slope(seen, root) or self._guess(key)[1]  # (one point seen: the root of a neighbour, reused)
        self._roots[key] = (root, slope)
        err = max(e for _, _, e in seen[-3:])
        dz = ROOT_XTOL + (err / abs(slope) if slope != 0 else math.inf)
        lp = float(special.log_ndtr(root if self.rising else -root))
        log_err = -0.5 * root**2 - 0.5 * math.log(2 * math.pi) + math.log(dz) if math.isfinite(dz) else 0.0
        return _Root(key, lp, log_err, self.evaluations - before, self.seconds - spent, _monotone(seen, self.rising),
                     root, slope, dz)

    def conditioned_on(self, cond: int, rising: bool) -> LimitState:
        """The same limit state integrated exactly along coordinate ``cond`` instead (``rising``: whether the
        margin grows along it), keeping the margins solved so far and their count."""
        return replace(self, cond=cond, rising=rising, _roots={}, _lobatto_roots={}, _found={})

    def rises_along_cond(self) -> bool:
        """Whether the margin grows along the (shape) conditioning coordinate: compared at z = -+0.5 there, the
        others at 0 (two margin evaluations)."""
        Z = np.zeros((2, len(self.coords)))
        Z[:, self.cond] = (-0.5, 0.5)
        lnM, _ = self.log_margins(Z)
        return bool(lnM[1] >= lnM[0])

    def _guess(self, key: tuple) -> tuple[float, float]:
        """A first point for the root and the slope of ln m there: those of the nearest outer point solved
        before, else (0, 0: unknown)."""
        if not self._roots:
            return 0.0, 0.0
        near = min(self._roots, key=lambda k: sum((a - b) ** 2 for a, b in zip(k, key)))
        return self._roots[near]

    def _secant(self, g, key: tuple) -> float | None:
        """The root by the secant method from the nearest root found before and the slope there (a few
        evaluations where the boundary moves smoothly with the outer point); None where there is none to start
        from or it does not settle inside +-CAP in 8 steps."""
        from scipy.optimize import root_scalar

        z0, slope = self._guess(key)
        sign = 1.0 if self.rising else -1.0
        if not sign * slope > 0:  # no neighbour's root (or slope) to start from: bracket instead
            return None
        f0 = g(z0)
        if f0 == 0:
            return z0
        try:
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # a flat step: reported as not converged
                res = root_scalar(g, method="secant", x0=z0, x1=z0 + float(np.clip(-f0 / slope, -0.5, 0.5)),
                                  xtol=ROOT_XTOL, rtol=4 * np.finfo(float).eps, maxiter=8)
        except (ArithmeticError, ValueError):
            return None
        return float(res.root) if res.converged and abs(res.root) <= CAP and math.isfinite(res.root) else None

    def _bracket(self, g, z0: float) -> tuple[float, float] | None:
        """A sign change of g next to z0 within [-CAP, CAP], stepping away from z0 (steps 0.25, doubling)
        in the direction the monotone margin points to; None if g keeps its sign to the end."""
        f0 = g(z0)
        if f0 == 0:
            return (z0, z0 + 1e-12)
        # g rises with z if the margin rises: below the root g < 0
        direction = (1.0 if f0 < 0 else -1.0) * (1.0 if self.rising else -1.0)
        step, z = 0.25, z0
        while abs(z) < CAP:
            z_next = float(np.clip(z + direction * step, -CAP, CAP))
            f = g(z_next)
            if (f < 0) != (f0 < 0) or f == 0:
                return (min(z, z_next), max(z, z_next))
            z, step = z_next, 2 * step
        return None



@dataclass(frozen=True)
class _Root:
    """One conditional probability found at a root: its outer point (``key``), ln P and ln of its error, the
    evaluations and seconds it took, whether the margin looked monotone, the root and the slope of ln m there."""

    key: tuple
    log_p: float
    log_error: float
    evaluations: int
    seconds: float
    not_monotone: bool
    root: float | None = None
    slope: float = 0.0
    dz: float = math.inf


def _monotone(seen: list, rising: bool) -> bool:
    """True where the margins seen along the line are NOT monotone in the expected direction."""
    pts = sorted(seen)
    vals = np.array([v for _, v, _ in pts])
    d = np.diff(vals) * (1.0 if rising else -1.0)
    return bool(np.any(d < -1e-9 * np.maximum(1.0, np.abs(vals[1:]))))


def _slope(seen: list, root: float) -> float:
    """d ln m / dz at the root from the two points seen closest to it (0: unknown)."""
    pts = sorted(seen, key=lambda p: abs(p[0] - root))[:2]
    if len(pts) < 2 or pts[0][0] == pts[1][0]:
        return 0.0
    return (pts[0][1] - pts[1][1]) / (pts[0][0] - pts[1][0])


def _log(x: float) -> float:
    return -math.inf if x <= 0 else math.inf if math.isinf(x) else math.log(x)
