"""The [orbit] table: a good table parses; each error names orbit.FIELD."""

from __future__ import annotations

import datetime as dt
import math

import pytest

from etcheck.errors import MissionError
from etcheck.input.orbit_table import parse_orbit
from etcheck.orbit import KeplerianElements, TwoLineElements

GOOD = {"altitude": "500 km", "inclination": "51.6 deg", "epoch": "2027-03-01T00:00:00"}
ISS = [
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482",
]


def test_circular_orbit_parses_with_defaults():
    spec = parse_orbit(GOOD)
    assert isinstance(spec.orbit, KeplerianElements)
    assert spec.orbit.perigee_altitude == spec.orbit.apogee_altitude == pytest.approx(500e3)
    assert spec.orbit.inclination == pytest.approx(math.radians(51.6))
    assert spec.start == "2027-03-01T00:00:00.000" and spec.duration == 86400.0 and spec.step is None
    assert spec.libration_in_plane == 0.0 == spec.libration_out_of_plane


def test_elliptical_orbit_and_options_parse():
    spec = parse_orbit({
        "perigee_altitude": "400 km", "apogee_altitude": "1200 km", "inclination": "98 deg",
        "raan": "-30 deg", "argument_of_perigee": "1 rad", "mean_anomaly": "370 deg",
        "epoch": dt.datetime(2027, 3, 1, 6, tzinfo=dt.timezone(dt.timedelta(hours=2))),
        "duration": "12 h", "step": "10 s", "libration_in_plane": "10 deg", "libration_out_of_plane": "5 deg",
    })
    o = spec.orbit
    assert o.eccentricity == pytest.approx(800e3 / (2 * 6378137 + 1600e3))
    assert o.raan == pytest.approx(math.radians(330)) and o.mean_anomaly == pytest.approx(math.radians(10))
    assert spec.start == "2027-03-01T04:00:00.000"
    assert spec.duration == 43200.0 and spec.step == 10.0
    assert spec.libration_in_plane == pytest.approx(math.radians(10))


def test_tle_parses_and_starts_at_its_epoch():
    spec = parse_orbit({"tle": ISS, "duration": "1 h"})
    assert isinstance(spec.orbit, TwoLineElements)
    assert spec.start.startswith("2019-12-09T16:38:29")


def _error(table) -> MissionError:
    with pytest.raises(MissionError) as info:
        parse_orbit(table)
    return info.value


@pytest.mark.parametrize(
    "change, field, words",
    [
        ({"inclination": None}, "orbit.inclination", "missing"),
        ({"epoch": None}, "orbit.epoch", "missing"),
        ({"altitude": None}, "orbit.altitude", "missing"),
        ({"altitude": None, "perigee_altitude": "400 km"}, "orbit.apogee_altitude", "missing"),
    ],
    ids=["inclination", "epoch", "altitude", "apogee"],
)
def test_missing_fields(change, field, words):
    table = {k: v for k, v in {**GOOD, **change}.items() if v is not None}
    exc = _error(table)
    assert exc.field == field and words in str(exc) and f"[{field}]" in str(exc)


def test_wrong_dimension():
    exc = _error({**GOOD, "altitude": "500 s"})
    assert exc.field == "orbit.altitude" and "expected a length" in str(exc)
    exc = _error({**GOOD, "inclination": "51 km"})
    assert exc.field == "orbit.inclination" and "expected an angle" in str(exc)
    exc = _error({**GOOD, "duration": "1 m"})
    assert exc.field == "orbit.duration" and "expected a time" in str(exc)


def test_no_unit():
    exc = _error({**GOOD, "inclination": 51.6})
    assert exc.field == "orbit.inclination" and "no unit" in str(exc) and "deg" in exc.fix


def test_nan():
    exc = _error({**GOOD, "altitude": "nan km"})
    assert exc.field == "orbit.altitude" and "not a finite number" in str(exc)
    exc = _error({**GOOD, "raan": "nan deg"})
    assert exc.field == "orbit.raan" and "not a finite number" in str(exc)


def test_altitude_below_the_atmosphere():
    exc = _error({**GOOD, "altitude": "120 km"})
    assert exc.field == "orbit.altitude" and "atmosphere" in str(exc) and "150 km" in exc.fix
    exc = _error({**{k: v for k, v in GOOD.items() if k != "altitude"}, "perigee_altitude": "100 km", "apogee_altitude": "900 km"})
    assert exc.field == "orbit.perigee_altitude"


def test_apogee_below_perigee():
    table = {**{k: v for k, v in GOOD.items() if k != "altitude"}, "perigee_altitude": "900 km", "apogee_altitude": "400 km"}
    exc = _error(table)
    assert exc.field == "orbit.apogee_altitude" and "below the perigee" in str(exc)


@pytest.mark.parametrize("value", ["-1 deg", "181 deg", "4 rad"])
def test_inclination_outside_0_180(value):
    exc = _error({**GOOD, "inclination": value})
    assert exc.field == "orbit.inclination" and "0-180 deg" in str(exc)


@pytest.mark.parametrize("epoch, duration", [("1899-12-31T00:00:00", "1 d"), ("2029-12-31T12:00:00", "1 d"), ("2031-01-01", "1 h")])
def test_epoch_outside_the_igrf(epoch, duration):
    exc = _error({**GOOD, "epoch": epoch, "duration": duration})
    assert exc.field == "orbit.epoch" and "IGRF-14" in str(exc) and "2030-01-01" in str(exc)


def test_epoch_unreadable():
    exc = _error({**GOOD, "epoch": "1st of March"})
    assert exc.field == "orbit.epoch" and "ISO 8601" in str(exc)


def test_tle_checksum_and_format():
    bad = [ISS[0][:-1] + "0", ISS[1]]
    exc = _error({"tle": bad})
    assert exc.field == "orbit.tle" and "checksum" in str(exc)
    exc = _error({"tle": [ISS[0][:60], ISS[1]]})
    assert exc.field == "orbit.tle" and "69" in str(exc)
    exc = _error({"tle": ISS[0]})
    assert exc.field == "orbit.tle" and "two strings" in str(exc)


def test_tle_far_from_the_window():
    exc = _error({"tle": ISS, "epoch": "2027-03-01T00:00:00"})
    assert exc.field == "orbit.epoch" and "TLE epoch" in str(exc)
    assert parse_orbit({"tle": ISS, "epoch": "2019-12-10T00:00:00"}).start == "2019-12-10T00:00:00.000"


def test_tle_and_elements_both_given():
    exc = _error({"tle": ISS, "inclination": "51.6 deg"})
    assert exc.field == "orbit.inclination" and "not both" in exc.fix


def test_unknown_key_suggests_the_closest():
    exc = _error({**GOOD, "inclinaton": "51 deg"})
    assert exc.field == "orbit.inclinaton" and "did you mean 'inclination'" in str(exc)


def test_libration_bounds():
    exc = _error({**GOOD, "libration_in_plane": "90 deg"})
    assert exc.field == "orbit.libration_in_plane" and "[0, 90)" in str(exc)
    exc = _error({**GOOD, "libration_out_of_plane": "-5 deg"})
    assert exc.field == "orbit.libration_out_of_plane"


def test_step_and_duration_ranges():
    exc = _error({**GOOD, "duration": "1 h", "step": "2 h"})
    assert exc.field == "orbit.step"
    exc = _error({**GOOD, "duration": "0 s"})
    assert exc.field == "orbit.duration"
    exc = _error({**GOOD, "duration": "2 yr"})
    assert exc.field == "orbit.duration" and "366 d" in str(exc)


def test_not_a_table():
    exc = _error(["altitude", "500 km"])
    assert exc.field == "orbit"
