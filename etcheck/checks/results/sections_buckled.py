"""The buckled tether's sections of a check's results as types (rungs 2-3: ``postbuckling``, its bifurcation
diagram, the buckled state at the operating load and the coil region), in the conventions of
:mod:`etcheck.checks.results.sections`, which holds the rest of the layout."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from etcheck.jsonable import OMITTED, Omitted, key


@dataclass(frozen=True, slots=True, kw_only=True)
class SpecialPoint:
    """A branch point, secondary pitchfork or fold on a branch, with the measures of the state there."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "A branch point, secondary pitchfork or fold on a branch, with the measures of the state there."
    }

    kind: str
    B: float
    IB0_N_per_m: float
    measure1: float
    measure2: float = key("measure_2 of the located state (paper caption of Fig. 6)")
    max_deflection_m: float = key("maximum lateral deflection of the located state (m)")
    bracket: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class Shape:
    """A buckled shape on s in [0, 1]: dimensionless and in metres."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "A buckled shape on s in [0, 1]: dimensionless and in metres."}

    s: tuple[float, ...]
    x: tuple[float, ...]
    y: tuple[float, ...]
    z: tuple[float, ...]
    x_m: tuple[float, ...]
    y_m: tuple[float, ...]
    z_m: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class BranchShape(Shape):
    B: float
    measure1: float


@dataclass(frozen=True, slots=True, kw_only=True)
class BranchRecord:
    """One continued branch of whirling equilibria (``postbuckling.diagram.branches``).

    Stability keys (stable, max_growth, growth_error, check_time) where the
    branch's stability was computed; pitchfork keys on primary branches;
    ``from`` on connecting branches."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "One continued branch of whirling equilibria (``postbuckling.diagram.branches``)."
    }

    from_: str | Omitted = key(name="from", default=OMITTED)
    name: str
    parameter: str
    N: int
    symmetry: str | None
    values: tuple[float, ...]
    measure1: tuple[float, ...]
    measure2: tuple[float, ...]
    max_deflection: tuple[float, ...]
    special: tuple[SpecialPoint, ...]
    time: float
    reason: str
    residual: float
    label: str
    points: int
    IB0_N_per_m: tuple[float, ...]
    max_deflection_m: tuple[float, ...]
    measure1_error: float | None
    deflection_error: float | None
    N_check: int | None
    stable: tuple[bool | None, ...] | Omitted = key(default=OMITTED)
    max_growth: tuple[float | None, ...] | Omitted = key(default=OMITTED)
    growth_error: tuple[float | None, ...] | Omitted = key(default=OMITTED)
    shapes: dict[str, BranchShape]
    check_time: float | Omitted = key(default=OMITTED)
    pitchfork_B: float | Omitted = key(default=OMITTED)
    pitchfork_B_error: float | None | Omitted = key(
        "stated error of pitchfork_B (two resolutions, dimensionless); null where none", default=OMITTED
    )
    pitchfork_IB0_N_per_m: float | Omitted = key(default=OMITTED)
    liftoff_omega: float | None | Omitted = key(default=OMITTED)
    liftoff_omega_error: float | None | Omitted = key(
        "stated error of liftoff_omega (dimensionless); null where none", default=OMITTED
    )


@dataclass(frozen=True, slots=True, kw_only=True)
class DiagramParameters:
    P: float
    R: float
    Gamma: float
    f: float
    omega: float
    T: float
    gamma: float


@dataclass(frozen=True, slots=True, kw_only=True)
class LiftedOff:
    label: str
    liftoff_omega: float
    liftoff_omega_error: float | None = key("stated error of liftoff_omega (dimensionless); null where none")


@dataclass(frozen=True, slots=True, kw_only=True)
class BifurcationDiagram:
    """``postbuckling.diagram``: branches of whirling equilibria (rung 2)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "``postbuckling.diagram``: branches of whirling equilibria (rung 2)."}

    model: str
    params: DiagramParameters
    B_max: float
    IB0_max_N_per_m: float
    N: int
    branches: tuple[BranchRecord, ...]
    lifted_off: tuple[LiftedOff, ...]
    paths_computed: tuple[str, ...] = key(
        "labels of the branches whose eigenvalue paths were computed (eigenvalue_paths)"
    )  # labels of the branches whose eigenvalue paths were computed
    time_s: float


@dataclass(frozen=True, slots=True, kw_only=True)
class DampingSensitivity:
    factor: float
    gamma: float
    damping_time_s: float
    growth_rate_per_s: float | None
    damping_ratio: float | None
    decay_time_s: float | None
    stable: bool


@dataclass(frozen=True, slots=True, kw_only=True)
class LeastDamped:
    re: float
    im: float
    growth_rate_per_s: float
    frequency_Hz: float
    damping_ratio: float | None
    decay_time_s: float | None
    error: float


@dataclass(frozen=True, slots=True, kw_only=True)
class BuckledOperatingPoint:
    """The buckled tether at the operating load (rung 3); only ``available`` and ``reason`` when it has none."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "The buckled tether at the operating load (rung 3); only ``available`` and ``reason`` when it has none."
    }

    damping_sensitivity: tuple[DampingSensitivity, ...] | Omitted = key(default=OMITTED)
    available: bool
    reason: str | Omitted = key(default=OMITTED)
    branch: str | Omitted = key(default=OMITTED)
    B: float | Omitted = key(default=OMITTED)
    measure1: float | Omitted = key(default=OMITTED)
    max_deflection: float | Omitted = key(default=OMITTED)
    max_deflection_m: float | Omitted = key(default=OMITTED)
    end_shortening_m: float | Omitted = key(default=OMITTED)
    end_force_N: dict[str, tuple[float, ...]] | Omitted = key(default=OMITTED)  # {"s=0": [3 components], "s=L": [...]}
    end_moment_N_m: dict[str, tuple[float, ...]] | Omitted = key(default=OMITTED)
    shape: Shape | Omitted = key(default=OMITTED)
    deflection_error_m: float | None | Omitted = key(default=OMITTED)
    residual: float | Omitted = key(default=OMITTED)
    N: int | Omitted = key(default=OMITTED)
    N_check: int | None | Omitted = key(default=OMITTED)
    stable: bool | Omitted = key(default=OMITTED)
    spectrum_converged: bool | Omitted = key(default=OMITTED)
    least_damped: LeastDamped | None | Omitted = key(default=OMITTED, nullable="anyOf")
    points: int | Omitted = key(default=OMITTED)
    time_s: float | Omitted = key(default=OMITTED)


@dataclass(frozen=True, slots=True, kw_only=True)
class RegionRow:
    omega: float
    spin_rpm: float
    pitchfork_B: float | None
    secondary_B: float | None
    pitchfork_IB0_N_per_m: float | None
    secondary_IB0_N_per_m: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class RegionCurve:
    omega: tuple[float, ...]
    spin_rpm: tuple[float, ...]
    B: tuple[float, ...]
    IB0_N_per_m: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class SecondaryCurve(RegionCurve):
    interpolation: str
    interpolation_error_B: float | None
    interpolation_error_IB0_N_per_m: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class CoilRegion:
    """``postbuckling.region``: where b1 is stable in the (spin, load) plane (rung 3)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "``postbuckling.region``: where b1 is stable in the (spin, load) plane (rung 3)."
    }

    rows: tuple[RegionRow, ...]
    N: int
    liftoff_omega: float | None
    liftoff_rpm: float | None
    pitchfork_curve: RegionCurve
    secondary_curve: SecondaryCurve
    time_s: float
    liftoff_omega_error: float | None = key("stated error of liftoff_omega (dimensionless); null where none")
    operating_rpm: float
    lowest_stable_spin_rpm: float | None


@dataclass(frozen=True, slots=True, kw_only=True)
class PostbucklingSection:
    """``postbuckling``: rungs 2-3, or why they were not computed (``computed`` False with a ``reason``).

    With ``computed`` True: the diagram and, where b1 was found, its secondary
    pitchfork and stability; ``operating`` and ``region`` where the operating
    load lies on b1 (:func:`etcheck.checks.rungs.buckled.postbuckling_check`)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "post-buckling analysis"}

    B_c: float | None = key("dimensionless first critical load", minimum=0)
    load_ratio: float | None = key("operating / critical load (dimensionless)", minimum=0)
    computed: bool = key("whether the buckled branch was computed")
    reason: str | Omitted = key("why (not) computed", default=OMITTED)
    diagram: BifurcationDiagram | Omitted = key(default=OMITTED)
    secondary_pitchfork_B: float | None | Omitted = key(default=OMITTED)
    secondary_pitchfork_error: float | None | Omitted = key(default=OMITTED)
    secondary_pitchfork_IB0_N_per_m: float | None | Omitted = key(default=OMITTED)
    secondary_pitchfork_reason: str | Omitted = key(default=OMITTED)
    b1_first_unstable_B: float | None | Omitted = key(
        "dimensionless load of the first computed state of b1 found unstable: where the continuation placed a state, not a located value (secondary_pitchfork_B is the located end of b1's stable part); null if none",
        default=OMITTED,
    )
    b1_stable_at_start: bool | None | Omitted = key(default=OMITTED)
    b1_stable_to_B: float | None | Omitted = key(
        "Dimensionless load up to which b1 was followed and found stable from the operating load on, with no secondary pitchfork (a lower bound of the secondary pitchfork); null where a pitchfork was found or a state past the operating load is not stable.",
        default=OMITTED,
    )
    b1_stable_to_IB0_N_per_m: float | None | Omitted = key("b1_stable_to_B in N/m (I B0).", default=OMITTED)
    operating: BuckledOperatingPoint | None | Omitted = key(default=OMITTED, nullable="anyOf")
    region: CoilRegion | None | Omitted = key(default=OMITTED, nullable="anyOf")
    time_s: float | Omitted = key(default=OMITTED)
