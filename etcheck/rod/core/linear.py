"""The O(delta) linearisation about a whirling base state, discretised (dimensionless).

Continuous problem (Secs. V B and VI of arXiv:0810.3668, eqs. (71)-(75)
with (82)-(85); derived afresh from eqs. (37)-(41) rather than copied from
Appendix A, which has errata: docs/errata.md).
All perturbations are **e-frame** vectors (rotating frame, omega = omega e3):
x = x0 + delta xi e^{lambda t}, d_i = d_i0 + delta (a x d_i0) e^{lambda t},
F = F0 + delta phi e^{lambda t}, M = M0 + delta m e^{lambda t}::

    xi'  = a x d3_0                                                   (75)
    phi' = -B (a x d3_0) x e3 + lambda^2 xi + 2 lambda omega e3 x xi
           + omega^2 e3 x (e3 x xi)                                   (71)
    m'   = -(a x d3_0) x F0 - d3_0 x phi
           + sum_i c_i [ lambda^2 d_i0 x (a x d_i0)
                         + 2 lambda d_i0 x (omega e3 x (a x d_i0))
                         + (omega e3 . (a x d_i0)) (d_i0 x omega e3)
                         + (omega e3 . d_i0) ((a x d_i0) x omega e3) ]  (72)
    (1 + gamma lambda) D0 K D0^T a' = m + M0 x a            (73) + (74)

with c_1 = P R, c_2 = P, c_3 = 0 and K = diag(1, R, Gamma (1+R)/2) / f (body
stiffnesses; the perturbed body curvature is a' . d_j0 and the perturbed body
moment (m + M0 x a) . d_j0). The constitutive row is kept polynomial in
lambda (no division by 1 + gamma lambda). Boundary conditions
(eqs. (76)-(81), linearised (23)-(34)):

    s = 0:  xi . e1 = xi . e2 = 0,  phi . e3 = 0,
            (a x d3_0).e1 = (a x d3_0).e2 = (a x d1_0).e2 = 0   (a = 0 when D0(0) = I)
    s = 1:  xi = 0,  (a x d3_0).e1 = (a x d3_0).e2 = (a x d1_0).e2 = 0

Discretisation: rectangular Chebyshev collocation (Driscoll & Hale 2016).
The 12 unknown fields are sampled at the N+1 Lobatto points s_j of [0, 1];
the 12 ODE rows are imposed at the N first-kind points t_k (values resampled
there by the barycentric matrix P, derivatives by P D) and the 12 boundary
rows are appended, so the matrices are square of size 12 (N+1) and

    (A0 + lambda A1 + lambda^2 A2) Y = 0.

**Variable ordering** of Y (component-major, node-minor): the unknown
component c in ``VARIABLES`` at Lobatto node j sits at index c (N+1) + j,
where ``VARIABLES = (xi1, xi2, xi3, a1, a2, a3, phi1, phi2, phi3, m1, m2, m3)``
(e-frame components). **Row ordering**: ODE group e (same order: the rows
of xi', a', phi', m') at point t_k is row e N + k; rows 12 N ... 12 N + 11
are the boundary conditions in the order listed above.

The coefficient blocks are built once for a general base state by applying the
vector expressions above to the basis vectors (vectorised over the points);
nothing is specialised to the straight rod.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from etcheck.numerics.chebyshev import (
    diff_matrix,
    first_kind_nodes,
    lobatto_nodes,
    lobatto_weights,
    resample_matrix,
)
from etcheck.rod.core.base_state import BaseState, StraightBaseState
from etcheck.rod.core.ends import ALL_WELDED, Ends
from etcheck.rod.core.parameters import RodParameters
from etcheck.runtime.memory import matrix_bytes, require

__all__ = [
    "skew",
    "VARIABLES",
    "NFIELDS",
    "Collocation",
    "collocation",
    "stiffness_diag",
    "coefficient_blocks",
    "linear_operator",
    "static_operator",
    "field_slice",
    "boundary_rows",
    "end_rows",
]

VARIABLES = ("xi1", "xi2", "xi3", "a1", "a2", "a3", "phi1", "phi2", "phi3", "m1", "m2", "m3")
NFIELDS = 12
XI, ALPHA, PHI, MOM = slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 12)
_E3 = np.array([0.0, 0.0, 1.0])
_EYE = np.eye(3)


@dataclass(frozen=True)
class Collocation:
    """Grids and matrices of the rectangular collocation at resolution N."""

    N: int
    s: np.ndarray  # N+1 Lobatto points (unknowns)
    t: np.ndarray  # N first-kind points (ODE rows)
    D: np.ndarray  # (N+1, N+1) differentiation on s
    P: np.ndarray  # (N, N+1) resampling s -> t
    PD: np.ndarray  # (N, N+1) = P @ D


@lru_cache(maxsize=64)
def collocation(N: int) -> Collocation:
    """Rectangular collocation matrices for N (cached; treat as read-only)."""
    if N < 4:
        raise ValueError(f"N must be >= 4, got {N}")
    s = lobatto_nodes(N)
    w = lobatto_weights(N)
    t = first_kind_nodes(N)
    D = diff_matrix(s, w)
    P = resample_matrix(s, t, w)
    for arr in (s, t, D, P):
        arr.setflags(write=False)
    PD = P @ D
    PD.setflags(write=False)
    return Collocation(N=N, s=s, t=t, D=D, P=P, PD=PD)


def field_slice(name: str, N: int) -> slice:
    """Index range of the nodal values of the unknown ``name`` in Y."""
    c = VARIABLES.index(name)
    return slice(c * (N + 1), (c + 1) * (N + 1))


def stiffness_diag(params: RodParameters) -> np.ndarray:
    """Body stiffnesses K = (1, R, Gamma (1+R)/2) / f of eq. (41)."""
    return np.array([1.0, params.R, params.Gamma * (1.0 + params.R) / 2.0]) / params.f


def skew(v: np.ndarray) -> np.ndarray:
    """Matrices (..., 3, 3) of the cross products v x (.) for the rows of v (..., 3)."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def _moment_blocks(params: RodParameters, d: np.ndarray, F0: np.ndarray, W: np.ndarray):
    """The a-columns of the m' rows of eq. (72): static, gyroscopic (lambda) and inertia (lambda^2) parts.

    ``d`` (n, 3, 3) holds the directors as columns, ``F0`` (n, 3) the contact
    force, ``W`` (3, 3) the cross product with omega e3. With a x d_i =
    -[d_i]x a: -(a x d3) x F0 = -[F0]x [d3]x a; (w . (a x d_i)) (d_i x w) =
    (d_i x w)(d_i x w)^T a; (w . d_i)((a x d_i) x w) = (w . d_i) [w]x [d_i]x a;
    d_i x (w x (a x d_i)) = -[d_i]x [w]x [d_i]x a; d_i x (a x d_i) = -[d_i]x [d_i]x a.
    """
    c = np.array([params.P * params.R, params.P, 0.0])
    Sd = skew(np.moveaxis(d, 2, 1))  # (n, 3 directors, 3, 3): [d_i]x
    w = W[[2, 0, 1], [1, 2, 0]]  # the vector omega e3 back from its cross-product matrix
    dw = np.cross(np.moveaxis(d, 2, 1), w)  # (n, i, 3): d_i x w
    wd = np.einsum("nai,a->ni", d, w)  # w . d_i
    static = (-skew(F0) @ Sd[:, 2]
              + np.einsum("i,nia,nib->nab", c, dw, dw)
              + np.einsum("i,ni,ab,nibc->nac", c, wd, W, Sd))
    gyro = -2.0 * np.einsum("i,niab,bc,nicd->nad", c, Sd, W, Sd)
    inertia = -np.einsum("i,niab,nibc->nac", c, Sd, Sd)
    return static, gyro, inertia


def coefficient_blocks(params: RodParameters, base: BaseState, s: np.ndarray):
    """Pointwise coefficients of the first-order system E(lambda) y' = G(lambda) y.

    Returns ``(E0, E1, G0, G1, G2)``, each of shape (n, 12, 12) at the points s,
    with E(lambda) = E0 + lambda E1 and G(lambda) = G0 + lambda G1 +
    lambda^2 G2, rows/columns in ``VARIABLES`` order (dimensionless;
    eqs. (71), (72), (74), (75)). Every block is a product of cross-product
    matrices, evaluated for all points at once.
    """
    s = np.atleast_1d(np.asarray(s, dtype=float))
    n = s.size
    if n > 1 and isinstance(base, StraightBaseState):  # the same at every point: made at one, repeated
        return tuple(np.repeat(block, n, axis=0) for block in coefficient_blocks(params, base, s[:1]))
    D0 = base.D0(s)
    F0 = base.F0(s)
    M0 = base.M0(s)
    Sd3 = skew(D0[:, :, 2])
    W = skew(params.omega * _E3)
    E0, E1, G0, G1, G2 = (np.zeros((n, NFIELDS, NFIELDS)) for _ in range(5))
    for grp in (XI, PHI, MOM):
        E0[:, grp, grp] = _EYE

    G0[:, XI, ALPHA] = -Sd3  # xi' = a x d3_0                                   (75)
    # (1 + gamma lambda) D0 K D0^T a' = m + M0 x a                                (74)
    DKD = np.einsum("nai,i,nbi->nab", D0, stiffness_diag(params), D0)
    E0[:, ALPHA, ALPHA] = DKD
    E1[:, ALPHA, ALPHA] = params.gamma * DKD
    G0[:, ALPHA, MOM] = _EYE
    G0[:, ALPHA, ALPHA] = skew(M0)
    # phi' = -B (a x d3_0) x e3 + lambda^2 xi + 2 lambda w x xi + w x (w x xi)   (71)
    G0[:, PHI, ALPHA] = -params.B * skew(_E3) @ Sd3
    G2[:, PHI, XI] = _EYE
    G1[:, PHI, XI] = 2.0 * W
    G0[:, PHI, XI] = W @ W
    # m' = -(a x d3_0) x F0 - d3_0 x phi + sum_i c_i [...]                       (72)
    G0[:, MOM, ALPHA], G1[:, MOM, ALPHA], G2[:, MOM, ALPHA] = _moment_blocks(params, D0, F0, W)
    G0[:, MOM, PHI] = -Sd3
    return E0, E1, G0, G1, G2


def _assemble(E: np.ndarray | None, G: np.ndarray | None, col: Collocation) -> np.ndarray:
    """The 12 (N+1) square matrix whose rows e N + k, columns v (N+1) + j hold  E(t_k) (P D) - G(t_k) P,
    its last 12 rows (the boundary rows) zero.

    Only the (e, v) pairs where E or G is non-zero somewhere are written (most of the 144 are zero)."""
    N = col.N
    out = np.zeros((NFIELDS * (N + 1), NFIELDS * (N + 1)))
    ode = out[: NFIELDS * N].reshape(NFIELDS, N, NFIELDS, N + 1)  # a view
    nz = [np.any(C != 0.0, axis=0) if C is not None else np.zeros((NFIELDS, NFIELDS), dtype=bool) for C in (E, G)]
    e, v = np.nonzero(nz[0] | nz[1])
    if e.size:  # all pairs at once: (pairs, N) coefficients times the (N, N+1) matrices
        ce = E[:, e, v].T if E is not None else np.zeros((e.size, N))
        cg = G[:, e, v].T if G is not None else np.zeros((e.size, N))
        ode[e, :, v, :] = ce[:, :, None] * col.PD - cg[:, :, None] * col.P
    return out


def boundary_rows(base: BaseState, N: int, ends: Ends = ALL_WELDED) -> np.ndarray:
    """The 12 linearised boundary conditions: welded (eqs. (76)-(81)), pinned or swivel ends
    (:mod:`etcheck.rod.core.ends`)."""
    at = np.array([0.0, 1.0])
    moments = any(end.free_moments for end in ends.conditions)
    return end_rows(base.D0(at), N, ends, base.M0(at) if moments else None)


def end_rows(D: np.ndarray, N: int, ends: Ends = ALL_WELDED, M: np.ndarray | None = None) -> np.ndarray:
    """:func:`boundary_rows` from the base state's frames at the two ends, ``D`` (2, 3, 3), column i = d_i, and its
    contact moments there, ``M`` (2, 3) (needed only for an end that passes no moment about some axis).

    Position rows at both ends (s = 0: xi . e1 = xi . e2 = 0 and the end force phi . e3 = 0; s = 1: xi = 0), then
    three rows per end on (a, m), each end's :meth:`~etcheck.rod.core.ends.EndCondition.collocation_rows`: welded,
    the end rotations (a x d3) . e1 = (a x d3) . e2 = (a x d1) . e2 = 0 (eqs. (76)-(81)); pinned, no perturbed
    bending moment (m + M0 x a) . d1 = (m + M0 x a) . d2 = 0 (the linearised M . d_j = 0) and the twist
    (a x d1) . e2 = 0; swivel, no perturbed moment about any d_j."""
    rows = np.zeros((12, NFIELDS, N + 1))
    # s = 0: xi1 = xi2 = 0, phi3 = 0; s = 1: xi = 0
    rows[0, 0, 0] = rows[1, 1, 0] = rows[2, 8, 0] = 1.0
    rows[[6, 7, 8], [0, 1, 2], N] = 1.0
    # at each end: (a x d3).e1 = a.(d3 x e1), (a x d3).e2 = a.(d3 x e2), (a x d1).e2 = a.(d1 x e2)
    d1, d3 = D[:, :, 0], D[:, :, 2]
    zero = np.zeros(2)
    g = np.stack([np.stack([zero, d3[:, 2], -d3[:, 1]], axis=1),  # d3 x e1
                  np.stack([-d3[:, 2], zero, d3[:, 0]], axis=1),  # d3 x e2
                  np.stack([-d1[:, 2], zero, d1[:, 0]], axis=1)], axis=1)  # d1 x e2; (end, row, component)
    for end, (first, node) in enumerate(((3, 0), (9, N))):
        block = ends.conditions[end].collocation_rows(g[end], D[end], None if M is None else M[end])
        rows[first:first + 3, 3:6, node] = block[:, :3]
        rows[first:first + 3, 9:12, node] = block[:, 3:]
    return rows.reshape(12, NFIELDS * (N + 1))


def linear_operator(params: RodParameters, base: BaseState, N: int):
    """Discretised linearisation ``(A0, A1, A2)``, each of shape (12(N+1), 12(N+1)).

    A(lambda) = A0 + lambda A1 + lambda^2 A2 is the rectangular Chebyshev
    collocation (N+1 Lobatto points, ODE rows at N first-kind points, 12
    boundary rows appended) of the dimensionless O(delta) problem
    eqs. (71)-(75) with the boundary conditions (76)-(81) about ``base``; see the
    module docstring for the variable and row ordering. A1 vanishes unless
    omega != 0 or gamma != 0; the boundary rows are all in A0.
    """
    require(f"the linearised operator at N = {int(N)}", matrix_bytes(NFIELDS * (int(N) + 1), count=3))
    col = collocation(int(N))
    E0, E1, G0, G1, G2 = coefficient_blocks(params, base, col.t)
    A0 = _assemble(E0, G0, col)
    A0[NFIELDS * col.N:] = boundary_rows(base, col.N, params.ends)
    return A0, _assemble(E1, G1, col), _assemble(None, G2, col)



def static_operator(params: RodParameters, base: BaseState, N: int) -> np.ndarray:
    """A0 of :func:`linear_operator` alone (lambda = 0: the stiffness with the boundary rows), one assembly."""
    col = collocation(int(N))
    E0, _, G0, _, _ = coefficient_blocks(params, base, col.t)
    A0 = _assemble(E0, G0, col)
    A0[NFIELDS * col.N:] = boundary_rows(base, col.N, params.ends)
    return A0


def static_differences(ref: RodParameters, ref_base: BaseState, others, N: int) -> tuple[np.ndarray, list]:
    """``static_operator(ref, ref_base, N)`` and, for each (params, base) of ``others``,
    ``static_operator(params, base, N)`` minus it, assembled from the difference of the coefficients (A0 is linear
    in them): only the entries that differ are written, without cancellation; the reference's coefficients are
    made once."""
    col = collocation(int(N))
    E0r, _, G0r, _, _ = coefficient_blocks(ref, ref_base, col.t)
    rows = NFIELDS * col.N
    bc = boundary_rows(ref_base, col.N, ref.ends)
    A0 = _assemble(E0r, G0r, col)
    A0[rows:] = bc
    out = []
    for params, base in others:
        E0, _, G0, _, _ = coefficient_blocks(params, base, col.t)
        D = _assemble(E0 - E0r, G0 - G0r, col)
        D[rows:] = boundary_rows(base, col.N, params.ends) - bc
        out.append(D)
    return A0, out
