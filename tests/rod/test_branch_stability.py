"""Rung 3: stability of buckled, whirling equilibria (etcheck.rod.buckled).

Published values from the paper (docs/validation.md): secondary pitchfork of b1 at
B = 1.942 (Sec. VII A), spin pushes it up (Sec. VIII), b1 at B = 1.2 with
gamma = 0.04375 stable at least up to omega = 4 (Sec. VII B). The paper's Hopf
claims (gamma = 0.01) and "all branches but b1 unstable" are checked as
strict xfails carrying the measured values.
"""

import json
import math

import numpy as np
import pytest

from etcheck.rod.buckled import branches as br
from etcheck.rod.buckled import damping_map, hopf, secondary, spectra, structure
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import linear_operator
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import spectrum

SET = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)
N = 24
GAMMA_SET = 0.04375  # Sec. VII B: damping of a real tether


@pytest.fixture(scope="module")
def b1_static():
    """b1 at omega = 0 from BP1 to B = 2.3 (past its secondary pitchfork), with steps of at most 0.1 (its stability
    is checked state by state: ten or more of them below B*)."""
    start = br.primary_branches(SET, 1, N)[0]
    return br.continue_branch(SET, start, stop=(0.0, 2.3), ds_max=0.1)


@pytest.fixture(scope="module")
def pitchfork0():
    return secondary.secondary_pitchfork(SET, 0.0, N=N, N_check=32)


@pytest.fixture(scope="module")
def b1_spun():
    """b1 at B = 1.2 continued in omega from 0 to 4.2 (Figs. 17 and 18)."""
    return secondary.b1_spin_branch(SET, 1.2, 4.2, N)


# --- secondary pitchfork ---------------------------------------------------------------------


def test_secondary_pitchfork_at_rest_matches_paper(pitchfork0):
    p = pitchfork0
    assert p.error < 1e-4  # N = 24 vs N = 32
    assert round(p.B, 3) == 1.942  # Sec. VII A
    assert abs(p.B - 1.9424629) < 1e-4 + p.error  # converged value (N = 32, 40 agree to 1e-8)


def test_secondary_pitchfork_is_where_the_static_operator_is_singular(b1_static, pitchfork0):
    """The located break point is a zero of A0 (lambda = 0 eigenvalue of rung 3)."""
    brk = [q for q in b1_static.special if q.kind == "break"][0]
    assert abs(brk.value - pitchfork0.B_check) < 1e-9  # both at N = 24 (pitchfork0.B is at 32)
    A0 = linear_operator(brk.state.params, brk.state, N)[0]
    near = eq.solve_equilibrium(brk.state.params.with_(B=1.5), brk.state)
    A0_far = linear_operator(near.params, near, N)[0]
    sv = np.linalg.svd(A0, compute_uv=False)
    sv_far = np.linalg.svd(A0_far, compute_uv=False)
    assert sv[-1] / sv[0] < 1e-4 * sv_far[-1] / sv_far[0]


def test_spin_pushes_the_secondary_pitchfork_up(pitchfork0):
    curve = secondary.secondary_pitchfork_curve(SET, [0.25, 1.0], N=N, N_check=32)
    B = np.concatenate([[pitchfork0.B], curve.B])
    assert np.all(np.diff(B) > 0.05), B  # Sec. VIII
    assert np.all(curve.error < 1e-4)
    assert abs(curve.B[0] - 2.0643166) < 1e-4  # independent in-house value at omega = 0.25


# --- stability along branches ----------------------------------------------------------------


def test_b1_stable_up_to_the_secondary_pitchfork_and_unstable_after(b1_static, pitchfork0):
    sp = spectra.branch_spectra(b1_static, GAMMA_SET, k=4, state_stride=8)
    B = sp.values
    Bstar = pitchfork0.B
    below = (B > B[0] + 1e-3) & (B < Bstar - 0.01)
    above = B > Bstar + 0.01
    assert below.sum() >= 10 and above.sum() >= 2
    assert np.all(sp.stable[below])
    assert not np.any(sp.stable[above])
    assert np.all(sp.decided[below | above])
    # Kelvin-Tait-Chetaev: one negative stiffness direction past B*, none before
    assert np.all(sp.index[below] == 0) and np.all(sp.index[above] == 1)
    # the unstable eigenvalue is real (a divergence, not a Hopf point)
    for i in np.nonzero(above)[0]:
        lam = sp.eigenvalues[i]
        grow = lam[np.nan_to_num(lam.real, nan=-1.0) > 0]
        assert grow.size == 1 and abs(grow[0].imag) < 1e-10
    # two-resolution errors of the tracked paths (operator and base state)
    assert np.max(sp.errors[below]) < 1e-4
    assert np.nanmax(sp.state_errors) < 1e-4


def test_b12_is_unstable(b1_static):
    b12 = br.connecting_branch(b1_static, max_points=60)
    idx = np.linspace(2, len(b12.states) - 3, 4).astype(int)
    sp = spectra.branch_spectra([b12.states[i] for i in idx], GAMMA_SET, k=3, state_stride=0, name="b12")
    assert not np.any(sp.stable)
    for i in idx:
        chk = structure.structure_check(b12.states[i], gammas=(GAMMA_SET,))
        assert chk.index == 1 and chk.kelvin_tait_chetaev


def _b2_state(n):
    start = br.primary_branches(SET, 1, n)[1]
    b2 = br.continue_branch(SET, start, stop=(0.0, 1.0))
    return br.locate(b2, lambda s: s.params.B, 0.9)[1]


def test_b2_is_stable_at_rest_in_this_model():
    """Finding (not the paper's claim): b2 at omega = 0, B = 0.9 has a positive definite
    stiffness and a purely imaginary undamped spectrum, for two base-state
    resolutions and two operator resolutions."""
    lows = []
    for n in (24, 32):
        st = _b2_state(n)
        for n_op in (n, n + 16):
            chk = structure.structure_check(st, N=n_op, gammas=(0.01, GAMMA_SET))
            assert chk.index == 0 and chk.unstable_damped == (0, 0)
            assert chk.max_real_undamped < 1e-9
            lam = spectra.operator_eigenvalues(spectra.damped_operator(st.params, st, n_op), 0.0, 12, False)
            lows.append(np.min(np.abs(lam)))
    assert np.ptp(lows) < 1e-3 * np.max(lows)  # lowest frequency converged (about 0.19)
    assert min(lows) > 0.1


@pytest.mark.xfail(strict=True, reason="paper (Secs. VII B, VIII): all branches but b1 unstable; measured: b2 at "
                   "omega = 0, B = 0.9 stable (K index 0, lowest undamped frequency 0.189, N = 24..48)")
def test_paper_claim_b2_unstable():
    st = _b2_state(N)
    assert structure.structure_check(st, gammas=(GAMMA_SET,)).unstable_damped[0] > 0


def test_b1_spun_at_B12_stable_up_to_omega4(b1_spun):
    """Sec. VII B: b1 at B = 1.2, gamma = 0.04375 stable at least up to omega = 4."""
    upto4 = [s for s in b1_spun.states if s.params.omega <= 4.0 + 1e-9]
    states = upto4[:-1:2] + upto4[-1:]  # every other state, and the last one below omega = 4
    assert states[-1].params.omega > 3.5
    sp = spectra.branch_spectra(states, GAMMA_SET, k=3, state_stride=0, name="b1@B=1.2")
    assert np.all(sp.stable) and np.all(sp.decided)
    assert np.all(sp.index == 0)  # K > 0 all along: no gamma > 0 can destabilise (KTC)
    assert np.all(sp.max_real < -3e-3)  # decay rate of the least-damped mode >= 3e-3
    assert np.max(sp.max_real_error) < 1e-4


@pytest.mark.xfail(strict=True, reason="paper (Sec. VII B): Hopf of lambda1 at omega ~ 1.5 for gamma = 0.01, "
                   "B = 1.2; measured: no crossing up to omega = 4.2, max Re lambda (complex modes) = -9.27e-4 "
                   "near omega = 2.2 (N = 24 vs 36 differ by < 1e-5)")
def test_paper_claim_hopf_at_gamma001(b1_spun):
    scan = hopf.find_hopf(b1_spun, 0.01, k=3)
    assert any(abs(p.value - 1.5) < 0.3 for p in scan.points)


def test_no_hopf_at_gamma001_along_b1_spun(b1_spun):
    """What the model gives: the complex modes stay damped, convergently."""
    scan = hopf.find_hopf(b1_spun, 0.01, k=3)
    assert scan.points == ()
    assert np.nanmax(scan.max_real_complex) < -5e-4
    assert np.nanmax(scan.error) < 1e-4


# --- cross-rung and structure ----------------------------------------------------------------


def test_trivial_branch_reproduces_rung1():
    p = SET.with_(B=0.3, omega=0.25, gamma=GAMMA_SET)
    a = spectrum(p, k=6, N=N)
    b = spectrum(p, base=eq.straight_state(p, N), k=6, N=N)
    assert a.eigenvalues.size == b.eigenvalues.size >= 6
    assert np.max(np.abs(a.eigenvalues - b.eigenvalues)) < 1e-9
    # and the gamma-split operator of rung 3 equals linear_operator at that gamma
    st = eq.straight_state(p, N)
    op = spectra.damped_operator(p, st, N)
    for X, Y in zip(op.at(p.gamma), linear_operator(p, st, N)):
        assert np.max(np.abs(X - Y)) <= 1e-12 * max(1.0, np.max(np.abs(Y)))


def test_damped_operator_splits_by_rows_on_a_buckled_spun_state(b1_spun):
    """damped_operator builds once (gamma = 1) and splits A1 by rows: the Kelvin-Voigt term
    lives only in the constitutive rows, the gyroscopic terms only outside them."""
    st = b1_spun.states[len(b1_spun.states) // 2]
    assert st.params.omega > 1.0
    op = spectra.damped_operator(st.params, st, N)
    A1g = linear_operator(st.params.with_(gamma=0.0), st, N)[1]
    assert np.max(np.abs(A1g[3 * N:6 * N])) == 0.0 and np.max(np.abs(op.at(1.0)[1][op.damped])) > 0.1
    assert np.max(np.abs(op.at(0.0)[1] - A1g)) <= 1e-13 * np.max(np.abs(A1g))
    for X, Y in zip(op.at(GAMMA_SET), linear_operator(st.params.with_(gamma=GAMMA_SET), st, N)):
        assert np.max(np.abs(X - Y)) <= 1e-12 * max(1.0, np.max(np.abs(Y)))


def test_mode_labels_of_the_straight_rod():
    """Unloaded straight rod: weak-axis bending (about d2) lowest, stiff-axis
    bending (about d1) next, the first torsion mode at pi sqrt(Gamma/(2 P f))."""
    st = eq.straight_state(SET, N)
    op = spectra.damped_operator(SET, st, N)
    lam, V = spectra.operator_eigenvalues(op, 0.0, 40, True)
    rep = spectra.pair_representatives(lam)
    rep = rep[np.argsort(np.abs(lam[rep]))]
    E = spectra.mode_energies(st, V[:, rep], N, SET)
    assert np.argmax(E[0]) == 1 and E[0, 1] > 0.999
    assert np.argmax(E[1]) == 0 and E[1, 0] > 0.999
    mu_t = math.pi * math.sqrt(SET.Gamma / (2 * SET.P * SET.f))
    j = np.argmin(np.abs(lam[rep].imag - mu_t))
    assert abs(lam[rep][j].imag - mu_t) < 1e-6 and E[j, 2] > 0.999


@pytest.mark.parametrize("B, omega, index", [(1.2, 0.5, 0), (2.2, 0.0, 1)])
def test_structure_hamiltonian_symmetric_stiffness_and_ktc(B, omega, index):
    st = secondary.b1_state(SET, B, omega, N=N)
    chk = structure.structure_check(st, gammas=(0.01, GAMMA_SET, 0.2))
    fine = structure.structure_check(st, N=40, gammas=())
    # (lambda, -lambda, conj) at gamma = 0, up to a discretisation error that decays with N
    assert chk.hamiltonian_defect < 1e-6
    assert fine.hamiltonian_defect < 1e-9 and fine.hamiltonian_defect <= max(chk.hamiltonian_defect, 1e-11)
    assert chk.stiffness_asymmetry < 1e-10  # mu = lambda^2 real when A1 = 0: K symmetric
    assert chk.index == fine.index == index
    assert chk.kelvin_tait_chetaev  # unstable count = index of K for every gamma > 0
    if index == 0:
        assert chk.max_real_undamped < 1e-6 and fine.max_real_undamped < 1e-9  # purely imaginary


def test_branch_spectra_tracks_paths_continuously(b1_spun):
    states = [s for s in b1_spun.states if s.params.omega <= 2.5]
    sp = spectra.branch_spectra(states, 0.01, k=3, state_stride=0)
    assert sp.crossings == ()
    # from each state to the next, every path continues to the eigenvalue nearest to it (a swap of two paths would
    # continue to a farther one): measured steps up to 0.27 against distances of 0.37 or more to the other paths
    lam = sp.eigenvalues
    dist = np.abs(lam[1:, None, :] - lam[:-1, :, None])  # [state, path, path at the next state]
    assert np.all(np.argmin(dist, axis=2) == np.arange(lam.shape[1]))
    json.dumps(sp.as_dict())
    # without the stiffness index (damped): the same paths, the index left out (-1)
    paths_only = spectra.branch_spectra(states[:6], 0.01, k=3, state_stride=0, stiffness=False)
    np.testing.assert_array_equal(paths_only.eigenvalues, sp.eigenvalues[:6])
    assert np.all(paths_only.index == -1) and np.all(sp.index >= 0)
    # undamped, the index decides stability: always computed
    assert np.all(spectra.branch_spectra(states[:2], 0.0, k=3, state_stride=0, stiffness=False).index >= 0)


# --- damping map --------------------------------------------------------------------------------


def test_damping_map_sanity(pitchfork0):
    Bstar = pitchfork0.B
    # B* - 1e-4 is 15x the two-resolution error of B* at N = 24 (closer, the
    # rung-3 operator and the continuation Jacobian may disagree on the side)
    grid = np.array([0.5, 1.0, 1.5, Bstar - 1e-3, Bstar - 1e-4])
    dm = damping_map.damping_map(SET, grid, [0.0], gammas=(0.01, GAMMA_SET), N=N, margin=1e-5)
    assert abs(dm.curve_B[0] - pitchfork0.B_check) < 1e-9  # the map's curve is at N = 24, B* at 32
    assert not dm.inside[0, 0]  # below the primary pitchfork: no b1
    assert np.all(dm.inside[0, 1:])
    d = dm.decay[:, 0, 1:]
    assert np.all(d > 0)  # stable inside
    assert np.all(d[:, -1] < 0.5 * d[:, 1])  # decay -> 0 at the secondary pitchfork
    # there the least-damped mode is the real (static) one, decaying ~ (B* - B) / gamma
    assert np.all(np.isinf(dm.log_decrement[:, 0, -1]))
    assert np.all(np.isinf(dm.log_decrement[1, 0, -2:]))
    ratio = d[1, -1] / d[1, -2]
    assert 0.05 < ratio < 0.2, ratio
    # away from the pitchfork (complex modes) more damping gives more decay
    assert np.all(dm.decay[1, 0, 1:3] > dm.decay[0, 0, 1:3])
    json.dumps(dm.as_dict())


# --- error estimates bound the true error (issue 11) ------------------------------------------


_F = 4.730040744862704**4


@pytest.mark.parametrize("params", [RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, f=_F),
                                    RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, f=_F, omega=0.3)],
                         ids=["SET", "SET-omega0.3"])
def test_secondary_pitchfork_estimate_bounds_its_error(params):
    """B* (the value at the finer resolution) is within its stated error of B* at a much finer
    resolution, and the check's route (b1 from its pitchfork at the scene's spin) and the curve's
    route (b1 reached through spin at B_ref) give one value."""
    b = secondary.b1_direct(params, 20, 2.5)
    pt = secondary.secondary_pitchfork(params, params.omega, N=20, N_check=28, branch=b)
    ref = secondary.first_break(secondary.b1_direct(params, 40, 1.02 * pt.B)).value
    assert abs(pt.B - ref) <= pt.error
    if params.omega == 0:
        up, _ = secondary.b1_in_B(params, 0.0, 28, 1.2, 2.5)
        assert abs(secondary.first_break(up, above=1.2).value - pt.B) <= 1e-9  # one value, one route


def test_measure1_estimate_bounds_its_error():
    """measure_1 along b1: the two-resolution estimate of resolution_check bounds the change
    against a much finer resolution (SET, omega = 0.3)."""
    p = RodParameters(P=0.001, R=21 / 38, Gamma=1 / 1.3, f=_F, omega=0.3)
    b = secondary.b1_direct(p, 20, 1.6)
    chk = br.resolution_check(b)
    B, st = br.locate(b, lambda s: s.params.B, 1.5)
    fine = eq.solve_equilibrium(st.params, eq.resample_state(st, 40))
    assert abs(eq.measure1(fine) - eq.measure1(st)) <= chk.measure1_error


def test_a_buckled_states_spectrum_climbs_from_the_states_own_resolution(b1_static, monkeypatch):
    """The stability of a state of b1 (known at N = 24) is solved at N = 24 and above, never below (an operator
    sampled from the state's interpolant on fewer points cannot agree with the finer one); its growth rate agrees
    with another pair of resolutions within both error estimates."""
    from etcheck.checks.rungs import coil
    from etcheck.rod.core import spectrum as sp_module

    st = b1_static.states[len(b1_static.states) // 2]
    solved = []
    lowest = sp_module.lowest_eigenvalues

    def recorded(params, base, n, nev, vectors=False, operator=None):
        solved.append(n)
        return lowest(params, base, n, nev, vectors, operator)

    monkeypatch.setattr(sp_module, "lowest_eigenvalues", recorded)
    stable, growth, error = coil.state_stability(st, GAMMA_SET)
    assert solved[:2] == [N, 32] and min(solved) == st.N == N  # the ladder (16, 24, 32, ...) from 24 on
    fixed = spectrum(st.params.with_(gamma=GAMMA_SET), base=st, k=6, tol=1e-6, N=N)  # the pair (24, 36)
    other = float(np.max(fixed.eigenvalues.real))
    assert fixed.converged and abs(growth - other) <= error + float(np.max(fixed.errors))
    assert stable is (growth <= 1e-9) is (other <= 1e-9)


def test_a_branch_s_eigenvalue_paths_decide_its_stability_without_solves_of_their_own(monkeypatch):
    """At the diagram's resolution (N = 32, checked at 48: the first pair of the stability ladder) the spectra of a
    branch's eigenvalue paths give the stability of its probed states as their own solves do, to round-off, and
    none is solved again; at N = 24 (checked at 36, the ladder's next rung is 32) they are solved as before."""
    from etcheck.checks.rungs import coil
    from etcheck.rod.core import spectrum as sp_module

    for n, reused, B_end in ((32, True, 1.2), (24, False, 0.8)):
        start = br.primary_branches(SET, 1, n)[0]
        branch = br.continue_branch(SET, start, stop=(0.0, B_end), ds_max=0.25)
        paths = coil.path_spectra(branch, GAMMA_SET)
        calls = []
        lowest = sp_module.lowest_eigenvalues

        def counted(*a, calls=calls, lowest=lowest, **k):
            calls.append(a[2])
            return lowest(*a, **k)

        monkeypatch.setattr(sp_module, "lowest_eigenvalues", counted)
        stable, growth, error = coil.branch_stability(branch, GAMMA_SET, paths)
        assert (calls == []) is reused
        monkeypatch.setattr(sp_module, "lowest_eigenvalues", lowest)
        own = coil.branch_stability(branch, GAMMA_SET)
        assert stable == own[0] and [g is None for g in growth] == [g is None for g in own[1]]
        for a, b, ea, eb in zip(growth, own[1], error, own[2]):
            if a is not None:
                assert abs(a - b) <= 1e-11 and abs(ea - eb) <= 1e-10
