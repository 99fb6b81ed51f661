"""Stability of the straight whirling rod along parameter lines (dimensionless).

Everything here linearises about the straight state of eq. (86) of arXiv:0810.3668 (erratum
F0 = +T e3) with :func:`etcheck.rod.core.linear.linear_operator` and decides
stability from the least-|lambda| eigenvalues (unstable iff some
Re lambda > ``THRESHOLD``; Sec. VI of the paper, eqs. (82)-(85)).

Structure used (not assumed; each conclusion is checked numerically):

* **Static (divergence) points.** At lambda = 0 the operator A0 is affine in
  B and in T and affine in omega^2 (the straight base state does not depend
  on B or omega). So the parameter values where A0 is singular, i.e. the
  static bifurcations / divergence points of eq. (91) generalised to
  omega, T != 0, are the real eigenvalues of a *linear* pencil, solved
  directly (QR elimination of the lambda-free unknowns phi, m, then QZ) at two
  resolutions. No scanning.
* **Stability changes.** The scan evaluates max Re lambda on a grid that
  contains every static point +/- a relative 1e-6. A change of state across a
  static point is reported at the pencil value (kind "divergence"). Any other
  change is located by bisection on the predicate max Re lambda > THRESHOLD
  and reported as "flutter" (a complex pair crossing: undamped, a Krein
  collision on the imaginary axis; with damping gamma > 0 none is expected by
  the Kelvin-Tait-Chetaev theorem, see docs/model.md, section 8, but the solver would find
  one). The bisection predicate has threshold ``THRESHOLD`` = 1e-9 on
  Re lambda: undamped collisions give Re lambda ~ sqrt(distance), so the
  located point is limited by ``tol`` only; a linear (damped) crossing would
  be located to about THRESHOLD / |d Re lambda / d parameter|.
* Windows narrower than the scan spacing can be missed; ``n_scan`` controls it.

Only the k least-|lambda| pairs enter the indicator (``K_MODES``): high modes
are stabilised by bending stiffness (Re lambda of high modes is negative with
damping and zero without).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property

import numpy as np

from etcheck.numerics.eigen import factor_static, match_spectra, pencil_eigenvalues, qep_dense
from etcheck.rod.core.base_state import straight
from etcheck.rod.core.linear import NFIELDS, linear_operator, static_differences
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.core.spectrum import (
    ERROR_FLOOR,
    SIGMA,
    check_resolution,
    damping_cluster,
    nearest_eigenvalues,
    prefers_dense,
    roundoff_floor,
    select_pairs,
)
from etcheck.rod.straight.exact.mode_band import band_modes
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.memory import WORKSPACE, Memo, matrix_bytes, require
from etcheck.runtime.parallel import split_map

__all__ = [
    "THRESHOLD",
    "K_MODES",
    "CriticalPoint",
    "Campbell",
    "StraightFamily",
    "straight_family",
    "family_bytes",
    "static_points",
    "divergence_loads",
    "critical_load",
    "critical_spin",
    "stable_intervals",
    "scan_line",
    "stable_windows",
    "stability_map",
    "campbell",
]

class CriticalKind(StrEnum):
    """How the straight rod loses stability along a line (a str: it is written to JSON as its value)."""

    DIVERGENCE = "divergence"  # a real eigenvalue through 0: the tether buckles (or whirls) statically
    FLUTTER = "flutter"  # a complex pair crosses: growing oscillation (undamped, Krein collision)
    UNSTABLE_AT_START = "unstable at start"  # already unstable where the line starts: nothing to locate
    NONE_FOUND = "none found"  # stable over the whole line scanned
    NEVER = "never"  # stable at every value of the line: proved, not scanned (R = 1 undamped below its static load)
    NOT_LOCATED = "not located"  # informative only (e.g. a critical spin of a mission without spin)

    @property
    def located(self) -> bool:
        """A crossing whose parameter value was located (divergence or flutter)."""
        return self in (CriticalKind.DIVERGENCE, CriticalKind.FLUTTER)


#: R = 1: every static point is double (the u and v planes are alike) and round-off splits it by about
#: sqrt(eps), really or into a complex pair: roots this close (relative) are one double root; the same for
#: R within this of 1, whose pairs are split by less than round-off splits them.
DOUBLE = 1e-6


def nearly_isotropic(R: float) -> bool:
    """Whether the static points of a rod with stiffness ratio R are double to round-off (|1 - R| < DOUBLE)."""
    return abs(1.0 - R) < DOUBLE


#: Re lambda above this counts as unstable (dimensionless growth rate).
THRESHOLD = 1e-9
#: Number of least-|lambda| pairs examined by the stability indicator.
K_MODES = 12
#: Most eigenvalues the undamped stability indicator examines for the band that load and spin reshape.
BAND_MAX = 64
#: Relative offset of the scan points placed either side of a static point.
_DELTA = 1e-6
_AXES = ("B", "omega", "T")


_BLOCKS = ("A00", "AB", "AT", "Aw", "A10", "A1w", "A2")
#: a family at resolution N in 12(N+1)-square float64 matrices: held with every block, its reduced forms and its
#: parts (9.4 measured with tracemalloc), and at most while they are built and used (15.7-16.2 from N = 16 to 96)
FAMILY_HELD, FAMILY_PEAK = 10, 16


def family_bytes(N: int, peak: bool = True) -> float:
    """Bytes of a :class:`StraightFamily` at resolution N: at most while it is built (``peak``), or held."""
    return matrix_bytes(NFIELDS * (int(N) + 1), count=FAMILY_PEAK if peak else FAMILY_HELD) + WORKSPACE


def _uncoupled(fam) -> list[tuple[np.ndarray, np.ndarray]]:
    """(rows, columns) of the parts of the family's operator that share no row or column (one part if any is not square)."""
    import scipy.sparse as sp  # here: a draft (static pencils only) never loads scipy.sparse
    from scipy.sparse.csgraph import connected_components

    pattern = sum(np.abs(getattr(fam, name)) for name in _BLOCKS) != 0.0
    n = pattern.shape[0]
    graph = sp.bmat([[None, sp.csr_matrix(pattern)], [sp.csr_matrix(pattern.T), None]])
    _, label = connected_components(graph, directed=False)
    parts = [(np.nonzero(label[:n] == c)[0], np.nonzero(label[n:] == c)[0]) for c in np.unique(label)]
    if any(rows.size != cols.size for rows, cols in parts):
        return [(np.arange(n), np.arange(n))]
    return parts


class _Part:
    """One uncoupled part of a family, phi and m eliminated; constant parts keep their eigenvalues."""

    def __init__(self, fam, rows: np.ndarray, cols: np.ndarray):
        sub = {name: getattr(fam, name)[np.ix_(rows, cols)] for name in _BLOCKS}
        static = np.nonzero(np.isin(cols, fam.static_cols))[0]
        self.r = dict(zip(_BLOCKS, factor_static(sub["A00"], static).reduce(*(sub[name] for name in _BLOCKS))))
        self.gamma = fam.params.gamma
        self.constant = not any(np.any(self.r[name]) for name in ("AB", "AT", "Aw", "A1w"))
        self.all = qep_dense(self.r["A00"], self.r["A10"], self.r["A2"]) if self.constant else None

    def nearest(self, B: float, omega: float, T: float, nev: int, past_cluster: bool, dense: bool) -> np.ndarray:
        """The nev eigenvalues of this part nearest the shift (all of a constant part)."""
        if self.constant:
            return self.all[~damping_cluster(self.all, self.gamma)] if past_cluster else self.all
        r = self.r
        A0 = r["A00"] + B * r["AB"] + T * r["AT"] + omega**2 * r["Aw"]
        return nearest_eigenvalues(A0, r["A10"] + omega * r["A1w"], r["A2"], nev, self.gamma,
                                   past_cluster=past_cluster, dense=dense, reduced=True)


class StraightFamily:
    """Operators of the straight rod as exact polynomials in (B, omega, T).

    A0 = A00 + B AB + T AT + omega^2 Aw,  A1 = A10 + omega A1w,  A2 fixed, at
    resolution N (P, R, Gamma, f, gamma from ``params``); dimensionless.
    The lambda-free unknowns phi, m enter A0 through columns that none of
    B, omega, T touches, so one QR eliminates them for the whole family: the
    blocks of A0 are also kept reduced (``reduced_static``: Q2^T A[:, keep],
    size 6(N+1)), on which the static pencils run; A10, A1w, A2 (and
    ``reduced``, every block) are built when first asked for: the static pencils,
    i.e. every damped critical value, never need them. For the eigenvalues the operator is
    also split into its uncoupled parts (read off the sparsity of all blocks;
    for the straight rod: bending xi1,2, a1,2 with phi1,2, m1,2; torsion a3, m3;
    axial xi3, phi3), each reduced the same way; a part that none of B, omega,
    T reaches (torsion, axial) is solved once, densely, for the family.
    """

    def __init__(self, params: RodParameters, N: int):
        require(f"the straight tether's collocation operators at N = {int(N)}", family_bytes(N))
        self.params = params
        self.N = int(N)
        self._p0 = p0 = params.with_(B=0.0, omega=0.0, T=0.0)
        variants = [(q, straight(q)) for q in (p0.with_(B=1.0), p0.with_(T=1.0), p0.with_(omega=1.0))]
        A00, (self.AB, self.AT, self.Aw) = static_differences(p0, straight(p0), variants, self.N)
        self.A00 = A00
        n = self.N + 1
        self.static_cols = np.arange(6 * n, NFIELDS * n)
        self._factor = factor_static(A00, self.static_cols)
        self.reduced_static = dict(zip(("A00", "AB", "AT", "Aw"), self._factor.reduce(A00, self.AB, self.AT, self.Aw)))

    @cached_property
    def _dynamic(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(A10, A1w, A2): the damping, gyroscopic and inertia blocks, made when first needed (the static pencils,
        i.e. every critical load and spin with damping, never are)."""
        _, A10, A2 = linear_operator(self._p0, straight(self._p0), self.N)
        pw = self._p0.with_(omega=1.0)
        return A10, linear_operator(pw, straight(pw), self.N)[1] - A10, A2

    A10 = cached_property(lambda self: self._dynamic[0])
    A1w = cached_property(lambda self: self._dynamic[1])
    A2 = cached_property(lambda self: self._dynamic[2])

    @cached_property
    def reduced(self) -> dict[str, np.ndarray]:
        """Every block reduced (Q2^T A[:, keep]: phi, m eliminated)."""
        dyn = dict(zip(("A10", "A1w", "A2"), self._factor.reduce(*self._dynamic)))
        return self.reduced_static | dyn

    @cached_property
    def parts(self) -> list[_Part]:
        """The uncoupled parts, made when eigenvalues are first asked for (the static pencils do not need them)."""
        return [_Part(self, rows, cols) for rows, cols in _uncoupled(self)]

    def operator(self, B: float, omega: float, T: float, reduced: bool = False):
        """(A0, A1, A2) at the given load, spin and tension (``reduced``: phi, m eliminated)."""
        r = self.reduced if reduced else {name: getattr(self, name) for name in _BLOCKS}
        A0 = r["A00"] + B * r["AB"] + T * r["AT"] + omega**2 * r["Aw"]
        A1 = r["A10"] + omega * r["A1w"]
        return A0, A1, r["A2"]

    def eigenvalues(self, B: float, omega: float, T: float, nev: int, past_cluster: bool = False) -> np.ndarray:
        """The nev eigenvalues nearest the shift (the nearest of every uncoupled part, merged).

        ``past_cluster=True`` removes the Kelvin-Voigt damping cluster and asks
        for more until nev lie outside it (for display). The stability
        indicator does not need that: cluster eigenvalues decay at a rate
        >= 1/gamma, and with damping the only way to lose stability is through
        lambda = 0, next to the shift (Kelvin-Tait-Chetaev).
        """
        dense = prefers_dense(self.params, nev)
        lam = np.concatenate([part.nearest(B, omega, T, nev, past_cluster, dense) for part in self.parts])
        return lam[np.argsort(np.abs(lam - SIGMA), kind="stable")][:nev]

    def growth(self, B: float, omega: float, T: float, k: int = K_MODES) -> float:
        """max Re lambda over the 2k + 4 eigenvalues nearest the shift (at least the k least-|lambda| pairs: with
        heavy damping the overdamped modes piling up towards -1/gamma can push a growing one past them).
        Undamped, over every eigenvalue of the band that load and spin reshape (:mod:`etcheck.rod.straight.exact.mode_band`)
        if that is more: with a dense low spectrum (large P, loads past several static points) a flutter pair
        can lie beyond the k least-|lambda| pairs."""
        nev = 2 * k + 4
        if self.params.gamma == 0:  # the band, up to what the resolution resolves (past it: spurious modes) and
            # at most BAND_MAX eigenvalues (a sampled map's cost; the margins come from the exact determinant)
            band = 2 * band_modes(self.params.with_(B=B, omega=omega, T=T)) + 4
            nev = max(nev, min(band, 4 * (self.N + 1), BAND_MAX))
        lam = self.eigenvalues(B, omega, T, nev)
        return float(np.max(lam.real))

    def pencil_roots(self, axis: str, B: float, omega: float, T: float) -> np.ndarray:
        """Real parameter values on ``axis`` where A0 is singular (others fixed).

        Returns values of B (or T) or of omega^2 (axis "omega"). ``axis =
        "ray"`` gives the values t where A0(t B, sqrt(t) omega, T) is singular
        (load and spin squared scaled together from zero). One pencil of the
        reduced operator (phi, m eliminated once for the family), solved by
        :func:`~etcheck.numerics.eigen.pencil_eigenvalues` (an LU of A0 and an
        eigenproblem through the columns the axis reaches). A root
        counts as real when its imaginary part is below 1e-8 times its
        modulus, or below :data:`DOUBLE` times it for a nearly isotropic rod
        (:func:`nearly_isotropic`: its double roots split under round-off,
        possibly into a complex pair).
        """
        r = self.reduced_static
        vals = {"B": B, "omega": omega, "T": T}
        if axis == "ray":
            n0 = B * r["AB"] + omega**2 * r["Aw"]
            vals["B"] = vals["omega"] = 0.0
        else:
            n0 = r[{"B": "AB", "T": "AT", "omega": "Aw"}[axis]]
            vals[axis] = 0.0
        A0 = r["A00"] + vals["B"] * r["AB"] + vals["T"] * r["AT"] + vals["omega"]**2 * r["Aw"]
        x = pencil_eigenvalues(A0, n0)
        imag_tol = DOUBLE if nearly_isotropic(self.params.R) else 1e-8
        real = np.abs(x.imag) <= imag_tol * np.maximum(np.abs(x), 1e-300)
        return np.sort(x[real].real)


#: the families most recently asked for, within a share of the memory budget (etcheck.runtime.memory.Memo)
_family_cached = Memo(StraightFamily, lambda params, N: family_bytes(N, peak=False))


def straight_family(params: RodParameters, N: int) -> StraightFamily:
    """The operator family of the straight rod with these P, R, Gamma, f, ends at resolution N (memoised: B, omega, T
    are the family's coordinates, not its key)."""
    return _family_cached(params.with_(B=0.0, omega=0.0, T=0.0), int(N))


@single_blas_thread
def static_points(params: RodParameters, axis: str = "B", lo: float = 0.0, hi: float = np.inf,
                  N: int = 48):
    """Values on ``axis`` ("B", "omega" or "T") where lambda = 0 is an eigenvalue.

    The other parameters are fixed at ``params``. Computed from the linear
    pencil at resolutions N and check_resolution(N); returns ``(values,
    errors)`` (values sorted, with multiplicity; errors relative, from the
    two-resolution comparison; values without a partner are dropped).
    """
    if axis not in _AXES:
        raise ValueError(f"axis must be one of {_AXES}, got {axis!r}")
    M = check_resolution(N)
    out = []
    for n in (N, M):
        r = straight_family(params, n).pencil_roots(axis, params.B, params.omega, params.T)
        if axis == "omega":
            r = np.sqrt(r[r > 0])
        out.append(r)
    m = match_spectra(out[1], out[0], accept=1e-4, floor=1e-3)
    vals = m.values.real
    sel = (vals >= lo) & (vals <= hi)
    order = np.argsort(vals[sel])
    return vals[sel][order], m.errors[sel][order]


@single_blas_thread
def divergence_loads(params: RodParameters, n: int = 5, N: int | None = None) -> np.ndarray:
    """The n smallest B > 0 where lambda = 0 is an eigenvalue (with multiplicity; dimensionless).

    Static bifurcations of the straight rod at the given omega, T (gamma is
    irrelevant at lambda = 0), from the linear eigenproblem in B at lambda = 0
    (A0 affine in B). At omega = T = 0 these are beta_k^3 sqrt(R) / f with
    beta_k the (double) zeros of chi (eq. (91)).
    """
    if N is None:
        N = max(32, 6 * n)
    vals, _ = static_points(params, "B", lo=1e-12, N=N)
    return vals[:n]


@dataclass(frozen=True)
class CriticalPoint:
    """First loss of stability along a parameter line (dimensionless).

    kind: "divergence" (real eigenvalue through 0, value from the exact
    pencil), "flutter" (complex pair crossing, value by bisection), "unstable
    at start" (value = start of the line, nothing to locate) or "none found"
    (stable over the scanned range; value = nan).
    """

    axis: str
    value: float
    kind: str
    bracket: tuple
    error: float
    converged: bool
    message: str
    N: int


def _line_params(params: RodParameters, axis: str, x: float) -> tuple:
    vals = {"B": params.B, "omega": params.omega, "T": params.T}
    vals[axis] = x
    return vals["B"], vals["omega"], vals["T"]


class _Line:
    """max Re lambda along one axis at resolution N (memoised)."""

    def __init__(self, params: RodParameters, axis: str, N: int, k: int):
        self.params, self.axis, self.k = params, axis, k
        self.fam = straight_family(params, N)
        self.memo: dict[float, float] = {}

    def growth(self, x: float) -> float:
        if x not in self.memo:
            self.memo[x] = self.fam.growth(*_line_params(self.params, self.axis, x), k=self.k)
        return self.memo[x]

    def unstable(self, x: float) -> bool:
        return self.growth(x) > THRESHOLD


def _bisect(line: _Line, a: float, b: float, tol: float) -> tuple:
    ua = line.unstable(a)
    while b - a > tol:
        c = 0.5 * (a + b)
        if c in (a, b):
            break
        if line.unstable(c) == ua:
            a = c
        else:
            b = c
    return a, b


@dataclass(frozen=True)
class _Change:
    a: float
    b: float
    value: float
    kind: str
    error: float
    to_unstable: bool


def _distinct_static(params, axis, lo, hi, N) -> list:
    """Static points (value, relative error) on [lo, hi], coincident ones merged."""
    spts, serr = static_points(params, axis, lo=lo, hi=hi, N=max(N, 32))
    distinct: list = []
    for v, e in zip(spts, serr):
        if not distinct or v - distinct[-1][0] > 1e-7 * max(1.0, abs(v)):
            distinct.append((v, e))
    return distinct


def _scan_grid(lo: float, hi: float, n_scan: int, distinct: list) -> list:
    """n_scan even points on [lo, hi] plus each static point +/- a relative _DELTA."""
    grid = set(np.linspace(lo, hi, n_scan).tolist())
    for v, _ in distinct:
        h = _DELTA * max(abs(v), 1e-3)
        grid.update(float(x) for x in (v - h, v + h) if lo < x < hi)
    return sorted(grid)


def _flutter_error(params, axis, lo, hi, tol, N, k, a, b) -> float:
    """Two-resolution error of a change bisected to [a, b]: the same change located at check_resolution(N)."""
    check = _Line(params, axis, check_resolution(N), k)
    x = 0.5 * (a + b)
    w = max(10 * (b - a), 1e-8 * max(1.0, abs(x)))
    for _ in range(6):
        a2, b2 = max(lo, x - w), min(hi, x + w)
        if check.unstable(a2) != check.unstable(b2):
            a2, b2 = _bisect(check, a2, b2, tol)
            return max(0.5 * (b - a), abs(0.5 * (a2 + b2) - x))
        w *= 10
    return np.inf


def _changes(params, axis, lo, hi, tol, N, n_scan, k, refine_error=True):
    """All stability changes on [lo, hi] and the state at lo.

    A change across exactly one static point in a bracket as narrow as the
    points placed around it is that point (divergence, its pencil value);
    any other is bisected to ``tol`` (flutter) and, with ``refine_error``,
    located again at the check resolution for its error.
    """
    line = _Line(params, axis, N, k)
    distinct = _distinct_static(params, axis, lo, hi, N)
    grid = _scan_grid(lo, hi, n_scan, distinct)
    states = [line.unstable(x) for x in grid]
    changes = []
    for i in range(len(grid) - 1):
        if states[i] == states[i + 1]:
            continue
        a, b = grid[i], grid[i + 1]
        hit = [(v, e) for v, e in distinct if a < v < b]
        if len(hit) == 1 and (b - a) <= 2.5 * _DELTA * max(abs(hit[0][0]), 1e-3):
            v, e = hit[0]
            changes.append(_Change(a, b, v, CriticalKind.DIVERGENCE, e * max(abs(v), 1e-3), states[i + 1]))
            continue
        a, b = _bisect(line, a, b, tol)
        err = _flutter_error(params, axis, lo, hi, tol, N, k, a, b) if refine_error else 0.5 * (b - a)
        changes.append(_Change(a, b, 0.5 * (a + b), CriticalKind.FLUTTER, err, states[i + 1]))
    return states[0], changes, line


def _default_hi(params: RodParameters, axis: str) -> float:
    pts, _ = static_points(params, axis, lo=1e-12, N=32)
    distinct = np.unique(np.round(pts, 8))
    if axis == "omega":
        return float(max(2.0, 1.25 * distinct[1])) if distinct.size >= 2 else 2.0
    if distinct.size >= 3:
        return float(1.1 * distinct[2])
    return float(2.0 * distinct[-1]) if distinct.size else 1.0


def stable_windows(changes, lo: float, hi: float, start_unstable: bool) -> list[tuple[float, float]]:
    """The stable intervals of [lo, hi] from the ordered changes of stability along a line (each with
    ``value`` and ``to_unstable``), given whether the line starts unstable (dimensionless)."""
    windows, start = [], None if start_unstable else lo
    for c in changes:
        if c.to_unstable and start is not None:
            windows.append((float(start), float(c.value)))
            start = None
        elif not c.to_unstable and start is None:
            start = c.value
    if start is not None:
        windows.append((float(start), float(hi)))
    return windows


def _scan(params: RodParameters, axis: str, tol: float, hi: float | None, N: int,
          n_scan: int, k: int, refine_error: bool = True) -> tuple[CriticalPoint, list, float]:
    """One scan of a parameter line: its first loss of stability, its stable
    windows and the end of the scanned range."""
    lo = getattr(params, axis)
    if hi is None:
        hi = max(_default_hi(params, axis), lo + 1.0 if axis == "omega" else lo)
    start_unstable, changes, line = _changes(params, axis, lo, hi, tol, N, n_scan, k, refine_error)
    windows = stable_windows(changes, lo, hi, start_unstable)
    if start_unstable:
        g = line.growth(lo)
        return CriticalPoint(axis, float(lo), CriticalKind.UNSTABLE_AT_START, (lo, lo), 0.0, True,
                             f"already unstable at {axis} = {lo:g} (max Re lambda = {g:.3e})", N), windows, hi
    if not changes:
        return CriticalPoint(axis, float("nan"), CriticalKind.NONE_FOUND, (lo, hi), float("nan"), False,
                             f"stable on the scanned range {axis} in [{lo:g}, {hi:g}] "
                             f"({n_scan} scan points)", N), windows, hi
    c = changes[0]
    conv = bool(np.isfinite(c.error) and c.error <= max(tol, 1e-8 * max(1.0, abs(c.value))))
    msg = (f"first instability at {axis} = {c.value:.12g} ({c.kind}); "
           f"bracket [{c.a:.12g}, {c.b:.12g}], error estimate {c.error:.2e}")
    return CriticalPoint(axis, float(c.value), c.kind, (c.a, c.b), float(c.error), conv, msg, N), windows, hi


def _critical(params: RodParameters, axis: str, tol: float, hi: float | None, N: int,
              n_scan: int, k: int) -> CriticalPoint:
    return _scan(params, axis, tol, hi, N, n_scan, k)[0]


@single_blas_thread
def scan_line(params: RodParameters, axis: str = "omega", tol: float = 1e-10, hi: float | None = None,
              N: int = 24, n_scan: int = 64, k: int = K_MODES) -> tuple[CriticalPoint, list, float]:
    """First loss of stability from ``params`` along ``axis``, every stable window
    [(start, end), ...] and the end of the scanned range (``hi``, by default as
    in :func:`critical_spin`), from a single scan (dimensionless)."""
    return _scan(params, axis, tol, hi, N, n_scan, k)


@single_blas_thread
def critical_load(params: RodParameters, tol: float = 1e-10, B_max: float | None = None,
                  N: int = 24, n_scan: int = 48, k: int = K_MODES) -> CriticalPoint:
    """First loss of stability of the straight rod as B increases from params.B (dimensionless).

    omega, T, gamma fixed. Divergence: exact pencil value (error from two
    resolutions). Flutter: bisection to ``tol`` plus a check at the companion
    resolution. ``B_max`` defaults to 1.1 x the third distinct static load.
    """
    return _critical(params, "B", tol, B_max, N, n_scan, k)


@single_blas_thread
def critical_spin(params: RodParameters, tol: float = 1e-10, omega_max: float | None = None,
                  N: int = 24, n_scan: int = 48, k: int = K_MODES) -> CriticalPoint:
    """First loss of stability of the straight rod as omega increases from params.omega.

    Dimensionless spin (units omega_c). At B = T = 0 this tends to sqrt(R) as
    P -> 0 (finite P shifts it: rotary inertia).
    """
    return _critical(params, "omega", tol, omega_max, N, n_scan, k)


@single_blas_thread
def stable_intervals(params: RodParameters, axis: str = "B", lo: float = 0.0, hi: float | None = None,
                     tol: float = 1e-10, N: int = 24, n_scan: int = 64, k: int = K_MODES) -> list:
    """All stability windows [(start, end), ...] of the straight rod on axis in [lo, hi].

    Dimensionless; axis "B", "omega" or "T", the other parameters from
    ``params``. Boundaries at static points are exact pencil values, others
    (Krein collisions when undamped) are bisected to ``tol``. A window that
    reaches ``hi`` ends at ``hi``.
    """
    if hi is None:
        hi = _default_hi(params, axis)
    return _scan(params.with_(**{axis: lo}), axis, tol, hi, N, n_scan, k, refine_error=False)[1]


@single_blas_thread
def stability_map(params: RodParameters, B_grid, omega_grid, N: int = 16, k: int = 8) -> np.ndarray:
    """max Re lambda of the straight rod on a (omega, B) grid, shape (len(omega), len(B)).

    Dimensionless growth rate (> THRESHOLD: unstable). Single resolution,
    N = 16 by default (the lowest ~8 pairs are accurate to ~1e-8 there at
    SET-like parameters); the operator is assembled once and recombined
    per point (it is polynomial in B and omega), so each point costs one
    shift-invert solve (milliseconds). T, gamma, P, R, Gamma from ``params``.
    """
    fam = straight_family(params, N)
    B_grid = np.asarray(B_grid, dtype=float)
    omega_grid = np.asarray(omega_grid, dtype=float)
    out = np.empty((omega_grid.size, B_grid.size))
    for i, w in enumerate(omega_grid):
        for j, b in enumerate(B_grid):
            out[i, j] = fam.growth(b, w, params.T, k=k)
    return out


@dataclass(frozen=True)
class Campbell:
    """Eigenvalues of the straight rod versus spin (dimensionless).

    ``eigenvalues[i]``: the k least-|lambda| pairs at omega[i] (one per
    conjugate pair, both members of real pairs), sorted by Im then Re,
    NaN-padded to a common length, all at resolution ``N``. Frequencies are
    Im, growth rates Re. ``error``: the largest distance of those eigenvalues
    to their partners at ``N_check`` over the spins ``checked`` (indices into
    omega), relative, absolute below |lambda| = 0.1 (inf if one has none).
    """

    omega: np.ndarray
    eigenvalues: np.ndarray
    N: int
    N_check: int
    checked: np.ndarray
    error: float

    @property
    def frequencies(self) -> np.ndarray:
        return self.eigenvalues.imag

    @property
    def growth_rates(self) -> np.ndarray:
        return self.eigenvalues.real


@single_blas_thread
def campbell(params: RodParameters, omega_grid, k: int = 10, N: int = 24, N_check: int | None = None,
             n_check: int = 3) -> Campbell:
    """Campbell diagram data: least-|lambda| eigenvalues of the straight rod vs omega (dimensionless).

    One resolution for the whole diagram (one shift-invert solve of the
    reduced operator per spin); the error is estimated by a second resolution
    ``N_check`` (default :func:`check_resolution` (N)) at ``n_check`` spins
    spread evenly over the grid, ends included.
    """
    omega_grid = np.asarray(omega_grid, dtype=float)
    nev = 2 * k + 2  # the 2k least-|lambda| and a conjugate cut at the edge (the shift is ~0: same order)
    N_check = check_resolution(N) if N_check is None else int(N_check)
    checked = np.unique(np.linspace(0, omega_grid.size - 1, min(n_check, omega_grid.size)).round().astype(int))
    coarse, fine = straight_family(params, N), straight_family(params, N_check)
    _ = coarse.parts, fine.parts  # made here, before the spins are shared with a forked helper

    def solve(job) -> np.ndarray:
        fam, w = job
        return fam.eigenvalues(params.B, w, params.T, nev, past_cluster=True)

    solved = split_map(solve, [(coarse, w) for w in omega_grid] + [(fine, omega_grid[i]) for i in checked],
                       min_items=8)
    rows = []
    for lam in solved[: omega_grid.size]:
        sel = lam[select_pairs(lam, k)]
        rows.append(sel[np.lexsort((sel.real, sel.imag))])
    width = max((r.size for r in rows), default=0)
    out = np.full((omega_grid.size, width), np.nan + 1j * np.nan)
    for i, r in enumerate(rows):
        out[i, : r.size] = r
    error = roundoff_floor(max(int(N), N_check))
    for i, ref in zip(checked, solved[omega_grid.size:]):
        m = match_spectra(rows[i], ref, accept=np.inf, floor=ERROR_FLOOR)
        error = max(error, float(np.max(m.errors, initial=0.0)) if m.values.size == rows[i].size else math.inf)
    return Campbell(omega=omega_grid, eigenvalues=out, N=int(N), N_check=N_check, checked=checked, error=error)
