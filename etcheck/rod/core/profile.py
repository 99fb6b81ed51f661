"""A profile along the tether: a dimensionless function of s, the fraction of the length from the lower end,
continuous and piecewise smooth (the current I(s)/I_max, the tension T(s)/T_max of docs/model.md section 10).
numpy only."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as cheb

__all__ = ["Profile"]


@dataclass(frozen=True)
class Profile:
    """A continuous function on [0, 1] (s from the lower end, as a fraction of the length), piecewise
    smooth: on each piece [breaks[i], breaks[i + 1]] a Chebyshev series (the piece mapped to
    [-1, 1]) with coefficients ``coefficients[i]``. Breaks are where derivatives may jump (kinks):
    the collocation puts subdomain edges there. Dimensionless; hashable."""

    breaks: tuple[float, ...]
    coefficients: tuple[tuple[float, ...], ...]

    def __post_init__(self) -> None:
        b = np.asarray(self.breaks, dtype=float)
        if b.size < 2 or b[0] != 0.0 or b[-1] != 1.0 or np.any(np.diff(b) <= 0):
            raise ValueError(f"profile breaks must rise from 0 to 1, got {self.breaks!r}")
        if len(self.coefficients) != b.size - 1 or any(len(c) == 0 for c in self.coefficients):
            raise ValueError("a profile needs one non-empty coefficient series per piece")
        if not all(math.isfinite(x) for c in self.coefficients for x in c):
            raise ValueError("profile coefficients must be finite")

    @classmethod
    def uniform(cls, value: float = 1.0) -> Profile:
        return cls((0.0, 1.0), ((float(value),),))

    @classmethod
    def piecewise_linear(cls, at, values) -> Profile:
        """The piecewise-linear interpolant of ``values`` at the points ``at`` (from 0 to 1, rising)."""
        at, values = np.asarray(at, dtype=float), np.asarray(values, dtype=float)
        if at.size < 2 or at.size != values.size:
            raise ValueError("a piecewise-linear profile needs as many values as points, at least two")
        coeffs = tuple((0.5 * (a + b), 0.5 * (b - a)) for a, b in zip(values[:-1], values[1:]))
        return cls(tuple(float(x) for x in at), coeffs)

    @classmethod
    def from_function(cls, fn, breaks=(0.0, 1.0), degree: int = 32) -> Profile:
        """Chebyshev interpolants of degree ``degree`` of a smooth vectorised function on each piece."""
        coeffs = []
        for a, b in zip(breaks[:-1], breaks[1:]):
            c = cheb.chebinterpolate(lambda x, a=a, b=b: fn(a + 0.5 * (b - a) * (x + 1.0)), degree)
            coeffs.append(tuple(float(x) for x in c))
        return cls(tuple(float(x) for x in breaks), tuple(coeffs))

    @property
    def uniform_value(self) -> float | None:
        """The constant value of a uniform profile, else None."""
        if len(self.coefficients) == 1 and all(x == 0.0 for x in self.coefficients[0][1:]):
            return self.coefficients[0][0]
        return None

    def _pieces(self, s: np.ndarray):
        s = np.asarray(s, dtype=float)
        i = np.clip(np.searchsorted(self.breaks, s, side="right") - 1, 0, len(self.coefficients) - 1)
        a = np.asarray(self.breaks)[i]
        h = np.asarray(self.breaks)[i + 1] - a
        return s, i, 2.0 * (s - a) / h - 1.0, h

    def __call__(self, s) -> np.ndarray:
        s, i, x, _ = self._pieces(s)
        out = np.empty_like(s)
        for j, c in enumerate(self.coefficients):
            m = i == j
            out[m] = cheb.chebval(x[m], c)
        return out

    def derivative(self, s) -> np.ndarray:
        """d/ds of the profile (one-sided at the breaks: the piece to the right, the last one at 1)."""
        s, i, x, h = self._pieces(s)
        out = np.empty_like(s)
        for j, c in enumerate(self.coefficients):
            m = i == j
            out[m] = cheb.chebval(x[m], cheb.chebder(np.asarray(c))) * 2.0 / h[m] if len(c) > 1 else 0.0
        return out

    def scaled(self, factor: float) -> Profile:
        return Profile(self.breaks, tuple(tuple(factor * x for x in c) for c in self.coefficients))

    def reversed(self) -> Profile:
        """The same profile seen from the other end, p(1 - s)."""
        flip = tuple(tuple(x * (-1.0) ** k for k, x in enumerate(c)) for c in self.coefficients[::-1])
        return Profile(tuple(1.0 - x for x in self.breaks[::-1]), flip)

    def extremes(self, n: int = 2049) -> tuple[float, float]:
        """(min, max) on [0, 1], sampled (every break and n points)."""
        s = np.unique(np.concatenate([np.linspace(0.0, 1.0, n), self.breaks]))
        v = self(s)
        return float(v.min()), float(v.max())
