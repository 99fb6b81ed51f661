"""The bowed tether (etcheck.rod.bowed): equilibria under a field across the chord, their path in B, the taut-string
limit, the engineering quantities (dimensionless, f-scaling)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from etcheck.numerics.chebyshev import clenshaw_curtis_weights
from etcheck.rod.bowed import path as bp
from etcheck.rod.bowed import quantities as bq
from etcheck.rod.bowed import statics as bs
from etcheck.rod.bowed import string as bstr
from etcheck.rod.bowed.field import CrossField
from etcheck.rod.buckled import equilibria as eq
from etcheck.rod.core.linear import collocation
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile
from etcheck.rod.core.spectrum import lowest_eigenvalues
from etcheck.rod.straight.analytic import critical_loads

GAMMA = 0.76923


def rod(R: float = 0.5, **kw) -> RodParameters:
    return RodParameters(P=0.001, R=R, Gamma=GAMMA, **kw)


def solved(params: RodParameters, field: CrossField, N: int, steps: int = 1) -> eq.Equilibrium:
    """The equilibrium at params.B, reached from the straight tether in ``steps`` equal load steps."""
    state = eq.straight_state(params.with_(B=0.0), N)
    for B in np.linspace(0.0, params.B, steps + 1)[1:]:
        state = bs.solve(params.with_(B=float(B)), field, state)
    return state


@pytest.mark.parametrize("ends", [("welded", "welded"), ("pinned", "welded"), ("pinned", "pinned")])
def test_jacobian_is_exact(ends):
    p = rod(B=0.4, T=1.0, ends=ends)
    field = CrossField(math.radians(40.0), 0.3, Profile.piecewise_linear([0.0, 1.0], [0.4, 1.0]))
    rng = np.random.default_rng(1)
    N = 10
    u = eq.retract(eq.straight_state(p, N), 1e-2 * rng.standard_normal(12 * (N + 1)))
    J = bs.jacobian(p, field, u)
    h = 1e-6
    for c in rng.choice(J.shape[1], 40, replace=False):
        d = np.zeros(J.shape[1])
        d[c] = h
        fd = (bs.residual(p, field, eq.retract(u, d)) - bs.residual(p, field, eq.retract(u, -d))) / (2 * h)
        assert np.max(np.abs(fd - J[:, c])) < 1e-6 * max(1.0, np.max(np.abs(J[:, c])))
    dB = (bs.residual(p.with_(B=0.4 + h), field, u) - bs.residual(p.with_(B=0.4 - h), field, u)) / (2 * h)
    assert np.max(np.abs(dB - bs.load_derivative(p, field, u))) < 1e-8


def test_spin_and_thin_end_layers_are_refused():
    with pytest.raises(ValueError, match="at rest only"):
        solved(rod(B=0.1, omega=0.5), CrossField(1.0), 20)
    with pytest.raises(bs.EndLayerError, match="graded multi-domain"):
        solved(rod(R=1e-6, B=1.0, T=1e4), CrossField(1.0), 20)
    with pytest.raises(bs.EndLayerError, match="need N >="):
        solved(rod(B=1.0, T=1e3), CrossField(1.0), 40)


def test_along_the_chord_the_path_is_straight_and_singular_at_the_first_critical_load():
    p = rod(R=0.5)
    B1 = critical_loads(0.5, p.f, 1)[0]
    path = bp.follow(p, CrossField(0.0), 1.5 * B1, N=24)
    bow = max(float(np.max(np.abs(s.x[:, :2]))) for s in path.states)
    assert bow < 1e-12
    first = path.singular[0]
    assert first.kind == "double"  # the straight tether's pitchfork is double (docs/model.md section 7)
    assert first.B == pytest.approx(B1, rel=1e-6)


def interior_curvature(state: eq.Equilibrium, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Curvature and torsion of the centreline from x' = d3, x'', x''' (Chebyshev derivatives)."""
    D = collocation(state.N).D
    d3 = state.D[:, :, 2]
    t, t1, t2 = (state._interp(s, v) for v in (d3, D @ d3, D @ (D @ d3)))
    b = np.cross(t, t1)
    return np.linalg.norm(t1, axis=1), np.einsum("na,na->n", b, t2) / np.einsum("na,na->n", b, b)


def string_error(R: float, T: float, alpha: float) -> tuple[float, float, float]:
    """(curvature error, torsion error, end layer) of the rod against the taut string in the interior, both
    relative to B/T."""
    p = rod(R=R, T=T, B=0.5 * T)
    field = CrossField(alpha, math.pi / 2 if R < 1 else 0.0)
    stiff = math.sqrt(1.0 / (p.f * T))
    N = max(bs.required_resolution(p), math.ceil(6.5 / math.sqrt(stiff)))
    state = solved(p, field, N)
    h = bstr.helix(T, p.B, alpha)
    s = np.linspace(0.25, 0.75, 21)
    kappa, tau = interior_curvature(state, s)
    return (float(np.max(np.abs(kappa - h.curvature))) / h.k, float(np.max(np.abs(tau - h.torsion))) / h.k,
            math.sqrt(R / (p.f * T)))


@pytest.mark.parametrize("R", [1.0, 0.5])
def test_taut_string_across_the_field_is_a_circular_arc(R):
    errors = []
    for T in (1e2, 1e3):
        err, _, layer = string_error(R, T, math.pi / 2)
        assert err < layer  # within the end layer's width of the string
        errors.append(err)
    assert errors[1] < errors[0] / 2.0  # falls like the end layer, sqrt(1/T)
    rho = bstr.arc_radius(1e3, 500.0)
    assert rho * math.cos(0.5 / rho) == pytest.approx(2.0, rel=1e-14)
    assert 1.0 / rho == pytest.approx(bstr.helix(1e3, 500.0, math.pi / 2).curvature, rel=1e-12)


def test_tilted_field_gives_a_helical_arc():
    alpha = math.radians(45.0)
    errs = [string_error(1.0, T, alpha) for T in (1e2, 1e3)]
    for kappa_err, tau_err, layer in errs:
        assert kappa_err < layer and tau_err < 2 * layer
    assert errs[1][0] < errs[0][0] / 2.0 and errs[1][1] < errs[0][1] / 2.0
    h = bstr.helix(1e3, 500.0, alpha)
    assert h.curvature == pytest.approx(0.5 * math.sin(alpha), rel=0.02)  # (B/T) sin(alpha) to O(B/T)^2
    assert math.hypot(h.curvature, h.torsion) == pytest.approx(h.k, rel=1e-14)


@pytest.mark.parametrize("R, alpha, phi", [(1.0, 10.0, 0.0), (1.0, 45.0, 0.0), (1.0, 90.0, 0.0),
                                           (0.5, 10.0, 90.0), (0.5, 45.0, 90.0), (0.5, 90.0, 90.0),
                                           (0.5, 10.0, 0.0), (0.5, 45.0, 0.0)])
def test_no_singular_point_up_to_six_critical_loads(R, alpha, phi):
    p = rod(R=R)
    B1 = critical_loads(R, p.f, 1)[0]
    path = bp.follow(p, CrossField(math.radians(alpha), math.radians(phi)), 6.0 * B1, N=20)
    assert path.loads[-1] == pytest.approx(6.0 * B1)
    assert path.singular == ()
    assert all(not d.singular for d in path.dips)


@pytest.mark.parametrize("alpha, phi, ratio", [(0.5, 90.0, 4.08), (90.0, 0.0, 1.96)])
def test_branch_points_that_survive(alpha, phi, ratio):
    """R = 0.5: a small tilt keeps a branch point above the straight load (the tilted secondary pitchfork of the
    coil bowed in the weak plane); a field across the chord along the stiff axis bows the tether in its stiff
    plane, which a branch point out of that plane ends (lateral-torsional buckling)."""
    p = rod(R=0.5)
    B1 = critical_loads(0.5, p.f, 1)[0]
    path = bp.follow(p, CrossField(math.radians(alpha), math.radians(phi)), 6.0 * B1, N=20)
    assert [s.kind for s in path.singular][:1] == ["bp"]
    assert path.singular[0].B / B1 == pytest.approx(ratio, abs=0.02)


def test_two_resolutions_agree_to_the_stated_error():
    p = rod(B=0.8, T=1.0)
    field = CrossField(math.radians(45.0), 0.3)
    a = bq.assess(solved(p, field, 24, 4), field)
    finer = bq.quantities(solved(p, field, 48, 4), field)
    stated = a.error.vector()
    assert np.all(np.abs(a.value.vector() - finer.vector()) <= 10.0 * stated + 1e-12)
    assert np.max(stated) < 1e-5 and a.value.stable and a.value.out_of_plane > 0.0
    assert a.value.bow >= a.value.in_plane >= a.value.out_of_plane


def test_resultant_lorentz_force_depends_on_the_ends_only():
    field = CrossField(math.radians(60.0), 1.0)
    b = field.direction
    for ends in [("welded", "welded"), ("pinned", "pinned")]:
        state = solved(rod(B=2.0, T=0.5, ends=ends), field, 24, 8)
        resultant = -(state.F[-1] - state.F[0])
        assert np.allclose(resultant, 2.0 * np.cross(state.x[-1] - state.x[0], b), atol=1e-10)
        if ends[0] == "pinned":
            assert np.max(np.abs(np.einsum("a,ab->b", state.M[0], state.D[0][:, :2]))) < 1e-12
    with pytest.raises(ValueError, match="smooth current profile"):
        CrossField(1.0, 0.0, Profile.piecewise_linear([0.0, 0.5, 1.0], [0.2, 0.7, 1.0]))
    profile = Profile.piecewise_linear([0.0, 1.0], [0.2, 1.0])
    varying = CrossField(field.alpha, field.phi, profile)
    state = solved(rod(B=2.0, T=0.5), varying, 24, 8)
    n2 = 64
    s = collocation(n2).s
    load = 2.0 * profile(s)[:, None] * np.cross(state.D0(s)[:, :, 2], b)
    assert np.allclose(-(state.F[-1] - state.F[0]), clenshaw_curtis_weights(n2) @ load, atol=1e-6)


def test_lowest_frequency_and_stability():
    """Along the chord the generalised linearisation is the straight rod's; a small tilt keeps the knee: the
    lowest frequency falls towards it."""
    p = rod(T=0.0)
    B1 = critical_loads(0.5, p.f, 1)[0]
    straight = lowest_eigenvalues(p.with_(B=0.9 * B1), None, 24, 4)
    q = bq.quantities(solved(p.with_(B=0.9 * B1), CrossField(0.0), 24), CrossField(0.0))
    assert q.frequency == pytest.approx(float(np.min(straight.imag[straight.imag > 0])), rel=1e-10)
    assert q.bow == 0.0 and q.stable
    field = CrossField(math.radians(2.0), math.pi / 2)
    q0 = bq.quantities(solved(p, field, 24), field)
    q = bq.quantities(solved(p.with_(B=0.9 * B1), field, 24, 6), field)
    assert q0.stable and q.stable
    assert q.frequency < 0.7 * q0.frequency
