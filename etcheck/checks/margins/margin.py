"""Results -> margins and verdicts, back in physical units."""

from __future__ import annotations

from dataclasses import replace
from enum import StrEnum

from etcheck.checks.plan import PROFILES, Plan
from etcheck.checks.results.sections import Margin
from etcheck.checks.results.sections_buckled import PostbucklingSection
from etcheck.checks.results.sections_straight import LinearSection, StraightRodSection
from etcheck.input.mission import Mission
from etcheck.jsonable import OMITTED
from etcheck.rod.core.ends import describe, is_welded
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.scaling import Scaled, Scene


class Verdict(StrEnum):
    """The verdict of a margin or of a check (a str: written to JSON as its value)."""

    PASS = "pass"
    FAIL = "fail"
    INCOMPLETE = "incomplete"  # a question the chosen model cannot answer: never a pass
    OUTSIDE = "outside"  # the scene is outside the model's validity (etcheck.checks.verdict.validity): never a pass


PASS, FAIL, INCOMPLETE, OUTSIDE = Verdict.PASS, Verdict.FAIL, Verdict.INCOMPLETE, Verdict.OUTSIDE

#: the names of the margins of a check
LOAD_AT_REST = "magnetic load |I B0|"
LOAD_AT_SPIN = "magnetic load |I B0| at the operating spin and tension"
SPIN = "spin rate at the operating load"
BUCKLED = "buckled tether (b1): load to its secondary pitchfork"


def ratio_margin(
    name: str, unit: str, critical: float, operating: float, required: float, rung: int, error: float, why: str
) -> Margin:
    """Margin = critical / operating (both >= 0, same unit); pass if >= required.

    A margin is judged on its pessimistic side, value * (1 - error), so a
    numerical error can never turn a fail into a pass.
    """
    if operating == 0:
        return Margin(name, unit, critical, operating, None, required, PASS, rung, error, why)
    value = critical / operating
    verdict = PASS if value * (1.0 - error) >= required else FAIL
    return Margin(name, unit, critical, operating, value, required, verdict, rung, error, why)


def incomplete_margin(name: str, unit: str, operating: float, required: float, rung: int, why: str) -> Margin:
    """A margin the chosen model cannot answer: never a pass."""
    return Margin(name, unit, None, operating, None, required, INCOMPLETE, rung, None, why)


def overall_verdict(margins: list[Margin], within_validity: bool = True) -> str:
    """The check's verdict: "outside" where the scene is outside the model's validity (whatever its margins
    say: the model does not describe the tether), else fail, incomplete or pass from the margins."""
    if not within_validity:
        return OUTSIDE
    verdicts = {m.verdict for m in margins}
    if FAIL in verdicts:
        return FAIL
    if INCOMPLETE in verdicts or not margins:
        return INCOMPLETE
    return PASS


# The margin rules of each rung (what is compared with what).


def straight_margins(mission: Mission, sc: Scene, scaled: Scaled, chosen: Plan, static: StraightRodSection,
                     linear: LinearSection | None, damping: str = "") -> list[Margin]:
    required = mission.check.required_margin
    first = static.critical_loads[0]
    if linear is not None:
        return linear_margins(sc, scaled, required, linear, damping)
    if chosen.rung == 0 and chosen.complete:
        return [
            ratio_margin(
                LOAD_AT_REST,
                "N/m",
                first.IB0_N_per_m,
                sc.load,
                required,
                chosen.rung,
                first.relative_error,
                _static_why(scaled.params.ends),
            )
        ]
    return [incomplete_margin(LOAD_AT_REST, "N/m", sc.load, required, chosen.rung, chosen.reason)]


def _static_why(ends) -> str:
    if is_welded(ends):
        return "first (doubly degenerate) static buckling load of the straight welded tether, arXiv:0810.3668 eq. (91)"
    return (f"first (doubly degenerate) static buckling load of the straight tether {describe(ends)}: a zero of "
            "its closed-form characteristic function (docs/model.md)")


#: How each kind of loss of stability reads in a margin's reason.
KIND_WORDS = {"divergence": "divergence (a static buckling: a real eigenvalue through zero)",
              "flutter": "flutter (two vibration modes merge and one grows)"}


def linear_margins(sc: Scene, scaled: Scaled, required: float, linear: LinearSection, damping: str = "") -> list[Margin]:
    """Load margin at the operating spin; spin margin at the operating load (rung 1); ``damping``: which damping
    the critical values of rung 1v hold for, and why (docs/model.md section 10)."""
    p = scaled.params
    load, spin = linear.critical_load, linear.critical_spin
    window = ""
    if linear.operating_stable:
        window = (
            "; the operating point itself is stable, inside a stability window that does not reach back to zero "
            "(gyroscopic stabilisation, which damping removes): a window is not counted as margin"
        )
    along = ""
    if linear.route == PROFILES:
        along = (" with its current and tension along it, by " + KIND_WORDS.get(load.kind, load.kind)
                 + (f"; damping: {damping}" if damping else ""))
    margins = [
        margin_from_critical(
            LOAD_AT_SPIN,
            "N/m",
            load,
            load.IB0_N_per_m,
            sc.load,
            scaled.scales.load,
            required,
            "the straight tether first loses stability as I B0 grows at the operating spin, tension and damping"
            + along,
            "the straight tether is already unstable with no magnetic load at the operating spin and tension" + window,
        )
    ]
    if p.omega > 0:
        margins.append(
            margin_from_critical(
                SPIN,
                "rpm",
                spin,
                spin.rpm,
                sc.spin_rpm,
                scaled.scales.spin_rpm,
                required,
                "the straight tether first loses stability as the spin rate grows at the operating load",
                "the straight tether is already unstable without spin at the operating load (statically buckled)"
                + window,
            )
        )
    return [replace(m, route=linear.route) for m in margins]


def margin_from_critical(name, unit, point, critical, operating, scale_to_si, required, why, why_unstable) -> Margin:
    """The margin critical / operating of one rung-1 critical point (``point``, dimensionless; ``critical`` and
    ``operating`` in ``unit``, ``scale_to_si`` from dimensionless to it): 0 where the tether is unstable at the
    start, unlimited (value None) where no value destabilises it, a lower bound where none was found in the
    scanned range, incomplete where the value was not located."""
    kind = point.kind
    if point.value is None and kind not in (CriticalKind.UNSTABLE_AT_START, CriticalKind.NONE_FOUND,
                                               CriticalKind.NEVER):
        return incomplete_margin(name, unit, operating, required, 1, point.message)
    if kind == CriticalKind.UNSTABLE_AT_START:
        return ratio_margin(name, unit, 0.0, operating, required, 1, 0.0, why_unstable)
    if kind == CriticalKind.NEVER:  # proved stable at every value: an unlimited margin
        return Margin(name, unit, None, operating, None, required, PASS, 1, 0.0, point.message)
    if kind == CriticalKind.NONE_FOUND:
        hi = point.bracket[1] * scale_to_si
        return ratio_margin(
            name, unit, hi, operating, required, 1, 0.0,
            f"stable over the whole scanned range (up to {hi:.4g} {unit}); the margin shown is a lower bound",
        )
    error = (point.error or 0.0) / point.value if point.value else 0.0
    if not point.within_tolerance:
        why = f"{why}; the critical value missed its tolerance (an ill-conditioned root): its error estimate is carried here"
    return ratio_margin(name, unit, critical, operating, required, 1, error, f"{why} ({kind})")


def buckled_margins(post: PostbucklingSection, sc: Scene, scaled: Scaled, required: float) -> list[Margin]:
    """Load margin of the buckled tether on b1 up to its secondary pitchfork (rungs 2-3)."""
    B_star = post.secondary_pitchfork_B
    op = post.operating
    if op is None or op is OMITTED or not op.available:
        return []
    name = BUCKLED
    if not op.stable:
        return [ratio_margin(name, "N/m", 0.0, sc.load, required, 3, 0.0,
                             "the buckled state at the operating load is unstable (rung 3)")]
    if B_star is None:
        bound = post.b1_stable_to_IB0_N_per_m
        reason = post.secondary_pitchfork_reason
        why = reason if reason is not OMITTED and reason else "no secondary pitchfork found on b1 in the computed range"
        if bound is None:
            return [incomplete_margin(name, "N/m", sc.load, required, 3, why)]
        stable_to = (f"b1 stays stable from the operating load to the end of its computed range ({bound:.4g} N/m) "
                     "with no secondary pitchfork")
        if sc.load == 0 or bound / sc.load >= required:
            return [ratio_margin(name, "N/m", bound, sc.load, required, 3, 0.0,
                                 f"{stable_to}; the margin shown is a lower bound (rungs 2-3)")]
        return [incomplete_margin(name, "N/m", sc.load, required, 3,
                                  f"{stable_to}: the margin is at least {bound / sc.load:.3g}, short of the required "
                                  f"{required:g}, and b1 was not followed further (rung 2's range)")]
    return [ratio_margin(BUCKLED, "N/m",
                         post.secondary_pitchfork_IB0_N_per_m, sc.load, required, 3,
                         post.secondary_pitchfork_error,
                         "the buckled (coiled) tether on b1 stays stable up to its symmetry-breaking secondary "
                         "pitchfork at the operating spin and tension (rungs 2-3)")]


def needs_postbuckling(B: float, B_c: float | None, required: float) -> bool:
    """The scene needs rungs 2-3 when the operating load is past, or within the
    required margin of, the first critical load (dimensionless loads)."""
    return B_c is not None and B > 0 and B * required >= B_c
