"""Time scales and the rotation of inertial positions to the Earth-fixed frame.

Two inertial frames are handled:

* GCRS (the geocentric celestial frame, aligned with ICRF: what engineers call
  J2000/EME2000 to within 23 mas) for Keplerian elements. GCRS -> ITRS is
  ``R3(ERA) @ C2I`` with the IAU 2006/2000A celestial-to-intermediate matrix
  (``erfa.c2i06a``) and the Earth rotation angle (``erfa.era00``): the
  CIO-based chain astropy's GCRS -> ITRS uses, evaluated here with
  UT1 = UTC and no polar motion. C2I is evaluated once per half day (the
  nearest node): precession-nutation moves < 0.1 arcsec in that time.
* TEME (the frame of SGP4 output) -> ITRS is ``R3(GMST82)`` with UT1 = UTC and
  no polar motion (Vallado et al. 2006, "Revisiting Spacetrack Report #3").

Errors of these approximations: |UT1 - UTC| < 0.9 s is < 0.0038 deg of Earth
rotation (< 0.5 km along the ground at 500 km altitude), polar motion
< 0.5 arcsec (< 20 m). Measured against astropy's GCRS -> ITRS (with its IERS
table extrapolated, since future epochs have no IERS data offline) at 500 km
for 2027: 89 m, in milliseconds per 10^4 samples where astropy takes seconds. A rotation by
GMST alone (no precession-nutation) would be 46 km off in 2027 (0.37 deg of
precession since J2000), so it is not used. The magnetic field changes by
< 0.01 % over 100 m in LEO.

Units: times in seconds since a UTC start instant, Julian dates as two-part
(jd1, jd2) arrays, positions in metres, angles in radians unless named ``_deg``.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import warnings

import erfa
import numpy as np
from astropy.time import Time

_DAY = 86400.0
#: Spacing of the nodes at which the precession-nutation matrix is evaluated.
C2I_NODE_SPACING = 43200.0


@contextlib.contextmanager
def quiet():
    """Silence erfa's "dubious year" for instants past its leap-second table
    (the IGRF runs to 2030; a leap second announced later shifts UTC by 1 s)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", erfa.ErfaWarning)
        yield


def past_leap_second_table(t: Time) -> bool:
    """Whether the UTC instant ``t`` lies past the years ERFA's leap-second table vouches for (its "dubious
    year"): UTC - TAI is then taken as it is at the table's end, as astropy and ERFA do."""
    t = t.utc
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", erfa.ErfaWarning)
        erfa.dat(*erfa.jd2cal(t.jd1, t.jd2))
    return any(issubclass(w.category, erfa.ErfaWarning) for w in caught)


def parse_utc(value) -> Time:
    """A UTC instant from an ISO 8601 string, ``datetime`` or ``date`` (naive = UTC).

    Raises ``ValueError`` with a readable message.
    """
    if isinstance(value, Time):
        return value.utc
    if isinstance(value, _dt.datetime):
        if value.tzinfo is not None:
            value = value.astimezone(_dt.UTC).replace(tzinfo=None)
        with quiet():
            return Time(value, scale="utc")
    if isinstance(value, _dt.date):
        return parse_utc(_dt.datetime(value.year, value.month, value.day))
    if not isinstance(value, str):
        raise ValueError(f"expected a UTC date and time such as \"2027-03-01T00:00:00\", got {value!r}")
    text = value.strip()
    try:
        parsed = _dt.datetime.fromisoformat(text)
    except ValueError:
        parsed = None
    if parsed is not None:
        return parse_utc(parsed)
    try:  # e.g. a leap second 23:59:60, which datetime cannot hold
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return Time(text.rstrip("Z"), scale="utc")
    except ValueError:
        raise ValueError(
            f"cannot read {value!r} as a UTC date and time; expected ISO 8601 such as \"2027-03-01T00:00:00\""
        ) from None


def iso(t: Time) -> str:
    """ISO 8601 UTC text with milliseconds (``2027-03-01T00:00:00.000``)."""
    with quiet():
        return t.utc.isot


def utc_jd(start: Time, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two-part UTC Julian dates of ``start + t`` (t in seconds; a leap second
    inside the window shifts UTC by 1 s, ignored)."""
    start = start.utc
    jd1 = np.full(np.shape(t), float(start.jd1))
    jd2 = float(start.jd2) + np.asarray(t, dtype=float) / _DAY
    return jd1, jd2


def ends_after(start: Time, seconds: float, t: Time) -> bool:
    """Whether ``start + seconds`` lies after the UTC instant ``t``, on UTC Julian dates (as :func:`utc_jd`: a
    leap second inside the window ignored): no time-scale conversion, so no leap-second table is consulted."""
    (jd1,), (jd2,) = utc_jd(start, np.array([seconds]))
    t = t.utc
    return bool((jd1 - float(t.jd1)) + (jd2 - float(t.jd2)) > 0)


def tt_minus_utc(start: Time) -> float:
    """TT - UTC in seconds at ``start`` (32.184 s + leap seconds)."""
    with quiet():
        tt = start.tt
        utc = start.utc
    return float(((tt.jd1 - utc.jd1) + (tt.jd2 - utc.jd2)) * _DAY)


def _r3(angle: np.ndarray) -> np.ndarray:
    """Rotation matrices about z by ``angle`` (frame rotation), shape (n, 3, 3)."""
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros(np.shape(angle) + (3, 3))
    out[..., 0, 0] = c
    out[..., 0, 1] = s
    out[..., 1, 0] = -s
    out[..., 1, 1] = c
    out[..., 2, 2] = 1.0
    return out


def gcrs_to_itrs(start: Time, t: np.ndarray) -> np.ndarray:
    """Rotation matrices GCRS -> ITRS at ``start + t`` (seconds), shape (n, 3, 3)."""
    t = np.asarray(t, dtype=float)
    jd1, jd2 = utc_jd(start, t)
    dtt = tt_minus_utc(start) / _DAY
    nodes = np.round(t / C2I_NODE_SPACING).astype(int)
    c2i = np.empty(t.shape + (3, 3))
    for node in np.unique(nodes):  # one per half day: a handful
        sel = nodes == node
        node_jd2 = float(start.utc.jd2) + node * C2I_NODE_SPACING / _DAY + dtt
        c2i[sel] = erfa.c2i06a(float(start.utc.jd1), node_jd2)
    era = erfa.era00(jd1, jd2)  # UT1 = UTC
    return _r3(era) @ c2i


def teme_to_itrs(start: Time, t: np.ndarray) -> np.ndarray:
    """Rotation matrices TEME -> ITRS (GMST 1982, UT1 = UTC), shape (n, 3, 3)."""
    jd1, jd2 = utc_jd(start, np.asarray(t, dtype=float))
    return _r3(erfa.gmst82(jd1, jd2))


def rotate(matrices: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Apply (n, 3, 3) matrices to (n, 3) vectors."""
    return np.einsum("nij,nj->ni", matrices, vectors)


def geodetic(position: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """WGS84 geodetic latitude (deg), east longitude (deg, -180..180] and
    height above the ellipsoid (m) of ITRS positions (n, 3) in metres."""
    lon, lat, height = erfa.gc2gd(1, np.ascontiguousarray(position, dtype=float))
    return np.degrees(lat), np.degrees(lon), height
