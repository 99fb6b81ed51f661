"""The library entry point: mission -> orbit field -> scene -> plan -> solve -> margins -> results.

``check(mission)`` returns a :class:`CheckResult` whose ``results`` are plain
JSON-able data; reports are rendered from those alone (see :mod:`etcheck.report`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass, field, replace
from pathlib import Path

from etcheck.checks.fidelity import fidelity_of
from etcheck.checks.margins.attachment import Alternative, alternatives, attachment_section, with_alternatives
from etcheck.checks.margins.margin import (
    FAIL,
    INCOMPLETE,
    LOAD_AT_REST,
    LOAD_AT_SPIN,
    OUTSIDE,
    PASS,
    Margin,
    buckled_margins,
    needs_postbuckling,
    overall_verdict,
    straight_margins,
)
from etcheck.checks.orbit_field import resolve
from etcheck.checks.plan import (
    DRAFT_BOUND,
    EXACT,
    LAYER_MIN,
    PROFILES,
    R_MIN_SPECTRAL,
    Plan,
    boundary_layer,
    modelled_along,
    plan,
    varies_along,
)
from etcheck.checks.results.header import header_fields, results_header
from etcheck.checks.results.sections import (
    CheckResults,
    PlanSection,
    ResourcesSection,
    ScaledSection,
    ScalesSection,
    SceneSection,
    SkippedPart,
)
from etcheck.checks.results.sections_buckled import PostbucklingSection
from etcheck.checks.results.sections_straight import AccuracyRow, LinearSection, ProfilesSection, StraightRodSection
from etcheck.checks.results.sections_verdict import (
    AssumptionsSection,
    DesignLimitsSection,
)
from etcheck.checks.rungs.static_buckling import straight_rod
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS, Extras, WhirlOptions, accuracy, linear_answers
from etcheck.checks.verdict.assumptions import assumptions
from etcheck.checks.verdict.design_limits import design_limits
from etcheck.checks.verdict.flight import flight
from etcheck.checks.verdict.orbit_load import orbit_results
from etcheck.checks.verdict.validity import model_validity, validity
from etcheck.input.mission import Mission, load_mission, mission_from_dict
from etcheck.jsonable import OMITTED, fields_of, from_json, to_json
from etcheck.rod.core.ends import BUCKLED_WELDED_ONLY, describe, is_welded
from etcheck.rod.straight.collocation.spectral import CriticalKind
from etcheck.runtime import memory
from etcheck.runtime.memory import OverBudget
from etcheck.runtime.parallel import ahead
from etcheck.scaling import Scaled, Scene, scale

EXIT_CODES = {PASS: 0, FAIL: 1, INCOMPLETE: 1, OUTSIDE: 1}
N_LOADS = 5


@dataclass(frozen=True)
class CheckResult:
    """What a check produced: its ``results`` as plain JSON data (the JSON form of
    :class:`etcheck.checks.results.sections.CheckResults`, written once by :func:`etcheck.jsonable.to_json`) and the CLI
    exit code."""

    results: dict

    @property
    def verdict(self) -> str:
        return self.results["verdict"]

    @property
    def exit_code(self) -> int:
        return EXIT_CODES[self.verdict]


def check(mission: Mission | str | Path | dict, options: WhirlOptions = DEFAULT_OPTIONS) -> CheckResult:
    """Run the stability check of a mission (a Mission, a TOML path or a dict).

    ``options`` sets the resolution of the rung-1 answers (tolerances, map
    and Campbell grids, accuracy table). A mission with an ``[uncertainty]``
    table also gets its uncertainty study (``results["uncertainty"]``:
    :mod:`etcheck.checks.margins.uncertainty`), its margins by the same route and
    tolerances.
    """
    if isinstance(mission, (str, Path)):
        mission = load_mission(mission)
    elif isinstance(mission, dict):
        mission = mission_from_dict(mission)
    started = time.perf_counter()
    resolved = resolve(mission)
    mission, sc = resolved.mission, resolved.scene
    scaled = scale(sc)
    along = modelled_along(sc, mission.check.draft)
    chosen = plan(scaled.params, mission.check.model, along)
    if along != varies_along(sc):
        chosen = replace(chosen, reason=f"{chosen.reason}; {DRAFT_BOUND}")
    fid = fidelity_of(mission.check.draft, mission.check.tolerance)
    static = straight_rod(scaled, sc)
    options = replace(options, N=mission.check.resolution, eig_tol=fid.tolerance)  # the mission's [check] rules
    if fid.draft:
        options = replace(options, tol=max(options.tol, fid.tolerance), draft=True, accuracy_N=(), time_budget=None)
    # the report's extras not computed by then are skipped (the margins never are)
    deadline = None if options.time_budget is None else started + options.time_budget
    # the same margins under the other attachments of the ends (with profiles: at the damping the verdict uses,
    # computed by rung 1v beside its own parts); not in a draft, which says so in fidelity.left_out
    def other_ends(damping: float | None = None) -> tuple[Alternative, ...]:
        return () if fid.draft else alternatives(mission, sc, scaled, options, damping)

    answers = _straight_answers(mission, scaled, chosen, options, deadline, None if fid.draft else other_ends)
    linear, profiles, skipped, alts = answers.linear, answers.profiles, answers.skipped, answers.alternatives
    margins = straight_margins(mission, sc, scaled, chosen, static, linear,
                               profiles.damping.why if profiles else "")
    alts = other_ends() if alts is None else alts
    margins = with_alternatives(margins, alts)
    post = None if fid.draft else _postbuckling(mission, scaled, static, linear, profiles)
    if post and post.computed:
        margins += buckled_margins(post, sc, scaled, mission.check.required_margin)
    margins_s = time.perf_counter() - started
    study = None
    if mission.studies.uncertainty is not None and profiles is not None:
        skipped.append(SkippedPart(part="uncertainty study", why="not computed with the current or tension along the "
                               "tether: its margins take rung 1v (seconds each) and the study needs hundreds"))
    elif mission.studies.uncertainty is not None:  # [uncertainty]: the margins again at other inputs, by the same route
        from etcheck.checks.margins.uncertainty import uncertainty_study

        study = uncertainty_study(mission, sc, scaled, chosen, margins, options).section()
    scope = model_validity(mission, sc)
    verdict = overall_verdict(margins, scope.within)
    extras = Extras(skipped, deadline, options.time_budget)
    decides, limits = _what_decides(mission, sc, margins, chosen.complete and not fid.draft, options, extras,
                                    profiles)
    sections = CheckResults(
        **header_fields(results_header(mission)),
        scene=scene_section(sc),
        scaled=ScaledSection(**fields_of(scaled.params)),
        scales=ScalesSection(length_m=scaled.scales.length, reference_frequency_rad_s=scaled.scales.frequency,
                             force_N=scaled.scales.force, load_N_per_m=scaled.scales.load),
        plan=PlanSection(rung=chosen.rung, model=chosen.model, reason=chosen.reason, complete=chosen.complete,
                         route=chosen.route),
        fidelity=fid.section(),
        straight_rod=static,
        linear=answers.linear,
        profiles=answers.profiles,
        postbuckling=post,
        accuracy=answers.accuracy,
        margins=tuple(margins),
        verdict=verdict,
        attachment=attachment_section(scaled, alts),
        model_validity=scope,
        assumptions=decides,
        design_limits=limits,
        flight=flight(mission, verdict, margins, scope),
        validity=tuple(validity(mission, scaled, chosen, post)),
        orbit=orbit_results(resolved, margins),  # None without an [orbit] table
        elapsed_s=time.perf_counter() - started,
        resources=ResourcesSection(memory_budget_bytes=memory.budget(), time_budget_s=options.time_budget,
                                   skipped=tuple(skipped), margins_s=margins_s),
        uncertainty=OMITTED if study is None else study,
    )
    return CheckResult(results=to_json(sections))


@dataclass(frozen=True)
class StraightAnswers:
    """The straight tether's answers past rung 0 (:func:`_straight_answers`), as their builders write them:
    rung 1's ``linear`` section, or rung 1v's ``linear`` and ``profiles`` (None each where the plan stops before
    them), rung 1's ``accuracy`` table, the extras ``skipped`` for the time budget (the check adds to them), and
    with profiles the margins under the other ``alternatives`` of the ends (None: not computed here)."""

    linear: LinearSection | None = None
    profiles: ProfilesSection | None = None
    accuracy: tuple[AccuracyRow, ...] | None = None
    skipped: list[SkippedPart] = field(default_factory=list)
    alternatives: tuple[Alternative, ...] | None = None


def _straight_answers(mission: Mission, scaled: Scaled, chosen: Plan, options: WhirlOptions, deadline: float | None,
                      other_ends: Callable[[float], tuple[Alternative, ...]] | None = None) -> StraightAnswers:
    """The straight tether's answers past rung 0: rung 1v with profiles along the tether, else rung 1 and its
    accuracy table (:class:`StraightAnswers`); with profiles, ``other_ends(gamma)`` at the damping the verdict
    uses (computed beside rung 1v's parts; none without ``other_ends``)."""
    skipped: list[SkippedPart] = []
    if not chosen.complete or (chosen.route != PROFILES and chosen.rung != 1):
        return StraightAnswers(skipped=skipped)
    if chosen.route == PROFILES:
        # imported here on purpose: rung 1v (scipy.sparse) loads only for a mission with profiles
        from etcheck.checks.rungs.profiles import profile_stability, stability_map

        tol = max(options.tol, options.eig_tol)
        linear, profiles, alts = profile_stability(scaled, mission.tether.damping_time is not None, tol=tol,
                                                   draft=options.draft, beside=other_ends)
        if not options.draft:  # the report's extra, within the sign-off's time budget
            linear = replace(linear, stability_map=Extras(skipped, deadline, options.time_budget)(
                "stability map", lambda: stability_map(scaled, linear, profiles.damping.gamma, tol)))
        return StraightAnswers(linear, profiles, None, skipped, () if alts is None else alts)  # none in a draft

    # the spectral accuracy table says nothing about the exact determinant (no resolution to trade); it needs
    # nothing from the rest: where a core is free a helper computes it meanwhile
    def table() -> tuple[AccuracyRow, ...] | None:
        return accuracy(scaled, options.accuracy_N)

    if not options.accuracy_N or chosen.route == EXACT:
        later = nullcontext(lambda: None)
    else:
        later = ahead(table) if options.accuracy_beside else nullcontext(table)
    with later as accuracy_later:
        linear, skipped = linear_answers(scaled, options, chosen.route, deadline)
        return StraightAnswers(linear, None, Extras(skipped, deadline, options.time_budget)("accuracy table",
                                                                                            accuracy_later), skipped)


def _what_decides(mission: Mission, sc: Scene, margins: list[Margin], wanted: bool, options: WhirlOptions,
                  extras: Extras, profiles: ProfilesSection | None
                  ) -> tuple[AssumptionsSection | None, DesignLimitsSection | None]:
    """How far the smallest margin of the straight tether moves with each assumption, and how far each input may
    go (None for both in a draft or an incomplete check: ``wanted`` False; each None where the sign-off's time
    budget ran out first, said in ``resources.skipped``); ``profiles``: rung 1v's section, where it answered."""
    if not wanted:
        return None, None
    straight = [m for m in margins if m.value is not None and m.rung < 3]
    governing = min(straight, key=lambda m: m.value) if straight else None
    def decides() -> AssumptionsSection:
        return assumptions(mission, sc, governing.name if governing else None,
                           governing.value if governing else None, options,
                           governing.alternatives if governing else (), profiles)

    if profiles is not None:  # rung 1v's margins are not re-evaluated: milliseconds, whatever the time budget
        along = None
        if governing is not None and governing.name in (LOAD_AT_REST, LOAD_AT_SPIN):
            along = (governing.value, governing.error if governing.error is not None else math.nan)
        return decides(), design_limits(mission, sc, options, True, along)
    return (extras("how far the margin moves with each assumption", decides),
            extras("design limits", lambda: design_limits(mission, sc, options)))


def _postbuckling(mission: Mission, scaled: Scaled, static: StraightRodSection, linear: LinearSection | None,
                  profiles: ProfilesSection | None = None) -> PostbucklingSection | None:
    """Rungs 2-3 when the operating point is past, or within the required margin of, the first critical load
    (or why not)."""
    p = scaled.params
    if profiles is not None:
        crit = linear.critical_load if linear else None
        B_c = crit.value if crit else None
        if B_c is None or not needs_postbuckling(p.B, B_c, mission.check.required_margin):
            return None
        return PostbucklingSection(computed=False, B_c=B_c, load_ratio=p.B / B_c if B_c else None,
                                   reason=profiles.post_buckling)
    if linear is not None:
        crit = linear.critical_load
        kind = CriticalKind(crit.kind)
        B_c = crit.value if kind.located else (0.0 if kind == CriticalKind.UNSTABLE_AT_START else None)
    else:
        B_c = static.critical_loads[0].B if p.omega == 0 and p.T == 0 else None
    if B_c is None or not needs_postbuckling(p.B, B_c, mission.check.required_margin):
        return None
    if B_c == 0.0:
        return PostbucklingSection(
            computed=False, B_c=0.0, load_ratio=None,
            reason="the straight tether is unstable without any magnetic load at this spin and tension "
            "(it whirls): no buckled branch grows from a stable straight state here")
    if not is_welded(p.ends):
        return PostbucklingSection(
            computed=False, B_c=B_c, load_ratio=p.B / B_c,
            reason=f"the buckled tether (rungs 2-3) is {BUCKLED_WELDED_ONLY} (this tether is "
            f"{describe(p.ends)}); the margins of the straight tether above decide the verdict")
    if linear is not None and linear.route == EXACT:
        layer = boundary_layer(p)
        return PostbucklingSection(
            computed=False, B_c=B_c, load_ratio=p.B / B_c,
            reason=f"beyond rungs 2-3: the buckled tether's end boundary layers ({layer:.2g} of its length, "
            f"or a string-like weak axis, R = {p.R:.2g}) are thinner than their Chebyshev collocation resolves "
            f"(they need layers wider than {LAYER_MIN:g} of the length and R >= {R_MIN_SPECTRAL:g})")
    # imported here on purpose: rungs 2-3 (continuation, branch stability) load only for a scene that needs them
    from etcheck.checks.rungs.buckled import postbuckling_check

    try:  # rungs 2-3 still write their section as JSON data: read into its record here
        return from_json(PostbucklingSection, postbuckling_check(p, scaled.scales, B_c, mission.check.required_margin))
    except OverBudget as exc:  # rungs 2-3 need more memory than the budget: not answered, with the reason
        return PostbucklingSection(computed=False, B_c=B_c, load_ratio=p.B / B_c, reason=str(exc))


def scene_section(sc: Scene) -> SceneSection:
    """The ``scene`` section of a check's results: the worst-case operating point in SI (the tension the minimum
    of a gravity-gradient profile, which is given beside it)."""
    profile = sc.gravity_gradient
    return SceneSection(
        worst_current_A=sc.current,
        worst_field_T=sc.field.axial,
        length_m=sc.length,
        EI1_N_m2=sc.EI1,
        EI2_N_m2=sc.EI2,
        GJ_N_m2=sc.GJ,
        mass_per_length_kg_per_m=sc.mass_per_length,
        P=sc.P,
        load_N_per_m=sc.load,
        spin_rate_rad_s=sc.spin_rate,
        tension_N=sc.tension,
        # tether.end_masses: the gravity-gradient profile (N), which rung 1v uses; tension_N is its minimum (a bound)
        tension_profile=None if profile is None else profile.echo(),
        damping_time_s=sc.damping_time,
        f=sc.f,
    )
