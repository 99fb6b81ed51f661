"""The load margin along the orbit: where on the orbit the margin is smallest.

The critical load of the straight tether (N/m, at the operating spin and
tension) does not depend on the field, so the margin at time t is

    margin(t) = critical I·B0 / (|I|_worst · B_axial,worst(t))

with B_axial,worst(t) the worst axial field over the libration set at that
sample (T). Its minimum over the window is the check's load margin (the check
uses the envelope's worst field), attained where the field is largest.

``orbit_results`` returns the ``orbit`` section of the results:
the envelope summary, the convergence of the sampling, the series over the
first orbit at full resolution and over the whole window downsampled to at
most :data:`MAX_SERIES` points (every k-th sample plus the worst one; the
stride is stated). Units: SI (T, s, m, N/m); latitude, longitude and angles in
degrees (named ``_deg``).
"""

from __future__ import annotations

import math

import numpy as np

from etcheck.checks.margins.margin import Margin
from etcheck.checks.orbit_field import Resolved, statement
from etcheck.checks.results.sections import (
    OrbitHistogram,
    OrbitMargin,
    OrbitPercentiles,
    OrbitSampling,
    OrbitSection,
    OrbitSeries,
    OrbitWorst,
)
from etcheck.jsonable import finite_or_none

#: Most samples of the whole-window series written to results.json.
MAX_SERIES = 3000


def load_margin(margins: list[Margin]) -> Margin | None:
    """The straight tether's load margin (N/m) with a critical value, if the check answered one."""
    return next((m for m in margins if m.unit == "N/m" and m.name.startswith("magnetic load") and m.critical is not None), None)


def _finite(a) -> tuple[float | None, ...]:
    """The samples ``a`` with None where not finite."""
    return tuple(finite_or_none(a))


def _series(s, idx: np.ndarray, current: float, critical: float | None) -> OrbitSeries:
    load = current * s.axial_worst[idx]  # N/m
    with np.errstate(divide="ignore"):
        margin = critical / load if critical is not None else None
    return OrbitSeries(
        time_s=_finite(s.time[idx]),
        latitude_deg=_finite(s.latitude[idx]),
        longitude_deg=_finite(s.longitude[idx]),
        altitude_m=_finite(s.altitude[idx]),
        b_up_T=_finite(s.b_up[idx]),
        b_along_T=_finite(s.b_along[idx]),
        b_cross_T=_finite(s.b_cross[idx]),
        axial_nominal_T=_finite(s.axial_nominal[idx]),
        axial_worst_T=_finite(s.axial_worst[idx]),
        load_N_per_m=_finite(load),
        load_margin=None if margin is None else _finite(margin),
    )


def orbit_results(resolved: Resolved, margins: list[Margin]) -> OrbitSection | None:
    """The field and the load margin along the mission's orbit (None without an [orbit] table) at the scene's
    worst current."""
    env = resolved.envelope
    if env is None:
        return None
    from etcheck.orbit.envelope import orbital_period

    s = env.series
    n = len(s)
    current = resolved.scene.current
    m = load_margin(margins)
    critical = m.critical if m is not None else None
    period = orbital_period(resolved.mission.orbit)
    first = np.flatnonzero(s.time <= period * (1 + 1e-9))
    stride = max(1, math.ceil(n / (MAX_SERIES - 1)))
    k = int(np.argmax(s.axial_worst))
    whole = np.union1d(np.arange(0, n, stride), [k, n - 1])
    worst_load = current * env.worst
    return OrbitSection(
        model=env.model,
        start=env.start,
        duration_s=env.duration,
        period_s=period,
        libration_in_plane_deg=math.degrees(env.libration_in_plane),
        libration_out_of_plane_deg=math.degrees(env.libration_out_of_plane),
        sampling=OrbitSampling(step_s=env.step, step_change=env.step_change, converged=env.converged,
                               tolerance=env.tolerance, steps_s=tuple(env.steps),
                               worst_by_step_T=tuple(env.worst_by_step), samples=n),
        worst=OrbitWorst(axial_field_T=env.worst, time_s=env.worst_time, utc=env.worst_utc,
                         latitude_deg=env.worst_latitude, longitude_deg=env.worst_longitude,
                         altitude_m=env.worst_altitude, pitch_deg=math.degrees(env.worst_pitch),
                         roll_deg=math.degrees(env.worst_roll)),
        worst_nominal_T=env.worst_nominal,
        percentiles=OrbitPercentiles(levels=tuple(env.percentile_levels.tolist()),
                                     axial_worst_T=tuple(env.percentiles.tolist()),
                                     axial_nominal_T=tuple(env.percentiles_nominal.tolist())),
        histogram=OrbitHistogram(counts=tuple(env.histogram_counts.tolist()),
                                 edges_T=tuple(env.histogram_edges.tolist())),
        worst_current_A=current,
        worst_load_N_per_m=worst_load,
        margin=None if m is None else OrbitMargin(name=m.name, critical_N_per_m=critical,
                                                  smallest=critical / worst_load if worst_load > 0 else None,
                                                  required=m.required),
        statement=statement(env),
        envelope_s=env.seconds,
        first_orbit=_series(s, first, current, critical),
        series=_series(s, whole, current, critical),
        series_note=(f"all {n} samples" if stride == 1 else
                     f"every {stride}th of the {n} samples ({stride * env.step:g} s apart) plus the worst one: "
                     f"{whole.size} points (the first orbit is at full resolution)"),
    )


__all__ = ["MAX_SERIES", "load_margin", "orbit_results"]
