"""Stability of the straight rod (etcheck.rod.straight.collocation.spectral)."""

import numpy as np
import pytest
from scipy.optimize import brentq

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum
from etcheck.rod.straight.collocation.spectral import (
    campbell,
    critical_load,
    critical_spin,
    divergence_loads,
    stability_map,
    stable_intervals,
    static_points,
)

SET = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)


def _chi(b):
    """eq. char_welded."""
    r3 = np.sqrt(3.0)
    return (2 * np.cos(b) + np.cos(2 * b) - 2 * (np.cos(b / 2) + np.cos(3 * b / 2)) * np.cosh(r3 * b / 2)
            + (2 - np.cos(b)) * np.cosh(r3 * b) - r3 * np.sin(b) * np.sinh(r3 * b)
            - 2 * r3 * (np.sin(b / 2) - np.sin(3 * b / 2)) * np.sinh(r3 * b / 2))


def _dchi(b):
    """chi'(b) by complex step (exact to rounding); its simple zeros are chi's double zeros."""
    h = 1e-30
    return np.imag(_chi(b + 1j * h)) / h


def _beta(lo, hi):
    return brentq(lambda b: _dchi(b) * np.exp(-np.sqrt(3.0) * b), lo, hi, xtol=1e-15, rtol=1e-15)


BETAS = [_beta(7.2, 7.45), _beta(13.5, 13.7), _beta(19.8, 20.0)]


def test_independent_betas_are_double_zeros_of_chi():
    for b, printed in zip(BETAS, (7.332130, 13.613561, 19.896753)):
        assert abs(b - printed) < 1e-6
        assert abs(_chi(b)) < 1e-9 * np.cosh(np.sqrt(3) * b)
        assert _chi(b - 0.05) > 0 and _chi(b + 0.05) > 0  # touches zero: double


@pytest.mark.parametrize("R", [21 / 38, 1.0, 0.3])
def test_static_loads_are_double_zeros_of_chi(R):
    p = SET.with_(R=R)
    loads = divergence_loads(p, n=6)
    expected = np.repeat([b**3 * np.sqrt(R) / p.f for b in BETAS], 2)
    assert np.allclose(loads, expected, rtol=1e-8, atol=0)
    # gamma and P do not move static loads at omega = 0
    assert np.allclose(divergence_loads(p.with_(gamma=0.1, P=0.02), n=2), expected[:2], rtol=1e-9)


def test_spin_and_tension_split_the_pair_only_when_anisotropic():
    for kw in (dict(omega=0.3), dict(T=0.5), dict(omega=0.3, T=0.5)):
        aniso = divergence_loads(SET.with_(**kw), n=4)
        assert aniso[1] - aniso[0] > 1e-4 and aniso[3] - aniso[2] > 1e-4
        iso = divergence_loads(SET.with_(R=1.0, **kw), n=4)
        assert abs(iso[1] - iso[0]) < 1e-8 * iso[0] and abs(iso[3] - iso[2]) < 1e-8 * iso[2]
    # tension stiffens, spin softens (isotropic rod)
    base = divergence_loads(SET.with_(R=1.0), n=1)[0]
    assert divergence_loads(SET.with_(R=1.0, T=0.5), n=1)[0] > base
    assert divergence_loads(SET.with_(R=1.0, omega=0.3), n=1)[0] < base


def test_critical_spin_tends_to_sqrt_R():
    values = []
    for P in (1e-3, 1e-4, 1e-6):
        c = critical_spin(SET.with_(P=P), omega_max=1.0, n_scan=24)
        assert c.kind == "divergence" and c.converged
        values.append(c.value)
    assert values[0] > values[1] > values[2] > np.sqrt(SET.R)
    assert abs(values[2] - np.sqrt(SET.R)) < 1e-5
    assert abs(values[0] - np.sqrt(SET.R)) > 1e-3  # rotary inertia shifts it at P = 1e-3


def test_set_scene_omega_025_stable_up_to_first_pitchfork():
    for gamma in (0.0, 0.04375):
        p = SET.with_(omega=0.25, gamma=gamma)
        c = critical_load(p)
        first = divergence_loads(p, n=1)[0]
        assert c.kind == "divergence" and c.converged
        assert c.value == pytest.approx(first, rel=1e-12)
        below = spectrum(p.with_(B=0.999 * first))
        above = spectrum(p.with_(B=1.001 * first))
        assert below.max_real < 1e-9 and above.max_real > 1e-6


def test_set_scene_omega_075_damped_never_stable():
    p = SET.with_(omega=0.75, gamma=0.04375)
    c = critical_load(p)
    assert c.kind == "unstable at start" and c.value == 0.0
    assert stable_intervals(p, "B", 0.0, 12.0) == []


def test_set_scene_omega_075_undamped_structure():
    """Whatever windows the solver finds: imaginary spectrum inside, a
    lambda -> -conj(lambda) symmetric unstable one outside."""
    p = SET.with_(omega=0.75)
    iv = stable_intervals(p, "B", 0.0, 5.0)
    assert critical_load(p, B_max=1.0).kind == "unstable at start"
    edges = [0.0] + [x for w in iv for x in w] + [5.0]
    for a, b in zip(edges[:-1], edges[1:]):
        if b - a < 1e-6:
            continue
        sp = spectrum(p.with_(B=0.5 * (a + b)))
        inside = any(lo <= 0.5 * (a + b) <= hi for lo, hi in iv)
        if inside:
            assert np.max(np.abs(sp.eigenvalues.real)) < 1e-9
        else:
            assert sp.max_real > 1e-6
    # gyroscopic stabilisation: a window exists between the first static load
    # (where K regains definiteness) and a Krein collision
    assert iv, "expected at least one gyroscopically stabilised window"
    first_static = static_points(p, "B", 0.0, 5.0)[0][0]
    assert iv[0][0] == pytest.approx(first_static, rel=1e-10)


def test_damped_boundaries_are_static_points():
    """Kelvin-Tait-Chetaev: with gamma > 0 stability changes only where A0 is singular."""
    p = SET.with_(omega=0.25, gamma=0.04375)
    iv = stable_intervals(p, "omega", 0.0, 2.2, n_scan=40)
    pts = static_points(p, "omega", 0.0, 2.2)[0]
    for lo, hi in iv:
        for x in (lo, hi):
            if 0.0 < x < 2.2:
                assert np.min(np.abs(pts - x)) < 1e-12
    undamped = stable_intervals(p.with_(gamma=0.0), "omega", 0.0, 2.2, n_scan=40)
    assert len(undamped) > len(iv)  # gyroscopic windows exist only without damping


def test_map_and_campbell():
    p = SET.with_(gamma=0.04375)
    B = np.array([0.1, 0.5, 0.7])
    w = np.array([0.0, 0.5, 0.9])
    g = stability_map(p, B, w)
    assert g.shape == (3, 3)
    assert g[0, 0] < 0 and g[0, 2] > 0 and g[2, 0] > 0
    cb = campbell(SET, np.linspace(0, 1, 5), k=4)
    assert cb.eigenvalues.shape[0] == 5
    assert np.nanmin(cb.frequencies[0]) == pytest.approx(spectrum(SET, k=1).eigenvalues[0].imag, rel=1e-10)
    # one resolution, its error from a second one at the ends and the middle: honest both ways
    assert (cb.N, cb.N_check, cb.checked.tolist()) == (24, 36, [0, 2, 4])
    assert cb.error < 1e-11
    coarse = campbell(SET, np.linspace(0, 1, 5), k=4, N=8, N_check=24)
    assert coarse.error > 1e-4  # N = 8 is off by ~1e-1 (accuracy table)


@pytest.mark.parametrize("gamma", [0.0, 0.04375])
def test_family_eigenvalues_from_its_uncoupled_parts(gamma):
    # bending, torsion and axial parts solved apart (torsion once) give the spectrum of the whole operator
    from etcheck.rod.core.spectrum import nearest_eigenvalues
    from etcheck.rod.straight.collocation.spectral import StraightFamily

    p = SET.with_(gamma=gamma)
    fam = StraightFamily(p, 16)
    assert [(part.r["A00"].shape[0], part.constant) for part in fam.parts] == [(68, False), (17, True), (17, True)]
    for w in (0.0, 0.8):
        whole = nearest_eigenvalues(*fam.operator(0.3, w, 0.1, reduced=True), 22, gamma, reduced=True)
        parts = fam.eigenvalues(0.3, w, 0.1, 22, past_cluster=True)
        inside = np.abs(whole) < 0.999 * np.max(np.abs(whole))
        assert np.count_nonzero(np.abs(parts) < 0.999 * np.max(np.abs(whole))) == np.count_nonzero(inside)
        for z in whole[inside]:
            assert np.min(np.abs(parts - z)) <= 1e-10 * max(abs(z), 0.1)
