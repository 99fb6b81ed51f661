"""The taut-string limit of the bowed tether (dimensionless, f-scaling; lengths in units of the tether's length L).

A string (no bending stiffness) carrying one current in the field B b (:mod:`etcheck.rod.bowed.field`) has
n' = -B t x b with n = tau t: tau' = 0 and t' = (B / tau) b x t. Its tangent precesses about b at the rate
k = B / tau per unit length, at a constant angle theta to b: the centreline is a helix about b of curvature
k sin(theta) and torsion k cos(theta) (Pelaez et al., AAS 99-194; Beletsky & Levin 1993). Its arc length is 1 and
its chord is e3 (both ends on the chord): the chord of one unit of helix, cos(theta) b + sin(theta) q w with
q = sin(k/2)/(k/2), makes the angle alpha with b, so tan(theta) = tan(alpha) / q. The end force along the chord is
T = tau t(0) . e3, with t(0) . e3 = (cos^2 theta + q cos(k/2) sin^2 theta) / |chord|.

Field across the chord (alpha = 90 deg): theta = 90 deg, a circular arc of radius rho = 1/k that solves
rho cos(1/(2 rho)) = T/B, chord 2 rho sin(1/(2 rho)). Bending stiffness adds end layers of width sqrt(R/(f T))
(:func:`etcheck.rod.bowed.statics.end_layer`); away from them the rod follows the string.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from etcheck.numerics.optimize import brentq

__all__ = ["Helix", "arc_radius", "helix"]


@dataclass(frozen=True)
class Helix:
    """The taut string's centreline: precession rate ``k`` = B/tau, angle ``theta`` (rad) between tangent and
    field, ``curvature`` k sin(theta), ``torsion`` k cos(theta), tension ``tau`` (|F| along the string), ``chord``
    (distance between the ends), ``bow`` (largest distance from the chord; alpha = 90 deg only, else nan)."""

    k: float
    theta: float
    curvature: float
    torsion: float
    tau: float
    chord: float
    bow: float


def _end_cosine(k: float, alpha: float) -> tuple[float, float, float]:
    """(t(0) . e3, theta, |chord|) of a unit helix of precession k whose chord makes the angle alpha with b."""
    q = math.sin(0.5 * k) / (0.5 * k) if k > 0 else 1.0
    theta = math.atan2(math.sin(alpha), q * math.cos(alpha))
    c = math.hypot(math.cos(theta), q * math.sin(theta))
    return (math.cos(theta) ** 2 + q * math.cos(0.5 * k) * math.sin(theta) ** 2) / c, theta, c


def helix(T: float, B: float, alpha: float) -> Helix:
    """The taut string of unit length under end force T along the chord and field load B at angle alpha (rad)
    to the chord (one current; T > 0, B > 0, the precession k = B/tau below pi, the half turn)."""
    if T <= 0 or B <= 0:
        raise ValueError(f"the taut string needs T > 0 and B > 0, got T = {T}, B = {B}")
    k = brentq(lambda k: B / k * _end_cosine(k, alpha)[0] - T, 1e-12 * B / T, math.pi * (1.0 - 1e-12), xtol=1e-15)
    cos0, theta, c = _end_cosine(k, alpha)
    bow = (1.0 - math.cos(0.5 * k)) / k if abs(math.sin(alpha)) == 1.0 else math.nan
    return Helix(k=k, theta=theta, curvature=k * math.sin(theta), torsion=k * math.cos(theta), tau=B / k,
                 chord=c, bow=bow)


def arc_radius(T: float, B: float) -> float:
    """The radius rho of the circular arc of a taut string across the field: rho cos(1/(2 rho)) = T/B."""
    return brentq(lambda rho: rho * math.cos(0.5 / rho) - T / B, 1.0 / math.pi, T / B + 1.0, xtol=1e-15)
