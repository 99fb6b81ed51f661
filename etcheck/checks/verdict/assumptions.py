"""The assumptions that decide the verdict, one record each, with how far the margin moves with them.

Page 1 of the report lists them: how the ends are attached, the current along the tether, the tension and
where it comes from, the field along the tether and where it comes from, and the damping. Each record says
the value as the check used it, where it comes from (``flag``: "data" as given, "assumed" where the mission
lists the field under ``[mission] assumed``, "default" where etcheck chose it, "model" where the model
assumes it), and how far the governing margin (the smallest margin of the straight tether) moves with it:
its elasticity d ln margin / d ln input, and the margin under an alternative where one is computed (no
tension; no damping). The margins come from the routes of :mod:`etcheck.checks.verdict.design_limits`.

Elasticities: the load margin is critical load / (|I| B0) with a critical load that depends on neither, so
its elasticity in the current and in the field is exactly -1; with damping the critical values do not depend
on the damping (Kelvin-Tait-Chetaev: the static operator does not contain it), exactly 0. Elsewhere (the
tension, a spin margin) central differences of ln margin in ln input with relative step :data:`STEP`.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

from etcheck.checks.margins.margin import LOAD_AT_REST, LOAD_AT_SPIN
from etcheck.checks.results.sections import AlternativeMargin
from etcheck.checks.results.sections_straight import ProfilesSection
from etcheck.checks.results.sections_verdict import AssumptionRecord, AssumptionsSection
from etcheck.checks.rungs.straight import WhirlOptions
from etcheck.checks.verdict.design_limits import Inputs, NoAnswer, inputs_of, not_sought, point_margins
from etcheck.input.mission import DEFAULT_GAMMA, Mission
from etcheck.rod.core.ends import describe
from etcheck.scaling import Scene, scale

#: relative step of the central differences (truncation ~ STEP^2, round-off ~ margin error / STEP)
STEP = 1e-3

DATA, ASSUMED, DEFAULT, MODEL = "data", "assumed", "default", "model"


def assumptions(mission: Mission, base: Scene, margin_name: str | None, margin_value: float | None,
                options: WhirlOptions, other_ends: tuple[AlternativeMargin, ...] = (),
                profiles: ProfilesSection | None = None) -> AssumptionsSection:
    """The records of the module docstring for the mission's worst-case scene ``base``; ``margin_name`` and
    ``margin_value``: the governing margin as the check reported it, ``options`` the check's rung-1 settings,
    ``other_ends`` the same margin under the other attachments of the ends (:mod:`etcheck.checks.margins.attachment`);
    ``profiles``: rung 1v's section where the current or the tension varies along the tether (then
    :func:`_profile_rows`)."""
    started = time.perf_counter()
    inp = inputs_of(mission, base, options)
    if profiles is not None:
        rows = [_ends(mission, other_ends), *_profile_rows(inp, margin_name, margin_value, profiles)]
    else:
        rows = [_ends(mission, other_ends), _current(inp), _tension(inp), _field(inp), _damping(inp)]
    return AssumptionsSection(margin=margin_name, margin_value=margin_value, required=mission.check.required_margin,
                              rows=tuple(rows), time_s=time.perf_counter() - started)


def _flag(mission: Mission, *fields: str) -> str:
    return ASSUMED if mission.provenance.is_assumed(*fields) else DATA


def _record(key: str, assumption: str, value: str, source: str, flag: str, note: str = "",
            elasticity: float | None = None, method: str = "", alternative: str | None = None,
            margin: float | None = None) -> AssumptionRecord:
    return AssumptionRecord(key=key, assumption=assumption, value=value, source=source, flag=flag,
                            elasticity=elasticity, elasticity_method=method, alternative=alternative,
                            margin_alternative=margin, note=note)


def _ends(mission: Mission, others: tuple[AlternativeMargin, ...]) -> AssumptionRecord:
    """How the ends are held, and the governing margin under each other attachment (computed by the check)."""
    ends = mission.tether.end_conditions
    if "tether.end_conditions" in mission.provenance.given:
        source, flag = "tether.end_conditions", _flag(mission, "tether.end_conditions")
    else:
        source, flag = "not given: welded, as in the paper", DEFAULT
    alt = others[0] if others else None
    alternatives = "; ".join(f"{_short(a.ends)}: {_value(a.value)}" for a in others[1:])
    return _record("ends", "end attachment", describe(ends), source, flag, alternatives, None, "",
                   _short(alt.ends) if alt else None, alt.value if alt else None)


def _short(ends: list[str]) -> str:
    return f"both ends {ends[0]}" if ends[0] == ends[1] else describe(tuple(ends))


def _value(x: float | None) -> str:
    return "unlimited" if x is None else f"{x:.3g}"


def _current(inp: Inputs) -> AssumptionRecord:
    m = inp.mission
    lo, hi = m.operation.current_range_A
    value = f"{inp.current:.4g} A" + (f" (worst of {lo:.4g} … {hi:.4g} A)" if lo != hi else "")
    value += "; uniform along the tether"
    el, how = _load_elasticity(inp)
    return _record("current", "current along the tether", value,
                   "operation.current; uniform: no operation.current_profile", _flag(m, "operation.current"),
                   "right for an insulated tether; a bare tether collects its current along its length, so the "
                   "current varies along it (the load is then circulatory and flutter is possible): give "
                   "operation.current_profile", el, how)


def _tension(inp: Inputs, uniform_routes: bool = True) -> AssumptionRecord:
    """The tension record of a tether with one tension along it (end masses make a profile: rung 1v's records);
    ``uniform_routes`` False: its margins come from rung 1v, so no elasticity or alternative is computed here."""
    m, T = inp.mission, inp.base.tension
    if T != 0:
        source, flag = "operation.end_tension", _flag(m, "operation.end_tension")
        value = f"{T:.4g} N" + (" (compression)" if T < 0 else "")
    elif "operation.end_tension" in m.provenance.given:
        source, value, flag = "operation.end_tension: no tension", "0 N", _flag(m, "operation.end_tension")
    else:
        source, value, flag = "not given: no tension (conservative)", "0 N", DEFAULT
    if T == 0:
        return _record("tension", "end tension", value, source, flag,
                       "tension stabilises the straight tether; without it the tether is held by bending alone")
    if not uniform_routes:
        return _record("tension", "end tension", value, source, flag, "tension stabilises the straight tether",
                       None, _RUNG_1V_COST if T > 0 else "")
    el, how = _difference(inp, "end_tension", T) if T > 0 else (None, "")
    alt = _margin_or_none(inp, "end_tension", 0.0)
    return _record("tension", "end tension", value, source, flag, "tension stabilises the straight tether",
                   el, how, "no end force (T = 0)", alt)


def _rate_source(text: str) -> str:
    """The orbit rate's source in a few words: the part before its first comma or colon."""
    return text.split(", at apogee")[0].split(": 3 Omega")[0].split(", mean motion")[0]


def _field(inp: Inputs, elasticity: tuple[float | None, str] | None = None) -> AssumptionRecord:
    """The field record; ``elasticity`` (value, how) where the caller has it, else from the uniform routes."""
    m = inp.mission
    value = f"{inp.field * 1e6:.4g} µT"
    if m.orbit is not None:
        source = f"the worst over the [orbit] ({m.orbit.model}, with libration)"
        flag = _flag(m, "orbit")
    else:
        lo, hi = m.operation.axial_field_range_uT
        source = "operation.axial_field" + (f" (worst of {lo:.4g} … {hi:.4g} µT)" if lo != hi else "")
        flag = _flag(m, "operation.axial_field")
    el, how = _load_elasticity(inp) if elasticity is None else elasticity
    return _record("field", "field along the tether", value, source, flag,
                   "uniform along the undeformed tether (the model's assumption)", el, how)


def _damping(inp: Inputs) -> AssumptionRecord:
    m = inp.mission
    p = scale(inp.base).params
    if m.tether.damping_time is None:
        value, source, flag = (f"γ = {p.gamma:.4g} ({inp.base.damping_time:.3g} s)",
                               "not given: the paper's estimate (Sec. VII B)", DEFAULT)
    else:
        value, source, flag = (f"damping time {inp.base.damping_time:.3g} s (γ = {p.gamma:.4g})",
                               "tether.damping_time", _flag(m, "tether.damping_time"))
    if p.gamma > 0:
        alt = _margin_or_none(inp, "damping_time", 0.0)
        return _record("damping", "material damping (Kelvin-Voigt)", value, source, flag,
                       "with any damping the straight tether loses stability only where its static operator is "
                       "singular (Kelvin-Tait-Chetaev): its critical values do not depend on the damping", 0.0,
                       "exact (Kelvin-Tait-Chetaev)", "no damping (flutter possible)", alt)
    gamma_time = scale(inp.base).scales.damping_time(DEFAULT_GAMMA)
    alt = _margin_or_none(inp, "damping_time", gamma_time)
    return _record("damping", "material damping (Kelvin-Voigt)", value, source, flag,
                   "without damping the straight tether can also lose stability by flutter, and gyroscopic "
                   "windows above the critical spin close with any damping", None, "",
                   f"the paper's damping γ = {DEFAULT_GAMMA}", alt)


def _margin_at(inp: Inputs, name: str, x: float) -> float:
    why = not_sought(inp.base)  # an undamped spinning tether: its margins are not re-evaluated (seconds each)
    if why and name != "damping_time":
        raise NoAnswer(why)
    if name == "damping_time":
        return point_margins(scale(replace(inp.base, damping_time=x)).params, inp.options).smallest
    return inp.margins(name, x).smallest


def _margin_or_none(inp: Inputs, name: str, x: float) -> float | None:
    try:
        value = _margin_at(inp, name, x)
    except NoAnswer:
        return None
    return value if math.isfinite(value) else None


def _load_elasticity(inp: Inputs) -> tuple[float | None, str]:
    """d ln margin / d ln (|I| B0): -1 exactly without spin (the load margin alone), else a central difference."""
    if inp.base.spin_rate == 0:
        return -1.0, "exact: the load margin is critical load / (|I| B0)"
    return _difference(inp, "current", inp.current)


def _difference(inp: Inputs, name: str, x: float) -> tuple[float | None, str]:
    """Central difference of ln margin in ln x (relative step STEP); None where a margin is not located or
    infinite."""
    try:
        up, down = (_margin_at(inp, name, x * math.exp(s * STEP)) for s in (1.0, -1.0))
    except NoAnswer as exc:
        return None, str(exc) if str(exc).startswith("not sought") else f"not located: {exc}"
    if not (0 < up < math.inf and 0 < down < math.inf) or math.isnan(up - down):
        return None, "not differentiable here (a margin of zero or without limit)"
    return (math.log(up) - math.log(down)) / (2 * STEP), f"central difference, relative step {STEP:g}"


# --------------------------------------------------------------------------- profiles along the tether (rung 1v)

#: why no difference is taken with profiles along the tether
_RUNG_1V_COST = "not computed: each margin with profiles along the tether takes rung 1v (seconds)"


def _profile_rows(inp: Inputs, name: str | None, value: float | None,
                  profiles: ProfilesSection) -> list[AssumptionRecord]:
    """The current, tension, field and damping records of a tether with its current or tension along it (rung 1v,
    :mod:`etcheck.checks.rungs.profiles`). The load margin's elasticity in the largest current and in the field is -1
    exactly (rung 1v's load is B b(s), b fixed); the alternatives are what the check computed beside its verdict:
    the uniform check (one current, the smallest tension held constant), the smallest tension held constant under
    the profile of current (``profiles.uniform_tension_bound``) and no damping (``profiles.undamped``)."""
    m = inp.mission
    p = scale(inp.base).params
    load_governs = name == LOAD_AT_SPIN or name == LOAD_AT_REST
    if value is None or not 0 < value < math.inf:
        exact = (None, "the margin is zero or without limit: no elasticity")
    elif load_governs:
        exact = (-1.0, "exact: the load margin is critical load / (|I| B0), the shape of the profile fixed")
    else:
        exact = (None, _RUNG_1V_COST)
    cp = m.operation.current_profile
    # the uniform check's margin (one current, the smallest tension), where an alternative below shows it
    uniform = _margin_or_none(inp, "current", inp.current) \
        if cp is not None or profiles.uniform_tension_bound is None else None

    def ratio(point) -> float | None:
        """The load margin at another critical load (dimensionless), where the load margin governs."""
        if not load_governs or point is None or point.value is None or p.B == 0:
            return None
        return point.value / p.B

    lo, hi = m.operation.current_range_A
    current = f"largest {inp.current:.4g} A" + (f" (worst of {lo:.4g} … {hi:.4g} A)" if lo != hi else "")
    if cp is None:
        current_row = _record("current", "current along the tether", current + "; uniform along the tether",
                              "operation.current", _flag(m, "operation.current"),
                              "an insulated tether: one current along its length", *exact)
    else:
        how = "orbital-motion-limited collection" if cp.collection is not None else "the points given"
        current_row = _record(
            "current", "current along the tether", f"{current}; varies along the tether ({how})",
            "operation.current_profile", _flag(m, "operation.current", "operation.current_profile",
                                                "operation.collection"),
            "a current that varies along the tether makes the magnetic load circulatory: flutter is possible and "
            "damping can lower the threshold", *exact,
            "one current along the whole tether (the uniform check, smallest tension held constant)", uniform)
    tension_row = _profile_tension(inp, ratio(profiles.uniform_tension_bound),
                                   uniform if cp is None else None)
    field_row = _field(inp, exact)
    d = profiles.damping
    undamped = ratio(profiles.undamped) if d.gamma > 0 else None
    damping_row = _record(
        "damping", "material damping (Kelvin-Voigt)", f"γ = {d.gamma:.4g} ({d.damping_time_s:.3g} s)",
        "tether.damping_time" if m.tether.damping_time is not None else "not given: the least favourable up to the "
        "paper's estimate (Sec. VII B)", _flag(m, "tether.damping_time") if m.tether.damping_time is not None else DEFAULT,
        d.why, *_damping_elasticity(profiles.circulatory, d.gamma),
        "no damping" if undamped is not None else None, undamped)
    return [current_row, tension_row, field_row, damping_row]


def _damping_elasticity(circulatory: bool, gamma: float) -> tuple[float | None, str]:
    """How the margin of rung 1v moves with the damping: not an elasticity under a circulatory load (damping can
    lower its threshold: Ziegler), exactly 0 under a conservative one with damping (Kelvin-Tait-Chetaev)."""
    if circulatory:
        return None, "not an elasticity: with a circulatory load damping can lower the threshold (Ziegler)"
    if gamma > 0:
        return 0.0, "exact (Kelvin-Tait-Chetaev: a conservative load)"
    return None, _RUNG_1V_COST


def _profile_tension(inp: Inputs, bound: float | None, uniform: float | None) -> AssumptionRecord:
    """The tension record with a profile of current or of tension: under the gravity gradient the profile is used
    and the smallest tension held constant is the alternative (``bound``, computed by the check); with one tension
    along the tether the uniform check's margin is the one under its tension."""
    m = inp.mission
    gg = m.operation.gravity_gradient
    if gg is None:
        return _tension(inp, uniform_routes=False)
    source = (f"gravity gradient: end masses {gg.upper_mass:.4g} kg, {gg.lower_mass:.4g} kg (tether.end_masses), "
              f"Ω = {gg.orbit_rate:.4g} rad/s ({_rate_source(gg.rate_source)})")
    value = f"the profile along the tether: {gg.minimum:.4g} N ({gg.minimum_at}) … {gg.maximum:.4g} N (centre)"
    alt, margin = ("the smallest tension held constant along the tether", bound) if bound is not None else \
        ("the smallest tension held constant, one current (the uniform check)", uniform)
    return _record("tension", "tension along the tether", value, source, _flag(m, "tether.end_masses"),
                   "tension stabilises the straight tether; the profile is larger than its smallest value almost "
                   "everywhere", None, _RUNG_1V_COST, alt if margin is not None else None, margin)
