"""Rung 1v: where the straight tether with profiles first loses stability along load or spin, and how
(divergence or flutter), from the spectra of :mod:`etcheck.rod.straight.varying.profiles` (dimensionless).

With a current that varies along the tether the load is circulatory (docs/model.md, section 10):
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
* **error**: the same crossing located on a second, finer mesh (:func:`~etcheck.rod.straight.varying.profiles.check_resolution`);
  the resolution rises along :data:`LADDER` until the two agree to the tolerance.

A tether whose unloaded spectrum has double frequencies (R = 1) under a current that varies
flutters at any load: the circulatory part splits the double pair off the axis in proportion to B.
So does an undamped spinning tether with a current that varies, at any load above 0 and (loaded) at
any spin above 0: Re lambda grows in proportion to the load or the spin from 0. Such a crossing is
located at 0 (the crossing eigenvalue's real part positive all the way back to the start of the line)
and reported as a critical value of 0.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from etcheck.numerics.eigen import sparse_pencil_nearest, sparse_qep_nearest
from etcheck.numerics.optimize import brentq
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.varying.line import (
    PAST,
    STATIC_ROOTS,
    Line,
    collides,
    threshold,
)
from etcheck.rod.straight.varying.line_band import (
    ORDER,
    RESTARTS,
    NotLocated,
    default_hi,
    forget_bands,
    stages,
)
from etcheck.rod.straight.varying.profiles import Tether, check_resolution
from etcheck.runtime.blas import single_blas_thread

__all__ = [
    "LADDER",
    "MODEL",
    "Crossing",
    "critical",
    "critical_spin",
    "crossing_mode",
    "first_crossings",
    "forget",
    "static_only",
]

MODEL = "rung 1v (graded collocation, profiles)"
#: Middle resolutions tried in turn until two meshes agree.
LADDER = (24, 32, 48, 64, 96)
#: Evenly spaced points of the scan along a line.
SCAN = 24
#: Two meshes whose crossings differ by less than this many times the crossing's round-off
#: (:func:`_roundoff`) agree as well as any finer pair would: the ladder stops there.
NOISE = 10.0
#: A bracket is narrowed to this fraction of its end before the crossing in it is located.
NARROW = 0.25
#: A critical load below this fraction of the scanned range is a crossing at zero (flutter at any load).
AT_ZERO = 1e-7


@dataclass(frozen=True)
class Crossing:
    """The first loss of stability along a line (dimensionless).

    ``value``: B or omega at the crossing (nan when none was found up to ``hi``, 0 when unstable at
    any value); ``kind``: a :class:`~etcheck.rod.straight.collocation.spectral.CriticalKind`; ``eigenvalue``: the
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


def _scan(line: Line, lo: float, hi: float, n: int) -> tuple[float, float] | None:
    """(last stable, first unstable) point of n even steps from lo to hi and the points either side of each
    static point; None when all are stable. Unstable at lo: (lo, lo)."""
    if line.growth(lo) > 0:
        return lo, lo
    grid = set(np.linspace(lo, hi, n + 1)[1:].tolist())
    for r in line.static_roots():
        grid.update(x for x in (r * (1 - PAST), r * (1 + PAST)) if lo < x <= hi)
    prev = lo
    for x in sorted(grid):
        if line.unstable(float(x)):
            return prev, float(x)
        prev = float(x)
    return None


def _unstable_eigenvalue(lam: np.ndarray) -> complex:
    z = complex(lam[np.argmax(lam.real - threshold(lam))])
    return complex(z.real, abs(z.imag))  # the member of a pair with Im >= 0


def _nearest(lam: np.ndarray, z: complex, k: int = 1) -> np.ndarray:
    return lam[np.argsort(np.abs(lam - z), kind="stable")[:k]]


def _crossing_function(line: Line, a: float, b: float):
    """A function of the axis value, negative at a (stable), positive at b (unstable) and smooth through the
    crossing (see the module docstring), from the few eigenvalues near the one that crosses."""
    z = _unstable_eigenvalue(line.spectrum(b))
    if not collides(line.tether):  # from the left half-plane: its real part

        line.tracked = []

        def real_part(x: float) -> float:
            return float(line.track(x, z).real)
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


def static_only(tether: Tether) -> bool:
    """Whether stability can change only at static points (a real eigenvalue through 0): damped (Kelvin-Voigt,
    acting on all bending) under a conservative load (one current: the operator at lambda = 0 is symmetric, the
    spin's term gyroscopic), Kelvin-Tait-Chetaev, as on rung 1's static pencils; the tension may vary along the
    tether (it keeps the stiffness symmetric)."""
    return tether.params.gamma > 0 and not tether.circulatory


def _bisect(line: Line, a: float, b: float, rtol: float) -> float:
    while b - a > rtol * abs(b):
        c = 0.5 * (a + b)
        if line.unstable(c):
            b = c
        else:
            a = c
    return b


def _middle(a: float, b: float) -> float:
    """The next point of a bisection of [a, b]: the geometric middle while b spans decades above a (a crossing of a
    damped tether may lie 1e-5 of the way along the line), the arithmetic one after."""
    floor = max(a, 1e-3 * b)
    return math.sqrt(floor * b) if b > 8.0 * floor else 0.5 * (a + b)


def _single(line: Line, a: float, b: float) -> tuple[float, float]:
    """[a, b] shrunk by bisection on stability until one eigenvalue (a real one, or one of a pair with Im > 0) is
    unstable at b and the bracket is narrower than :data:`NARROW` of b: then one crossing lies in it."""
    while True:
        lam = line.spectrum(b)
        lam = lam[lam.imag >= 0]
        if np.sum(lam.real - threshold(lam) > 0) <= 1 and b - a <= NARROW * abs(b) or b <= AT_ZERO * line.hi:
            return a, b
        c = _middle(a, b)
        if c in (a, b):
            return a, b
        if line.unstable(c):
            b = c
        else:
            a = c


def _behind(h, a: float, ha: float, b: float, lo: float) -> tuple[float, float]:
    """Where the crossing eigenvalue's real part is already positive at a, but below the threshold that counts it
    as unstable (a slow crossing), the point a moved back until it is negative: the crossing is where Re lambda
    = 0, not where the threshold is passed (1e-8 |lambda| of threshold on a slope of 1e-6 per unit load moves it
    by 1 %)."""
    step = b - a
    while ha >= 0 and a > lo:
        a = max(lo, a - step)
        ha = h(a)
        step *= 2.0
    return a, ha


def _memoised(h):
    """h with its values remembered: a function that tracks an eigenvalue depends on where it was tracked from, and
    the root finder evaluates the ends of its bracket again (a value of another sign there: no bracket)."""
    seen: dict[float, float] = {}

    def once(x: float) -> float:
        if x not in seen:
            seen[x] = h(x)
        return seen[x]
    return once


def _locate(line: Line, a: float, b: float, rtol: float) -> tuple[float, complex]:
    """The crossing between a (stable) and b (unstable), and its eigenvalue (just past it; 0 at a static point):
    a static point between points this close to it is the crossing (divergence). Where the crossing eigenvalue's
    real part is not negative anywhere back to the start of the line (where the scan found the tether stable: Re
    lambda within the threshold of 0 there), it leaves the axis at the start: an undamped spinning tether with a
    circulatory load, Re lambda growing in proportion to the load or the spin from 0 (docs/model.md, section 10),
    is unstable at any value above 0. The point where Re lambda passes the threshold is no crossing (it moves
    with the round-off of each mesh, and the meshes never agree on it)."""
    for r in (r for r in line.static_roots() if a < r <= b):
        if b - a <= 3 * PAST * r or not line.unstable(r * (1 - PAST)):
            return float(r), 0j  # a real eigenvalue through 0
        b = r * (1 - PAST)  # unstable before its first static point: a flutter point lies before it
        break
    a, b = _single(line, a, b)
    if b <= AT_ZERO * line.hi:  # unstable at any value above 0
        return b, _unstable_eigenvalue(line.spectrum(b))
    h = _memoised(_crossing_function(line, a, b))
    ha, hb = h(a), h(b)
    a, ha = _behind(h, a, ha, b, line.lo)
    if ha >= 0 and a <= line.lo:  # off the axis all the way back to the start: it leaves the axis there
        x = line.lo
    elif ha < 0 < hb:
        x = brentq(h, a, b, xtol=0.25 * rtol * abs(b), rtol=4 * np.finfo(float).eps, maxiter=100)
    else:  # no clean sign change of the smooth function: the stability predicate, bisected
        x = _bisect(line, a, b, rtol)
    if x <= AT_ZERO * line.hi:  # at the start: unstable at any value above it
        return min(b, AT_ZERO * line.hi), _unstable_eigenvalue(line.spectrum(b))
    past = min(x * (1 + 4 * rtol), b) if x > 0 else b
    lam = line.spectrum(past)
    if line.growth(past) > 0:
        return x, _unstable_eigenvalue(lam)
    # a slow crossing: just past it the crossing eigenvalue is off the axis by less than the threshold; it is the one
    # that continues the eigenvalue unstable at b (not the one nearest 0: another mode's frequency and shape)
    z = complex(_nearest(lam[lam.imag >= 0], _unstable_eigenvalue(line.spectrum(b)), 1)[0])
    return x, complex(z.real, abs(z.imag))


def _kind(z: complex) -> str:
    return CriticalKind.FLUTTER if abs(z.imag) > 1e-6 * max(1.0, abs(z)) else CriticalKind.DIVERGENCE


#: Most steps by which a bracket from another mesh is widened upwards until its end is unstable.
WIDEN = 6


def _widened(line: Line, near: tuple[float, float], lo: float, hi: float) -> tuple[float, float] | None:
    """The bracket ``near`` (from another mesh or a neighbouring tether) widened by its width either side, stable at
    its start and unstable at its end on this mesh: its end moved up by a width growing 8 times a step while stable
    there (a slow crossing, Re lambda of 1e-10 a little past it, is not yet counted as unstable), at most
    :data:`WIDEN` steps, never past a static point (a band of the upper half-plane sees the real eigenvalue it
    sends into Re lambda > 0 only just past it); None where it is unstable at its start or stays stable."""
    a, b = near
    width = max(b - a, 1e-6 * abs(b))
    a2, b2 = max(lo, a - width), min(hi, b + width)
    if line.unstable(a2):
        return None
    for _ in range(WIDEN):
        if line.unstable(b2) or np.any((line.static_roots() > a2) & (line.static_roots() <= b2)):
            return a2, b2  # a static point in it: the crossing, or unstable past it (_locate)
        if b2 >= hi:
            return None
        width *= 8.0
        a2, b2 = b2, min(hi, b2 + width)
    return None


def _first_static(line: Line):
    """:func:`_first` from 0 where stability changes only at static points (:func:`static_only`): unstable at 0
    where the stiffness is not positive there, else lost at the first static point (a simple root: one real
    eigenvalue through 0). At 0 the stiffness is positive (bending and tension) up to the first static point of the
    other axis from rest: a spin below the unloaded tether's first static spin (a line along the load), a load below
    the first static load at rest (a line along the spin), from one static pencil, not from the spectrum (a band of
    dozens of modes at the line's start, seconds where its far end reshapes them)."""
    if not _positive_at_start(line):
        return 0.0, 0j
    roots = line.static_roots()
    return (float(roots[0]), 0j) if roots.size else (None, None)


def _positive_at_start(line: Line) -> bool:
    """Whether the stiffness of a :func:`static_only` tether is positive at the start of its line (the other axis at
    its value, this one at 0): that value below the other axis's first static point at 0 here."""
    other = "omega" if line.axis == "B" else "B"
    value = abs(line.base[other])
    if value == 0.0:
        return True
    A, Nx = line.fam.static(other, **(line.base | {line.axis: 0.0, other: 0.0}))
    x = sparse_pencil_nearest(A, Nx, k=STATIC_ROOTS, shift=0.0, ordering=ORDER)
    x = x[np.abs(x.imag) <= 1e-8 * np.abs(x)].real
    first = np.sqrt(x[x > 0]) if other == "omega" else np.abs(x[x != 0])
    return bool(first.size == 0 or value < float(np.min(first)))


def _first(line: Line, lo: float, hi: float, rtol: float, near=None, hint=None):
    """The first crossing on one mesh: (value, eigenvalue), (lo, eigenvalue) when unstable at lo, or
    (None, None) when stable up to hi. ``near``: a bracket (a, b) from another mesh to start from; the crossing
    found from it is kept only when the tether is stable just below it on this mesh. ``hint``: (x, lambda), that
    crossing on the other mesh: a flutter eigenvalue crossing on its own is followed from it (:func:`_secant`)."""
    if hint is not None and near is not None and lo == 0 < hint[0] <= AT_ZERO * hi:
        # the other mesh: unstable at any value above 0 (its crossing eigenvalue off the axis from 0 on); so is this
        # one where it is stable at 0 and the same eigenvalue lies clearly off the axis where the other located it
        z = complex(_nearest(line.near(hint[0], hint[1]), hint[1], 1)[0])
        if line.growth(lo) <= 0 and z.real > 1e3 * np.finfo(float).eps * abs(z):
            return hint[0], complex(z.real, abs(z.imag))
    if static_only(line.tether) and lo == 0:
        return _first_static(line)
    if (hint is not None and near is not None and hint[0] > lo and not collides(line.tether)
            and _kind(hint[1]) == CriticalKind.FLUTTER):
        found = _secant(line, hint[0], hint[1], hi, rtol)
        if found is not None:
            return found
    bracket = None if near is None else _widened(line, near, lo, hi)
    if bracket is not None:
        a2, b2 = bracket
        x, z = _locate(line, a2, b2, rtol)
        below = x * (1 - 1e-6) if x > 0 else lo
        if x <= a2 or not line.unstable(below) or below <= lo:
            return x, z
    found = _scan(line, lo, hi, SCAN)
    if found is None:
        return None, None
    a, b = found
    if a == b:
        return a, _unstable_eigenvalue(line.spectrum(a))
    return _locate(line, a, b, rtol)


#: The first crossing found on each mesh, by how it was sought (from a bracket, or scanned from 0): a search repeated on
#: the same mesh (the verdict's crossing after the damping map's survey) reuses it. At most :data:`FOUND_SIZE`.
_FOUND: dict = {}
FOUND_SIZE = 64


def _first_on(line: Line, lo: float, hi: float, rtol: float, near, hint=None):
    """:func:`_first`, memoised in :data:`_FOUND` (a search from a bracket may reuse a scan's answer, the first
    crossing; a scan only a scan's)."""
    key = (line.tether, line.axis, line.N, lo, hi, rtol)
    for scanned in (True,) if near is None else (True, False):
        if key + (scanned,) in _FOUND:
            return _FOUND[key + (scanned,)]
    found = _first(line, lo, hi, rtol, near, hint)
    _remember(key + (near is None,), found)
    return found


def forget() -> None:
    """Empty the memo of crossings found (:data:`_FOUND`) and of the bands' frequencies: a benchmark's runs start
    from nothing."""
    _FOUND.clear()
    forget_bands()


def _remember(key: tuple, found) -> None:
    if len(_FOUND) >= FOUND_SIZE:
        _FOUND.pop(next(iter(_FOUND)))
    _FOUND[key] = found


#: Most secant steps of the continuation of a crossing to the next damping of a survey.
SECANT_STEPS = 12


def first_crossings(tether: Tether, param: str, values: tuple[float, ...], tol: float = 1e-8,
                    after: tuple[float, Crossing] | None = None, hi: float | None = None) -> list[Crossing]:
    """The first crossing along the load up to ``hi`` (default :func:`default_hi`) at each value of ``param``
    ("gamma": the Kelvin-Voigt damping of a damping map; "omega": the spin rows of a stability map), rising, on
    one mesh (N = LADDER[0]): as :func:`critical` with ``check=False`` at each. The first is searched for (or
    continued from ``after``: (value, crossing) at a smaller value, computed apart); each next one is continued
    from the last: the crossing eigenpair tracked (nonlinear inverse iteration) at the new value and its real part
    brought to 0 by secant steps along the load, kept where the tether is stable just below it on the mesh (as a
    search from a bracket); else searched from the last one's bracket. A survey's crossings carry no error estimate
    (error nan): a map's points, not a verdict."""
    if param not in ("gamma", "omega"):
        raise ValueError(f"param must be 'gamma' or 'omega', got {param!r}")
    hi = default_hi(tether, "B") if hi is None else float(hi)
    rtol = min(tol, 1e-6) * 1e-2
    out: list[Crossing] = []
    last, seed = None, None
    if after is not None:
        v, last = after
        seed = (_seed(tether.with_(**{param: v}), hi, last) if _positive(last) and last.kind == CriticalKind.FLUTTER
                else None)
    for v in values:
        t = tether.with_(**{param: v})
        c, seed = (None, None) if seed is None else _continued(t, hi, rtol, tol, seed)
        if c is None:
            near = None if last is None or not _positive(last) else (0.8 * last.value, 1.25 * last.value)
            c = critical(t, hi=hi, tol=tol, near=near, mode=False, check=False, estimate=False)
            seed = _seed(t, hi, c) if _positive(c) and c.kind == CriticalKind.FLUTTER else None
        out.append(c)
        last = c
    return out


def _positive(c: Crossing) -> bool:
    return CriticalKind(c.kind).located and c.value > 0


def _seed(t: Tether, hi: float, c: Crossing) -> tuple[float, complex, np.ndarray] | None:
    """(x, lambda, y): the crossing eigenpair of ``c`` on the survey's mesh."""
    try:
        line = Line(t, "B", LADDER[0], hi)
        lam = line.track(c.value, c.eigenvalue)
    except NotLocated:
        return None
    return line.tracked[-1] if abs(lam - c.eigenvalue) <= 1e-6 * (1 + abs(lam)) else None


def _continued(t: Tether, hi: float, rtol: float, tol: float, seed) -> tuple[Crossing | None, tuple | None]:
    """The crossing of ``t`` continued from ``seed`` (another damping's crossing eigenpair on the same mesh) and its
    own eigenpair, or (None, None) where :func:`_secant` finds none."""
    line = Line(t, "B", LADDER[0], hi)
    line.tracked = [seed]
    found = _secant(line, seed[0], seed[1], hi, rtol)
    if found is None:
        return None, None
    _remember((t, "B", line.N, 0.0, hi, rtol, False), found)
    x, z = found
    return _crossing(line, "B", x, x, z, 0.0, hi, line.N, tol, rtol, False, estimate=False), line.tracked[-1]


def _secant(line: Line, x: float, z: complex, hi: float, rtol: float) -> tuple[float, complex] | None:
    """The crossing near x of the eigenvalue near z (a flutter eigenvalue crossing from the left half-plane, from
    another mesh or damping): tracked along the line (from ``line.tracked``, else found near z) and its real part
    brought to 0 by secant steps, at most :data:`SECANT_STEPS`; None where they do not converge, where Re lambda does
    not grow along the line, or where the tether is unstable just below the point found."""
    x0, x1 = x, x * (1 + 1e-4)
    h0 = line.track(x0, z).real
    h1 = line.track(x1, z).real
    if h1 <= h0:  # Re lambda does not grow along the line here: not this crossing
        return None
    for _ in range(SECANT_STEPS):
        if h1 == h0:
            return None
        x0, h0, x1 = x1, h1, x1 - h1 * (x1 - x0) / (h1 - h0)
        if not 0 < x1 <= hi:
            return None
        lam = line.track(x1, complex(0.0, z.imag))
        h1 = lam.real
        if abs(x1 - x0) <= rtol * x1:
            break
    else:
        return None
    if _kind(lam) != CriticalKind.FLUTTER or line.unstable(x1 * (1 - 1e-6)):
        return None
    return float(x1), complex(lam.real, abs(lam.imag))


@single_blas_thread
def critical(tether: Tether, axis: str = "B", hi: float | None = None, tol: float = 1e-8,
             ladder: tuple[int, ...] = LADDER, mode: bool = True, near: tuple[float, float] | None = None,
             check: bool = True, hint: tuple[float, complex] | None = None, estimate: bool = True) -> Crossing:
    """The first loss of stability of the straight tether with profiles along ``axis`` ("B" or "omega"),
    from 0 to ``hi`` (default: :func:`default_hi`), the others fixed at ``tether.params``; dimensionless.

    Scanned and located on the mesh of middle resolution N, located again on the finer check mesh
    (:func:`~etcheck.rod.straight.varying.profiles.check_resolution`), climbing ``ladder`` until the two agree to
    ``tol`` (relative); the error is their distance plus the root finder's tolerance. ``near``: where a crossing
    is expected (a bracket, from a neighbouring tether): sought there first, and kept only where the tether is
    stable just below it; else the line is scanned from 0. ``check=False``: the first mesh alone (no error
    estimate from a second one: a survey, such as the points of a damping map, not a verdict). ``hint``: with
    ``near``, the crossing (value, eigenvalue) found there on the first mesh (a survey's): a flutter eigenvalue
    crossing on its own is followed from it first. ``estimate=False`` (with ``check=False``): not even the
    round-off of the one mesh is estimated (error nan: a survey's point).

    The line is searched in stages (:func:`stages`), each from 0 to its end with the band of modes that end
    reshapes, so that a crossing near the expected value is found without the modes of a far end. Every solve
    and loop is bounded: a search that exceeds a bound is reported as not located, with the reason."""
    if axis not in ("B", "omega"):
        raise ValueError(f"axis must be 'B' or 'omega', got {axis!r}")
    hi = default_hi(tether, axis) if hi is None else float(hi)
    try:
        for end in stages(tether, axis, hi):
            c = _ladder(tether, axis, end, tol, ladder, mode, near, check, hint, estimate)
            if c.kind != CriticalKind.NONE_FOUND:
                return c
            near = hint = None
        return c
    except NotLocated as err:
        return Crossing(axis, math.nan, CriticalKind.NOT_LOCATED, complex(math.nan), math.nan, False, 0.0, hi,
                        ladder[0], ladder[0], f"not located: {err} ({MODEL})")
    except (RuntimeError, ValueError, ArithmeticError) as err:  # a solver that failed (SuperLU, ARPACK, Brent)
        return Crossing(axis, math.nan, CriticalKind.NOT_LOCATED, complex(math.nan), math.nan, False, 0.0, hi,
                        ladder[0], ladder[0], f"not located: a solver failed ({type(err).__name__}: {err}; {MODEL})")


def _ladder(tether: Tether, axis: str, hi: float, tol: float, ladder: tuple[int, ...], mode: bool,
            near: tuple[float, float] | None, check: bool, hint: tuple[float, complex] | None = None,
            estimate: bool = True) -> Crossing:
    """:func:`critical` on [0, hi] (one stage)."""
    lo = 0.0
    rtol = min(tol, 1e-6) * 1e-2
    noise = None
    for N in ladder:
        M = check_resolution(N)
        line = Line(tether, axis, N, hi)
        if not (line.resolved or static_only(tether) or N == ladder[-1]):
            continue  # a finer mesh first: this one's top modes would collide spuriously
        x1, z1 = _first_on(line, lo, hi, rtol, near, hint if N == ladder[0] else None)
        if not check:
            M, x2, z2 = N, x1, z1
            break
        bracket = None if x1 is None else (x1 * (1 - 1e-3), x1 * (1 + 1e-3) + 1e-12 * hi)
        x2, z2 = _first_on(Line(tether, axis, M, hi), lo, hi, rtol, bracket, None if x1 is None else (x1, z1))
        if x1 is None and x2 is None:
            return Crossing(axis, math.nan, CriticalKind.NONE_FOUND, complex(math.nan), math.nan, True, lo, hi, N, M,
                            f"stable on the scanned range {axis} in [{lo:g}, {hi:g}] ({MODEL}, N = {N} and {M})")
        if x1 is not None and x2 is not None:
            if abs(x1 - x2) + rtol * abs(x2) <= tol * abs(x2) or max(x1, x2) <= AT_ZERO * hi:  # the meshes agree
                break
            if noise is None:
                noise = _roundoff(line, x1, z1) if x1 > lo else 0.0
            if abs(x1 - x2) <= NOISE * noise:  # they differ by round-off: finer meshes would not agree better
                break
            near = (min(x1, x2), max(x1, x2))
    if x1 is None or x2 is None:
        return Crossing(axis, math.nan, CriticalKind.NOT_LOCATED, complex(math.nan), math.nan, False, lo, hi, N, M,
                        f"the meshes N = {N} and {M} disagree on whether the tether loses stability up to "
                        f"{axis} = {hi:g} ({MODEL})")
    return _crossing(line, axis, x1, x2, z2, lo, hi, M, tol, rtol, mode, noise, estimate)


def critical_spin(tether: Tether, tol: float = 1e-8) -> Crossing:
    """The first loss of stability as the spin grows at the tether's load, as :func:`critical` along "omega";
    except for an undamped isotropic tether (R = 1) with a conservative load (one current) below its static load at
    rest, which is stable at every spin (docs/model.md §6: its gyroscopic pencil is hyperbolic, whatever the
    self-adjoint stiffness, a tension along the tether included); its double static points along the spin line
    would otherwise read as crossings."""
    p = tether.params
    if p.R == 1.0 and p.gamma == 0 and not tether.circulatory and p.B > 0:
        rest = critical(tether.with_(omega=0.0), tol=tol, mode=False)
        if rest.kind == CriticalKind.DIVERGENCE and p.B < rest.value * (1 - rest.error / max(rest.value, 1e-300)):
            hi = default_hi(tether, "omega")
            return Crossing("omega", math.nan, CriticalKind.NEVER, complex(math.nan), math.nan, True, 0.0, hi,
                            rest.N, rest.N_check,
                            f"stable at every spin: below its static load at rest (B = {rest.value:.9g}) no spin can "
                            f"destabilise an undamped isotropic tether (its gyroscopic pencil is hyperbolic; {MODEL})")
    return critical(tether, "omega", tol=tol, mode=False)


def _roundoff(line: Line, x: float, z: complex) -> float:
    """How far the round-off of the crossing eigenvalue's real part moves a crossing that it makes on its own
    (not a collision, not a static point): that round-off (the spread of Re lambda computed from two shifts)
    over the slope of Re lambda along the line. A weakly damped flutter crosses the axis slowly (Re lambda
    changing by 1e-4 per unit load), and 1e-10 of round-off then moves it by 1e-6."""
    if collides(line.tether) or z.imag == 0 or x <= 0:
        return 0.0
    d = 1e-4 * x
    re = [_nearest(line.near(x + dx, z), z, 1)[0].real for dx in (-d, d)]
    slope = abs(re[1] - re[0]) / (2 * d)
    other = _nearest(line.near(x, z * (1 + 1e-2)), z, 1)[0].real
    noise = abs(other - 0.5 * (re[0] + re[1])) + 1e-14 * abs(z)
    return noise / slope if slope > 0 else math.inf


def _crossing(line, axis, x1, x2, z2, lo, hi, M, tol, rtol, mode, noise=None, estimate=True) -> Crossing:
    N = line.N
    zero = max(x1, x2) <= AT_ZERO * hi
    if noise is None:
        noise = 0.0 if zero or x1 == x2 == lo else _roundoff(line, x1, z2) if estimate else math.nan
    err = abs(x1 - x2) + rtol * abs(x2) + noise
    kind = _kind(z2)
    if x1 == x2 == lo:
        return Crossing(axis, lo, CriticalKind.UNSTABLE_AT_START, z2, 0.0, True, lo, hi, N, M,
                        f"already unstable at {axis} = {lo:g} ({MODEL})")
    at = f" at frequency Im lambda = {abs(z2.imag):.9g}" if kind == CriticalKind.FLUTTER else ""
    if zero:
        what = "a double frequency" if axis == "B" and line.tether.params.omega == 0 else "a frequency of the spinning tether"
        msg = (f"unstable at any {axis} > 0: {kind}{at} from {axis} = 0 on, the circulatory load moving {what} off the "
               f"imaginary axis in proportion to {axis} ({MODEL})")
    else:
        how = f"meshes N = {N} and {M}" if M != N else f"one mesh, N = {N}: round-off only, no second mesh"
        msg = (f"first instability at {axis} = {x2:.12g} ({kind}{at}; {MODEL}); " +
               (f"error estimate {err:.2e} ({how})" if estimate else f"one mesh, N = {N}, no error estimate (a survey)"))
    converged = zero or not estimate or bool(err <= tol * abs(x2))
    shape = _mode(line, x2 * (1 + 8 * rtol) if not zero else AT_ZERO * hi, z2) if mode else None
    return Crossing(axis, 0.0 if zero else x2, kind, z2, 0.0 if zero else err, converged, lo, hi, N, M, msg, shape)


def crossing_mode(tether: Tether, c: Crossing) -> Crossing:
    """The crossing with its mode (:attr:`Crossing.mode`), on the finer of its two meshes, where it was located
    without one (none where the solvers could not give it)."""
    if c.mode is not None or not CriticalKind(c.kind).located:
        return c
    x = c.value * (1 + 1e-8) if c.value > 0 else AT_ZERO * c.hi
    try:
        return replace(c, mode=_mode(Line(tether, c.axis, c.N_check, c.hi), x, c.eigenvalue))
    except (NotLocated, RuntimeError, ValueError, ArithmeticError):
        return c


def _mode(line: Line, x: float, z: complex):
    """(s, u, v) of the eigenvector nearest z at x on a uniform grid of 201 points, complex, scaled so that the
    larger of |u|, |v| peaks at 1 with zero phase there."""
    A = line.fam.operator(**line.point(x))
    lam, Y = sparse_qep_nearest(*A, k=2, sigma=z + 1e-7 * (1 + abs(z)), vectors=True, scale=line.scale,
                                ordering=ORDER, maxiter=RESTARTS)
    if lam.size == 0:  # the solver did not converge: no mode to draw
        return None
    s, u, v = line.fam.field_values(Y[:, int(np.argmin(np.abs(lam - z)))], 201)
    k = int(np.argmax(np.maximum(np.abs(u), np.abs(v))))
    peak = u[k] if abs(u[k]) >= abs(v[k]) else v[k]
    return s, u / peak, v / peak
