"""The [orbit] table wired into missions, the check, the report and sweeps (issue 14):
the check's axial field is the envelope's worst case (compared with axial_field_envelope
called directly), errors name the fields, the report has its section and figures,
results.json its series, and a 2 x 2 altitude x inclination sweep uses each orbit's field."""

from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from helpers import set_like

from etcheck.checks.orbit_field import resolve
from etcheck.checks.pipeline import check
from etcheck.errors import MissionError
from etcheck.input.mission import load_mission, mission_from_dict
from etcheck.input.orbit_table import parse_orbit
from etcheck.input.sweep_axes import parse_option
from etcheck.jsonable import OMITTED
from etcheck.orbit import axial_field_envelope
from etcheck.scaling import scene
from etcheck.studies.orbit_sweep import SWEEP_STEP
from etcheck.studies.sweep import SweepOptions, sweep

ROOT = Path(__file__).resolve().parents[2]
#: a short window keeps the envelope cheap (a fixed 60 s step: no halving loop)
ORBIT = {"altitude": "500 km", "inclination": "51.6 deg", "epoch": "2027-03-01T00:00:00", "duration": "3 h",
         "step": "60 s", "libration_in_plane": "10 deg", "libration_out_of_plane": "5 deg"}


def orbit_mission(orbit=None, **fields) -> dict:
    data = set_like(**fields)
    del data["operation"]["axial_field"]
    data["orbit"] = dict(ORBIT if orbit is None else orbit)
    return data


@pytest.fixture(scope="module")
def mission():
    return mission_from_dict(orbit_mission())


@pytest.fixture(scope="module")
def envelope():
    return axial_field_envelope(parse_orbit(ORBIT))


@pytest.fixture(scope="module")
def results(mission):
    return check(mission).results


# --- the mission ------------------------------------------------------------------------------


def test_loading_an_orbit_mission_only_reads_it(mission):
    """The mission holds the orbit's specification; nothing is propagated or evaluated at load."""
    assert mission.orbit == parse_orbit(ORBIT)
    assert mission.operation.axial_field is None
    echo = mission.echo()
    assert echo.operation.axial_field is None
    assert echo.orbit.inclination_deg == pytest.approx(51.6) and echo.orbit.period_s == pytest.approx(5677, rel=1e-3)
    assert not hasattr(echo.orbit, "statement") and not any("worst case over the orbit" in n for n in mission.provenance.notes)
    with pytest.raises(ValueError, match="orbit stage"):  # its field is the orbit stage's, not the file's
        scene(mission)


def test_orbit_mission_takes_the_envelopes_worst_case(mission, envelope, results):
    operating = resolve(mission)
    resolved = operating.mission
    assert operating.envelope.worst == envelope.worst and operating.envelope.seconds > 0
    assert 20e-6 < envelope.worst < 60e-6  # LEO at 51.6 deg
    lo, hi = resolved.operation.axial_field
    assert lo.to_value("T") == hi.to_value("T") == envelope.worst
    assert operating.scene.field.axial == envelope.worst
    assert operating.scene.load == pytest.approx(1.0 * envelope.worst, rel=1e-15)
    assert resolved.echo().operation.axial_field == (f"{envelope.worst * 1e6:.6g} µT",)
    stated = results["orbit"]["statement"]
    assert stated.startswith("axial field: worst case over the orbit, ")
    assert f"{envelope.worst * 1e6:.4g} µT" in stated and envelope.worst_utc[:19] in stated
    lat = f"{abs(envelope.worst_latitude):.2f}° {'N' if envelope.worst_latitude >= 0 else 'S'}"
    assert lat in stated
    assert any(n.startswith(stated) for n in resolved.provenance.notes)
    assert any(n.startswith(stated) for n in results["mission"]["notes"])
    assert results["orbit"]["envelope_s"] > 0
    assert results["mission"]["operation"]["axial_field"] == [f"{envelope.worst * 1e6:.6g} µT"]


def test_mission_stays_immutable_and_comparable(mission):
    with pytest.raises(AttributeError):
        mission.orbit = None
    again = mission_from_dict(orbit_mission())
    assert again == mission  # the envelope (arrays) takes no part in equality
    assert hash(again) == hash(mission)


def test_missions_without_orbit_are_unchanged():
    m = mission_from_dict(set_like())
    assert m.orbit is None and m.echo().orbit is OMITTED
    assert scene(m).field.axial == pytest.approx(70e-6)


@pytest.mark.parametrize("case", ["both", "neither"])
def test_both_or_neither_field_sources_exit_2_naming_the_fields(case, tmp_path):
    data = orbit_mission() if case == "neither" else set_like()
    if case == "neither":
        del data["orbit"]
    else:
        data["orbit"] = dict(ORBIT)
    with pytest.raises(MissionError) as exc:
        mission_from_dict(data)
    assert exc.value.field == "operation.axial_field" and exc.value.exit_code == 2
    assert "[orbit]" in str(exc.value) and "axial_field" in str(exc.value)
    assert ("both" in exc.value.problem) == (case == "both")


def _toml(data: dict) -> str:
    lines = []
    for table, fields in data.items():
        lines.append(f"[{table}]")
        for k, v in fields.items():
            lines.append(f"{k} = {json.dumps(v)}")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("key, value, field, words", [
    ("altitude", "100 km", "orbit.altitude", "atmosphere"),
    ("altitud", "500 km", "orbit.altitud", "did you mean 'altitude'"),
    ("epoch", "2035-01-01T00:00:00", "orbit.epoch", "validity"),
    ("inclination", "51.6", "orbit.inclination", "no unit"),
    ("inclination", "51.6 km", "orbit.inclination", "expected an angle"),
    ("duration", "-1 h", "orbit.duration", "must be > 0"),
    ("libration_in_plane", "95 deg", "orbit.libration_in_plane", "outside"),
])
def test_bad_orbit_fields_are_named_through_parse_orbit(key, value, field, words, tmp_path):
    data = orbit_mission()
    if key == "altitud":
        del data["orbit"]["altitude"]
    data["orbit"][key] = value
    path = tmp_path / "bad.toml"
    path.write_text(_toml(data))
    with pytest.raises(MissionError) as exc:
        load_mission(path)
    assert exc.value.field == field and words in str(exc.value)
    with pytest.raises(MissionError) as direct:  # the same error as parse_orbit's own
        parse_orbit(data["orbit"], str(path))
    assert str(direct.value) == str(exc.value)


def test_orbit_must_be_a_table():
    data = orbit_mission()
    data["orbit"] = "500 km"
    with pytest.raises(MissionError) as exc:
        mission_from_dict(data)
    assert exc.value.field == "orbit"


def test_shipped_orbit_mission_loads_with_assumptions_marked():
    text = (ROOT / "missions" / "proseds-orbit.toml").read_text()
    orbit_table = text.split("[orbit]")[1].split("[check]")[0]
    for line in orbit_table.strip().splitlines():  # every orbit value says where it comes from
        assert "ASSUMPTION" in line or "Johnson" in line or "one day" in line, line
    operating = resolve(load_mission(ROOT / "missions" / "proseds-orbit.toml"))
    m = operating.mission
    assert m.orbit is not None and operating.envelope.converged
    assert math.degrees(m.orbit.orbit.inclination) == pytest.approx(28.5)
    # a 28.5 deg, 360 km orbit: the worst axial field lies in the South Atlantic-Indian band, 30-60 uT
    assert 30e-6 < operating.envelope.worst < 60e-6


# --- the check ------------------------------------------------------------------------------------


def test_check_uses_the_envelopes_worst_field(results, envelope):
    assert results["scene"]["worst_field_T"] == envelope.worst
    assert results["scene"]["load_N_per_m"] == pytest.approx(1.0 * envelope.worst, rel=1e-15)
    o = results["orbit"]
    assert o["worst"]["axial_field_T"] == envelope.worst
    assert o["worst"]["latitude_deg"] == envelope.worst_latitude and o["worst"]["utc"] == envelope.worst_utc
    assert o["model"] == "IGRF-14" and o["sampling"]["step_s"] == 60.0


def test_margin_along_the_orbit(results, envelope):
    o = results["orbit"]
    load = next(m for m in results["margins"] if m["unit"] == "N/m")
    assert o["margin"]["critical_N_per_m"] == load["critical"]
    assert o["margin"]["smallest"] == pytest.approx(load["value"], rel=1e-12)  # the check's load margin
    s = o["series"]
    margin = np.array(s["load_margin"], dtype=float)
    field = np.array(s["axial_worst_T"], dtype=float)
    np.testing.assert_allclose(margin, load["critical"] / (1.0 * field), rtol=1e-12)
    k = int(np.argmin(margin))
    assert margin[k] == pytest.approx(o["margin"]["smallest"], rel=1e-12)
    assert s["latitude_deg"][k] == envelope.worst_latitude and s["time_s"][k] == envelope.worst_time
    first = o["first_orbit"]
    assert first["time_s"][-1] <= o["period_s"] < first["time_s"][-1] + 60.0
    assert len(s["time_s"]) == len(envelope.series) == 181  # 3 h at 60 s: every sample


def test_long_series_are_downsampled_with_the_worst_sample_kept():
    m = mission_from_dict(orbit_mission(ORBIT | {"duration": "2 d", "step": "30 s"}))
    o = check(m).results["orbit"]
    env = resolve(m).envelope
    n = len(env.series)
    assert n == 5761 and o["sampling"]["samples"] == n
    assert len(o["series"]["time_s"]) <= 3000 and "every 2th" in o["series_note"]
    assert max(o["series"]["axial_worst_T"]) == env.worst
    assert len(o["first_orbit"]["time_s"]) == int(o["period_s"] // 30) + 1  # full resolution


def test_report_has_the_orbit_section_with_numbered_figures(results):
    from etcheck.report import render

    out = render(results, ("html", "json"))
    html = out["html"].decode()
    assert "<h3>The field along the orbit</h3>" in html
    assert results["orbit"]["statement"].replace("°", "°") in html
    numbers = [int(n) for n in re.findall(r"Figure (\d+):", html)]
    assert numbers == list(range(1, len(numbers) + 1))
    section = html.split("The field along the orbit</h3>")[1].split("<h2>")[0]
    assert section.count("<img src=\"data:image/png") == 3 and section.count("<figcaption>Figure") == 3
    assert "Ground track" in section and "IGRF-14" in section
    data = json.loads(out["json"])
    assert len(data["orbit"]["series"]["axial_worst_T"]) == 181


def test_report_without_orbit_has_no_orbit_section():
    from etcheck.report import render

    r = check(set_like()).results
    assert r["orbit"] is None
    assert "The field along the orbit" not in render(r, ("html",))["html"].decode()


# --- sweeps over orbits -----------------------------------------------------------------------


def test_orbit_axes_parse_to_si():
    h = parse_option("altitude", "300km:1500km:20")
    i = parse_option("inclination", "0deg:98deg:20")
    assert h.name == "altitude" and h.values[0] == 300e3 and h.values[-1] == 1500e3 and h.unit == "km"
    assert i.values[-1] == pytest.approx(math.radians(98)) and i.unit == "deg"
    assert i.as_dict()["display_values"][-1] == pytest.approx(98.0)
    with pytest.raises(MissionError, match="150 km"):
        parse_option("altitude", "100km:500km:3")
    with pytest.raises(MissionError, match="180 deg"):
        parse_option("inclination", "0deg:200deg:3")


def test_altitude_by_inclination_sweep_uses_each_orbits_field(tmp_path):
    m = mission_from_dict(orbit_mission(ORBIT | {"step": "120 s"}))
    axes = (parse_option("altitude", "400km:1200km:2"), parse_option("inclination", "10deg:90deg:2"))
    r = sweep(m, axes, SweepOptions(workers=1, cache=tmp_path / "cache"))
    o = r["orbit"]
    assert o["orbits"] == 4 and o["step_s"] == 120.0
    g = r["grid"]
    fields = np.zeros((2, 2))
    for a, h in enumerate((400e3, 1200e3)):
        for b, inc in enumerate((10.0, 90.0)):
            spec = parse_orbit(ORBIT | {"step": "120 s", "altitude": f"{h} m", "inclination": f"{inc} deg"})
            fields[a, b] = axial_field_envelope(spec).worst  # independent of the sweep's own call
            row = next(e for e in o["envelopes"] if e["altitude_km"] == h / 1e3 and e["inclination_deg"] == pytest.approx(inc))
            assert row["axial_field_uT"] == pytest.approx(fields[a, b] * 1e6, rel=1e-12)
    np.testing.assert_allclose(np.array(g["load_N_per_m"]), 1.0 * fields, rtol=1e-12)
    # field higher at high inclination and low altitude
    assert fields[0, 1] > fields[0, 0] and fields[0, 1] > fields[1, 1]
    # the critical load does not depend on the orbit: margin x field is the same at every point
    product = np.array(g["load_margin"]) * fields
    np.testing.assert_allclose(product, product[0, 0], rtol=1e-9)
    assert r["operating"]["altitude"] == 500e3 and r["operating"]["inclination"] == pytest.approx(math.radians(51.6))
    again = sweep(m, axes, SweepOptions(workers=1, cache=tmp_path / "cache"))  # resumed from the cache
    assert again["orbit"]["from_cache"] == 4 and again["grid"]["load_margin"] == g["load_margin"]


def test_orbit_sweep_default_step_and_bad_combinations():
    m = mission_from_dict(orbit_mission({k: v for k, v in ORBIT.items() if k != "step"}))
    r = sweep(m, (parse_option("altitude", "400km:800km:2"),), SweepOptions(workers=1))
    assert r["orbit"]["step_s"] == SWEEP_STEP == 60.0 and "0.085 %" in r["orbit"]["sampling_note"]
    with pytest.raises(MissionError) as exc:
        sweep(mission_from_dict(set_like()), (parse_option("altitude", "400km:800km:2"),), SweepOptions(workers=1))
    assert exc.value.field == "orbit"
    with pytest.raises(MissionError) as exc:
        sweep(m, (parse_option("altitude", "400km:800km:2"), parse_option("field", "20uT:70uT:2")), SweepOptions(workers=1))
    assert exc.value.field == "--field"


def test_sweep_table_accepts_orbit_axes():
    data = orbit_mission()
    data["sweep"] = {"inclination": {"from": "0 deg", "to": "98 deg", "points": 3}}
    m = mission_from_dict(copy.deepcopy(data))
    assert m.studies.sweep[0].name == "inclination" and m.studies.sweep[0].values[-1] == pytest.approx(math.radians(98))


def test_a_window_past_the_leap_second_table_prints_nothing_on_stderr_and_says_so(tmp_path):
    """An orbit in 2029 (past ERFA's leap-second table): astropy's ErfaWarning is caught where it arises, the
    CLI's stderr stays empty and the mission's notes state the assumption."""
    import subprocess
    import sys

    text = (ROOT / "missions" / "proseds-orbit.toml").read_text()
    path = tmp_path / "orbit-2029.toml"
    path.write_text(text.replace('epoch = "2003-01-15T00:00:00"', 'epoch = "2029-06-15T00:00:00"'))
    assert "2029-06-15" in path.read_text()
    out = subprocess.run([sys.executable, "-m", "etcheck", str(path), "--draft", "--format", "json",
                          "--out", str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert out.returncode in (0, 1), out.stderr
    assert out.stderr == ""
    notes = json.loads(next((tmp_path / "out").rglob("results.json")).read_text())["mission"]["notes"]
    assert any("past the leap-second table" in n for n in notes)


def test_a_window_within_the_leap_second_table_has_no_such_note(mission):
    notes = resolve(mission).mission.provenance.notes
    assert any("worst case over the orbit" in n for n in notes)
    assert not any("leap-second" in n for n in notes)
