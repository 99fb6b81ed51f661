"""Orbit descriptions and their propagation to Earth-fixed positions.

Two descriptions:

* :class:`KeplerianElements`: perigee and apogee altitudes (equal for a
  circular orbit), inclination, right ascension of the ascending node (RAAN),
  argument of perigee and mean anomaly at a UTC epoch, in GCRS (or TEME for
  elements read from a TLE). Propagated two-body with the secular drift of
  RAAN, argument of perigee and mean anomaly due to J2 (first order, mean
  elements; Vallado, "Fundamentals of Astrodynamics", Sec. 9.6)::

      p = a (1 - e^2),   k = (3/2) J2 (R_E/p)^2 n
      dRAAN/dt = -k cos i
      dargp/dt =  (k/2) (5 cos^2 i - 1)
      dM/dt    =  n + (k/2) sqrt(1 - e^2) (3 cos^2 i - 1)

  Short-period J2 terms (about 10 km in position in LEO), drag and the other
  harmonics are left out: they move the sample points, not the field model,
  and the envelope is a maximum over a day of samples.
* :class:`TwoLineElements`: a TLE propagated by SGP4 (the ``sgp4`` package,
  WGS72 constants as the TLE format requires), output in TEME.

Altitudes of the Keplerian description are above the equatorial radius
R_E = 6378.137 km (r = R_E + altitude); the geodetic altitude along the orbit
(reported in the series) differs by up to 21 km at high latitude.

Units: metres, seconds, radians (SI) unless named ``_deg``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from astropy.time import Time

from etcheck.orbit import frames

if TYPE_CHECKING:  # SGP4 loads where a TLE is read or propagated: orbital elements need none of it
    from sgp4.api import Satrec

#: Earth's gravitational parameter (m^3/s^2, IERS 2010 / EGM2008).
MU_EARTH = 3.986004418e14
#: Earth's equatorial radius (m, WGS84), reference of the altitudes and of J2.
R_EARTH = 6378137.0
#: Second zonal harmonic (EGM2008, unnormalised).
J2 = 1.08262668e-3


@dataclass(frozen=True)
class KeplerianElements:
    """Mean orbital elements at ``epoch``.

    perigee_altitude, apogee_altitude: m above R_E (equal: circular orbit).
    inclination, raan, argument_of_perigee, mean_anomaly: rad.
    epoch: UTC instant, ISO 8601 text (``2027-03-01T00:00:00``).
    frame: ``"GCRS"`` (default) or ``"TEME"`` (elements taken from a TLE).
    """

    perigee_altitude: float
    apogee_altitude: float
    inclination: float
    raan: float = 0.0
    argument_of_perigee: float = 0.0
    mean_anomaly: float = 0.0
    epoch: str = "2027-03-01T00:00:00"
    frame: str = "GCRS"

    def __post_init__(self):
        if self.frame not in ("GCRS", "TEME"):
            raise ValueError(f"frame must be 'GCRS' or 'TEME', got {self.frame!r}")
        if not self.apogee_altitude >= self.perigee_altitude > -R_EARTH:
            raise ValueError("need -R_E < perigee_altitude <= apogee_altitude")

    @classmethod
    def circular(cls, altitude: float, inclination: float, **kw) -> KeplerianElements:
        """A circular orbit at ``altitude`` (m); the argument of perigee is then the
        argument of latitude at epoch together with ``mean_anomaly``."""
        return cls(altitude, altitude, inclination, **kw)

    @classmethod
    def from_tle(cls, tle: TwoLineElements) -> KeplerianElements:
        """The TLE's mean elements (TEME, Kozai mean motion) as a Keplerian description."""
        s = tle.satrec
        n = s.no_kozai / 60.0  # rad/min -> rad/s
        a = (MU_EARTH / n**2) ** (1.0 / 3.0)
        return cls(
            perigee_altitude=a * (1 - s.ecco) - R_EARTH,
            apogee_altitude=a * (1 + s.ecco) - R_EARTH,
            inclination=s.inclo,
            raan=s.nodeo,
            argument_of_perigee=s.argpo,
            mean_anomaly=s.mo,
            epoch=tle.epoch,
            frame="TEME",
        )

    @property
    def semi_major_axis(self) -> float:
        """m."""
        return R_EARTH + 0.5 * (self.perigee_altitude + self.apogee_altitude)

    @property
    def eccentricity(self) -> float:
        rp, ra = R_EARTH + self.perigee_altitude, R_EARTH + self.apogee_altitude
        return (ra - rp) / (ra + rp)

    @property
    def mean_motion(self) -> float:
        """Two-body mean motion n = sqrt(mu / a^3), rad/s."""
        return math.sqrt(MU_EARTH / self.semi_major_axis**3)

    @property
    def period(self) -> float:
        """Anomalistic period 2 pi / (dM/dt), s."""
        return 2 * math.pi / self.secular_rates[2]

    @property
    def secular_rates(self) -> tuple[float, float, float]:
        """J2 secular rates (dRAAN/dt, dargp/dt, dM/dt) in rad/s."""
        a, e, i, n = self.semi_major_axis, self.eccentricity, self.inclination, self.mean_motion
        p = a * (1 - e * e)
        k = 1.5 * J2 * (R_EARTH / p) ** 2 * n
        c2 = math.cos(i) ** 2
        return -k * math.cos(i), 0.5 * k * (5 * c2 - 1), n + 0.5 * k * math.sqrt(1 - e * e) * (3 * c2 - 1)


def solve_kepler(mean_anomaly: np.ndarray, e: float) -> np.ndarray:
    """Eccentric anomaly E with E - e sin E = M (vectorised Newton, to 1e-14 rad)."""
    M = np.remainder(mean_anomaly, 2 * np.pi)
    E = np.where(e < 0.8, M, np.pi)
    for _ in range(50):
        dE = (E - e * np.sin(E) - M) / (1 - e * np.cos(E))
        E = E - dE
        if np.max(np.abs(dE), initial=0.0) < 1e-14:
            break
    return E


def kepler_state(elements: KeplerianElements, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position (m) and velocity (m/s), shape (n, 3), in the elements' inertial
    frame at ``t`` seconds after the epoch (two-body + J2 secular drift)."""
    t = np.asarray(t, dtype=float)
    a, e = elements.semi_major_axis, elements.eccentricity
    raan_dot, argp_dot, m_dot = elements.secular_rates
    raan = elements.raan + raan_dot * t
    argp = elements.argument_of_perigee + argp_dot * t
    E = solve_kepler(elements.mean_anomaly + m_dot * t, e)
    cE, sE = np.cos(E), np.sin(E)
    b = math.sqrt(1 - e * e)
    xp, yp = a * (cE - e), a * b * sE
    r = a * (1 - e * cE)
    vfac = math.sqrt(MU_EARTH * a) / r
    vxp, vyp = -vfac * sE, vfac * b * cE
    cO, sO = np.cos(raan), np.sin(raan)
    cw, sw = np.cos(argp), np.sin(argp)
    ci, si = math.cos(elements.inclination), math.sin(elements.inclination)
    P = np.stack([cO * cw - sO * sw * ci, sO * cw + cO * sw * ci, sw * si], axis=-1)
    Q = np.stack([-cO * sw - sO * cw * ci, -sO * sw + cO * cw * ci, cw * si], axis=-1)
    pos = xp[:, None] * P + yp[:, None] * Q
    vel = vxp[:, None] * P + vyp[:, None] * Q
    return pos, vel


class TleError(ValueError):
    """A two-line element set that cannot be used (format, checksum, SGP4)."""


def tle_checksum(line: str) -> int:
    """Modulo-10 checksum of the first 68 characters (digits count, '-' counts 1)."""
    return sum(int(c) if c.isdigit() else (1 if c == "-" else 0) for c in line[:68]) % 10


@dataclass(frozen=True)
class TwoLineElements:
    """A two-line element set (TEME, SGP4). Checked on construction: line
    lengths, line numbers, checksums, matching satellite numbers, SGP4 init."""

    line1: str
    line2: str

    def __post_init__(self):
        for k, line in ((1, self.line1), (2, self.line2)):
            if not isinstance(line, str):
                raise TleError(f"line {k} is not text")
            line = line.rstrip()
            if len(line) != 69:
                raise TleError(f"line {k} has {len(line)} characters, a TLE line has 69")
            if not line.startswith(f"{k} "):
                raise TleError(f"line {k} must start with '{k} '")
            if not line[68].isdigit() or tle_checksum(line) != int(line[68]):
                raise TleError(f"line {k} fails its checksum (last digit {line[68]!r}, computed {tle_checksum(line)})")
        if self.line1[2:7] != self.line2[2:7]:
            raise TleError(f"satellite numbers differ ({self.line1[2:7]!r} and {self.line2[2:7]!r})")
        from sgp4.api import SGP4_ERRORS

        try:
            sat = self.satrec
        except Exception as exc:  # sgp4 raises ValueError or IndexError on bad fields
            raise TleError(f"SGP4 cannot read it ({exc})") from None
        if sat.error:
            raise TleError(f"SGP4 rejects it: {SGP4_ERRORS.get(sat.error, sat.error)}")

    @cached_property
    def satrec(self) -> Satrec:
        from sgp4.api import WGS72, Satrec

        return Satrec.twoline2rv(self.line1.rstrip(), self.line2.rstrip(), WGS72)

    @property
    def epoch(self) -> str:
        """The TLE epoch, ISO 8601 UTC."""
        s = self.satrec
        return frames.iso(Time(s.jdsatepoch, s.jdsatepochF, format="jd", scale="utc"))

    @property
    def perigee_altitude(self) -> float:
        """m above SGP4's equatorial radius (6378.135 km, WGS72)."""
        return float(self.satrec.altp * self.satrec.radiusearthkm * 1e3)


class PropagationError(RuntimeError):
    """SGP4 could not propagate over the requested window."""


def tle_state(tle: TwoLineElements, start: Time, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """SGP4 position (m) and velocity (m/s) in TEME, shape (n, 3), at ``start + t``."""
    from sgp4.api import SGP4_ERRORS

    jd1, jd2 = frames.utc_jd(start, t)
    err, r, v = tle.satrec.sgp4_array(jd1, jd2)
    if np.any(err):
        k = int(np.argmax(err != 0))
        raise PropagationError(
            f"SGP4 stops at {float(np.asarray(t)[k]):.0f} s after the start: {SGP4_ERRORS.get(int(err[k]), err[k])}"
        )
    return r * 1e3, v * 1e3


@dataclass(frozen=True)
class Trajectory:
    """Samples of an orbit in the Earth-fixed frame (ITRS).

    time: s since ``start`` (UTC, ISO 8601). position: (n, 3) m, ITRS.
    radial, along_track, cross_track: (n, 3) unit vectors in ITRS of the local
    orbital frame: radial = r/|r| (up), cross_track = orbit normal r x v/|r x v|
    (v inertial), along_track = cross_track x radial (the direction of motion
    for a circular orbit). latitude, longitude: geodetic WGS84, deg;
    altitude: m above the WGS84 ellipsoid.
    """

    start: str
    time: np.ndarray
    position: np.ndarray
    radial: np.ndarray
    along_track: np.ndarray
    cross_track: np.ndarray
    latitude: np.ndarray
    longitude: np.ndarray
    altitude: np.ndarray


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def trajectory(orbit: KeplerianElements | TwoLineElements, start, t) -> Trajectory:
    """Propagate ``orbit`` to ``start + t`` (t in s; start a UTC instant) and
    rotate to ITRS. For Keplerian elements ``start`` may differ from their epoch."""
    start = frames.parse_utc(start)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    if isinstance(orbit, TwoLineElements):
        pos, vel = tle_state(orbit, start, t)
        rot = frames.teme_to_itrs(start, t)
    else:
        with frames.quiet():  # past the leap-second table UTC - TAI is taken as constant (frames.quiet)
            since = float((start - frames.parse_utc(orbit.epoch)).to_value("s"))
        pos, vel = kepler_state(orbit, t + since)
        rot = frames.gcrs_to_itrs(start, t) if orbit.frame == "GCRS" else frames.teme_to_itrs(start, t)
    radial = _unit(pos)
    normal = _unit(np.cross(pos, vel))
    along = np.cross(normal, radial)
    pos_f = frames.rotate(rot, pos)
    lat, lon, alt = frames.geodetic(pos_f)
    return Trajectory(
        start=frames.iso(start),
        time=t,
        position=pos_f,
        radial=frames.rotate(rot, radial),
        along_track=frames.rotate(rot, along),
        cross_track=frames.rotate(rot, normal),
        latitude=lat,
        longitude=lon,
        altitude=alt,
    )
