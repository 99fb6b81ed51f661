"""Whirling relative equilibria: the O(1) boundary-value problem and its Newton solver.

Everything here is dimensionless (eq. (36) of arXiv:0810.3668, f-scaling).

Equations (Sec. V A, eqs. (49)-(57) written in vector form in the frame
rotating with omega e3, i.e. eqs. (37)-(41) with the time derivatives set
to zero; erratum
M_3^0 = Gamma (1 + R)/(2 f) kappa_3^0 applied)::

    x'  = d3                                                  (55)
    D K kappa - M = 0,  kappa = axial(D^T D') (body)          (56), (57)
    F' + B d3 x e3 - omega^2 e3 x (e3 x x) = 0                (49)-(51)
    M' + d3 x F - sum_i c_i (omega e3 . d_i)(d_i x omega e3) = 0   (52)-(54)

with K = diag(1, R, Gamma (1+R)/2)/f, c = (P R, P, 0), and the welded boundary
conditions (58)-(69) (F(0).e3 = +T, tension positive, the erratum of
eq. (86); docs/errata.md, #5); (70) holds by
construction because D(s) is kept in SO(3).

Formulation (chosen, and why). The unknown fields are x(s), D(s) in SO(3),
F(s), M(s) at the N+1 Chebyshev-Lobatto nodes. The residual is the rectangular
collocation of :mod:`etcheck.rod.core.linear`: fields (and D' from the nodal
values) are resampled to the N first-kind points t_k where the 12 ODE rows are
imposed, and the 12 boundary rows are appended, so residual rows and unknowns
are ordered exactly like the rows and columns of the linear operator
(``linear.VARIABLES``). Newton's update is

    x += xi,  D <- expm(skew(a)) D,  F += phi,  M += m,

the same (xi, a, phi, m) in which :func:`etcheck.rod.core.linear.linear_operator`
is written. Reasons: (i) one set of perturbation variables serves Newton,
continuation, branch detection and (rung 3) stability (docs/model.md, section 5.2);
(ii) the rotation-vector update keeps D exactly orthonormal with 12 unknowns
per node (no constraint rows, no redundant director components as in the
paper's 18-ODE AUTO formulation); (iii) spectral accuracy: the SET branches
converge to 1e-12 with N = 32-40. ``scipy.integrate.solve_bvp`` was not used
as the solver (it would need the first-order system with orthonormality kept
by hand, offers no access to the Jacobian for branch detection, and its
4th-order collocation needs thousands of nodes for 1e-10); the tests use it
on an independent quaternion formulation as a cross-check (agreement 1e-10).

Which Jacobian. The lambda = 0 operator A0 of ``linear_operator`` about the
iterate is *not* exactly the derivative of this discrete residual: A0
evaluates its coefficients from interpolated base fields at t_k (e.g.
(P a) x (P d3)), while the residual differentiates products of nodal values
(P (a x d3)); the two differ by the aliasing error of the collocation (for
smooth directions ~1e-9 relative at N = 32 on a buckled SET state, decaying
spectrally; O(1) for the highest modes) plus terms proportional to the
residual. They are identical at the straight rod and on the boundary rows.
Newton with A0 converges, but only linearly in its last steps. So
:func:`jacobian` assembles the exact derivative of the discrete residual by
default (same cost as A0, checked column by column against finite
differences in the tests), which gives quadratic convergence to rounding;
``jacobian(..., exact=False)`` returns A0. Consequences: the discrete
pitchforks of the straight rod are exactly the divergence loads of
:mod:`etcheck.rod.straight.collocation.spectral` at the same N, and the singular points of A0
along a buckled branch (rung 3, lambda = 0) agree with the branch points found
here to the discretisation error.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg as sla

from etcheck.errors import SolverError
from etcheck.numerics.chebyshev import clenshaw_curtis_weights, lobatto_weights, resample_matrix
from etcheck.rod.core.ends import BUCKLED_WELDED_ONLY
from etcheck.rod.core.linear import NFIELDS, collocation, end_rows, skew, static_operator, stiffness_diag
from etcheck.rod.core.parameters import RodParameters

__all__ = [
    "PARAMETERS",
    "Equilibrium",
    "Measures",
    "straight_state",
    "residual",
    "jacobian",
    "parameter_derivative",
    "retract",
    "solve_equilibrium",
    "resample_state",
    "ResolutionError",
    "resolution_error",
    "measures",
    "measure1",
    "rodrigues",
    "require_welded",
]

#: Parameters a branch can be continued in.
PARAMETERS = ("B", "omega", "T", "R")
_E3 = np.array([0.0, 0.0, 1.0])


def rodrigues(a: np.ndarray) -> np.ndarray:
    """expm(skew(a)) for rotation vectors a of shape (n, 3); returns (n, 3, 3)."""
    a = np.atleast_2d(a)
    th = np.linalg.norm(a, axis=1)
    small = th < 1e-6
    th2 = th * th
    with np.errstate(invalid="ignore", divide="ignore"):
        s1 = np.where(small, 1.0 - th2 / 6.0 + th2 * th2 / 120.0, np.sin(th) / np.where(small, 1.0, th))
        s2 = np.where(small, 0.5 - th2 / 24.0 + th2 * th2 / 720.0, (1.0 - np.cos(th)) / np.where(small, 1.0, th2))
    K = np.zeros((a.shape[0], 3, 3))
    K[:, 0, 1], K[:, 0, 2] = -a[:, 2], a[:, 1]
    K[:, 1, 0], K[:, 1, 2] = a[:, 2], -a[:, 0]
    K[:, 2, 0], K[:, 2, 1] = -a[:, 1], a[:, 0]
    return np.eye(3) + s1[:, None, None] * K + s2[:, None, None] * (K @ K)


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """A whirling relative equilibrium on N+1 Chebyshev-Lobatto nodes (dimensionless).

    Nodal arrays (e-frame components, node j at s_j = lobatto_nodes(N)[j]):
    ``x`` (N+1, 3) centreline, ``D`` (N+1, 3, 3) directors (column i is d_i),
    ``F`` (N+1, 3) contact force, ``M`` (N+1, 3) contact moment.
    ``residual_norm`` is the max-norm of the collocation residual, ``iterations``
    the Newton steps taken, ``converged`` whether ``residual_norm`` met the
    tolerance. Satisfies the :class:`~etcheck.rod.core.base_state.BaseState`
    protocol through its Chebyshev interpolants (``x0``, ``D0``, ``F0``, ``M0``,
    ``kappa0``; D0 is the raw interpolant, orthonormal at the nodes and to
    discretisation accuracy in between), so :func:`etcheck.rod.core.linear.linear_operator`
    linearises about it (rung 3).
    """

    params: RodParameters
    x: np.ndarray
    D: np.ndarray
    F: np.ndarray
    M: np.ndarray
    residual_norm: float = math.nan
    iterations: int = 0
    converged: bool = False
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def N(self) -> int:
        return self.x.shape[0] - 1

    @property
    def s(self) -> np.ndarray:
        return collocation(self.N).s

    def _interp(self, s, values: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s, dtype=float))
        key = s.tobytes()
        P = self._cache.get(key)
        if P is None:
            P = resample_matrix(self.s, s, lobatto_weights(self.N))
            if len(self._cache) < 8:
                self._cache[key] = P
        return np.tensordot(P, values, axes=(1, 0))

    def x0(self, s) -> np.ndarray:
        return self._interp(s, self.x)

    def D0(self, s) -> np.ndarray:
        return self._interp(s, self.D)

    def F0(self, s) -> np.ndarray:
        return self._interp(s, self.F)

    def M0(self, s) -> np.ndarray:
        return self._interp(s, self.M)

    def kappa0(self, s) -> np.ndarray:
        """Body curvature kappa_j = kappa . d_j from axial(D^T D') (eq. (40))."""
        col = collocation(self.N)
        Dp = np.einsum("jk,kab->jab", col.D, self.D)
        return _axial(self._interp(s, self.D), self._interp(s, Dp))

    def vector(self) -> np.ndarray:
        """Nodal values stacked in ``linear.VARIABLES`` order with a replaced by 0
        (used only to form differences of x, F, M between states)."""
        z = np.zeros_like(self.x)
        return np.concatenate([v.T.reshape(-1) for v in (self.x, z, self.F, self.M)])

    def with_params(self, params: RodParameters) -> Equilibrium:
        return replace(self, params=params, residual_norm=math.nan, converged=False, _cache={})


def _axial(Dt: np.ndarray, Dp: np.ndarray) -> np.ndarray:
    """Body curvature axial(antisym(Dt^T Dp)) at each point; shapes (n,3,3) -> (n,3)."""
    X = np.einsum("nba,nbc->nac", Dt, Dp)
    X = 0.5 * (X - np.transpose(X, (0, 2, 1)))
    return np.stack([X[:, 2, 1], X[:, 0, 2], X[:, 1, 0]], axis=-1)


def straight_state(params: RodParameters, N: int) -> Equilibrium:
    """The straight rod x = s e3, D = I, F = +T e3, M = 0 (eq. (86), erratum F = +T e3)."""
    s = collocation(int(N)).s
    x = np.zeros((s.size, 3))
    x[:, 2] = s
    D = np.broadcast_to(np.eye(3), (s.size, 3, 3)).copy()
    F = np.zeros((s.size, 3))
    F[:, 2] = params.T
    return Equilibrium(params, x, D, F, np.zeros((s.size, 3)), 0.0, 0, True)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (n, 3) arrays (np.cross without its axis bookkeeping)."""
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1], a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=1)


def require_welded(params: RodParameters) -> None:
    """Raise ValueError (:data:`~etcheck.rod.core.ends.BUCKLED_WELDED_ONLY`) unless both ends are welded: no
    buckled state is ever computed with the wrong ends."""
    if not params.ends.is_welded:
        raise ValueError(f"rungs 2-3 are {BUCKLED_WELDED_ONLY} (ends {params.ends[0]}, {params.ends[1]})")


def residual(params: RodParameters, state: Equilibrium) -> np.ndarray:
    """Collocation residual of the O(1) BVP, shape (12 (N+1),), dimensionless.

    Rows as in :func:`etcheck.rod.core.linear.linear_operator`: ODE group e
    (x', constitutive, F', M' rows, e-frame components) at first-kind point
    t_k is row e N + k; then the 12 welded boundary rows
    (eqs. (58)-(69)). Welded ends only (:func:`require_welded`).
    """
    require_welded(params)
    N = state.N
    col = collocation(N)
    P, PD = col.P, col.PD
    x, D, F, M = state.x, state.D, state.F, state.M
    n1 = N + 1
    Dt = (P @ D.reshape(n1, 9)).reshape(N, 3, 3)
    Dp = (PD @ D.reshape(n1, 9)).reshape(N, 3, 3)
    Ft, Mt, xt = P @ F, P @ M, P @ x
    d3 = Dt[:, :, 2]
    K = stiffness_diag(params)
    kb = _axial(Dt, Dp)
    w2 = params.omega**2
    r_x = PD @ x - d3
    r_a = np.einsum("nab,nb->na", Dt, kb * K[None, :]) - Mt
    # B d3 x e3 = B (d3_2, -d3_1, 0); -w x (w x x) = omega^2 (x_1, x_2, 0)
    r_phi = PD @ F
    r_phi[:, 0] += params.B * d3[:, 1] + w2 * xt[:, 0]
    r_phi[:, 1] += -params.B * d3[:, 0] + w2 * xt[:, 1]
    r_m = PD @ M + _cross(d3, Ft)
    for ci, i in ((params.P * params.R, 0), (params.P, 1)):
        if ci != 0.0 and params.omega != 0.0:
            di = Dt[:, :, i]
            r_m -= ci * (di @ _E3)[:, None] * w2 * np.stack([di[:, 1], -di[:, 0], np.zeros(N)], axis=1)
    ode = np.concatenate([r.T.reshape(-1) for r in (r_x, r_a, r_phi, r_m)])
    d0, d1 = D[0], D[-1]
    bc = np.array([
        x[0, 0], x[0, 1], F[0, 2] - params.T, d0[0, 2], d0[1, 2], d0[1, 0],
        x[-1, 0], x[-1, 1], x[-1, 2] - 1.0, d1[0, 2], d1[1, 2], d1[1, 0],
    ])
    return np.concatenate([ode, bc])


def jacobian(params: RodParameters, state: Equilibrium, exact: bool = True) -> np.ndarray:
    """Newton matrix of :func:`residual` for the update (xi, a, phi, m) of :func:`retract`.

    Shape (12 (N+1), 12 (N+1)), rows/columns as in ``linear_operator``.
    ``exact=True``: the exact derivative of the discrete residual (assembled
    from the same products of interpolants; verified against finite
    differences in the tests). ``exact=False``: the lambda = 0 operator A0 of
    :func:`etcheck.rod.core.linear.linear_operator` about ``state``, which equals
    the exact one at the straight rod and differs from it elsewhere by the
    aliasing error of the collocation plus O(residual) (module docstring).
    """
    require_welded(params)
    if not exact:
        return static_operator(params.with_(gamma=0.0), state, state.N)
    return _exact_jacobian(params, state)


def _levi_civita() -> np.ndarray:
    e = np.zeros((3, 3, 3))
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        e[i, j, k], e[i, k, j] = 1.0, -1.0
    return e


# axial(antisym(A^T skew(e_i) B))_m = sum over (r q), (s p) of A_rq B_sp _CURV[(r q), m, i, (s p)]:
# (A^T E_i B)_qp = -(A_q x B_p)_i (columns), axial_m = 1/2 eps_mpq (.)_qp
_EPS = _levi_civita()
_CURV = (-0.5 * np.einsum("mpq,irs->rqmisp", _EPS, _EPS)).reshape(9, 9, 9)


def _curvature_sensitivity(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """G[k, j, m, i] = axial(antisym(A_k^T skew(e_i) B_j))_m for A (n, 3, 3), B (n', 3, 3);
    shape (n, n', 3, 3). Bilinear in (A, B): two BLAS products with the constant tensor _CURV."""
    X = (A.reshape(-1, 9) @ _CURV.reshape(9, 81)).reshape(-1, 9, 9)  # (k, (m i), (s p))
    G = X.reshape(-1, 9) @ B.reshape(-1, 9).T  # ((k m i), j)
    return G.reshape(A.shape[0], 3, 3, B.shape[0]).transpose(0, 3, 1, 2)


def _exact_jacobian(params: RodParameters, state: Equilibrium) -> np.ndarray:
    """Exact derivative of :func:`residual` (module docstring, "Which Jacobian").

    Every ODE block is a sum of terms W[k, j] C[k, j] (W = P or PD, the
    resampling and differentiation matrices; C a 3 x 3 coefficient at
    first-kind point t_k and node j), assembled with broadcasting and BLAS
    products (the curvature term through :func:`_curvature_sensitivity`).
    """
    N = state.N
    n1 = N + 1
    col = collocation(N)
    P, PD = col.P, col.PD
    D, F = state.D, state.F
    Dt = (P @ D.reshape(n1, 9)).reshape(N, 3, 3)
    Dp = (PD @ D.reshape(n1, 9)).reshape(N, 3, 3)
    Ft = P @ F
    K = stiffness_diag(params)
    kb = _axial(Dt, Dp)
    w = params.omega * _E3
    out = np.zeros((NFIELDS * n1, NFIELDS * n1))
    J = out[: NFIELDS * N].reshape(NFIELDS, N, NFIELDS, n1)  # a view: the ODE rows

    def put(rg: int, cg: int, T: np.ndarray) -> None:
        """Add T of shape (N, N+1, 3, 3) [k, j, row comp, col comp] to block (rg, cg)."""
        J[3 * rg:3 * rg + 3, :, 3 * cg:3 * cg + 3, :] += T.transpose(2, 0, 3, 1)

    def put_weighted(rg: int, cg: int, C: np.ndarray, at: str) -> None:
        """Add P[k, j] C to block (rg, cg) for a 3 x 3 C that is constant (``at`` "", shape (3, 3)), per node j
        ("j", (N+1, 3, 3)) or per first-kind point k ("k", (N, 3, 3)), in the block's layout [a, k, b, j]."""
        if at == "j":
            C = C.transpose(1, 2, 0)[:, None]
        elif at == "k":
            C = C.transpose(1, 0, 2)[..., None]
        else:
            C = C[:, None, :, None]
        J[3 * rg:3 * rg + 3, :, 3 * cg:3 * cg + 3, :] += C * P[None, :, None, :]

    def put_identity(rg: int, cg: int, W: np.ndarray, sign: float = 1.0) -> None:
        """Add sign W[k, j] I to block (rg, cg)."""
        for a in range(3):
            J[3 * rg + a, :, 3 * cg + a, :] += sign * W

    def weighted(W: np.ndarray, C: np.ndarray) -> np.ndarray:
        """W[k, j] C[k, j] with C broadcastable to (N, N+1, 3, 3)."""
        return W[:, :, None, None] * C

    # d(d_i(t_k)) / d a_j = P_kj (a_j x d_i,j) = -P_kj skew(d_i,j) a_j
    skew_d3 = skew(D[:, :, 2])  # (N+1, 3, 3)
    # x rows: PD xi - d(d3)
    put_identity(0, 0, PD)
    put_weighted(0, 1, skew_d3, "j")
    # constitutive rows: d(Dt) K kb + Dt K dkb - P m
    v = kb * K[None, :]  # (N, 3) body vector K kb
    Dv = np.einsum("jab,kb->kja", D, v)  # D_j (K kb_k)
    T = weighted(P, -skew(Dv))  # d/da_j of (a_j x D_j v_k) weighted by P_kj
    # dkb: axial(antisym(-P_kj D_j^T E_i Dp_k + PD_kj Dt_k^T E_i D_j)) for a_j = e_i
    dkb = -P[:, :, None, None] * _curvature_sensitivity(D, Dp).transpose(1, 0, 2, 3)
    dkb += PD[:, :, None, None] * _curvature_sensitivity(Dt, D)
    T += np.matmul((Dt * K[None, None, :])[:, None], dkb)
    put(1, 1, T)
    put_identity(1, 3, P, -1.0)
    # force rows: PD phi + B d(d3) x e3 - w x (w x P xi)
    put_identity(2, 2, PD)
    put_weighted(2, 1, params.B * (skew(_E3) @ skew_d3), "j")  # -B e3 x d(d3), d(d3) = -P [d3]x
    ww = skew(w) @ skew(w)
    put_weighted(2, 0, -ww, "")
    # moment rows: PD m + d(d3) x Ft + d3t x P phi - rotary terms
    put_identity(3, 3, PD)
    J[9:12, :, 3:6, :] += _moment_rotation_block(params, D, Dt, Ft, P)
    put_weighted(3, 2, skew(Dt[:, :, 2]), "k")
    out[NFIELDS * N:] = end_rows(D[[0, -1]], N)  # linearised welded BCs at the end nodes (interpolant = nodal value there)
    return out


def _moment_rotation_block(params: RodParameters, D: np.ndarray, Dt: np.ndarray, Ft: np.ndarray,
                           P: np.ndarray) -> np.ndarray:
    """d(moment rows) / d(rotations a_j): block (3, 1) of :func:`_exact_jacobian` as [a, k, b, j] (its layout in
    the Jacobian), a sum of terms P_kj f(k) g(j), each written as one product over the pairs (k, j).

    -[Ft]x d(d3) = P [Ft]x [d3]x = P (d3 Ft^T - (Ft . d3) I); the rotary terms (eq. (72)), for d = d_i(t_k),
    d_i,j = d_i at node j: d[(w.d)(d x w)] = (w.dd)(d x w) + (w.d)(dd x w) with dd = -P [d_i,j]x a and
    w^T [d_i,j]x = (w x d_i,j)^T, times -c_i: c_i P ((d x w) (w x d_i,j)^T - (w . d) [w]x [d_i,j]x), where
    [w]x [d]x = d w^T - (w . d) I."""
    N, n1 = P.shape
    d3 = D[:, :, 2]
    # d3_j[a] Ft_k[b] - (Ft_k . d3_j) delta_ab
    block = d3.T[:, None, None, :] * Ft[None, :, :, None]
    diag = Ft @ d3.T  # (k, j)
    w = params.omega * _E3
    terms = [(ci, i) for ci, i in ((params.P * params.R, 0), (params.P, 1)) if ci != 0.0 and params.omega != 0.0]
    if terms:
        c = np.array([ci for ci, _ in terms])
        dk = Dt[:, :, [i for _, i in terms]]  # (k, comp, term)
        dj = D[:, :, [i for _, i in terms]]  # (j, comp, term)
        wk = np.broadcast_to(w, (N, 3))
        wj = np.broadcast_to(w, (n1, 3))
        u = np.stack([_cross(dk[:, :, t], wk) for t in range(len(terms))], axis=-1) * c  # c_i (d x w): (k, a, t)
        v = np.stack([_cross(wj, dj[:, :, t]) for t in range(len(terms))], axis=-1)  # (w x d_i,j): (j, b, t)
        # sum_t u[k, a, t] v[j, b, t] as one product, rows (a, k), columns (b, j)
        block += (u.transpose(1, 0, 2).reshape(3 * N, -1) @ v.transpose(2, 1, 0).reshape(-1, 3 * n1)).reshape(3, N, 3, n1)
        s = (dk * w[None, :, None]).sum(axis=1) * c  # c_i (w . d): (k, t)
        # -c_i (w . d) (d_i,j w^T - (w . d_i,j) I)
        wd = dj.transpose(0, 2, 1) @ w  # (j, t): w . d_i,j
        outer = np.einsum("kt,jat->akj", s, dj)  # sum_t s_t(k) d_i,j[a]
        block -= outer[:, :, None, :] * w[None, None, :, None]
        diag -= s @ wd.T
    block[[0, 1, 2], :, [0, 1, 2], :] -= diag
    return block * P[None, :, None, :]


def parameter_derivative(params: RodParameters, state: Equilibrium, name: str) -> np.ndarray:
    """d residual / d parameter for ``name`` in :data:`PARAMETERS` (dimensionless).

    B enters only the force rows (d3 x e3 at the t_k) and T only the
    sliding-end boundary row (F3(0) - T): both written out. The residual is
    affine in R and quadratic in omega, so there a difference quotient of
    step 1/2 (central; one-sided for R, kept in (0, 1]) is exact up to
    rounding.
    """
    if name not in PARAMETERS:
        raise ValueError(f"parameter must be one of {PARAMETERS}, got {name!r}")
    N = state.N
    if name in ("B", "T"):
        out = np.zeros(NFIELDS * (N + 1))
        if name == "T":
            out[NFIELDS * N + 2] = -1.0
        else:
            d3 = collocation(N).P @ state.D[:, :, 2]
            out[6 * N:7 * N] = d3[:, 1]
            out[7 * N:8 * N] = -d3[:, 0]
        return out
    v = getattr(params, name)
    if name == "R":
        h = 0.5 * v
        return (residual(params, state) - residual(params.with_(R=v - h), state)) / h
    h = 0.5
    return (residual(params.with_(**{name: v + h}), state) - residual(params.with_(**{name: v - h}), state)) / (2 * h)


def retract(state: Equilibrium, delta: np.ndarray, params: RodParameters | None = None) -> Equilibrium:
    """The state moved by the update delta = (xi, a, phi, m) (shape (12 (N+1),)).

    x += xi, D <- expm(skew(a)) D (Rodrigues; D stays in SO(3)), F += phi, M += m.
    """
    n1 = state.N + 1
    f = np.asarray(delta, dtype=float).reshape(NFIELDS, n1).T
    D = np.einsum("nab,nbc->nac", rodrigues(f[:, 3:6]), state.D)
    return Equilibrium(params if params is not None else state.params,
                       state.x + f[:, 0:3], D, state.F + f[:, 6:9], state.M + f[:, 9:12])


def _project_so3(D: np.ndarray) -> np.ndarray:
    U, _, Vt = np.linalg.svd(D)
    R = U @ Vt
    neg = np.linalg.det(R) < 0
    if np.any(neg):
        U[neg, :, -1] *= -1
        R = U @ Vt
    return R


def resample_state(state: Equilibrium, N: int) -> Equilibrium:
    """The state interpolated onto N+1 Lobatto nodes (D projected back onto SO(3))."""
    s = collocation(int(N)).s
    return Equilibrium(state.params, state.x0(s), _project_so3(state.D0(s)), state.F0(s), state.M0(s))


def solve_equilibrium(params: RodParameters, guess: Equilibrium, N: int | None = None, tol: float = 1e-11,
                      max_iter: int = 25, raise_on_failure: bool = True) -> Equilibrium:
    """Newton's method for the O(1) BVP at fixed parameters (dimensionless).

    ``guess`` is resampled to N if N differs from ``guess.N``. Converged when
    the max-norm of the residual is below ``tol`` (absolute; the fields are
    O(1)). Returns an :class:`Equilibrium` with ``residual_norm``,
    ``iterations`` and ``converged``; raises :class:`~etcheck.errors.SolverError`
    on failure unless ``raise_on_failure`` is False. Works at isolated
    solutions; at folds or branch points use :mod:`etcheck.rod.buckled.branches`.
    """
    state = guess if N is None or int(N) == guess.N else resample_state(guess, int(N))
    state = state.with_params(params)
    history = []
    for it in range(max_iter + 1):
        r = residual(params, state)
        rn = float(np.max(np.abs(r)))
        history.append(rn)
        if rn < tol:
            return replace(state, residual_norm=rn, iterations=it, converged=True)
        if it == max_iter or not np.isfinite(rn):
            break
        J = jacobian(params, state)
        try:
            with warnings.catch_warnings():  # nearly singular next to a branch point: the residual judges the step
                warnings.simplefilter("ignore", sla.LinAlgWarning)
                delta = sla.solve(J, -r)
        except (sla.LinAlgError, ValueError):
            break
        state = retract(state, delta, params)
    if raise_on_failure:
        raise SolverError(f"equilibrium Newton did not converge at {params} (N = {state.N}): residual history "
                          + ", ".join(f"{h:.1e}" for h in history[-6:]))
    return replace(state, residual_norm=history[-1], iterations=len(history) - 1, converged=False)


@dataclass(frozen=True)
class ResolutionError:
    """Two-resolution error estimate of one equilibrium (dimensionless).

    The state is re-solved at ``N_check`` with the same parameters;
    ``centreline`` is the largest difference of x(s) on a fine grid,
    ``measure1`` and ``end_force`` the differences of measure_1 and of F(0).
    """

    N: int
    N_check: int
    centreline: float
    measure1: float
    end_force: float
    residual: float


def resolution_error(state: Equilibrium, N_check: int | None = None) -> ResolutionError:
    """Estimate the discretisation error of ``state`` by re-solving it at N_check
    (default N + max(8, N // 2)); needs a regular point (not a fold or branch point)."""
    M = state.N + max(8, state.N // 2) if N_check is None else int(N_check)
    other = solve_equilibrium(state.params, state, M)
    sf = np.linspace(0.0, 1.0, 201)
    return ResolutionError(
        N=state.N, N_check=M,
        centreline=float(np.max(np.abs(other.x0(sf) - state.x0(sf)))),
        measure1=abs(measure1(other) - measure1(state)),
        end_force=float(np.max(np.abs(other.F[0] - state.F[0]))),
        residual=other.residual_norm,
    )


@dataclass(frozen=True)
class Measures:
    """Solution measures of a relative equilibrium (dimensionless; lengths in units of L).

    measure1 = int_0^1 |x^0(s)| ds and measure2 = int_0^1 x^0 y^0 ds with x^0,
    y^0 the e1, e2 components of the centreline (captions of Figs.
    5 and 6); max_deflection =
    max_s sqrt(x^2 + y^2); end_shortening = x3(0) (the sliding end moves in by
    that much); F0, F1, M0, M1 the contact force and moment at s = 0 and s = 1
    (e-frame, units f EI1/L^2 and f EI1/L).
    """

    measure1: float
    measure2: float
    max_deflection: float
    end_shortening: float
    F0: tuple
    F1: tuple
    M0: tuple
    M1: tuple


def _cheb_coeffs(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients (on [0, 1] mapped to [-1, 1]) of the interpolant at Lobatto nodes."""
    N = values.shape[0] - 1
    # Lobatto nodes ascend: s_j = (1 - cos(pi j / N)) / 2, i.e. u_j = -cos(pi j/N) = cos(pi (N - j)/N)
    v = values[::-1]
    ext = np.concatenate([v, v[-2:0:-1]])
    c = np.real(np.fft.fft(ext)) / N
    c = c[: N + 1]
    c[0] /= 2
    c[N] /= 2
    return c


def measure1(state: Equilibrium) -> float:
    """int_0^1 |x^0(s)| ds (paper's measure_1), exact for the interpolant.

    The Chebyshev interpolant of x^0 is split at its real roots in [0, 1] and
    integrated piecewise with its antiderivative (|.| is not smooth, so plain
    quadrature would converge only algebraically).
    """
    from numpy.polynomial import chebyshev as C

    c = _cheb_coeffs(state.x[:, 0])
    scale = np.max(np.abs(c))
    if scale == 0.0:
        return 0.0
    ct = c.copy()
    ct[np.abs(ct) < 1e-15 * scale] = 0.0
    roots = C.chebroots(np.trim_zeros(ct, "b")) if np.any(ct[1:]) else np.array([])
    roots = roots[np.abs(roots.imag) < 1e-7].real
    u = np.unique(np.clip(np.concatenate([[-1.0, 1.0], roots]), -1.0, 1.0))
    anti = C.chebint(c)
    vals = C.chebval(u, anti)
    return float(0.5 * np.sum(np.abs(np.diff(vals))))


def measures(state: Equilibrium) -> Measures:
    """The :class:`Measures` of a state (dimensionless)."""
    # x*y has degree 2N: integrate it exactly on a finer grid
    n2 = 2 * state.N + 2
    s2 = collocation(n2).s
    xy = state.x0(s2)
    m2 = float(clenshaw_curtis_weights(n2) @ (xy[:, 0] * xy[:, 1]))
    sf = np.linspace(0.0, 1.0, 401)
    xs = state.x0(sf)
    defl = float(np.max(np.hypot(xs[:, 0], xs[:, 1])))
    return Measures(
        measure1=measure1(state),
        measure2=m2,
        max_deflection=max(defl, float(np.max(np.hypot(state.x[:, 0], state.x[:, 1])))),
        end_shortening=float(state.x[0, 2]),
        F0=tuple(state.F[0]), F1=tuple(state.F[-1]), M0=tuple(state.M[0]), M1=tuple(state.M[-1]),
    )
