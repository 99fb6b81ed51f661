"""The undamped isotropic tether (R = 1) from the scalar complex problem D+ (etcheck.rod.straight.exact.undamped_isotropic).

Checked across models: the roots of D+ are roots of the coupled real determinant E(mu) of
etcheck.rod.straight.exact.undamped; with P = 0 the spin is a change of frame (the static load at rest is
critical at every spin, exactly); every critical value and window edge is bracketed by the full dense
collocation spectrum (rod.linear, every eigenvalue, no selection).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from helpers import collocation_growth
from scipy.optimize import brentq

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.exact.roots import exact_root
from etcheck.rod.straight.exact.undamped import has_real_pair, undamped_critical
from etcheck.rod.straight.exact.undamped_isotropic import characteristic_plus
from etcheck.rod.straight.exact.undamped_kernel import characteristic_mu

GAMMA = 0.76923


def _rest(p: RodParameters) -> float:
    return exact_root(p.with_(B=0.0, omega=0.0), "B").value


def test_plus_roots_are_roots_of_the_coupled_determinant():
    """Every real root Omega of D+ makes E(mu) of the coupled 8 x 8 problem change sign at mu = Omega^2 (a root
    at Omega < 0 is a mode of the other whirl direction at -Omega); D+ is real and its two formulations agree."""
    p = RodParameters(P=0.1, R=1.0, Gamma=GAMMA, B=1.0, omega=0.05, T=0.3)
    x = np.linspace(-6.0, 6.0, 1201)
    D = characteristic_plus(p, x)
    assert np.allclose(D, characteristic_plus(p, x, route="schur"), rtol=1e-8, atol=1e-10 * np.max(np.abs(D)))
    i = np.nonzero(np.sign(D[:-1]) * np.sign(D[1:]) < 0)[0]
    roots = [brentq(lambda om: characteristic_plus(p, om).item(), x[j], x[j + 1], xtol=1e-15) for j in i]
    assert len(roots) >= 10 and min(roots) < 0 < max(roots)
    for om in roots:
        E = characteristic_mu(p, om**2 * np.array([1 - 1e-7, 1 + 1e-7]))
        assert E[0] * E[1] < 0, om


@pytest.mark.parametrize("omega", [0.3, 1.0, 2.5])
def test_without_rotary_inertia_spin_is_a_change_of_frame(omega):
    """P = 0: the whirl w(s) exp(i Omega t) in the rotating frame is exp(i (Omega + omega) t) in the inertial one,
    so the static load at rest is critical at every spin (a collision at Omega = -omega), to round-off."""
    p = RodParameters(P=0.0, R=1.0, Gamma=GAMMA, T=2.0, omega=omega)
    u = undamped_critical(p, windows=False)
    assert u.critical_load.converged
    assert u.critical_load.value == pytest.approx(_rest(p), rel=1e-10)
    assert "Omega = " + f"{omega:.9g}"[:6] in u.critical_load.message


def test_below_the_static_load_at_rest_stable_at_every_spin():
    """The hyperbolic bound: below the static load at rest no spin destabilises an undamped isotropic rod (the
    collocation spectrum agrees at spins from 0.2 to 8, rotary inertia P = 0.05); just past it, at rest, a real
    pair of eigenvalues."""
    p = RodParameters(P=0.05, R=1.0, Gamma=GAMMA, T=0.5)
    Bs = _rest(p)
    u = undamped_critical(p.with_(B=0.95 * Bs, omega=1.0))
    assert u.stable and u.critical_spin.kind == "never" and "every spin" in u.critical_spin.message
    assert not has_real_pair(p.with_(B=0.95 * Bs, omega=3.0))
    for omega in (0.2, 2.0, 8.0):
        assert collocation_growth(p.with_(B=0.95 * Bs, omega=omega)) < 1e-8
    assert collocation_growth(p.with_(B=1.02 * Bs)) > 1e-3


@pytest.mark.parametrize("kw", [dict(P=0.02, T=2.0, omega=1.0), dict(P=0.1, T=0.3, omega=0.05),
                                dict(P=1e-3, T=-0.05, omega=0.3)])  # compressed, short of its Euler load
def test_critical_load_against_the_collocation_spectrum(kw):
    """Gyroscopically raised critical loads (above the static load at rest, flutter): stable just below, unstable
    just above by the whole collocation spectrum."""
    p = RodParameters(R=1.0, Gamma=GAMMA, **kw)
    u = undamped_critical(p, windows=False)
    Bc = u.critical_load.value
    assert u.critical_load.converged and u.critical_load.kind == "flutter" and Bc > _rest(p)
    assert collocation_growth(p.with_(B=Bc * (1 - 1e-6))) < 1e-8
    assert collocation_growth(p.with_(B=Bc * (1 + 1e-6))) > 1e-5


def test_stable_window_against_the_collocation_spectrum():
    """Past the static load at rest (B = 14 > 13.956) the spinning rod is restabilised gyroscopically: the window's
    start is bracketed by the collocation spectrum."""
    p = RodParameters(P=0.02, R=1.0, Gamma=GAMMA, T=2.0, B=14.0, omega=1.0)
    u = undamped_critical(p)
    assert u.critical_spin.kind == "unstable at start" and not u.stable
    start = u.windows[0][0]
    assert 0.5 < start < 2.0
    assert collocation_growth(p.with_(omega=start * (1 - 1e-6))) > 1e-6
    assert collocation_growth(p.with_(omega=start * (1 + 1e-6))) < 1e-8


def test_unstable_where_a_selected_spectrum_saw_a_window():
    """Regression: B = 20 at T = 0 (past three static loads at rest), omega = 6: the spectral scan's k modes
    nearest the axis saw a stable window at omega in [5.42, 7.14]; the whole spectrum has lambda = 4.235 +- 2.741 i
    there, and the lines of D+ find no window."""
    p = RodParameters(P=0.05, R=1.0, Gamma=GAMMA, T=0.0, B=20.0, omega=6.0)
    u = undamped_critical(p)
    assert not u.stable and u.windows == ()
    assert collocation_growth(p) == pytest.approx(4.23499, rel=1e-4)


TAUT = (3.3195457008935313e-03, 490.5875991336071, 1731.180710937537, 0.05727789819714589)


@pytest.mark.slow
def test_taut_isotropic_critical_load_against_the_collocation_spectrum():
    """The first taut scene below, bracketed by the collocation spectrum to 1e-4 (N = 48 shifts the load by 3e-6
    there: its boundary layers)."""
    P, T, B, omega = TAUT
    p = RodParameters(P=P, R=1.0, Gamma=GAMMA, B=B, omega=omega, T=T)
    Bc = undamped_critical(p, windows=False).critical_load.value
    assert collocation_growth(p.with_(B=Bc * (1 - 1e-4)), N=48) < 1e-8
    assert collocation_growth(p.with_(B=Bc * (1 + 1e-4)), N=48) > 1e-3


@pytest.mark.parametrize("P,T,B,omega", [
    TAUT,
    pytest.param(0.00109839696169695, 39395.18081821686, 311279.20897419355, 0.4475983236152271,
                 marks=pytest.mark.slow),
])
def test_taut_isotropic_scenes_are_answered(P, T, B, omega):
    """Regression: random undamped taut R = 1 scenes that the coupled determinant could not answer (touching
    roots; the Schur route's budget): flutter just past the static load at rest (the first is checked against the
    collocation spectrum above)."""
    p = RodParameters(P=P, R=1.0, Gamma=GAMMA, B=B, omega=omega, T=T)
    u = undamped_critical(p, windows=False)
    Bc = u.critical_load.value
    assert u.critical_load.converged and u.critical_load.kind == "flutter"
    assert _rest(p) < Bc < _rest(p) * (1 + 1e-2)
    assert math.isfinite(u.critical_load.error)


def test_collocation_indicator_looks_at_the_whole_coupled_band():
    """The same scene on the collocation route: the flutter pair lambda = 4.235 +- 2.741 i lies beyond the 12
    least-|lambda| pairs (a dense low spectrum: P = 0.05, B past three static loads); the undamped stability
    indicator looks at every eigenvalue of the band that load and spin reshape, so it sees it (it saw a stable
    window at omega in [5.42, 7.14])."""
    from etcheck.rod.straight.collocation.spectral import straight_family

    p = RodParameters(P=0.05, R=1.0, Gamma=GAMMA, T=0.0)
    assert straight_family(p, 24).growth(20.0, 6.0, 0.0) == pytest.approx(collocation_growth(p.with_(B=20.0, omega=6.0)), rel=1e-6)


def test_a_change_of_stability_below_the_static_load_at_rest_is_refused(monkeypatch):
    """The hyperbolic bound is also a check of the load line: a change located below the static load at rest
    (root counts not resolved, e.g. next to the rotary-inertia accumulation of a taut tether's modes at
    Omega^2 = T / P) ends in ArithmeticError ("not located"), never in a wrong critical load."""
    import etcheck.rod.straight.exact.undamped as us

    p = RodParameters(P=0.05, R=1.0, Gamma=GAMMA, B=0.0, omega=1.0, T=30.0, gamma=0.0)
    rest = exact_root(p.with_(B=0.0, omega=0.0), "B").value
    real = us.stability_line

    def early(params, axis, lo, hi, **kw):
        line = real(params, axis, lo, hi, **kw)
        if axis != "B":
            return line
        fake = us.Crossing(0.99 * rest, 1e-9, "flutter", 1.0, True, (0.99 * rest, 0.99 * rest))
        return replace(line, crossings=(fake, *line.crossings))

    monkeypatch.setattr(us, "stability_line", early)
    with pytest.raises(ArithmeticError, match="below the static load at rest"):
        undamped_critical(p, 1e-8, windows=False)
