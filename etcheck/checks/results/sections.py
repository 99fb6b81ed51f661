"""The sections of a check's results as records: what ``CheckResult.results`` holds, key by key.

Each section and nested record is a frozen dataclass, typed field by field: the one description of the layout.
:func:`etcheck.jsonable.to_json` writes a check's results from them (a dict per record, its fields in order,
:data:`etcheck.jsonable.OMITTED` keys left out), and :mod:`etcheck.checks.results.schema` makes
docs/results.schema.json from the same fields (their types, and the descriptions and bounds :func:`key` gives).
Units are in the key names (``_m``, ``_N``, ``_N_per_m``, ``_rad_s``, ``_rpm``, ``_Hz``, ``_s``, ``_T``); keys
without a unit are dimensionless (the scalings of docs/scaling.md: B, omega, T, gamma, P, R, Gamma, f).

Fields that may be ``OMITTED`` are present only in some results (named in each record's docstring); ``X | None``
values are null when not answered.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal

from etcheck.checks.plan import route_model

# the straight tether's sections (rungs 0, 1, 1v), the buckled tether's (rungs 2-3) and those page 1 reads (validity, assumptions, design limits, flight)
# live in their own modules
from etcheck.checks.results.sections_buckled import PostbucklingSection
from etcheck.checks.results.sections_straight import (
    AccuracyRow,
    LinearSection,
    ProfilesSection,
    StraightRodSection,
)
from etcheck.checks.results.sections_verdict import (
    AssumptionsSection,
    DesignLimitsSection,
    FlightSection,
    ModelValidity,
)

# the records of the inputs as read are built in the input layer (which may not import this one)
from etcheck.input.echo import End, MissionEcho, TensionProfile, UncertaintyInputs
from etcheck.jsonable import OMITTED, Omitted, key, to_json

#: the model that answered a margin, in words (etcheck.checks.plan.route_model)
Model = Literal[
    "rung 0 (analytic)",
    "rung 1 (linear spectral)",
    "rung 1 (linear, exact characteristic determinant)",
    "rungs 2-3 (post-buckling equilibria and their stability)",
    "rung 1v (linear, profiles along the tether)",
]
#: the verdict of one margin (a etcheck.checks.margins.margin.Verdict value)
MarginVerdict = Literal["pass", "fail", "incomplete"]
#: how a rung-1 critical value was computed ("" for the other rungs; etcheck.checks.plan)
Route = Literal["", "spectral", "exact determinant", "profiles"]

# --------------------------------------------------------------------------- scene, scalings, plan


@dataclass(frozen=True, slots=True, kw_only=True)
class SceneSection:
    """``scene``: the physical problem the rod model solves (SI; the worst case of any range)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "the operating point in SI (worst case of the mission's ranges)"}

    worst_current_A: float = key("worst current (A)")
    worst_field_T: float = key("worst axial magnetic field (T)")
    length_m: float = key("tether length (m)", exclusiveMinimum=0)
    EI1_N_m2: float = key("stiff-axis bending stiffness (N m²)", exclusiveMinimum=0)
    EI2_N_m2: float = key("weak-axis bending stiffness (N m²)", exclusiveMinimum=0)
    GJ_N_m2: float = key("torsional stiffness (N m²)", exclusiveMinimum=0)
    mass_per_length_kg_per_m: float = key("mass per length (kg/m)", exclusiveMinimum=0)
    P: float = key("rotary inertia ratio I1/(A L²) (dimensionless)", minimum=0)
    load_N_per_m: float = key("magnetic load |I B0| (N/m)", minimum=0)
    spin_rate_rad_s: float = key("spin rate (rad/s), magnitude", minimum=0)
    tension_N: float = key(
        "end tension used by the rod model (N, positive pulls); with tether.end_masses the minimum of the gravity-gradient profile (conservative)"
    )
    tension_profile: TensionProfile | None | Omitted = key(
        "the gravity-gradient tension profile (N, keys carry their unit) when the mission gives tether.end_masses; null otherwise",
        default=OMITTED,
    )
    damping_time_s: float = key("Kelvin-Voigt damping time gamma_v (s)", minimum=0)
    f: float = key("scaling constant f of arXiv:0810.3668 eq. (36) (dimensionless)", exclusiveMinimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class ScaledSection:
    """``scaled``: the dimensionless parameters of the rod (eqs. (36), (42) of arXiv:0810.3668 and docs/scaling.md)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the dimensionless rod parameters (arXiv:0810.3668 eq. (36); etcheck.rod.parameters.RodParameters)"
    }

    P: float = key("rotary inertia I1/(A L²)", minimum=0)
    R: float = key("anisotropy EI2/EI1 (0 < R <= 1)", exclusiveMinimum=0, maximum=1)
    Gamma: float = key("torsion/bending 2 GJ/(EI1 + EI2)", exclusiveMinimum=0)
    f: float = key("scaling constant", exclusiveMinimum=0)
    B: float = key("magnetic load B0 I L³/(f EI1)", minimum=0)
    omega: float = key("spin rate omega/omega_c", minimum=0)
    T: float = key("end tension T L²/(f EI1), positive in tension")
    gamma: float = key("Kelvin-Voigt damping gamma_v omega_c", minimum=0)
    ends: tuple[End, ...] = key(
        "how the rod is held at s = 0 (lower end) and s = 1 (upper end); etcheck.rod.core.ends", minItems=2, maxItems=2
    )  # [s = 0 (lower end), s = 1 (upper end)]: welded, pinned or swivel


@dataclass(frozen=True, slots=True, kw_only=True)
class ScalesSection:
    """``scales``: the units that turn the dimensionless answers back into SI."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "what turns the dimensionless numbers back into SI"}

    length_m: float = key("length scale L (m)", exclusiveMinimum=0)
    reference_frequency_rad_s: float = key("reference frequency omega_c (rad/s)", exclusiveMinimum=0)
    force_N: float = key("force scale (N)", exclusiveMinimum=0)
    load_N_per_m: float = key("load-per-length scale (N/m)", exclusiveMinimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class PlanSection:
    """``plan``: the rung of the model ladder that answers the check, and why."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "the model rung chosen for the straight-tether question and why"}

    rung: Literal[0, 1] = key("0 analytic (static, tension-free) or 1 linear")
    model: Literal[
        "rung 0 (analytic)",
        "rung 1 (linear spectral)",
        "rung 1 (linear, exact characteristic determinant)",
        "rung 1v (linear, profiles along the tether)",
    ] = key("the rung in words")
    reason: str = key("why this rung")
    complete: bool = key(
        "false when the requested fidelity cannot answer the scene (the check is then incomplete and never passes)"
    )
    route: Route = key(
        "rung 1: 'spectral' or 'exact determinant'; '' for rung 0"
    )  # "", "spectral" or "exact determinant"


@dataclass(frozen=True, slots=True, kw_only=True)
class FidelitySection:
    """``fidelity``: sign-off or draft, the tolerance, and what a draft leaves out."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "which fidelity ran",
        "allOf": [
            {
                "if": {"properties": {"name": {"const": "draft"}}},
                "then": {"properties": {"left_out": {"minItems": 1}}},
                "else": {"properties": {"left_out": {"maxItems": 0}}},
            }
        ],
    }

    name: Literal["sign-off", "draft"] = key(
        "sign-off computes everything; draft answers the margins and the verdict only, at a looser tolerance"
    )
    tolerance: float = key(
        "relative two-resolution agreement of critical values and eigenvalues (dimensionless)", exclusiveMinimum=0
    )
    left_out: tuple[str, ...] = key("what a draft leaves out (empty for sign-off)")


@dataclass(frozen=True, slots=True, kw_only=True)
class SkippedPart:
    """A part of a sign-off's extras that was not computed (``resources.skipped``): which, and why (past the time
    budget, or over the memory budget)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "one part that was skipped"}

    part: str = key('e.g. "Campbell diagram"')
    why: str = key("why it was skipped")


@dataclass(frozen=True, slots=True, kw_only=True)
class ResourcesSection:
    """The budgets a check ran under and what it skipped to stay within them (``resources``)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the budgets the check ran under and what it skipped to stay within them"
    }

    memory_budget_bytes: int = key(
        "most memory one process may use (bytes; --memory-budget, ETCHECK_MEMORY_BUDGET, default 1 GB)", minimum=1
    )
    time_budget_s: float | None = key(
        "seconds of a sign-off's computation after which the report's extras not yet computed are skipped (--time-budget); null: no limit (a draft, the Python API)",
        exclusiveMinimum=0,
    )
    skipped: tuple[SkippedPart, ...] = key(
        "the report's extras not computed, each with the reason (time or memory budget); the margins never are"
    )
    margins_s: float = key(
        "seconds from the start of the check until every margin was answered (the margins are never skipped: a sign-off that takes longer than its target says so and offers the draft)",
        minimum=0,
    )  # seconds from the start of the check until every margin was answered (never budgeted)


# --------------------------------------------------------------------------- margins and verdict


@dataclass(frozen=True, slots=True, kw_only=True)
class AlternativeMargin:
    """The same margin under another attachment of the ends (:mod:`etcheck.checks.margins.attachment`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the same margin under another attachment of the ends (rung 0, or rung 1's critical values only); etcheck.checks.margins.attachment"
    }

    ends: tuple[End, ...] = key("[lower end, upper end] of the alternative", minItems=2, maxItems=2)
    described: str = key("the alternative attachment in words")
    critical: float | None = key("critical value under it (in the margin's `unit`); null when incomplete", minimum=0)
    value: float | None = key("the margin under it (dimensionless); null when unlimited or incomplete", minimum=0)
    verdict: MarginVerdict = key(
        "the margin's verdict under it, against the same required margin"
    )  # a Verdict value
    error: float | None = key("estimated relative numerical error of `value`", minimum=0)
    model: Model = key("the model that answered it")


@dataclass(frozen=True, slots=True)
class Margin:
    """One design margin: critical / operating, judged against the required margin (made by
    :mod:`etcheck.checks.margins.margin`).

    ``critical`` and ``operating`` are in ``unit`` (SI); ``value`` is their
    ratio (None when the operating value is zero: an unlimited margin, or when
    the check is incomplete); ``error`` is the estimated relative numerical
    error of ``value``; ``rung`` the model that answered (``model`` in words, from ``rung`` and ``route``);
    ``alternatives`` the same margin under other attachments of the ends (:mod:`etcheck.checks.margins.attachment`;
    none for the buckled tether's).
    """

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "one design margin: critical / operating, judged on its pessimistic side value * (1 - error) against `required`"
    }

    name: str = key("what the margin is about, e.g. 'magnetic load |I B0| at the operating spin and tension'")
    unit: Literal["N/m", "rpm"] = key(
        "SI unit of `critical` and `operating`: N/m for the magnetic load |I B0|, rpm for the spin rate"
    )
    critical: float | None = key("critical value (in `unit`); null when the check is incomplete", minimum=0)
    operating: float = key("operating value (in `unit`)", minimum=0)
    value: float | None = key(
        "margin = critical / operating (dimensionless); null when the operating value is zero (an unlimited margin) or the check is incomplete",
        minimum=0,
    )
    required: float = key("required margin of the mission ([check] required_margin, dimensionless)", minimum=1)
    verdict: MarginVerdict = key(
        "pass, fail, or incomplete (the chosen model cannot answer: never a pass)"
    )  # a Verdict value: pass, fail, incomplete
    rung: Literal[0, 1, 3] = key("model rung that answered: 0 analytic, 1 linear, 3 post-buckling (rungs 2-3)")
    error: float | None = key(
        "estimated relative numerical error of `value` (dimensionless); null when incomplete", minimum=0
    )
    why: str = key("the reason in words")
    route: Route = key(
        "how a rung-1 critical value was computed: 'spectral' (Chebyshev collocation) or 'exact determinant'; '' for other rungs",
        default="",
    )
    alternatives: tuple[AlternativeMargin, ...] = key(
        "the same margin under the other attachments (welded against both pinned, pinned against both welded, one of each against both); empty for the buckled tether's margin",
        default=(),
    )
    model: Model = key("the model that answered, in words", init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "model", route_model(self.rung, self.route))

    def as_dict(self) -> dict:
        """The margin as written to results.json."""
        return to_json(self)


@dataclass(frozen=True, slots=True, kw_only=True)
class AttachmentAlternative:
    """The straight tether's margins under another attachment: their verdict and the model that answered."""

    ends: tuple[End, ...] = key("[lower end, upper end]", minItems=2, maxItems=2)
    described: str = key("in words")
    model: Model = key("the model that answered")
    verdict: MarginVerdict = key(
        "the straight margins' overall verdict under it"
    )  # a Verdict value


@dataclass(frozen=True, slots=True, kw_only=True)
class AttachmentSection:
    """``attachment``: how the tether is held at its ends (:mod:`etcheck.checks.margins.attachment`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "how the tether is held at its ends, and the verdict of the straight tether's margins under the other attachments (etcheck.checks.margins.attachment)"
    }

    ends: tuple[End, ...] = key("[lower end, upper end]", minItems=2, maxItems=2)  # [lower end, upper end]
    described: str = key("the attachment in words")
    torsion: str = key("the torsional condition at the ends (twist held, or free at a swivel)")
    buckled: str = key(
        "whether the buckled tether (rungs 2-3) is computed for these ends, and why not"
    )  # whether rungs 2-3 are computed for these ends, and why not
    alternatives: tuple[AttachmentAlternative, ...] = key(
        "each alternative attachment and the verdict of the straight margins under it"
    )


# --------------------------------------------------------------------------- along the orbit


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitSampling:
    step_s: float
    step_change: float
    converged: bool
    tolerance: float
    steps_s: tuple[float, ...]
    worst_by_step_T: tuple[float, ...]
    samples: int


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitWorst:
    """Where and when the axial field is worst (T, s, UTC, degrees, m)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the worst sample: axial_field_T (T), time_s (s), utc, latitude_deg, longitude_deg (deg), altitude_m (m)"
    }

    axial_field_T: float
    time_s: float
    utc: str
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    pitch_deg: float
    roll_deg: float


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitPercentiles:
    levels: tuple[float, ...]
    axial_worst_T: tuple[float, ...]
    axial_nominal_T: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitHistogram:
    counts: tuple[int, ...]
    edges_T: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitMargin:
    """The load margin over the orbit: ``smallest`` at the worst field (None with no load)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the load margin at the worst sample: critical_N_per_m (N/m), smallest (dimensionless), required"
    }

    name: str
    critical_N_per_m: float | None
    smallest: float | None
    required: float


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitSeries:
    """Samples along the orbit (None where not finite; load_margin None without a critical load)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "Samples along the orbit (None where not finite; load_margin None without a critical load)."
    }

    time_s: tuple[float | None, ...]
    latitude_deg: tuple[float | None, ...]
    longitude_deg: tuple[float | None, ...]
    altitude_m: tuple[float | None, ...]
    b_up_T: tuple[float | None, ...]
    b_along_T: tuple[float | None, ...]
    b_cross_T: tuple[float | None, ...]
    axial_nominal_T: tuple[float | None, ...]
    axial_worst_T: tuple[float | None, ...]
    load_N_per_m: tuple[float | None, ...]
    load_margin: tuple[float | None, ...] | None = key(nullable="anyOf")


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitSection:
    """``orbit`` (missions with an [orbit] table): the field and the load margin along the orbit
    (:func:`etcheck.checks.verdict.orbit_load.orbit_results`)."""

    model: str = key("the field and orbit model in words")
    start: str
    duration_s: float
    period_s: float
    libration_in_plane_deg: float
    libration_out_of_plane_deg: float
    sampling: OrbitSampling
    worst: OrbitWorst
    worst_nominal_T: float
    percentiles: OrbitPercentiles
    histogram: OrbitHistogram
    worst_current_A: float
    worst_load_N_per_m: float = key("worst magnetic load along the orbit (N/m)", minimum=0)
    margin: OrbitMargin | None = key(nullable="type")
    statement: str
    envelope_s: float = key(
        "wall time of the orbit stage: the envelope of the axial field over the window (s)", minimum=0
    )
    first_orbit: OrbitSeries
    series: OrbitSeries
    series_note: str


# --------------------------------------------------------------------------- uncertainty study


@dataclass(frozen=True, slots=True, kw_only=True)
class ElasticityRecord:
    """d ln margin / d ln input (None where not differentiable), and how it was found."""

    input: str
    label: str
    value: float | None
    method: str


@dataclass(frozen=True, slots=True, kw_only=True)
class SwingRecord:
    """The margin with one input at the ends of its tolerance range."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "The margin with one input at the ends of its tolerance range."}

    input: str
    label: str
    low: float | None
    high: float | None
    margin_low: float | None
    margin_high: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class MarginSensitivityRecord:
    margin: str = key("margin name (as in `margins`)")
    nominal: float | None = key("nominal margin (dimensionless)")
    elasticities: tuple[ElasticityRecord, ...] = key("d ln margin / d ln input per input")
    hinges_on: tuple[str, ...]
    does_not_matter: tuple[str, ...]
    swings: tuple[SwingRecord, ...]


@dataclass(frozen=True, slots=True)
class CrossCheck:
    """FORM and SORM (Breitung) at the design point (asymptotic approximations, for comparison with the
    probability of :mod:`etcheck.checks.margins.probability`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "FORM and SORM (Breitung) at the design point (etcheck.checks.margins.probability.CrossCheck)"
    }

    beta: float | None = key(
        "reliability index (distance of the design point from the origin in standard-normal space)"
    )
    form: float | None = key("Phi(-beta)", minimum=0, maximum=1)
    sorm: float | None = key(
        "Breitung's second-order approximation (null where undefined or not computed)", minimum=0, maximum=1
    )


@dataclass(frozen=True, slots=True)
class Probability:
    """P(margin < required) (dimensionless) and how good it is (:func:`etcheck.checks.margins.probability.failure_probability`).

    ``value``: the estimate (None when below FLOOR, then ``bound`` holds P < bound, or when not answered);
    ``low``, ``high``: the 95 % interval (sampling) or value -+ the stated error (exact, quadrature);
    ``error``: relative: the stated error bound (exact, quadrature) or the 95 % half-width (sampling);
    ``method``: exact, quadrature, sampling or not answered; ``how``: what was done, in words;
    ``evaluations``: margin evaluations by the check's route (closed-form ones counted too);
    ``points``: points at which the conditional probability was evaluated (quadrature nodes or samples);
    ``conditioned_on``: the input integrated exactly;
    ``inputs``: the uncertain inputs that move the margin; ``inert``: those that provably do not.
    """

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "P(margin < required) of one margin with its stated error or 95 % interval, or a bound (etcheck.checks.margins.probability.Probability)"
    }

    margin: str = key("margin name (as in margins[])")
    required: float = key("required margin (dimensionless)")
    value: float | None = key(
        "the probability (0-1); null when below what the method resolves (then bound) or not answered",
        minimum=0,
        maximum=1,
    )
    bound: float | None = key(
        "P < bound where value is null: 1e-9, or the rule of three of a sampling in which no point came near failing; null otherwise",
        minimum=0,
        maximum=1,
    )
    low: float | None = key(
        "lower end: of the 95 % confidence interval (sampling), of value - stated error (exact, quadrature)",
        minimum=0,
        maximum=1,
    )
    high: float | None = key("upper end (as low)", minimum=0, maximum=1)
    error: float | None = key(
        "relative: the stated error bound (exact, quadrature) or the 95 % half-width over value (sampling)", minimum=0
    )
    method: Literal["exact", "quadrature", "sampling", "not answered"] = key(
        "how the probability was computed"
    )  # exact, quadrature, sampling, not answered
    how: str = key("what was done, in words (or why not answered)")
    evaluations: int = key(
        "margin evaluations by the check's route (each one solve; a closed form counts once)", minimum=0
    )
    points: int = key(
        "points at which the conditional probability was evaluated (quadrature nodes or sampled points)", minimum=0
    )
    conditioned_on: str | None = key("the uncertain input integrated exactly (conditioning)")
    inputs: tuple[str, ...] = key("uncertain inputs that move this margin")
    inert: tuple[str, ...] = key("uncertain inputs that provably do not move it")
    model: str = key("the route that computed each margin (the check's)")
    cross_check: CrossCheck | None = key(
        "asymptotic cross-check for probabilities at or below 1e-4 (null otherwise)", default=None
    )
    note: str = ""
    elapsed_s: float = key("time of this probability (s)", minimum=0, default=0.0)


@dataclass(frozen=True, slots=True, kw_only=True)
class UncertaintySection:
    """``uncertainty`` (missions with an [uncertainty] table; :meth:`etcheck.checks.margins.uncertainty.UncertaintyStudy.section`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "sensitivities of every margin and, with an [uncertainty] table, tolerance swings and the probability of each margin falling below the required margin (etcheck.studies.uncertainty). Added by `etcheck check` only when the mission has an [uncertainty] table"
    }

    route: str = key("what computed each sample's margin: the check's own route")
    required_margin: float = key("required margin (dimensionless)", minimum=1)
    step: float
    nominal_inputs_SI: dict[str, float | None]
    inputs: UncertaintyInputs
    margins: tuple[MarginSensitivityRecord, ...] = key("one entry per margin")
    probabilities: tuple[Probability, ...] = key(
        "probability of falling short per margin (empty without probabilities)"
    )
    sensitivity_time_s: float
    elapsed_s: float = key("time of the study (s)", minimum=0)


# --------------------------------------------------------------------------- the whole


@dataclass(frozen=True, slots=True, kw_only=True)
class ResultsHeader:
    """The common head of every results file (:func:`etcheck.checks.results.header.results_header`)."""

    schema_version: Literal[4] = key("version of this layout (etcheck.checks.results.header.SCHEMA_VERSION)")
    etcheck_version: str = key("etcheck version that wrote the file")
    generated: str = key("UTC time stamp (ISO 8601, seconds)", format="date-time")
    mission: MissionEcho


@dataclass(frozen=True, slots=True, kw_only=True)
class CheckResults(ResultsHeader):
    """A check's results (``CheckResult.results``; results.json)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "etcheck check results (results.json), schema_version 3",
        "description": "The results of `etcheck check` (etcheck.checks.pipeline.check(mission).results, written as reports/<mission>/results.json). Strict JSON: no NaN or Infinity (a missing or unbounded number is null). Units are in each field's description and in key suffixes (_m, _N, _N_per_m, _rpm, _rad_s, _s, _T, _A); unsuffixed numbers in scaled and linear are dimensionless (scales turns them into SI). Every object lists its keys (no others allowed) and which are required, as the records of etcheck/checks/results/sections.py do (the schema is made from them: etcheck.checks.results.schema); only the shapes of a branch (keyed by where they were taken) and the end loads of a buckled tether (keyed s=0, s=L) are maps.",
        "allOf": [
            {
                "if": {"properties": {"verdict": {"const": "pass"}}},
                "then": {
                    "properties": {
                        "margins": {"minItems": 1, "items": {"properties": {"verdict": {"const": "pass"}}}},
                        "model_validity": {"properties": {"within": {"const": True}}},
                    }
                },
            },
            {
                "if": {"properties": {"verdict": {"const": "fail"}}},
                "then": {"properties": {"margins": {"contains": {"properties": {"verdict": {"const": "fail"}}}}}},
            },
            {
                "if": {"properties": {"verdict": {"const": "incomplete"}}},
                "then": {
                    "properties": {"margins": {"items": {"properties": {"verdict": {"enum": ["pass", "incomplete"]}}}}}
                },
            },
            {
                "if": {"properties": {"verdict": {"const": "outside"}}},
                "then": {"properties": {"model_validity": {"properties": {"within": {"const": False}}}}},
            },
        ],
    }

    scene: SceneSection
    scaled: ScaledSection
    scales: ScalesSection
    plan: PlanSection
    fidelity: FidelitySection
    straight_rod: StraightRodSection
    linear: LinearSection | None = key(
        "rung-1 answers (operating spectrum, critical load and spin, spin windows, Campbell diagram, stability map); null unless rung 1 answered"
    )
    profiles: ProfilesSection | None
    postbuckling: PostbucklingSection | None = key(
        "rungs 2-3 (the buckled tether and its stability) when the operating point is past, or within the required margin of, the first critical load; null otherwise and in a draft (B_c dimensionless, *_N_per_m in N/m, *_rpm in rpm)"
    )
    accuracy: tuple[AccuracyRow, ...] | None = key(
        "accuracy table of the spectral solver for this scene (sign-off, spectral route only); null otherwise"
    )
    margins: tuple[Margin, ...] = key("the design margins (the verdict is decided by them)")
    verdict: Literal["pass", "fail", "incomplete", "outside"] = key(
        "outside if the scene is outside the model's validity (model_validity.within false); else fail if any margin fails; else incomplete if any is incomplete or there is none; else pass"
    )  # a Verdict value
    attachment: AttachmentSection
    model_validity: ModelValidity
    assumptions: AssumptionsSection | None = key(nullable="type")
    design_limits: DesignLimitsSection | None = key(nullable="type")
    flight: FlightSection | None = key(nullable="type")
    validity: tuple[str, ...] = key("statements on the validity of the models for this mission")
    orbit: OrbitSection | None | Omitted = key(
        "the margin along the orbit (only with an [orbit] table; null otherwise): worst axial field (T), sampling, percentiles, histogram, time series",
        default=OMITTED,
    )
    elapsed_s: float = key("wall time of the check (s)", minimum=0)
    resources: ResourcesSection
    uncertainty: UncertaintySection | Omitted = key(default=OMITTED)
