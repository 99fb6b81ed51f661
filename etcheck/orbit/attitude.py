"""Tether attitude: local vertical with bounded libration, and the axial field
(the component of B along the tether) nominal and worst over the libration set.

Directions. In the local orbital frame (up u, along-track a, cross-track c =
orbit normal) a tether at pitch theta (in-plane libration, about the orbit
normal, positive towards the direction of motion) and roll phi (out-of-plane
libration, positive towards the orbit normal) points along

    t(theta, phi) = cos(phi) (cos(theta) u + sin(theta) a) + sin(phi) c.

Libration bounds |theta| <= Theta, |phi| <= Phi (0 <= Theta, Phi < 90 deg)
make a curved rectangle S of unit vectors ("the libration cone").

Worst case, exactly. With b = (b_u, b_a, b_c) the field in the local frame,
max over S of |b . t| = max(F(b), F(-b)) with F(b) = max over S of b . t. The
map (theta, phi) -> t is a local diffeomorphism for |phi| < 90 deg, and the
only critical points of the linear function b . t on the sphere are +-b/|b|.
So F(b) is attained

1. in the interior, at t = b/|b| (value |b|), if its pitch atan2(b_a, b_u)
   and roll asin(b_c/|b|) are within the bounds; or
2. on an edge theta = +-Theta: A cos(phi) + b_c sin(phi), A = b_u cos(Theta)
   +- b_a sin(Theta), a sinusoid in phi whose peak atan2(b_c, A) counts if
   within [-Phi, Phi] (value hypot(A, b_c)); or
3. on an edge phi = +-Phi: cos(Phi) hypot(b_u, b_a) cos(theta - atan2(b_a, b_u))
   +- b_c sin(Phi), peak counted if atan2(b_a, b_u) is within [-Theta, Theta];
   or
4. at a corner (+-Theta, +-Phi).

:func:`worst_axial` takes the largest of these candidates (no search, no
grid); it is checked against a brute-force grid of directions in the tests.

Units: angles in radians, fields in tesla.
"""

from __future__ import annotations

import numpy as np


def tether_direction(radial, along_track, cross_track, pitch, roll) -> np.ndarray:
    """Unit tether direction(s) t(pitch, roll) from the local frame vectors (n, 3)."""
    pitch = np.asarray(pitch, dtype=float)[..., None]
    roll = np.asarray(roll, dtype=float)[..., None]
    return np.cos(roll) * (np.cos(pitch) * radial + np.sin(pitch) * along_track) + np.sin(roll) * cross_track


def axial_component(b_up, b_along, b_cross, pitch=0.0, roll=0.0) -> np.ndarray:
    """b . t(pitch, roll) from local components (the nominal axial field at 0, 0)."""
    return np.cos(roll) * (b_up * np.cos(pitch) + b_along * np.sin(pitch)) + b_cross * np.sin(roll)


def _max_linear(bu, ba, bc, Th, Ph):
    """max over the libration set of b . t, with its (pitch, roll): arrays (n,)."""
    neg_inf = np.full_like(bu, -np.inf)
    values, pitches, rolls = [], [], []

    def add(value, pitch, roll, valid=None):
        values.append(value if valid is None else np.where(valid, value, neg_inf))
        pitches.append(np.broadcast_to(pitch, bu.shape))
        rolls.append(np.broadcast_to(roll, bu.shape))

    # 4. corners
    for sth in (-1.0, 1.0):
        for sph in (-1.0, 1.0):
            add(axial_component(bu, ba, bc, sth * Th, sph * Ph), sth * Th, sph * Ph)
    # 2. edges theta = +-Theta, peak in phi
    for sth in (-1.0, 1.0):
        A = bu * np.cos(Th) + sth * ba * np.sin(Th)
        peak = np.arctan2(bc, A)
        add(np.hypot(A, bc), sth * Th, peak, np.abs(peak) <= Ph)
    # 3. edges phi = +-Phi, peak in theta
    h = np.hypot(bu, ba)
    peak = np.arctan2(ba, bu)
    inside = np.abs(peak) <= Th
    for sph in (-1.0, 1.0):
        add(np.cos(Ph) * h + sph * bc * np.sin(Ph), peak, sph * Ph, inside)
    # 1. interior: the unconstrained maximiser b/|b|
    roll_b = np.arctan2(bc, h)
    add(np.sqrt(bu * bu + ba * ba + bc * bc), peak, roll_b, inside & (np.abs(roll_b) <= Ph))

    values = np.stack(values)
    k = np.argmax(values, axis=0)
    pick = lambda a: np.take_along_axis(np.stack(a), k[None], axis=0)[0]
    return pick(values), pick(pitches), pick(rolls)


def worst_axial(b_up, b_along, b_cross, max_pitch: float, max_roll: float):
    """Worst axial field over the libration set, exactly.

    Returns (worst, pitch, roll): worst = max |b . t| (T, >= 0) over
    |pitch| <= max_pitch, |roll| <= max_roll (rad, each in [0, pi/2)), and the
    pitch and roll (rad) of a tether direction that attains it.
    """
    if not (0.0 <= max_pitch < np.pi / 2 and 0.0 <= max_roll < np.pi / 2):
        raise ValueError("libration bounds must be in [0, 90) deg")
    bu, ba, bc = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (b_up, b_along, b_cross))
    vp, pp, rp = _max_linear(bu, ba, bc, max_pitch, max_roll)
    vn, pn, rn = _max_linear(-bu, -ba, -bc, max_pitch, max_roll)
    neg = vn > vp
    return np.where(neg, vn, vp), np.where(neg, pn, pp), np.where(neg, rn, rp)
