"""Rung 1 for a mission: buckling and whirl of the straight tether with spin,
end tension and damping, in the numbers the report shows.

Everything is solved dimensionless in :mod:`etcheck.rod.straight.collocation.spectral` and
:mod:`etcheck.rod.core.spectrum`; this module chooses what to ask (the operating
point, the critical load at the operating spin, the critical spin at the
operating load, the Campbell diagram and the stability map of the
(I·B0, spin rate) plane) and converts the answers to SI with the mission's
:class:`~etcheck.scaling.Scales`. A critical value whose error estimate
misses the tolerance is reported with that estimate (its margin is judged on
the pessimistic side and says so), and as "not located" when the estimate
exceeds :data:`REPORTABLE` (the margin is then incomplete): the check never
stops on a hard root.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from etcheck.checks.plan import EXACT, SPECTRAL
from etcheck.checks.results.sections import SkippedPart
from etcheck.checks.results.sections_straight import (
    AccuracyRow,
    Campbell,
    CriticalLoad,
    CriticalPoint,
    CriticalSpin,
    LinearSection,
    Mode,
    OperatingPoint,
    OperatingSpectrum,
    SpinWindow,
    StabilityMap,
    StableRow,
    StaticPoints,
)
from etcheck.jsonable import fields_of, finite_or_none
from etcheck.rod.core.spectrum import spectrum
from etcheck.rod.straight.analytic import critical_loads
from etcheck.rod.straight.collocation.convergence import accuracy_table, reference_resolution
from etcheck.rod.straight.collocation.damped_critical import DRAFT_LADDER, LADDER
from etcheck.rod.straight.collocation.spectral import (
    THRESHOLD,
    CriticalKind,
    campbell,
    critical_load,
    scan_line,
    stability_map,
)
from etcheck.rod.straight.collocation.spectral import CriticalPoint as StabilityPoint
from etcheck.rod.straight.collocation.static_map import stable_rows, static_curves
from etcheck.rod.straight.exact.roots import exact_critical, first_exact_root, pencil_or_exact
from etcheck.rod.straight.exact.undamped import undamped_critical
from etcheck.runtime.memory import OverBudget
from etcheck.runtime.parallel import split_map
from etcheck.runtime.timelimit import OutOfTime, within
from etcheck.scaling import Scaled, Scales


@dataclass(frozen=True)
class WhirlOptions:
    """Resolution of the rung-1 answers (all dimensionless settings).

    ``tol``: tolerance of critical loads and spins; ``eig_tol``: two-resolution
    agreement required of the operating spectrum; ``N``: fixed Chebyshev
    resolution (None: chosen to meet eig_tol); ``k``: eigenvalue pairs;
    ``map_points``: grid of the stability map per axis; ``row_points``: spins
    at which the damped map is cut exactly at its static points; ``campbell_points``:
    spin values of the Campbell diagram; ``accuracy_N``: resolutions of the
    accuracy table (empty: skip it); ``accuracy_beside``: the table computed by a
    forked helper while the spectra are computed here (where a core is free: its
    solves are timed, and read up to twice as long beside other work, such as
    the CLI's report process loading the report stack); ``draft``: critical
    values and verdict only; ``time_budget``: seconds after which a sign-off
    skips what it has not computed of the report's extras (the operating
    spectrum, Campbell diagram, stability map, accuracy table), saying so
    (None: no limit; the CLI's default is
    :data:`etcheck.checks.fidelity.TIME_BUDGET`). The margins
    are always answered.
    """

    tol: float = 1e-10
    eig_tol: float = 1e-8
    N: int | None = None
    k: int = 10
    map_points: int = 20
    row_points: int = 61
    campbell_points: int = 41
    accuracy_N: tuple[int, ...] = (8, 12, 16, 24, 32)
    accuracy_beside: bool = True
    draft: bool = False
    time_budget: float | None = None

    def __post_init__(self) -> None:
        if not (0 < self.tol < 1e-2 and 0 < self.eig_tol < 1e-2):
            raise ValueError("tolerances must lie in (0, 1e-2)")
        if self.k < 1 or min(self.map_points, self.row_points, self.campbell_points) < 4:
            raise ValueError("k >= 1 and at least 4 map, row and Campbell points are required")


DEFAULT_OPTIONS = WhirlOptions()


#: Relative error estimate up to which a critical value that missed its tolerance is still reported
#: (with that estimate, which its margin carries); beyond it the value is "not located".
REPORTABLE = 1e-3


def _unconverged(point: CriticalPoint, what: str, error: float | None) -> CriticalPoint:
    """A located critical value whose error estimate missed the tolerance: kept with its estimate
    when that is at most REPORTABLE relative, else "not located" (its margin is then incomplete)."""
    value = point.value
    if value is not None and error is not None and error <= REPORTABLE * abs(value):
        return replace(point, within_tolerance=False,
                       message=f"{point.message}; the {what} missed its tolerance: it is reported with "
                               f"its error estimate {error:.1e} (the margin is judged on its pessimistic side)")
    est = f"error estimate {error:.1e}" if error is not None else "no error estimate"
    return replace(point, value=None, kind=CriticalKind.NOT_LOCATED, error=None,
                   message=f"the {what} was not located: {est} ({point.message})")


def _critical(point, what: str) -> CriticalPoint:
    """A solver's critical point as its record (an unconverged one through :func:`_unconverged`)."""
    out = CriticalPoint(
        value=point.value if math.isfinite(point.value) else None,
        kind=point.kind,
        bracket=tuple(float(b) for b in point.bracket),
        error=float(point.error) if math.isfinite(point.error) else None,
        message=point.message,
        N=point.N,
        within_tolerance=True,
    )
    if CriticalKind(point.kind).located and not point.converged:
        return _unconverged(out, what, out.error)
    return out


def _pencil_critical(root, what: str, hi: float) -> CriticalPoint:
    """A first pencil root (damped rod, Kelvin-Tait-Chetaev) as a critical point (an unconverged or
    failed one through :func:`_unconverged`)."""
    if not root.converged:
        value = root.value if math.isfinite(root.value) and root.value > 0 else None
        error = root.error * value if value is not None and math.isfinite(root.error) else None
        at = f" at N = {root.N}" if root.N else ""
        point = CriticalPoint(value=value, kind=CriticalKind.DIVERGENCE, bracket=(float(value or 0.0),) * 2,
                              error=error, message=f"first root of the static operator ({root.model}){at}", N=root.N,
                              within_tolerance=True)
        return _unconverged(point, what, error)
    if root.value == 0:
        kind = CriticalKind.UNSTABLE_AT_START
    elif math.isinf(root.value):
        kind = CriticalKind.NONE_FOUND
    else:
        kind = CriticalKind.DIVERGENCE  # with damping the straight rod loses stability only through lambda = 0
    value = root.value if 0 < root.value < math.inf else None
    return CriticalPoint(
        value=value, kind=kind, bracket=(0.0, float(hi)) if kind == CriticalKind.NONE_FOUND else
        (float(root.value), float(root.value)), error=root.error * (value or 0.0),
        message=f"first root of the static operator ({root.model})" + (f", N = {root.N}" if root.N else ""),
        N=root.N, within_tolerance=True)


def _damped_critical(p, options: WhirlOptions, route: str,
                     spin: bool = True) -> tuple[CriticalPoint, CriticalPoint, bool, float]:
    """Critical load at the operating spin and critical spin at the operating load of a damped
    tether from the static pencils or the exact determinant (milliseconds; the determinant also where a pencil
    root next to the end of its line missed the tolerance: :func:`~etcheck.rod.straight.exact.roots.pencil_or_exact`),
    whether the operating point is stable, and the spin that destabilises the unloaded tether (dimensionless).
    ``spin=False``: the critical spin is not asked (its point is then "not located")."""
    if route == EXACT:  # root located to round-off; its estimate (two formulations) is judged by the mission's tolerance
        dc = exact_critical(p, tol=max(options.tol, options.eig_tol), spin=spin)
    else:
        dc = pencil_or_exact(p, tol=options.tol, ladder=DRAFT_LADDER if options.draft else LADDER, spin=spin)
    B_hi = 1.6 * max(float(critical_loads(p.R, p.f, 1, p.ends)[0]), p.B)
    w_hi = 1.6 * max(p.omega, math.sqrt(p.R))
    load = _pencil_critical(dc.critical_load, "critical load at the operating spin", B_hi)
    spin = _pencil_critical(dc.critical_spin, "critical spin at the operating load", w_hi)
    return load, spin, dc.stable, dc.spin_at_rest.value


def _undamped_critical(p, options: WhirlOptions, N: int, op, exact: bool, windows: bool = True, spin: bool = True,
                       extra: Extras | None = None):
    """Critical load, critical spin point, stable spin windows, the spin they were sought up to and the
    operating point's stability of an undamped tether (dimensionless): from the exact undamped determinant
    (:func:`etcheck.rod.straight.exact.undamped.undamped_critical`); where that cannot isolate a change of
    stability (a tangency of two roots), from the spectral scans of :mod:`etcheck.rod.straight.collocation.spectral` on the
    collocation route, and "not located" on the exact route (its margins are then incomplete).
    ``windows=False``: the stable spin windows are not sought; ``spin=False``: nor the critical spin. With
    ``extra`` (a sign-off) the windows are sought within its time budget, and the critical values are answered
    without them where they are skipped."""
    try:
        u = _exact_undamped(p, options, windows, spin, extra)
        return u.critical_load, u.critical_spin, list(u.windows), u.scanned_to, u.stable
    except (ArithmeticError, ValueError) as exc:
        why = f"the exact undamped determinant gave no answer: {exc}"
    if exact:  # boundary layers too thin for collocation: no second route
        lost = [StabilityPoint(axis, math.nan, CriticalKind.NOT_LOCATED, (0.0, 0.0), math.nan, False, why, 0)
                for axis in ("B", "omega")]
        return lost[0], lost[1], [], None, False
    load = critical_load(p.with_(B=0.0), tol=options.tol, N=N)
    spin_point, windows, scanned_to = scan_line(p.with_(omega=0.0), "omega", tol=options.tol, N=N)
    op = op or spectrum(p, k=options.k, tol=options.eig_tol, N=options.N)
    return load, spin_point, windows, scanned_to, bool(op.stable)


def critical_values(p, options: WhirlOptions = DEFAULT_OPTIONS, route: str = SPECTRAL,
                    spin: bool = True) -> tuple[CriticalPoint, CriticalPoint]:
    """The critical load at the operating spin and the critical spin at the operating load (dimensionless
    critical points) exactly as :func:`linear_stability` computes them for its margins, by the same route and
    tolerances: the static pencils or the exact determinant with damping, the exact undamped determinant
    without (its spectral fallback at ``options.N`` or N = 24). ``spin=False``: the critical spin is not asked
    (then "not located"). The uncertainty study evaluates its samples' margins here."""
    if p.gamma > 0:
        load, spin_point, _, _ = _damped_critical(p, options, route, spin)
        return load, spin_point
    load_point, spin_point, *_ = _undamped_critical(p, options, options.N or 24, None, route == EXACT, windows=False,
                                                    spin=spin or not p.B > 0)
    return (_critical(load_point, "critical load at the operating spin"),
            _critical(spin_point, "critical spin at the operating load"))


def _exact_undamped(p, options: WhirlOptions, windows: bool, spin: bool, extra: Extras | None):
    """:func:`~etcheck.rod.straight.exact.undamped.undamped_critical`, its stable spin windows through ``extra`` where
    given (without them, the same line up to its first static spin, where they are skipped)."""
    if not windows or extra is None:
        return undamped_critical(p, tol=options.tol, windows=windows, spin=spin)
    got = extra("stable spin windows", lambda: undamped_critical(p, tol=options.tol, spin=spin))
    return got if got is not None else undamped_critical(p, tol=options.tol, windows=False, spin=spin)


def _operating_spectrum(op, sc: Scales) -> OperatingSpectrum:
    lam = op.eigenvalues
    return OperatingSpectrum(
        N=op.N,
        N_check=op.N_check,
        message=op.message,
        modes=tuple(
            Mode(
                re=float(z.real),
                im=float(z.imag),
                error=float(e),
                frequency_Hz=float(sc.hz(abs(z.imag))),
                growth_rate_per_s=float(sc.rad_s(z.real)),
                damping_ratio=float(-z.real / abs(z)) if abs(z) > 0 else None,
            )
            for z, e in zip(lam, op.errors)
        ),
        least_damped=int(np.argmax(lam.real)) if lam.size else None,
        stable=bool(op.stable),
    )


#: Relative error up to which a map row's boundary is drawn (a figure resolves about 1e-3 of its axis; the margins
#: keep their own tolerance): near the unloaded critical spin a tape's roots carry ~1e-8 from their two formulations,
#: and rows held to 1e-10 would be left empty, drawn unstable where the tether is stable.
MAP_TOLERANCE = 1e-6


def _exact_rows(p, w_rows, B_hi: float, rest: float, tol: float) -> list[list[float]]:
    """Stable load interval [0, B_c(omega)) of each spin row, from the exact determinant (damped), each boundary to
    the looser of ``tol`` and :data:`MAP_TOLERANCE`; the rows are independent, shared with a forked helper on two
    cores."""

    def row(w: float) -> list:
        if w >= rest:
            return []
        root = first_exact_root(p.with_(omega=w), "B", max(tol, MAP_TOLERANCE))
        return [(0.0, min(root.value, B_hi))] if root.converged and root.value > 0 else []

    return split_map(row, [float(w) for w in w_rows])


def linear_stability(scaled: Scaled, options: WhirlOptions = DEFAULT_OPTIONS, route: str = SPECTRAL) -> LinearSection:
    """All rung-1 answers for the scene, dimensionless and in SI, without a deadline: :func:`linear_answers`."""
    return linear_answers(scaled, options, route)[0]


def linear_answers(scaled: Scaled, options: WhirlOptions = DEFAULT_OPTIONS, route: str = SPECTRAL,
                   deadline: float | None = None) -> tuple[LinearSection, list[SkippedPart]]:
    """All rung-1 answers for the scene, dimensionless and in SI, and the parts skipped.

    Returns rung 1's record: the operating spectrum (with two-resolution
    errors), the critical load at the operating spin and tension
    (B_c(omega, T, gamma)), the critical spin at the operating load
    (omega_c(B, T, gamma)), the stable spin windows at the operating load,
    the Campbell diagram and the stability map.

    With damping the critical values are first roots of the static pencils
    (Kelvin-Tait-Chetaev: one small pencil per resolution, no scan) and there
    are no stability windows; without damping they come from the exact undamped
    determinant, the spectral scans where it cannot isolate a change (flutter
    possible). The map's static curves and damped rows come from
    :mod:`etcheck.rod.straight.collocation.static_map` (one LU per family, small Schur complements
    per row, rows classified by crossing directions: no eigenvalue solve); the
    Campbell diagram is one resolution with a two-resolution error on three
    spins. ``options.draft`` answers the critical values and the
    operating point only (no spectrum when damped, no Campbell diagram, no map).
    ``route`` "exact determinant" (damped only; boundary layers too thin for
    collocation, see :func:`etcheck.checks.plan.straight_route`): the critical
    values from :func:`etcheck.rod.straight.exact.roots.exact_critical`, the map rows
    from its first load roots, no spectrum and no Campbell diagram.

    The operating spectrum, the Campbell diagram and the map are the report's extras: each is skipped, and
    listed with the reason (``part``, ``why``), where it would end past ``deadline`` (a ``time.perf_counter()``
    value) or exceed the memory budget (:mod:`etcheck.runtime.memory`); the critical values never are.
    """
    exact = route == EXACT
    p = scaled.params
    skipped: list[SkippedPart] = []
    extra = Extras(skipped, deadline, options.time_budget)
    op = None
    if not (options.draft or exact):  # the spectrum at the operating point: the report's eigenvalues
        op = extra("operating spectrum", lambda: _operating(p, options, deadline))

    # the critical points are located at the resolution the operating spectrum
    # needed (boundary layers under strong tension need more than the default)
    N = options.N or max(24, op.N_check if op else 24)
    out = _critical_values(scaled, options, route, op, N, extra)
    if options.draft or (exact and p.gamma == 0):  # no frequencies and no map on the exact undamped route
        return out, skipped
    if not exact and op is None:
        skipped += [SkippedPart(part=part, why="it is drawn at the operating spectrum's resolution, which was skipped")
                    for part in ("Campbell diagram", "stability map")]
        return out, skipped
    return replace(out, **_pictures(scaled, options, route, op, N, out, extra)), skipped


def _operating(p, options: WhirlOptions, deadline: float | None):
    """The operating point's spectrum (its ladder stops before a resolution that would end past ``deadline``)."""
    op = spectrum(p, k=options.k, tol=options.eig_tol, N=options.N, deadline=deadline)
    if not op.converged:  # shown as such; the critical values below do not depend on it
        fix = " (raise [check] resolution or leave it out)" if options.N else ""
        op = replace(op, message=f"NOT CONVERGED to the tolerance {options.eig_tol:.0e}: {op.message}{fix}; "
                                 f"each eigenvalue carries its own error estimate")
    return op


class Extras:
    """Runs a part of the report's extras within the deadline and the memory budget: its value, or None with the
    part and the reason appended to ``skipped``."""

    def __init__(self, skipped: list[SkippedPart], deadline: float | None, budget: float | None) -> None:
        self.skipped, self.deadline, self.budget = skipped, deadline, budget

    def __call__(self, part: str, fn):
        try:
            return within(self.deadline, fn)
        except OutOfTime:
            why = (f"not computed within the sign-off's time budget ({self.budget:g} s of computation; "
                   "--time-budget changes it); the margins do not depend on it")
        except OverBudget as exc:
            why = str(exc)
        self.skipped.append(SkippedPart(part=part, why=why))
        return None


def _critical_values(scaled: Scaled, options: WhirlOptions, route: str, op, N: int,
                     extra: Extras | None = None) -> LinearSection:
    """The rung-1 section without its pictures: critical load and spin, spin windows, the operating point."""
    exact = route == EXACT
    p, sc = scaled.params, scaled.scales
    damped = p.gamma > 0
    windows: list = []
    scanned_to = None
    if damped:
        load, spin, stable, _ = _damped_critical(p, options, route)
    else:  # flutter possible
        load_point, spin_point, windows, scanned_to, stable = _undamped_critical(
            p, options, N, op, exact, windows=not options.draft, spin=not (options.draft and p.omega == 0),
            extra=extra)
        load = _critical(load_point, "critical load at the operating spin")
        spin = _critical(spin_point, "critical spin at the operating load")
    return LinearSection(
        model=("rung 1, exact characteristic determinant" if exact else
               "rung 1 (linear spectral)" + (", critical values from the static pencils" if damped else "")),
        route=route,
        threshold=THRESHOLD,
        operating_stable=bool(stable),
        operating_spectrum=_operating_spectrum(op, sc) if op else None,
        critical_load=CriticalLoad(**fields_of(load),
                                   IB0_N_per_m=None if load.value is None else sc.line_load(load.value)),
        critical_spin=CriticalSpin(
            **fields_of(spin),
            rad_s=None if spin.value is None else sc.rad_s(spin.value),
            rpm=None if spin.value is None else sc.rpm(spin.value),
        ),
        spin_windows=tuple(SpinWindow(omega=(a, b), rpm=(sc.rpm(a), sc.rpm(b))) for a, b in windows),
        spin_windows_scanned_to_rpm=None if scanned_to is None else sc.rpm(scanned_to),
        operating=OperatingPoint(B=p.B, omega=p.omega, IB0_N_per_m=sc.line_load(p.B), spin_rpm=sc.rpm(p.omega)),
        campbell=None,
        stability_map=None,
    )


def picture_ranges(p, linear: LinearSection) -> tuple[float, float]:
    """(B, omega) up to which the stability map and the Campbell diagram are drawn (dimensionless): 1.6 times past
    the operating point and the located critical values of ``linear`` (the spin at least sqrt(R); without a load
    or a located critical load, the first static load at rest)."""
    load, spin = linear.critical_load, linear.critical_spin
    B_ref = load.value if load.value is not None and CriticalKind(load.kind).located else None
    w_ref = spin.value if spin.value is not None and CriticalKind(spin.kind).located else None
    B_hi = 1.6 * max(B_ref or 0.0, p.B) or 1.6 * float(critical_loads(p.R, p.f, 1, p.ends)[0])
    return B_hi, 1.6 * max(w_ref or 0.0, p.omega, math.sqrt(p.R))


def _pictures(scaled: Scaled, options: WhirlOptions, route: str, op, N: int, out: LinearSection,
              extra: Extras) -> dict:
    """The Campbell diagram and the stability map (each through ``extra``: skipped past the deadline), as the
    fields of ``out`` they fill."""
    p, sc = scaled.params, scaled.scales
    B_hi, w_hi = picture_ranges(p, out)
    w_rows = np.linspace(0.0, w_hi, options.row_points)
    campbell_data = None
    if route != EXACT:
        omegas = np.linspace(0.0, w_hi, options.campbell_points)
        campbell_data = extra("Campbell diagram", lambda: _campbell(p, omegas, options, N, op, sc))
    grid = extra("stability map", lambda: _map(p, options, route, N, B_hi, w_hi, w_rows))
    if grid is None:
        return {"campbell": campbell_data}
    B_grid, w_grid, growth, cuts, curve_B, curve_w = grid
    rows = None if cuts is None else tuple(
        StableRow(omega=float(w), spin_rpm=float(sc.rpm(w)),
                  IB0_N_per_m=tuple((sc.line_load(a), sc.line_load(b)) for a, b in iv))
        for w, iv in zip(w_rows, cuts)
    )
    return {
        "campbell": campbell_data,
        "stability_map": StabilityMap(
            B=tuple(B_grid.tolist()),
            omega=tuple(w_grid.tolist()),
            IB0_N_per_m=tuple(sc.line_load(B_grid).tolist()),
            spin_rpm=tuple(sc.rpm(w_grid).tolist()),
            max_growth=growth,  # undamped only: dimensionless, shape (omega, B)
            stable_rows=rows,
            static_points=StaticPoints(
                IB0_N_per_m=tuple(sc.line_load(curve_B).tolist()),
                spin_rpm=tuple(sc.rpm(curve_w).tolist()),
            ),
        ),
    }


def _campbell(p, omegas: np.ndarray, options: WhirlOptions, N: int, op, sc: Scales) -> Campbell:
    """The Campbell diagram at one resolution, checked at the operating spectrum's finer one on a few spins."""
    cd = campbell(p, omegas, k=options.k, N=N, N_check=op.N if op.N > N else None)
    return Campbell(
        omega=tuple(omegas.tolist()),
        spin_rpm=tuple(sc.rpm(omegas).tolist()),
        frequency_Hz=tuple(map(tuple, finite_or_none(sc.hz(np.abs(cd.frequencies))))),
        growth_rate_per_s=tuple(map(tuple, finite_or_none(sc.rad_s(cd.growth_rates)))),
        N=cd.N,
        N_check=cd.N_check,
        checked_spin_rpm=tuple(sc.rpm(omegas[cd.checked]).tolist()),
        error=finite_or_none(cd.error),
    )


def _map(p, options: WhirlOptions, route: str, N: int, B_hi: float, w_hi: float, w_rows: np.ndarray):
    """(B grid, omega grid, growth (undamped) or None, stable rows (damped) or None, static points B, omega)."""
    B_grid = np.linspace(0.0, B_hi, options.map_points)
    w_grid = np.linspace(0.0, w_hi, options.map_points)
    growth = cuts = None
    curve_B = curve_w = np.array([])
    if route == EXACT:  # no frequencies on this route; the damped rows end at the first determinant root
        rest = _damped_critical(p, options, route)[3]
        cuts = _exact_rows(p, w_rows, B_hi, rest, options.tol)
    else:
        curves = static_curves(p, B_hi, w_hi, omega_rows=w_rows, N=N)
        curve_B, curve_w = curves.B, curves.omega_points
        if p.gamma > 0:  # stability changes only at static points: cut each row there exactly
            cuts = stable_rows(p, curves, B_hi)
        else:  # undamped: flutter can occur anywhere, sample a grid
            growth = tuple(map(tuple, stability_map(p, B_grid, w_grid, N=16 if N <= 24 else N).tolist()))
    return B_grid, w_grid, growth, cuts, curve_B, curve_w


def accuracy(scaled: Scaled, Ns: tuple[int, ...] = WhirlOptions.accuracy_N, k: int = 10) -> tuple[AccuracyRow, ...]:
    """Time and error of the lowest k eigenvalue pairs and of B_c versus N.

    A measurement for this scene (BLAS on one thread, one solve per N), against
    a reference at :func:`etcheck.rod.straight.collocation.convergence.reference_resolution` (Ns)
    (N = 48 for the default Ns, 96 up to N = 64); see
    :func:`etcheck.rod.straight.collocation.convergence.accuracy_table`.
    """
    N_ref = reference_resolution(Ns)
    rows = accuracy_table(scaled.params, Ns=Ns, k=k, N_ref=N_ref)
    return tuple(
        AccuracyRow(N=r.N, solve_time_s=r.solve_time, eigenvalue_error=finite_or_none(r.eig_error),
                    load_error=finite_or_none(r.load_error), reference_N=N_ref)
        for r in rows
    )

