"""Where a mission's axial field comes from: ``[operation] axial_field`` or an ``[orbit]`` table,
never both; the orbit as read, echoed (degrees, km).

Reading only: the field along the orbit (IGRF over the window, its worst case) is the
check's orbit stage, :mod:`etcheck.checks.orbit_field`. etcheck.orbit is imported here only
when a mission has an ``[orbit]`` table.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from etcheck.errors import MissionError
from etcheck.input.echo import OrbitEcho

if TYPE_CHECKING:
    from etcheck.orbit.spec import OrbitSpec


def check_one_field_source(operation: dict, data: dict, source: str) -> None:
    """Exactly one of ``operation.axial_field`` and ``[orbit]``; MissionError (exit 2) naming both otherwise."""
    has_field, has_orbit = "axial_field" in operation, "orbit" in data
    if has_field and has_orbit:
        raise MissionError(source, "operation.axial_field", "both operation.axial_field and an [orbit] table given",
                           "give either operation.axial_field (the field along the tether) or [orbit] "
                           "(the field is then computed along the orbit from IGRF), not both")
    if not has_field and not has_orbit:
        raise MissionError(source, "operation.axial_field", "missing: neither operation.axial_field nor an [orbit] table given",
                           'add axial_field = "70 uT" under [operation], or an [orbit] table '
                           '(altitude, inclination, epoch) to compute it along the orbit')


def orbit_echo(spec: OrbitSpec) -> OrbitEcho:
    """The orbit as read, for the results (degrees, km for the reader)."""
    from etcheck.orbit.elements import KeplerianElements
    from etcheck.orbit.envelope import orbital_period

    o = spec.orbit
    if isinstance(o, KeplerianElements):
        orbit = {"kind": "elements", "perigee_altitude_km": o.perigee_altitude / 1e3, "apogee_altitude_km": o.apogee_altitude / 1e3,
                 "inclination_deg": math.degrees(o.inclination), "raan_deg": math.degrees(o.raan),
                 "argument_of_perigee_deg": math.degrees(o.argument_of_perigee),
                 "mean_anomaly_deg": math.degrees(o.mean_anomaly), "frame": o.frame}
    else:
        orbit = {"kind": "tle", "lines": (o.line1, o.line2), "epoch": o.epoch,
                 "perigee_altitude_km": o.perigee_altitude / 1e3}
    return OrbitEcho(
        **orbit,
        period_s=orbital_period(spec),
        start=spec.start,
        duration_s=spec.duration,
        step_s=spec.step,
        libration_in_plane_deg=math.degrees(spec.libration_in_plane),
        libration_out_of_plane_deg=math.degrees(spec.libration_out_of_plane),
        model=spec.model,
    )


__all__ = ["check_one_field_source", "orbit_echo"]
