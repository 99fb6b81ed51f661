"""Orbit axes of a sweep: the worst axial field of every (altitude, inclination).

``etcheck sweep --altitude 300km:1500km:20 --inclination 0deg:98deg:20``
maps the margins over orbits: every grid point takes the mission's ``[orbit]``
table (epoch, window, libration, RAAN, ...) with its circular altitude and/or
inclination replaced, evaluates the envelope of the axial field
(:func:`etcheck.orbit.envelope.axial_field_envelope`) and uses its worst case
as the point's axial field (the current as in the mission). Each distinct
orbit is evaluated once (a 20 x 20 altitude x inclination grid is 400
envelopes; with length or spin as the other axis one envelope serves a whole
row), on the sweep's workers and kept in the sweep's cache folder.

Sampling: unless the mission's ``[orbit]`` fixes a step, sweeps sample every
:data:`SWEEP_STEP` = 60 s (no halving). Measured over a day at 10 deg / 5 deg
libration on 20 orbits (300-1500 km x 0-98 deg, epoch 2027-03-01): the worst
field at 60 s is below the converged one (halved to < 0.1 % change) by at most
0.085 % (so the margin is at most 0.085 % optimistic), in a fraction of the
time of the halving; 120 s would be 0.30 %. A single check
(``etcheck check``) always converges its one orbit.

Units: SI at this level (m, rad, T); display in km, deg, µT.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import replace
from typing import Any

from etcheck import __version__
from etcheck.errors import MissionError
from etcheck.input.mission import Mission
from etcheck.input.sweep_axes import Axis

ORBIT_AXES = ("altitude", "inclination")
#: Sampling step (s) of the envelopes of a sweep (see the module docstring for its measured error).
SWEEP_STEP = 60.0
#: Measured largest relative underestimate of the worst field at SWEEP_STEP (20 LEO orbits, 1 day).
SWEEP_STEP_ERROR = 8.5e-4


def _spec_for(base, altitude: float | None, inclination: float | None):
    """The mission's OrbitSpec with a circular altitude (m) and/or inclination (rad) replaced."""
    o = base.orbit
    changes: dict[str, float] = {}
    if altitude is not None:
        changes |= {"perigee_altitude": altitude, "apogee_altitude": altitude}
    if inclination is not None:
        changes["inclination"] = inclination
    return replace(base, orbit=replace(o, **changes), step=base.step if base.step is not None else SWEEP_STEP)


def _envelope_chunk(items: list[tuple[str, Any]]) -> list[tuple[str, dict]]:
    """Worker entry: (key, OrbitSpec) -> (key, worst field and where), JSON-able."""
    import time

    from etcheck.orbit.envelope import axial_field_envelope

    out = []
    for key, spec in items:
        t0 = time.perf_counter()
        env = axial_field_envelope(spec)
        out.append((key, {"axial_field_T": env.worst, "latitude_deg": env.worst_latitude,
                          "longitude_deg": env.worst_longitude, "utc": env.worst_utc, "step_s": env.step,
                          "step_change": env.step_change, "time_s": time.perf_counter() - t0}))
    return out


class OrbitFields:
    """The worst axial field (T) of each orbit of a sweep, evaluated once per (altitude, inclination)."""

    def __init__(self, mission: Mission, axes: tuple[Axis, ...], options, cache, run) -> None:
        from etcheck.orbit.elements import KeplerianElements

        names = [a.name for a in axes]
        if mission.orbit is None:
            raise MissionError(mission.provenance.file, "orbit", "altitude and inclination axes need the mission's [orbit] table",
                               "add an [orbit] table (epoch, and optionally duration and libration) to the mission")
        if not isinstance(mission.orbit.orbit, KeplerianElements):
            raise MissionError(mission.provenance.file, "orbit.tle", "altitude and inclination axes need orbital elements, not a TLE",
                               "give the orbit as altitude, inclination and epoch to sweep it")
        if "axial_field" in names:
            raise MissionError("command line", "--field", "the axial field follows from the orbit axes",
                               "sweep either the field or the orbit (altitude, inclination)")
        self.mission, self.axes = mission, axes
        o = mission.orbit.orbit
        self.operating = {"altitude": o.perigee_altitude, "inclination": o.inclination}
        grids = {a.name: a.values for a in axes if a.name in ORBIT_AXES}
        alts = grids.get("altitude", [None])
        incs = grids.get("inclination", [None])
        self.specs = {(h, i): _spec_for(mission.orbit, None if h is None else float(h), None if i is None else float(i))
                      for h in alts for i in incs}
        self.fields: dict[tuple, dict] = {}
        keys = {k: hashlib.sha256(json.dumps(["orbit-envelope", repr(spec), __version__]).encode()).hexdigest()
                for k, spec in self.specs.items()}
        by_key = {v: k for k, v in keys.items()}
        todo = []
        for k, key in keys.items():
            hit = cache.get(key)
            if hit is not None:
                self.fields[k] = hit
            else:
                todo.append((key, self.specs[k]))
        self.from_cache = len(self.fields)

        def arrived(key: str, r: dict) -> None:
            cache.put(key, r)
            self.fields[by_key[key]] = r

        run(_envelope_chunk, [todo[i:i + 4] for i in range(0, len(todo), 4)], options, arrived)

    def field(self, values: dict[str, float]) -> float:
        """Worst axial field (T) of the orbit of a grid point (``values``: axis name -> SI value)."""
        return self.fields[(values.get("altitude"), values.get("inclination"))]["axial_field_T"]

    def as_dict(self) -> dict[str, Any]:
        """JSON-able: the envelope of every orbit (km, deg, µT) and how it was sampled."""
        spec = self.mission.orbit
        rows = [{"altitude_km": None if h is None else h / 1e3,
                 "inclination_deg": None if i is None else math.degrees(i),
                 "axial_field_uT": r["axial_field_T"] * 1e6, "latitude_deg": r["latitude_deg"],
                 "longitude_deg": r["longitude_deg"], "utc": r["utc"], "step_s": r["step_s"],
                 "step_change": r["step_change"]}
                for (h, i), r in sorted(self.fields.items(), key=lambda kv: tuple(-1 if v is None else v for v in kv[0]))]
        step = spec.step if spec.step is not None else SWEEP_STEP
        return {
            "orbits": len(rows),
            "from_cache": self.from_cache,
            "model": "IGRF-14",
            "start": spec.start,
            "duration_s": spec.duration,
            "step_s": step,
            "sampling_note": (f"every orbit sampled at a fixed {step:g} s (the mission's step)" if spec.step is not None else
                              f"every orbit sampled at a fixed {SWEEP_STEP:g} s (no halving): on 20 orbits (300-1500 km, 0-98 deg, "
                              f"one day) it underestimated the worst field by at most {SWEEP_STEP_ERROR * 100:.3g} % against "
                              "the converged sampling of a single check"),
            "libration_in_plane_deg": math.degrees(spec.libration_in_plane),
            "libration_out_of_plane_deg": math.degrees(spec.libration_out_of_plane),
            "envelopes": rows,
            "cpu_s": sum(r.get("time_s", 0.0) for r in self.fields.values()),
        }


def orbit_fields(mission: Mission, axes: tuple[Axis, ...], options, cache, run) -> OrbitFields | None:
    """The orbit fields of a sweep with altitude or inclination axes (None without them).

    ``options`` and ``cache`` are the sweep's (SweepOptions, Cache); ``run(fn, chunks, options, on_result)``
    is the sweep's executor (serial, local processes or dask).
    """
    if not any(a.name in ORBIT_AXES for a in axes):
        return None
    return OrbitFields(mission, axes, options, cache, run)


__all__ = ["ORBIT_AXES", "SWEEP_STEP", "OrbitFields", "orbit_fields"]
