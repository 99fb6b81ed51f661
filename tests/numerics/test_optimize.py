"""Bracketed roots (false position), the pairing from distinct minima and the lazily loaded scipy.optimize
forwarders of numerics.optimize."""

from __future__ import annotations

import math

import numpy as np
import pytest

from etcheck.numerics.optimize import bracketed_roots, brentq


def test_every_bracket_is_refined_to_the_last_bits_in_few_evaluations():
    a = np.array([3.0, 6.0, 9.0, 12.0])
    calls = []
    roots = bracketed_roots(lambda x: calls.append(1) or np.sin(x), a, a + 1.0)
    np.testing.assert_allclose(roots, np.pi * np.arange(1, 5), rtol=2 * np.finfo(float).eps, atol=0)
    assert len(calls) <= 2 + 12  # the ends, then superlinear convergence (bisection would take ~50)


def test_an_exact_zero_and_a_zero_at_an_end_are_returned_exactly():
    # the first midpoint is the root itself; the second bracket has its root at its left end
    roots = bracketed_roots(lambda x: x - 1.0, np.array([0.0, 1.0]), np.array([2.0, 5.0]))
    assert roots.tolist() == [1.0, 1.0]


def test_a_bracket_without_a_sign_change_is_refused():
    with pytest.raises(ValueError, match="sign"):
        bracketed_roots(np.cos, np.array([0.0, 1.0]), np.array([1.0, 1.5]))


def test_the_forwarders_are_scipy_s_functions():
    assert brentq(math.cos, 1.0, 2.0, xtol=1e-15) == pytest.approx(math.pi / 2, rel=1e-15)


def test_assignment_from_distinct_minima_is_optimal_and_clusters_go_to_scipy():
    from scipy.optimize import linear_sum_assignment as scipy_lsa

    from etcheck.numerics.optimize import linear_sum_assignment

    rng = np.random.default_rng(7)
    for _ in range(2000):
        n, m = rng.integers(1, 7, size=2)
        cost = np.round(rng.random((n, m)) ** 2, 2)  # rounding makes ties and shared minima common
        r, c = linear_sum_assignment(cost)
        r0, c0 = scipy_lsa(cost)
        assert cost[r, c].sum() == pytest.approx(cost[r0, c0].sum(), abs=1e-12)
        assert r.tolist() == sorted(r.tolist()) and len(r) == min(n, m) and len(set(c.tolist())) == len(c)
    # both rows prefer column 0: the minima do not give an assignment, the Hungarian method does
    r, c = linear_sum_assignment(np.array([[0.0, 1.0], [0.1, 5.0]]))
    assert (r.tolist(), c.tolist()) == ([0, 1], [1, 0])


def test_a_root_false_position_approaches_slowly_is_still_found():
    # x^9 is flat at its root and steep at the bracket's far end: plain false position would crawl
    roots = bracketed_roots(lambda x: x**9 - 0.1**9, np.array([0.0, -1.0]), np.array([5.0, 3.0]))
    np.testing.assert_allclose(roots, [0.1, 0.1], rtol=4 * np.finfo(float).eps)
