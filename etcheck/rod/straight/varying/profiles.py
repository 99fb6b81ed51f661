"""Rung 1v: the straight tether with a current and a tension that vary along it, discretised by
graded multi-domain Chebyshev collocation (dimensionless).

About the straight tether x = s e3 (paper Sec. 6.1, eq. (86) with F = +T(s) e3; docs/model.md,
section 10) in the rotating frame of the f-scaling (eq. (36)), u along the weak axis e1, v along e2,
normal modes exp(lambda t):

    lambda^2 (u - P R u'') + lambda (gamma (R/f) u'''' - 2 omega v)
        + (R/f) u'''' - (T(s) u')' - P R omega^2 u'' - omega^2 u - B b(s) v' = 0
    lambda^2 (v - P v'') + lambda (gamma (1/f) v'''' + 2 omega u)
        + (1/f) v'''' - (T(s) v')' - P omega^2 v'' - omega^2 v + B b(s) u' = 0

with T(s) = T tau(s) and the magnetic load B b(s) (b = I(s)/I_max), each end welded
(u = u' = v = v' = 0) or pinned or on a swivel (u = u'' = v = v'' = 0; :mod:`etcheck.rod.core.ends`). For b and tau constant this is the
constant-coefficient system of :mod:`etcheck.rod.straight.exact.determinant`. With b not constant the
load has no potential (circulatory, docs/model.md section 10): the operator is not self-adjoint even
without spin or damping, and stability is lost by flutter as well as by divergence.

**Why graded multi-domain collocation.** Under tension the bending stiffness acts only in end
layers of width sqrt(R / (f T)) (1e-5 of the length for a tape, 3e-10 at R = 1e-7 and f T = 1e12),
which a Chebyshev grid on the whole length cannot resolve (its finest spacing is 1/N^2). Here each
end carries a geometric sequence of thin subdomains, the first a few layer widths wide and each
the next :data:`GRADING` times wider, up to a tenth of the length; the middle is one subdomain per
piece of the profiles (their kinks are subdomain edges, so a piecewise-linear current keeps
spectral accuracy). The unknowns are u, v at the Chebyshev-Lobatto points of every subdomain; the
equations are collocated at its first-kind points (rectangular collocation, Driscoll & Hale 2016:
no spurious eigenvalues from replaced rows), and u, u', u'', u''' and the same of v are continuous
at every interface (the coefficients are continuous). Rows are scaled per subdomain, so no entry
carries the powers of the layer width. The operator is sparse (blocks per subdomain): the
eigenvalues nearest a shift come from a sparse LU and ARPACK, in milliseconds, where a Riccati or
compound-matrix shooting would give one determinant value per (lambda, B) and need a root search
in the complex plane for every eigenvalue. The resolution is checked by a second, finer mesh
(:func:`check_resolution`); an independent discretisation (Hermite finite elements on a graded
mesh, in the tests) agrees with it.

Every operator is affine in (B, T, omega^2) at lambda = 0 and the lambda-terms in omega: a family
is assembled once per mesh and recombined per point.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from etcheck.numerics.chebyshev import diff_matrix, first_kind_nodes, lobatto_nodes, lobatto_weights, resample_matrix
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.profile import Profile

__all__ = [
    "GRADING",
    "Mesh",
    "Tether",
    "TetherFamily",
    "check_resolution",
    "family",
    "layer_widths",
    "mesh",
]

#: Ratio of the widths of successive end subdomains.
GRADING = 4.0
#: The first end subdomain is this many (thinnest) layer widths wide.
FIRST = 2.0
#: End subdomains are made up to this fraction of the length; past it the middle subdomains start.
GRADED_TO = 0.1
#: Layers wider than this fraction of the length need no grading.
WIDE = 0.05


UNIFORM = Profile.uniform()


@dataclass(frozen=True)
class Tether:
    """The straight tether with profiles (dimensionless): ``params`` as for the uniform rod (its ends included:
    :mod:`etcheck.rod.core.ends`), with the magnetic load B b(s) and the tension T tau(s) (``current`` = b,
    ``tension`` = tau). b = tau = 1 is the rod of :mod:`etcheck.rod.straight.exact.roots`."""

    params: RodParameters
    current: Profile = UNIFORM
    tension: Profile = UNIFORM

    @property
    def uniform(self) -> bool:
        return self.current.uniform_value == 1.0 and self.tension.uniform_value == 1.0

    @property
    def circulatory(self) -> bool:
        """Whether the load has no potential (b not constant): docs/model.md, section 10."""
        return self.current.uniform_value is None

    def with_(self, **changes) -> Tether:
        return Tether(self.params.with_(**changes), self.current, self.tension)


# --- the mesh ------------------------------------------------------------------------------------


def layer_widths(tether: Tether) -> tuple[float, float]:
    """The thinnest boundary-layer width at s = 0 and at s = 1 (fraction of the length): the inverse of the
    largest real part of the exponents k of the frozen-coefficient problem there at lambda = 0, the roots of
    (R/f^2) k^8 - ((R b + a)/f) k^6 + (a b - omega^2 (1 + R)/f) k^4 + (omega^2 (a + b) + B^2) k^2 + omega^4
    (a = T + P R omega^2, b = T + P omega^2 with the local tension and load); inf where no exponent has a
    real part above 1."""
    p = tether.params
    w2 = p.omega**2
    out = []
    for s in (0.0, 1.0):
        T = p.T * float(tether.tension(np.array([s]))[0])
        B = p.B * float(tether.current(np.array([s]))[0])
        a, b = T + p.P * p.R * w2, T + p.P * w2
        k2 = np.roots([p.R / p.f**2, -(p.R * b + a) / p.f, a * b - w2 * (p.R + 1) / p.f, w2 * (a + b) + B**2, w2**2])
        k = float(np.max(np.sqrt(k2.astype(complex)).real, initial=0.0))
        out.append(1.0 / k if k > 1.0 else math.inf)
    return out[0], out[1]


@dataclass(frozen=True)
class Mesh:
    """Subdomains [edges[i], edges[i + 1]] with Chebyshev degree degrees[i]."""

    edges: tuple[float, ...]
    degrees: tuple[int, ...]

    @property
    def size(self) -> int:
        """Collocation points per field (u, v, or a moment)."""
        return sum(n + 1 for n in self.degrees)


def _graded(width: float) -> list[float]:
    """Distances from an end of the edges of its graded subdomains (empty for wide layers)."""
    if not width < WIDE:
        return []
    out, d = [], FIRST * width
    while d < GRADED_TO:
        out.append(d)
        d *= GRADING
    return out + [GRADED_TO] if out and GRADED_TO - out[-1] > 0.25 * out[-1] else out


def mesh(tether: Tether, N: int, N_end: int | None = None) -> Mesh:
    """The collocation mesh at middle resolution N: graded end subdomains of degree N_end (default
    max(12, N // 2)) from the layer widths, then one middle subdomain per profile piece, of degree
    N times its share of the middle (at least 12)."""
    N_end = N_end or max(12, N // 2)
    w0, w1 = layer_widths(tether)
    left, right = _graded(w0), _graded(w1)
    lo = left[-1] if left else 0.0
    hi = 1.0 - right[-1] if right else 1.0
    kinks = set(tether.current.breaks[1:-1]) | set(tether.tension.breaks[1:-1])
    edges = sorted({0.0, 1.0, *left, *(1.0 - x for x in right), *kinks})
    degrees = []
    for a, b in zip(edges[:-1], edges[1:]):
        middle = a >= lo and b <= hi
        degrees.append(max(12, round(N * (b - a) / (hi - lo))) if middle else N_end)
    return Mesh(tuple(edges), tuple(degrees))


def check_resolution(N: int) -> int:
    """The middle resolution of the mesh that checks resolution N."""
    return N + max(8, N // 2)


# --- the operator --------------------------------------------------------------------------------


@lru_cache(maxsize=64)
def _reference(n: int):
    """On [0, 1] at degree n: the derivative matrices D^k (k = 0, 1, 2) at the Lobatto points and their rows at
    the n - 1 first-kind points (P D^k), and those points."""
    x = lobatto_nodes(n)
    w = lobatto_weights(n)
    D = diff_matrix(x, w)
    Dk = (np.eye(n + 1), D, D @ D)
    y = first_kind_nodes(n - 1)
    P = resample_matrix(x, y, w)
    return y, Dk, tuple(P @ d for d in Dk)


_BLOCKS = ("K0", "KB", "KT", "Kw", "C0", "Cw", "M")
#: The unknowns of a subdomain, in order: u, v and their bending moments m = (R/f) u'', n = (1/f) v''.
_FIELDS = 4


@dataclass
class _Builder:
    n: int
    rows: dict = field(default_factory=lambda: {k: ([], [], []) for k in _BLOCKS})

    def add(self, block: str, rows, cols: np.ndarray, vals: np.ndarray) -> None:
        """vals (len(rows), len(cols)) into the rows and columns given (one row: a scalar and a vector)."""
        vals = np.atleast_2d(np.asarray(vals, dtype=float))
        rows = np.atleast_1d(rows)
        r, c = np.nonzero(vals)
        R, C, V = self.rows[block]
        R.append(rows[r])
        C.append(np.asarray(cols)[c])
        V.append(vals[r, c])

    def matrix(self, block: str) -> sp.csc_matrix:
        R, C, V = self.rows[block]
        if not R:
            return sp.csc_matrix((self.n, self.n))
        return sp.csc_matrix((np.concatenate(V), (np.concatenate(R), np.concatenate(C))), shape=(self.n, self.n))


def _equation_rows(bld: _Builder, row: int, cols: tuple, s: np.ndarray, h: float, PDk, tether: Tether) -> int:
    """The balance and moment equations of u and of v collocated at the first-kind points s of one subdomain
    (width h; ``cols``: the columns of its u, v, m, n values), each row scaled by its largest coefficient:

        lambda^2 (u - P R u'') + lambda (gamma m'' - 2 omega v) + m'' - (T u')' - P R omega^2 u'' - omega^2 u
            - B b v' = 0,      (R/f) u'' - m = 0,

    and the same for v with 1/f, P, +2 omega u, +B b u' and n."""
    p = tether.params
    cu, cv, cm, cn = cols
    d0, d1, d2 = (PDk[k] / h**k for k in range(3))
    tau, dtau = tether.tension(s)[:, None], tether.tension.derivative(s)[:, None]
    b = tether.current(s)[:, None]
    k = s.size
    scale = 1.0 / (np.abs(p.T * tau) / h**2 + np.abs(p.B * b) / h + 1.0)
    for own, other, moment, c4, pc, sign in ((cu, cv, cm, p.R / p.f, p.P * p.R, 1.0),
                                             (cv, cu, cn, 1.0 / p.f, p.P, -1.0)):
        balance, law = row + np.arange(k), row + k + np.arange(k)
        bld.add("K0", balance, moment, scale * d2)
        bld.add("KT", balance, own, -scale * (tau * d2 + dtau * d1))
        bld.add("KB", balance, other, -sign * scale * b * d1)
        bld.add("Kw", balance, own, -scale * (pc * d2 + d0))
        bld.add("C0", balance, moment, scale * d2)  # times gamma in the operator
        bld.add("Cw", balance, other, -sign * 2.0 * scale * d0)
        bld.add("M", balance, own, scale * (d0 - pc * d2))
        c = 1.0 / max(c4 / h**2, 1.0)
        bld.add("K0", law, np.concatenate([own, moment]), np.hstack([c * c4 * d2, -c * d0]))
        row += 2 * k
    return row


def _columns(start: int, m: int) -> tuple[np.ndarray, ...]:
    """Columns of the u, v, m, n values of a subdomain of degree m whose unknowns start at ``start``."""
    base = start + np.arange(m + 1)
    return tuple(base + k * (m + 1) for k in range(_FIELDS))


def _assemble(tether: Tether, grid: Mesh) -> dict[str, sp.csc_matrix]:
    """The blocks of the operator on the mesh: A0 = K0 + B KB + T KT + omega^2 Kw, A1 = gamma C0 + omega Cw,
    A2 = M. Rows: the equations of each subdomain, the boundary rows of each end (u and u' welded, u and m pinned
    or on a swivel: torsion, which holds the difference, decouples; the same of v) and the interface rows (u, u', m, m' and v, v', n, n' continuous), each scaled to
    derivatives in units of the thinner neighbour."""
    n = _FIELDS * grid.size
    bld = _Builder(n)
    starts = np.cumsum([0] + [_FIELDS * (m + 1) for m in grid.degrees])
    row = 0
    for j, (a, b, m) in enumerate(zip(grid.edges[:-1], grid.edges[1:], grid.degrees)):
        y, _, PDk = _reference(m)
        row = _equation_rows(bld, row, _columns(starts[j], m), a + (b - a) * y, b - a, PDk, tether)
    for end, side in zip(tether.params.ends.conditions, (0, 1)):
        at = 0 if side == 0 else len(grid.degrees) - 1
        m = grid.degrees[at]
        _, Dk, _ = _reference(m)
        point = 0 if side == 0 else m
        cu, cv, cm, cn = _columns(starts[at], m)
        for disp, moment in ((cu, cm), (cv, cn)):
            for k in (0, end.bending_order):  # u, then h u' (welded) or the moment, zero with u'' (pinned, swivel)
                bld.add("K0", row, disp if k < 2 else moment, Dk[k if k < 2 else 0][point])
                row += 1
    for j in range(len(grid.degrees) - 1):
        ml, mr = grid.degrees[j], grid.degrees[j + 1]
        hl = grid.edges[j + 1] - grid.edges[j]
        hr = grid.edges[j + 2] - grid.edges[j + 1]
        hs = min(hl, hr)
        _, Dl, _ = _reference(ml)
        _, Dr, _ = _reference(mr)
        for cl, cr in zip(_columns(starts[j], ml), _columns(starts[j + 1], mr)):
            for k in range(2):
                bld.add("K0", row, np.concatenate([cl, cr]),
                        np.concatenate([Dl[k][ml] * (hs / hl) ** k, -Dr[k][0] * (hs / hr) ** k]))
                row += 1
    if row != n:
        raise AssertionError(f"{row} rows for {n} unknowns")
    return {k: bld.matrix(k) for k in _BLOCKS}


class TetherFamily:
    """The operator of a tether on one mesh as exact polynomials in (B, T, omega, gamma): assembled once,
    recombined per point (P, R, f, the profiles and the ends fixed; the damping is ``tether.params.gamma``)."""

    def __init__(self, tether: Tether, grid: Mesh, blocks: dict[str, sp.csc_matrix]):
        self.tether = tether
        self.mesh = grid
        self.blocks = blocks

    def operator(self, B: float, omega: float, T: float, damped: bool = True):
        """(A0, A1, A2) at the given load, spin and tension (sparse; ``damped=False``: without the Kelvin-Voigt
        term)."""
        k = self.blocks
        gamma = self.tether.params.gamma if damped else 0.0
        A0 = k["K0"] + B * k["KB"] + T * k["KT"] + omega**2 * k["Kw"]
        A1 = gamma * k["C0"] + omega * k["Cw"]
        return A0.tocsc(), A1.tocsc(), k["M"]

    def static(self, axis: str, B: float, omega: float, T: float):
        """(A, N): the operator at lambda = 0 is A + x N along ``axis`` (x = B, or omega^2 for "omega"), the
        others at the values given."""
        k = self.blocks
        if axis == "B":
            return (k["K0"] + T * k["KT"] + omega**2 * k["Kw"]).tocsc(), k["KB"]
        return (k["K0"] + B * k["KB"] + T * k["KT"]).tocsc(), k["Kw"]

    def field_values(self, y: np.ndarray, n: int = 201) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(s, u, v) of the unknowns y on n evenly spaced points (polynomial interpolation per subdomain)."""
        s = np.linspace(0.0, 1.0, n)
        u = np.zeros(n, dtype=y.dtype)
        v = np.zeros(n, dtype=y.dtype)
        start = 0
        edges, degrees = self.mesh.edges, self.mesh.degrees
        for j, (a, b, m) in enumerate(zip(edges[:-1], edges[1:], degrees)):
            inside = (s >= a) & ((s < b) | (j == len(degrees) - 1))
            if np.any(inside):
                P = resample_matrix(lobatto_nodes(m), (s[inside] - a) / (b - a), lobatto_weights(m))
                u[inside] = P @ y[start:start + m + 1]
                v[inside] = P @ y[start + m + 1:start + 2 * (m + 1)]
            start += _FIELDS * (m + 1)
        return s, u, v


@lru_cache(maxsize=32)
def _assembled(tether: Tether, N: int) -> tuple[Mesh, dict[str, sp.csc_matrix]]:
    """The mesh and the blocks of the undamped ``tether`` at middle resolution N (the damping scales one block and
    moves neither the mesh nor the others)."""
    grid = mesh(tether, N)
    return grid, _assemble(tether, grid)


def family(tether: Tether, N: int) -> TetherFamily:
    """The family of ``tether`` at middle resolution N (its assembly memoised over the damping; the mesh follows
    the layers at the tether's own load, spin and tension)."""
    return TetherFamily(tether, *_assembled(tether.with_(gamma=0.0), int(N)))
