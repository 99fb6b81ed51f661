"""The bracket bisection of numerics.optimize and the lazily loaded scipy.optimize forwarders."""

from __future__ import annotations

import math

import numpy as np
import pytest

from etcheck.numerics.optimize import bisect_brackets, brentq


def test_bisection_refines_every_bracket_to_the_last_bit():
    a = np.array([3.0, 6.0, 9.0, 12.0])
    roots = bisect_brackets(np.sin, a, a + 1.0)
    np.testing.assert_allclose(roots, np.pi * np.arange(1, 5), rtol=2 * np.finfo(float).eps, atol=0)


def test_bisection_stops_on_an_exact_zero_and_handles_a_zero_at_an_end():
    # the first midpoint is the root itself; the second bracket has its root at its left end
    roots = bisect_brackets(lambda x: x - 1.0, np.array([0.0, 1.0]), np.array([2.0, 5.0]))
    assert roots.tolist() == [1.0, 1.0]


def test_bisection_refuses_a_bracket_without_a_sign_change():
    with pytest.raises(ValueError, match="sign"):
        bisect_brackets(np.cos, np.array([0.0, 1.0]), np.array([1.0, 1.5]))


def test_the_forwarders_are_scipy_s_functions():
    assert brentq(math.cos, 1.0, 2.0, xtol=1e-15) == pytest.approx(math.pi / 2, rel=1e-15)
