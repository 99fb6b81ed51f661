"""Rung 0 (etcheck/rod/straight/analytic.py) against published and independent values.

Independent references computed here, never copied from the code:

* chi(beta) of eq. ``char_welded`` written out again from the paper and solved
  for its double zeros (zeros of chi') with mpmath at 40 digits;
* the real coupled static problem x'''' = (B/R) y', y'''' = -B x' (eq.
  ``lin_eqs`` at lambda = 0, f = 1) clamped at both ends, by a matrix
  exponential: its boundary matrix has a two-dimensional kernel at B_k;
* clamped-clamped Euler-Bernoulli roots of cos a cosh a = 1 (mpmath) and a
  determinant of the 4x4 boundary matrix of the Rayleigh beam (Sec. VI B)
  built from the general solution, root-bracketed on a grid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import brentq

from etcheck.rod.core.parameters import F_CLAMPED
from etcheck.rod.straight import analytic

mp = pytest.importorskip("mpmath")
mp.mp.dps = 40

SQRT3 = math.sqrt(3.0)


# --- independent references -------------------------------------------------------

from independent import beta_ref, chi_mp, chi_scaled_mp  # noqa: E402


def clamped_clamped_root(n: int) -> float:
    """n-th positive root of cos a cosh a = 1 (Euler-Bernoulli clamped beam)."""
    guess = (n + 0.5) * mp.pi
    return float(mp.findroot(lambda a: mp.cos(a) * mp.cosh(a) - 1, guess))


F = clamped_clamped_root(1) ** 4  # the paper's f = 500.5639, computed here


def coupled_static_matrix(B1: float, R: float) -> np.ndarray:
    """4x4 boundary matrix of x'''' = (B1/R) y', y'''' = -B1 x' (f = 1), x = x' = y = y' = 0
    at both ends; the unknowns are x''(0), x'''(0), y''(0), y'''(0)."""
    A = np.zeros((8, 8))
    for i in range(3):
        A[i, i + 1] = 1.0
        A[4 + i, 5 + i] = 1.0
    A[3, 5] = B1 / R
    A[7, 1] = -B1
    E = scipy.linalg.expm(A)
    return E[np.ix_([0, 1, 4, 5], [2, 3, 6, 7])]


def rayleigh_beam_det(mu: float, P: float, stiffness: float) -> float:
    """Determinant of the clamped-clamped boundary matrix of
    x'''' - lambda^2 P x'' + lambda^2/stiffness x = 0, lambda = i mu (f = 1), built from
    the basis sin(as), cos(as), e^{-bs}, e^{b(s-1)} (bounded for every b)."""
    root = math.sqrt(mu**4 * P**2 + 4 * mu**2 / stiffness)
    a = math.sqrt(0.5 * (root + mu**2 * P))
    b = math.sqrt(0.5 * (root - mu**2 * P))
    rows = []
    for s in (0.0, 1.0):
        rows.append([math.sin(a * s), math.cos(a * s), math.exp(-b * s), math.exp(b * (s - 1))])
        rows.append([a * math.cos(a * s), -a * math.sin(a * s), -b * math.exp(-b * s), b * math.exp(b * (s - 1))])
    return float(np.linalg.det(np.array(rows)))


def rayleigh_beam_roots(P: float, stiffness: float, n: int) -> np.ndarray:
    """First n frequencies mu (f = 1) of the clamped Rayleigh beam, by a fine scan of
    rayleigh_beam_det (sign changes) and Brent refinement."""
    roots: list[float] = []
    mu, step = 1e-3, 0.02 * math.sqrt(stiffness)
    g_old = rayleigh_beam_det(mu, P, stiffness)
    while len(roots) < n:
        g_new = rayleigh_beam_det(mu + step, P, stiffness)
        if g_old == 0.0 or np.sign(g_old) != np.sign(g_new):
            roots.append(brentq(rayleigh_beam_det, mu, mu + step, args=(P, stiffness), xtol=1e-14, rtol=1e-15))
        mu, g_old = mu + step, g_new
    return np.array(roots)


# --- chi and its double zeros -------------------------------------------------------

PUBLISHED_BETAS = [7.332130, 13.613561, 19.896753]


@pytest.mark.parametrize("k, printed", list(enumerate(PUBLISHED_BETAS, start=1)))
def test_roots_match_published_digits(k, printed):
    roots = analytic.characteristic_roots(3)
    # Fig. 4 prints six decimals; 19.8967535... rounds to ...754 (docs/validation.md)
    assert abs(roots[k - 1].beta - printed) <= 1.01e-6
    assert roots[k - 1].k == k


def test_roots_match_independent_to_1e12():
    roots = analytic.characteristic_roots(5)
    assert len(roots) == 5
    for r in roots:
        ref = beta_ref(r.k)
        assert r.beta == pytest.approx(ref, rel=1e-12, abs=0)
        assert r.error < 1e-12


def test_chi_matches_paper_formula():
    for b in [0.3, 1.0, 2.5, 5.0, 7.0, 7.332, 10.0, 13.6, 19.9, 25.0]:
        ref = float(chi_mp(mp.mpf(b)))
        assert float(analytic.chi(b)) == pytest.approx(ref, rel=1e-9, abs=1e-9)
        assert float(analytic.chi_scaled(b)) == pytest.approx(float(chi_scaled_mp(mp.mpf(b))), rel=1e-9, abs=1e-14)


@pytest.mark.parametrize("k", [1, 2, 3])
def test_double_zero_no_sign_change(k):
    beta = beta_ref(k)
    # chi is tiny at the root and non-negative all around it: a touching zero
    offsets = np.concatenate([-np.logspace(-6, -0.3, 40), np.logspace(-6, -0.3, 40)])
    values = analytic.chi_scaled(beta + offsets)
    assert np.all(values >= 0)
    assert abs(float(analytic.chi_scaled(beta))) < 1e-14
    # grows quadratically away from the root (double, not higher order)
    h = 1e-3
    ratio = float(analytic.chi_scaled(beta + 2 * h) / analytic.chi_scaled(beta + h))
    assert ratio == pytest.approx(4.0, rel=1e-2)
    r = analytic.characteristic_roots(k)[-1]
    assert r.curvature > 0
    assert r.residual < 1e-14


def test_chi_nonnegative_on_a_grid():
    """chi is proportional to a squared modulus: it never goes negative."""
    b = np.linspace(0.01, 60.0, 20001)
    assert np.all(analytic.chi_scaled(b) >= -1e-15)


@pytest.mark.parametrize("k", [1, 2, 3])
def test_complex_determinant_vanishes_at_roots(k):
    beta = analytic.characteristic_roots(k)[-1].beta
    d0 = abs(analytic.determinant(beta))
    d_off = abs(analytic.determinant(beta + 0.1))
    assert d0 < 1e-12
    assert d_off > 1e-4


@pytest.mark.parametrize("R", [21 / 38, 0.2, 1.0])
@pytest.mark.parametrize("k", [1, 2, 3])
def test_kernel_is_two_dimensional(k, R):
    r = analytic.characteristic_roots(k)[-1]
    assert r.kernel_dimension == 2
    # independent: the real coupled x-y clamped problem at B = beta^3 sqrt(R) (f = 1)
    sv = np.linalg.svd(coupled_static_matrix(beta_ref(k) ** 3 * math.sqrt(R), R), compute_uv=False)
    sv = sv / sv[0]
    assert sv[1] > 0.5
    assert sv[2] < 1e-12 and sv[3] < 1e-12
    sv_off = np.linalg.svd(coupled_static_matrix((beta_ref(k) - 0.2) ** 3 * math.sqrt(R), R), compute_uv=False)
    assert sv_off[2] / sv_off[0] > 1e3 * sv[2]  # the kernel is a feature of the root only


# --- large beta ---------------------------------------------------------------------


def test_chi_scaled_finite_for_large_beta():
    b = np.linspace(0.0, 1000.0, 100001)
    with np.errstate(over="raise", invalid="raise", divide="raise", under="ignore"):
        values = analytic.chi_scaled(b)
        dvalues = analytic.chi_scaled_derivative(np.linspace(0.0, 300.0, 3001))
    assert np.all(np.isfinite(values))
    assert np.all(np.isfinite(dvalues))
    # asymptotically 1 - cos(beta - pi/3)
    big = b[b > 60]
    assert np.allclose(values[b > 60], 1 - np.cos(big - math.pi / 3), atol=1e-12)


def test_roots_for_beta_beyond_200():
    roots = analytic.characteristic_roots(34)
    assert roots[-1].beta > 200
    for r in roots:
        assert math.isfinite(r.beta)
        assert r.kernel_dimension == 2
    # consecutive roots are ~2 pi apart and approach pi/3 + 2 pi k
    for r in roots[10:]:
        assert r.beta == pytest.approx(math.pi / 3 + 2 * math.pi * r.k, abs=1e-10)
    assert roots[-1].beta == pytest.approx(beta_ref(34), rel=1e-12)
    assert roots[7].beta == pytest.approx(beta_ref(8), rel=1e-12)


# --- critical loads -------------------------------------------------------------------


def test_set_critical_loads_R_21_38():
    R = 21 / 38
    loads = analytic.critical_loads(R, F, 5)
    assert len(loads) == 5
    expected = [beta_ref(k) ** 3 * math.sqrt(R) / F for k in range(1, 6)]
    for got, ref in zip(loads, expected):
        assert got == pytest.approx(ref, rel=5e-8)  # 7 significant digits
    # published (Sec. VII A): 0.585, 3.747, 11.698
    assert loads[0] == pytest.approx(0.585395, abs=1e-6)
    assert loads[1] == pytest.approx(3.74691, abs=1e-5)
    assert loads[2] == pytest.approx(11.6978, abs=1e-4)
    assert round(float(loads[2]), 3) == 11.698


def test_set_critical_load_R_rounded():
    loads = analytic.critical_loads(0.5526, F, 3)
    assert loads[2] == pytest.approx(beta_ref(3) ** 3 * math.sqrt(0.5526) / F, rel=5e-8)
    assert round(float(loads[2]), 4) == 11.6975


def test_set_critical_IB0():
    """B f EI1 / L^3 with EI1 = 38 N m2, L = 100 m: 1.1135e-2 N/m, not the paper's 2.104e-5."""
    B1 = analytic.critical_loads(21 / 38, F, 1)[0]
    IB0 = B1 * F * 38.0 / 100.0**3
    assert IB0 == pytest.approx(1.1135e-2, rel=1e-3)
    assert IB0 == pytest.approx(beta_ref(1) ** 3 * math.sqrt(21 * 38) / 1e6, rel=1e-10)
    assert abs(IB0 - 2.104e-5) > 1e-3


@pytest.mark.parametrize(
    "R, f",
    [(1.0, 1.0), (0.1, 1.0), (0.9, 500.0), (0.37, F), (1e-3, 12.5), (0.5526, 1e4)],
)
def test_critical_loads_other_R_and_f(R, f):
    loads = analytic.critical_loads(R, f, 4)
    for k, got in enumerate(loads, start=1):
        assert got == pytest.approx(beta_ref(k) ** 3 * math.sqrt(R) / f, rel=1e-11)


@pytest.mark.parametrize("R, f", [(21 / 38, F), (0.3, 1.0), (1.0, 100.0)])
def test_beta_of_load_inverts_critical_load(R, f):
    for k, B in enumerate(analytic.critical_loads(R, f, 3), start=1):
        assert analytic.beta_of_load(B, R, f) == pytest.approx(beta_ref(k), rel=1e-12)


# --- buckling mode ----------------------------------------------------------------------


@pytest.mark.parametrize("R", [21 / 38, 1.0, 0.2])
@pytest.mark.parametrize("k", [1, 2])
def test_buckling_mode_clamped_and_solves_equations(k, R):
    s = np.linspace(0.0, 1.0, 401)
    x, y = analytic.buckling_mode(k, R, s)
    assert x.shape == y.shape == s.shape
    assert np.max(np.hypot(x, y)) == pytest.approx(1.0, rel=1e-12)
    # clamped: x = y = 0 and x' = y' = 0 at both ends
    cx = np.polynomial.Chebyshev.fit(s, x, 40, domain=[0, 1])
    cy = np.polynomial.Chebyshev.fit(s, y, 40, domain=[0, 1])
    assert np.max(np.abs(cx(s) - x)) < 1e-10 and np.max(np.abs(cy(s) - y)) < 1e-10
    for end in (0.0, 1.0):
        assert abs(cx(end)) < 1e-9 and abs(cy(end)) < 1e-9
        assert abs(cx.deriv()(end)) < 1e-7 and abs(cy.deriv()(end)) < 1e-7
    # interior: x'''' = (B/R) y', y'''' = -B x'  (f = 1, B = beta^3 sqrt(R))
    B1 = beta_ref(k) ** 3 * math.sqrt(R)
    si = s[20:-20]
    scale = B1 * np.max(np.abs(cx.deriv()(si)))
    res1 = cx.deriv(4)(si) - (B1 / R) * cy.deriv()(si)
    res2 = cy.deriv(4)(si) + B1 * cx.deriv()(si)
    assert np.max(np.abs(res1)) < 1e-5 * scale / R
    assert np.max(np.abs(res2)) < 1e-5 * scale
    # not a trivial or purely planar picture at the ends
    assert np.max(np.abs(x)) > 0.1


# --- unperturbed spectrum (Sec. VI B) --------------------------------------------------


@pytest.mark.parametrize("R", [21 / 38, 1.0, 0.25])
def test_bending_frequencies_P0_are_euler_bernoulli(R):
    weak = analytic.bending_frequencies(0.0, R, F, 5, "weak")
    stiff = analytic.bending_frequencies(0.0, R, F, 5, "stiff")
    assert weak[0] == pytest.approx(math.sqrt(R), rel=1e-10)
    assert stiff[0] == pytest.approx(1.0, rel=1e-10)
    for n in range(1, 6):
        a = clamped_clamped_root(n)
        assert weak[n - 1] == pytest.approx(math.sqrt(R) * a**2 / math.sqrt(F), rel=1e-10)
        assert stiff[n - 1] == pytest.approx(a**2 / math.sqrt(F), rel=1e-10)


def test_bending_frequencies_f_equals_one():
    mu = analytic.bending_frequencies(0.0, 0.5, 1.0, 3, "weak")
    for n in range(1, 4):
        assert mu[n - 1] == pytest.approx(math.sqrt(0.5) * clamped_clamped_root(n) ** 2, rel=1e-10)


@pytest.mark.parametrize("P", [1e-3, 1e-2, 5e-2])
@pytest.mark.parametrize("R, axis", [(21 / 38, "weak"), (21 / 38, "stiff"), (0.3, "weak")])
def test_bending_frequencies_with_rotary_inertia(P, R, axis):
    stiffness = R if axis == "weak" else 1.0
    got = analytic.bending_frequencies(P, R, F, 5, axis)
    at_zero = analytic.bending_frequencies(0.0, R, F, 5, axis)
    assert np.all(got < at_zero)
    assert np.all(np.diff(got) > 0)
    ref = rayleigh_beam_roots(P, stiffness, 5) / math.sqrt(F)
    np.testing.assert_allclose(got, ref, rtol=1e-10)
    # and they satisfy the printed Sec. VI B equation (a^2-b^2) sin a sinh b = 2ab(1 - cos a cosh b)
    for mu_f in got:
        mu = mp.mpf(float(mu_f)) * mp.sqrt(F)
        root = mp.sqrt(mu**4 * P**2 + 4 * mu**2 / stiffness)
        a = mp.sqrt((mu**2 * P + root) / 2)
        b = mp.sqrt((root - mu**2 * P) / 2)
        lhs = (a**2 - b**2) * mp.sin(a) * mp.sinh(b)
        rhs = 2 * a * b * (1 - mp.cos(a) * mp.cosh(b))
        assert abs(lhs - rhs) < 1e-8 * (abs(a * b * mp.cosh(b)) + 1)


def test_bending_frequencies_decrease_with_P():
    Ps = [0.0, 1e-4, 1e-3, 1e-2, 0.1]
    firsts = [analytic.bending_frequencies(P, 21 / 38, F, 3, "weak")[2] for P in Ps]
    assert all(b < a for a, b in zip(firsts, firsts[1:]))


@pytest.mark.parametrize("P, Gamma, f", [(1e-3, 1 / 1.3, F), (0.01, 0.7, 1.0), (2e-4, 1.0, 37.0)])
def test_torsion_frequencies(P, Gamma, f):
    mu = analytic.torsion_frequencies(P, Gamma, f, 4)
    # M3'' + (2 mu1^2 P / Gamma) M3 = 0, M3' = 0 at both ends -> sqrt(2 P / Gamma) mu1 = n pi,
    # and mu_f = mu1 / sqrt(f)
    for n in range(1, 5):
        mu1 = n * math.pi / math.sqrt(2 * P / Gamma)
        assert mu[n - 1] == pytest.approx(mu1 / math.sqrt(f), rel=1e-13)


def test_torsion_frequencies_set_value():
    mu = analytic.torsion_frequencies(1e-3, 1 / 1.3, F, 1)[0]
    assert mu == pytest.approx(math.pi * math.sqrt((1 / 1.3) / (2e-3 * F)), rel=1e-13)
    assert mu == pytest.approx(2.7538, rel=1e-4)


def test_torsion_frequencies_without_rotary_inertia_are_infinite():
    assert np.all(np.isinf(analytic.torsion_frequencies(0.0, 0.77, F, 3)))


@pytest.mark.parametrize("P, R", [(0.05, 1.0), (0.3, 0.4), (1.0, 0.2)])
def test_bending_frequencies_large_rotary_inertia_match_rung1(P, R):
    # regression: the scan range once grew with P and skipped roots; rotary inertia only lowers them
    from etcheck.rod.core.parameters import RodParameters
    from etcheck.rod.core.spectrum import spectrum

    weak = analytic.bending_frequencies(P, R, F, 3, "weak")
    stiff = analytic.bending_frequencies(P, R, F, 3, "stiff")
    assert np.all(weak <= np.sqrt(R) * np.array([1.0, 2.7565, 5.4040]) + 1e-9)
    s = spectrum(RodParameters(P=P, R=R, Gamma=0.77), k=14)
    assert s.converged
    mu = np.sort(s.eigenvalues.imag)
    for target in np.concatenate([weak, stiff]):
        assert np.min(np.abs(mu - target)) <= 1e-8 * target, target


# --- natural frequencies under tension -----------------------------------------------------------------------


@pytest.mark.parametrize("ends", [("welded", "welded"), ("pinned", "pinned"), ("welded", "pinned")])
@pytest.mark.parametrize("R, P, T", [(0.55, 1e-3, 2.0), (2.56e-6, 2e-10, 1.44), (0.9, 1e-2, 50.0)])  # R = 1: double roots
def test_tensioned_frequencies_are_roots_of_the_exact_undamped_determinant(R, P, T, ends):
    """Each frequency mu of the weak and stiff equations under tension is a real root -lambda^2 = mu^2 of the
    exact characteristic function E of the undamped straight rod at B = omega = 0 (its own formulation, the
    4x4 blocks of both axes at once): E changes sign across mu^2 (1 +- 1e-7)."""
    from etcheck.rod.core.parameters import RodParameters
    from etcheck.rod.straight.exact.undamped_kernel import characteristic_mu

    p = RodParameters(P=P, R=R, Gamma=0.75, f=F_CLAMPED, B=0.0, omega=0.0, T=T, gamma=0.0, ends=ends)
    for axis in ("weak", "stiff"):
        for mu in analytic.bending_frequencies(P, R, F_CLAMPED, 3, axis, ends, T):
            lo, hi = characteristic_mu(p, np.array([mu**2 * (1 - 1e-7), mu**2 * (1 + 1e-7)]))
            assert lo * hi < 0, (axis, mu)


def test_taut_tape_is_a_string_with_end_layers():
    """The tape tether's weak axis under 0.0106 N: n pi sqrt(T) (the string) to within its clamped boundary
    layers, 2 eps_u = 2 sqrt(R / (f T)) relative, and far above the unloaded 8.4e-7 Hz-like sqrt(R) mode."""
    R, P, T = 2.556164383561644e-06, 2.0857142857142857e-10, 1.4446060436451282
    mu = analytic.bending_frequencies(P, R, F_CLAMPED, 3, "weak", T=T)
    string = np.arange(1, 4) * math.pi * math.sqrt(T)
    assert mu == pytest.approx(string * (1 + 2 * math.sqrt(R / (F_CLAMPED * T))), rel=1e-6)
    assert mu[0] > 1e3 * analytic.bending_frequencies(P, R, F_CLAMPED, 1, "weak")[0]


def test_tension_zero_is_the_papers_spectrum_and_compression_is_refused():
    assert analytic.bending_frequencies(1e-3, 0.55, F_CLAMPED, 5, "weak", T=0.0) == pytest.approx(
        analytic.bending_frequencies(1e-3, 0.55, F_CLAMPED, 5, "weak"), rel=0)
    with pytest.raises(ValueError):
        analytic.bending_frequencies(1e-3, 0.55, F_CLAMPED, 5, "weak", T=-1.0)
