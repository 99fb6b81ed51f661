"""Rung 1v for a mission: the straight tether with its current and its tension along it (docs/model.md,
section 10), in the numbers the report shows.

Everything is solved dimensionless in :mod:`etcheck.rod.straight.varying.circulatory`; this module chooses what to
ask and converts the answers to SI:

* the critical load at the operating spin and the critical spin at the operating load, each with its kind
  (divergence or flutter), its eigenvalue and the shape of the mode that crosses;
* **damping, honestly**: with a current that varies along the tether the load is circulatory and damping
  can lower the threshold (Ziegler). The threshold is computed undamped and over the damping the mission
  allows: the given ``damping_time`` when the mission fixes it, else from none up to the paper's estimate
  (gamma = 0.04375 at the tether's length) on a small map; the verdict uses the given damping, or the least
  favourable value of the map and says so. Points of the map below the undamped threshold are marked as
  destabilised by damping;
* with end masses, the same critical load under the uniform smallest tension, a bound reported beside it;
* the profiles themselves, for the report's figures.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from etcheck.checks.results.sections_straight import (
    CriticalLoad,
    CriticalPoint,
    CriticalSpin,
    DampingPoint,
    DampingSection,
    LinearSection,
    OperatingPoint,
    ProfileCurrent,
    ProfileMode,
    ProfilesSection,
    ProfileTension,
    StabilityMap,
    StableRow,
    StaticPoints,
)
from etcheck.checks.rungs.straight import picture_ranges
from etcheck.jsonable import fields_of
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.varying.circulatory import (
    Crossing,
    critical,
    critical_spin,
    crossing_mode,
    first_crossings,
)
from etcheck.rod.straight.varying.line import THRESHOLD
from etcheck.rod.straight.varying.profiles import Tether
from etcheck.runtime.parallel import ahead, can_split, split_map
from etcheck.scaling import Scaled, Scales

#: Dimensionless damping of the map, as fractions of the largest the mission allows (0 is computed apart).
DAMPING_FRACTIONS = (1e-3, 1e-2, 1e-1, 0.3, 1.0)
#: Spin rows of the stability map (each the first crossing along the load at that spin).
MAP_ROWS = 7
#: Tolerance of the uniform-tension bound (it is a bound, not the verdict).
BOUND_TOLERANCE = 1e-6
MODEL = "rung 1v (linear, profiles along the tether)"


def _record(c: Crossing, tol: float) -> CriticalPoint:
    """A crossing as a critical point record (dimensionless value; absolute error)."""
    located = CriticalKind(c.kind).located
    value = c.value if located or c.kind == CriticalKind.UNSTABLE_AT_START else None
    bracket = ([c.lo, c.hi] if c.kind in (CriticalKind.NONE_FOUND, CriticalKind.NEVER) else
               [c.value] * 2 if value is not None else [0.0, 0.0])
    within = not located or c.value == 0 or bool(c.error <= tol * abs(c.value))
    return CriticalPoint(value=value, kind=str(c.kind), bracket=tuple(float(x) for x in bracket),
                         error=float(c.error) if located and math.isfinite(c.error) else None, message=c.message,
                         N=c.N, within_tolerance=within)


def _load_point(c: Crossing, tol: float, scales: Scales) -> CriticalLoad:
    point = _record(c, tol)
    return CriticalLoad(**fields_of(point),
                        IB0_N_per_m=None if point.value is None else scales.line_load(point.value))


def _mode(c: Crossing, scales: Scales) -> ProfileMode | None:
    if c.mode is None:
        return None
    s, u, v = c.mode
    return ProfileMode(s=tuple(s.tolist()), u_re=tuple(u.real.tolist()), u_im=tuple(u.imag.tolist()),
                       v_re=tuple(v.real.tolist()), v_im=tuple(v.imag.tolist()), kind=str(c.kind),
                       frequency_Hz=scales.hz(abs(c.eigenvalue.imag)))


def _damping_map(gammas: tuple[float, ...], survey: list[Crossing], scales: Scales, undamped: Crossing,
                 least: Callable[[], Crossing | None]) -> tuple[list[DampingPoint], Crossing]:
    """The map's points from the critical load at each damping ``gammas`` (``survey``: one mesh), and the least
    favourable crossing: the undamped one where no point of the map lies below it, else the lowest point located
    again on two meshes (``least()``, :func:`_least`), which the map then shows."""
    points: list[DampingPoint] = []
    ref = undamped.value if CriticalKind(undamped.kind).located else math.inf
    for g, c in zip(gammas, survey):
        value = c.value if CriticalKind(c.kind).located else None
        points.append(DampingPoint(gamma=g, damping_time_s=scales.damping_time(g), B=value,
                                   IB0_N_per_m=None if value is None else scales.line_load(value), kind=str(c.kind),
                                   destabilised=bool(value is not None and value < ref * (1 - 1e-6))))
    lowest = _lowest(gammas, survey)
    if lowest is None or (CriticalKind(undamped.kind).located and undamped.value <= lowest[1].value):
        return points, undamped
    worst = least()
    if CriticalKind(worst.kind).located:  # the map shows the verdict's value where it was located again
        points = [replace(q, B=worst.value, IB0_N_per_m=scales.line_load(worst.value)) if q.gamma == lowest[0] else q
                  for q in points]
    return points, worst


def _lowest(gammas: tuple[float, ...], survey: list[Crossing]) -> tuple[float, Crossing] | None:
    """(damping, crossing) of the survey's lowest located crossing; None where none was located."""
    found = [(g, c) for g, c in zip(gammas, survey) if CriticalKind(c.kind).located]
    return min(found, key=lambda gc: gc[1].value) if found else None


def _least(t: Tether, gammas: tuple[float, ...], survey: list[Crossing], tol: float) -> Crossing | None:
    """The survey's lowest crossing located again on two meshes (followed from the survey's; the verdict's
    candidate), None where the survey located none."""
    lowest = _lowest(gammas, survey)
    if lowest is None:
        return None
    g, c = lowest
    return critical(t.with_(gamma=g), tol=tol, near=(0.98 * c.value, 1.02 * c.value), mode=False,
                    hint=(c.value, c.eigenvalue))


def _undamped_and_survey(t: Tether, gammas: tuple[float, ...], tol: float, draft: bool, wanted: bool
                         ) -> tuple[Crossing, list[Crossing] | None, Callable[[], Crossing | None]]:
    """The undamped crossing (in a draft on one mesh), and, where the map is ``wanted``, the map's survey and a
    function giving its lowest crossing on two meshes (:func:`_least`); the survey None where not wanted, or in a
    draft where the tether flutters undamped at any load (no damping can be less favourable).

    Where there are two cores the undamped threshold and the survey's first crossing (at the smallest damping,
    searched for) are located side by side: in a draft the undamped threshold here (it decides whether the survey
    is needed), in a sign-off on the other core (two meshes: the longer). Then the survey's others (each continued
    from the last) are computed on another core while the first is located again on two meshes here: it is the
    lowest where damping destabilises (Ziegler), and where it is not, this work was done while waiting."""
    def undamped() -> Crossing:
        return critical(t.with_(gamma=0.0), tol=tol, mode=False, check=not draft)

    def first() -> Crossing:
        return first_crossings(t, "gamma", gammas[:1], tol)[0]

    if not wanted:
        return undamped(), None, lambda: None
    speculative = can_split()
    with ahead(first if draft else undamped) as beside:
        if draft:
            u = undamped()
            if u.kind == CriticalKind.FLUTTER and u.value == 0:
                return u, None, lambda: None
            c1 = beside()
        else:
            c1 = first()
        with ahead(lambda: first_crossings(t, "gamma", gammas[1:], tol, after=(gammas[0], c1))) as rest:
            least = _least(t, gammas[:1], [c1], tol) if speculative else None
            survey = [c1, *rest()]
        if not draft:
            u = beside()
    lowest = _lowest(gammas, survey)
    if least is not None and lowest is not None and lowest[0] == gammas[0]:
        return u, survey, lambda: least
    return u, survey, lambda: _least(t, gammas, survey, tol)


def _bound(scaled: Scaled, gamma: float) -> CriticalPoint | None:
    """The critical load under the uniform smallest tension (end masses only): a bound."""
    t = scaled.tether
    if scaled.params.T == t.params.T and t.tension.uniform_value is not None:
        return None
    uniform = Tether(scaled.params.with_(gamma=gamma), t.current)
    c = critical(uniform, tol=BOUND_TOLERANCE, mode=False, check=False)  # a bound: one mesh, no error estimate
    return _load_point(c, BOUND_TOLERANCE, scaled.scales)


def _samples(scaled: Scaled) -> tuple[ProfileCurrent | None, ProfileTension | None]:
    t, sc = scaled.tether, scaled.scales
    s = np.linspace(0.0, 1.0, 101)
    current = None if t.current.uniform_value is not None else ProfileCurrent(
        s=tuple(s.tolist()), height_m=tuple(sc.distance(s).tolist()), fraction=tuple(t.current(s).tolist()),
        current_A=tuple((sc.worst_current * t.current(s)).tolist()))
    tension = None if t.tension.uniform_value is not None else ProfileTension(
        s=tuple(s.tolist()), height_m=tuple(sc.distance(s).tolist()),
        tension_N=tuple((sc.tension(t.params.T) * t.tension(s)).tolist()))
    return current, tension


def _damping_policy(t: Tether, fixed: bool, tol: float, scales: Scales, draft: bool = False):
    """(undamped crossing or None, damping map, the crossing the verdict uses or None, why) of a circulatory load
    (a conservative one: the mission's damping, the crossing computed with the other parts of the check).
    ``draft``: the undamped threshold on one mesh unless the verdict uses it (then on two, as every crossing a
    verdict uses)."""
    p = t.params
    if not t.circulatory:  # conservative: the mission's damping, as for a uniform tether
        return None, [], None, ("the load is conservative (one current along the tether): the critical load at "
                                f"the mission's damping (gamma = {p.gamma:.4g})")
    gammas = tuple(frac * p.gamma for frac in DAMPING_FRACTIONS)
    undamped, survey, least = _undamped_and_survey(t, gammas, tol, draft, wanted=not fixed and p.gamma > 0)
    if draft and undamped.kind == CriticalKind.FLUTTER and undamped.value == 0:  # no damping can be less favourable
        undamped = critical(t.with_(gamma=0.0), tol=tol, mode=False)  # the verdict's: on two meshes
        return undamped, [], undamped, ("undamped the tether flutters at any load: no damping can give a lower "
                                        "threshold (the damping map is not computed in a draft)")
    if fixed or p.gamma == 0:
        if p.gamma == 0 and draft:  # the verdict's: on two meshes (the first one's search reused)
            undamped = critical(t.with_(gamma=0.0), tol=tol, mode=False)
        return undamped, [], None if p.gamma > 0 else undamped, (
            f"the mission fixes the damping (tether.damping_time: gamma = {p.gamma:.4g}); the undamped threshold is "
            "reported beside it")
    points, worst = _damping_map(gammas, survey, scales, undamped, least)
    if worst is undamped and draft:  # the verdict's: on two meshes (the first one's search reused)
        worst = undamped = critical(t.with_(gamma=0.0), tol=tol, mode=False)
    where = "undamped" if worst is undamped else f"at gamma = {worst_gamma(points, worst):.4g}"
    return undamped, points, worst, (
        "the mission does not fix the damping (no tether.damping_time): the circulatory load's threshold is "
        f"computed undamped and with damping up to the paper's estimate gamma = {p.gamma:.4g}; the verdict uses the "
        f"least favourable, {where}")


def worst_gamma(points: list[DampingPoint], worst: Crossing) -> float:
    """The damping of the map point whose critical load is the least favourable crossing's."""
    return min(points, key=lambda q: abs((q.B if q.B is not None else math.inf) - worst.value)).gamma


def profile_stability(scaled: Scaled, damping_fixed: bool, tol: float = 1e-8,
                      draft: bool = False, beside: Callable[[float], Any] | None = None
                      ) -> tuple[LinearSection, ProfilesSection, Any]:
    """Rung 1v's answers for the scene (``scaled.tether`` set): the linear section the margins read (critical
    load at the operating spin, critical spin at the operating load), the profiles section the report shows,
    and ``beside(gamma)`` (None without it): work at the damping the verdict uses (the margins under another
    attachment of the ends), done together with this function's own once that damping is known, on both cores
    where there are two. ``damping_fixed``: whether the mission gives its damping time."""
    t = scaled.tether
    sc = scaled.scales
    p = t.params
    undamped, points, verdict, why = _damping_policy(t, damping_fixed, tol, sc, draft)
    gamma = verdict_gamma(p.gamma, points, verdict, undamped)
    tg = t.with_(gamma=gamma)
    # independent of each other once the damping is known: heaviest first, shared between the cores
    jobs = {"verdict": None if verdict is not None else lambda: critical(tg, tol=tol, mode=False),
            "beside": None if beside is None else lambda: beside(gamma),
            "bound": None if draft else lambda: _bound(scaled, gamma),
            "spin": None if p.omega == 0 else lambda: critical_spin(tg, tol=tol)}
    names = [k for k, job in jobs.items() if job is not None]
    done = dict(zip(names, split_map(lambda k: jobs[k](), names)))
    verdict = crossing_mode(tg, verdict if verdict is not None else done["verdict"])  # the verdict's mode only
    linear = _linear(scaled, tg, verdict, done.get("spin"), tol)
    current, tension = _samples(scaled)
    section = ProfilesSection(
        model=MODEL,
        circulatory=t.circulatory,
        current=current,
        tension=tension,
        damping=DampingSection(fixed=damping_fixed or p.gamma == 0, gamma=gamma,
                               damping_time_s=sc.damping_time(gamma), why=why, map=tuple(points)),
        undamped=None if undamped is None else _load_point(undamped, tol, sc),
        uniform_tension_bound=done.get("bound"),
        mode=_mode(verdict, sc),
        post_buckling=_after(verdict),
    )
    return linear, section, done.get("beside")


def _linear(scaled: Scaled, t: Tether, verdict: Crossing, spin: Crossing | None, tol: float) -> LinearSection:
    """The linear section the margins read: the crossing along the load (``verdict``) and, with spin, the critical
    spin of ``t`` at its load (``spin``)."""
    p, sc = t.params, scaled.scales
    load_point = _load_point(verdict, tol, sc)
    stable = bool(verdict.kind in (CriticalKind.NONE_FOUND, CriticalKind.NEVER) or
                  (load_point.value is not None and p.B < load_point.value))
    spin_point = _record(spin, tol) if spin else CriticalPoint(
        value=None, kind=str(CriticalKind.NOT_LOCATED), bracket=(0.0, 0.0), error=None,
        message="no spin: the critical spin is not asked", N=0, within_tolerance=True)
    w = spin_point.value
    return LinearSection(
        model=MODEL, route="profiles", threshold=THRESHOLD, operating_stable=stable,
        operating_spectrum=None, critical_load=load_point,
        critical_spin=CriticalSpin(**fields_of(spin_point), rad_s=None if w is None else sc.rad_s(w),
                                   rpm=None if w is None else sc.rpm(w)),
        spin_windows=(), spin_windows_scanned_to_rpm=None,
        operating=OperatingPoint(B=p.B, omega=p.omega, IB0_N_per_m=sc.line_load(p.B), spin_rpm=sc.rpm(p.omega)),
        campbell=None, stability_map=None,
    )


def stability_map(scaled: Scaled, linear: LinearSection, gamma: float, tol: float) -> StabilityMap | None:
    """The (load, spin) plane at the verdict's damping ``gamma``, as the uniform tether's map is drawn (the ranges
    1.6 times past the operating point and the critical values of ``linear``): at each of :data:`MAP_ROWS` spins the
    first crossing along the load (:func:`~etcheck.rod.straight.varying.circulatory.first_crossings`, one mesh, continued
    from spin to spin where it can be; the rows in two chains, one per core; at zero spin the verdict's own where
    the tether does not spin), each row stable from zero load up to it. None where a row's crossing is not located
    (the map would be wrong there): the report then draws none."""
    t = scaled.tether.with_(gamma=gamma)
    p, sc = t.params, scaled.scales
    load = linear.critical_load
    B_hi, w_hi = picture_ranges(p, linear)
    omegas = np.linspace(0.0, w_hi, MAP_ROWS)
    at_rest = p.omega == 0 and load.kind != str(CriticalKind.NOT_LOCATED)  # row 0 is the verdict's line
    todo = omegas[1:] if at_rest else omegas
    half = (len(todo) + 1) // 2
    chains = [tuple(todo[:half]), tuple(todo[half:])]
    found = [(c.value if CriticalKind(c.kind).located else None, c.kind)
             for chain in split_map(lambda ws: first_crossings(t, "omega", ws, tol, hi=B_hi), chains) for c in chain]
    if at_rest:
        found.insert(0, (load.value, load.kind))
    if any(kind == CriticalKind.NOT_LOCATED for _, kind in found):
        return None
    stable: list[StableRow] = []
    for w, (value, kind) in zip(omegas, found):
        if kind == CriticalKind.UNSTABLE_AT_START or value == 0:
            intervals = ()
        else:
            intervals = ((0.0, sc.line_load(float(min(value if value is not None else B_hi, B_hi)))),)
        stable.append(StableRow(omega=float(w), spin_rpm=float(sc.rpm(w)), IB0_N_per_m=intervals))
    B = np.linspace(0.0, B_hi, 2)
    return StabilityMap(B=tuple(B.tolist()), omega=tuple(omegas.tolist()), IB0_N_per_m=tuple(sc.line_load(B).tolist()),
                        spin_rpm=tuple(sc.rpm(omegas).tolist()), max_growth=None, stable_rows=tuple(stable),
                        static_points=StaticPoints(IB0_N_per_m=(), spin_rpm=()))


def alternative_linear(scaled: Scaled, gamma: float, tol: float) -> LinearSection:
    """Rung 1v's linear section for ``scaled`` (its tether, ends included) at one damping ``gamma``: the margins of
    another attachment of the ends, at the damping the mission's verdict uses (one mesh: shown beside the margin,
    not judged)."""
    t = scaled.tether.with_(gamma=gamma)
    spin = critical_spin(t, tol=tol) if t.params.omega > 0 else None
    return _linear(scaled, t, critical(t, tol=tol, mode=False, check=False), spin, tol)  # beside the margin: one mesh


def verdict_gamma(gamma: float, points: list[DampingPoint], verdict: Crossing | None, undamped: Crossing | None
                  ) -> float:
    """The damping of the crossing the verdict uses."""
    if verdict is not None and verdict is undamped:
        return 0.0
    return worst_gamma(points, verdict) if points else gamma


def _after(c: Crossing) -> str:
    if c.kind == CriticalKind.FLUTTER:
        return ("the straight tether first loses stability by flutter: two vibration modes merge and one grows "
                "(an oscillation of growing amplitude, not a static coil). The post-buckling rungs (whirling coils, "
                "rungs 2-3) describe static buckling under one current and one tension: they do not describe what "
                "follows, and no coil is drawn")
    return ("the post-buckling rungs (whirling coils, rungs 2-3) model one current and one tension along the tether: "
            "they are not run for a tether with profiles")
