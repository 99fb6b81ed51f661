"""TLE round trip and the Earth-fixed rotations.

The ISS element set is the example of the sgp4 package's documentation.
SGP4's elements are mean (Kozai/Brouwer) elements: as osculating two-body
elements they differ from SGP4's position by the short-period J2 terms, about
10 km in LEO, which bounds the round trip.
"""

from __future__ import annotations

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import GCRS, ITRS, TEME, CartesianRepresentation
from astropy.utils import iers

from etcheck.orbit import KeplerianElements, TwoLineElements, trajectory
from etcheck.orbit.elements import kepler_state, tle_state
from etcheck.orbit.frames import parse_utc

ISS = (
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482",
)


@pytest.fixture(scope="module")
def tle():
    return TwoLineElements(*ISS)


def test_tle_round_trip_at_epoch_and_over_an_orbit(tle):
    kep = KeplerianElements.from_tle(tle)
    assert kep.frame == "TEME"
    assert kep.inclination == pytest.approx(np.radians(51.6439))
    assert kep.eccentricity == pytest.approx(0.0007417, rel=1e-9)
    assert kep.period == pytest.approx(86400 / 15.50103472, rel=1e-3)
    start = parse_utc(tle.epoch)
    t = np.linspace(0.0, kep.period, 50)
    r_sgp4, v_sgp4 = tle_state(tle, start, t)
    r_kep, v_kep = kepler_state(kep, t)
    assert np.linalg.norm(r_sgp4[0] - r_kep[0]) < 12e3
    assert np.max(np.linalg.norm(r_sgp4 - r_kep, axis=1)) < 25e3
    assert np.max(np.linalg.norm(v_sgp4 - v_kep, axis=1)) < 30.0
    # the same through the ITRS trajectories (both TEME -> ITRS)
    a, b = trajectory(tle, tle.epoch, t), trajectory(kep, tle.epoch, t)
    assert np.max(np.linalg.norm(a.position - b.position, axis=1)) < 25e3


def test_teme_and_gcrs_to_itrs_agree_with_astropy(tle):
    """astropy with its bundled IERS data (2019: UT1 - UTC and polar motion
    known); the difference is UT1 - UTC = -0.17 s times the Earth's rotation."""
    t = np.linspace(0.0, 5400.0, 7)
    start = parse_utc(tle.epoch)
    obstime = start + t * u.s
    r_teme, _ = tle_state(tle, start, t)
    r_gcrs, _ = kepler_state(KeplerianElements(400e3, 420e3, 0.9, 1.0, 0.3, 0.2, tle.epoch), t)
    ours_teme = trajectory(tle, tle.epoch, t).position
    ours_gcrs = trajectory(KeplerianElements(400e3, 420e3, 0.9, 1.0, 0.3, 0.2, tle.epoch), tle.epoch, t).position
    with iers.conf.set_temp("auto_download", False):
        ref_teme = TEME(CartesianRepresentation(r_teme.T, unit=u.m), obstime=obstime).transform_to(ITRS(obstime=obstime))
        ref_gcrs = GCRS(CartesianRepresentation(r_gcrs.T, unit=u.m), obstime=obstime).transform_to(ITRS(obstime=obstime))
    for ours, ref in ((ours_teme, ref_teme), (ours_gcrs, ref_gcrs)):
        err = np.linalg.norm(ours - ref.cartesian.xyz.to_value(u.m).T, axis=1)
        assert err.max() < 500.0  # |UT1 - UTC| < 0.9 s is < 450 m at this radius


def test_tle_epoch_and_perigee(tle):
    assert tle.epoch.startswith("2019-12-09T16:38:29")
    assert 405e3 < tle.perigee_altitude < 420e3
