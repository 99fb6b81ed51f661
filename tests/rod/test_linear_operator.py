"""The discretised O(delta) operator (etcheck.rod.core.linear)."""

import numpy as np
import pytest
import scipy.linalg as sla

from etcheck.numerics.chebyshev import diff_matrix, lobatto_nodes, lobatto_weights
from etcheck.numerics.eigen import match_spectra, qep_dense
from etcheck.rod.core.base_state import CallableBaseState, rotated, straight
from etcheck.rod.core.linear import (
    NFIELDS,
    coefficient_blocks,
    collocation,
    field_slice,
    linear_operator,
    stiffness_diag,
)
from etcheck.rod.core.parameters import RodParameters

SET = RodParameters(P=0.001, R=21 / 38, Gamma=0.76923)


def skew(v):
    v = np.asarray(v)
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def expm_batch(V):
    return np.array([sla.expm(skew(v)) for v in V])


def test_shapes_and_structure():
    N = 12
    p = SET.with_(B=0.4)
    A0, A1, A2 = linear_operator(p, straight(p), N)
    n = NFIELDS * (N + 1)
    assert A0.shape == A1.shape == A2.shape == (n, n)
    assert not np.any(A1)  # no spin, no damping
    # lambda never multiplies phi or m
    for name in ("phi1", "phi2", "phi3", "m1", "m2", "m3"):
        sl = field_slice(name, N)
        assert not np.any(A1[:, sl]) and not np.any(A2[:, sl])
    A0g, A1g, _ = linear_operator(p.with_(gamma=0.1, omega=0.3), straight(p), N)
    assert np.any(A1g[:, field_slice("a1", N)]) and np.any(A1g[:, field_slice("xi2", N)])


class _Wavy:
    """A smooth, deliberately non-equilibrium base state with D0 != I."""

    def __init__(self):
        self.th = lambda s: np.stack([0.3 * s, -0.2 * s**2, 0.5 * s * (1 - s) + 0.1], axis=-1)

    def state(self):
        return CallableBaseState(
            x0_fn=lambda s: np.stack([0.1 * s**2, -0.05 * s, s], axis=-1),
            D0_fn=lambda s: expm_batch(self.th(s)),
            F0_fn=lambda s: np.stack([0.2 - s, 0.3 * s**2, 1.5 + 0.2 * s], axis=-1),
            M0_fn=lambda s: np.stack([0.01 * s, -0.002 + 0.003 * s, 0.004 * s**2], axis=-1),
            kappa0_fn=lambda s: np.zeros((np.size(s), 3)),
        )


def _residual(params, base, N, Y, eps, lam):
    """Nonlinear residual of eqs. (37)-(41) at the ODE points for the
    perturbation eps * Y e^{lam t} (t = 0), in the operator's row form."""
    col = collocation(N)
    s, t = col.s, col.t
    n1 = N + 1
    f = Y.reshape(NFIELDS, n1).T  # (n1, 12)
    xi, a, phi, m = f[:, 0:3], f[:, 3:6], f[:, 6:9], f[:, 9:12]
    K = stiffness_diag(params)
    w = params.omega * np.array([0, 0, 1.0])
    c = (params.P * params.R, params.P, 0.0)
    D0t = base.D0(t)

    def fields(e):
        x = base.x0(s) + e * xi
        D = np.einsum("nab,nbc->nac", expm_batch(e * a), base.D0(s))
        F = base.F0(s) + e * phi
        M = base.M0(s) + e * m
        return x, D, F, M

    def kappa_body(e):
        _, D, _, _ = fields(e)
        Dt = np.einsum("kj,jab->kab", col.P, D)
        Dp = np.einsum("kj,jab->kab", col.PD, D)
        X = np.einsum("nba,nbc->nac", Dt, Dp)
        X = 0.5 * (X - np.transpose(X, (0, 2, 1)))
        return np.stack([X[:, 2, 1], X[:, 0, 2], X[:, 1, 0]], axis=-1)

    x, D, F, M = fields(eps)
    P, PD = col.P, col.PD
    xt, Dt, Ft, Mt = P @ x, np.einsum("kj,jab->kab", P, D), P @ F, P @ M
    xp, Fp, Mp = PD @ x, PD @ F, PD @ M
    d = [Dt[:, :, i] for i in range(3)]
    at = P @ a
    ahat = skew(eps * at)
    # time derivatives of x and d_i for the e^{lam t} perturbation at t = 0
    x_t, x_tt = eps * lam * (P @ xi), eps * lam**2 * (P @ xi)
    d_t = [lam * np.einsum("nab,nb->na", ahat, di) for di in d]
    d_tt = [lam**2 * (np.einsum("nab,nb->na", ahat, di) + np.einsum("nab,nbc,nc->na", ahat, ahat, di)) for di in d]
    h = 1e-6
    kb = kappa_body(eps)
    kb_t = lam * eps * (kappa_body(eps * (1 + h)) - kappa_body(eps * (1 - h))) / (2 * eps * h)
    e3 = np.array([0, 0, 1.0])
    r_xi = xp - d[2]
    r_a = np.einsum("nab,b,nb->na", D0t, K, kb + params.gamma * kb_t) - np.einsum(
        "nab,ncb,nc->na", D0t, Dt, Mt)
    r_phi = Fp + params.B * np.cross(d[2], e3) - (x_tt + 2 * np.cross(w, x_t) + np.cross(w, np.cross(w, xt)))
    rhs = np.zeros_like(Mp)
    for ci, di, dit, ditt in zip(c, d, d_t, d_tt):
        rhs += ci * (np.cross(di, ditt) + 2 * np.cross(di, np.cross(w, dit))
                     + (di @ w)[:, None] * np.cross(di, w))
    r_m = Mp + np.cross(d[2], Ft) - rhs
    return np.concatenate([r.T.reshape(-1) for r in (r_xi, r_a, r_phi, r_m)])


@pytest.mark.parametrize("lam", [0.0, 0.7, -1.3])
def test_operator_is_the_linearisation_for_a_general_base_state(lam):
    """Central differences of the nonlinear PDE residual (eqs. (37), (38),
    (39), (40), (41)) about a base state with D0 != I, F0, M0 != 0
    reproduce (A0 + lam A1 + lam^2 A2) Y on the ODE rows."""
    N = 14
    params = RodParameters(P=0.02, R=0.6, Gamma=0.8, f=3.0, B=0.7, omega=0.9, T=0.3, gamma=0.15)
    base = _Wavy().state()
    rng = np.random.default_rng(1)
    s = lobatto_nodes(N)
    # smooth random perturbation fields
    Y = np.concatenate([np.polynomial.Polynomial(rng.normal(size=5))(s) for _ in range(NFIELDS)])
    A0, A1, A2 = linear_operator(params, base, N)
    lin = ((A0 + lam * A1 + lam**2 * A2) @ Y)[: NFIELDS * N]
    eps = 1e-4
    fd = (_residual(params, base, N, Y, eps, lam) - _residual(params, base, N, Y, -eps, lam)) / (2 * eps)
    assert np.max(np.abs(fd - lin)) <= 1e-6 * np.max(np.abs(lin))
    # the check is sharp: dropping the rotary-inertia term is detected
    A0b, A1b, A2b = linear_operator(params.with_(P=0.0), base, N)
    if lam != 0.0:
        bad = ((A0b + lam * A1b + lam**2 * A2b) @ Y)[: NFIELDS * N]
        assert np.max(np.abs(fd - bad)) > 1e-4 * np.max(np.abs(lin))


def _reduced_fourth_order(params, N):
    """Independent square collocation of the straight-rod reduction (docs/model.md, section 6):
    lam^2 (u - P R u'') - 2 lam w v + (R/f)(1 + g lam) u'''' - (T + P R w^2) u'' - w^2 u - B v' = 0
    lam^2 (v - P v'') + 2 lam w u + (1/f)(1 + g lam) v'''' - (T + P w^2) v'' - w^2 v + B u' = 0
    clamped at both ends; returns all finite eigenvalues."""
    P, R, f, B, w, T, g = params.P, params.R, params.f, params.B, params.omega, params.T, params.gamma
    s = lobatto_nodes(N)
    D = diff_matrix(s, lobatto_weights(N))
    D2, D4 = D @ D, D @ D @ D @ D
    Id = np.eye(N + 1)
    Z = np.zeros_like(Id)
    M2 = np.block([[Id - P * R * D2, Z], [Z, Id - P * D2]])
    M1 = np.block([[g * R / f * D4, -2 * w * Id], [2 * w * Id, g / f * D4]])
    M0 = np.block([[R / f * D4 - (T + P * R * w**2) * D2 - w**2 * Id, -B * D],
                   [B * D, D4 / f - (T + P * w**2) * D2 - w**2 * Id]])
    n = N + 1
    for blk in (0, 1):
        for r, row in ((1, Id[0]), (0, D[0]), (N - 1, D[N]), (N, Id[N])):
            i = blk * n + r
            for Mk in (M0, M1, M2):
                Mk[i] = 0.0
            M0[i, blk * n:(blk + 1) * n] = row
    return qep_dense(M0, M1, M2)


def _torsion(params, nmax):
    """P(1+R) lam^2 a3 = Gamma(1+R)/(2f)(1 + g lam) a3'', a3 = 0 at the ends."""
    c = params.Gamma / (2 * params.P * params.f)
    out = []
    for n in range(1, nmax + 1):
        q = c * (n * np.pi) ** 2
        out += list(np.roots([1.0, params.gamma * q, q]))
    return np.array(out, dtype=complex)


@pytest.mark.parametrize("kw", [
    dict(),
    dict(omega=0.4, B=0.3),
    dict(omega=0.8, T=0.5, gamma=0.05, B=0.2),
    dict(R=1.0, omega=1.3, B=0.6, T=-0.1),
    dict(omega=0.75, B=0.45),
])
def test_straight_rod_reduces_to_the_fourth_order_system(kw):
    params = SET.with_(**kw)
    A = linear_operator(params, straight(params), 28)
    full = qep_dense(*A)
    full = full[np.abs(full) < 12]
    ref = np.concatenate([_reduced_fourth_order(params, 40), _torsion(params, 4)])
    ref = ref[np.abs(ref) < 10]
    assert ref.size >= 16
    for lam in ref:
        assert np.min(np.abs(full - lam)) <= 1e-8 * max(1.0, abs(lam))
    for lam in full[np.abs(full) < 10]:
        assert np.min(np.abs(ref - lam)) <= 1e-8 * max(1.0, abs(lam))


def _same(a, b):
    a, b = a[np.abs(a) < 10], b[np.abs(b) < 10]
    assert a.size == b.size > 10
    m = match_spectra(a, b, accept=np.inf, floor=1.0)
    assert m.values.size == a.size and np.max(m.errors) < 1e-9


def test_rotated_base_state_gives_the_same_spectrum():
    """Rotations about e3 of the straight state (D0 != I) leave the spectrum unchanged."""
    params = SET.with_(omega=0.5, B=0.3, gamma=0.02, T=0.2)
    Q = np.diag([-1.0, -1.0, 1.0])
    a = qep_dense(*linear_operator(params, straight(params), 24))
    b = qep_dense(*linear_operator(params, rotated(straight(params), Q), 24))
    _same(a, b)
    # an isotropic rod does not care about any rotation about its axis
    iso = params.with_(R=1.0)
    c = qep_dense(*linear_operator(iso, straight(iso), 24))
    Qz = sla.expm(skew([0.0, 0.0, 0.7]))
    d = qep_dense(*linear_operator(iso, rotated(straight(iso), Qz), 24))
    _same(c, d)
    # rotating the whole problem about e3 is a symmetry for any R (field and
    # spin are along e3; the linearised welds are a = 0 whatever D0(0), D0(1))
    e = qep_dense(*linear_operator(params, rotated(straight(params), Qz), 24))
    _same(a, e)


def test_straight_coefficients_made_once_are_those_of_every_point():
    """The straight state's coefficients are made at one point and repeated: the same as a general base state
    with the same fields, point by point, for load, spin, tension and damping."""
    p = RodParameters(P=1e-3, R=0.55, Gamma=0.77, B=0.3, omega=0.25, T=2.0, gamma=0.04)
    s = np.linspace(0.0, 1.0, 9)
    fast = coefficient_blocks(p, straight(p), s)
    general = coefficient_blocks(p, rotated(straight(p), np.eye(3)), s)
    for a, b in zip(fast, general):
        assert a.shape == b.shape == (9, 12, 12)
        assert np.array_equal(a, b)
