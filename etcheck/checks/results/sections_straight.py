"""The straight tether's sections of a check's results as records (rungs 0, 1 and 1v: ``straight_rod``, ``linear``,
``profiles``, ``accuracy``), in the conventions of :mod:`etcheck.checks.results.sections` (units in the key names;
unsuffixed numbers dimensionless, docs/scaling.md)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal

from etcheck.jsonable import key

# --------------------------------------------------------------------------- rung 0: the straight rod at rest


@dataclass(frozen=True, slots=True, kw_only=True)
class StaticCriticalLoad:
    """One critical load of the static rod (omega = T = 0, eq. (91)): the k-th zero beta of chi (of its closed-form
    analogue 2 g^2 for other ends than welded, docs/model.md section 10; ``chi_*`` keep their names)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "one static buckling load"}

    k: int
    beta: float
    B: float = key("dimensionless load", minimum=0)
    IB0_N_per_m: float = key("|I B0| (N/m)", minimum=0)
    multiplicity: int
    chi_residual: float = key(
        "|chi(beta)| e^(-sqrt(3) beta) at the root (eq. (91)); for other ends its analogue 2 g(beta)^2 (docs/model.md section 9)"
    )
    chi_curvature: float = key("second derivative of that scaled function at the root (> 0: a touching, double zero)")
    relative_error: float = key("relative error (dimensionless)", minimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class ModeShape:
    """The first buckling mode on s in [0, 1] (dimensionless)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "The first buckling mode on s in [0, 1] (dimensionless)."}

    s: tuple[float, ...]
    x: tuple[float, ...]
    y: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class ChiCurve:
    beta: tuple[float, ...]
    chi_scaled: tuple[float, ...] = key(
        "chi(beta) e^(-sqrt(3) beta) (eq. (91)), or 2 g(beta)^2 for other ends than welded (docs/model.md section 9)"
    )


@dataclass(frozen=True, slots=True, kw_only=True)
class NaturalFrequency:
    """mu dimensionless (units of the reference frequency), rad/s and Hz."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "mu dimensionless (units of the reference frequency), rad/s and Hz."}

    mu: float
    rad_s: float
    Hz: float


@dataclass(frozen=True, slots=True, kw_only=True)
class NaturalFrequencies:
    """The straight tether's natural frequencies under its end tension (``tension_N``), without magnetic load
    and spin; ``model`` says how they were found."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the straight tether's natural frequencies under its end tension, without magnetic load and spin"
    }

    model: str = key("how they were found")
    tension_N: float = key("the end tension they are computed under (N)")
    bending_weak: tuple[NaturalFrequency, ...]
    bending_stiff: tuple[NaturalFrequency, ...]
    torsion: tuple[NaturalFrequency, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class StaticLimits:
    """Critical current at the worst field and critical length at the operating load (None: no limit)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "critical current at the worst field and critical length at the operating load"
    }

    critical_IB0_N_per_m: float = key("first static critical load (N/m)", minimum=0)
    critical_current_A: float | None = key("critical current at the worst field (A); null without field")
    critical_length_m: float | None = key("critical length at the operating load (m); null without load")


@dataclass(frozen=True, slots=True, kw_only=True)
class StaticBuckling:
    """Rung 0 answers of the scene (:func:`etcheck.checks.rungs.static_buckling.static_buckling`)."""

    model: str = key("'rung 0 (analytic)'")
    critical_loads: tuple[StaticCriticalLoad, ...] = key(
        "the first static buckling loads; IB0_N_per_m in N/m, B dimensionless, relative_error dimensionless", minItems=1
    )
    operating_beta: float
    loads_exceeded: int
    operating_B: float
    first_mode: ModeShape
    chi_curve: ChiCurve
    natural_frequencies: NaturalFrequencies


@dataclass(frozen=True, slots=True, kw_only=True)
class StraightRodSection(StaticBuckling):
    """``straight_rod``: rung 0 answers and the limits they set on the mission
    (:func:`etcheck.checks.rungs.static_buckling.static_limits`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "rung-0 answers for the straight tether at rest (static buckling loads, natural frequencies, mode shape, limits), for the tether's ends (scaled.ends)"
    }

    limits: StaticLimits


# --------------------------------------------------------------------------- rung 1: linear stability


@dataclass(frozen=True, slots=True, kw_only=True)
class CriticalPoint:
    """The first critical load or spin (dimensionless ``value``; ``kind`` a CriticalKind value)."""

    value: float | None = key(
        "dimensionless critical value (load B or spin omega, scaled units of `scales`); null unless kind is divergence or flutter",
        minimum=0,
    )
    kind: Literal["divergence", "flutter", "unstable at start", "none found", "never", "not located"] = key(
        "how stability is lost: divergence (real eigenvalue through 0), flutter (complex pair), 'unstable at start' (already unstable at zero), 'none found' (stable over the scanned bracket: the margin is a lower bound), 'never' (stable at every value, proved: an undamped isotropic tether below its static load at rest whatever the spin; the margin is unlimited), 'not located' (critical spin of a mission without spin that did not converge; informative only)"
    )
    bracket: tuple[float, ...] = key(
        "dimensionless [low, high] bracket of the critical value (scanned range for 'none found')",
        minItems=2,
        maxItems=2,
    )
    error: float | None = key(
        "absolute two-resolution error of `value` (dimensionless); null when not finite", minimum=0
    )
    message: str = key("solver message")
    N: int | None = key(
        "Chebyshev resolution used (of the pencil when damped; 0 on the exact-determinant route, which has no resolution)",
        type="integer",
        minimum=0,
    )
    within_tolerance: bool = key(
        "false when the value was located but its error estimate missed the check's tolerance (reported with that estimate, which its margin carries)"
    )


@dataclass(frozen=True, slots=True, kw_only=True)
class CriticalLoad(CriticalPoint):
    JSON_SCHEMA: ClassVar[dict] = {"description": "critical magnetic load at the operating spin, tension and damping"}

    IB0_N_per_m: float | None = key("critical load |I B0| (N/m); null when value is null", minimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class CriticalSpin(CriticalPoint):
    JSON_SCHEMA: ClassVar[dict] = {"description": "critical spin rate at the operating load, tension and damping"}

    rad_s: float | None = key("critical spin (rad/s); null when value is null", minimum=0)
    rpm: float | None = key("critical spin (rpm); null when value is null", minimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class Mode:
    """One eigenvalue of the operating point: re, im in units of the reference frequency."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "One eigenvalue of the operating point: re, im in units of the reference frequency."
    }

    re: float
    im: float
    error: float
    frequency_Hz: float
    growth_rate_per_s: float
    damping_ratio: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class OperatingSpectrum:
    JSON_SCHEMA: ClassVar[dict] = {
        "description": "eigenvalues at the operating point (growth rates 1/s, frequencies Hz); null in a damped draft or on the exact route"
    }

    N: int
    N_check: int | None
    message: str
    modes: tuple[Mode, ...]
    least_damped: int | None
    stable: bool


@dataclass(frozen=True, slots=True, kw_only=True)
class SpinWindow:
    """A window of stable spins [low, high]: dimensionless and in rpm."""

    omega: tuple[float, ...]
    rpm: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class OperatingPoint:
    JSON_SCHEMA: ClassVar[dict] = {"description": "the operating point"}

    B: float = key("dimensionless load", minimum=0)
    omega: float = key("dimensionless spin", minimum=0)
    IB0_N_per_m: float = key("|I B0| (N/m)", minimum=0)
    spin_rpm: float = key("spin (rpm)", minimum=0)


@dataclass(frozen=True, slots=True, kw_only=True)
class Campbell:
    """Frequencies and growth rates of the lowest modes against the spin (sign-off, spectral route)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "Campbell diagram (spin rpm, frequency Hz, growth rate 1/s; null entries where not finite); null in a draft"
    }

    omega: tuple[float, ...]
    spin_rpm: tuple[float, ...]
    frequency_Hz: tuple[tuple[float | None, ...], ...]
    growth_rate_per_s: tuple[tuple[float | None, ...], ...]
    N: int
    N_check: int | None
    checked_spin_rpm: tuple[float, ...]  # the spins checked at N_check
    error: float | None  # largest difference N vs N_check at the checked spins (dimensionless)


@dataclass(frozen=True, slots=True, kw_only=True)
class StableRow:
    """At one spin: the intervals of I B0 (N/m) where the straight tether is stable."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "At one spin: the intervals of I B0 (N/m) where the straight tether is stable."
    }

    omega: float
    spin_rpm: float
    IB0_N_per_m: tuple[tuple[float, ...], ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class StaticPoints:
    IB0_N_per_m: tuple[float, ...]
    spin_rpm: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class StabilityMap:
    """The (load, spin) plane: stable rows (damped) or the largest growth rate on a grid (undamped)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "stability map (|I B0| N/m x spin rpm); null in a draft"}

    B: tuple[float, ...]
    omega: tuple[float, ...]
    IB0_N_per_m: tuple[float, ...]
    spin_rpm: tuple[float, ...]
    max_growth: tuple[tuple[float, ...], ...] | None = key(nullable="anyOf")
    stable_rows: tuple[StableRow, ...] | None = key(nullable="anyOf")
    static_points: StaticPoints


@dataclass(frozen=True, slots=True, kw_only=True)
class LinearSection:
    """``linear``: rung 1 (:func:`etcheck.checks.rungs.straight.linear_stability`); the pictures (campbell,
    stability_map) are None in a draft."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "rung-1 answers"}

    model: str = key("the model in words")
    route: Literal["spectral", "exact determinant", "profiles"] = key("'spectral' or 'exact determinant'")
    threshold: float = key("growth-rate threshold for 'unstable' (dimensionless)")
    operating_stable: bool = key("whether the operating point is stable")
    operating_spectrum: OperatingSpectrum | None = key(nullable="type")
    critical_load: CriticalLoad = key("critical magnetic load at the operating spin, tension and damping")
    critical_spin: CriticalSpin
    spin_windows: tuple[SpinWindow, ...] = key("stable spin windows at the operating load (omega dimensionless, rpm)")
    spin_windows_scanned_to_rpm: float | None = key("how far the spin scan went (rpm); null with damping")
    operating: OperatingPoint
    campbell: Campbell | None = key(nullable="type")
    stability_map: StabilityMap | None = key(nullable="type")


# --------------------------------------------------------------------------- rung 1v: profiles along the tether


@dataclass(frozen=True, slots=True, kw_only=True)
class ProfileCurrent:
    """``profiles.current``: I(s) / I_max and I(s) at fractions s of the length from the lower end."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "I(s)/I_max and I(s) [A] at fractions s of the length from the lower end (height_m above it); null for one current"
    }

    s: tuple[float, ...]
    height_m: tuple[float, ...]
    fraction: tuple[float, ...]
    current_A: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class ProfileTension:
    """``profiles.tension``: the tension T(s) [N] at fractions s of the length from the lower end."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the tension T(s) [N] at fractions s of the length from the lower end; null for one tension"
    }

    s: tuple[float, ...]
    height_m: tuple[float, ...]
    tension_N: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class DampingPoint:
    """One point of the damping map: the critical load at the operating spin at one damping."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "one damping of the map: the critical load at the operating spin"}

    gamma: float
    damping_time_s: float
    B: float | None
    IB0_N_per_m: float | None
    kind: Literal["divergence", "flutter", "unstable at start", "none found", "never", "not located"] = key(
        "how stability is lost: divergence (real eigenvalue through 0), flutter (complex pair), 'unstable at start' (already unstable at zero), 'none found' (stable over the scanned bracket: the margin is a lower bound), 'never' (stable at every value, proved: an undamped isotropic tether below its static load at rest whatever the spin; the margin is unlimited), 'not located' (critical spin of a mission without spin that did not converge; informative only)"
    )
    destabilised: bool = key(
        "below the undamped threshold: damping lowered it (Ziegler's paradox)"
    )  # below the undamped threshold: damping lowered it (Ziegler)


@dataclass(frozen=True, slots=True, kw_only=True)
class DampingSection:
    """``profiles.damping``: which damping the verdict uses and why; the map (empty when fixed or conservative)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "which damping the verdict's critical values hold for and why; the map of the critical load against damping (empty when the mission fixes the damping or the load is conservative)"
    }

    fixed: bool
    gamma: float
    damping_time_s: float
    why: str
    map: tuple[DampingPoint, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class ProfileMode:
    """``profiles.mode``: the mode that crosses first, complex (u weak axis, v stiff axis), peak 1."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the mode that crosses first (u along the weak axis, v along the stiff axis), complex, peak 1"
    }

    s: tuple[float, ...]
    u_re: tuple[float, ...]
    u_im: tuple[float, ...]
    v_re: tuple[float, ...]
    v_im: tuple[float, ...]
    kind: str
    frequency_Hz: float


@dataclass(frozen=True, slots=True, kw_only=True)
class ProfilesSection:
    """``profiles``: rung 1v, the straight tether with its current and tension along it (docs/model.md §10)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "rung 1v: the straight tether with its current and tension along it (docs/model.md section 10); null for a tether with one current and one tension"
    }

    model: str
    circulatory: bool = key("the load has no potential (the current varies along the tether)")
    current: ProfileCurrent | None
    tension: ProfileTension | None
    damping: DampingSection
    undamped: CriticalLoad | None = key(
        "the critical load without damping (circulatory loads; null for a conservative one)"
    )
    uniform_tension_bound: CriticalLoad | None
    mode: ProfileMode | None
    post_buckling: str = key("why the post-buckling rungs (coils) are not run")


@dataclass(frozen=True, slots=True, kw_only=True)
class AccuracyRow:
    """One resolution of the spectral accuracy table (``accuracy``)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "one resolution"}

    N: int = key("Chebyshev resolution", minimum=1)
    solve_time_s: float = key("solve time (s)", minimum=0)
    eigenvalue_error: float | None = key(
        "relative error of the lowest eigenvalues against N = reference_N (dimensionless); null where not finite",
        minimum=0,
    )
    load_error: float | None = key(
        "relative error of B_c against N = reference_N (dimensionless); null where not finite", minimum=0
    )
    reference_N: int = key(
        "Chebyshev resolution of the reference solve (the smallest of 48, 64, 96, 128 at least 1.5 times the finest N of the table)",
        minimum=1,
    )
