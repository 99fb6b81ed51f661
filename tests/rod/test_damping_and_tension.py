"""Heavy Kelvin-Voigt damping and strong tension: the regimes where a naive
spectral solve fails (accumulation of eigenvalues at -1/gamma; boundary layers).
References from tests/independent.py (exact shooting), not the solver under test."""

from __future__ import annotations

import numpy as np
import pytest
from independent import first_static_load

from etcheck.rod.core.parameters import F_CLAMPED, RodParameters
from etcheck.rod.core.spectrum import damping_cluster, spectrum
from etcheck.rod.straight.collocation.spectral import THRESHOLD, critical_load, straight_family
from etcheck.rod.straight.collocation.static_map import plane, stable_rows, static_curves


@pytest.mark.parametrize("gamma", [0.2, pytest.param(0.5, marks=pytest.mark.slow), 2.0])  # 0.5: between the two
def test_heavy_damping_spectrum_converges_outside_the_cluster(gamma):
    p = RodParameters(P=0.001, R=0.5, Gamma=0.77, omega=0.2, gamma=gamma)
    s = spectrum(p, k=6)
    assert s.converged, s.message
    assert s.eigenvalues.size >= 1
    assert not np.any(damping_cluster(s.eigenvalues, gamma))
    assert np.all(s.eigenvalues.real < 0)  # damped, below the critical spin
    # the lowest mode is the same at a fixed, different resolution
    fixed = spectrum(p, k=6, N=40)
    assert fixed.eigenvalues[0] == pytest.approx(s.eigenvalues[0], rel=1e-8)


@pytest.mark.slow  # 7 s of spectral scans; the damped pencils against the scans: tests/studies/test_sweep.py
def test_damping_does_not_move_the_divergence_load():
    # Kelvin-Tait-Chetaev: with damping, stability is lost where the static operator is singular
    ref = first_static_load(0.001, 0.5, F_CLAMPED, omega=0.2, B_max=1.0)
    for gamma in (0.0, 1.0):  # undamped and heavily damped (the paper's 0.04375 is covered by the check tests)
        c = critical_load(RodParameters(P=0.001, R=0.5, Gamma=0.77, omega=0.2, gamma=gamma))
        assert c.kind == "divergence" and c.converged
        assert c.value == pytest.approx(ref, rel=1e-9)


@pytest.mark.slow  # 5 s; tension against independent solvers: tests/rod/test_exact_straight.py, tests/checks
def test_strong_tension_raises_the_critical_load():
    T = 0.5  # f T = 250: boundary layers of width ~ 0.06
    c = critical_load(RodParameters(P=0.001, R=0.3, Gamma=0.77, omega=0.1, T=T, gamma=0.04375), N=32)
    ref = first_static_load(0.001, 0.3, F_CLAMPED, omega=0.1, T=T, B_max=4.0, n=60)
    assert c.converged and c.kind == "divergence"
    assert c.value == pytest.approx(ref, rel=1e-8)
    assert c.value > first_static_load(0.001, 0.3, F_CLAMPED, omega=0.1, B_max=2.0)


def test_damped_map_rows_end_at_the_critical_load():
    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, gamma=0.04375)
    spins = [0.0, 0.25, 0.5, 0.8]
    rows = stable_rows(p, static_curves(p, 1.0, 1.0, omega_rows=spins, n_loads=4), B_max=1.0)
    for w, row in zip(spins, rows):
        c = critical_load(p.with_(omega=w))
        if c.kind == "unstable at start":  # above the critical spin: no stable load at all
            assert row == [] or row[0][0] > 0
        else:
            assert row[0][0] == 0.0
            assert row[0][1] == pytest.approx(c.value, rel=1e-9)


@pytest.mark.parametrize("T", [0.0, 0.3])
def test_crossing_count_classifies_like_the_growth_rate(T):
    # the map's pieces are classified by counting crossing directions, no eigenvalue solve; an
    # independent growth evaluation at each piece's middle must agree, also past the second root
    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, gamma=0.04375, T=T)
    spins, B_max = [0.0, 0.3, 0.9], 4.5
    curves = static_curves(p, B_max, 1.0, omega_rows=spins, n_loads=4, N=16)
    fam = straight_family(p, 16)
    for w, roots, row in zip(spins, curves.loads, stable_rows(p, curves, B_max)):
        edges = [0.0, *roots[roots > 0], B_max]
        assert len(edges) >= 4  # at least two roots crossed
        for a, b in zip(edges[:-1], edges[1:]):
            if b - a <= 1e-9 * b:
                continue  # between the members of a double root (omega = 0): no piece
            x = 0.5 * (a + b)
            counted_stable = any(lo <= x <= hi for lo, hi in row)
            assert counted_stable == (fam.growth(x, w, T) <= THRESHOLD), (w, a, b)


def test_plane_roots_are_the_pencil_roots():
    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, gamma=0.04375, T=0.2)
    fam, pl = straight_family(p, 24), plane(p, 24)
    for w in (0.0, 0.4, 1.1):
        qz = fam.pencil_roots("B", 0.0, w, p.T)
        small = pl.roots("B", w * w)[0]
        qz, small = qz[np.abs(qz) < 5], small[np.abs(small) < 5]
        assert small.size == qz.size and small.size > 0
        assert np.allclose(small, qz, rtol=1e-10, atol=0)
    for B in (0.0, 0.5):
        qz = fam.pencil_roots("omega", B, 0.0, p.T)
        small = pl.roots("w", B)[0]
        qz, small = qz[np.abs(qz) < 5], small[np.abs(small) < 5]
        assert small.size == qz.size and small.size > 0
        assert np.allclose(small, qz, rtol=1e-10, atol=0)


def test_no_rotary_inertia_with_damping():
    # P = 0: torsion has no inertia, every torsion mode sits exactly at -1/gamma
    p = RodParameters(P=0.0, R=21 / 38, Gamma=1 / 1.3, omega=0.12, gamma=0.04375)
    s = spectrum(p)
    assert s.converged, s.message
    assert not np.any(damping_cluster(s.eigenvalues, p.gamma))
    c = critical_load(p)
    assert c.kind == "divergence"
    assert c.value == pytest.approx(first_static_load(0.0, 21 / 38, F_CLAMPED, omega=0.12, B_max=1.0), rel=1e-9)


@pytest.mark.parametrize("where", ["two cores", "one core"])
def test_static_curves_are_the_same_on_two_cores(where):
    """Rows and columns are shared with a forked helper where it can help: the same numbers."""
    from etcheck.runtime import parallel

    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, gamma=0.04375, omega=0.3)
    spins = np.linspace(0.0, 0.9, 6)

    def run():
        return static_curves(p, 2.0, 1.0, omega_rows=spins, n_loads=5, N=16)

    with parallel.serial():
        serial_curves = run()
    with parallel.serial(where == "one core"):
        curves = run()
    np.testing.assert_array_equal(curves.B, serial_curves.B)
    np.testing.assert_array_equal(curves.omega_points, serial_curves.omega_points)
    for a, b in zip(curves.loads + curves.changes, serial_curves.loads + serial_curves.changes):
        np.testing.assert_array_equal(a, b)
