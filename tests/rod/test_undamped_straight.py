"""Rung 1u: the exact undamped determinant E(mu) of the straight rod and the stability lines built on it.

Every check is against an independent computation: the Chebyshev collocation spectrum of the general
linear operator (eigenvalues, growth rates on either side of a located point), the static pencils, the
chi roots of eq. (91) and the string limit. The agreement with the spectral scans on eight scenes is
measured in benchmarks/bench_undamped.py (too slow for the suite).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.damped_critical import first_root
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.exact.roots import exact_critical, string_limit_load
from etcheck.rod.straight.exact.undamped import complex_pairs, complex_pairs_on_line, has_real_pair, undamped_critical
from etcheck.rod.straight.exact.undamped_kernel import (
    characteristic_mu,
    horner,
    rayleigh_floor,
    rounding_scale,
    stiffness_definite,
)
from etcheck.rod.straight.exact.undamped_lines import Line, stability_line, static_roots

SET = dict(P=1e-3, R=21 / 38, Gamma=0.76923)


def _growth(p: RodParameters) -> float:
    return float(np.max(spectrum(p, k=8, tol=1e-9).eigenvalues.real))


@pytest.fixture(scope="module")
def set_spin_line():
    """SET at B = 0.3: stable, divergence, stable again, flutter, stable again up to omega = 2."""
    return stability_line(RodParameters(**SET, B=0.3), "omega", 0.0, 2.0)


@pytest.mark.parametrize("B,omega,T", [(0.3, 0.25, 0.0), (0.0, 0.4, 0.0), (0.2, 0.0, 2.0), (0.5, 1.3, 0.5)])
def test_both_formulations_agree(B, omega, T):
    p = RodParameters(**SET, B=B, omega=omega, T=T)
    mu = np.array([-3.0, -0.2, 0.05, 0.7, 4.0, 31.0])
    a, b = characteristic_mu(p, mu, route="exponential"), characteristic_mu(p, mu, route="schur")
    assert np.all(np.isfinite(a))
    assert np.allclose(a, b, rtol=1e-10, atol=0)


@pytest.mark.parametrize("T", [0.0, 3.0, 500.0])
def test_uncoupled_beams_at_rest_have_the_sign_of_the_coupled_determinant(T):
    """At B = omega = 0 E is the product of two clamped Rayleigh-beam determinants: a positive multiple of the
    coupled determinant (Schur route), so its roots and its sign at a line's cut are the coupled ones."""
    p = RodParameters(**SET, T=T)
    mu = np.concatenate([-np.geomspace(1e3, 1e-3, 12), np.geomspace(1e-3, 1e5, 40)])
    ratio = characteristic_mu(p, mu, route="schur") / characteristic_mu(p, mu)
    assert np.all(np.isfinite(ratio)) and np.all(ratio > 0)


def test_roots_are_the_eigenvalues_of_the_collocation_spectrum():
    p = RodParameters(**SET, B=0.3, omega=0.25)
    lam = spectrum(p, k=10, tol=1e-10).eigenvalues
    mu = np.sort((-lam**2).real)
    torsion = (np.arange(1, 4) * math.pi) ** 2 * p.Gamma / (2 * p.P * p.f)  # decoupled, not a root of E
    bending = [m for m in mu if np.min(np.abs(torsion - m)) > 1e-6 * m]
    assert len(bending) >= 6
    for m in bending:
        lo, hi = characteristic_mu(p, np.array([m * (1 - 1e-9), m * (1 + 1e-9)]))
        assert lo * hi < 0, m  # a sign change within 1e-9 of every bending eigenvalue


def test_spin_line_crossings_are_confirmed_by_the_spectrum(set_spin_line):
    kinds = [c.kind for c in set_spin_line.crossings]
    assert kinds == [CriticalKind.DIVERGENCE, CriticalKind.DIVERGENCE, CriticalKind.FLUTTER, CriticalKind.FLUTTER]
    p = RodParameters(**SET, B=0.3)
    for c in set_spin_line.crossings:
        assert c.error < 1e-10 * c.value
        if c.kind == CriticalKind.FLUTTER:
            before, after = (_growth(p.with_(omega=c.value * (1 + s * 1e-7))) for s in (-1, 1))
            stable, unstable = (after, before) if not c.to_unstable else (before, after)
            assert stable < 1e-8 < 1e-5 < unstable  # Re lambda ~ sqrt(distance) past a Krein collision
    for a, b in set_spin_line.windows:
        assert _growth(p.with_(omega=0.5 * (a + b))) < 1e-8
    gaps = [(a, b) for (_, a), (b, _) in zip(set_spin_line.windows[:-1], set_spin_line.windows[1:])]
    assert len(gaps) == 2 and all(_growth(p.with_(omega=0.5 * (a + b))) > 1e-6 for a, b in gaps)


def test_divergence_points_are_the_static_pencil_roots(set_spin_line):
    first = set_spin_line.crossings[0]
    pencil = first_root(RodParameters(**SET, B=0.3), "omega")
    assert pencil.converged and first.value == pytest.approx(pencil.value, rel=1e-9)


def test_critical_values_at_an_operating_point():
    u = undamped_critical(RodParameters(**SET, B=0.3, omega=0.25), windows=False)
    assert u.converged and u.stable
    load = first_root(RodParameters(**SET, omega=0.25), "B")  # stable up to the first static point here
    assert u.critical_load.kind == CriticalKind.DIVERGENCE
    assert u.critical_load.value == pytest.approx(load.value, rel=1e-9)
    assert u.critical_spin.kind == CriticalKind.DIVERGENCE


@pytest.mark.parametrize("B,omega", [(0.3, 0.25), (0.1, 0.0), (0.05, 0.9), (0.0046, 1.2), (0.7, 0.25)])
def test_the_load_line_alone_gives_the_same_load_and_verdict(B, omega):
    """``spin=False`` (the sweep's critical lengths) skips the spin line: same critical load and stability."""
    p = RodParameters(**SET, B=B, omega=omega)
    full, alone = undamped_critical(p, windows=False), undamped_critical(p, windows=False, spin=False)
    assert (alone.critical_load.kind, alone.critical_load.value) == (full.critical_load.kind, full.critical_load.value)
    assert alone.stable == full.stable and math.isnan(alone.critical_spin.value)


#: Undamped taut scenes found by random draws that raised "could not isolate the change of stability" (R = 0.5,
#: large P, strong tension); at each both critical values are divergences: the damped static roots.
FOUND = [
    # the grid's nodes next to mu = 0 are 4 apart and a close pair of roots (0.42 and ~2) is found by zooming
    # in; placed at the midpoints of the zoom's sign changes, the first root fell below 0 or above it as the
    # load changed by one ulp and the count of real pairs flipped
    pytest.param(dict(P=7.27e-3, T=51.2, B=276.8, omega=0.031), id="close-pair-next-to-mu-zero"),
    # spinning up moves the high modes across the line's cut by more than their spacing between two samples:
    # two roots leave together, E at the cut keeps its sign, and the lost pair was taken for flutter
    pytest.param(dict(P=9.48e-2, T=16.4, B=47.5, omega=0.0152), id="two-modes-through-the-cut"),
    # the Rayleigh floor ignored the tension (see the test below); the whole scene takes 5 s
    pytest.param(dict(P=2.09e-3, T=1.51e4, B=4.681e4, omega=0.0345), id="taut-slow-spin", marks=pytest.mark.slow),
]


@pytest.mark.parametrize("scene", FOUND)
def test_found_taut_scenes_are_answered_by_their_static_roots(scene):
    p = RodParameters(R=0.5, Gamma=0.76923, **scene)
    u = undamped_critical(p, windows=False)
    damped = exact_critical(p.with_(gamma=0.01))
    assert u.converged and u.stable
    assert u.critical_load.value == pytest.approx(damped.critical_load.value, rel=1e-10)
    assert u.critical_spin.value == pytest.approx(damped.critical_spin.value, rel=1e-10)


def test_a_taut_rod_spun_slowly_has_no_spurious_real_pairs():
    """Strong tension, slow spin (found by random draws): the Rayleigh floor ignored the tension, so mu down
    to -1.3e-3 was sampled where, without load and at small lambda, the exponential basis is off by up to
    30 decades; its sign changes were taken for real pairs of eigenvalues. The floor now includes T pi^2:
    no real root can lie below 0 here, and none is sought."""
    p = RodParameters(P=2.09e-3, R=0.5, Gamma=0.76923, T=1.51e4)
    for omega in (0.0014375, 0.0043125, 0.0345):  # samples of the unloaded rod's spin line
        assert not has_real_pair(p.with_(omega=omega))


@pytest.mark.parametrize("R,T", [(21 / 38, 0.0), (0.2, 30.0), (0.9, 0.0), (0.5, 300.0)])
def test_real_pairs_only_past_the_first_static_load_at_rest(R, T):
    """Without spin and compression the stiffness is positive definite below the first static load: no real pair
    (the spin line of a sweep point relies on it and does not look); just past it without tension a root mu < 0
    (under tension the roots past it can come as a close pair that the 64-point scan need not see)."""
    from etcheck.rod.straight.exact.roots import exact_root

    p = RodParameters(P=1e-3, R=R, Gamma=0.76923, T=T)
    static = exact_root(p, "B").value
    assert not any(has_real_pair(p.with_(B=s * static)) for s in (0.2, 0.6, 0.97, 0.999))
    assert T > 0 or has_real_pair(p.with_(B=1.01 * static))


def test_without_spin_the_critical_load_is_the_first_chi_root():
    u = undamped_critical(RodParameters(**SET, B=0.1), windows=False)
    assert u.critical_load.value == pytest.approx(critical_loads(SET["R"], RodParameters(**SET).f, 1)[0], rel=1e-9)


def test_isotropic_rod_double_roots_at_rest():
    """R = 1: at zero spin every root of E is double (E is a square); the spin line still starts there."""
    p = RodParameters(P=1e-3, R=1.0, Gamma=0.76923, B=0.2)
    line = stability_line(p, "omega", 0.0, 1.5, samples=13)
    for a, b in line.windows:
        assert _growth(p.with_(omega=0.5 * (a + b))) < 1e-8


def test_thin_boundary_layers_undamped():
    """A 500 m aluminium tape under 0.18 N (layers of 1e-5 L): beyond collocation; without spin the
    undamped critical load is the static one (the damped exact route) and near the string limit."""
    L, EI1, EI2, rho_A = 500.0, 3.65, 9.3e-6, 2.7e-3
    f = RodParameters(P=0.0, R=1.0, Gamma=1.0).f
    p = RodParameters(P=EI1 / 70e9 / (rho_A / 2700) / L**2, R=EI2 / EI1, Gamma=1 / 1.33,
                      T=0.18 * L**2 / (f * EI1), B=30e-6 * L**3 / (f * EI1))
    u = undamped_critical(p, windows=False)
    assert u.converged and u.stable
    damped = exact_critical(p.with_(gamma=0.01)).critical_load.value
    assert u.critical_load.value == pytest.approx(damped, rel=1e-12)
    assert u.critical_load.value == pytest.approx(string_limit_load(p, order=2), rel=1e-5)


def test_a_line_that_needs_too_many_samples_is_refused_not_run():
    """Long, taut, thin tethers with large P have tens of thousands of modes below the cut: a line that would
    need more than MAX_GRID samples per point raises ArithmeticError at once (the check then says it is
    not answered) instead of running for minutes; without spin the critical load is still answered."""
    p = RodParameters(P=0.05, R=1e-4, Gamma=0.76923, omega=0.01, B=0.38, T=1e5)
    with pytest.raises(ArithmeticError, match="mu samples per point"):
        undamped_critical(p, tol=1e-10, windows=False)
    rest = undamped_critical(p.with_(omega=0.0), tol=1e-10, windows=False)
    assert rest.critical_load.kind == "divergence" and rest.critical_load.converged
    assert rest.critical_spin.kind == "not located" and "mu samples" in rest.critical_spin.message


@pytest.mark.parametrize("B,omega", [(0.3, 1.5), (0.3, 2.0), (0.6, 0.8)])
def test_complex_pairs_at_a_point_as_along_the_located_line(B, omega):
    """Two routes to the number of complex pairs at a point: the located spin line (every change of stability
    on the way) and the line's two ends with the roots that pass its cut in between."""

    p = RodParameters(**SET, B=B, omega=omega)
    line = stability_line(p, "omega", 0.0, omega)
    pairs, real, _ = complex_pairs(p)
    assert pairs == line.pairs_at_hi
    assert (pairs > 0 or real) == line.unstable_at(omega)


def test_roots_through_the_cut_all_at_once_as_one_by_one():
    """The roots that pass a line's cut (the unloaded long tether spun up: 7 sign changes of E at the cut, roots
    entering and leaving) get, all located together, the directions that a scalar Brent root and central
    differences give each on its own."""
    from scipy.optimize import brentq


    line = Line(RodParameters(P=2e-6, R=0.55, Gamma=0.77, f=500.0), "omega", 0.0, 1000.0)
    x = line.mu_cut
    ps = np.linspace(0.0, 1000.0, 97)
    top = line.E(ps, np.full(ps.size, x))
    j = np.nonzero(np.sign(top[:-1]) * np.sign(top[1:]) < 0)[0]

    def one(pa: float, pb: float) -> int:
        pc = brentq(lambda q: line.E(q, x).item(), pa, pb, xtol=1e-12 * max(abs(pa), abs(pb)))
        hp, hm = 1e-6 * abs(pb - pa), 1e-6 * abs(x)
        e = line.E(np.array([pc - hp, pc + hp, pc, pc]), np.array([x, x, x - hm, x + hm]))
        return -1 if -((e[1] - e[0]) / hp) / ((e[3] - e[2]) / hm) > 0 else 1

    expected = [one(ps[i], ps[i + 1]) for i in j]
    assert j.size >= 5 and {-1, 1} <= set(expected)
    assert line._through_cut(ps[j], ps[j + 1], x, 1).tolist() == expected
    assert line._through_cut(ps[j + 1][::-1], ps[j][::-1], x, -1).tolist() == expected[::-1]  # backwards, above

def test_taut_scene_whose_unloaded_spin_line_spent_the_schur_budget():
    """Regression (random taut undamped scene, R = 0.5): anchoring the load line by locating every change on the
    unloaded rod's spin line sent 33 points past the Schur route's budget; the critical load is the first
    static load at this spin (a divergence), as the exact static determinant gives it."""
    p = RodParameters(P=2.9738126427068263e-06, R=0.5, Gamma=0.76923, B=17331.56785504523,
                      omega=0.014348113597318036, T=6959.611458591513)
    u = undamped_critical(p, windows=False)
    assert u.critical_load.kind == "divergence" and u.stable
    assert u.critical_load.value == pytest.approx(exact_critical(p.with_(gamma=1e-3)).critical_load.value, rel=1e-10)


NEARLY_ISOTROPIC = RodParameters(P=0.00014843474801984845, R=0.999, Gamma=0.76923, B=233.00889815408212,
                                  omega=1.3538859962783918, T=198.00648507177962)


def test_nearly_isotropic_pair_closer_than_the_samples_is_counted():
    """Regression (random taut undamped scene, R = 0.999): under tension the u and v string modes split by far less
    than the zoom's finest samples; the parabola through them dips below zero but was taken as no root because
    the ratio's sign was dropped ("inconsistent root count ... 2 roots in all, 4 real"). Now counted as a pair.
    Its first instability is a divergence interval 0.004 wide at B = 1251.98, between two static loads closer than
    the line's scan of static points (400 samples to B = 1300): once reported as the flutter at 1252.56; the
    collocation spectrum grows at 1 + 1e-6 of it and not at 1 + 1e-4 (the slow test below)."""
    u = undamped_critical(NEARLY_ISOTROPIC, windows=False)
    assert u.critical_load.converged and u.critical_load.kind == "divergence" and u.stable
    assert u.critical_load.value == pytest.approx(1251.9832019, rel=1e-9)


@pytest.mark.slow
def test_nearly_isotropic_flutter_load_against_the_collocation_spectrum():
    """The scene above: its critical load is bracketed by the whole collocation spectrum (N = 48 for the layers at
    T-bar = 198)."""
    from helpers import collocation_growth

    Bc = undamped_critical(NEARLY_ISOTROPIC, windows=False).critical_load.value
    assert collocation_growth(NEARLY_ISOTROPIC.with_(B=Bc * (1 - 1e-6)), N=48) < 1e-8
    assert collocation_growth(NEARLY_ISOTROPIC.with_(B=Bc * (1 + 1e-6)), N=48) > 1e-4


def test_horner_in_k_squared_is_the_polynomial_and_its_derivative():

    rng = np.random.default_rng(3)
    c = rng.normal(size=(40, 9)) + 1j * rng.normal(size=(40, 9))
    c[:, [1, 3, 5]] = 0.0  # the rows of the exponential basis: p(k) = Q(k^2) + c7 k
    z = rng.normal(size=(40, 8)) + 1j * rng.normal(size=(40, 8))
    p, q = horner(c, z)
    for i in range(c.shape[0]):
        np.testing.assert_allclose(p[i], np.polyval(c[i], z[i]), rtol=1e-13)
        np.testing.assert_allclose(q[i], np.polyval(np.polyder(c[i]), z[i]), rtol=1e-13)
        np.testing.assert_allclose(rounding_scale(c, z)[i], np.polyval(np.abs(c[i]), np.abs(z[i])), rtol=1e-13)


@pytest.mark.parametrize("omega", [0.0, 0.25])
def test_the_load_line_followed_by_a_helper_gives_the_same_answer(omega):
    """On two cores the load line is followed in a forked helper while the spin line is followed here."""
    from etcheck.runtime import parallel

    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, B=0.2, omega=omega, T=0.05, gamma=0.0)
    with parallel.serial():
        serial = undamped_critical(p, 1e-8, windows=True)
    import etcheck.rod.straight.exact.roots as ex
    import etcheck.rod.straight.exact.undamped as us

    for module in (us, ex):  # nothing memoised: the helper computes the load line afresh
        for fn in vars(module).values():
            if hasattr(fn, "cache_clear"):
                fn.cache_clear()
    with parallel.serial(False):
        assert undamped_critical(p, 1e-8, windows=True) == serial


def _edge(proof, lo: float = 0.0, hi: float = 10.0) -> float:
    """The largest x in (lo, hi) where proof(x) still holds (bisection; proof(lo) holds)."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if proof(mid) else (lo, mid)
    return lo


@pytest.mark.parametrize("R,T,P", [(21 / 38, 0.0, 1e-12), (1.0, 0.0, 1e-12), (0.3, -0.01, 1e-12), (0.5, 4.0, 2e-3)])
def test_the_stiffness_proof_holds_to_its_edge_and_no_further(R, T, P):
    """The proof that the unloaded stiffness is positive (no real and no complex pair: the load line's anchor
    and the real-pair test take no samples then) against the counted spin line from omega = 0: just inside its
    edge every root is real and positive; just outside it, without rotary inertia and tension, the weak beam's
    first clamped mode has gone soft (its edge is sharp there: beta^4 R / f) and, for R < 1 (one negative
    direction: Kelvin-Tait-Chetaev), a real pair appears (R = 1 loses two at once: gyroscopic stabilisation).
    Under compression (T < 0) the proof is looser than the rod: its edge is only checked from inside."""

    p = RodParameters(P=P, R=R, Gamma=0.76923, T=T)
    lo = _edge(lambda w: stiffness_definite(p.with_(omega=w)))
    assert lo > 0.1
    assert complex_pairs_on_line(p.with_(omega=0.999 * lo))[:2] == (0, False)
    if T == 0.0:
        assert lo**2 == pytest.approx(R * 4.730040744862704**4 / p.f, rel=1e-8)  # the proof keeps a margin of 1e-9
        assert R == 1.0 or complex_pairs_on_line(p.with_(omega=1.001 * lo))[1]  # the weak mode's real pair


@pytest.mark.parametrize("R,T,omega", [(21 / 38, 0.0, 0.0), (0.05, 0.0, 0.0), (0.9, 2.0, 0.0), (0.3, -0.01, 0.0),
                                       (21 / 38, 0.0, 0.4), (0.1, 1.0, 0.2)])
def test_the_stiffness_proof_under_load_stops_short_of_the_static_load(R, T, omega):
    """With load the proof bounds the load's term (2 B int u' v) by the clamped beams' bending: along B it must stop
    short of the first static load (where K is singular: a proof past it would be wrong), and where it holds the
    counted line has no real and no complex pair."""
    from etcheck.rod.straight.exact.roots import exact_root

    p = RodParameters(P=1e-3, R=R, Gamma=0.76923, T=T, omega=omega)
    static = exact_root(p, "B").value
    edge = _edge(lambda B: stiffness_definite(p.with_(B=B)), 0.0, 10.0 * static)
    assert 0.05 * static < edge < static
    if omega:
        assert complex_pairs_on_line(p.with_(B=0.999 * edge))[:2] == (0, False)


@pytest.mark.parametrize("omega", [0.2, 0.3])
def test_a_compressed_spinning_rod_has_a_critical_load(omega):
    """Under compression (below the Euler load) the unloaded rod's spin line starts at omega = 0, B = 0, where E is
    the product of two beam determinants; at mu = 0 it came from another formulation, two decades larger, and the
    dips next to it were taken for a double root: a complex pair at B = 0, so a critical load of 0 (found by the
    proof of :func:`test_the_stiffness_proof_holds_to_its_edge_and_no_further`; at omega = 0.3 the proof
    does not apply and the line decides). The critical load against the collocation spectrum either side."""
    p = RodParameters(P=1e-3, R=0.3, Gamma=0.76923, T=-0.01, omega=omega, B=0.05)
    u = undamped_critical(p, windows=False)
    assert u.critical_load.kind == "divergence" and u.converged and u.stable
    Bc = u.critical_load.value
    assert _growth(p.with_(B=0.98 * Bc)) < 1e-8 < _growth(p.with_(B=1.02 * Bc))


@pytest.mark.parametrize("R,load", [(0.01, 10.0), (0.01, 100.0), (0.1, 30.0), (21 / 38, 100.0)])
def test_no_real_root_below_the_rayleigh_floor(R, load):
    """The lines sample mu from the Rayleigh floor up: a real root below it is never counted. Heavily loaded weak
    rods (the load's term bounded with its factor 2 and the best split of |u|, |v|): E keeps its sign on a fine
    grid from three times the floor down to it, and has its lowest root between the floor and 0. With the factor
    1 the floor of R = 0.01 at ten times its static load was -64.6 and the lowest root -73.1."""
    from etcheck.rod.straight.exact.roots import exact_root

    p = RodParameters(P=0.0, R=R, Gamma=0.77)
    q = p.with_(B=load * exact_root(p, "B").value)
    floor = rayleigh_floor(q, q.B, 0.0, 0.0)
    below = characteristic_mu(q, np.linspace(3.0 * floor, floor, 6001))
    assert np.all(np.sign(below) == np.sign(below[0]))
    above = characteristic_mu(q, np.linspace(floor, 0.0, 6001))
    assert np.any(np.sign(above[:-1]) != np.sign(above[1:]))


def test_a_close_pair_of_static_loads_bounds_an_unstable_interval():
    """A taut tether (R = 0.8, T-bar = 50) past its string load: two static loads 0.43 apart at B = 318, between two
    of the 400 samples of the line's scan of static points; the rod is unstable between them (a real pair), which
    the 25 samples of the load line never saw: the first instability was reported as the flutter at 318.49. Now the
    scan splits the pair at its dip and the line samples either side of both; the collocation spectrum grows
    between them."""

    p = RodParameters(P=7.56939008700586e-05, R=0.8, Gamma=0.77, B=0.6070943507877418, omega=0.748300882787012,
                      T=50.0)
    roots = static_roots(p, "B", 325.0)
    assert roots.size == 2 and 0.4 < roots[1] - roots[0] < 0.5
    u = undamped_critical(p, windows=False)
    assert u.critical_load.kind == "divergence" and u.critical_load.value == pytest.approx(roots[0], rel=1e-9)
    assert _growth(p.with_(B=0.5 * (roots[0] + roots[1]))) > 1e-3


def test_two_roots_through_the_cut_between_two_of_its_points_are_counted():
    """A taut tether with large rotary inertia spun fast (R = 0.8, P = 0.027, T-bar = 50: about 200 roots below the
    spin line's cut near omega = 17): two roots passed the cut between two of the 33 points between samples, the
    count missed them, and the bisection met a change of stability with no root on the move ("could not isolate").
    The pair shows as a dip of |E| at the cut and is split; the critical spin then located is the collocation
    spectrum's (stable just below, growing just past it)."""
    p = RodParameters(P=0.02656164711598646, R=0.8, Gamma=0.77, B=0.16325064945998125, omega=0.2535642542278924,
                      T=50.0)
    u = undamped_critical(p, windows=False)
    spin = u.critical_spin
    assert spin.kind == "divergence" and spin.converged and u.stable
    assert _growth(p.with_(omega=0.999 * spin.value)) < 1e-8 < 1e-3 < _growth(p.with_(omega=1.00001 * spin.value))


def test_a_nearly_round_wire_pair_between_two_samples_is_not_a_collision():
    """R = 0.97 spun at 2.6: its u and v roots come in pairs closer than the lines' samples. A pair between two
    samples, with no dip of |E| at either, looked like two real roots that had met and left the real axis: flutter
    reported at B = 0.772, where the collocation spectrum is still stable (it first grows at 0.7764). The pair is
    looked for again by a fine scan at the sample that lacks it; the flutter load is the spectrum's."""
    p = RodParameters(P=0.001017571917077209, R=0.97, Gamma=0.77, B=0.978133116954041, omega=2.612414557492265)
    load = undamped_critical(p, windows=False).critical_load
    assert load.kind == "flutter" and load.converged
    assert _growth(p.with_(B=(1 - 1e-6) * load.value)) < 1e-8 < 1e-4 < _growth(p.with_(B=(1 + 1e-6) * load.value))
