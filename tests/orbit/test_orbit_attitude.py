"""The exact worst axial field over the libration set against brute force."""

from __future__ import annotations

import numpy as np
import pytest

from etcheck.orbit import axial_component, tether_direction, worst_axial

BOUNDS = [(10, 5), (30, 2), (0, 20), (25, 0), (0, 0), (80, 85)]


@pytest.mark.parametrize("pitch_deg, roll_deg", BOUNDS)
def test_worst_axial_matches_a_fine_grid_of_directions(pitch_deg, roll_deg):
    rng = np.random.default_rng(pitch_deg * 100 + roll_deg)
    b = rng.normal(size=(3, 300)) * 40e-6
    Th, Ph = np.radians(pitch_deg), np.radians(roll_deg)
    worst, pitch, roll = worst_axial(*b, Th, Ph)
    m = 301
    TH, PH = np.meshgrid(np.linspace(-Th, Th, m), np.linspace(-Ph, Ph, m))
    # 20 fields at a time (all 300 at once touch ~1 GB of fresh pages: seconds)
    brute = np.concatenate([
        np.abs(axial_component(*(c[:, None, None] for c in b[:, k : k + 20]), TH, PH)).max(axis=(1, 2))
        for k in range(0, b.shape[1], 20)
    ])
    mag = np.linalg.norm(b, axis=0)
    # exact is an upper bound of any sample, and the grid gets within its O(h^2) error
    assert np.all(worst >= brute - 1e-15 * mag)
    h = max(2 * Th, 2 * Ph) / (m - 1)
    assert np.all(worst - brute <= 0.5 * h**2 * mag + 1e-18)
    # the returned direction is in the set and attains the value
    assert np.all(np.abs(pitch) <= Th + 1e-15) and np.all(np.abs(roll) <= Ph + 1e-15)
    np.testing.assert_allclose(np.abs(axial_component(*b, pitch, roll)), worst, rtol=1e-13)


def test_limits():
    b = np.array([[3.0, -1.0], [4.0, 0.5], [0.0, 0.2]])
    # no libration: the vertical component
    w, _, _ = worst_axial(*b, 0.0, 0.0)
    np.testing.assert_allclose(w, np.abs(b[0]))
    # a set containing +-b/|b|: the magnitude
    w, _, _ = worst_axial(*b, np.radians(89), np.radians(89))
    np.testing.assert_allclose(w, np.linalg.norm(b, axis=0))
    with pytest.raises(ValueError):
        worst_axial(*b, np.pi / 2, 0.0)


def test_tether_direction_is_a_unit_vector_in_the_local_frame():
    e = np.eye(3)[None]
    t = tether_direction(e[:, 0], e[:, 1], e[:, 2], np.radians(30), np.radians(20))
    np.testing.assert_allclose(np.linalg.norm(t, axis=-1), 1.0)
    np.testing.assert_allclose(t[0], [np.cos(np.radians(20)) * np.cos(np.radians(30)),
                                      np.cos(np.radians(20)) * np.sin(np.radians(30)), np.sin(np.radians(20))])
