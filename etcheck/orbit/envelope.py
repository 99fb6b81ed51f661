"""The axial field along an orbit: series, envelope, distribution, worst case.

:func:`axial_field_envelope` is the one entry point for the mission check: it
takes an :class:`~etcheck.orbit.spec.OrbitSpec` (or the ``[orbit]`` table as a
dict), samples the orbit, evaluates the field and the libration worst case and
returns an :class:`AxialFieldEnvelope` whose ``worst`` (T) replaces the
mission's ``axial_field`` in the magnetic load current x axial field.

Sampling. Without a given step, the grid starts at min(60 s, period/64) and
is halved (only the new midpoints are evaluated) until the worst case and the
nominal maximum each change by less than ``tolerance`` (0.1 %) relative; the
step used and the last change are reported. With a given step, the change is
measured against every other sample of the same grid (step x 2), at no cost.

Units: SI (tesla, metres, seconds); latitude and longitude in degrees
(geodetic WGS84), libration angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import astropy.units as u
import numpy as np

from etcheck.errors import MissionError
from etcheck.orbit import frames
from etcheck.orbit.attitude import axial_component, worst_axial
from etcheck.orbit.elements import KeplerianElements, PropagationError, trajectory
from etcheck.orbit.field import CentredDipole, field_along
from etcheck.orbit.spec import MAX_SAMPLES, OrbitSpec

#: Longest starting step (s) of the convergence loop.
INITIAL_STEP = 60.0
#: Relative change of the worst case below which the sampling counts as converged.
TOLERANCE = 1e-3
PERCENTILE_LEVELS = (0.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0, 100.0)


@dataclass(frozen=True)
class AxialFieldSeries:
    """Samples along the orbit.

    time: s since the start. latitude, longitude: deg (geodetic WGS84).
    altitude: m above the WGS84 ellipsoid. b_up, b_along, b_cross: field
    components (T) on the local orbital frame (radial up, along-track,
    orbit normal); b_magnitude: |B| (T). axial_nominal: B . up (T, signed),
    the axial field of a tether on the local vertical. axial_worst: max |B . t|
    over the libration set (T, >= 0), attained at worst_pitch, worst_roll (rad).
    """

    time: np.ndarray
    latitude: np.ndarray
    longitude: np.ndarray
    altitude: np.ndarray
    b_up: np.ndarray
    b_along: np.ndarray
    b_cross: np.ndarray
    b_magnitude: np.ndarray
    axial_nominal: np.ndarray
    axial_worst: np.ndarray
    worst_pitch: np.ndarray
    worst_roll: np.ndarray

    def __len__(self) -> int:
        return int(self.time.size)


@dataclass(frozen=True)
class AxialFieldEnvelope:
    """The envelope of the axial field over the window.

    worst: max over samples of axial_worst (T): the magnetic load's field.
    worst_nominal: max |axial_nominal| (T), the tether on the local vertical.
    worst_time (s since start), worst_utc (ISO 8601), worst_latitude,
    worst_longitude (deg), worst_altitude (m), worst_pitch, worst_roll (rad):
    where and how the worst case occurs. percentile_levels (%) with
    percentiles (T) of axial_worst and percentiles_nominal (T) of |axial_nominal|
    (time-weighted: samples are uniform in time). histogram_counts over
    histogram_edges (T) of axial_worst. step: the sampling step used (s);
    step_change: relative change of the worst case (or of the nominal maximum,
    whichever is larger) from step x 2 to step; converged: step_change <
    tolerance; steps (s) and worst_by_step (T): the convergence history.
    start (UTC ISO), duration (s), model: the window and the field model;
    libration_in_plane, libration_out_of_plane: the bounds (rad). seconds: the
    wall time of the evaluation (set by the check's orbit stage; 0 if not timed).
    """

    series: AxialFieldSeries
    worst: float
    worst_nominal: float
    worst_time: float
    worst_utc: str
    worst_latitude: float
    worst_longitude: float
    worst_altitude: float
    worst_pitch: float
    worst_roll: float
    percentile_levels: np.ndarray
    percentiles: np.ndarray
    percentiles_nominal: np.ndarray
    histogram_counts: np.ndarray
    histogram_edges: np.ndarray
    step: float
    step_change: float
    converged: bool
    tolerance: float
    steps: tuple[float, ...]
    worst_by_step: tuple[float, ...]
    start: str
    duration: float
    model: str
    libration_in_plane: float
    libration_out_of_plane: float
    seconds: float = 0.0


def axial_field_series(spec: OrbitSpec, t, model: str | CentredDipole | None = None, source: str = "mission") -> AxialFieldSeries:
    """The series at ``t`` (s since ``spec.start``) with ``model`` (default
    ``spec.model``; a :class:`CentredDipole` for verification)."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    try:
        traj = trajectory(spec.orbit, spec.start, t)
    except PropagationError as exc:
        raise MissionError(source, "orbit.tle", str(exc), "use a TLE closer to the window, or a shorter duration") from None
    b = field_along(traj, spec.model if model is None else model)
    worst, pitch, roll = worst_axial(b.up, b.along_track, b.cross_track, spec.libration_in_plane, spec.libration_out_of_plane)
    return AxialFieldSeries(
        time=t,
        latitude=traj.latitude,
        longitude=traj.longitude,
        altitude=traj.altitude,
        b_up=b.up,
        b_along=b.along_track,
        b_cross=b.cross_track,
        b_magnitude=b.magnitude,
        axial_nominal=axial_component(b.up, b.along_track, b.cross_track),
        axial_worst=worst,
        worst_pitch=pitch,
        worst_roll=roll,
    )


def _interleave(coarse: AxialFieldSeries, mid: AxialFieldSeries) -> AxialFieldSeries:
    out = {}
    for f in fields(AxialFieldSeries):
        a, b = getattr(coarse, f.name), getattr(mid, f.name)
        c = np.empty(a.size + b.size, dtype=a.dtype)
        c[0::2], c[1::2] = a, b
        out[f.name] = c
    return AxialFieldSeries(**out)


def _maxima(series: AxialFieldSeries, every: int = 1) -> tuple[float, float]:
    return float(np.max(series.axial_worst[::every])), float(np.max(np.abs(series.axial_nominal[::every])))


def _change(fine: tuple[float, float], coarse: tuple[float, float]) -> float:
    return max(abs(f - c) / f if f > 0 else 0.0 for f, c in zip(fine, coarse))


def orbital_period(spec: OrbitSpec) -> float:
    """Anomalistic period (s) of the spec's orbit."""
    if isinstance(spec.orbit, KeplerianElements):
        return spec.orbit.period
    return 2 * math.pi / (spec.orbit.satrec.no_kozai / 60.0)


def axial_field_envelope(
    spec: OrbitSpec,
    *,
    tolerance: float = TOLERANCE,
    model: str | CentredDipole | None = None,
    bins: int = 40,
    source: str = "mission",
) -> AxialFieldEnvelope:
    """Sample the orbit until the worst axial field converges; its envelope.

    ``spec``: the orbit, window and libration (:class:`OrbitSpec`; a mission's ``[orbit]`` table is read into
    one by :func:`etcheck.input.orbit_table.parse_orbit`). ``model`` overrides the field
    model (e.g. a :class:`CentredDipole`). Raises MissionError for orbits that
    cannot be propagated over the window.
    """
    D = spec.duration
    first = spec.step if spec.step is not None else min(INITIAL_STEP, orbital_period(spec) / 64, D)
    n = max(2, math.ceil(D / first - 1e-9) + 1)
    series = axial_field_series(spec, np.linspace(0.0, D, n), model, source)
    steps, history = [D / (n - 1)], [_maxima(series)[0]]
    if spec.step is not None:
        change = _change(_maxima(series), _maxima(series, 2)) if n > 2 else math.inf
    else:
        change = math.inf
        while 2 * len(series) - 1 <= MAX_SAMPLES:
            coarse = _maxima(series)
            t = series.time
            series = _interleave(series, axial_field_series(spec, 0.5 * (t[:-1] + t[1:]), model, source))
            steps.append(steps[-1] / 2)
            history.append(_maxima(series)[0])
            change = _change(_maxima(series), coarse)
            if change < tolerance:
                break

    k = int(np.argmax(series.axial_worst))
    start = frames.parse_utc(spec.start)
    with frames.quiet():  # UTC arithmetic goes through TAI: constant past the leap-second table
        worst_utc = frames.iso(start + series.time[k] * u.s)
    levels = np.array(PERCENTILE_LEVELS)
    counts, edges = np.histogram(series.axial_worst, bins=bins, range=(0.0, float(series.axial_worst[k]) or 1e-9))
    return AxialFieldEnvelope(
        series=series,
        worst=float(series.axial_worst[k]),
        worst_nominal=float(np.max(np.abs(series.axial_nominal))),
        worst_time=float(series.time[k]),
        worst_utc=worst_utc,
        worst_latitude=float(series.latitude[k]),
        worst_longitude=float(series.longitude[k]),
        worst_altitude=float(series.altitude[k]),
        worst_pitch=float(series.worst_pitch[k]),
        worst_roll=float(series.worst_roll[k]),
        percentile_levels=levels,
        percentiles=np.percentile(series.axial_worst, levels),
        percentiles_nominal=np.percentile(np.abs(series.axial_nominal), levels),
        histogram_counts=counts,
        histogram_edges=edges,
        step=steps[-1],
        step_change=float(change),
        converged=bool(change < tolerance),
        tolerance=tolerance,
        steps=tuple(steps),
        worst_by_step=tuple(history),
        start=spec.start,
        duration=D,
        model=(spec.model if model is None else (model if isinstance(model, str) else "centred dipole")),
        libration_in_plane=spec.libration_in_plane,
        libration_out_of_plane=spec.libration_out_of_plane,
    )


__all__ = ["AxialFieldSeries", "AxialFieldEnvelope", "axial_field_series", "axial_field_envelope", "orbital_period"]
