"""The uncertainty study of a check: which input each margin hinges on, and the probability of falling short.

Run by :func:`etcheck.checks.pipeline.check` when the mission has an
``[uncertainty]`` table; its results are the check's ``uncertainty`` section.
The margins are re-evaluated by the check's own route and tolerances
(:mod:`etcheck.checks.margins.margin_model`); the elasticities and tolerance swings
come from :mod:`etcheck.checks.margins.sensitivity`, the probabilities from
:mod:`etcheck.checks.margins.probability`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields, is_dataclass, replace

from etcheck.checks.margins.margin import INCOMPLETE, Margin
from etcheck.checks.margins.margin_model import LABELS, MarginModel, margin_model
from etcheck.checks.margins.probability import BUDGET, NOT_ANSWERED, Probability, failure_probability
from etcheck.checks.margins.sensitivity import STEP, MarginSensitivity, sensitivities, swings
from etcheck.checks.plan import Plan
from etcheck.checks.results.sections import (
    ElasticityRecord,
    MarginSensitivityRecord,
    SwingRecord,
    UncertaintySection,
)
from etcheck.checks.rungs.straight import DEFAULT_OPTIONS, WhirlOptions
from etcheck.input.echo import UncertaintyInputs
from etcheck.input.mission import Mission
from etcheck.runtime.blas import single_blas_thread
from etcheck.scaling import Scaled, Scene

SEED = 20240615
#: Relative tolerance of every margin the study computes (the check's own where tighter): a margin error eps moves
#: P by about eps |d ln P / d ln margin|, which the probability's stated error carries; at 1e-8 it is below the
#: 1e-6 the probabilities are stated to, and the pencils' round-off next to the end of a line (1e-9) meets it
#: without the exact determinant's second opinion (1.5 ms a margin instead of 15-60 ms).
MARGIN_TOL = 1e-8


@dataclass(frozen=True)
class UncertaintyStudy:
    """Sensitivities of every margin, and the probabilities of falling short."""

    model: MarginModel
    sensitivities: tuple[MarginSensitivity, ...]
    probabilities: tuple[Probability, ...] = ()
    inputs: UncertaintyInputs = UncertaintyInputs(inputs=(), notes=())
    elapsed_s: float = 0.0
    sensitivity_time_s: float = 0.0

    def section(self) -> UncertaintySection:
        """The ``uncertainty`` section of the results (None where a number is not finite)."""
        margins: list[MarginSensitivityRecord] = []
        for s in self.sensitivities:
            ranked = sorted((e for e in s.elasticities if e.value is not None), key=lambda e: -abs(e.value))
            margins.append(MarginSensitivityRecord(
                margin=s.margin, nominal=_num(s.nominal),
                elasticities=tuple(ElasticityRecord(input=e.input, label=LABELS[e.input], value=_num(e.value),
                                                    method=e.method) for e in s.elasticities),
                hinges_on=tuple(e.input for e in ranked if abs(e.value) >= 0.1),
                does_not_matter=tuple(e.input for e in ranked if abs(e.value) < 1e-3),
                swings=tuple(SwingRecord(input=w.input, label=LABELS.get(w.input, w.input), low=_num(w.low),
                                         high=_num(w.high), margin_low=_num(w.margin_low),
                                         margin_high=_num(w.margin_high)) for w in s.swings),
            ))
        return UncertaintySection(
            route=self.model.name,
            required_margin=self.model.required,
            step=STEP,
            nominal_inputs_SI=dict(self.model.nominal),
            inputs=self.inputs,
            margins=tuple(margins),
            probabilities=tuple(_finite(p) for p in self.probabilities),
            sensitivity_time_s=self.sensitivity_time_s,
            elapsed_s=self.elapsed_s,
        )


def _num(x) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def _finite(x):
    """A probability's record with every number that is not finite as None (null in results.json)."""
    if is_dataclass(x):
        return replace(x, **{f.name: _finite(getattr(x, f.name)) for f in fields(x) if f.init})
    if isinstance(x, tuple):
        return tuple(_finite(v) for v in x)
    return None if isinstance(x, float) and not math.isfinite(x) else x


@single_blas_thread
def uncertainty_study(mission: Mission, scene: Scene, scaled: Scaled, chosen: Plan, margins: list[Margin],
                      options: WhirlOptions = DEFAULT_OPTIONS, probabilities: bool = True, seed: int = SEED,
                      budget: int = BUDGET) -> UncertaintyStudy:
    """The study of a checked mission with an [uncertainty] table: elasticities of every margin, the tolerance
    swings and (``probabilities``) the probability of each margin falling below the required margin, on the
    route and at the tolerances the check used (``chosen``, ``options``; ``margins`` are the check's)."""
    started = time.perf_counter()
    unc = mission.studies.uncertainty
    answered = [m for m in margins if m.verdict != INCOMPLETE]
    model = margin_model(mission, scene, scaled, chosen, answered, options)
    sens = sensitivities(model)  # at the check's tolerance: the differences divide the margins' errors by 1e-3
    model = replace(model, options=replace(options, tol=max(options.tol, MARGIN_TOL)))
    t_sens = time.perf_counter() - started
    sw = swings(model, unc)
    sens = tuple(replace(s, swings=sw.get(s.margin, ())) for s in sens)
    probs: list[Probability] = []
    if probabilities:
        by_name = {s.margin: s for s in sens}
        for m in margins:
            if m.verdict == INCOMPLETE or m.name not in model.kinds:
                probs.append(_unanswered_margin(m, model))
            else:
                probs.append(failure_probability(model, m.name, unc, by_name.get(m.name), seed=seed, budget=budget))
    return UncertaintyStudy(model, sens, tuple(probs), unc.echo(), time.perf_counter() - started, t_sens)


def study_model(mission: Mission, options: WhirlOptions = DEFAULT_OPTIONS) -> MarginModel:
    """The margin model of a mission's straight-tether margins as its check builds it (the critical values of a
    draft check, none of its other answers), at the study's margin tolerance: for scripts and tests that ask
    for probabilities on their own (:func:`etcheck.checks.margins.probability.failure_probability`)."""
    from etcheck.checks.margins.margin import straight_margins
    from etcheck.checks.orbit_field import resolve
    from etcheck.checks.plan import plan, varies_along
    from etcheck.checks.rungs.static_buckling import straight_rod
    from etcheck.checks.rungs.straight import linear_stability
    from etcheck.scaling import scale

    resolved = resolve(mission)
    mission, sc = resolved.mission, resolved.scene
    scaled = scale(sc)
    if varies_along(sc):
        raise ValueError(f"no margin model with {varies_along(sc)} along the tether: its margins take rung 1v "
                         "(seconds each), and the check computes no uncertainty study for it")
    chosen = plan(scaled.params, mission.check.model)
    static = straight_rod(scaled, sc)
    linear = linear_stability(scaled, replace(options, draft=True), chosen.route) \
        if chosen.rung == 1 and chosen.complete else None
    margins = [m for m in straight_margins(mission, sc, scaled, chosen, static, linear) if m.verdict != INCOMPLETE]
    model = margin_model(mission, sc, scaled, chosen, margins, options)
    return replace(model, options=replace(options, tol=max(options.tol, MARGIN_TOL)))


def _unanswered_margin(m: Margin, model: MarginModel) -> Probability:
    why = "the check did not answer this margin" if m.verdict == INCOMPLETE else "this margin is not re-evaluated"
    return Probability(m.name, m.required, None, None, None, None, None, NOT_ANSWERED, why, 0, 0, None, (), (),
                       model.name)
