"""The numpy PCHIP of numerics.pchip is scipy's PchipInterpolator (to round-off), and it stays monotone."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from etcheck.numerics.pchip import Pchip


@pytest.mark.parametrize("seed", range(12))
def test_the_same_values_as_scipy_on_random_data(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 25))
    x = np.cumsum(rng.uniform(0.01, 2.0, n))
    # smooth, oscillating, with repeated values and sign changes: every branch of the slope rules
    y = rng.choice([np.sin(3 * x), rng.normal(size=n), np.round(rng.normal(size=n)), np.exp(x / 5)])
    t = np.concatenate([x, np.linspace(x[0], x[-1], 301)])
    ref = PchipInterpolator(x, y)(t)
    np.testing.assert_allclose(Pchip.through(x, y)(t), ref, rtol=0, atol=1e-13 * max(1.0, np.max(np.abs(y))))


def test_the_end_slopes_are_limited_as_scipy_limits_them():
    # an end slope of the wrong sign (set to zero) and one next to an extremum larger than 3x the secant (clipped)
    for y in ([0.0, 1.0, 0.0, 1.0], [0.0, 0.1, 5.0, 5.05], [1.0, 0.0, 3.0, 0.0], [0.0, 0.0, 1.0, 1.0]):
        x = np.array([0.0, 1.0, 1.2, 4.0])
        t = np.linspace(0.0, 4.0, 97)
        np.testing.assert_allclose(Pchip.through(x, y)(t), PchipInterpolator(x, y)(t), rtol=0, atol=1e-14)


def test_monotone_data_give_a_monotone_curve_through_every_point():
    x = np.array([0.0, 0.1, 0.5, 2.0, 2.1, 6.0])
    y = np.array([0.0, 0.0, 0.2, 5.0, 5.1, 5.1])
    f = Pchip.through(x, y)
    t = np.linspace(0.0, 6.0, 2001)
    assert np.all(np.diff(f(t)) >= -1e-15)
    np.testing.assert_array_equal(f(x), y)


def test_two_points_are_joined_by_a_line_and_bad_abscissae_are_refused():
    np.testing.assert_allclose(Pchip.through([0.0, 2.0], [1.0, 3.0])([0.5, 1.5]), [1.5, 2.5], rtol=1e-15)
    with pytest.raises(ValueError, match="increasing"):
        Pchip.through([0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="two points"):
        Pchip.through([1.0], [1.0])
