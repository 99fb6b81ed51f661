"""The static-point curves of the straight rod in the (B, omega) plane, and the damped stability map they cut.

Dimensionless (scalings of eq. (36) of arXiv:0810.3668). At lambda = 0 the
linearisation about the straight rod (eqs. (71)-(75), (86)) is

    A0(B, omega) = K + B U_B V_B^T + omega^2 U_w V_w^T        (T fixed),

where K is the operator at B = omega = 0 and the load and centrifugal terms
touch only 2N rows (phi' rows of eq. (71), load) and 4N rows (phi' and m'
rows of eqs. (71)-(72), spin): U selects those rows and V^T holds them. With
one LU of K per family the whole plane reduces to the small matrix
W = V^T K^-1 U (6N x 6N): A0 is singular exactly where I + W D is, with
D = diag(B I, omega^2 I). So

* the load roots at a spin omega are B = -1/mu for the eigenvalues mu of the
  2N x 2N Schur complement S_B(omega) = W_BB - omega^2 W_Bw (I + omega^2 W_ww)^-1 W_wB;
* the spin roots at a load B are omega^2 = -1/nu for the eigenvalues nu of
  the 4N x 4N S_w(B) = W_ww - B W_wB (I + B W_BB)^-1 W_Bw;

the same values as the static pencils of :class:`etcheck.rod.straight.collocation.spectral.StraightFamily`
(one pencil of the 6(N+1) reduced operator each), at a fraction of the cost. (The
Schur complements need the other block regular: a row exactly at a spin root
of the unloaded rod, or a column exactly at a static load of the rod at rest,
is ill-conditioned; the grids of a check do not fall on them but by chance.)

**Crossing directions (damped rod).** Where A0 is singular a real eigenvalue
of A0 + lambda A1 + lambda^2 A2 passes through lambda = 0 with speed
lambda' = -(u^T dA0 v) / (u^T A1 v) (u, v the left and right null vectors),
so the number of eigenvalues with Re lambda > 0 changes there by +1
(lambda' > 0) or -1; with damping gamma > 0 this number changes nowhere else
(Kelvin-Tait-Chetaev, docs/model.md, section 8). Both products live in the
small space: u^T dA0 v = c^T W E e and u^T A1 v = -c^T H D e with c, e the
left and right null vectors of I + W D, E the block of the moving parameter and
H = V^T K^-1 A1 K^-1 U. A cluster of m coincident roots (the double load roots
at omega = 0, and every static point of an isotropic rod, R = 1, where round-off
splits them by about sqrt(eps): :data:`DOUBLE`) gives m speeds from the m x m
version of the same ratio; with spin they can be a complex pair, and each
eigenvalue crosses to the side of the sign of Re(speed). Counting
from the unloaded rod at rest (stable for T >= 0) gives the number of unstable
eigenvalues of every piece of every row without an eigenvalue solve; a piece
whose count cannot be told (a zero speed, T < 0) is classified by one growth
evaluation instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.spectral import (
    DOUBLE,
    K_MODES,
    THRESHOLD,
    StraightFamily,
    family_bytes,
    nearly_isotropic,
    straight_family,
)
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import Memo
from etcheck.runtime.parallel import split_map

__all__ = ["StaticPlane", "StaticCurves", "plane", "static_curves", "stable_rows"]

#: Roots closer than this (relative) are one multiple root.
CLUSTER = 1e-9
#: A crossing speed below this (relative to its parts) cannot be told from zero.
SPEED_FLOOR = 1e-10
#: Loads about which A0 is expanded, tried in turn until it is regular there (0: the unloaded rod).
BASE_LOADS = (0.0, 0.01234567, -0.02345678)


def _rows(A: np.ndarray) -> np.ndarray:
    return np.nonzero(np.any(A != 0.0, axis=1))[0]


class StaticPlane:
    """The static operator A0(B, omega) of one family at tension T, reduced to W = V^T K^-1 U.

    K = A0(B0, 0) with B0 the first of ``BASE_LOADS`` where it is regular
    (0 unless T sits on a compressive root); loads enter as offsets B - B0.
    """

    def __init__(self, fam: StraightFamily, T: float):
        self.fam, self.T = fam, float(T)
        self.cluster = DOUBLE if nearly_isotropic(fam.params.R) else CLUSTER
        rB, rw = _rows(fam.AB), _rows(fam.Aw)
        self.nB = rB.size
        rows = np.concatenate([rB, rw])
        Vt = np.vstack([fam.AB[rB], fam.Aw[rw]])  # V^T: the rows the parameters touch
        for self.B0 in BASE_LOADS:  # the expansion point: the unloaded rod unless A0 is singular there
            K = fam.A00 + self.T * fam.AT + self.B0 * fam.AB
            lu = sla.lu_factor(K, check_finite=False)
            pivots = np.abs(np.diag(lu[0]))
            if np.min(pivots) > 1e-12 * np.max(pivots):
                break
        n = K.shape[0]
        U = np.zeros((n, rows.size))
        U[rows, np.arange(rows.size)] = 1.0
        X = sla.lu_solve(lu, U, check_finite=False)  # K^-1 U
        Y = sla.lu_solve(lu, Vt.T, trans=1, check_finite=False)  # K^-T V
        self.W = Vt @ X
        self.H0 = Y.T @ (fam.A10 @ X)
        self.H1 = Y.T @ (fam.A1w @ X)

    def _blocks(self, axis: str):
        a = slice(0, self.nB) if axis == "B" else slice(self.nB, None)
        o = slice(self.nB, None) if axis == "B" else slice(0, self.nB)
        return a, o

    def roots(self, axis: str, other: float) -> tuple[np.ndarray, tuple]:
        """Real roots on ``axis`` ("B": loads at spin^2 = ``other``; "w": spins^2 at load B = ``other``).

        Returns the sorted real roots (B or omega^2) and the Schur complement
        data that :meth:`changes` needs. One LU of the other block and one
        eigenvalue solve of S (2N x 2N for loads, 4N x 4N for spins).
        """
        a, o = self._blocks(axis)
        W = self.W
        if axis == "w":
            other = other - self.B0
        G = sla.lu_factor(np.eye(W[o, o].shape[0]) + other * W[o, o], check_finite=False)
        C = sla.lu_solve(G, W[o, a], check_finite=False)
        S = W[a, a] - other * (W[a, o] @ C)
        mu = sla.eigvals(S, check_finite=False)
        mu = mu[np.abs(mu) > 1e-14 * max(np.max(np.abs(mu), initial=0.0), 1e-300)]
        x = -1.0 / mu
        x = np.sort(x[np.abs(x.imag) <= max(self.cluster, 1e-8) * np.abs(x)].real)
        return x + (self.B0 if axis == "B" else 0.0), (axis, other, G, C, S)

    def changes(self, roots: np.ndarray, data: tuple, omega: float) -> np.ndarray:
        """Change of the number of unstable eigenvalues across each root (crossing directions, see module docstring).

        ``roots`` ascending (a subset of those from :meth:`roots` with the
        same ``data``); a cluster of coincident roots carries its whole change
        on its first member and 0 on the others; NaN where the change cannot
        be told (a zero or complex speed). A1 = A10 + omega A1w.
        """
        H = self.H0 + omega * self.H1
        offsets = roots - self.B0 if data[0] == "B" else roots
        out = np.zeros(roots.size)
        i = 0
        while i < roots.size:
            j = i + 1
            while j < roots.size and roots[j] - roots[i] <= self.cluster * max(abs(roots[i]), 1.0):
                j += 1
            out[i] = self._change(offsets[i], j - i, data, H)
            i = j
        return out

    def _change(self, x: float, m: int, data: tuple, H: np.ndarray) -> float:
        axis, other, G, C, S = data
        a, o = self._blocks(axis)
        # null vectors of S + I / x: one step of inverse iteration from m fixed vectors (the
        # shift is the root itself to round-off, so the step amplifies them ~1e12 against the rest)
        lu = sla.lu_factor(S + ((1.0 + 1e-12) / x) * np.eye(S.shape[0]), check_finite=False)
        start = np.cos(np.arange(S.shape[0] * m).reshape(S.shape[0], m))
        P = sla.lu_solve(lu, start, check_finite=False)
        Z = sla.lu_solve(lu, start, trans=1, check_finite=False)
        if m > 1:
            P, Z = np.linalg.qr(P)[0], np.linalg.qr(Z)[0]
        n = self.W.shape[0]
        E, Ea, Cl = np.zeros((n, m)), np.zeros((n, m)), np.zeros((n, m))
        E[a] = Ea[a] = P  # right null vectors e of I + W D, and their moving block
        E[o] = -x * (C @ P)
        Cl[a] = Z  # left null vectors c: c^T (I + W D) = 0
        Cl[o] = -other * sla.lu_solve(G, self.W[a, o].T @ Z, trans=1, check_finite=False)
        E[a] *= x
        E[o] *= other
        num = Cl.T @ (self.W @ Ea)  # u^T dA0 v
        den = Cl.T @ (H @ E)  # -u^T A1 v (E now holds D e)
        speed = np.atleast_1d(sla.eigvals(num, den, check_finite=False) if m > 1 else num[0, 0] / den[0, 0])
        scale = np.linalg.norm(num) / max(np.linalg.norm(den), 1e-300)
        # eigenvalues leave lambda = 0 as lambda = -dx / speed: Re lambda has the sign of Re(speed) (dx > 0). At
        # a multiple root (R = 1) the Coriolis coupling inside the null space can make the speeds a complex pair.
        if (not np.all(np.isfinite(speed)) or np.any(np.abs(speed) <= SPEED_FLOOR * scale)
                or np.any(np.abs(speed.real) <= 1e-6 * np.abs(speed))
                or (m == 1 and abs(speed[0].imag) > 1e-6 * abs(speed[0]))):
            return math.nan
        return float(np.sum(np.sign(speed.real)))


def _plane_of(params: RodParameters, N: int, T: float) -> StaticPlane:
    return StaticPlane(straight_family(params, N), T)


#: the planes most recently asked for, within a share of the memory budget; each holds its family
_plane = Memo(_plane_of, lambda params, N, T: family_bytes(N, peak=False))


def plane(params: RodParameters, N: int) -> StaticPlane:
    """The static plane of the family of ``params`` at its tension (memoised)."""
    return _plane(params.with_(B=0.0, omega=0.0, T=0.0), int(N), float(params.T))


@dataclass(frozen=True)
class StaticCurves:
    """Static points of the straight rod in the box [0, B_max] x [0, omega_max] (dimensionless).

    ``omega``: the spins of the rows; ``loads[i]``: the load roots in
    [0, B_max] at omega[i], ascending; ``changes[i]``: the change of the
    number of unstable eigenvalues across each of them (damped rod only,
    else None; see :meth:`StaticPlane.changes`); ``B``, ``omega_points``:
    every static point found (the rows' load roots and the spin roots at
    ``n_loads`` loads), exact at resolution ``N``.
    """

    omega: np.ndarray
    loads: tuple
    changes: tuple | None
    B: np.ndarray
    omega_points: np.ndarray
    N: int


@single_blas_thread
def static_curves(params: RodParameters, B_max: float, omega_max: float, omega_rows=None, n_loads: int = 60,
                  N: int = 24) -> StaticCurves:
    """The set det A0(B, omega) = 0 in the box, sampled along spin rows and load columns.

    T, P, R, Gamma, f from ``params`` (gamma plays no part at lambda = 0).
    The load roots at each spin of ``omega_rows`` (default 60 spins evenly in
    [0, omega_max]) and the spin roots at ``n_loads`` loads evenly in
    [0, B_max], so curves are sampled in both directions. With damping these
    curves are the whole stability boundary of the straight rod
    (Kelvin-Tait-Chetaev); :func:`stable_rows` cuts the rows at them, with
    the crossing directions computed here (damped rod only).
    """
    pl = plane(params, N)
    rows = np.linspace(0.0, omega_max, 60) if omega_rows is None else np.asarray(omega_rows, dtype=float)
    columns = np.linspace(0.0, B_max, n_loads)

    def row(w: float):
        r, data = pl.roots("B", w * w)
        r = r[(r >= 0) & (r <= B_max)]
        return r, pl.changes(r, data, w) if params.gamma > 0 else None

    def column(b: float):
        r = pl.roots("w", b)[0]
        return np.sqrt(r[(r >= 0) & (r <= omega_max**2)])

    # every row and column is independent: on two cores
    out = split_map(lambda job: row(job[1]) if job[0] == "row" else column(job[1]),
                    [("row", w) for w in rows] + [("column", b) for b in columns], min_items=8)
    loads = [r for r, _ in out[:rows.size]]
    Bs = [np.concatenate(loads)] if loads else []
    ws = [np.repeat(rows, [x.size for x in loads])]
    for b, r in zip(columns, out[rows.size:]):
        Bs.append(np.full(r.size, b))
        ws.append(r)
    return StaticCurves(rows, tuple(loads), tuple(c for _, c in out[:rows.size]) if params.gamma > 0 else None,
                        np.concatenate(Bs), np.concatenate(ws), int(N))


def _rest_crossings(params: RodParameters, pl: StaticPlane) -> tuple[np.ndarray, np.ndarray]:
    """Spin roots omega^2 > 0 of the unloaded rod and the change of its unstable count across each.

    The count of the unloaded rod at rest is 0 for T >= 0; with compression
    it is not counted here (NaN changes: the rows fall back to growth
    evaluations).
    """
    roots, data = pl.roots("w", 0.0)
    roots = roots[roots > 0]
    if params.T < 0:
        return roots, np.full(roots.size, math.nan)
    steps = np.zeros(roots.size)
    i = 0
    while i < roots.size:  # A1 is taken at each cluster's own spin (its gyroscopic part depends on it)
        j = i + 1
        while j < roots.size and roots[j] - roots[i] <= pl.cluster * max(roots[i], 1.0):
            j += 1
        steps[i:j] = pl.changes(roots[i:j], data, math.sqrt(roots[i]))
        i = j
    return roots, steps


@single_blas_thread
def stable_rows(params: RodParameters, curves: StaticCurves, B_max: float, k: int = K_MODES) -> list:
    """Stable intervals of B in [0, B_max] at each spin row of ``curves`` (damped rod).

    Dimensionless. With damping gamma > 0 stability changes only where the
    static operator is singular (Kelvin-Tait-Chetaev): each row is cut at its
    exact load roots and the number of unstable eigenvalues is counted across
    them by their crossing directions (:meth:`StaticPlane.changes`), from the
    unloaded rod at the row's spin; the boundaries are exact, not
    grid-limited, and no eigenvalue is solved. A piece whose count cannot be
    told is classified by one growth evaluation (k least-|lambda| pairs).
    Returns one list of (start, end) per spin.
    """
    if params.gamma <= 0 or curves.changes is None:
        raise ValueError("stable_rows needs damping gamma > 0 (undamped rods can flutter between static points)")
    pl = plane(params, curves.N)
    rest, rest_steps = _rest_crossings(params, pl)
    rows = []
    for w, roots, steps in zip(curves.omega, curves.loads, curves.changes):
        count = float(np.sum(rest_steps[rest < w * w]))
        edges = [0.0, *roots[roots > 0].tolist(), float(B_max)]
        steps = steps[roots > 0]
        stable: list = []
        for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
            if i > 0:
                count += steps[i - 1]
            if b <= a:
                continue
            unstable = (count > 0 if count >= 0 else  # NaN (or an inconsistent negative count): not told
                        pl.fam.growth(0.5 * (a + b), w, params.T, k=k) > THRESHOLD)
            if unstable:
                continue
            if stable and stable[-1][1] == a:
                stable[-1] = (stable[-1][0], b)
            else:
                stable.append((a, b))
        rows.append(stable)
    return rows
