"""Rung 1x: the exact characteristic function of the straight tether.

References: the collocation pencil (etcheck.rod.straight.collocation.damped_critical.first_root)
where it converges, the chi roots (rung 0), the 50-digit shooting
determinant of tests/independent.py, and an exponential-basis determinant
in mpmath written here (exponents from mpmath.polyroots, no scaling tricks
shared with the code under test), itself checked against the shooting
determinant where both are affordable.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(next(p for p in Path(__file__).resolve().parents if (p / "independent.py").exists())))
from independent import static_determinant  # noqa: E402

from etcheck.rod.core.parameters import F_CLAMPED, RodParameters  # noqa: E402
from etcheck.rod.straight.analytic import critical_loads  # noqa: E402
from etcheck.rod.straight.collocation.damped_critical import damped_critical, first_root  # noqa: E402
from etcheck.rod.straight.exact.determinant import (  # noqa: E402
    characteristic,
    evaluate,
    isotropic_characteristic,
    kernel_dimension,
)
from etcheck.rod.straight.exact.roots import exact_critical, exact_root, first_exact_root, string_limit_load  # noqa: E402

F = F_CLAMPED
SET = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)


@pytest.fixture(autouse=True, scope="module")
def _one_blas_thread():
    """The collocation references are dense QZ of a few hundred: threads only contend."""
    with threadpool_limits(limits=1, user_api="blas"):
        yield


# --- an independent reference in mpmath ---------------------------------------------------


def _polyroots(coeffs, **kw):
    """mpmath.polyroots of coefficients given highest first (mpmath 1.4 deprecates that order; 1.3 has no other)."""
    try:
        return mp.polyroots(coeffs[::-1], asc=True, **kw)
    except TypeError:
        return mp.polyroots(coeffs, **kw)


def expo_det(B, P, R, f, omega, T, dps=50):
    """Clamped determinant from exponentials e^{k (s - s_k)} (s_k = 1 for Re k > 0) with
    null vectors of the 2x2 symbol, in mpmath; complex, with a phase that is constant
    near a root (the basis is analytic in the parameters)."""
    with mp.workdps(dps):
        B, P, R, f, omega, T = (mp.mpf(x) for x in (B, P, R, f, omega, T))
        a, b, w2 = T + P * R * omega**2, T + P * omega**2, omega**2
        c = [R / f**2, -(R * b + a) / f, a * b - w2 * (R + 1) / f, w2 * (a + b) + B**2, w2**2]
        static = w2 == 0
        kap = _polyroots(c[:4] if static else c, maxsteps=400, extraprec=4 * dps)
        ks = [s * mp.sqrt(q) for q in kap for s in (1, -1)]
        ks.sort(key=lambda z: (float(mp.re(z)), float(mp.im(z))))
        cols = []
        for k in ks:
            Pu = R / f * k**4 - a * k**2 - w2
            Pv = k**4 / f - b * k**2 - w2
            g1, g2 = (B * k, Pu), (Pv, -B * k)
            cols.append((k, g1 if abs(g1[0]) + abs(g1[1]) >= abs(g2[0]) + abs(g2[1]) else g2))
        if static:  # k = 0 twice: the constant solutions
            cols += [(mp.mpf(0), (1, 0)), (mp.mpf(0), (0, 1))]
        M = mp.matrix(8, 8)
        for j, (k, (u, v)) in enumerate(cols):
            shift = 1 if mp.re(k) > 0 else 0
            for i, s in enumerate((0, 1)):
                e = mp.exp(k * (s - shift))
                M[4 * i, j], M[4 * i + 1, j], M[4 * i + 2, j], M[4 * i + 3, j] = u * e, u * k * e, v * e, v * k * e
        return mp.det(M)


def reference_changes_sign(p: RodParameters, axis: str, lo: float, hi: float) -> bool:
    """The mpmath determinant changes sign between axis values lo and hi (lo, hi doubles)."""
    def at(x):
        q = p.with_(**{axis: x})
        return expo_det(q.B, q.P, q.R, q.f, q.omega, q.T)

    r = at(lo) / at(hi)
    assert abs(mp.im(r)) < 1e-20 * abs(mp.re(r))  # constant phase: the ratio is real
    return bool(mp.re(r) < 0)


def test_mpmath_reference_agrees_with_the_shooting_determinant():
    """The two references locate the same roots (where shooting is affordable)."""
    for p, axis in ((SET.with_(omega=0.3), "B"), (RodParameters(P=0.0, R=2.5e-6, Gamma=0.77, T=0.5 / F), "B"),
                    (SET.with_(B=0.3, T=0.01), "omega")):
        x = exact_root(p, axis).value
        for lo, hi, sign_change in ((x * (1 - 1e-10), x * (1 + 1e-10), True), (0.9 * x, 0.95 * x, False)):
            q = {axis: lo}
            d_lo = static_determinant(**{"B": p.B, "P": p.P, "R": p.R, "f": p.f, "omega": p.omega, "T": p.T, **q})
            q = {axis: hi}
            d_hi = static_determinant(**{"B": p.B, "P": p.P, "R": p.R, "f": p.f, "omega": p.omega, "T": p.T, **q})
            assert (np.sign(d_lo) != np.sign(d_hi)) == sign_change
            assert reference_changes_sign(p, axis, lo, hi) == sign_change


# --- the characteristic function ------------------------------------------------------------


@pytest.mark.parametrize("kw", [dict(B=0.3, omega=0.2), dict(B=0.5, omega=0.3, T=0.01), dict(B=0.7, T=0.05),
                                dict(B=0.1, T=-0.001), dict(B=0.4), dict(B=2.0, omega=1.0, T=1.0),
                                dict(B=0.2, omega=0.6, T=0.3, R=0.01, P=0.0)])
def test_the_two_routes_give_the_same_function(kw):
    p = SET.with_(**kw)
    e, s = characteristic(p, "exponential"), characteristic(p, "schur")
    assert abs(e - s) <= 1e-11 * abs(s)
    ev = evaluate(p)
    assert ev.imaginary < 1e-12 and ev.value == pytest.approx(s, rel=1e-11)


def test_the_function_is_O1_and_continuous_at_extreme_scale_separation():
    """T f = 1e12 with R = 1e-7: layer exponents 3e9 next to string exponents 2 pi."""
    p = RodParameters(P=0.0, R=1e-7, Gamma=0.77, T=1e12 / F)
    x = np.linspace(0.5, 1.5, 41) * 2 * math.pi * p.T
    d = np.array([characteristic(p.with_(B=b)) for b in x])
    # no exponential growth (exp(3e9) would overflow), smooth on this grid
    assert np.all(np.isfinite(d)) and 1e-6 < np.max(np.abs(d)) < 1e20
    assert np.all(np.abs(np.diff(d)) < 0.2 * np.max(np.abs(d)))
    assert np.all(np.abs(np.diff(d, 2)) < 0.05 * np.max(np.abs(d)))


@pytest.mark.parametrize("kw", [dict(R=1.0, B=0.3, omega=0.2), dict(R=1.0, B=0.5, omega=0.3, T=0.01),
                                dict(R=1.0, B=0.7, T=0.05), dict(B=0.4), dict(B=1.9, R=0.01)])
def test_isotropic_problem_is_the_square_root(kw):
    """R = 1 or omega = T = 0: D is the square of the real complex-problem determinant."""
    p = SET.with_(**kw)
    for route in ("exponential", "schur"):
        assert characteristic(p) == pytest.approx(isotropic_characteristic(p, route) ** 2, rel=1e-10)


# --- roots against the collocation pencil -----------------------------------------------------

# (params, axis, options, collocation ladder): the smallest ladder that converges to 1e-9
COLLOCATION_SCENES = [
    (SET, "B", {}, (24,)),
    (SET.with_(omega=0.3), "B", {}, (32,)),
    (SET.with_(omega=0.6), "B", {}, (32,)),  # 0.8 of the spin at rest
    (SET.with_(T=0.01), "B", {}, (32,)),
    (SET.with_(B=0.3), "omega", {}, (32,)),
    (SET, "T", {"sign": -1.0}, (32,)),
    (SET.with_(B=0.3, omega=0.4), "ray", {}, (32,)),
    (SET.with_(R=1.0, omega=0.3, T=0.02), "B", {}, (32,)),
    (SET.with_(R=0.999, T=0.001), "B", {}, (32,)),  # a close pair: the first root is the lower one
    (SET.with_(R=0.1, T=1.0, P=0.0), "B", {}, (48,)),
    (SET.with_(R=0.01, T=0.5, P=0.0), "B", {}, (48,)),
    (SET.with_(R=1.0, T=50.0), "B", {}, (48,)),
]


@pytest.mark.parametrize("p, axis, kw, ladder", COLLOCATION_SCENES)
def test_roots_agree_with_the_collocation_pencil(p, axis, kw, ladder):
    ref = first_root(p, axis, tol=1e-9, ladder=ladder, **kw)
    assert ref.converged
    got = first_exact_root(p, axis, **kw)
    assert got.converged and got.model.startswith("rung 1x")
    assert abs(got.value - ref.value) <= 1e-9 * abs(ref.value)


# --- the strong-tension / tiny-R regime against mpmath -----------------------------------------


@pytest.mark.parametrize("Tf, omega", [(1.0, 0.0), (1e2, 0.0), (1e4, 0.0), (1e4, 0.5), (1e6, 0.0), (1e8, 0.0),
                                       (1e8, 3.0)])
def test_thin_tape_under_strong_tension_against_mpmath(Tf, omega):
    """R = 2.5e-6 (the 500 m aluminium tape): layers of width sqrt(R / (f T))."""
    p = RodParameters(P=0.0, R=2.5e-6, Gamma=0.77, T=Tf / F, omega=omega)
    r = exact_root(p, "B")
    assert r.multiplicity == 1 and r.error <= 1e-10
    x = r.value
    assert reference_changes_sign(p, "B", x * (1 - 1e-8), x * (1 + 1e-8))
    assert not reference_changes_sign(p, "B", 0.5 * x, x * (1 - 1e-8))  # no earlier root below


@pytest.mark.parametrize("p, axis", [(SET.with_(omega=0.3), "B"), (SET.with_(B=0.3, T=0.01), "omega"),
                                     (RodParameters(P=0.0, R=2.5e-6, Gamma=0.77, T=1e6 / F), "B"),
                                     (RodParameters(P=0.0, R=0.01, Gamma=0.77, T=1e8 / F, omega=3.0), "B"),
                                     (RodParameters(P=0.02, R=0.3, Gamma=0.77, T=1e4 / F, omega=5.0), "B")])
def test_error_estimate_bounds_the_true_error(p, axis):
    r = exact_root(p, axis)
    x, e = r.value, max(r.error, 1e-15)
    assert reference_changes_sign(p, axis, x * (1 - e), x * (1 + e))


# --- double roots ----------------------------------------------------------------------------


@pytest.mark.parametrize("R", [1.0, 21 / 38, 0.1, 1e-4, 2.5e-6])
def test_double_roots_at_rest_are_the_chi_roots(R):
    p = RodParameters(P=0.001, R=R, Gamma=0.77)
    r = exact_root(p, "B")
    assert r.multiplicity == 2
    assert abs(r.value - critical_loads(R, F, 1)[0]) <= 1e-10 * r.value
    assert kernel_dimension(p.with_(B=r.value)) == 2
    # D touches zero: the same sign on both sides, far below its size nearby
    near = [characteristic(p.with_(B=r.value * (1 + d))) for d in (-1e-3, 1e-3)]
    assert near[0] * near[1] > 0


def test_split_roots_are_simple_with_a_one_dimensional_kernel():
    p = SET.with_(T=0.01)
    r = exact_root(p, "B")
    assert r.multiplicity == 1 and kernel_dimension(p.with_(B=r.value)) == 1


def test_isotropic_rod_keeps_double_roots_under_spin_and_tension():
    p = SET.with_(R=1.0, omega=0.3, T=0.02)
    r = exact_root(p, "B")
    assert r.multiplicity == 2 and kernel_dimension(p.with_(B=r.value)) == 2


# --- the damped critical values ------------------------------------------------------------------


@pytest.mark.parametrize("kw", [dict(omega=0.25, B=0.3), dict(omega=0.25, B=0.3, T=0.01), dict(B=0.7),
                                dict(omega=0.8, B=0.1), dict(T=-0.01, B=0.1), dict(T=-1.0)])
def test_exact_critical_mirrors_damped_critical(kw):
    p = SET.with_(gamma=0.04375, **kw)
    ref, got = damped_critical(p, ladder=(32,)), exact_critical(p)
    assert ref.converged and got.converged and got.stable == ref.stable
    for a, b in ((got.critical_load, ref.critical_load), (got.critical_spin, ref.critical_spin),
                 (got.spin_at_rest, ref.spin_at_rest)):
        assert abs(a.value - b.value) <= 1e-9 * max(abs(b.value), 1e-3)


def test_exact_critical_needs_damping():
    with pytest.raises(ValueError):
        exact_critical(SET)


def test_tape_under_tension_is_decided_exactly():
    """500 m aluminium tape, EI1 = 3.65 N m^2, R = 2.5e-6, 0.18 N: layers of 7 mm."""
    EI1, L, T_N = 3.65, 500.0, 0.18
    p = RodParameters(P=0.0, R=2.5e-6, Gamma=0.77, T=T_N * L**2 / (F * EI1), gamma=0.01,
                      B=30e-6 * L**3 / (F * EI1))
    c = exact_critical(p)
    assert c.converged
    load = c.critical_load.value
    assert load == pytest.approx(string_limit_load(p, 2), rel=1e-5)
    assert reference_changes_sign(p, "B", load * (1 - 1e-9), load * (1 + 1e-9))
    assert c.stable == (p.B < load)


# --- the string limit ----------------------------------------------------------------------------


@pytest.mark.parametrize("R", [0.01, 21 / 38])
def test_string_limit_is_approached_with_the_predicted_order(R):
    """order 1 (the layer correction) leaves O(1/(f T)), order 2 O((f T)^-3/2)."""
    err = {}
    for Tf in (1e4, 1e6, 1e8):
        p = RodParameters(P=0.0, R=R, Gamma=0.77, T=Tf / F)
        x = exact_root(p, "B").value
        err[Tf] = [abs(string_limit_load(p, order) - x) / x for order in (0, 1, 2)]
    assert 10 * 0.7 < err[1e6][0] / err[1e8][0] < 10 / 0.7  # order 0: (f T)^-1/2
    for a, b in ((1e4, 1e6), (1e6, 1e8)):
        assert 100 * 0.7 < err[a][1] / err[b][1] < 100 / 0.7  # order 1: (f T)^-1
    assert err[1e4][2] / err[1e6][2] > 1000 * 0.5  # order 2: (f T)^-3/2
    assert err[1e8][2] < 1e-9


def test_string_limit_with_spin_and_rotary_inertia():
    for Tf in (1e6, 1e8):
        p = RodParameters(P=0.02, R=0.3, Gamma=0.77, T=Tf / F, omega=5.0)
        x = exact_root(p, "B").value
        assert abs(string_limit_load(p, 2) - x) < 3 * (Tf / 1e4) ** -1.5 * x


@pytest.mark.parametrize("B", [0.0, 1000.0])
def test_critical_spin_under_extreme_tension_is_the_whirling_string(B, R=2.5e-6):
    """Issue 11: at T = 1e7 the u and v string exponents differ by P omega^2 (1 - R) / T ~ 1e-8
    relative. The expanded quartic split that pair only to sqrt(eps) and the route fell back to
    Schur (error eps x 1e7 / gap): a spurious root 1.3e-3 low (9921.29) and formulations 2.8e-3 apart.
    The whirling string with welded ends: omega^2 = pi^2 a (1 + 2 eps_u)^2 - B^2 / (4 T), to O(eps_u^2)."""
    p = RodParameters(P=1e-9, R=R, Gamma=1 / 1.3, T=1e7, B=B, gamma=0.04375)
    r = exact_root(p.with_(omega=0.0), "omega")
    w = r.value
    a = p.T + p.P * p.R * w * w
    eps = math.sqrt(p.R / (p.f * a))
    string = math.sqrt((math.pi * math.sqrt(a) * (1 + 2 * eps)) ** 2 - B**2 / (4 * p.T))
    assert r.error < 1e-12
    assert w == pytest.approx(string, rel=1e-12 + 20 * eps**2)


def test_second_formulation_where_the_exponential_basis_stops_applying():
    """R = 0.9, P = 0.3, taut: next to the critical spin at this load the exponents coincide, and the second
    formulation (the exponential basis at other scales) raised ValueError there (an internal error of the
    check). It falls back to Schur where the basis does not apply; the unloaded rod has no critical spin, and
    the error of the critical spin is judged relative to the spin itself (its floor, 1 % of an infinite spin,
    made it NaN)."""
    from etcheck.rod.straight.exact.roots import exact_critical

    p = RodParameters(P=0.3, R=0.9, Gamma=1.0844737162142614e-4, f=F_CLAMPED, B=4.557013742222468, omega=0.0,
                      T=30.0, gamma=0.04)
    root = exact_root(p, "omega")
    assert 2e4 < root.value < 2.1e4
    c = exact_critical(p, 1e-8)
    assert not math.isnan(c.critical_spin.error)
    assert math.isinf(c.spin_at_rest.value)
    assert c.critical_load.error < 1e-8


def test_a_root_next_to_the_end_of_its_line_comes_from_the_determinant():
    """SET 8e-6 below its static load: the critical spin falls like a square root, and the pencil's round-off
    (N = 48: 2.8e-7 off) is amplified past the tolerance; the pencil says so (not converged, an estimate that
    bounds its error) and the determinant answers within its own estimate of the reference."""
    from etcheck.rod.straight.exact.roots import first_exact_root, pencil_or_exact

    p = RodParameters(P=1e-3, R=21 / 38, Gamma=0.76923, gamma=0.1, B=0.58539)
    ref = first_exact_root(p, "omega", 1e-12)
    pencil = damped_critical(p, tol=1e-8).critical_spin
    assert not pencil.converged
    assert abs(pencil.value - ref.value) / ref.value <= pencil.error
    both = pencil_or_exact(p, tol=1e-8)
    assert both.converged and both.critical_spin.model == "rung 1x (exact determinant)"
    assert abs(both.critical_spin.value - ref.value) / ref.value <= both.critical_spin.error + ref.error
    away = pencil_or_exact(p.with_(B=0.3), tol=1e-8)  # far from the end: the pencils alone
    assert away.converged and away.critical_spin.model == "rung 1 (static pencil)"
