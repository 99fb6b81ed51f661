"""What the models assume, computed for the scene: is the tether straight, slender and inextensible enough
for the straight-tether model, and the text of the report's validity list.

**Straightness.** The model linearises about a straight tether with the field along it. The field component
across the tether, B⊥, pushes it sideways with the Lorentz load q = |I| B⊥ per length (the electrodynamic drag
the tether is flown for). Held at its ends under the tension T, with bending stiffness EI about the axis it
bends (the weak axis, the conservative choice), the tether is a tensioned beam under a uniform load,
EI w'''' - T w'' = q with w = w' = 0 at both ends; its bow at mid-span is

    w = q L² / (8 T) · [1 - tanh(k L / 4) / (k L / 4)],   k = √(T / EI),

which is the taut string's q L² / (8 T) when k L is large and the clamped beam's q L⁴ / (384 EI) when T -> 0.
With a pinned end the beam's bow at mid-span is the pinned one (module function :func:`mid_span_bow`), the
larger. A bow of w / L tilts the tether by about 4 w / L rad near its ends (taut string), which changes the field along
it by up to B⊥ · 4 w / L: above :data:`BOW_LIMIT` (2 %: ends turned by about 4.6°, the field along the tether
changed by up to 8 % of B⊥) the straight base state does not represent the tether, and the check's verdict is
"outside the model's validity".

**Slenderness.** Rod theory needs P = I1 / (A L²) << 1: above :data:`P_LIMIT` the tether is too short (or
thick) for it (the sweep uses the same limit).

**Extensibility.** The rod is inextensible: the strain T / (E A) under the largest tension along the tether
must stay small (:data:`STRAIN_LIMIT`, 1 %: the critical values move by about the strain, and metal tethers
yield near 0.2-0.5 %). Checked where the mission gives E and A.

SI floats throughout (N, m, T, N m²).
"""

from __future__ import annotations

import math

from etcheck.checks.margins.attachment import alternative_ends
from etcheck.checks.plan import EXACT, PROFILES, Plan
from etcheck.checks.results.sections_buckled import PostbucklingSection
from etcheck.checks.results.sections_verdict import LateralLoad, ModelValidity, ValidityCheck
from etcheck.input.mission import Mission
from etcheck.numerics.optimize import brentq
from etcheck.rod.core.ends import Ends, describe, is_welded
from etcheck.scaling import Scaled, Scene

#: Bow at mid-span over the length above which the straight-tether model does not describe the tether.
BOW_LIMIT = 0.02
#: Rotary inertia ratio P above which the tether is too short (or thick) for rod theory (P << 1).
P_LIMIT = 0.1
#: P above which rod theory's corrections are noticeable (said, not refused).
P_NOTE = 1e-2
#: Axial strain T / (E A) above which the inextensible rod does not describe the tether.
STRAIN_LIMIT = 1e-2


def mid_span_bow(load: float, length: float, tension: float, stiffness: float, clamped: bool = True) -> float:
    """Deflection (m) at mid-span of a tensioned beam under a uniform lateral load, its ends clamped or pinned.

    ``load`` q (N/m), ``length`` L (m), ``tension`` T >= 0 (N), ``stiffness`` EI (N m²). Clamped ends: the
    module docstring's w. Pinned ends (w = w'' = 0): w = q L² / (8 T) · [1 - 2 (1 - sech z) / z²], z = k L / 2,
    the taut string's when z is large and 5 q L⁴ / (384 EI) when T -> 0. Each bracket is evaluated by its series
    below 0.1 (no cancellation).
    """
    if load == 0.0:
        return 0.0
    if tension <= 0.0:
        return (1.0 if clamped else 5.0) * load * length**4 / (384.0 * stiffness)
    k = math.sqrt(tension / stiffness)
    return load * length**2 / (8.0 * tension) * (_clamped_bracket(k * length / 4) if clamped else
                                                  _pinned_bracket(k * length / 2))


def _clamped_bracket(y: float) -> float:
    """1 - tanh(y) / y."""
    if y < 0.1:
        y2 = y * y
        return y2 * (1.0 / 3.0 - y2 * (2.0 / 15.0 - y2 * (17.0 / 315.0 - y2 * 62.0 / 2835.0)))
    return 1.0 - math.tanh(y) / y


def _pinned_bracket(z: float) -> float:
    """1 - 2 (1 - sech z) / z²."""
    z2 = z * z
    if z < 0.1:
        return z2 * (5.0 / 12.0 - z2 * (61.0 / 360.0 - z2 * (277.0 / 4032.0 - z2 * 50521.0 / 1814400.0)))
    return 1.0 - 2.0 * (1.0 - 2.0 * math.exp(-z) / (1.0 + math.exp(-2.0 * z))) / z2


def tension_for_bow(load: float, length: float, stiffness: float, bow: float, clamped: bool = True) -> float:
    """Smallest tension (N) that keeps the mid-span bow at most ``bow`` (m); 0 where bending alone does."""
    if mid_span_bow(load, length, 0.0, stiffness, clamped) <= bow:
        return 0.0
    hi = load * length**2 / (8.0 * bow)  # the string's: the beam's bending only lowers the bow
    return brentq(lambda t: mid_span_bow(load, length, t, stiffness, clamped) - bow, 0.0, hi, rtol=1e-10)


def cross_field_source(mission: Mission) -> tuple[str, bool]:
    """Where the field across the tether (the scene's ``field.cross``, etcheck.scaling) comes from, and whether
    it is an assumption: the mission's provenance, for the report.

    Stated (``operation.cross_field``), else from the orbit (the largest √(|B|² - (B·up)²) over the window:
    the field across a tether on the local vertical), else etcheck's default: the worst field along the
    tether (a field of that size may as well lie across it).
    """
    if mission.operation.cross_field is not None:
        return "operation.cross_field", mission.provenance.is_assumed("operation.cross_field")
    if mission.orbit is not None:
        return "the largest over the orbit (IGRF, tether on the local vertical)", mission.provenance.is_assumed("orbit")
    return ("not given: taken equal to the worst axial field (a field of that size may lie across the "
            "tether); give [operation] cross_field or an [orbit] table", True)


def lateral_load(mission: Mission, sc: Scene) -> LateralLoad:
    """The Lorentz load across the tether and the bow it implies (SI); the mission for where the field across it
    comes from (:func:`cross_field_source`)."""
    source, assumed = cross_field_source(mission)
    b_perp, current = sc.field.cross, sc.current
    q = current * b_perp
    clamped = all(end.holds_slope for end in Ends.of(sc.ends).conditions)  # a pinned end lets it bow more: both taken pinned then
    bow = mid_span_bow(q, sc.length, sc.tension, sc.EI2, clamped)
    outside = bow > BOW_LIMIT * sc.length
    return LateralLoad(
        cross_field_T=b_perp,
        cross_field_source=source,
        cross_field_assumed=assumed,
        current_A=current,
        load_N_per_m=q,
        total_N=q * sc.length,
        tension_N=sc.tension,
        load_over_tension=q * sc.length / sc.tension if sc.tension > 0 else None,
        stiffness_N_m2=sc.EI2,
        bow_m=bow,
        bow_over_length=bow / sc.length,
        limit=BOW_LIMIT,
        # what would bring a bowed tether within the limit (None within it: nothing to bring)
        tension_for_limit_N=tension_for_bow(q, sc.length, sc.EI2, BOW_LIMIT * sc.length, clamped) if outside else None,
        ends="welded (clamped)" if clamped else "pinned (a pinned end, taken at both)",
        cross_field_for_limit_T=b_perp * BOW_LIMIT * sc.length / bow if outside else None,
    )


def model_validity(mission: Mission, sc: Scene) -> ModelValidity:
    """Straightness, slenderness and extensibility of the scene against the model's limits (module docstring);
    ``within`` False with the reasons where any is exceeded."""
    lat = lateral_load(mission, sc)
    checks = [_straightness(lat), _slenderness(sc.P), _extensibility(sc)]
    reasons = tuple(c.summary for c in checks if c.within is False)
    return ModelValidity(within=not reasons, reasons=reasons, checks=tuple(checks), lateral=lat)


def _straightness(lat: LateralLoad) -> ValidityCheck:
    w = lat.bow_over_length
    within = w <= BOW_LIMIT
    fix = ""
    if not within:
        fix = (f"; straight within {100 * BOW_LIMIT:g} % it would need a tension of at least "
               f"{lat.tension_for_limit_N:.3g} N or a field across it of at most "
               f"{lat.cross_field_for_limit_T * 1e6:.3g} µT")
    ratio = "" if lat.load_over_tension is None else f", {lat.load_over_tension:.3g} times the tension"
    detail = (f"the lateral Lorentz load |I|·B⊥ = {lat.current_A:.3g} A × {lat.cross_field_T * 1e6:.3g} µT = "
              f"{lat.load_N_per_m:.3g} N/m ({lat.total_N:.3g} N in all{ratio}) bows the tether by "
              f"{lat.bow_m:.3g} m at mid-span, {_share(w)} (limit {100 * BOW_LIMIT:g} %){fix}")
    bows = _share(w) if w <= 1.0 else f"{w:.3g} times its length"
    summary = f"the tether bows by {bows} under the lateral Lorentz load (the model's limit {100 * BOW_LIMIT:g} %)"
    return ValidityCheck(name="straight under the lateral Lorentz load", quantity="bow at mid-span / L", value=w,
                         limit=BOW_LIMIT, within=within, detail=detail, summary=summary)


def _share(w: float) -> str:
    """A bow over the length in words: a percentage up to the length, a multiple beyond (where the linear bow
    says only that nothing holds the tether straight)."""
    if w <= 1.0:
        return f"{100 * w:.3g} % of its length"
    return f"{w:.3g} times its length (a linear estimate: nothing holds it straight)"


def _slenderness(P: float) -> ValidityCheck:
    within = P <= P_LIMIT
    if not within:
        detail = f"P = {P:.3g} > {P_LIMIT:g}: the tether is too short (or thick) for rod theory (P << 1)"
    elif P > P_NOTE:
        detail = f"P = {P:.3g}: slender enough for rod theory (limit {P_LIMIT:g}), with noticeable rotary inertia"
    else:
        detail = f"P = {P:.3g}: a slender rod (limit {P_LIMIT:g})"
    return ValidityCheck(
        name="slender (rod theory, rotary inertia)", quantity="P = I1 / (A L²)", value=P, limit=P_LIMIT,
        within=within, detail=detail,
        summary=f"the tether is too short (or thick) for rod theory (P = {P:.3g}, the model's limit {P_LIMIT:g})")


def _extensibility(sc: Scene) -> ValidityCheck:
    base = {"name": "inextensible", "quantity": "strain T / (E A)", "limit": STRAIN_LIMIT,
            "summary": f"the tether stretches past the inextensible model's limit (strain above {100 * STRAIN_LIMIT:g} %)"}
    ea = sc.axial_stiffness
    if ea is None:
        return ValidityCheck(**base, value=None, within=None,
                             detail="not checked: the mission gives no youngs_modulus and cross_section_area")
    tension = sc.largest_tension
    strain = tension / ea
    where = "the largest tension, at the centre of mass" if sc.gravity_gradient is not None else "the end tension"
    within = strain <= STRAIN_LIMIT
    return ValidityCheck(**base, value=strain, within=within,
                         detail=f"strain {strain:.2g} under {where} ({tension:.3g} N, E A = {ea:.3g} N; "
                                f"limit {100 * STRAIN_LIMIT:g} %)")


def _after_buckling(post: PostbucklingSection | None, ends) -> str:
    if not is_welded(ends):
        return ("Linear stability of the straight tether: margins say where it first buckles or whirls. The buckled "
                "tether (rungs 2-3) is computed for welded ends only and is not analysed for these ends.")
    if post and post.computed:
        return ("Past (or near) the first critical load the first post-buckling branch b1 is followed as nonlinear "
                "whirling equilibria (rung 2, Chebyshev collocation, Newton with the exact Jacobian, pseudo-arclength "
                "continuation) and each state's stability from its linearisation (rung 3); other branches (b2, b12, "
                "...) are in `etcheck diagram`. Every measure is checked at a second resolution.")
    return ("Linear stability of the straight tether: margins say where it first buckles or whirls; when the operating "
            "point is within the required margin of that load, the buckled tether is analysed too (rungs 2-3).")


def _model(ends) -> str:
    held = "welded (clamped) at both ends" if is_welded(ends) else describe(ends)
    return (f"Model: inextensible, unshearable, intrinsically straight Kirchhoff rod, {held}, one current along "
            "the whole tether, uniform field along the undeformed axis (Valverde & van der Heijden, arXiv:0810.3668).")


def _attachment(ends) -> str:
    """What the attachment means for the answers, and the other attachment beside each margin."""
    if is_welded(ends):
        held = ("Welded ends, as in the paper: the end bodies hold the tether's position, direction and twist. A "
                "tether on a gimbal, a hinge or an exit guide passes no bending moment (pinned) and buckles much "
                "sooner; each margin is shown beside the same margin with both ends pinned.")
    else:
        held = ("The paper welds both ends; a pinned end holds the position but passes no bending moment "
                "(u = u'' = v = v'' = 0 on the straight tether; docs/model.md), which lowers the critical loads; "
                "torsion decouples from bending on the straight tether, so the twist condition (gimbal or swivel) "
                f"changes only the torsional frequencies. Each margin is shown beside the same margin {_others(ends)}; "
                "the buckled tether (rungs 2-3) is computed for welded ends only and is not computed here.")
    return held + (" The alternatives are computed on the same rung with the critical values only (no spectrum).")


def _others(ends) -> str:
    alts = alternative_ends(ends)
    if len(alts) == 2:
        return "with both ends welded and with both pinned, which bound it"
    return f"with both ends {alts[0][0]}"


def validity(mission: Mission, scaled: Scaled, chosen: Plan, post: PostbucklingSection | None = None) -> list[str]:
    """The statements of the report's validity list: what the model assumes and how each answer was computed."""
    p = scaled.params
    items = [
        _model(p.ends),
        _after_buckling(post, p.ends),
        _attachment(p.ends),
        "The load is the worst case |I| x |B0| over the given ranges; the field across the tether drives the "
        "intended drag and bows the tether (its straightness is checked on page 1), it does not enter the "
        "stability problem.",
    ]
    if chosen.rung == 0:
        items.append(
            ("Rung 0 roots of chi(beta) are located" if is_welded(p.ends) else
             "Rung 0 roots of the closed-form characteristic function of these ends are located")
            + " to ~1e-15 relative (a-posteriori Newton step); "
            "the static loads do not depend on P, damping or mass per length."
        )
    if chosen.route == PROFILES:
        items += _profiles_items(p, scaled)
    elif chosen.rung == 1 and chosen.route == EXACT:
        items += _exact_items(p)
    elif chosen.rung == 1:
        items += _spectral_items(p)
    gg = mission.operation.gravity_gradient
    if gg is not None:
        items.append(
            f"Tension from the gravity gradient (tether.end_masses, {gg.rate_source}): the tension varies along "
            f"the tether from {gg.minimum:.4g} N at the {gg.minimum_at} to {gg.maximum:.4g} N at the centre of mass, "
            + ("and the check uses that profile (rung 1v); the smallest tension held constant along the tether is "
               "reported beside it as a bound (tension stabilises). " if chosen.route == PROFILES else
               "and this draft holds the smallest constant along the tether, a conservative bound (tension "
               "stabilises; a sign-off uses the profile). ")
            + "The axial pull of the gradient is taken along the "
            "undeformed tether; the lateral forces of the orbital frame on a displaced element (Hill's equations) "
            "are left out. Tether on the local vertical of a circular orbit, no libration (at the extremes of a "
            "libration swing the tension is lower, by about cos² of the angle)."
        )
    return items


def _exact_items(p) -> list[str]:
    return [
        "The straight tether's linear problem (Sec. V B) has constant coefficients: its characteristic "
        "determinant, with each growing or decaying exponential scaled at the end where it is small, is exact "
        "at any tension and stiffness ratio. Critical values are its first roots (bracketed, then Brent's "
        "method); each error estimate is the root's distance to that of a second, independent formulation.",
        "With damping the straight tether loses stability only where its static operator is singular "
        "(Kelvin-Tait-Chetaev), so those roots are the whole stability boundary; the map's stable rows run from "
        "zero load to the first root at each spin. Frequencies at the operating point (Campbell diagram, "
        "operating eigenvalues) are not computed on this route." if p.gamma > 0 else
        "Without damping the determinant is a real function of mu = -lambda^2 whose real roots are the "
        "vibration frequencies (for an isotropic tether, R = 1, one complex scalar problem per direction of "
        "whirl): divergence and flutter points, and the edges of stable spin windows, are located as its "
        "roots and folds, not sampled. No map, Campbell diagram or operating eigenvalues on this route.",
    ]


def _spectral_items(p) -> list[str]:
    items = [
        "Rung 1 linearises the full O(delta) equations (Sec. V B) about the straight tether and solves the "
        "damped gyroscopic eigenproblem by Chebyshev collocation; every eigenvalue and critical value is "
        "computed at two resolutions and their agreement is its error estimate (Appendix A).",
        "Stability is judged on the lowest 12 eigenvalue pairs (Re lambda > 1e-9 counts as growing); higher "
        "modes are stiffened by bending. With damping, the straight tether can only lose stability where "
        "its static operator is singular (divergence, Kelvin-Tait-Chetaev); without damping, gyroscopic "
        "windows above the critical spin may appear and are lost with any damping.",
        "The stability map is exact with damping (each spin row cut at its static points) and sampled on a "
        "grid without (boundaries interpolated between grid points); the margins and critical values in the "
        "tables are located to 1e-10.",
    ]
    if p.gamma > 0:
        items.append(
            f"Eigenvalues left of -1/gamma = {-1 / p.gamma:.4g} on the real axis (the Kelvin-Voigt "
            "accumulation of heavily damped high modes) are not listed: they decay faster than the material "
            "relaxation rate."
        )
    return items


def _profiles_items(p, scaled: Scaled) -> list[str]:
    """What rung 1v assumes and how it is checked."""
    t = scaled.tether
    items = [
        "Rung 1v linearises about the straight tether with its current and tension along it (docs/model.md "
        "section 10): Chebyshev collocation on subdomains graded towards the ends (down to the boundary layers "
        "of the weak axis), stability read from the eigenvalues (Re lambda > 1e-8 |lambda| counts as growing). Every "
        "critical value is located on two meshes; their distance (with the round-off of a slow crossing) is its "
        "error. An independent finite-element discretisation agrees with it in the tests.",
    ]
    if t is not None and t.circulatory:
        items.append(
            "With a current that varies along the tether the magnetic load has no potential (it is circulatory): the "
            "tether can lose stability by flutter, two vibration modes merging into one that grows, and damping can "
            "lower the threshold (Ziegler's paradox), so the threshold is computed undamped and over the damping the "
            "mission allows. A round wire (R = 1) flutters at any load without damping.")
    return items
