"""etcheck/numerics/quadrature.py: integrals against the normal density, adaptively, to their relative
tolerance far into the tails, with the integrand's own error carried and the range's cut stated."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from scipy import special

from etcheck.numerics.quadrature import CAP, normal_integrals

A = np.array([-2.0, 0.0, 3.0, -1.0, -5.0, -6.0])
S = np.array([1.0, 2.0, 0.3, 8.0, 30.0, 0.5])


def _log_phi(a, s):
    return special.log_ndtr(a / np.sqrt(1.0 + s**2))


def test_integrals_of_normal_distribution_functions_to_their_tolerance():
    """int Phi(a + s z) phi(z) dz = Phi(a / sqrt(1 + s^2)) (exactly): values from 0.998 down to 1e-10, one
    steep (s = 30), all at once; each within its stated error and 1e-9 relative."""
    def log_f(i, z):
        return special.log_ndtr(A[i] + S[i] * z), np.full(z.shape, -np.inf)

    r = normal_integrals(log_f, len(A), rtol=1e-10)
    exact = _log_phi(A, S)
    rel = np.abs(np.expm1(r.log_value - exact))
    assert np.all(rel <= 1e-9)
    assert np.all(rel <= r.quadrature + r.truncation / np.exp(exact))
    assert r.converged.all() and r.own.max() == 0.0
    assert r.truncation == pytest.approx(math.erfc(CAP / math.sqrt(2)), rel=1e-12)


def test_a_tail_integral_against_mpmath():
    """int Phi(-7 - 0.8 z) ... = 1.9e-8 against 30 digits; the peak sits at the design point."""
    mp.mp.dps = 30
    exact = float(mp.quad(lambda z: mp.ncdf(-7 - 0.8 * z) * mp.npdf(z), [-mp.inf, -8, -4, 0, mp.inf]))
    r = normal_integrals(lambda i, z: (special.log_ndtr(-7.0 - 0.8 * z), np.full(z.shape, -np.inf)), 1, rtol=1e-10)
    assert math.exp(r.log_value[0]) == pytest.approx(exact, rel=1e-9)
    assert r.peak[0] == pytest.approx(-7 * 0.8 / (1 + 0.8**2), abs=0.2)


def test_the_integrands_own_error_is_integrated_and_bounds_refinement():
    """An integrand known to 1e-6 (relative) everywhere: its own error integrates to 1e-6 of the value, and
    the panels stop refining there (fewer points than for 1e-12)."""
    def noisy(i, z):
        return special.log_ndtr(0.5 * z - 1.0), special.log_ndtr(0.5 * z - 1.0) + math.log(1e-6)

    def exact(i, z):
        return special.log_ndtr(0.5 * z - 1.0), np.full(z.shape, -np.inf)

    a = normal_integrals(noisy, 1, rtol=1e-12)
    b = normal_integrals(exact, 1, rtol=1e-12)
    assert a.own[0] == pytest.approx(1e-6, rel=1e-9)
    assert a.evaluations < b.evaluations
    assert math.exp(a.log_value[0]) == pytest.approx(math.exp(b.log_value[0]), rel=1e-6)


def test_a_vanishing_integrand_is_zero_exactly():
    r = normal_integrals(lambda i, z: (np.full(z.shape, -np.inf), np.full(z.shape, -np.inf)), 2)
    assert np.all(np.isneginf(r.log_value)) and r.converged.all()
