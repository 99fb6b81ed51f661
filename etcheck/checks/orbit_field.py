"""The check's orbit stage: the axial field of a mission with an ``[orbit]`` table.

A mission read from a file holds its orbit as a specification only
(:class:`etcheck.orbit.spec.OrbitSpec`); this stage evaluates the envelope of the
axial field over the window once (:func:`etcheck.orbit.envelope.axial_field_envelope`,
IGRF through ppigrf, SGP4) and returns the mission with its axial field set to the
worst case (T) and the statement of where it occurs in its notes: the check's magnetic
load is then the worst |current| times this field. The pipeline is
input -> orbit -> scaling -> rungs; a mission with ``[operation] axial_field`` passes
through unchanged. The envelope carries the seconds it took (``AxialFieldEnvelope.seconds``).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import TYPE_CHECKING

import astropy.units as u

from etcheck.input.mission import Mission

if TYPE_CHECKING:
    from etcheck.orbit.envelope import AxialFieldEnvelope
    from etcheck.orbit.spec import OrbitSpec


def with_orbit_field(mission: Mission) -> Mission:
    """``mission`` with the worst axial field over its orbit (a mission without an orbit, or one whose
    field is already evaluated, is returned as it is)."""
    if mission.orbit is None or mission.orbit_envelope is not None:
        return mission
    # imported here on purpose: IGRF and SGP4 load only for a mission with an [orbit] table
    from etcheck.orbit.envelope import axial_field_envelope

    started = time.perf_counter()
    env = axial_field_envelope(mission.orbit, source=mission.file)
    env = replace(env, seconds=time.perf_counter() - started)
    worst = env.worst * u.T
    return replace(mission, axial_field=(worst, worst), orbit_envelope=env,
                   notes=(*orbit_notes(mission.orbit, env), *mission.notes))


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
    if past_leap_seconds(spec):
        notes.append("orbit: the window reaches past the leap-second table: UTC - TAI is assumed constant after it "
                     "(a leap second announced later would shift the instants by 1 s: a negligible change of the field)")
    if not env.converged:
        notes.append(f"orbit: the worst axial field changed by {env.step_change:.2g} (relative) at the last halving of "
                     f"the step ({env.step:g} s), above the tolerance {env.tolerance:g}")
    return notes


def past_leap_seconds(spec: OrbitSpec) -> bool:
    """Whether the end of the orbit's window lies past the leap-second table (ERFA's "dubious year")."""
    from etcheck.orbit import frames

    with frames.quiet():
        end = frames.parse_utc(spec.start) + spec.duration * u.s
    return frames.past_leap_second_table(end)


__all__ = ["orbit_notes", "past_leap_seconds", "statement", "with_orbit_field"]
