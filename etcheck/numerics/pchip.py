"""Monotone piecewise-cubic Hermite interpolation (PCHIP) in numpy alone.

The interpolant of ``scipy.interpolate.PchipInterpolator`` (Fritsch & Carlson's
monotone slopes: zero at a local extremum of the data, else the weighted
harmonic mean of the neighbouring secants; the three-point end slopes of
Fritsch & Butland, limited so that they keep the secant's sign and, next to an
extremum, stay within three times it): the same values to round-off (tested
against scipy). Written here because importing ``scipy.interpolate`` takes
up to a second (it loads scipy.optimize and scipy's docstring machinery), more than
a report process spends drawing a diagram's branches with it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Pchip"]


def _end_slope(h0: float, h1: float, m0: float, m1: float) -> float:
    """The three-point slope at an end (h0, m0: the end interval and its secant; h1, m1: the next one), limited."""
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if np.sign(d) != np.sign(m0):
        return 0.0
    if np.sign(m0) != np.sign(m1) and abs(d) > 3.0 * abs(m0):
        return 3.0 * m0
    return d


def _slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    h = np.diff(x)
    m = np.diff(y) / h
    if x.size == 2:  # one interval: the straight line
        return np.array([m[0], m[0]])
    d = np.zeros_like(y)
    w1 = 2.0 * h[1:] + h[:-1]
    w2 = h[1:] + 2.0 * h[:-1]
    extremum = (np.sign(m[1:]) != np.sign(m[:-1])) | (m[1:] == 0.0) | (m[:-1] == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = (w1 + w2) / (w1 / m[:-1] + w2 / m[1:])
    d[1:-1] = np.where(extremum, 0.0, mean)
    d[0] = _end_slope(h[0], h[1], m[0], m[1])
    d[-1] = _end_slope(h[-1], h[-2], m[-1], m[-2])
    return d


@dataclass(frozen=True)
class Pchip:
    """The PCHIP interpolant through (x, y): x strictly increasing (at least two points), y finite.

    Called with points inside [x[0], x[-1]] (outside, the end cubics are extended)."""

    x: np.ndarray
    y: np.ndarray
    slopes: np.ndarray

    @classmethod
    def through(cls, x, y) -> Pchip:
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        if x.ndim != 1 or x.shape != y.shape or x.size < 2 or not np.all(np.diff(x) > 0):
            raise ValueError("PCHIP needs at least two points with strictly increasing x")
        return cls(x, y, _slopes(x, y))

    def __call__(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(self.x, t, side="right") - 1, 0, self.x.size - 2)
        h = self.x[k + 1] - self.x[k]
        s = (t - self.x[k]) / h
        y0, y1 = self.y[k], self.y[k + 1]
        d0, d1 = self.slopes[k] * h, self.slopes[k + 1] * h
        # cubic Hermite basis in the interval's own coordinate s in [0, 1]
        return y0 + s * (d0 + s * (3.0 * (y1 - y0) - 2.0 * d0 - d1 + s * (2.0 * (y0 - y1) + d0 + d1)))
