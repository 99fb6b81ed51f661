"""The mission as read, as types: the records that :meth:`etcheck.input.mission.Mission.echo` and the
uncertainty table write into a check's results (``results["mission"]``, ``results["uncertainty"]["inputs"]``).

Records typed field by field (see :mod:`etcheck.checks.results.sections` for the rest of the results and
docs/results.schema.json for the same layout as a JSON Schema). Quantities are "value unit" text as written
for the reader; numbers carry their unit in the key name.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal

from etcheck.jsonable import OMITTED, Omitted, key

#: how an end of the tether is held (etcheck.rod.core.ends)
End = Literal["welded", "pinned", "swivel"]


@dataclass(frozen=True, slots=True, kw_only=True)
class TetherEcho:
    """``mission.tether``: the inputs as read ("value unit" text; None where not given)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "[tether] as read ('value unit' strings, null where not given)"}

    length: str
    bending_stiffness: tuple[str, ...]  # [EI] or [EI1, EI2]
    torsional_stiffness: str
    poisson_ratio: float | None
    mass_per_length: str
    rotary_inertia_ratio: float
    youngs_modulus: str | None
    cross_section_area: str | None
    damping_time: str | None
    end_conditions: tuple[End, ...] = key(
        "[lower end, upper end] as read: welded, pinned (no bending moment, twist held) or swivel (no moment); default welded at both",
        minItems=2,
        maxItems=2,
    )  # [lower end, upper end]: welded, pinned or swivel


@dataclass(frozen=True, slots=True, kw_only=True)
class TensionProfile:
    """Gravity-gradient tension along the tether (``tether.end_masses``; SI, units in the keys)."""

    JSON_SCHEMA: ClassVar[dict] = {"description": "gravity-gradient tension profile"}

    model: str = key("the tension model in words")
    used: str = key("which tension the rod model uses ('minimum')")
    used_N: float = key("tension used (N)", minimum=0)
    minimum_N: float = key("smallest tension along the tether (N)", minimum=0)
    minimum_at: str
    maximum_N: float = key("largest tension, at the centre of mass (N)", minimum=0)
    at_centre_of_mass_N: float
    upper_end_N: float
    lower_end_N: float
    centre_of_mass_above_lower_end_m: float
    upper_mass_kg: float
    lower_mass_kg: float
    tether_mass_kg: float
    orbit_rate_rad_s: float = key("orbit rate (rad/s)", exclusiveMinimum=0)
    orbit_rate_source: str


@dataclass(frozen=True, slots=True, kw_only=True)
class CollectionEcho:
    """``mission.operation.current_profile.collection``: orbital-motion-limited collection (SI, units in the keys)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "orbital-motion-limited collection (Sanmartín, Martínez-Sánchez & Ahedo 1993): its inputs and the characteristic length L*, L/L*, sigma E_m A and the largest current it predicts (SI, units in the keys)"
    }

    plasma_density_per_m3: float
    motional_field_V_per_m: float
    conductivity_S_per_m: float
    perimeter_m: float
    conductive_area_m2: float
    anode_end: Literal["upper", "lower"]
    characteristic_length_m: float
    length_ratio: float
    short_circuit_current_A: float
    largest_current_A: float


@dataclass(frozen=True, slots=True, kw_only=True)
class CurrentProfileEcho:
    """``mission.operation.current_profile``: I(s) / I_max at fractions ``at`` of the length from the lower end
    (the points given, or samples of the OML profile), how it was made and what it assumed."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "operation.current_profile: I(s)/I_max at fractions `at` of the length from the lower end (the points given, or samples of the OML profile), how it was made and what it assumed"
    }

    model: Literal["given", "orbital-motion-limited collection"]
    at: tuple[float, ...]
    fraction: tuple[float, ...]
    collection: CollectionEcho | None
    notes: tuple[str, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class OperationEcho:
    """``mission.operation``: current and field as [value] or [low, high]; the field in µT."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "[operation] as read ('value unit' strings; spin_rate_rpm a number; gravity_gradient the tension profile or null; current_profile the current along the tether, or null for one current)"
    }

    current: tuple[str, ...]
    current_profile: CurrentProfileEcho | None  # None: one current along the whole tether
    axial_field: tuple[str, ...] | None = key(
        "the axial field as given (µT); null for a mission with an [orbit] table read but not yet checked (the check fills it with the worst field over the orbit)",
        nullable="type",
    )  # None: from the [orbit], not yet evaluated
    cross_field: tuple[str, ...] | None = key(
        "the field across the tether as given (µT); null where not given", nullable="type"
    )  # None: not given (from the [orbit], or etcheck's default)
    spin_rate: str
    spin_rate_rpm: float
    end_tension: str
    gravity_gradient: TensionProfile | None = key(
        "Gravity-gradient tension along the tether (``tether.end_masses``; SI, units in the keys).", nullable="anyOf"
    )


@dataclass(frozen=True, slots=True, kw_only=True)
class CheckEcho:
    """``mission.check``: the rules of the check as read."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "[check] as read: required_margin, fidelity, scaling_constant, resolution (integer or null), tolerance"
    }

    required_margin: float
    fidelity: str
    scaling_constant: float
    resolution: int | None
    tolerance: float


@dataclass(frozen=True, slots=True, kw_only=True)
class OrbitEcho:
    """``mission.orbit`` (missions with an [orbit] table): the orbit as read (the field along it is in the
    results' ``orbit`` section).

    Orbital elements give the element keys (``kind`` "elements"); a TLE gives
    ``lines`` and ``epoch`` (``kind`` "tle")."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the [orbit] table as read (only with [orbit]; the field along it is under the top-level orbit section)"
    }

    kind: str
    perigee_altitude_km: float
    apogee_altitude_km: float | Omitted = key(default=OMITTED)
    inclination_deg: float | Omitted = key(default=OMITTED)
    raan_deg: float | Omitted = key(default=OMITTED)
    argument_of_perigee_deg: float | Omitted = key(default=OMITTED)
    mean_anomaly_deg: float | Omitted = key(default=OMITTED)
    frame: str | Omitted = key(default=OMITTED)
    lines: tuple[str, ...] | Omitted = key(default=OMITTED)
    epoch: str | Omitted = key(default=OMITTED)
    period_s: float
    start: str
    duration_s: float
    step_s: float | None
    libration_in_plane_deg: float
    libration_out_of_plane_deg: float
    model: str


@dataclass(frozen=True, slots=True, kw_only=True)
class FlightEcho:
    """``mission.flight``: what the tether did in flight ("coiled" or "straight") and who reported it."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "[mission] flight: what the tether did in flight and who reported it; null where not flown"
    }

    outcome: Literal["coiled", "straight"]
    reported: str


@dataclass(frozen=True, slots=True, kw_only=True)
class MissionEcho:
    """``mission``: the mission file as read (:meth:`etcheck.input.mission.Mission.echo`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "the mission as read (etcheck.input.mission.Mission.echo): quantities as 'value unit' strings"
    }

    name: str = key("mission name")
    description: str = key("mission description")
    source: str = key("where the mission came from (file name or 'mission' for a dict)")
    file: str | None = key("mission file path")
    sha256: str | None = key("SHA-256 of the mission file")
    tether: TetherEcho
    operation: OperationEcho
    check: CheckEcho
    notes: tuple[str, ...] = key("notes made while reading")
    assumed: tuple[str, ...] = key(
        "[mission] assumed: the fields ('table.field') the mission marks as assumptions"
    )  # the fields the mission marks as assumptions ("table.field")
    flight: FlightEcho | None = key(nullable="type")  # what the tether did in flight (None: not flown, or not said)
    orbit: OrbitEcho | Omitted = key(default=OMITTED)


@dataclass(frozen=True, slots=True, kw_only=True)
class DistributionRecord:
    """One uncertain input as read (:meth:`etcheck.input.uncertainty.Distribution.echo`)."""

    JSON_SCHEMA: ClassVar[dict] = {
        "description": "One uncertain input as read (:meth:`etcheck.input.uncertainty.Distribution.echo`)."
    }

    input: str
    written: str
    distribution: str
    nominal: float
    factor: bool
    unit: str
    describe: str
    range: tuple[float, ...]


@dataclass(frozen=True, slots=True, kw_only=True)
class UncertaintyInputs:
    inputs: tuple[DistributionRecord, ...]
    notes: tuple[str, ...]
