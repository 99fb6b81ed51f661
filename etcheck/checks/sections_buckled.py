"""The buckled tether's sections of a check's results as types (rungs 2-3: ``postbuckling``, its bifurcation
diagram, the buckled state at the operating load and the coil region), in the conventions of
:mod:`etcheck.checks.sections`, which holds the rest of the layout."""

# no ``from __future__ import annotations``: TypedDict reads NotRequired from evaluated annotations only
from typing import NotRequired, TypedDict


class SpecialPoint(TypedDict):
    """A branch point, secondary pitchfork or fold on a branch, with the measures of the state there."""

    kind: str
    B: float
    IB0_N_per_m: float
    measure1: float
    measure2: float
    max_deflection_m: float
    bracket: list[float]


class Shape(TypedDict):
    """A buckled shape on s in [0, 1]: dimensionless and in metres."""

    s: list[float]
    x: list[float]
    y: list[float]
    z: list[float]
    x_m: list[float]
    y_m: list[float]
    z_m: list[float]


class BranchShape(Shape):
    B: float
    measure1: float


#: ``from`` (connecting branches: the primary branch they leave) is a Python keyword: functional syntax
_ConnectingBranch = TypedDict("_ConnectingBranch", {"from": NotRequired[str]})


class BranchRecord(_ConnectingBranch):
    """One continued branch of whirling equilibria (``postbuckling.diagram.branches``).

    Stability keys (stable, max_growth, growth_error, check_time) where the
    branch's stability was computed; pitchfork keys on primary branches;
    ``from`` on connecting branches."""

    name: str
    parameter: str
    N: int
    symmetry: str | None
    values: list[float]
    measure1: list[float]
    measure2: list[float]
    max_deflection: list[float]
    special: list[SpecialPoint]
    time: float
    reason: str
    residual: float
    label: str
    points: int
    IB0_N_per_m: list[float]
    max_deflection_m: list[float]
    measure1_error: float | None
    deflection_error: float | None
    N_check: int | None
    stable: NotRequired[list[bool | None]]
    max_growth: NotRequired[list[float | None]]
    growth_error: NotRequired[list[float | None]]
    shapes: dict[str, BranchShape]
    check_time: NotRequired[float]
    pitchfork_B: NotRequired[float]
    pitchfork_IB0_N_per_m: NotRequired[float]
    liftoff_omega: NotRequired[float | None]
    pitchfork_B_error: NotRequired[float | None]
    liftoff_omega_error: NotRequired[float | None]


class DiagramParameters(TypedDict):
    P: float
    R: float
    Gamma: float
    f: float
    omega: float
    T: float
    gamma: float


class LiftedOff(TypedDict):
    label: str
    liftoff_omega: float
    liftoff_omega_error: float | None


class BifurcationDiagram(TypedDict):
    """``postbuckling.diagram``: branches of whirling equilibria (rung 2)."""

    model: str
    params: DiagramParameters
    B_max: float
    IB0_max_N_per_m: float
    N: int
    branches: list[BranchRecord]
    lifted_off: list[LiftedOff]
    paths_computed: list[str]  # labels of the branches whose eigenvalue paths were computed
    time_s: float


class DampingSensitivity(TypedDict):
    factor: float
    gamma: float
    damping_time_s: float
    growth_rate_per_s: float | None
    damping_ratio: float | None
    decay_time_s: float | None
    stable: bool


class LeastDamped(TypedDict):
    re: float
    im: float
    growth_rate_per_s: float
    frequency_Hz: float
    damping_ratio: float | None
    decay_time_s: float | None
    error: float


class BuckledOperatingPoint(TypedDict):
    """The buckled tether at the operating load (rung 3); only ``available`` and ``reason`` when it has none."""

    available: bool
    reason: NotRequired[str]
    damping_sensitivity: NotRequired[list[DampingSensitivity]]
    branch: NotRequired[str]
    B: NotRequired[float]
    measure1: NotRequired[float]
    max_deflection: NotRequired[float]
    max_deflection_m: NotRequired[float]
    end_shortening_m: NotRequired[float]
    end_force_N: NotRequired[dict[str, list[float]]]  # {"s=0": [3 components], "s=L": [...]}
    end_moment_N_m: NotRequired[dict[str, list[float]]]
    shape: NotRequired[Shape]
    deflection_error_m: NotRequired[float | None]
    residual: NotRequired[float]
    N: NotRequired[int]
    N_check: NotRequired[int | None]
    stable: NotRequired[bool]
    spectrum_converged: NotRequired[bool]
    least_damped: NotRequired[LeastDamped | None]
    points: NotRequired[int]
    time_s: NotRequired[float]


class RegionRow(TypedDict):
    omega: float
    spin_rpm: float
    pitchfork_B: float | None
    secondary_B: float | None
    pitchfork_IB0_N_per_m: float | None
    secondary_IB0_N_per_m: float | None


class RegionCurve(TypedDict):
    omega: list[float]
    spin_rpm: list[float]
    B: list[float]
    IB0_N_per_m: list[float]


class SecondaryCurve(RegionCurve):
    interpolation: str
    interpolation_error_B: float | None
    interpolation_error_IB0_N_per_m: float | None


class CoilRegion(TypedDict):
    """``postbuckling.region``: where b1 is stable in the (spin, load) plane (rung 3)."""

    rows: list[RegionRow]
    N: int
    liftoff_omega: float | None
    liftoff_omega_error: float | None
    liftoff_rpm: float | None
    pitchfork_curve: RegionCurve
    secondary_curve: SecondaryCurve
    time_s: float
    operating_rpm: float
    lowest_stable_spin_rpm: float | None


class PostbucklingSection(TypedDict):
    """``postbuckling``: rungs 2-3, or why they were not computed (``computed`` False with a ``reason``).

    With ``computed`` True: the diagram and, where b1 was found, its secondary
    pitchfork and stability; ``operating`` and ``region`` where the operating
    load lies on b1 (:func:`etcheck.checks.buckled.postbuckling_check`)."""

    computed: bool
    B_c: float | None
    load_ratio: float | None
    reason: NotRequired[str]
    diagram: NotRequired[BifurcationDiagram]
    secondary_pitchfork_B: NotRequired[float | None]
    secondary_pitchfork_error: NotRequired[float | None]
    secondary_pitchfork_IB0_N_per_m: NotRequired[float | None]
    secondary_pitchfork_reason: NotRequired[str]
    b1_first_unstable_B: NotRequired[float | None]
    b1_stable_at_start: NotRequired[bool | None]
    b1_stable_to_B: NotRequired[float | None]
    b1_stable_to_IB0_N_per_m: NotRequired[float | None]
    operating: NotRequired[BuckledOperatingPoint | None]
    region: NotRequired[CoilRegion | None]
    time_s: NotRequired[float]
