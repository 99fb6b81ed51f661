"""The parts of a :class:`~etcheck.input.mission.Mission`, one frozen record per concern.

:class:`TetherProperties` is what the tether is (the ``[tether]`` table), :class:`Operation` how it is run (the
``[operation]`` table), :class:`Provenance` where the mission comes from and what etcheck assumed reading it
(the ``[mission]`` table, the file, the notes) and :class:`Studies` what studies the file asks for (the
``[sweep]`` and ``[uncertainty]`` tables). The ``[check]`` table is
:class:`etcheck.input.mission.CheckSettings` and the ``[orbit]`` table :class:`etcheck.orbit.spec.OrbitSpec`.
Quantities are astropy Quantities in SI; a new mission field goes into the record of its table.
"""

from __future__ import annotations

from dataclasses import dataclass

import astropy.units as u

from etcheck.input.current_profile import CurrentProfile
from etcheck.input.gravity_gradient import GravityGradient
from etcheck.input.sweep_axes import Axis
from etcheck.input.uncertainty import Uncertainty
from etcheck.rod.core.ends import ALL_WELDED


@dataclass(frozen=True)
class TetherProperties:
    """The ``[tether]`` table: the tether itself (SI quantities)."""

    length: u.Quantity  # L, m
    bending_stiffness: tuple[u.Quantity, u.Quantity]  # (EI1, EI2), N m^2, EI1 >= EI2
    torsional_stiffness: u.Quantity  # GJ, N m^2 (given, or from the Poisson ratio)
    mass_per_length: u.Quantity  # kg/m
    rotary_inertia_ratio: float  # P = I1 / (A L^2) (given, or from youngs_modulus and cross_section_area)
    damping_time: u.Quantity | None = None  # s; None: etcheck's default damping (stated in the notes)
    end_conditions: tuple[str, str] = ALL_WELDED  # (lower end, upper end): etcheck.rod.core.ends
    poisson_ratio: float | None = None  # nu where GJ follows from it
    youngs_modulus: u.Quantity | None = None  # E, Pa, where P follows from it
    cross_section_area: u.Quantity | None = None  # A, m^2, where P follows from it


@dataclass(frozen=True)
class Operation:
    """The ``[operation]`` table: how the tether is run (SI quantities).

    Ranges (current, fields) are (low, high) pairs; the check uses the worst case |I| * |B0| and says so.
    """

    current: tuple[u.Quantity, u.Quantity]  # A
    axial_field: tuple[u.Quantity, u.Quantity] | None  # T; None: from the [orbit], evaluated by the orbit stage
    spin_rate: u.Quantity = 0.0 * u.rad / u.s
    # N; with a gravity_gradient its minimum along the tether (conservative)
    end_tension: u.Quantity = 0.0 * u.N
    # the field across the undeformed tether (its bow under the Lorentz load), T; None: not given (from the
    # [orbit] when there is one, else etcheck's default, stated in the report)
    cross_field: tuple[u.Quantity, u.Quantity] | None = None
    # tether.end_masses + orbit rate: the tension profile (etcheck.input.gravity_gradient)
    gravity_gradient: GravityGradient | None = None
    # current_profile: I(s)/I_max along the tether (None: one current along the whole tether)
    current_profile: CurrentProfile | None = None

    @property
    def worst_current(self) -> u.Quantity:
        return max(abs(self.current[0]), abs(self.current[1]))

    @property
    def current_range_A(self) -> tuple[float, float]:
        """operation.current as given, (low, high) in A: plain floats for the report's statements."""
        lo, hi = (float(x.to_value(u.A)) for x in self.current)
        return lo, hi

    @property
    def axial_field_range_uT(self) -> tuple[float, float]:
        """operation.axial_field as given, (low, high) in µT: plain floats for the report's statements."""
        lo, hi = (float(x.to_value(u.uT)) for x in self.axial_field)
        return lo, hi

    @property
    def worst_cross_field(self) -> u.Quantity | None:
        """The largest |field across the tether| given (None where not given)."""
        return None if self.cross_field is None else max(abs(self.cross_field[0]), abs(self.cross_field[1]))


@dataclass(frozen=True)
class Provenance:
    """Where the mission comes from (the ``[mission]`` table and the file) and what etcheck assumed reading it.

    ``notes`` records every assumption etcheck made (defaults taken, derived values) for the report.
    """

    name: str
    description: str = ""
    source: str = ""  # [mission] source: where the values come from
    file: str = "mission"  # the file read
    sha256: str = ""  # of the file's bytes
    notes: tuple[str, ...] = ()
    assumed: tuple[str, ...] = ()  # [mission] assumed: the fields ("table.field") whose values are assumptions
    given: frozenset[str] = frozenset()  # the fields the file gives ("table.field"); the rest took their defaults
    flight: dict[str, str] | None = None  # [mission] flight: {"outcome", "reported"}, where the tether flew

    def is_assumed(self, *fields: str) -> bool:
        """Whether the mission marks any of ``fields`` ("table.field", or "table" for a whole table) as assumed."""
        return any(f == a or a.startswith(f + ".") for f in fields for a in self.assumed)


@dataclass(frozen=True)
class Studies:
    """The studies a mission file asks for beside the check."""

    sweep: tuple[Axis, ...] = ()  # the [sweep] table: default axes of `etcheck sweep`
    uncertainty: Uncertainty | None = None  # the [uncertainty] table (etcheck.input.uncertainty)


__all__ = ["Operation", "Provenance", "Studies", "TetherProperties"]
