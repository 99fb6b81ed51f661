"""Design limits: how far each input may go before the straight tether's margins fall to the required margin.

For each of the length, the current, the tension and the spin rate, the other inputs held at the mission's
worst case, the value at which the smallest straight-tether margin (load margin, and spin margin where the
tether spins) equals the required margin: the longest tether, the largest current, the smallest tension (and
for a tether under the gravity gradient the end masses that give it) and the largest spin rate that still meet
it. The margins at every trial value come from the check's own routes (:func:`point_margins`): with damping the
first roots of the static operator (Kelvin-Tait-Chetaev; the exact determinant where the end boundary layers
are too thin for the static pencils, :func:`etcheck.checks.plan.straight_route`), without damping the exact
undamped determinant; milliseconds to tens of milliseconds a value.

The limit is a root of g(u) = ln(smallest margin / required) in u = ln x: bracketed from the mission's value by
secant steps, then Brent's method to a relative tolerance of :data:`LIMIT_TOLERANCE`. Its relative error is that
tolerance plus the margin's own numerical error divided by |d ln margin / d ln x| there (the slope of the
final bracket). A length changes every dimensionless number at once (B ∝ L³, T ∝ L², ω ∝ L², P ∝ L⁻²); under
the gravity gradient the tension is recomputed at each length from the end masses as given.

SI floats at the edges (m, A, N, rad/s); the rod is dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from etcheck.checks.plan import EXACT, straight_route
from etcheck.checks.results.sections_straight import CriticalPoint
from etcheck.checks.results.sections_verdict import DesignLimit, DesignLimitsSection
from etcheck.checks.rungs.straight import WhirlOptions, critical_values
from etcheck.input.mission import Mission
from etcheck.numerics.optimize import brentq
from etcheck.rod.core.parameters import RodParameters
from etcheck.rod.straight.collocation.damped_critical import first_root
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.rod.straight.exact.roots import first_exact_root
from etcheck.runtime.parallel import split_map
from etcheck.scaling import RPM, Scene, scale, with_length

#: relative tolerance of a located limit (in the input)
LIMIT_TOLERANCE = 1e-7
#: a limit is sought up to this factor from the mission's value (ln span); beyond it: "none found"
SPAN = math.log(1e2)
#: the margins' clamp in g (a margin of 0 or infinity is finite for the root finder)
_CLAMP = 700.0


class NoAnswer(Exception):
    """A margin at a trial value the route could not locate (its message says why)."""


@dataclass(frozen=True)
class PointMargins:
    """The straight tether's margins at one scene: ``load`` (critical load at its spin / its load) and
    ``spin`` (critical spin at its load / its spin), inf where the operating value is zero; ``error`` the
    relative numerical error of the smaller; ``model`` the route."""

    load: float
    spin: float
    error: float
    model: str

    @property
    def smallest(self) -> float:
        return min(self.load, self.spin)

    @property
    def governing(self) -> str:
        return "spin margin" if self.spin < self.load else "load margin"


def point_margins(p: RodParameters, options: WhirlOptions) -> PointMargins:
    """The margins at the dimensionless scene ``p`` by the check's route and tolerances (module docstring):
    :func:`etcheck.checks.rungs.straight.critical_values`, as the check's own margins; a damped tether without spin
    needs one root only, the static load the check takes there. NoAnswer where a needed root was not located
    (or its solver gave up: the limits and alternatives then say so)."""
    route = straight_route(p)
    try:
        if p.gamma > 0 and p.omega == 0 and p.T >= 0:
            return _static_load(p, options, route)
        load, spin = critical_values(p, options, route, spin=p.omega > 0)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
        raise NoAnswer(f"{type(exc).__name__}: {exc}") from None
    (m_load, e_load), (m_spin, e_spin) = _margin(load, p.B), _margin(spin, p.omega)
    return PointMargins(m_load, m_spin, e_spin if m_spin < m_load else e_load, route)


def _static_load(p: RodParameters, options: WhirlOptions, route: str) -> PointMargins:
    """Damped, without spin: the first load root of the static operator (the check's critical load there)."""
    tol = max(options.tol, options.eig_tol) if route == EXACT else options.tol
    root = (first_exact_root if route == EXACT else first_root)(p, "B", tol)
    if not root.converged and route != EXACT:
        root = first_exact_root(p, "B", tol)
    if not root.converged:
        raise NoAnswer(f"the critical load was not located (error estimate {root.error:.1e})")
    return PointMargins(_ratio(root.value, p.B), math.inf, root.error, route)


def _margin(point: CriticalPoint, operating: float) -> tuple[float, float]:
    """(critical / operating, its relative error) of one critical point by the check's rule
    (:func:`etcheck.checks.margins.margin.margin_from_critical`): 0 unstable at the start, inf where no value
    destabilises it (or the operating value is zero); NoAnswer where it was not located."""
    kind = point.kind
    if operating == 0 or kind in (CriticalKind.NONE_FOUND, CriticalKind.NEVER):
        return math.inf, 0.0
    if kind == CriticalKind.UNSTABLE_AT_START:
        return 0.0, 0.0
    if point.value is None:
        raise NoAnswer(point.message)
    return point.value / operating, (point.error or 0.0) / point.value if point.value else 0.0


def _ratio(critical: float, operating: float) -> float:
    return math.inf if operating == 0 else critical / operating


# --------------------------------------------------------------------------- the inputs


@dataclass(frozen=True)
class Inputs:
    """The mission's worst-case scene and how each input moves it (SI)."""

    base: Scene
    mission: Mission  # for the report's statements of the inputs (etcheck.checks.verdict.assumptions)
    required: float
    options: WhirlOptions  # the check's rung-1 settings (tolerances)

    @property
    def current(self) -> float:
        """The worst current [A]."""
        return self.base.current

    @property
    def field(self) -> float:
        """The worst field along the tether [T]."""
        return self.base.field.axial

    def scene(self, name: str, x: float) -> Scene:
        """The base scene with input ``name`` (length m, current A, end_tension N, spin_rate rad/s) set to x."""
        s = self.base
        if name == "length":
            s = with_length(s, x)
            gg = self.base.gravity_gradient
            return replace(s, tension=replace(gg, length=x).minimum) if gg is not None else s
        if name == "current":
            return replace(s, load=x * self.field, current=x)
        if name == "end_tension":
            return replace(s, tension=x)
        return replace(s, spin_rate=x)

    def margins(self, name: str, x: float) -> PointMargins:
        return point_margins(scale(self.scene(name, x)).params, self.options)


def inputs_of(mission: Mission, base: Scene, options: WhirlOptions) -> Inputs:
    return Inputs(base, mission, mission.check.required_margin, options)


#: input -> (label, unit shown, SI -> shown factor, direction: +1 the margin falls as it grows, -1 it rises,
#: the margin's guessed elasticity)
_LIMITS = {
    "length": ("longest tether", "m", 1.0, -2.5),
    "current": ("largest current", "A", 1.0, -1.0),
    "end_tension": ("smallest tension", "N", 1.0, 1.0),
    "spin_rate": ("largest spin rate", "rpm", RPM, -2.0),
}


def design_limits(mission: Mission, base: Scene, options: WhirlOptions, rung_1v: bool = False,
                  along: tuple[float, float] | None = None) -> DesignLimitsSection:
    """The four design limits of the mission's straight tether (module docstring) with the check's rung-1
    settings ``options``, computed on two cores where a core is free. ``rung_1v``: the tether has its current or
    tension along it; ``along``: then its load margin and that margin's relative error, or None where the load
    margin does not govern: the largest current follows from it exactly (the critical load of a profile of fixed
    shape does not depend on the current); the other limits are located under the smallest tension held constant
    where only the tension varies (:data:`BOUND`), and not sought under a current along the tether
    (:data:`RUNG_1V`)."""
    started = time.perf_counter()
    inp = inputs_of(mission, base, options)
    exact = {"current": _current_from_margin(inp, *along)} if rung_1v and along is not None and \
        base.spin_rate == 0 else {}
    skip = RUNG_1V if rung_1v and mission.operation.current_profile is not None else not_sought(base)  # circulatory: no bound
    sought = [name for name in _LIMITS if name not in exact and not skip]
    found = dict(zip(sought, split_map(lambda name: _limit(inp, name), sought)))
    limits = [exact.get(name) or found.get(name) or _not_sought(inp, name, skip) for name in _LIMITS]
    basis = BOUND if rung_1v and found else ""
    return DesignLimitsSection(required=inp.required, tolerance=LIMIT_TOLERANCE, limits=tuple(limits),
                               time_s=time.perf_counter() - started, basis=basis)


#: why a limit is not sought for a tether with a current along it
RUNG_1V = ("not sought with the current along the tether: each margin takes rung 1v (seconds an evaluation) and "
           "one current is no bound for a circulatory load; map it with etcheck sweep")
#: what the limits of a tether with only its tension along it are (but the largest current: rung 1v's own)
BOUND = ("under the smallest tension held constant along the tether, a conservative bound (tension stabilises; "
         "rung 1v takes seconds a margin)")


def _current_from_margin(inp: Inputs, margin: float, error: float) -> DesignLimit:
    """The largest current of a tether with profiles along it: the load margin is critical load / (|I| B0) with a
    critical load that depends on neither (the profile's shape held), so the limit is |I| × margin / required."""
    record = _not_sought(inp, "current", "")
    if not math.isfinite(margin) or margin <= 0:
        return replace(record, status="not located", note="the load margin is zero or without limit")
    return replace(record, limit=inp.current * margin / inp.required, status="located",
                   margin_at_limit=inp.required, governing="load margin", relative_error=error,
                   note="exact from rung 1v's load margin: the critical load of a profile of fixed shape does "
                        "not depend on the current")


def not_sought(base: Scene) -> str:
    """Why the limits (and the assumptions' differences) are not sought for this scene, or "": an undamped
    spinning tether's every margin takes the exact undamped determinant's spin and load lines (up to seconds a
    margin, tens of evaluations a limit); a compressive end force is not a tension to vary."""
    if base.damping_time == 0 and base.spin_rate > 0:
        return ("not sought for an undamped spinning tether: each margin takes the exact undamped determinant's "
                "spin and load lines (seconds); give tether.damping_time, or map it with etcheck sweep")
    if base.tension < 0:
        return "not sought under a compressive end force"
    return ""


def _not_sought(inp: Inputs, name: str, why: str) -> DesignLimit:
    label, unit, factor, _ = _LIMITS[name]
    return DesignLimit(input=name, label=label, unit=unit, mission_value=_mission_value(inp, name) * factor,
                       limit=None, status="not sought", margin_at_limit=None, governing=None,
                       relative_error=None, evaluations=0, note=why, end_mass_factor=None)


def _mission_value(inp: Inputs, name: str) -> float:
    return {"length": inp.base.length, "current": inp.current, "end_tension": inp.base.tension,
            "spin_rate": inp.base.spin_rate}[name]


def _limit(inp: Inputs, name: str) -> DesignLimit:
    _, _, factor, slope = _LIMITS[name]
    x0 = _mission_value(inp, name)
    record = replace(_not_sought(inp, name, ""), status="not located")
    counter = _Counted(inp, name)
    try:
        found = _solve(counter, name, x0, slope)
    except NoAnswer as exc:
        return replace(record, note=f"a margin was not located on the way: {exc}", evaluations=counter.n)
    # a margin without limit (no root) is None in JSON
    found = {k: None if isinstance(v, float) and not math.isfinite(v) else v for k, v in found.items()}
    record = replace(record, evaluations=counter.n, **found)
    if record.limit is not None:
        record = replace(record, limit=record.limit * factor)
    if name == "end_tension" and inp.base.gravity_gradient is not None and found.get("status") == "located":
        record = replace(record, **_end_masses(inp, found["limit"]))
    return record


class _Counted:
    """g(u) = ln(smallest margin / required) at x = exp(u), counting evaluations and keeping each one."""

    def __init__(self, inp: Inputs, name: str) -> None:
        self.inp, self.name, self.n, self.seen = inp, name, 0, {}

    def margins(self, x: float) -> PointMargins:
        self.n += 1
        return self.inp.margins(self.name, x)

    def __call__(self, u: float) -> float:
        m = self.margins(math.exp(u))
        g = math.log(m.smallest / self.inp.required) if 0 < m.smallest < math.inf else \
            (-_CLAMP if m.smallest == 0 else _CLAMP)
        self.seen[u] = (g, m)
        return max(min(g, _CLAMP), -_CLAMP)


def _solve(g: _Counted, name: str, x0: float, slope: float) -> dict:
    """Where g crosses zero, from the mission's value x0 (or a start of its own where x0 is zero)."""
    if name == "current" and g.inp.base.spin_rate == 0:  # load margin ∝ 1 / I exactly: no search
        m = g.margins(x0)
        limit = x0 * m.load / g.inp.required
        return {"limit": limit, "status": "located", "margin_at_limit": g.inp.required, "governing": "load margin",
                "relative_error": m.error, "note": "the load margin is critical load / (I B0): exactly ∝ 1 / I"}
    if name == "end_tension":
        at_zero = g.margins(0.0)
        if at_zero.smallest >= g.inp.required:
            return {"limit": 0.0, "status": "zero", "margin_at_limit": at_zero.smallest,
                    "governing": at_zero.governing, "relative_error": 0.0,
                    "note": "the margins are met without any tension"}
    if name == "spin_rate" and x0 == 0:
        at_rest = g.margins(0.0)
        if at_rest.smallest < g.inp.required:  # no spin can help a tether short of the margin at rest
            return {"status": "none", "margin_at_limit": at_rest.smallest, "governing": at_rest.governing,
                    "note": f"none: without spin the margin is already {at_rest.smallest:.3g}, short of the "
                            "required one (spin only lowers it)"}
    u0 = math.log(x0) if x0 > 0 else _start(g, name)
    bracket = _bracket(g, u0, slope)
    if bracket is None:
        u_end, (_, m_end) = max(g.seen.items(), key=lambda kv: abs(kv[0] - u0))
        return {"status": "none", "margin_at_limit": m_end.smallest, "governing": m_end.governing,
                "note": f"none within a factor {math.exp(SPAN):.0f}: the margin is "
                        f"{'still' if m_end.smallest >= g.inp.required else 'only'} {m_end.smallest:.3g} at "
                        f"{_plain(math.exp(u_end) * _LIMITS[name][2])} {_LIMITS[name][1]}"}
    u = brentq(g, *sorted(bracket), xtol=LIMIT_TOLERANCE, rtol=1e-15)
    m = g.margins(math.exp(u))
    return {"limit": math.exp(u), "status": "located", "margin_at_limit": m.smallest, "governing": m.governing,
            "relative_error": LIMIT_TOLERANCE + m.error / max(abs(_slope(g, u)), 1e-12)}


def _plain(x: float) -> str:
    """x to 4 digits, without an exponent between 1e-3 and 1e9 (50000, not 5e+04)."""
    text = f"{x:.4g}"
    return f"{x:.0f}" if "e+" in text and x < 1e9 else text


def _start(g: _Counted, name: str) -> float:
    """ln of a first trial value where the mission's is zero: the tension of a taut string whose first critical
    load I B0 = 2 pi T / L meets the required margin; the spin at which the spin margin alone is the required one."""
    inp = g.inp
    if name == "end_tension":
        return math.log(max(inp.required * inp.base.load * inp.base.length / (2 * math.pi), 1e-12))
    if name != "spin_rate":
        raise NoAnswer(f"the mission's {name.replace('_', ' ')} is zero: no limit is sought from it")
    p = scale(inp.base).params
    try:
        _, spin = critical_values(p, inp.options, straight_route(p), spin=True)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
        raise NoAnswer(f"{type(exc).__name__}: {exc}") from None
    w = spin.value if spin.value is not None else math.nan
    if not (math.isfinite(w) and w > 0):
        raise NoAnswer("the critical spin at the operating load was not located")
    return math.log(scale(inp.base).scales.rad_s(w) / inp.required)


def _bracket(g: _Counted, u0: float, slope: float) -> tuple[float, float] | None:
    """Two values of u about the crossing, from u0 by secant steps (at least doubling); None where there is
    none within SPAN of u0 (the last value tried is then u0 +- SPAN)."""
    a, ga = u0, g(u0)
    step = -ga / slope
    step = math.copysign(min(max(abs(step), 1e-3), 2.0), step if step else -slope)
    end = u0 + math.copysign(SPAN, step)
    while True:
        b = end if (a + step - end) * step > 0 else a + step
        gb = g(b)
        if (gb >= 0) != (ga >= 0):
            return a, b
        if b == end:
            return None
        secant = (gb - ga) / (b - a)
        guess = -gb / secant if secant and (secant > 0) == (slope > 0) else 2.0 * step
        step = math.copysign(min(max(abs(guess), 2.0 * abs(step)), 4.0), step)
        a, ga = b, gb


def _slope(g: _Counted, u: float) -> float:
    """d g / d u at u from the two evaluations nearest to it (one each side where there are)."""
    pts = sorted(g.seen.items(), key=lambda kv: abs(kv[0] - u))
    (u1, (g1, _)), (u2, (g2, _)) = pts[0], next(kv for kv in pts[1:] if kv[0] != pts[0][0])
    return (g2 - g1) / (u2 - u1)


def _end_masses(inp: Inputs, tension: float) -> dict:
    """The common factor on both end masses whose gravity-gradient tension (its smallest, as the check uses)
    is ``tension`` N."""
    gg = inp.base.gravity_gradient

    def short(k: float) -> float:
        return replace(gg, upper_mass=k * gg.upper_mass, lower_mass=k * gg.lower_mass).minimum - tension

    hi = 2.0
    while short(hi) < 0 and hi < 1e9:
        hi *= 2.0
    k = brentq(short, 0.0, hi, xtol=1e-14, rtol=1e-12)
    return {"end_mass_factor": k,
            "note": f"end masses × {k:.3g}: {k * gg.upper_mass:.3g} kg and {k * gg.lower_mass:.3g} kg"}
