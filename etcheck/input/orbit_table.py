"""The ``[orbit]`` table of a mission file -> :class:`etcheck.orbit.spec.OrbitSpec` (reading only:
nothing is propagated or evaluated here; the field along the orbit is a stage of the check,
:mod:`etcheck.checks.orbit_field`).

Either orbital elements::

    [orbit]
    altitude = "500 km"              # circular; or perigee_altitude + apogee_altitude
    inclination = "51.6 deg"
    raan = "0 deg"                   # optional, default 0
    argument_of_perigee = "0 deg"    # optional, default 0
    mean_anomaly = "0 deg"           # optional, default 0
    epoch = "2027-03-01T00:00:00"    # UTC: epoch of the elements and start of the window
    duration = "1 d"                 # optional, default one day
    step = "30 s"                    # optional, default: halved until the worst case converges
    libration_in_plane = "10 deg"    # optional pitch amplitude, default 0
    libration_out_of_plane = "5 deg" # optional roll amplitude, default 0

or a two-line element set, ``tle = ["1 ...", "2 ..."]`` (``epoch`` then
optional: the start of the window, default the TLE epoch, at most 30 days
from it), with the same duration, step and libration keys. Errors are
:class:`etcheck.errors.MissionError` naming the field (``orbit.FIELD``) and
the fix.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping

import astropy.units as u
from astropy.time import Time

from etcheck.errors import MissionError
from etcheck.input.units import QuantityProblem, to_quantity
from etcheck.orbit import frames
from etcheck.orbit.elements import KeplerianElements, TleError, TwoLineElements
from etcheck.orbit.models import DEFAULT_MODEL, igrf_validity
from etcheck.orbit.spec import (
    DEFAULT_DURATION,
    ELEMENT_KEYS,
    KEYS,
    MAX_DURATION,
    MAX_SAMPLES,
    MAX_TLE_AGE_DAYS,
    MIN_ALTITUDE,
    OrbitSpec,
)

EXAMPLES = {
    "altitude": 'altitude = "500 km"',
    "perigee_altitude": 'perigee_altitude = "400 km"',
    "apogee_altitude": 'apogee_altitude = "800 km"',
    "inclination": 'inclination = "51.6 deg"',
    "raan": 'raan = "30 deg"',
    "argument_of_perigee": 'argument_of_perigee = "90 deg"',
    "mean_anomaly": 'mean_anomaly = "0 deg"',
    "epoch": 'epoch = "2027-03-01T00:00:00" (UTC)',
    "tle": 'tle = ["1 25544U ...", "2 25544 ..."]',
    "duration": 'duration = "1 d"',
    "step": 'step = "30 s" (or leave it out)',
    "libration_in_plane": 'libration_in_plane = "10 deg"',
    "libration_out_of_plane": 'libration_out_of_plane = "5 deg"',
}


def _err(source: str, key: str, problem: str, fix: str = "") -> MissionError:
    return MissionError(source, f"orbit.{key}", problem, fix or f"e.g. {EXAMPLES.get(key, key + ' = ...')}")


def _suggest(word: str) -> str:
    close = difflib.get_close_matches(word, KEYS, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _quantity(table, key, kind, source) -> float:
    try:
        return float(to_quantity(table[key], kind).value)
    except QuantityProblem as exc:
        raise _err(source, key, str(exc)) from None


def _angle(table, key, source) -> float:
    """An angle in radians from a string with units (``"51.6 deg"``, ``"0.9 rad"``)
    or an astropy Quantity (the angle counterpart of ``to_quantity``)."""
    value = table[key]
    fix = f"e.g. {EXAMPLES[key]}"
    if isinstance(value, bool) or isinstance(value, (int, float)):
        raise _err(source, key, f"{value!r} has no unit; expected an angle", fix)
    if isinstance(value, str):
        try:
            q = u.Quantity(value)
        except (TypeError, ValueError):
            raise _err(source, key, f"cannot read {value!r} as an angle", fix) from None
    elif isinstance(value, u.Quantity):
        q = value
    else:
        raise _err(source, key, f"expected an angle, got {type(value).__name__} {value!r}", fix)
    if not q.isscalar:
        raise _err(source, key, f"expected a single value, got an array {value!r}", fix)
    if q.unit == u.dimensionless_unscaled:
        raise _err(source, key, f"{value!r} has no unit; expected an angle", fix)
    try:
        rad = float(q.to_value(u.rad))
    except u.UnitConversionError:
        raise _err(source, key, f"{value!r} is a quantity in {q.unit} ({q.unit.physical_type}), expected an angle", fix) from None
    if not math.isfinite(rad):
        raise _err(source, key, f"{value!r} is not a finite number", fix)
    return rad


def _libration(table, key, source) -> float:
    if key not in table:
        return 0.0
    rad = _angle(table, key, source)
    if not 0.0 <= rad < math.pi / 2:
        raise _err(source, key, f"{table[key]!r} is outside [0, 90) deg", "give the amplitude as a non-negative angle below 90 deg")
    return rad


def _altitude(table, key, source) -> float:
    h = _quantity(table, key, "length", source)
    if h < MIN_ALTITUDE:
        raise _err(
            source, key, f"{table[key]!r} is below {MIN_ALTITUDE / 1e3:.0f} km: the atmosphere would decay the orbit",
            f"give an altitude of at least {MIN_ALTITUDE / 1e3:.0f} km above the equatorial radius",
        )
    return h


def _tle(table, source) -> TwoLineElements:
    value = table["tle"]
    if not isinstance(value, (list, tuple)) or len(value) != 2 or not all(isinstance(x, str) for x in value):
        raise _err(source, "tle", "expected the two lines of a TLE as a list of two strings")
    try:
        tle = TwoLineElements(*value)
    except TleError as exc:
        raise _err(source, "tle", f"malformed two-line element set: {exc}", "copy both lines exactly, 69 characters each") from None
    if tle.perigee_altitude < MIN_ALTITUDE:
        raise _err(
            source, "tle", f"the TLE's perigee is {tle.perigee_altitude / 1e3:.0f} km, below {MIN_ALTITUDE / 1e3:.0f} km",
            "use the TLE of an orbit above the atmosphere",
        )
    return tle


def parse_orbit(table: Mapping, source: str = "mission") -> OrbitSpec:
    """Parse an ``[orbit]`` table (a dict from TOML) into an :class:`OrbitSpec`.

    ``source`` names the file in error messages. Raises
    :class:`etcheck.errors.MissionError` with field ``orbit.KEY``.
    """
    _check_keys(table, source)
    duration, step = _window(table, source)
    start = _epoch(table, source)
    if "tle" in table:
        orbit, start = _tle_and_start(table, start, source)
    else:
        orbit = _elements(table, start, source)
    _check_model_validity(table, start, duration, source)
    return OrbitSpec(
        orbit=orbit,
        start=frames.iso(start),
        duration=duration,
        step=step,
        libration_in_plane=_libration(table, "libration_in_plane", source),
        libration_out_of_plane=_libration(table, "libration_out_of_plane", source),
    )


def _check_keys(table: Mapping, source: str) -> None:
    """A table of known keys, with either a TLE or orbital elements."""
    if not isinstance(table, Mapping):
        raise MissionError(source, "orbit", "must be a table", "write it as [orbit] followed by its fields")
    for key in table:
        if key not in KEYS:
            raise MissionError(source, f"orbit.{key}", "unknown field" + _suggest(str(key)), f"fields of [orbit] are {', '.join(KEYS)}")
    given = [k for k in ELEMENT_KEYS if k in table]
    if "tle" in table and given:
        raise _err(source, given[0], f"both tle and orbital elements ({', '.join(given)}) given",
                   "give either tle or the orbital elements, not both")


def _window(table: Mapping, source: str) -> tuple[float, float | None]:
    """(duration, step) in s; step None: halved until the worst case converges."""
    duration = _quantity(table, "duration", "time", source) if "duration" in table else DEFAULT_DURATION
    if not 0 < duration <= MAX_DURATION:
        raise _err(source, "duration", f"must be > 0 and at most {MAX_DURATION / 86400:.0f} d, got {table['duration']!r}",
                   "a day covers the field's pattern under a LEO orbit; e.g. duration = \"1 d\"")
    if "step" not in table:
        return duration, None
    step = _quantity(table, "step", "time", source)
    if not 0 < step <= duration:
        raise _err(source, "step", f"must be > 0 and at most the duration, got {table['step']!r}")
    if duration / step + 1 > MAX_SAMPLES:
        raise _err(source, "step", f"{table['step']!r} gives more than {MAX_SAMPLES} samples over the duration",
                   "use a longer step or leave it out")
    return duration, step


def _epoch(table: Mapping, source: str) -> Time | None:
    if "epoch" not in table:
        return None
    try:
        return frames.parse_utc(table["epoch"])
    except ValueError as exc:
        raise _err(source, "epoch", str(exc)) from None


def _tle_and_start(table: Mapping, start: Time | None, source: str) -> tuple[TwoLineElements, Time]:
    """The TLE and the start of the window: its epoch unless given, at most MAX_TLE_AGE_DAYS from it."""
    orbit = _tle(table, source)
    if start is None:
        return orbit, frames.parse_utc(orbit.epoch)
    days = float(abs((start - frames.parse_utc(orbit.epoch)).to_value(u.d)))
    if days > MAX_TLE_AGE_DAYS:
        raise _err(source, "epoch", f"the window starts {days:.0f} days from the TLE epoch {orbit.epoch[:10]}; "
                   f"SGP4 errors grow by km per day", f"use a TLE within {MAX_TLE_AGE_DAYS:.0f} days of the window, or leave epoch out")
    return orbit, start


def _elements(table: Mapping, start: Time | None, source: str) -> KeplerianElements:
    """Keplerian elements at ``start`` (the epoch, required); angles in rad, altitudes in m."""
    if "inclination" not in table:
        raise _err(source, "inclination", "missing", f"add it under [orbit]: {EXAMPLES['inclination']}")
    if start is None:
        raise _err(source, "epoch", "missing", f"add it under [orbit]: {EXAMPLES['epoch']}")
    hp, ha = _perigee_apogee(table, source)
    inc = _angle(table, "inclination", source)
    if not 0.0 <= inc <= math.pi * (1 + 1e-15):
        raise _err(source, "inclination", f"{table['inclination']!r} is outside 0-180 deg",
                   "give the inclination between 0 and 180 deg (retrograde above 90)")
    angles = {k: _angle(table, k, source) % (2 * math.pi) for k in ("raan", "argument_of_perigee", "mean_anomaly") if k in table}
    return KeplerianElements(hp, ha, min(inc, math.pi), epoch=frames.iso(start), **angles)


def _perigee_apogee(table: Mapping, source: str) -> tuple[float, float]:
    """(perigee, apogee) altitudes in m: one circular ``altitude`` or both ``perigee_altitude`` and ``apogee_altitude``."""
    has_circ = "altitude" in table
    has_ell = [k for k in ("perigee_altitude", "apogee_altitude") if k in table]
    if has_circ and has_ell:
        raise _err(source, has_ell[0], "both altitude (circular) and perigee/apogee altitudes given",
                   "give either altitude or perigee_altitude and apogee_altitude")
    if has_circ:
        h = _altitude(table, "altitude", source)
        return h, h
    if not has_ell:
        raise _err(source, "altitude", "missing", f"add {EXAMPLES['altitude']} (circular) or perigee_altitude and apogee_altitude")
    if len(has_ell) == 1:
        other = ({"perigee_altitude", "apogee_altitude"} - set(has_ell)).pop()
        raise _err(source, other, "missing", f"give both perigee_altitude and apogee_altitude: {EXAMPLES[other]}")
    hp = _altitude(table, "perigee_altitude", source)
    ha = _quantity(table, "apogee_altitude", "length", source)
    if ha < hp:
        raise _err(source, "apogee_altitude", f"{table['apogee_altitude']!r} is below the perigee altitude {table['perigee_altitude']!r}",
                   "the apogee altitude must be at least the perigee altitude (swap them?)")
    return hp, ha


def _check_model_validity(table: Mapping, start: Time, duration: float, source: str) -> None:
    """The window [start, start + duration s] lies within the field model's validity."""
    lo, hi = igrf_validity(DEFAULT_MODEL)
    with frames.quiet():
        outside = bool(start < lo) or frames.ends_after(start, duration, hi)
    if outside:
        key = "epoch" if "epoch" in table else "tle"
        raise _err(source, key,
                   f"the window {frames.iso(start)} + {duration:g} s is outside {DEFAULT_MODEL}'s validity "
                   f"({frames.iso(lo)[:10]} to {frames.iso(hi)[:10]})",
                   "give an epoch (and duration) within the model's validity")


__all__ = ["parse_orbit"]
