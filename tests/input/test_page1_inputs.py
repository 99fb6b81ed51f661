"""Mission fields that page 1 reads: [mission] assumed and flight, [operation] cross_field, and an eccentric
orbit's perigee and apogee for the gravity-gradient rate."""

from __future__ import annotations

import pytest
from helpers import set_like

from etcheck import MissionError, mission_from_dict
from etcheck.input.gravity_gradient import apogee_rate


def test_assumed_fields_are_read_and_flagged():
    data = set_like(name="a", end_tension="0.1 N")
    data["mission"]["assumed"] = ["operation.end_tension", "tether.length"]
    m = mission_from_dict(data)
    assert m.provenance.assumed == ("operation.end_tension", "tether.length")
    assert m.provenance.is_assumed("operation.end_tension") and not m.provenance.is_assumed("operation.current")
    assert m.echo().assumed == ("operation.end_tension", "tether.length")


def test_an_assumed_field_not_given_is_a_note_not_an_error():
    data = set_like(name="a")
    data["mission"]["assumed"] = ["tether.end_masses"]
    m = mission_from_dict(data)
    assert m.provenance.assumed == () and any("tether.end_masses" in n and "does not give" in n for n in m.provenance.notes)


@pytest.mark.parametrize("value, words", [(["tether.lenght"], "unknown field"), ("tether.length", "list of field"),
                                          (["mission.name"], "unknown field"), ([3], "list of field")])
def test_bad_assumed_lists_name_the_field(value, words):
    data = set_like(name="a")
    data["mission"]["assumed"] = value
    with pytest.raises(MissionError, match="mission.assumed") as err:
        mission_from_dict(data)
    assert words in str(err.value)


def test_flight_record():
    data = set_like(name="a")
    data["mission"]["flight"] = {"outcome": "coiled", "reported": "a flight report"}
    assert mission_from_dict(data).provenance.flight == {"outcome": "coiled", "reported": "a flight report"}
    for bad in ({"outcome": "tangled"}, {"reported": "x"}, "coiled", {"outcome": "coiled", "when": "1993"}):
        data["mission"]["flight"] = bad
        with pytest.raises(MissionError, match="mission.flight"):
            mission_from_dict(data)


def test_cross_field_is_a_field_range():
    data = set_like(name="a")
    data["operation"]["cross_field"] = ["10 uT", "30 uT"]
    m = mission_from_dict(data)
    assert m.operation.worst_cross_field.to_value("uT") == pytest.approx(30.0)
    assert m.echo().operation.cross_field == ("10 µT", "30 µT")
    data["operation"]["cross_field"] = "30 m"
    with pytest.raises(MissionError, match="operation.cross_field"):
        mission_from_dict(data)


def test_orbit_altitude_as_perigee_and_apogee():
    data = set_like(name="a", end_masses=["950 kg", "20 kg"])
    data["operation"]["orbit_altitude"] = ["192 km", "850 km"]
    gg = mission_from_dict(data).operation.gravity_gradient
    assert gg.orbit_rate == apogee_rate(192e3, 850e3)
    assert "192 km x 850 km" in gg.rate_source and "apogee" in gg.rate_source
    data["operation"]["orbit_altitude"] = ["850 km", "192 km"]
    with pytest.raises(MissionError, match="operation.orbit_altitude"):
        mission_from_dict(data)
    data["operation"]["orbit_altitude"] = ["192 km", "850 km", "900 km"]
    with pytest.raises(MissionError, match="operation.orbit_altitude"):
        mission_from_dict(data)
