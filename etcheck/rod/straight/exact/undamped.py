"""Rung 1u: critical load, critical spin and the stable spin windows of the undamped
straight tether at an operating point (gamma = 0; paper Sec. VI, eq. (86) with lambda != 0;
docs/model.md sections 6 and 8), from the stability lines of
:mod:`etcheck.rod.straight.exact.undamped_lines` and the static roots of the exact determinant.
An isotropic tether (R = 1) goes through :mod:`etcheck.rod.straight.exact.undamped_isotropic`.

Dimensionless and pure; numpy/scipy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.spectral import CriticalKind, CriticalPoint
from etcheck.rod.straight.exact import roots as exact
from etcheck.rod.straight.exact.undamped_kernel import (
    CUT_SAMPLES,
    MAX_GRID,
    MODEL,
    characteristic_mu,
    rayleigh_floor,
    stiffness_definite,
)
from etcheck.rod.straight.exact.undamped_lines import (
    Crossing,
    Line,
    StabilityLine,
    close_pairs,
    dips,
    pair_count,
    stability_line,
    static_roots,
)
from etcheck.runtime.blas import single_blas_thread
from etcheck.runtime.parallel import can_split, split_map

__all__ = [
    "MODEL",
    "complex_pairs",
    "complex_pairs_on_line",
    "has_real_pair",
    "undamped_critical",
    "UndampedCritical",
]



@dataclass(frozen=True)
class UndampedCritical:
    """Critical values of the undamped straight rod at one operating point (dimensionless).

    ``critical_load``: first loss of stability as B grows from 0 at the
    operating omega and T; ``critical_spin``: as omega grows from 0 at the
    operating B and T (both :class:`~etcheck.rod.straight.collocation.spectral.CriticalPoint`,
    absolute errors, N = 0: no grid); ``windows``: the stable spin
    intervals at the operating load up to ``scanned_to``; ``stable``: the
    operating point itself; ``evaluations``: characteristic-function
    evaluations spent.
    """

    critical_load: CriticalPoint
    critical_spin: CriticalPoint
    windows: tuple[tuple[float, float], ...]
    scanned_to: float
    stable: bool
    evaluations: int

    @property
    def converged(self) -> bool:
        return self.critical_load.converged and self.critical_spin.converged


def _spin_hi(r: np.ndarray) -> float:
    """End of the spin line (as the spectral scan's default) from the static spins r of the rod:
    max(2, 1.25 x the second)."""
    return float(max(2.0, 1.25 * r[1])) if r.size >= 2 else 2.0


def _point(line: StabilityLine, tol: float) -> CriticalPoint:
    """The first loss of stability on a line as a CriticalPoint (value, kind, absolute error)."""
    axis, lo, hi = line.axis, line.lo, line.hi
    if line.unstable_at_start:
        return CriticalPoint(axis, lo, CriticalKind.UNSTABLE_AT_START, (lo, lo), 0.0, True,
                             f"already unstable at {axis} = {lo:g} ({MODEL})", 0)
    first = next((c for c in line.crossings if c.to_unstable), None)
    if first is None:
        return CriticalPoint(axis, math.nan, CriticalKind.NONE_FOUND, (lo, hi), math.nan, False,
                             f"stable on the scanned range {axis} in [{lo:g}, {hi:g}] ({MODEL})", 0)
    conv = bool(math.isfinite(first.error) and first.error <= tol * max(abs(first.value), 1e-3))
    at = f" at Omega = {first.frequency:.9g}" if first.kind == CriticalKind.FLUTTER else ""
    msg = (f"first instability at {axis} = {first.value:.12g} ({first.kind}{at}; {MODEL}); "
           f"error estimate {first.error:.2e} (two formulations)")
    return CriticalPoint(axis, first.value, first.kind, (first.value, first.value), first.error, conv, msg, 0)


@single_blas_thread
def undamped_critical(params: RodParameters, tol: float = 1e-8, windows: bool = True,
                      spin: bool = True) -> UndampedCritical:
    """Critical load, critical spin, stable spin windows and stability of the undamped straight rod.

    Dimensionless; gamma is ignored (undamped). Three lines of
    :func:`stability_line`: the spin line of the unloaded rod up to the
    operating spin (it anchors the next one: complex pairs at (0, omega)),
    the load line at the operating spin from 0 to just past its first
    static point (stable before it means unstable past it: a root mu goes
    negative), and the spin line at the operating load from 0 (self-adjoint
    there) to max(2, 1.25 x its second static point, 1.1 x the operating
    spin) with ``windows``, else to just past its first static point and
    the operating spin. Same shapes as the spectral scans of
    :mod:`etcheck.rod.straight.collocation.spectral` (critical_load, scan_line); errors are
    absolute, from a second formulation of E; ``tol`` is relative.
    ``spin=False`` (with B > 0) skips the spin line at the operating load: the critical spin is not asked
    (NaN) and the operating point is judged on the load line (stable iff below its first instability).
    """
    p = params.with_(gamma=0.0)
    if p.R == 1.0:
        return _isotropic(p, tol, windows, spin)
    if not spin and p.B > 0:
        return _load_only(p, tol)
    # the spin line and what the load line needs are independent: on two cores a forked helper follows the load
    # line meanwhile (pure work; in a sweep worker or on one core only where it is needed, after the spin line)
    jobs = [lambda: _spin_line(p, _spin_end(p, windows), windows), lambda: _load_part(p)]
    (spin_line, why), *ahead = split_map(lambda job: job(), jobs) if can_split() else [jobs[0]()]
    if spin_line is None:  # no spin: the load decides (self-adjoint); the critical spin is not answered
        return _without_spin(p, tol, why)
    stable, spent = _operating_stable(p, spin_line)
    evaluations = spin_line.evaluations + spent
    load_part = ahead[0] if ahead else _load_part(p)
    if isinstance(load_part, Exception):
        raise load_part
    if load_part is None:  # the unloaded rod already has a real pair at this spin
        load = CriticalPoint("B", 0.0, CriticalKind.UNSTABLE_AT_START, (0.0, 0.0), 0.0, True,
                             f"already unstable at B = 0: a real pair of eigenvalues ({MODEL})", 0)
        return UndampedCritical(load, _point(spin_line, tol), spin_line.windows, spin_line.hi, stable, evaluations)
    static, followed = load_part
    if followed is None:  # not gyroscopic (w = 0): K q = mu M q, stable exactly below the first static load
        return UndampedCritical(_point(_static_line(static), tol), _point(spin_line, tol), spin_line.windows,
                                spin_line.hi, stable, evaluations + static.evaluations)
    load_line, spent = followed
    return UndampedCritical(_point(load_line, tol), _point(spin_line, tol), spin_line.windows, spin_line.hi, stable,
                            evaluations + spent)


def _spin_end(p: RodParameters, windows: bool) -> float:
    """End of the spin line at the operating load (R < 1): just past the first static spin, or with ``windows``
    as far as :func:`_spin_hi` unless that would cost more than :data:`MAX_GRID` samples per point."""
    if windows:  # most lines end at 2: then the line's own scan of its static spins tells (memoised for it)
        near = static_roots(p, "omega", 2.0)
        if near.size >= 2 and 1.25 * near[1] <= 2.0 and Line(p, "omega", 0.0, 2.0).mu.size <= MAX_GRID:
            return 2.0
    first = static_roots(p, "omega", max(8.0 * exact.root_scale(p, "omega", 1.0), 4.0))
    short = max(1.02 * first[0] if first.size else 2.0, 1e-3)  # stable at rest: unstable past the first static spin
    if not windows:
        return short
    spin_hi = _spin_hi(first)
    # windows past the first static spin would cost too many samples: not sought
    return short if Line(p, "omega", 0.0, spin_hi).mu.size > MAX_GRID else spin_hi


def _operating_stable(p: RodParameters, spin_line: StabilityLine) -> tuple[bool, int]:
    """Whether the operating point is stable, from the spin line at the operating load where it reaches the
    operating spin, else from the complex pairs there; and the evaluations that took beyond the line's."""
    if p.omega <= spin_line.hi:
        return not spin_line.unstable_at(p.omega), 0
    if has_real_pair(p):  # a real pair of eigenvalues: unstable whatever the complex ones do
        return False, 0
    pairs, real, spent = complex_pairs(p)
    return pairs == 0 and not real, spent


def _load_part(p: RodParameters):
    """What :func:`undamped_critical` needs for the critical load, independent of the spin line: None when the
    unloaded rod has a real pair at the operating spin (unstable at B = 0), else (the first static load at B = 0,
    the load line with its evaluations, or None without spin); an error met on the way is returned, to be raised
    only where the result is used."""
    try:
        if p.omega > 0 and has_real_pair(p.with_(B=0.0)):
            return None
        static = exact.exact_root(p.with_(B=0.0), "B")
        return static, (_load_line(p, static) if p.omega != 0 else None)
    except (ArithmeticError, ValueError) as exc:
        return exc


def _at_rest(p: RodParameters):
    """The first static load of the rod at rest (omega = 0, ExactRoot): for R = 1 the undamped rod is stable at
    every spin below it (:mod:`etcheck.rod.straight.exact.undamped_isotropic`: a hyperbolic pencil)."""
    return exact.exact_root(p.with_(B=0.0, omega=0.0), "B")


def _isotropic(p: RodParameters, tol: float, windows: bool, spin: bool) -> UndampedCritical:
    """:func:`undamped_critical` for R = 1 on the lines of D+ (roots that never touch), with the bound of
    :mod:`etcheck.rod.straight.exact.undamped_isotropic`: below the static load at rest B_s the rod is stable at every spin,
    so only loads past B_s (and spins at such loads) are followed."""
    if p.T <= -p.ends.euler_load / p.f:  # the Euler load: K_B is not positive at B = 0
        raise ArithmeticError("R = 1 compressed past its Euler load: the undamped isotropic lines need "
                              "a rod stable at rest")
    rest = _at_rest(p)
    below = p.B < rest.value
    w = p.omega
    if w == 0:
        static = rest
        load_line, spent = _static_line(static), static.evaluations
    else:
        scale = exact.root_scale(p, "B", 1.0)
        roots = static_roots(p, "B", 16 * scale)
        load_hi = 1.1 * roots[2] if roots.size >= 3 else 2.0 * roots[-1] if roots.size else 16 * scale
        # stable (every root real) up to B_s: the line starts short of it, where no two roots are close
        lo = 0.98 * rest.value
        load_line = replace(stability_line(p, "B", lo, max(load_hi, 1.25 * rest.value)), lo=0.0)
        early = [c for c in load_line.crossings if c.value + c.error < rest.value * (1 - 1e-12)]
        if early:  # the hyperbolic bound says otherwise: the line's root counts are wrong (a dense spectrum)
            raise ArithmeticError(f"a change of stability at B = {early[0].value:.12g}, below the static load at "
                                  f"rest {rest.value:.12g}, where none can be: the root counts are not resolved")
        spent = rest.evaluations + load_line.evaluations
    load = _point(load_line, tol)
    if below:
        stable = True
    elif w == 0:
        stable = False  # past the static load at rest: a real pair of eigenvalues
    elif p.B <= load_line.hi:
        stable = not load_line.unstable_at(p.B)
    else:
        stable = None
    if not spin and p.B > 0 and stable is not None:
        none = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, True,
                             "critical spin not asked", 0)
        return UndampedCritical(load, none, (), 0.0, stable, spent)
    first = static_roots(p, "omega", max(8.0 * exact.root_scale(p, "omega", 1.0), 4.0))
    spin_hi = max(_spin_hi(first), 1.1 * w)
    if below:  # stable at every spin: nothing to follow
        point = CriticalPoint("omega", math.nan, CriticalKind.NEVER, (0.0, spin_hi), math.nan, True,
                              "stable at every spin: below its static buckling load at rest no spin can destabilise an "
                              f"undamped isotropic tether (its gyroscopic pencil is hyperbolic; {MODEL})", 0)
        return UndampedCritical(load, point, ((0.0, spin_hi),), spin_hi, True, spent)
    pairs = int(static_roots(p.with_(omega=0.0), "B", p.B).size)  # real pairs at rest: one per static load below B
    hi = spin_hi if windows else max(1.02 * w, 1e-3)
    spin_line = stability_line(p, "omega", 0.0, hi, pairs=pairs, samples=64 if windows else 25)
    if stable is None:
        stable = not spin_line.unstable_at(w)
    return UndampedCritical(load, _point(spin_line, tol), spin_line.windows, spin_line.hi, stable,
                            spent + spin_line.evaluations)


def complex_pairs(params: RodParameters) -> tuple[int, bool, int]:
    """(complex pairs of roots mu at params, whether it has a real pair (a root mu < 0), evaluations spent):
    the spin line from omega = 0 (self-adjoint: every root real) without locating anything on it, only the
    real roots at both ends and the roots that pass its cut in between (E at the cut on as many points as a
    line of 25 samples has). None of it where the stiffness is proven positive (:func:`stiffness_positive`:
    every root real and positive)."""
    if stiffness_definite(params):
        return 0, False, 0
    return complex_pairs_on_line(params.with_(gamma=0.0))


@lru_cache(maxsize=256)
def complex_pairs_on_line(params: RodParameters) -> tuple[int, bool, int]:
    """:func:`complex_pairs` counted along the spin line even where the stiffness is proven positive
    (``params`` with gamma = 0; memoised)."""
    line = Line(params.with_(omega=0.0), "omega", 0.0, params.omega)
    if line.mu.size > MAX_GRID:
        raise ArithmeticError(f"the omega line to {params.omega:.6g} needs {line.mu.size} mu samples per point "
                              f"(more than {MAX_GRID}: too many modes below its cut)")
    a, b = line.samples([0.0, params.omega])
    N = a.n_neg + a.n_pos + line.cut_crossing(a, b, samples=24 * (CUT_SAMPLES - 1) + 1)
    return pair_count(b, N), b.n_neg > 0, line.evaluations


def _load_line(p: RodParameters, static) -> tuple[StabilityLine, int]:
    """The load line at the operating spin (w > 0) from 0 to just past its first static point (R = 1: past the
    third, double static points do not end stability), anchored by the complex pairs of the unloaded rod (:func:`complex_pairs`); and the
    evaluations spent, ``static`` (the first static load at the operating spin) included."""
    pairs, _, spent = complex_pairs(p.with_(B=0.0))
    if pairs:  # flutter without load: unstable from the start of the line, nothing to locate on it
        return StabilityLine("B", 0.0, 0.0, True, (), (), pairs, spent), spent + static.evaluations
    scale = exact.root_scale(p, "B", 1.0)
    load_hi = max(1.02 * static.value, 1e-3 * scale) if math.isfinite(static.value) else 16 * scale
    if p.R == 1.0:  # double static points do not end stability: as far as the spectral scan's default
        roots = static_roots(p, "B", 16 * scale)
        load_hi = 1.1 * roots[2] if roots.size >= 3 else 2.0 * roots[-1] if roots.size else load_hi
    line = stability_line(p, "B", 0.0, load_hi, pairs=pairs)
    return line, spent + line.evaluations + static.evaluations


def _load_only(p: RodParameters, tol: float) -> UndampedCritical:
    """The critical load alone (B > 0): the operating point is stable iff B lies below it."""
    none = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, True,
                         "critical spin not asked", 0)
    static = exact.exact_root(p.with_(B=0.0), "B")
    if p.omega == 0:
        load = _point(_static_line(static), tol)
        return UndampedCritical(load, none, (), 0.0, p.B < load.value, static.evaluations)
    if has_real_pair(p.with_(B=0.0)):
        load = CriticalPoint("B", 0.0, CriticalKind.UNSTABLE_AT_START, (0.0, 0.0), 0.0, True,
                             f"already unstable at B = 0: a real pair of eigenvalues ({MODEL})", 0)
        return UndampedCritical(load, none, (), 0.0, False, 0)
    line, spent = _load_line(p, static)
    load = _point(line, tol)
    return UndampedCritical(load, none, (), 0.0, not line.unstable_at(p.B) if p.B <= line.hi else False, spent)


def _spin_line(p: RodParameters, spin_hi: float, windows: bool) -> tuple[StabilityLine | None, str]:
    """The spin line at the operating load from 0 to spin_hi (unstable from the start, not followed, when the
    rod has a real pair at rest and no windows are asked); (None, why) without spin where it cannot be drawn."""
    at_rest = p.with_(B=0.0, omega=0.0)  # stable at rest iff B is below its first static load (T >= 0)
    # below it, without compression, the stiffness is positive definite at rest: no real pair there (for real
    # lambda and real q, q^T (lambda^2 M + lambda G + K) q = lambda^2 q^T M q + q^T K q > 0)
    if not windows and (p.B >= exact.exact_root(at_rest, "B").value or (p.T < 0 and has_real_pair(p.with_(omega=0.0)))):
        return StabilityLine("omega", 0.0, 0.0, True, (), (), 0, 0), ""
    try:
        return stability_line(p, "omega", 0.0, spin_hi, samples=64 if windows else 25), ""
    except ArithmeticError as exc:
        if p.omega != 0:
            raise
        return None, str(exc)


def _static_line(static) -> StabilityLine:
    """The load line of a rod without spin: stable exactly below its first static load."""
    crossings = () if math.isinf(static.value) else (
        Crossing(static.value, static.error * static.value, CriticalKind.DIVERGENCE, 0.0, True,
                 (static.value, static.value)),)
    return StabilityLine("B", 0.0, static.value, False, crossings, (), 0, static.evaluations)


def _without_spin(p: RodParameters, tol: float, why: str) -> UndampedCritical:
    """Critical load of a rod without spin (its first static load) when the spin line cannot be drawn:
    the critical spin is "not located", with the reason."""
    static = exact.exact_root(p.with_(B=0.0), "B")
    spin = CriticalPoint("omega", math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, False,
                         f"critical spin not answered ({MODEL}): {why}", 0)
    return UndampedCritical(_point(_static_line(static), tol), spin, (), 0.0, not has_real_pair(p), static.evaluations)


def has_real_pair(params: RodParameters, n: int = 64) -> bool:
    """True when E has a real root mu < 0 at params (a real pair of eigenvalues: unstable), from sign
    changes on n points between the Rayleigh floor and 0 and close pairs at the dips of |E| between them (as a
    line's samples); False when none shows (not a proof). False by a proof
    where the stiffness is proven positive (:func:`stiffness_positive`) and, for R = 1 (short of the
    Euler compression), below the static load at rest (:mod:`etcheck.rod.straight.exact.undamped_isotropic`)."""
    if stiffness_definite(params):
        return False
    if params.R == 1.0 and params.T > -params.ends.euler_load / params.f and params.B < _at_rest(params).value:
        return False
    mu_lo = rayleigh_floor(params, params.B, params.omega, params.T)
    mu = -np.linspace(math.sqrt(-mu_lo), 0.0, n + 1) ** 2
    ends = characteristic_mu(params, mu[[0, -1]])
    if np.sign(ends[0]) * np.sign(ends[1]) < 0:  # an odd number of roots between: the scan would see a change
        return True
    E = np.concatenate([ends[:1], characteristic_mu(params, mu[1:-1]), ends[1:]])
    if np.any(np.sign(E[:-1]) * np.sign(E[1:]) < 0):
        return True
    # a close pair between two samples (R near 1 past its first static load: the u and v modes) shows as a dip
    found = close_pairs(lambda _, x: characteristic_mu(params, x), np.zeros(1), dips(0, mu, E))
    return any(r[0] < 0 for _, r in found)
