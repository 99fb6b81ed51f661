"""Chebyshev collocation tools on [0, 1] (etcheck.numerics.chebyshev)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from etcheck.numerics.chebyshev import (
    barycentric_weights,
    clenshaw_curtis_weights,
    diff_matrix,
    first_kind_nodes,
    first_kind_weights,
    lobatto_nodes,
    lobatto_weights,
    resample_matrix,
)


def test_nodes_are_ordered_and_symmetric():
    for N in (1, 2, 7, 16, 33):
        s = lobatto_nodes(N)
        assert s[0] == 0.0 and s[-1] == 1.0
        assert np.all(np.diff(s) > 0)
        assert np.allclose(s + s[::-1], 1.0, atol=1e-15)
        t = first_kind_nodes(N)
        assert np.all((t > 0) & (t < 1)) and np.all(np.diff(t) > 0)
        assert np.allclose(t + t[::-1], 1.0, atol=1e-15)


@pytest.mark.parametrize("N", [5, 12, 24])
def test_closed_form_weights_match_generic(N):
    for x, w in ((lobatto_nodes(N), lobatto_weights(N)), (first_kind_nodes(N), first_kind_weights(N))):
        g = barycentric_weights(x)
        ratio = w / g
        assert np.allclose(ratio, ratio[0], rtol=1e-9)


@settings(max_examples=30, deadline=None)
@given(st.integers(min_value=2, max_value=30), st.lists(st.floats(-3, 3), min_size=1, max_size=31))
def test_diff_and_resample_exact_on_polynomials(N, coeffs):
    coeffs = np.array(coeffs[: N + 1])
    p = np.polynomial.Polynomial(coeffs, domain=[0, 1], window=[0, 1])
    s = lobatto_nodes(N)
    D = diff_matrix(s, lobatto_weights(N))
    scale = max(1.0, np.max(np.abs(coeffs))) * (N + 1) ** 2
    assert np.max(np.abs(D @ p(s) - p.deriv()(s))) <= 1e-12 * scale * N
    y = np.linspace(0, 1, 37)
    P = resample_matrix(s, y, lobatto_weights(N))
    assert np.max(np.abs(P @ p(s) - p(y))) <= 1e-12 * scale


def test_resample_hits_nodes_exactly_and_rows_sum_to_one():
    s = lobatto_nodes(10)
    P = resample_matrix(s, s[[0, 3, 10]])
    assert np.array_equal(P, np.eye(11)[[0, 3, 10]])
    P = resample_matrix(s, first_kind_nodes(10), lobatto_weights(10))
    assert np.allclose(P.sum(axis=1), 1.0, atol=1e-14)


def test_spectral_accuracy_of_derivative():
    N = 32
    s = lobatto_nodes(N)
    D = diff_matrix(s, lobatto_weights(N))
    err = np.max(np.abs(D @ np.sin(6 * s) - 6 * np.cos(6 * s)))
    assert err < 1e-11
    # and it is not exact at low resolution (the test can fail)
    s8 = lobatto_nodes(8)
    assert np.max(np.abs(diff_matrix(s8) @ np.sin(6 * s8) - 6 * np.cos(6 * s8))) > 1e-4


@pytest.mark.parametrize("N", [1, 2, 3, 8, 9, 20])
def test_clenshaw_curtis(N):
    w = clenshaw_curtis_weights(N)
    s = lobatto_nodes(N)
    for deg in range(N + 1):
        assert abs(w @ s**deg - 1.0 / (deg + 1)) < 1e-14
    if N >= 20:
        assert abs(w @ np.exp(s) - (np.e - 1)) < 1e-14
