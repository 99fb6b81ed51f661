"""Rung 1v: the straight tether with profiles (graded multi-domain collocation) against exact values
(uniform profiles), analytic ones (pinned ends), an independent discretisation (Hermite finite elements,
tests/independent_fe.py) and the physics of a circulatory load."""

from __future__ import annotations

import contextlib
import math
import signal

import independent_fe as fe
import numpy as np
import pytest

from etcheck.numerics.eigen import sparse_qep_nearest
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.exact.roots import exact_critical
from etcheck.rod.straight.exact.undamped import undamped_critical
from etcheck.rod.straight.varying import circulatory, line_band
from etcheck.rod.straight.varying.circulatory import critical
from etcheck.rod.straight.varying.profiles import Tether, family, layer_widths, mesh

#: the shipped tape tether (missions/tape-tether.toml), scaled
TAPE = RodParameters(P=2.0857142857142857e-10, R=2.556164383561644e-06, Gamma=7.671213267830194e-06,
                     B=3.3796980016942935, T=1.4446060436451282, gamma=0.04375)
RISING = Profile.piecewise_linear([0.0, 1.0], [0.0, 1.0])
KINKED = Profile.piecewise_linear([0.0, 0.3, 1.0], [0.0, 0.8, 1.0])


def test_profiles_evaluate_as_given():
    p = Profile.piecewise_linear([0.0, 0.3, 1.0], [0.0, 0.8, 1.0])
    s = np.array([0.0, 0.15, 0.3, 0.65, 1.0])
    assert np.allclose(p(s), [0.0, 0.4, 0.8, 0.9, 1.0], atol=1e-15)
    assert np.allclose(p.derivative(np.array([0.1, 0.5])), [0.8 / 0.3, 0.2 / 0.7])
    q = Profile.from_function(lambda x: 1 + 3 * x * (1 - x), degree=2)
    x = np.linspace(0, 1, 7)
    assert np.allclose(q(x), 1 + 3 * x * (1 - x), atol=1e-14)
    assert np.allclose(q.derivative(x), 3 - 6 * x, atol=1e-13)
    assert np.allclose(p.reversed()(x), p(1 - x), atol=1e-15)
    assert Profile.uniform(2.0).uniform_value == 2.0 and p.uniform_value is None
    with pytest.raises(ValueError, match="rise from 0 to 1"):
        Profile((0.0, 0.5), ((1.0,),))


def test_mesh_grades_towards_thin_layers_and_puts_edges_at_kinks():
    t = Tether(TAPE, KINKED)
    w = layer_widths(t)[0]
    assert w == pytest.approx(math.sqrt(TAPE.R / (TAPE.f * TAPE.T)), rel=1e-3)
    m = mesh(t, 24)
    assert 0.3 in m.edges and m.edges[1] == pytest.approx(2 * w)
    assert max(np.diff(m.edges[:4]) / np.diff(m.edges[1:5])) < 1  # widths grow away from the end
    assert mesh(Tether(TAPE.with_(T=0.0, B=0.0)), 24).edges == (0.0, 1.0)


@pytest.mark.parametrize("gamma", [0.04375, 0.0])
def test_uniform_tape_reproduces_the_exact_determinant(gamma):
    """The shipped tape (layers of 6e-5 L, R = 2.6e-6): the first static load of the exact determinant,
    damped and undamped (no spin: the undamped critical load is the static one)."""
    p = TAPE.with_(gamma=gamma)
    c = critical(Tether(p), mode=False)
    exact = exact_critical(TAPE).critical_load
    assert c.kind == CriticalKind.DIVERGENCE
    assert abs(c.value - exact.value) <= max(c.error, 1e-9 * exact.value) + 1e-12 * exact.value
    assert c.error <= 1e-8 * c.value


@pytest.mark.parametrize("kw", [dict(omega=0.25), dict(omega=0.5, T=3.0)])
@pytest.mark.parametrize("gamma", [0.04375, 0.0])
def test_uniform_spinning_rod_reproduces_the_exact_routes(kw, gamma):
    """SET with spin (and tension): the damped critical load of the exact determinant, the undamped one of the
    undamped determinant."""
    p = RodParameters(P=1e-3, R=0.5526315789473685, Gamma=0.7692307692307692, gamma=gamma, **kw)
    c = critical(Tether(p), mode=False)
    ref = exact_critical(p).critical_load.value if gamma else undamped_critical(p, spin=False).critical_load.value
    assert c.value == pytest.approx(ref, rel=1e-9)
    assert c.error <= 1e-8 * c.value


def test_uniform_rod_at_rest_buckles_at_the_analytic_load():
    p = RodParameters(P=1e-3, R=0.3, Gamma=0.77, gamma=0.01)
    c = critical(Tether(p), mode=False)
    assert c.value == pytest.approx(float(critical_loads(p.R, p.f, 1)[0]), rel=1e-7)  # beta_1 to 7 digits


def test_thinnest_layers_reproduce_the_exact_determinant():
    """R = 1e-7 under f T = 1e12: layers of 3e-10 L (u) and 1e-6 L (v), undamped."""
    p = RodParameters(P=1e-12, R=1e-7, Gamma=1e-5, T=1e12 / 500.5639017404325)
    c = critical(Tether(p), mode=False)
    assert layer_widths(Tether(p))[0] < 1e-9
    ref = exact_critical(p.with_(gamma=0.01)).critical_load.value
    assert c.value == pytest.approx(ref, rel=1e-9)


def test_pinned_ends_give_the_analytic_frequencies():
    """A pinned-pinned beam under tension with rotary inertia: lambda = i sqrt((c4 k^4 + T k^2) / (1 + pc k^2)),
    k = n pi, for both axes."""
    p = RodParameters(P=1e-3, R=0.4, Gamma=0.7, T=2.0)
    fam = family(Tether(p.with_(ends=("pinned", "swivel"))), 32)
    lam = sparse_qep_nearest(*fam.operator(0.0, 0.0, p.T), k=16, sigma=0.01)
    got = np.sort(lam.imag[lam.imag > 0])
    k = np.pi * np.arange(1, 9)
    ref = np.sort(np.concatenate([np.sqrt((c4 * k**4 + p.T * k**2) / (1 + pc * k**2))
                                  for c4, pc in ((p.R / p.f, p.P * p.R), (1 / p.f, p.P))]))
    assert np.allclose(got, ref[:got.size], rtol=1e-10)


SCENES = [  # (params, current, tension shape): held-out kinds of tether, each against finite elements
    (RodParameters(P=1e-3, R=1.0, Gamma=0.77, T=0.0, gamma=0.04375), RISING, Profile.uniform()),  # no tension
    (RodParameters(P=1e-6, R=1e-3, Gamma=0.7, T=2.0), KINKED, Profile.uniform()),
    (RodParameters(P=1e-4, R=0.2, Gamma=0.7, T=0.5), Profile.piecewise_linear([0, 1], [0.2, 1]),
     Profile.from_function(lambda s: 1 + 3 * s * (1 - s), degree=2)),
    (RodParameters(P=1e-4, R=0.05, Gamma=0.7, T=5.0, omega=0.3, gamma=0.02), RISING,
     Profile.from_function(lambda s: 1 + 3 * s * (1 - s), degree=2)),
]


@pytest.mark.parametrize("params, current, tension", SCENES)
def test_critical_load_agrees_with_finite_elements(params, current, tension):
    """Two discretisations agree: the collocation's first crossing and the B where Hermite cubic elements on a
    graded mesh first show Re lambda > 0 (its own scan and bisection), to the elements' accuracy."""
    t = Tether(params, current, tension)
    c = critical(t, mode=False)
    assert c.kind == CriticalKind.FLUTTER and c.error <= 1e-8 * c.value
    layer = min(layer_widths(t.with_(B=c.value)))
    nodes = fe.graded_nodes(min(layer, 0.05), 160, 1.15)
    sigma = 0.0123 if params.gamma == 0 else 0.5 / params.gamma
    B_fe = fe.critical_load(params, current, tension, nodes, 1.02 * c.value, n_scan=3, rtol=1e-10, sigma=sigma, k=16)
    assert B_fe == pytest.approx(c.value, rel=5e-6)


def test_a_damped_spinning_tether_under_one_current_loses_stability_at_its_first_static_point():
    """Kelvin-Tait-Chetaev on rung 1v: damped, one current along a tension that varies and spinning, stability is
    lost where a real eigenvalue passes 0 (the route rung 1v takes, from the static pencils alone); Hermite finite
    elements scanning their own spectra for Re lambda > 0 find it there, no flutter before it."""
    params = RodParameters(P=1e-4, R=0.3, Gamma=0.7, T=3.0, omega=0.8, gamma=0.03)
    tension = Profile.from_function(lambda s: 1 + 3 * s * (1 - s), degree=2)
    t = Tether(params, Profile.uniform(), tension)
    assert circulatory.static_only(t)
    c = critical(t, mode=False)
    assert c.kind == CriticalKind.DIVERGENCE and c.error <= 1e-8 * c.value
    nodes = fe.graded_nodes(min(min(layer_widths(t.with_(B=c.value))), 0.05), 160, 1.15)
    B_fe = fe.critical_load(params, Profile.uniform(), tension, nodes, 1.02 * c.value, n_scan=3, rtol=1e-10, k=16)
    assert B_fe == pytest.approx(c.value, rel=5e-6)


def test_tape_with_a_rising_current_flutters_below_its_operating_load():
    """The issue's finding: the shipped tape with a current rising linearly along it flutters undamped at
    about 0.7 of its operating load; damping (gamma = 0.04375) lowers that threshold (Ziegler)."""
    undamped = critical(Tether(TAPE.with_(gamma=0.0), RISING))
    assert undamped.kind == CriticalKind.FLUTTER
    assert undamped.value / TAPE.B == pytest.approx(0.7222265, abs=1e-6)
    s, u, v = undamped.mode
    assert s.size == 201 and max(np.max(np.abs(u)), np.max(np.abs(v))) == pytest.approx(1.0)
    assert abs(u[0]) < 1e-12 and abs(v[-1]) < 1e-12  # welded ends
    damped = critical(Tether(TAPE, RISING), mode=False)
    assert damped.kind == CriticalKind.FLUTTER and damped.value < 0.1 * undamped.value


def test_round_wire_with_a_varying_current_flutters_at_any_load():
    p = RodParameters(P=1e-4, R=1.0, Gamma=0.7, T=1.0)
    c = critical(Tether(p, RISING), mode=False)
    assert c.value == 0.0 and c.kind == CriticalKind.FLUTTER
    # a uniform current on the same wire is conservative: stable up to its (double) static load
    u = critical(Tether(p), mode=False)
    assert u.value == pytest.approx(exact_critical(p.with_(gamma=0.01)).critical_load.value, rel=1e-8)


def test_reversed_profiles_give_the_same_critical_load():
    """The map (u, v)(s) -> (u(1 - s), -v(1 - s)) takes the tether with b(s), tau(s) to the one with b(1 - s),
    tau(1 - s): the same spectrum."""
    p = RodParameters(P=1e-4, R=0.2, Gamma=0.7, T=0.5)
    tau = Profile.from_function(lambda s: 1 + 2 * s, degree=1)
    a = critical(Tether(p, KINKED, tau), mode=False)
    b = critical(Tether(p, KINKED.reversed(), tau.reversed()), mode=False)
    assert a.value == pytest.approx(b.value, rel=1e-8)


@pytest.mark.parametrize("ends", [("pinned", "pinned"), ("welded", "swivel")])
def test_uniform_rod_with_other_ends_reproduces_the_exact_determinant(ends):
    """Pinned or swivel ends (rows u = u'' = 0 per end) against the exact determinant with the same ends, under
    tension (a tape's layers)."""
    p = TAPE.with_(ends=ends)
    c = critical(Tether(p), mode=False)
    ref = exact_critical(p).critical_load
    assert c.value == pytest.approx(ref.value, rel=1e-9)


@contextlib.contextmanager
def _terminates_within(seconds: int):
    """Fail (rather than hang) when the block runs past ``seconds``: a bound on termination, not a timing."""
    def stop(signum, frame):
        raise TimeoutError(f"still running after {seconds} s")
    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.mark.parametrize("gamma", [0.04375, 0.0])
def test_tape_without_tension_terminates_and_says_what_was_not_located(gamma):
    """A bare tape without tension (R = 2.6e-6, T = 0) under a rising current: the modes the load reshapes up to
    3 x its expected critical load are hundreds of soft weak-axis modes. The search ends at once, not located, and
    says why; it never reports a spurious eigenvalue (an instability at B = 0 from an unconverged solve)."""
    t = Tether(TAPE.with_(T=0.0, gamma=gamma), RISING)
    with _terminates_within(30):
        c = critical(t, mode=False)
    assert c.kind == CriticalKind.NOT_LOCATED and not c.converged
    assert "modes, more than rung 1v examines" in c.message


def test_a_band_the_mesh_cannot_resolve_is_not_located():
    """The pinned tape without tension: within its first stage the load reshapes about 90 modes, which the mesh
    (one subdomain of 25 points per field: no layers without tension) cannot resolve. Not located, and why."""
    t = Tether(TAPE.with_(T=0.0, gamma=0.0, ends=("pinned", "pinned")), RISING)
    with _terminates_within(30):
        c = critical(t, mode=False, check=False)
    assert c.kind == CriticalKind.NOT_LOCATED and "more than the mesh resolves" in c.message


@pytest.mark.parametrize("gamma", [0.04375, 0.0])
def test_round_wire_without_tension_terminates_with_its_flutter(gamma):
    """A round wire (R = 1) without tension under a rising current: flutter, damped at a load agreeing on two
    meshes, undamped at any load."""
    p = RodParameters(P=1e-3, R=1.0, Gamma=0.77, B=1.0, T=0.0, gamma=gamma)
    with _terminates_within(30):
        c = critical(Tether(p, RISING), mode=False)
    assert c.kind == CriticalKind.FLUTTER and c.converged
    if gamma:
        assert c.value == pytest.approx(0.0871160446584, rel=1e-9) and c.error <= 1e-8 * c.value
    else:
        assert c.value == 0.0


def test_an_eigenvalue_solve_that_does_not_converge_is_not_located(monkeypatch):
    """A solve that returns fewer eigenvalues than asked (what ARPACK gives when its restarts run out): the point
    is not located (a missing eigenvalue could be the unstable one), never read as stable."""
    solve = line_band.sparse_qep_nearest

    def partial(*args, **kwargs):
        return solve(*args, **kwargs)[:-1]
    monkeypatch.setattr(line_band, "sparse_qep_nearest", partial)
    c = critical(Tether(TAPE.with_(gamma=0.0, T=1.3), RISING), mode=False)  # a tether no other test searched
    assert c.kind == CriticalKind.NOT_LOCATED and "converged on" in c.message


def test_a_far_end_of_the_line_does_not_change_the_crossing():
    """The line searched in stages: a crossing near the expected load is found with the band of modes of the first
    stage, whatever the end asked for (here 20 x the expected range, where hundreds of modes are reshaped)."""
    t = Tether(TAPE.with_(gamma=0.0), RISING)
    hi = 20 * line_band.expected_end(t, "B")
    assert len(line_band.stages(t, "B", hi)) == 3
    far = critical(t, hi=hi, mode=False)
    assert far.kind == CriticalKind.FLUTTER
    assert far.value / TAPE.B == pytest.approx(0.7222265, abs=1e-6)


def test_damping_survey_agrees_with_a_search_at_each_damping():
    """The damping map's survey, continued in gamma from one crossing to the next, against a search of its own at
    each damping (one mesh each), on a tape with a rising current and a 200 m tether with a kinked current and a
    tension profile."""
    small = RodParameters(P=1e-3, R=0.5526315789473685, Gamma=0.7692307692307692, B=0.0126, T=0.0404)
    parabola = Profile.from_function(lambda s: 1.3 - 0.15 * (2 * s - 1) ** 2, degree=2)
    for t in (Tether(TAPE.with_(T=1.2), RISING), Tether(small, KINKED, parabola)):
        gammas = (4.375e-4, 4.375e-3, 0.04375)
        survey = circulatory.first_crossings(t, "gamma", gammas)
        for g, c in zip(gammas, survey):
            own = critical(t.with_(gamma=g), mode=False, check=False)
            assert c.kind == own.kind == CriticalKind.FLUTTER
            assert c.value == pytest.approx(own.value, rel=1e-8)


def test_damping_survey_continued_from_a_crossing_computed_apart_is_the_same_survey():
    """A survey split in two (its first crossing apart, the others continued from it: the check's two cores) gives
    the survey computed in one piece; its points say that they carry no error estimate."""
    t = Tether(TAPE.with_(T=1.2), RISING)
    gammas = (4.375e-4, 4.375e-3, 0.04375)
    whole = circulatory.first_crossings(t, "gamma", gammas)
    circulatory.forget()
    first = circulatory.first_crossings(t, "gamma", gammas[:1])
    split = first + circulatory.first_crossings(t, "gamma", gammas[1:], after=(gammas[0], first[0]))
    for a, b in zip(whole, split):
        assert a.kind == b.kind == CriticalKind.FLUTTER
        assert b.value == pytest.approx(a.value, rel=1e-9)
        assert math.isnan(b.error) and "no error estimate" in b.message


def test_spinning_tether_without_tension_is_answered_not_raised():
    """A spun SET-like tether without tension under a rising current (scenes where the root finder's tracked function
    could give the ends of its bracket other signs on a second evaluation, or land exactly on an eigenvalue: both
    raised before). Undamped it flutters from zero load on (two meshes agree); damped at 0.0412771033 and, at half
    that load, along the spin at 0.5426578528 (the values the code found before where it did not raise)."""
    p = RodParameters(P=1e-3, R=0.5526315789473685, Gamma=0.7692307692307692, B=0.0126, T=0.0, omega=0.25)
    undamped = critical(Tether(p.with_(gamma=0.0), RISING), mode=False)
    assert undamped.kind == CriticalKind.FLUTTER and undamped.value == 0.0
    damped = critical(Tether(p.with_(gamma=0.04375), RISING), mode=False)
    assert damped.kind == CriticalKind.FLUTTER and damped.value == pytest.approx(0.0412771033, rel=1e-9)
    spin = circulatory.critical_spin(Tether(p.with_(gamma=0.04375, B=0.5 * damped.value), RISING))
    assert spin.kind == CriticalKind.FLUTTER and spin.value == pytest.approx(0.5426578528, rel=1e-9)


def test_a_solver_that_fails_is_reported_not_located(monkeypatch):
    """A sparse factorisation or ARPACK that raises (here: every eigenvalue solve) gives 'not located' with the
    solver's message, never a traceback."""
    def fails(*args, **kwargs):
        raise RuntimeError("Factor is exactly singular")
    monkeypatch.setattr(line_band, "sparse_qep_nearest", fails)
    monkeypatch.setattr(circulatory, "sparse_qep_nearest", fails)
    c = critical(Tether(TAPE.with_(gamma=0.0, T=1.1), RISING), mode=False)
    assert c.kind == CriticalKind.NOT_LOCATED and "a solver failed (RuntimeError: Factor is exactly singular" in c.message


def test_an_undamped_spinning_tether_with_a_varying_current_is_unstable_at_any_load_and_any_spin():
    """docs/model.md section 10: spun, undamped, with a current rising along it (the scene-space benchmark's
    mission #28, rounded), the circulatory load moves a frequency off the imaginary axis in proportion to the load
    (and, loaded, to the spin): the crossing is at 0 on both lines, on two meshes. Where Re lambda passes the
    threshold (B ~ 2.3e-5) is no crossing: it moved with each mesh's round-off, and the ladder climbed to N = 144."""
    p = RodParameters(P=2.04e-9, R=1.32e-6, Gamma=0.826, B=7.2e-4, omega=1.15e-3, T=0.3, gamma=0.0)
    t = Tether(p, RISING)
    fam = family(t.with_(B=1e-4), 24)
    re = [np.max(line_band.solve(fam.operator(B, p.omega, p.T), 28, 0.3 * 1.7, 1.7, "test").real)
          for B in (1e-5, 2e-5)]
    assert re[0] > 0 and re[1] / re[0] == pytest.approx(2.0, rel=0.05)  # Re lambda in proportion to B
    for axis in ("B", "omega"):
        c = critical(t, axis, mode=False)
        assert (c.value, c.kind, c.converged) == (0.0, CriticalKind.FLUTTER, True), c.message
        assert c.N_check > c.N and c.N <= 36  # two meshes agree at once: no ladder
        assert "unstable at any" in c.message


def test_a_lone_eigenvalue_of_a_hamiltonian_tether_off_the_axis_is_round_off():
    """Undamped under one current (gyroscopic and conservative), an eigenvalue leaves the imaginary axis only with
    its mirror image -conj(lambda). The top of the band of a fine mesh carries Re lambda of 1e-8..1e-7 |lambda| of
    round-off: read as flutter it gave the spin line of the benchmark's mission #23 (pinned ends, a gravity-gradient
    tension) a crossing at omega = 22.5 on N = 96 against the divergence at 577.45 on N = 24."""
    lam = np.array([1e-4 + 5000j, 0.2 + 3j, -0.2 + 3j, 1e-9 + 7j, -1e-9 + 7j])
    assert np.array_equal(line_band.mirrored(lam), [5000j, 0.2 + 3j, -0.2 + 3j, 1e-9 + 7j, -1e-9 + 7j])
    p = RodParameters(P=1.3e-7, R=0.55, Gamma=0.7, B=43.4, omega=0.37, T=145635.0, gamma=0.0,
                      ends=("pinned", "pinned"))
    t = Tether(p, tension=Profile((0.0, 1.0), ((0.522, 0.043, -0.4775),)))
    found = [critical(t, "omega", tol=1e-10, ladder=(N,), check=False, mode=False) for N in (24, 96)]
    assert [c.kind for c in found] == [CriticalKind.DIVERGENCE] * 2
    assert found[1].value == pytest.approx(found[0].value, rel=1e-7) and found[0].value == pytest.approx(577.45, rel=1e-4)


def test_an_isotropic_tether_at_rest_under_one_current_only_diverges():
    """Undamped, at rest, under one current the problem is self-adjoint (M lambda^2 + K, both symmetric): lambda^2
    is real and no flutter exists. R = 1 has every frequency double, which round-off splits into a pair either side
    of the axis, like a collision: on one mesh the benchmark's mission #26 at rest (R = 1, a gravity-gradient
    tension) read as flutter at B = 6e-4 before, against its divergence at 271615.35."""
    p = RodParameters(P=1.5e-5, R=1.0, Gamma=0.8, B=1.56e-4, omega=0.0, T=85550.4, gamma=0.0)
    t = Tether(p, tension=Profile((0.0, 1.0), ((0.6025, 0.1911, -0.3856),)))
    assert line_band.mirrored(np.array([1e-9 + 5j, -1e-9 + 5j, 2.0 + 1e-12j]), real_square=True).tolist() == [
        5j, 5j, 2.0]
    found = [critical(t, tol=1e-6, ladder=(N,), check=False, mode=False) for N in (24, 36)]
    assert [c.kind for c in found] == [CriticalKind.DIVERGENCE] * 2, [c.message for c in found]
    assert found[1].value == pytest.approx(found[0].value, rel=1e-7)


def test_a_slow_flutter_reports_the_eigenvalue_that_crosses():
    """The shipped tape, lightly damped and slowly spun: Re lambda of the crossing eigenvalue passes 0 at 1e-3 per
    unit load, so just past the crossing it is still below the threshold of instability; the crossing reported is
    that eigenvalue, on the axis there (not the one nearest 0: another mode, its frequency and shape)."""
    from helpers import tape

    from etcheck.checks.orbit_field import resolve
    from etcheck.input.mission import mission_from_dict
    from etcheck.scaling import scale

    t = scale(resolve(mission_from_dict(tape())).scene).tether.with_(gamma=4.375e-5, omega=0.00256)
    c = critical(t, mode=False)
    assert c.kind == CriticalKind.FLUTTER
    assert abs(c.eigenvalue.real) <= 1e-9 * abs(c.eigenvalue)
    assert c.eigenvalue.imag == pytest.approx(4.1363211, rel=1e-7)


@pytest.mark.slow  # 15 s: a band of 228 eigenvalues per point
def test_the_ladder_starts_at_a_mesh_that_resolves_the_band():
    """An undamped spun tether between end masses under a large tension: the load up to its line's end reshapes
    112 modes, which the coarsest meshes (129 and 169 points per field) do not resolve (their top modes collided
    spuriously: flutter at 1538 and 2147; the ladder now starts past them). The crossing is located on meshes that
    resolve the band, and it is the divergence at the first static point that the same tether damped finds on its
    static route (Kelvin-Tait-Chetaev): two routes of rung 1v, spectra and static pencils, agree."""
    from etcheck.input.mission import mission_from_dict
    from etcheck.scaling import scale, scene

    data = {"mission": {"name": "spun between end masses"},
            "tether": {"length": "576.4505415411761 m",
                       "bending_stiffness": ["0.026131525907200956 N m2", "0.00890701270823247 N m2"],
                       "mass_per_length": "0.0006971129721733759 kg/m", "poisson_ratio": 0.411,
                       "rotary_inertia_ratio": 0.004056802354213013, "damping_time": "0 s",
                       "end_masses": ["168 kg", "10.5 kg"]},
            "operation": {"spin_rate": "0.0024066897792523953 rad/s", "axial_field": "50 uT",
                          "orbit_altitude": "1121 km", "current": "0.00032246005123118504 A"}}
    t = scale(scene(mission_from_dict(data))).tether
    c = critical(t, mode=False)
    assert c.kind == CriticalKind.DIVERGENCE and c.N >= 48
    damped = critical(t.with_(gamma=0.04375), mode=False)
    assert circulatory.static_only(t.with_(gamma=0.04375))
    assert c.value == pytest.approx(damped.value, rel=1e-6)
