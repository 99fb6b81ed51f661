"""The ``[orbit]`` table of a mission -> the axial field of the check (issue 14).

A mission gives either ``[operation] axial_field`` or an ``[orbit]`` table,
never both. With an orbit, :func:`orbit_axial_field` parses the table
(:func:`etcheck.orbit.spec.parse_orbit`, errors name ``orbit.FIELD``),
evaluates the envelope of the axial field over the window once
(:func:`etcheck.orbit.envelope.axial_field_envelope`, IGRF, about 0.3 s) and
returns its worst case in tesla: the check's magnetic load is then the
worst |current| times this field, and the statement of where it occurs goes
into the mission's notes and echo.

etcheck.orbit (IGRF through ppigrf, SGP4) is imported here only when a
mission has an ``[orbit]`` table.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, cast

from etcheck.errors import MissionError
from etcheck.input.echo import OrbitEcho

if TYPE_CHECKING:
    from etcheck.orbit.envelope import AxialFieldEnvelope
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


def orbit_axial_field(table: Any, source: str) -> tuple[OrbitSpec, AxialFieldEnvelope]:
    """Parse the ``[orbit]`` table and evaluate its envelope once (the worst axial field is ``env.worst``, T)."""
    from etcheck.orbit.envelope import axial_field_envelope
    from etcheck.orbit.spec import parse_orbit

    spec = parse_orbit(table, source)
    return spec, axial_field_envelope(spec, source=source)


def statement(env: AxialFieldEnvelope) -> str:
    """One line: the worst axial field over the orbit, where and when (µT, degrees, UTC)."""
    lat, lon = env.worst_latitude, env.worst_longitude
    return (f"axial field: worst case over the orbit, {env.worst * 1e6:.4g} µT at "
            f"{abs(lat):.2f}° {'N' if lat >= 0 else 'S'}, {abs(lon):.2f}° {'E' if lon >= 0 else 'W'}, "
            f"{env.worst_utc[:19]} UTC ({env.model}, {env.step:g} s sampling"
            f"{'' if env.converged else ', NOT converged'})")


def orbit_notes(spec: OrbitSpec, env: AxialFieldEnvelope) -> list[str]:
    """The assumptions behind the computed field, for the mission's notes."""
    notes = [statement(env) + "; the check uses it as the axial field (the current as given)"]
    if spec.libration_in_plane == 0 and spec.libration_out_of_plane == 0:
        notes.append("orbit: tether on the local vertical (no libration given); the worst case is |B . up|")
    else:
        notes.append(f"orbit: worst case over libration up to {math.degrees(spec.libration_in_plane):.3g}° in the orbit plane "
                     f"and {math.degrees(spec.libration_out_of_plane):.3g}° out of it; on the vertical the worst is "
                     f"{env.worst_nominal * 1e6:.4g} µT")
    if not env.converged:
        notes.append(f"orbit: the worst axial field changed by {env.step_change:.2g} (relative) at the last halving of "
                     f"the step ({env.step:g} s), above the tolerance {env.tolerance:g}")
    return notes


def orbit_echo(spec: OrbitSpec, env: AxialFieldEnvelope) -> OrbitEcho:
    """The orbit as read and the envelope's worst case, JSON-able (degrees, km, µT for the reader)."""
    from etcheck.orbit.elements import KeplerianElements
    from etcheck.orbit.envelope import orbital_period

    o = spec.orbit
    if isinstance(o, KeplerianElements):
        orbit = {"kind": "elements", "perigee_altitude_km": o.perigee_altitude / 1e3, "apogee_altitude_km": o.apogee_altitude / 1e3,
                 "inclination_deg": math.degrees(o.inclination), "raan_deg": math.degrees(o.raan),
                 "argument_of_perigee_deg": math.degrees(o.argument_of_perigee),
                 "mean_anomaly_deg": math.degrees(o.mean_anomaly), "frame": o.frame}
    else:
        orbit = {"kind": "tle", "lines": [o.line1, o.line2], "epoch": o.epoch,
                 "perigee_altitude_km": o.perigee_altitude / 1e3}
    return cast(OrbitEcho, {
        **orbit,
        "period_s": orbital_period(spec),
        "start": spec.start,
        "duration_s": spec.duration,
        "step_s": spec.step,
        "libration_in_plane_deg": math.degrees(spec.libration_in_plane),
        "libration_out_of_plane_deg": math.degrees(spec.libration_out_of_plane),
        "model": env.model,
        "worst_axial_field_uT": env.worst * 1e6,
        "statement": statement(env),
    })


__all__ = ["check_one_field_source", "orbit_axial_field", "orbit_echo", "orbit_notes", "statement"]
