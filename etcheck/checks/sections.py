"""The sections of a check's results as types: what ``CheckResult.results`` holds, key by key.

Results stay plain JSON-able dicts (the reports and results.json read them as
such); these TypedDicts give every section and nested record its keys and
value types for a reader and a type checker, without changing a byte of the
JSON. ``docs/results.schema.json`` documents the same layout for readers of
results.json; ``tests/checks/test_results_schema.py`` holds the two in step
(same keys, same required keys). Units are in the key names (``_m``, ``_N``,
``_N_per_m``, ``_rad_s``, ``_rpm``, ``_Hz``, ``_s``, ``_T``); keys without a
unit are dimensionless (the scalings of docs/scaling.md: B, omega, T, gamma,
P, R, Gamma, f).

``NotRequired`` keys are present only in some results (named in each
record's docstring); ``X | None`` values are null when not answered.
"""

# no ``from __future__ import annotations``: TypedDict reads NotRequired from evaluated annotations only
from typing import NotRequired, TypedDict

# the buckled tether's sections (rungs 2-3) and those page 1 reads (validity, assumptions, design limits, flight)
# live in their own modules
from etcheck.checks.sections_buckled import PostbucklingSection
from etcheck.checks.sections_verdict import AssumptionsSection, DesignLimitsSection, FlightSection, ModelValidity

# the records of the inputs as read are built in the input layer (which may not import this one)
from etcheck.input.echo import MissionEcho, TensionProfile, UncertaintyInputs

# --------------------------------------------------------------------------- scene, scalings, plan


class SceneSection(TypedDict):
    """``scene``: the physical problem the rod model solves (SI; the worst case of any range)."""

    worst_current_A: float
    worst_field_T: float
    length_m: float
    EI1_N_m2: float
    EI2_N_m2: float
    GJ_N_m2: float
    mass_per_length_kg_per_m: float
    P: float
    load_N_per_m: float
    spin_rate_rad_s: float
    tension_N: float
    tension_profile: NotRequired[TensionProfile | None]
    damping_time_s: float
    f: float


class ScaledSection(TypedDict):
    """``scaled``: the dimensionless parameters of the rod (eqs. (36), (42) of arXiv:0810.3668 and docs/scaling.md)."""

    P: float
    R: float
    Gamma: float
    f: float
    B: float
    omega: float
    T: float
    gamma: float
    ends: list[str]  # [s = 0 (lower end), s = 1 (upper end)]: welded, pinned or swivel


class ScalesSection(TypedDict):
    """``scales``: the units that turn the dimensionless answers back into SI."""

    length_m: float
    reference_frequency_rad_s: float
    force_N: float
    load_N_per_m: float


class PlanSection(TypedDict):
    """``plan``: the rung of the model ladder that answers the check, and why."""

    rung: int
    model: str
    reason: str
    complete: bool
    route: str  # "", "spectral" or "exact determinant"


class FidelitySection(TypedDict):
    """``fidelity``: sign-off or draft, the tolerance, and what a draft leaves out."""

    name: str
    tolerance: float
    left_out: list[str]


# --------------------------------------------------------------------------- rung 0: the straight rod at rest


class StaticCriticalLoad(TypedDict):
    """One critical load of the static rod (omega = T = 0, eq. (91)): the k-th zero beta of chi (of its closed-form
    analogue 2 g^2 for other ends than welded, docs/model.md section 10; ``chi_*`` keep their names)."""

    k: int
    beta: float
    B: float
    IB0_N_per_m: float
    multiplicity: int
    chi_residual: float
    chi_curvature: float
    relative_error: float


class ModeShape(TypedDict):
    """The first buckling mode on s in [0, 1] (dimensionless)."""

    s: list[float]
    x: list[float]
    y: list[float]


class ChiCurve(TypedDict):
    beta: list[float]
    chi_scaled: list[float]


class NaturalFrequency(TypedDict):
    """mu dimensionless (units of the reference frequency), rad/s and Hz."""

    mu: float
    rad_s: float
    Hz: float


class NaturalFrequencies(TypedDict):
    """The straight tether's natural frequencies under its end tension (``tension_N``), without magnetic load
    and spin; ``model`` says how they were found."""

    model: str
    tension_N: float
    bending_weak: list[NaturalFrequency]
    bending_stiff: list[NaturalFrequency]
    torsion: list[NaturalFrequency]


class StaticLimits(TypedDict):
    """Critical current at the worst field and critical length at the operating load (None: no limit)."""

    critical_IB0_N_per_m: float
    critical_current_A: float | None
    critical_length_m: float | None


class StaticBuckling(TypedDict):
    """Rung 0 answers of the scene (:func:`etcheck.checks.static_buckling.static_buckling`)."""

    model: str
    critical_loads: list[StaticCriticalLoad]
    operating_beta: float
    loads_exceeded: int
    operating_B: float
    first_mode: ModeShape
    chi_curve: ChiCurve
    natural_frequencies: NaturalFrequencies


class StraightRodSection(StaticBuckling):
    """``straight_rod``: rung 0 answers and the limits they set on the mission
    (:func:`etcheck.checks.static_buckling.static_limits`)."""

    limits: StaticLimits


# --------------------------------------------------------------------------- rung 1: linear stability


class CriticalPoint(TypedDict):
    """The first critical load or spin (dimensionless ``value``; ``kind`` a CriticalKind value)."""

    value: float | None
    kind: str
    bracket: list[float]
    error: float | None
    message: str
    N: int | None
    within_tolerance: bool  # False: located, but its error estimate missed the check's tolerance (carried by its margin)


class CriticalLoad(CriticalPoint):
    IB0_N_per_m: float | None


class CriticalSpin(CriticalPoint):
    rad_s: float | None
    rpm: float | None


class Mode(TypedDict):
    """One eigenvalue of the operating point: re, im in units of the reference frequency."""

    re: float
    im: float
    error: float
    frequency_Hz: float
    growth_rate_per_s: float
    damping_ratio: float | None


class OperatingSpectrum(TypedDict):
    N: int
    N_check: int | None
    message: str
    modes: list[Mode]
    least_damped: int | None
    stable: bool


class SpinWindow(TypedDict):
    """A window of stable spins [low, high]: dimensionless and in rpm."""

    omega: list[float]
    rpm: list[float]


class OperatingPoint(TypedDict):
    B: float
    omega: float
    IB0_N_per_m: float
    spin_rpm: float


class Campbell(TypedDict):
    """Frequencies and growth rates of the lowest modes against the spin (sign-off, spectral route)."""

    omega: list[float]
    spin_rpm: list[float]
    frequency_Hz: list[list[float | None]]
    growth_rate_per_s: list[list[float | None]]
    N: int
    N_check: int | None
    checked_spin_rpm: list[float]  # the spins checked at N_check
    error: float | None  # largest difference N vs N_check at the checked spins (dimensionless)


class StableRow(TypedDict):
    """At one spin: the intervals of I B0 (N/m) where the straight tether is stable."""

    omega: float
    spin_rpm: float
    IB0_N_per_m: list[list[float]]


class StaticPoints(TypedDict):
    IB0_N_per_m: list[float]
    spin_rpm: list[float]


class StabilityMap(TypedDict):
    """The (load, spin) plane: stable rows (damped) or the largest growth rate on a grid (undamped)."""

    B: list[float]
    omega: list[float]
    IB0_N_per_m: list[float]
    spin_rpm: list[float]
    max_growth: list[list[float]] | None
    stable_rows: list[StableRow] | None
    static_points: StaticPoints


class LinearSection(TypedDict):
    """``linear``: rung 1 (:func:`etcheck.checks.straight.linear_stability`); the pictures (campbell,
    stability_map) are None in a draft."""

    model: str
    route: str
    threshold: float
    operating_stable: bool
    operating_spectrum: OperatingSpectrum | None
    critical_load: CriticalLoad
    critical_spin: CriticalSpin
    spin_windows: list[SpinWindow]
    spin_windows_scanned_to_rpm: float | None
    operating: OperatingPoint
    campbell: Campbell | None
    stability_map: StabilityMap | None


# --------------------------------------------------------------------------- rung 1v: profiles along the tether


class ProfileCurrent(TypedDict):
    """``profiles.current``: I(s) / I_max and I(s) at fractions s of the length from the lower end."""

    s: list[float]
    height_m: list[float]
    fraction: list[float]
    current_A: list[float]


class ProfileTension(TypedDict):
    """``profiles.tension``: the tension T(s) [N] at fractions s of the length from the lower end."""

    s: list[float]
    height_m: list[float]
    tension_N: list[float]


class DampingPoint(TypedDict):
    """One point of the damping map: the critical load at the operating spin at one damping."""

    gamma: float
    damping_time_s: float
    B: float | None
    IB0_N_per_m: float | None
    kind: str
    destabilised: bool  # below the undamped threshold: damping lowered it (Ziegler)


class DampingSection(TypedDict):
    """``profiles.damping``: which damping the verdict uses and why; the map (empty when fixed or conservative)."""

    fixed: bool
    gamma: float
    damping_time_s: float
    why: str
    map: list[DampingPoint]


class ProfileMode(TypedDict):
    """``profiles.mode``: the mode that crosses first, complex (u weak axis, v stiff axis), peak 1."""

    s: list[float]
    u_re: list[float]
    u_im: list[float]
    v_re: list[float]
    v_im: list[float]
    kind: str
    frequency_Hz: float


class ProfilesSection(TypedDict):
    """``profiles``: rung 1v, the straight tether with its current and tension along it (docs/model.md §10)."""

    model: str
    circulatory: bool
    current: ProfileCurrent | None
    tension: ProfileTension | None
    damping: DampingSection
    undamped: CriticalLoad | None
    uniform_tension_bound: CriticalLoad | None
    mode: ProfileMode | None
    post_buckling: str


class AccuracyRow(TypedDict):
    """One resolution of the spectral accuracy table (``accuracy``)."""

    N: int
    solve_time_s: float
    eigenvalue_error: float | None
    load_error: float | None
    reference_N: int


class SkippedPart(TypedDict):
    """A part of a sign-off's extras that was not computed (``resources.skipped``): which, and why (past the time
    budget, or over the memory budget)."""

    part: str
    why: str


class ResourcesSection(TypedDict):
    """The budgets a check ran under and what it skipped to stay within them (``resources``)."""

    memory_budget_bytes: int
    time_budget_s: float | None
    skipped: list[SkippedPart]
    margins_s: float  # seconds from the start of the check until every margin was answered (never budgeted)


# --------------------------------------------------------------------------- margins and verdict


class AlternativeMargin(TypedDict):
    """The same margin under another attachment of the ends (:mod:`etcheck.checks.attachment`)."""

    ends: list[str]
    described: str
    critical: float | None
    value: float | None
    verdict: str  # a Verdict value
    error: float | None
    model: str


class MarginRecord(TypedDict):
    """One margin = critical / operating, as written to results.json: the JSON form of
    :class:`etcheck.checks.margins.Margin`, the one source of its fields (made only by its ``as_dict``; its fields
    and ``model`` are these keys, tests/checks/test_margin_record.py); ``alternatives``: the same margin under the
    other attachments (none for the buckled tether's)."""

    name: str
    unit: str
    critical: float | None
    operating: float
    value: float | None
    required: float
    verdict: str  # a Verdict value: pass, fail, incomplete
    rung: int
    error: float | None
    why: str
    route: str
    model: str
    alternatives: list[AlternativeMargin]


class AttachmentAlternative(TypedDict):
    """The straight tether's margins under another attachment: their verdict and the model that answered."""

    ends: list[str]
    described: str
    model: str
    verdict: str  # a Verdict value


class AttachmentSection(TypedDict):
    """``attachment``: how the tether is held at its ends (:mod:`etcheck.checks.attachment`)."""

    ends: list[str]  # [lower end, upper end]
    described: str
    torsion: str
    buckled: str  # whether rungs 2-3 are computed for these ends, and why not
    alternatives: list[AttachmentAlternative]


# --------------------------------------------------------------------------- along the orbit


class OrbitSampling(TypedDict):
    step_s: float
    step_change: float
    converged: bool
    tolerance: float
    steps_s: list[float]
    worst_by_step_T: list[float]
    samples: int


class OrbitWorst(TypedDict):
    """Where and when the axial field is worst (T, s, UTC, degrees, m)."""

    axial_field_T: float
    time_s: float
    utc: str
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    pitch_deg: float
    roll_deg: float


class OrbitPercentiles(TypedDict):
    levels: list[float]
    axial_worst_T: list[float]
    axial_nominal_T: list[float]


class OrbitHistogram(TypedDict):
    counts: list[int]
    edges_T: list[float]


class OrbitMargin(TypedDict):
    """The load margin over the orbit: ``smallest`` at the worst field (None with no load)."""

    name: str
    critical_N_per_m: float | None
    smallest: float | None
    required: float


class OrbitSeries(TypedDict):
    """Samples along the orbit (None where not finite; load_margin None without a critical load)."""

    time_s: list[float | None]
    latitude_deg: list[float | None]
    longitude_deg: list[float | None]
    altitude_m: list[float | None]
    b_up_T: list[float | None]
    b_along_T: list[float | None]
    b_cross_T: list[float | None]
    axial_nominal_T: list[float | None]
    axial_worst_T: list[float | None]
    load_N_per_m: list[float | None]
    load_margin: list[float | None] | None


class OrbitSection(TypedDict):
    """``orbit`` (missions with an [orbit] table): the field and the load margin along the orbit
    (:func:`etcheck.checks.orbit_load.orbit_results`)."""

    model: str
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
    worst_load_N_per_m: float
    margin: OrbitMargin | None
    statement: str
    envelope_s: float
    first_orbit: OrbitSeries
    series: OrbitSeries
    series_note: str


# --------------------------------------------------------------------------- uncertainty study


class ElasticityRecord(TypedDict):
    """d ln margin / d ln input (None where not differentiable), and how it was found."""

    input: str
    label: str
    value: float | None
    method: str


class SwingRecord(TypedDict):
    """The margin with one input at the ends of its tolerance range."""

    input: str
    label: str
    low: float | None
    high: float | None
    margin_low: float | None
    margin_high: float | None


class MarginSensitivityRecord(TypedDict):
    margin: str
    nominal: float | None
    elasticities: list[ElasticityRecord]
    hinges_on: list[str]
    does_not_matter: list[str]
    swings: list[SwingRecord]


class CrossCheckRecord(TypedDict):
    """FORM and SORM (Breitung) at the design point (:class:`etcheck.checks.probability.CrossCheck`)."""

    beta: float | None
    form: float | None
    sorm: float | None


class ProbabilityRecord(TypedDict):
    """P(margin < required), its stated error or 95 % interval, or a bound (:class:`etcheck.checks.probability.Probability`)."""

    margin: str
    required: float
    value: float | None
    bound: float | None
    low: float | None
    high: float | None
    error: float | None
    method: str  # exact, quadrature, sampling, not answered
    how: str
    evaluations: int
    points: int
    conditioned_on: str | None
    inputs: list[str]
    inert: list[str]
    model: str
    cross_check: CrossCheckRecord | None
    note: str
    elapsed_s: float


class UncertaintySection(TypedDict):
    """``uncertainty`` (missions with an [uncertainty] table; :meth:`etcheck.checks.uncertainty.UncertaintyStudy.as_dict`)."""

    route: str
    required_margin: float
    step: float
    nominal_inputs_SI: dict[str, float | None]
    inputs: UncertaintyInputs
    margins: list[MarginSensitivityRecord]
    probabilities: list[ProbabilityRecord]
    sensitivity_time_s: float
    elapsed_s: float


# --------------------------------------------------------------------------- the whole


class ResultsHeader(TypedDict):
    """The common head of every results file (:func:`etcheck.checks.results.results_header`)."""

    schema_version: int
    etcheck_version: str
    generated: str  # UTC, ISO 8601
    mission: MissionEcho


class CheckResults(ResultsHeader):
    """A check's results (``CheckResult.results``; results.json)."""

    scene: SceneSection
    scaled: ScaledSection
    scales: ScalesSection
    plan: PlanSection
    fidelity: FidelitySection
    straight_rod: StraightRodSection
    linear: LinearSection | None
    profiles: ProfilesSection | None
    postbuckling: PostbucklingSection | None
    accuracy: list[AccuracyRow] | None
    margins: list[MarginRecord]
    verdict: str  # a Verdict value
    attachment: AttachmentSection
    model_validity: ModelValidity
    assumptions: AssumptionsSection | None
    design_limits: DesignLimitsSection | None
    flight: FlightSection | None
    validity: list[str]
    orbit: NotRequired[OrbitSection | None]
    elapsed_s: float
    resources: ResourcesSection
    uncertainty: NotRequired[UncertaintySection]

