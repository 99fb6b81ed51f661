"""Rung 1v: where the straight tether with profiles first loses stability along load or spin, and how
(divergence or flutter), from the spectra of :mod:`etcheck.rod.straight.profiles` (dimensionless).

With a current that varies along the tether the load is circulatory (docs/model.md, section 9):
neither the Kelvin-Tait-Chetaev theorem (damped: stability lost only through lambda = 0) nor the
Hamiltonian symmetry of the undamped spectrum holds, so stability is read from the eigenvalues
themselves, as they cross into Re lambda > 0:

* **scan**: the eigenvalues nearest the shift (every mode the load and spin reshape, up to the
  Kelvin-Voigt cluster at -1/gamma) on evenly spaced points of the line, up to the first unstable
  one (Re lambda above :data:`RELATIVE` |lambda|, at least :data:`THRESHOLD`: the round-off of the
  spectrum stays below it);
* **locate**: between the last stable and the first unstable point, Brent's method on a function
  that changes sign at the crossing and is smooth through it: the real part of the crossing
  eigenvalue where it comes from the left half-plane (damped, or a spun circulatory tether), the
  discriminant Re (lambda_a - lambda_b)^2 of the two eigenvalues that meet where they collide on the
  imaginary axis (undamped flutter, a Krein-like collision: Re lambda grows like a square root
  there, which no root finder on Re lambda locates quickly). The crossing is divergence when its
  eigenvalue is real (a static point), flutter when it has a frequency;
* **error**: the same crossing located on a second, finer mesh (:func:`~etcheck.rod.straight.profiles.check_resolution`);
  the resolution rises along :data:`LADDER` until the two agree to the tolerance.

A tether whose unloaded spectrum has double frequencies (R = 1) under a current that varies
flutters at any load: the circulatory part splits the double pair off the axis in proportion to B.
Such a crossing is located at B -> 0 and reported as a critical load of 0.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from etcheck.numerics.blas import single_blas_thread
from etcheck.numerics.eigen import sparse_qep_nearest
from etcheck.numerics.optimize import brentq
from etcheck.rod.straight.mode_band import band_modes, mode_count
from etcheck.rod.straight.profiles import Tether, TetherFamily, check_resolution, family
from etcheck.rod.straight.spectral import CriticalKind

__all__ = [
    "LADDER",
    "MODEL",
    "RELATIVE",
    "THRESHOLD",
    "Crossing",
    "collides",
    "critical",
    "growth",
    "spectrum_at",
]

MODEL = "rung 1v (graded collocation, profiles)"
#: Re lambda above this (and above RELATIVE |lambda|) counts as unstable.
THRESHOLD = 1e-9
RELATIVE = 1e-8
#: Middle resolutions tried in turn until two meshes agree.
LADDER = (24, 32, 48, 64, 96)
#: Evenly spaced points of the scan along a line.
SCAN = 24
#: Least pairs of eigenvalues examined at each point.
K_MODES = 12
#: A bracket is narrowed to this fraction of its end before the crossing in it is located.
NARROW = 0.02
#: A critical load below this fraction of the scanned range is a crossing at zero (flutter at any load).
AT_ZERO = 1e-7


@dataclass(frozen=True)
class Crossing:
    """The first loss of stability along a line (dimensionless).

    ``value``: B or omega at the crossing (nan when none was found up to ``hi``, 0 when unstable at
    any value); ``kind``: a :class:`~etcheck.rod.straight.spectral.CriticalKind`; ``eigenvalue``: the
    eigenvalue that crosses (its imaginary part the flutter frequency); ``error``: absolute, from two
    meshes; ``N``, ``N_check``: the middle resolutions; ``mode``: (s, u, v) of the crossing mode on a
    uniform grid, complex, scaled so that max(|u|, |v|) = 1 (None when none crossed).
    """

    axis: str
    value: float
    kind: str
    eigenvalue: complex
    error: float
    converged: bool
    lo: float
    hi: float
    N: int
    N_check: int
    message: str
    mode: tuple | None = None


def _nev(tether: Tether, hi_params) -> int:
    """How many eigenvalues each point examines: the k least pairs, every mode the load and spin reshape
    (:func:`~etcheck.rod.straight.mode_band.band_modes` at the end of the line) and, with damping, none of the
    Kelvin-Voigt cluster (the modes below 0.8 / gamma: ARPACK converges slowly on the cluster)."""
    nev = max(2 * K_MODES + 4, 2 * band_modes(hi_params) + 4)
    if tether.params.gamma > 0:
        below = mode_count(hi_params, np.array([(0.8 / tether.params.gamma) ** 2]), hi_params.T)[0]
        nev = min(nev, max(8, 2 * int(below)))
    return nev


def _shift(tether: Tether) -> float:
    """A real shift between the low modes and the Kelvin-Voigt cluster at -1/gamma (small without damping)."""
    return 0.5 / tether.params.gamma if tether.params.gamma > 0 else 0.01234567


def _threshold(lam: np.ndarray) -> np.ndarray:
    return np.maximum(THRESHOLD, RELATIVE * np.abs(lam))


def spectrum_at(fam: TetherFamily, x: dict, nev: int, vectors: bool = False):
    """The nev eigenvalues nearest the shift at the point x = {"B": .., "omega": .., "T": ..} (and the
    eigenvectors with ``vectors``)."""
    A = fam.operator(x["B"], x["omega"], x["T"])
    return sparse_qep_nearest(*A, k=nev, sigma=_shift(fam.tether), vectors=vectors)


def growth(lam: np.ndarray) -> float:
    """max (Re lambda - threshold): positive when some eigenvalue counts as unstable."""
    return float(np.max(lam.real - _threshold(lam))) if lam.size else -math.inf


class _Line:
    """Spectra along one axis on one mesh (memoised): all the eigenvalues a point examines, or a few near a
    given one."""

    def __init__(self, tether: Tether, axis: str, N: int, hi: float):
        self.tether, self.axis, self.N = tether, axis, N
        p = tether.params
        ends = tether.with_(**{axis: hi})
        self.fam = family(ends, N)
        self.nev = _nev(tether, _mean_params(ends))
        self.base = {"B": p.B, "omega": p.omega, "T": p.T}
        self.memo: dict[float, np.ndarray] = {}

    def point(self, x: float) -> dict:
        return self.base | {self.axis: x}

    def spectrum(self, x: float) -> np.ndarray:
        if x not in self.memo:
            self.memo[x] = spectrum_at(self.fam, self.point(x), self.nev)
        return self.memo[x]

    def growth(self, x: float) -> float:
        return growth(self.spectrum(x))

    def near(self, x: float, z: complex, k: int = 6) -> np.ndarray:
        """The k eigenvalues nearest z at x (z real: a real shift next to it)."""
        A = self.fam.operator(**self.point(x))
        off = 1e-3 * (1.0 + abs(z))
        sigma = complex(z.real + off, z.imag) if z.imag != 0 else z.real + off
        return sparse_qep_nearest(*A, k=k, sigma=sigma)


def _mean_params(tether: Tether):
    """The tether's parameters with its mean tension and mean |load| (for mode counts)."""
    s = np.linspace(0.0, 1.0, 201)
    p = tether.params
    return p.with_(T=p.T * float(np.mean(tether.tension(s))), B=p.B * float(np.mean(np.abs(tether.current(s)))))


def _scan(line: _Line, lo: float, hi: float, n: int) -> tuple[float, float] | None:
    """(last stable, first unstable) point of n even steps from lo to hi; None when all are stable.
    Unstable at lo: (lo, lo)."""
    if line.growth(lo) > 0:
        return lo, lo
    prev = lo
    for x in np.linspace(lo, hi, n + 1)[1:]:
        if line.growth(float(x)) > 0:
            return prev, float(x)
        prev = float(x)
    return None


def _unstable_eigenvalue(lam: np.ndarray) -> complex:
    z = complex(lam[np.argmax(lam.real - _threshold(lam))])
    return complex(z.real, abs(z.imag))  # the member of a pair with Im >= 0


def _nearest(lam: np.ndarray, z: complex, k: int = 1) -> np.ndarray:
    return lam[np.argsort(np.abs(lam - z), kind="stable")[:k]]


def _crossing_function(line: _Line, a: float, b: float):
    """A function of the axis value, negative at a (stable), positive at b (unstable) and smooth through the
    crossing (see the module docstring), from the few eigenvalues near the one that crosses."""
    z = _unstable_eigenvalue(line.spectrum(b))
    if not collides(line.tether):  # from the left half-plane: its real part

        def real_part(x: float) -> float:
            return float(_nearest(line.near(x, z), z, 1)[0].real)
        return real_part
    centre = complex(0.0, z.imag)
    flutter = _kind(z) == CriticalKind.FLUTTER

    def discriminant(x: float) -> float:  # Re (lambda_a - lambda_b)^2 of the two that meet at i Im z
        lam = line.near(x, centre)
        if flutter:
            lam = lam[lam.imag > 0]
        pair = _nearest(lam, centre, 2)
        return float(((pair[0] - pair[1]) ** 2).real) if pair.size == 2 else math.nan
    return discriminant


def collides(tether: Tether) -> bool:
    """Whether eigenvalues leave the imaginary axis only in colliding pairs: undamped, and either without spin
    (the spectrum is symmetric under lambda -> -lambda, the equations having lambda^2 only) or with a uniform
    load (gyroscopic and conservative: Hamiltonian). Otherwise an eigenvalue crosses the axis on its own."""
    p = tether.params
    return p.gamma == 0 and (p.omega == 0 or not tether.circulatory)


def _bisect(line: _Line, a: float, b: float, rtol: float) -> float:
    while b - a > rtol * abs(b):
        c = 0.5 * (a + b)
        if line.growth(c) > 0:
            b = c
        else:
            a = c
    return b


def _single(line: _Line, a: float, b: float) -> tuple[float, float]:
    """[a, b] shrunk by bisection on stability until one eigenvalue (a real one, or one of a pair with Im > 0) is
    unstable at b and the bracket is narrower than :data:`NARROW` of b: then one crossing lies in it."""
    while True:
        lam = line.spectrum(b)
        lam = lam[lam.imag >= 0]
        if np.sum(lam.real - _threshold(lam) > 0) <= 1 and b - a <= NARROW * abs(b):
            return a, b
        c = 0.5 * (a + b)
        if c in (a, b):
            return a, b
        if line.growth(c) > 0:
            b = c
        else:
            a = c


def _locate(line: _Line, a: float, b: float, rtol: float) -> tuple[float, complex]:
    """The crossing between a (stable) and b (unstable), and its eigenvalue (just past it)."""
    a, b = _single(line, a, b)
    h = _crossing_function(line, a, b)
    ha, hb = h(a), h(b)
    if ha < 0 < hb:
        x = brentq(h, a, b, xtol=0.25 * rtol * abs(b), rtol=4 * np.finfo(float).eps, maxiter=100)
    else:  # no clean sign change of the smooth function: the stability predicate, bisected
        x = _bisect(line, a, b, rtol)
    past = min(x * (1 + 4 * rtol), b) if x > 0 else b
    lam = line.spectrum(past)
    z = _unstable_eigenvalue(lam) if line.growth(past) > 0 else complex(_nearest(lam, 0j, 1)[0])
    return x, z


def _kind(z: complex) -> str:
    return CriticalKind.FLUTTER if abs(z.imag) > 1e-6 * max(1.0, abs(z)) else CriticalKind.DIVERGENCE


def _first(line: _Line, lo: float, hi: float, rtol: float, near=None):
    """The first crossing on one mesh: (value, eigenvalue), (lo, eigenvalue) when unstable at lo, or
    (None, None) when stable up to hi. ``near``: a bracket (a, b) from another mesh to start from; the crossing
    found from it is kept only when the tether is stable just below it on this mesh."""
    if near is not None:
        a, b = near
        width = max(b - a, 1e-6 * abs(b))
        a2, b2 = max(lo, a - width), min(hi, b + width)
        if line.growth(a2) <= 0 and line.growth(b2) > 0:
            x, z = _locate(line, a2, b2, rtol)
            below = x * (1 - 1e-6) if x > 0 else lo
            if x <= a2 or line.growth(below) <= 0 or below <= lo:
                return x, z
    found = _scan(line, lo, hi, SCAN)
    if found is None:
        return None, None
    a, b = found
    if a == b:
        return a, _unstable_eigenvalue(line.spectrum(a))
    return _locate(line, a, b, rtol)


@single_blas_thread
def critical(tether: Tether, axis: str = "B", hi: float | None = None, tol: float = 1e-8,
             ladder: tuple[int, ...] = LADDER, mode: bool = True) -> Crossing:
    """The first loss of stability of the straight tether with profiles along ``axis`` ("B" or "omega"),
    from 0 to ``hi`` (default: :func:`default_hi`), the others fixed at ``tether.params``; dimensionless.

    Scanned and located on the mesh of middle resolution N, located again on the finer check mesh
    (:func:`~etcheck.rod.straight.profiles.check_resolution`), climbing ``ladder`` until the two agree to
    ``tol`` (relative); the error is their distance plus the root finder's tolerance."""
    if axis not in ("B", "omega"):
        raise ValueError(f"axis must be 'B' or 'omega', got {axis!r}")
    hi = default_hi(tether, axis) if hi is None else float(hi)
    lo = 0.0
    rtol = min(tol, 1e-6) * 1e-2
    near = None
    for N in ladder:
        M = check_resolution(N)
        line = _Line(tether, axis, N, hi)
        x1, z1 = _first(line, lo, hi, rtol, near)
        bracket = None if x1 is None else (x1 * (1 - 1e-3), x1 * (1 + 1e-3) + 1e-12 * hi)
        x2, z2 = _first(_Line(tether, axis, M, hi), lo, hi, rtol, bracket)
        if x1 is None and x2 is None:
            return Crossing(axis, math.nan, CriticalKind.NONE_FOUND, complex(math.nan), math.nan, True, lo, hi, N, M,
                            f"stable on the scanned range {axis} in [{lo:g}, {hi:g}] ({MODEL}, N = {N} and {M})")
        if x1 is not None and x2 is not None:
            if abs(x1 - x2) + rtol * abs(x2) <= tol * max(abs(x2), AT_ZERO * hi):
                break
            near = (min(x1, x2), max(x1, x2))
    if x1 is None or x2 is None:
        return Crossing(axis, math.nan, CriticalKind.NOT_LOCATED, complex(math.nan), math.nan, False, lo, hi, N, M,
                        f"the meshes N = {N} and {M} disagree on whether the tether loses stability up to "
                        f"{axis} = {hi:g} ({MODEL})")
    return _crossing(line, axis, x1, x2, z2, lo, hi, M, tol, rtol, mode)


def _crossing(line, axis, x1, x2, z2, lo, hi, M, tol, rtol, mode) -> Crossing:
    N = line.N
    err = abs(x1 - x2) + rtol * abs(x2)
    zero = max(x1, x2) <= AT_ZERO * hi
    kind = _kind(z2)
    if x1 == x2 == lo:
        return Crossing(axis, lo, CriticalKind.UNSTABLE_AT_START, z2, 0.0, True, lo, hi, N, M,
                        f"already unstable at {axis} = {lo:g} ({MODEL})")
    at = f" at frequency Im lambda = {abs(z2.imag):.9g}" if kind == CriticalKind.FLUTTER else ""
    if zero:
        msg = (f"unstable at any {axis} > 0: {kind}{at} from {axis} = 0 on, the circulatory load splitting a double "
               f"frequency of the unloaded tether off the imaginary axis ({MODEL})")
    else:
        msg = (f"first instability at {axis} = {x2:.12g} ({kind}{at}; {MODEL}); error estimate {err:.2e} "
               f"(meshes N = {N} and {M})")
    converged = zero or bool(err <= tol * abs(x2))
    shape = _mode(line, x2 * (1 + 8 * rtol) if not zero else AT_ZERO * hi, z2) if mode else None
    return Crossing(axis, 0.0 if zero else x2, kind, z2, 0.0 if zero else err, converged, lo, hi, N, M, msg, shape)


def _mode(line: _Line, x: float, z: complex):
    """(s, u, v) of the eigenvector nearest z at x on a uniform grid of 201 points, complex, scaled so that the
    larger of |u|, |v| peaks at 1 with zero phase there."""
    A = line.fam.operator(**line.point(x))
    lam, Y = sparse_qep_nearest(*A, k=4, sigma=z + 1e-7 * (1 + abs(z)), vectors=True)
    s, u, v = line.fam.field_values(Y[:, int(np.argmin(np.abs(lam - z)))], 201)
    k = int(np.argmax(np.maximum(np.abs(u), np.abs(v))))
    peak = u[k] if abs(u[k]) >= abs(v[k]) else v[k]
    return s, u / peak, v / peak


def default_hi(tether: Tether, axis: str) -> float:
    """End of the line scanned when none is given: for the load, 3 x the expected first critical load of the
    tether under its mean tension with the uniform load of its mean current; for the spin, 2 x the expected
    critical spin (:func:`etcheck.rod.straight.exact.root_scale`), at least 1.1 x the operating value."""
    from etcheck.rod.straight.exact import root_scale

    mean = _mean_params(tether)
    s = np.linspace(0.0, 1.0, 201)
    b = max(float(np.mean(np.abs(tether.current(s)))), 0.1)
    if axis == "B":
        return max(3.0 * root_scale(mean.with_(B=0.0), "B", 1.0) / b, 1.1 * tether.params.B)
    return max(2.0 * root_scale(mean.with_(omega=0.0), "omega", 1.0), 1.1 * tether.params.omega)
