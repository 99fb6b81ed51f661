"""The mission as read, as types: the records that :meth:`etcheck.input.mission.Mission.echo` and the
uncertainty table write into a check's results (``results["mission"]``, ``results["uncertainty"]["inputs"]``).

Plain JSON-able dicts described key by key (see :mod:`etcheck.checks.sections` for the rest of the results and
docs/results.schema.json for the same layout as a JSON Schema). Quantities are "value unit" text as written
for the reader; numbers carry their unit in the key name.
"""

# no ``from __future__ import annotations``: TypedDict reads NotRequired from evaluated annotations only
from typing import NotRequired, TypedDict


class TetherEcho(TypedDict):
    """``mission.tether``: the inputs as read ("value unit" text; None where not given)."""

    length: str
    bending_stiffness: list[str]  # [EI] or [EI1, EI2]
    torsional_stiffness: str
    poisson_ratio: float | None
    mass_per_length: str
    rotary_inertia_ratio: float
    youngs_modulus: str | None
    cross_section_area: str | None
    damping_time: str | None
    end_conditions: list[str]  # [lower end, upper end]: welded, pinned or swivel


class TensionProfile(TypedDict):
    """Gravity-gradient tension along the tether (``tether.end_masses``; SI, units in the keys)."""

    model: str
    used: str
    used_N: float
    minimum_N: float
    minimum_at: str
    maximum_N: float
    at_centre_of_mass_N: float
    upper_end_N: float
    lower_end_N: float
    centre_of_mass_above_lower_end_m: float
    upper_mass_kg: float
    lower_mass_kg: float
    tether_mass_kg: float
    orbit_rate_rad_s: float
    orbit_rate_source: str


class CollectionEcho(TypedDict):
    """``mission.operation.current_profile.collection``: orbital-motion-limited collection (SI, units in the keys)."""

    plasma_density_per_m3: float
    motional_field_V_per_m: float
    conductivity_S_per_m: float
    perimeter_m: float
    conductive_area_m2: float
    anode_end: str
    characteristic_length_m: float
    length_ratio: float
    short_circuit_current_A: float
    largest_current_A: float


class CurrentProfileEcho(TypedDict):
    """``mission.operation.current_profile``: I(s) / I_max at fractions ``at`` of the length from the lower end
    (the points given, or samples of the OML profile), how it was made and what it assumed."""

    model: str
    at: list[float]
    fraction: list[float]
    collection: CollectionEcho | None
    notes: list[str]


class OperationEcho(TypedDict):
    """``mission.operation``: current and field as [value] or [low, high]; the field in µT."""

    current: list[str]
    current_profile: CurrentProfileEcho | None  # None: one current along the whole tether
    axial_field: list[str] | None  # None: from the [orbit], not yet evaluated
    cross_field: list[str] | None  # None: not given (from the [orbit], or etcheck's default)
    spin_rate: str
    spin_rate_rpm: float
    end_tension: str
    gravity_gradient: TensionProfile | None


class CheckEcho(TypedDict):
    """``mission.check``: the rules of the check as read."""

    required_margin: float
    fidelity: str
    scaling_constant: float
    resolution: int | None
    tolerance: float


class OrbitEcho(TypedDict):
    """``mission.orbit`` (missions with an [orbit] table): the orbit as read (the field along it is in the
    results' ``orbit`` section).

    Orbital elements give the element keys (``kind`` "elements"); a TLE gives
    ``lines`` and ``epoch`` (``kind`` "tle")."""

    kind: str
    perigee_altitude_km: float
    apogee_altitude_km: NotRequired[float]
    inclination_deg: NotRequired[float]
    raan_deg: NotRequired[float]
    argument_of_perigee_deg: NotRequired[float]
    mean_anomaly_deg: NotRequired[float]
    frame: NotRequired[str]
    lines: NotRequired[list[str]]
    epoch: NotRequired[str]
    period_s: float
    start: str
    duration_s: float
    step_s: float | None
    libration_in_plane_deg: float
    libration_out_of_plane_deg: float
    model: str


class FlightEcho(TypedDict):
    """``mission.flight``: what the tether did in flight ("coiled" or "straight") and who reported it."""

    outcome: str
    reported: str


class MissionEcho(TypedDict):
    """``mission``: the mission file as read (:meth:`etcheck.input.mission.Mission.echo`)."""

    name: str
    description: str
    source: str
    file: str | None
    sha256: str | None
    tether: TetherEcho
    operation: OperationEcho
    check: CheckEcho
    notes: list[str]
    assumed: list[str]  # the fields the mission marks as assumptions ("table.field")
    flight: FlightEcho | None  # what the tether did in flight (None: not flown, or not said)
    orbit: NotRequired[OrbitEcho]


class DistributionRecord(TypedDict):
    """One uncertain input as read (:meth:`etcheck.input.uncertainty.Distribution.as_dict`)."""

    input: str
    written: str
    distribution: str
    nominal: float
    factor: bool
    unit: str
    describe: str
    range: list[float]


class UncertaintyInputs(TypedDict):
    inputs: list[DistributionRecord]
    notes: list[str]
