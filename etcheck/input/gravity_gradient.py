"""Gravity-gradient tension of a tether hanging on the local vertical.

A mission may give the masses of the two end bodies (``[tether] end_masses =
["upper", "lower"]``) and the orbit rate instead of ``[operation]
end_tension``. The tether is taken straight along the local vertical of a
circular orbit of rate Omega, at rest in the orbiting frame (no libration):
every element at height ``x`` above the system's centre of mass feels the
tidal plus centrifugal acceleration ``3 Omega^2 x`` along the tether, so the
tension at a point is ``3 Omega^2`` times the first moment about the centre
of mass of all the mass on the far side of that point (end body plus the
tether beyond the point). With ``h`` the height above the lower end, ``h_c``
that of the centre of mass and ``mu`` the mass per length, this is one
parabola along the whole tether:

    T(h) = T_c - (3/2) Omega^2 mu (h - h_c)^2,
    T_c  = 3 Omega^2 [m_upper (L - h_c) + mu (L - h_c)^2 / 2],

largest at the centre of mass and smallest at the end farther from it; at
the ends ``T(L) = 3 Omega^2 m_upper (L - h_c)`` and ``T(0) = 3 Omega^2
m_lower h_c``. With a massless tether it is ``3 Omega^2 m_u m_l L / (m_u +
m_l)`` everywhere.

The check uses the whole profile (:meth:`GravityGradient.shape`, rung 1v of
docs/model.md section 10). Tension stabilises the straight tether against
magnetic buckling and whirl, so the SMALLEST tension along the tether held
constant (:attr:`GravityGradient.minimum`) gives a conservative bound, which
the check reports beside it.

Orbit rate: given (``operation.orbit_rate``), from a circular altitude
(``operation.orbit_altitude``, the mean motion sqrt(mu_E / r^3)), or from the
mission's ``[orbit]`` table. On an eccentric orbit a tether kept on the local
vertical turns at the true-anomaly rate, and the along-tether acceleration per
unit height is ``2 mu_E / r^3 + (dnu/dt)^2 = mu_E (2 + p / r) / r^3`` (p the
semi-latus rectum), smallest at apogee where it is ``(3 - e) mu_E / r_a^3``:
the check takes that, i.e. ``Omega^2 = (3 - e) mu_E / (3 r_a^3)`` (the perigee
would give the largest tension, which is not conservative).

The functions below take and return SI floats (kg, m, kg/m, rad/s, N) and are
pure; :func:`parse_gravity_gradient` is the unit edge used by
:mod:`etcheck.input.mission`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from etcheck.errors import MissionError
from etcheck.input.echo import TensionProfile
from etcheck.input.units import QuantityProblem, to_quantity
from etcheck.rod.core.profile import Profile

if TYPE_CHECKING:
    from etcheck.orbit.spec import OrbitSpec

#: Earth's gravitational parameter (m^3/s^2) and equatorial radius (m), as etcheck.orbit.elements
#: (repeated here so that missions without an [orbit] table do not import the orbit package).
MU_EARTH = 3.986004418e14
R_EARTH = 6378137.0


@dataclass(frozen=True)
class GravityGradient:
    """Tension along a gravity-gradient-stabilised tether (SI: kg, m, kg/m, rad/s, N).

    ``centre_of_mass`` is the height of the system's centre of mass above the
    lower end (m); ``upper_end``, ``lower_end``, ``at_centre_of_mass``,
    ``minimum`` and ``maximum`` are tensions (N). ``rate_source`` says where
    the orbit rate came from (text for the report).
    """

    upper_mass: float
    lower_mass: float
    length: float
    mass_per_length: float
    orbit_rate: float
    rate_source: str = "given"

    @property
    def total_mass(self) -> float:
        """kg: both end bodies and the tether."""
        return self.upper_mass + self.lower_mass + self.mass_per_length * self.length

    @property
    def centre_of_mass(self) -> float:
        """m above the lower end."""
        L, mu = self.length, self.mass_per_length
        return (self.upper_mass * L + 0.5 * mu * L * L) / self.total_mass

    @property
    def at_centre_of_mass(self) -> float:
        """N: the largest tension, at the centre of mass."""
        up = self.length - self.centre_of_mass
        return 3.0 * self.orbit_rate**2 * (self.upper_mass * up + 0.5 * self.mass_per_length * up * up)

    def at(self, height: float) -> float:
        """Tension (N) at ``height`` m above the lower end (0 <= height <= length)."""
        if not 0.0 <= height <= self.length:
            raise ValueError(f"height {height} m is outside the tether [0, {self.length}] m")
        d = height - self.centre_of_mass
        return max(self.at_centre_of_mass - 1.5 * self.orbit_rate**2 * self.mass_per_length * d * d, 0.0)

    @property
    def upper_end(self) -> float:
        """N: 3 Omega^2 m_upper (L - h_c)."""
        return 3.0 * self.orbit_rate**2 * self.upper_mass * (self.length - self.centre_of_mass)

    @property
    def lower_end(self) -> float:
        """N: 3 Omega^2 m_lower h_c."""
        return 3.0 * self.orbit_rate**2 * self.lower_mass * self.centre_of_mass

    @property
    def minimum(self) -> float:
        """N: the smallest tension along the tether (at the end farther from the centre of mass)."""
        return min(self.upper_end, self.lower_end)

    @property
    def maximum(self) -> float:
        """N: the largest tension along the tether (at the centre of mass)."""
        return self.at_centre_of_mass

    @property
    def minimum_at(self) -> str:
        return "upper end" if self.upper_end <= self.lower_end else "lower end"

    def shape(self) -> Profile:
        """T(s) / maximum along the tether, s the fraction of the length from the lower end (dimensionless: one
        parabola, exact at degree 2)."""
        L, top = self.length, self.maximum
        return Profile.from_function(lambda s: np.array([self.at(float(x) * L) for x in np.atleast_1d(s)]) / top,
                                     degree=2)

    def echo(self) -> TensionProfile:
        """The profile for the results (SI, the names carry their unit)."""
        return TensionProfile(
            model="gravity gradient, tether on the local vertical at rest in the orbiting frame of a circular orbit "
                  "(no libration)",
            used="profile",
            used_N=self.minimum,
            minimum_N=self.minimum,
            minimum_at=self.minimum_at,
            maximum_N=self.maximum,
            at_centre_of_mass_N=self.at_centre_of_mass,
            upper_end_N=self.upper_end,
            lower_end_N=self.lower_end,
            centre_of_mass_above_lower_end_m=self.centre_of_mass,
            upper_mass_kg=self.upper_mass,
            lower_mass_kg=self.lower_mass,
            tether_mass_kg=self.mass_per_length * self.length,
            orbit_rate_rad_s=self.orbit_rate,
            orbit_rate_source=self.rate_source,
        )

    def statement(self) -> str:
        """One line for the mission's notes and the report."""
        return (f"end tension from the gravity gradient: end masses {self.upper_mass:.4g} kg (upper) and "
                f"{self.lower_mass:.4g} kg (lower), tether {self.mass_per_length * self.length:.4g} kg, orbit rate "
                f"{self.orbit_rate:.5g} rad/s ({self.rate_source}); the tension along the tether runs from "
                f"{self.minimum:.4g} N at the {self.minimum_at} to {self.maximum:.4g} N at the centre of mass "
                f"({self.centre_of_mass:.4g} m above the lower end; upper end {self.upper_end:.4g} N, lower end "
                f"{self.lower_end:.4g} N). The check uses this profile along the tether (tether on the local "
                f"vertical, no libration); the smallest, {self.minimum:.4g} N, held constant along it, is reported "
                "beside it as a bound (tension stabilises, so the uniform smallest tension is conservative)")


def circular_rate(altitude: float) -> float:
    """Mean motion sqrt(mu_E / r^3) (rad/s) of a circular orbit ``altitude`` m above R_E."""
    return math.sqrt(MU_EARTH / (R_EARTH + altitude) ** 3)


def apogee_rate(perigee_altitude: float, apogee_altitude: float) -> float:
    """Effective rate (rad/s) at apogee: 3 Omega^2 = (3 - e) mu_E / r_a^3 (altitudes in m above R_E).

    The smallest along-tether gradient over an orbit for a tether on the local
    vertical (the circular mean motion when perigee = apogee).
    """
    rp, ra = R_EARTH + perigee_altitude, R_EARTH + apogee_altitude
    e = (ra - rp) / (ra + rp)
    return math.sqrt((3.0 - e) * MU_EARTH / (3.0 * ra**3))


def orbit_rate_of(spec: OrbitSpec) -> tuple[float, str]:
    """The conservative (apogee) rate of an ``[orbit]`` table and a line saying so."""
    from etcheck.orbit.elements import KeplerianElements

    o = spec.orbit if isinstance(spec.orbit, KeplerianElements) else KeplerianElements.from_tle(spec.orbit)
    hp, ha = o.perigee_altitude, o.apogee_altitude
    if ha - hp < 1.0:
        return apogee_rate(hp, ha), f"[orbit]: circular at {hp / 1e3:.6g} km, mean motion"
    return apogee_rate(hp, ha), (f"[orbit]: at apogee ({ha / 1e3:.6g} km, perigee {hp / 1e3:.6g} km), where the "
                                 "gradient and the tension are smallest: 3 Omega^2 = (3 - e) mu_E / r_a^3")


def parse_gravity_gradient(tether: dict, operation: dict, orbit: OrbitSpec | None, length: float,
                           mass_per_length: float, source: str) -> GravityGradient | None:
    """The unit edge: ``tether.end_masses`` + orbit rate -> :class:`GravityGradient` (None without end masses).

    ``length`` (m) and ``mass_per_length`` (kg/m) are the parsed tether's.
    Raises MissionError naming the field: both end_tension and end_masses,
    end masses without an orbit rate, a rate without end masses, two rate
    sources, malformed, negative or non-finite values.
    """
    rate_keys = [k for k in ("orbit_rate", "orbit_altitude") if k in operation]
    if "end_masses" not in tether:
        if rate_keys:
            raise MissionError(source, f"operation.{rate_keys[0]}", "given without tether.end_masses: it is used only "
                               "for the gravity-gradient tension", 'add end_masses = ["20 kg", "1.5 kg"] (upper, lower) '
                               f"under [tether], or remove operation.{rate_keys[0]}")
        return None
    if "end_tension" in operation:
        raise MissionError(source, "operation.end_tension", "both operation.end_tension and tether.end_masses given",
                           "give either end_tension (a fixed end force) or end_masses with the orbit rate "
                           "(the tension is then computed from the gravity gradient), not both")
    upper, lower = _end_masses(tether["end_masses"], source)
    rate, how = _orbit_rate(operation, orbit, rate_keys, source)
    return GravityGradient(upper, lower, length, mass_per_length, rate, how)


def _end_masses(value: Any, source: str) -> tuple[float, float]:
    """tether.end_masses = [upper, lower] -> kg, each >= 0."""
    if not isinstance(value, list) or len(value) != 2:
        raise MissionError(source, "tether.end_masses", f"expected two masses [upper, lower], got {value!r}",
                           'e.g. end_masses = ["20 kg", "1.5 kg"]: the body at the upper end first, then the lower')
    masses = []
    for item in value:
        try:
            m = to_quantity(item, "mass").value
        except QuantityProblem as exc:
            raise MissionError(source, "tether.end_masses", str(exc)) from None
        if not m >= 0.0:
            raise MissionError(source, "tether.end_masses", f"masses must be >= 0, got {item!r}")
        masses.append(float(m))
    return masses[0], masses[1]


def _orbit_rate(operation: dict, orbit: OrbitSpec | None, rate_keys: list[str], source: str) -> tuple[float, str]:
    """The orbit rate (rad/s) from exactly one source (operation.orbit_rate, operation.orbit_altitude or the
    [orbit] table) and a line saying which."""
    if len(rate_keys) == 2:
        raise MissionError(source, "operation.orbit_altitude", "both operation.orbit_rate and operation.orbit_altitude "
                           "given", "give one of them")
    if rate_keys and orbit is not None:
        raise MissionError(source, f"operation.{rate_keys[0]}", "given together with an [orbit] table",
                           "leave it out: the orbit rate is then taken from the [orbit] table (at apogee, conservative)")
    if "orbit_rate" in operation:
        return _operation_value(operation, "orbit_rate", "angular_rate", source), "operation.orbit_rate"
    if "orbit_altitude" in operation:
        return _altitude_rate(operation, source)
    if orbit is not None:
        return orbit_rate_of(orbit)
    raise MissionError(source, "operation.orbit_rate", "tether.end_masses given without the orbit rate",
                       'add orbit_rate = "1.1e-3 rad/s" or orbit_altitude = "350 km" under [operation], '
                       "or an [orbit] table")


def _altitude_rate(operation: dict, source: str) -> tuple[float, str]:
    """operation.orbit_altitude: one altitude (a circular orbit, its mean motion) or [perigee, apogee] (the
    conservative apogee rate, :func:`apogee_rate`), and a line describing the orbit."""
    value = operation["orbit_altitude"]
    if not isinstance(value, list):
        h = _operation_value(operation, "orbit_altitude", "length", source)
        return circular_rate(h), f"circular orbit at operation.orbit_altitude = {h / 1e3:.6g} km, mean motion"
    if len(value) != 2:
        raise MissionError(source, "operation.orbit_altitude", f"expected one altitude or [perigee, apogee], got "
                           f"{len(value)} values", 'e.g. orbit_altitude = ["192 km", "850 km"]')
    hp, ha = (_operation_value({"orbit_altitude": v}, "orbit_altitude", "length", source) for v in value)
    if hp > ha:
        raise MissionError(source, "operation.orbit_altitude", f"perigee {value[0]!r} above apogee {value[1]!r}",
                           "write it as [perigee, apogee]")
    if ha - hp < 1.0:
        return circular_rate(hp), f"circular orbit at operation.orbit_altitude = {hp / 1e3:.6g} km, mean motion"
    return apogee_rate(hp, ha), (f"orbit {hp / 1e3:.6g} km x {ha / 1e3:.6g} km (operation.orbit_altitude), at "
                                 "apogee, where the gradient and the tension are smallest: 3 Omega^2 = (3 - e) mu_E "
                                 "/ r_a^3")


#: operation.KEY -> (accepted, problem when not): an orbit rate (rad/s) is positive, a circular altitude (m)
#: lies between 100 km and 100000 km
_RATE_LIMITS = {
    "orbit_rate": (lambda x: x > 0, "must be positive, got {!r}"),
    "orbit_altitude": (lambda x: 100e3 <= x <= 100000e3, "must lie between 100 km and 100000 km, got {!r}"),
}


def _operation_value(operation: dict, key: str, kind: str, source: str) -> float:
    """operation.KEY as an SI float within its limits (:data:`_RATE_LIMITS`)."""
    try:
        value = float(to_quantity(operation[key], kind).value)
    except QuantityProblem as exc:
        raise MissionError(source, f"operation.{key}", str(exc)) from None
    accepted, problem = _RATE_LIMITS[key]
    if not accepted(value):
        raise MissionError(source, f"operation.{key}", problem.format(operation[key]))
    return value


__all__ = ["GravityGradient", "apogee_rate", "circular_rate", "orbit_rate_of", "parse_gravity_gradient"]
