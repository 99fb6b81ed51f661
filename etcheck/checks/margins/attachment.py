"""How the tether is attached, and the same margins under the other attachment.

Every margin hangs on how the ends are held: pinned ends (no bending moment)
lower the static buckling load of the straight tether to 0.36 of the welded
one (R = 21/38), one of each to 0.63; strong tension shrinks the difference
(the tether acts as a string). So beside the mission's margins the check
evaluates the straight tether's margins again under the other attachments, on
the cheap rungs (0, or 1 with critical values only: a draft's rung-1 answers at
the mission's tolerance) and reports them next to each margin: welded ends
against both pinned, pinned against both welded, one of each against both
bounds. The buckled tether's margin (rungs 2-3) has no alternative: those rungs
are computed for welded ends only.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from etcheck.checks.margins.margin import Margin, overall_verdict, straight_margins
from etcheck.checks.plan import PROFILES, Plan, modelled_along, plan
from etcheck.checks.results.sections import AlternativeMargin, AttachmentAlternative, AttachmentSection
from etcheck.checks.rungs.static_buckling import straight_rod
from etcheck.checks.rungs.straight import WhirlOptions, linear_stability
from etcheck.input.mission import Mission
from etcheck.rod.core.ends import ALL_PINNED, ALL_WELDED, BUCKLED_WELDED_ONLY, Ends, describe, is_welded
from etcheck.scaling import Scaled, Scene

__all__ = ["Alternative", "alternatives", "alternative_ends", "attachment_section", "with_alternatives"]


@dataclass(frozen=True)
class Alternative:
    """The straight tether's margins under another attachment ``ends`` (the plan that answered them)."""

    ends: Ends
    plan: Plan
    margins: tuple[Margin, ...]

    @property
    def verdict(self) -> str:
        return overall_verdict(list(self.margins))


def alternative_ends(ends: Ends) -> tuple[Ends, ...]:
    """The attachments to compare with: welded and pinned at both ends, less those that bend as ``ends`` do (a
    swivel bends as a pin; torsion does not enter the straight tether's margins)."""
    return tuple(alt for alt in (ALL_WELDED, ALL_PINNED) if alt.bending != Ends.of(ends).bending)


def alternatives(mission: Mission, sc: Scene, scaled: Scaled, options: WhirlOptions,
                 damping: float | None = None) -> tuple[Alternative, ...]:
    """The straight tether's margins under each of :func:`alternative_ends` (rung 0, or rung 1's critical values
    only, at the mission's fidelity and tolerance). With profiles along the tether (``scaled.tether``), rung 1v's
    critical values at ``damping``, the one the mission's verdict uses."""
    out = []
    quick = replace(options, draft=True, accuracy_N=())
    for ends in alternative_ends(scaled.params.ends):
        tether = None if scaled.tether is None else scaled.tether.with_(ends=ends)
        alt = Scaled(params=scaled.params.with_(ends=ends), scales=scaled.scales, tether=tether)
        chosen = plan(alt.params, mission.check.model, modelled_along(sc, mission.check.draft))
        static = straight_rod(alt, sc)
        if chosen.route == PROFILES and chosen.complete:
            from etcheck.checks.rungs.profiles import alternative_linear  # rung 1v (scipy.sparse) for profiles only

            linear = alternative_linear(alt, alt.tether.params.gamma if damping is None else damping,
                                        max(options.tol, options.eig_tol))
        else:
            linear = linear_stability(alt, quick, chosen.route) if chosen.rung == 1 and chosen.complete else None
        out.append(Alternative(ends, chosen, tuple(straight_margins(mission, sc, alt, chosen, static, linear))))
    return tuple(out)


def _record(alt: Alternative, margin: Margin) -> AlternativeMargin:
    return AlternativeMargin(ends=tuple(alt.ends), described=describe(alt.ends), critical=margin.critical,
                             value=margin.value, verdict=str(margin.verdict), error=margin.error, model=margin.model)


def with_alternatives(margins: list[Margin], alts: tuple[Alternative, ...]) -> list[Margin]:
    """Each margin with the same margin (by name) under every alternative attachment; the buckled tether's
    margins have none."""
    out = []
    for m in margins:
        found = tuple(_record(alt, a) for alt in alts for a in alt.margins if a.name == m.name)
        out.append(replace(m, alternatives=found))
    return out


def attachment_section(scaled: Scaled, alts: tuple[Alternative, ...]) -> AttachmentSection:
    """``attachment``: the ends as given, in words, what they mean for torsion and the buckled rungs, and the
    straight margins' verdict under each alternative."""
    ends = scaled.params.ends
    if ends.holds_twist:
        torsion = ("twist held at both ends" + ("" if is_welded(ends) else " (a pinned end is taken as a gimbal: it "
                                                "passes the torque about the tether's axis, not a bending moment)"))
    else:
        which = "upper" if ends.lower.holds_twist else "lower"
        torsion = (f"the {which} end turns freely about the tether's axis (a swivel passes no torque); the other "
                   "holds the twist")
    return AttachmentSection(
        ends=tuple(ends),
        described=describe(ends),
        torsion=torsion,
        buckled=("computed (rungs 2-3) where the operating load nears the straight tether's first critical load"
                 if is_welded(ends) else f"not computed: rungs 2-3 are {BUCKLED_WELDED_ONLY}"),
        alternatives=tuple(AttachmentAlternative(ends=tuple(a.ends), described=describe(a.ends), model=a.plan.model,
                                                 verdict=str(a.verdict)) for a in alts),
    )
