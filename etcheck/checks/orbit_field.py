"""The check's orbit stage: the operating point of a mission, with the field over its ``[orbit]``.

A mission read from a file holds its orbit as a specification only
(:class:`etcheck.orbit.spec.OrbitSpec`); :func:`resolve` evaluates the envelope of the
axial field over the window once (:func:`etcheck.orbit.envelope.axial_field_envelope`,
IGRF through ppigrf, SGP4) and returns the :class:`Resolved` operating point: the scene
with the worst axial field (T) and the largest field across the tether over the orbit,
and the mission with that field echoed and the statement of where it occurs in its
notes: the check's magnetic load is then the worst |current| times this field. The
pipeline is input -> orbit -> scaling -> rungs; a mission with ``[operation] axial_field``
is resolved by :func:`etcheck.scaling.scene` alone. The envelope carries the seconds it
took (``AxialFieldEnvelope.seconds``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import astropy.units as u

from etcheck.input.mission import Mission
from etcheck.scaling import MagneticField, Scene, scene

if TYPE_CHECKING:
    from etcheck.orbit.envelope import AxialFieldEnvelope
    from etcheck.orbit.spec import OrbitSpec


@dataclass(frozen=True)
class Resolved:
    """A mission's operating point, the orbit stage's answer: ``mission`` as read (with an [orbit] table: its
    axial field echoed as the worst over the orbit, and the statements of the orbit's field first in its notes),
    ``scene`` its worst case in SI and ``envelope`` the field over the orbit (None without an [orbit] table)."""

    mission: Mission
    scene: Scene
    envelope: AxialFieldEnvelope | None = None


def resolve(mission: Mission) -> Resolved:
    """The operating point of ``mission``: its field evaluated over its orbit where it has an [orbit] table."""
    if mission.orbit is None:
        return Resolved(mission, scene(mission))
    # imported here on purpose: IGRF and SGP4 load only for a mission with an [orbit] table
    import numpy as np

    from etcheck.orbit.envelope import axial_field_envelope

    started = time.perf_counter()
    env = axial_field_envelope(mission.orbit, source=mission.provenance.file)
    env = replace(env, seconds=time.perf_counter() - started)
    worst = env.worst * u.T
    s = env.series  # across a tether on the local vertical: sqrt(|B|^2 - (B.up)^2), its largest over the window
    across = float(np.max(np.sqrt(np.maximum(s.b_magnitude**2 - s.axial_nominal**2, 0.0))))
    resolved = mission.with_operation(axial_field=(worst, worst)).with_provenance(
        notes=(*orbit_notes(mission.orbit, env), *mission.provenance.notes))
    return Resolved(resolved, scene(resolved, MagneticField(float(env.worst), across)), env)


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


__all__ = ["Resolved", "orbit_notes", "past_leap_seconds", "resolve", "statement"]
