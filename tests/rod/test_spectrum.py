"""Eigenvalues of the linearised rod (etcheck.rod.core.spectrum)."""

import numpy as np
import pytest
from scipy.optimize import brentq

from etcheck.numerics.eigen import eliminate_static, match_spectra, qep_dense
from etcheck.rod.core.base_state import straight
from etcheck.rod.core.linear import linear_operator
from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.core.spectrum import spectrum

SET = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)


def _beam_roots(P, R, count):
    """Sec. VI B (f = 1): (a^2 - b^2) sin a sinh b = 2ab (1 - cos a cosh b), mu_1 > 0."""

    def g(mu):
        root = np.sqrt(mu**4 * P**2 + 4 * mu**2 / R)
        a = np.sqrt(0.5 * mu**2 * P + 0.5 * root)
        b = np.sqrt(0.5 * root - 0.5 * mu**2 * P)
        # divided by cosh b to keep it O(1)
        return (a**2 - b**2) * np.sin(a) * np.tanh(b) - 2 * a * b * (1 / np.cosh(b) - np.cos(a))

    grid = np.linspace(1.0, 4000.0, 200001)
    vals = g(grid)
    idx = np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0][:count]
    return np.array([brentq(g, grid[i], grid[i + 1], xtol=1e-14, rtol=1e-15) for i in idx])


def test_unperturbed_frequencies_match_sec_6_2():
    p = SET
    sp = spectrum(p, k=10, tol=1e-10)
    assert sp.converged
    f = p.f
    # f-scaling: mu_1 = sqrt(f) mu, P unchanged; u (weak, R) and v (stiff) families
    mu_u = _beam_roots(p.P, p.R, 6) / np.sqrt(f)
    mu_v = _beam_roots(p.P, 1.0, 6) / np.sqrt(f)
    mu_t = np.arange(1, 6) * np.pi * np.sqrt(p.Gamma / (2 * p.P * f))
    expected = np.sort(np.concatenate([mu_u, mu_v, mu_t]))[:10]
    got = np.sort(sp.eigenvalues.imag)
    assert np.max(np.abs(sp.eigenvalues.real)) < 1e-10
    assert np.allclose(got, expected, rtol=1e-8, atol=0)
    # first weak-axis frequency is sqrt(R) up to rotary inertia (f = first clamped root^4)
    assert abs(mu_u[0] - np.sqrt(p.R)) < 5e-3


def test_torsion_frequencies():
    p = RodParameters(P=0.05, R=0.5, Gamma=0.7)  # torsion well below bending
    sp = spectrum(p, k=12)
    mu_t = np.arange(1, 4) * np.pi * np.sqrt(p.Gamma / (2 * p.P * p.f))
    for mu in mu_t:
        assert np.min(np.abs(sp.eigenvalues - 1j * mu)) <= 1e-8 * mu


@pytest.mark.parametrize("kw", [dict(omega=0.25), dict(omega=0.25, B=0.5), dict(omega=0.5, T=0.3, B=0.2)])
def test_undamped_stable_spectrum_is_imaginary(kw):
    sp = spectrum(SET.with_(**kw), k=10)
    assert sp.converged
    assert np.max(np.abs(sp.eigenvalues.real)) < 1e-10
    assert np.all(sp.eigenvalues.imag > 0)


def test_hamiltonian_symmetry_and_unstable_pair():
    """gamma = 0: lambda and -conj(lambda) are both eigenvalues (here a real pair)."""
    p = SET.with_(omega=0.75)
    A = linear_operator(p, straight(p), 24)
    lam = qep_dense(*A)
    lam = lam[np.abs(lam) < 10]
    m = match_spectra(lam, -np.conj(lam), accept=np.inf, floor=1.0)
    assert np.max(m.errors) < 1e-9
    sp = spectrum(p)
    real = sp.eigenvalues[sp.eigenvalues.imag == 0]
    assert real.size == 2 and abs(real[0] + real[1]) < 1e-10 and np.max(real) > 1e-2


def test_damping_moves_everything_left():
    sp = spectrum(SET.with_(omega=0.25, B=0.3, gamma=0.04375))
    assert sp.converged and np.all(sp.eigenvalues.real < 0)


def test_shift_invert_agrees_with_dense_elimination():
    """Strategy (b) against strategy (a) (QR elimination of phi, m + QZ)."""
    p = SET.with_(omega=0.6, B=0.3, gamma=0.02, T=0.1)
    N = 24
    A = linear_operator(p, straight(p), N)
    el = eliminate_static(*A, np.arange(6 * (N + 1), 12 * (N + 1)))
    dense = qep_dense(el.B0, el.B1, el.B2)
    sp = spectrum(p, N=N)
    for lam in sp.eigenvalues:
        assert np.min(np.abs(dense - lam)) < 1e-9 * max(1, abs(lam))


def test_resolution_control_and_error_estimates():
    p = SET.with_(omega=0.25)
    coarse = spectrum(p, N=8, tol=1e-8)
    assert not coarse.converged and coarse.errors.max() > 1e-8
    fine = spectrum(p, tol=1e-8)
    assert fine.converged and fine.errors.max() <= 1e-8 and fine.N > fine.N_check
    ref = spectrum(p, N=64)
    m = match_spectra(fine.eigenvalues, ref.eigenvalues, floor=0.1)
    assert m.values.size == fine.eigenvalues.size and np.max(m.errors) < 1e-8
    # the estimate is honest at a coarse resolution
    mid = spectrum(p, N=12)
    m = match_spectra(mid.eigenvalues, ref.eigenvalues, floor=0.1)
    true_err = np.max(m.errors)
    assert true_err <= 10 * mid.errors.max() + 1e-14


def test_modes():
    sp = spectrum(SET, k=3, with_modes=True)
    assert sp.modes.shape == (sp.eigenvalues.size, sp.mode_s.size, 6)
    first = sp.modes[0]
    # first mode: weak-axis (e1) bending, clamped ends, symmetric about s = 1/2
    assert np.max(np.abs(first[:, 0])) == pytest.approx(1.0)
    assert np.max(np.abs(first[:, 1:3])) < 1e-8
    assert abs(first[0, 0]) < 1e-10 and abs(first[-1, 0]) < 1e-10
    assert np.allclose(first[:, 0], first[::-1, 0], atol=1e-8)


def test_f_scaling_is_consistent():
    """f only rescales: lambda(f) sqrt(f) is f-independent with B f, T f, omega sqrt(f) fixed."""
    a = RodParameters(P=0.01, R=0.7, Gamma=0.8, f=1.0, B=20.0, omega=0.6 * np.sqrt(F_CLAMPED), T=10.0)
    b = a.with_(f=F_CLAMPED, B=20.0 / F_CLAMPED, omega=0.6, T=10.0 / F_CLAMPED)
    la, lb = spectrum(a, k=6).eigenvalues, spectrum(b, k=6).eigenvalues
    assert np.allclose(la, lb * np.sqrt(F_CLAMPED), rtol=1e-8)
