"""What an orbit evaluation needs, as a value: :class:`OrbitSpec` and its limits.

The mission file's ``[orbit]`` table (its fields: :mod:`etcheck.input.orbit_table`) is read into it by
:func:`etcheck.input.orbit_table.parse_orbit`.

Altitudes are above the equatorial radius 6378.137 km. SI units.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from etcheck.orbit.models import DEFAULT_MODEL

if TYPE_CHECKING:
    from etcheck.orbit.elements import KeplerianElements, TwoLineElements

#: Lowest perigee accepted: below it the atmosphere decays the orbit in days.
MIN_ALTITUDE = 150e3
#: Most samples one evaluation may hold (about 100 MB of series).
MAX_SAMPLES = 2_000_000
DEFAULT_DURATION = 86400.0
#: Longest window (s): one year at the 60 s starting step is 5e5 samples.
MAX_DURATION = 366 * 86400.0
#: Longest time between a TLE's epoch and the start of the window.
MAX_TLE_AGE_DAYS = 30.0

ELEMENT_KEYS = ("altitude", "perigee_altitude", "apogee_altitude", "inclination", "raan", "argument_of_perigee", "mean_anomaly")
KEYS = ELEMENT_KEYS + ("epoch", "tle", "duration", "step", "libration_in_plane", "libration_out_of_plane")

@dataclass(frozen=True)
class OrbitSpec:
    """What to evaluate: an orbit, a window and the libration bounds.

    orbit: Keplerian elements or a TLE. start: UTC, ISO 8601 (the elements'
    epoch, or the TLE epoch unless given). duration: s. step: s, or None to
    halve a starting step until the worst case converges.
    libration_in_plane (pitch) and libration_out_of_plane (roll) amplitudes:
    rad in [0, pi/2). model: the IGRF generation ("IGRF-14").
    """

    orbit: KeplerianElements | TwoLineElements
    start: str
    duration: float = DEFAULT_DURATION
    step: float | None = None
    libration_in_plane: float = 0.0
    libration_out_of_plane: float = 0.0
    model: str = DEFAULT_MODEL


__all__ = ["DEFAULT_DURATION", "ELEMENT_KEYS", "KEYS", "MAX_DURATION", "MAX_SAMPLES", "MAX_TLE_AGE_DAYS", "MIN_ALTITUDE", "OrbitSpec"]
